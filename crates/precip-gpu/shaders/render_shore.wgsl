// render_shore.wgsl: the shore each frame (docs/model.md (13.10)): the
// shallow-water equations over the shore's grid (precip_model::drawing::shore),
// the frame's steps (shore_steps.x: SHORE_STEPS_PER_FRAME, and the spin-up's on
// the shore's first frame) of Heun's two stages, each stage two kernels:
//   shore_faces_*   one invocation per cell corner (i, j) of (nx + 1)·(ny + 1):
//                   the flux through the face before cell (i, j) along x and the
//                   one before it along z (shore.wgsl shore_face_flux of the MUSCL
//                   faces either side, ghosts beyond the grid's edges), and cell
//                   (i, j)'s bed sources;
//   shore_update_*  one invocation per cell: the rates from its four faces and its
//                   sources, the stage's update (first: s1 = s0 + Δt·R(s0); second:
//                   s0 = (s0 + s1 + Δt·R(s1))/2), dry cells at rest, the bed's
//                   friction, the speed cap.
// Each face's flux is computed once and read by both its cells: the mass leaving
// one cell is the mass entering the next, bit for bit.
// Rust reference: precip_sea::Shore::step (shore/scheme.rs), the same arithmetic.
// The sea's draw reads the latest state (shore_surface, for vs_sea).
// Program: the Render program's files, after render_ocean.wgsl.
//
// The buffer (ShoreGrid::initial_buffer), array<vec4<f32>>:
//   [0]                  header: x the step of this frame the next stage belongs to
//                        (back to 0 after the frame's last)
//   [1, 1 + n)           state A, each cell (h m, q_x m²/s, q_z m²/s, bed m): the water
//   [1 + n, 1 + 2n)      state B: the first stage's
//   then (nx + 1)·ny     faces along x (mass, the left cell's normal momentum, the
//                        right cell's, tangential momentum), rows of nx + 1
//   then nx·(ny + 1)     faces along z, likewise, rows of nx
//   then n               each cell's bed sources (x, z, 0, 0)

@group(0) @binding(28) var<storage, read> shore: array<vec4<f32>>;
@group(0) @binding(29) var<storage, read_write> shore_cells: array<vec4<f32>>;

// precip_model::drawing::shore SHORE_WAVE_COMPONENTS, SHORE_DRY_SINK_M.
const SHORE_WAVE_COMPONENTS: u32 = 8u;
const SHORE_DRY_SINK_M: f32 = 0.3;
// Water thinner than this is drawn as dry ground, m.
const SHORE_DRAWN_WET_M: f32 = 1.0e-3;
// The shore's surface takes over from the open sea's over this many cells in
// from the grid's sides.
const SHORE_FADE_CELLS: f32 = 4.0;

fn shore_dims() -> vec2<u32> {
    return vec2<u32>(switches.shore_size.xy);
}

fn shore_state_base(second: bool) -> u32 {
    let n = shore_dims();
    return select(1u, 1u + n.x * n.y, second);
}

fn shore_faces_x_base() -> u32 {
    let n = shore_dims();
    return 1u + 2u * n.x * n.y;
}

fn shore_faces_z_base() -> u32 {
    let n = shore_dims();
    return shore_faces_x_base() + (n.x + 1u) * n.y;
}

fn shore_sources_base() -> u32 {
    let n = shore_dims();
    return shore_faces_z_base() + n.x * (n.y + 1u);
}

// The surface's rise over the still level at the incoming edge `tau` s after this
// frame's first shore step, `along_m` along the edge from its start
// (IncomingWaves::elevation_at_m).
fn shore_rise(tau: f32, along_m: f32) -> f32 {
    var rise = 0.0;
    for (var c = 0u; c < SHORE_WAVE_COMPONENTS; c += 1u) {
        let w = switches.shore_waves[c];
        rise += w.x * cos(w.z + w.y * tau - w.w * along_m);
    }
    return rise;
}

// A cell's state along the sweep's axis: (h, q_normal, q_tangent, b).
fn shore_oriented(c: vec4<f32>, along_x: bool) -> vec4<f32> {
    return select(vec4<f32>(c.x, c.z, c.y, c.w), c, along_x);
}

// Cell (i, j) of the state at `base` along the sweep's axis, a ghost beyond the
// grid's edges (scheme.rs fill_edges: a wall mirrors, an open edge continues, the
// sea's waves come in) at `tau` s into the frame's steps.
fn shore_cell(base: u32, i: i32, j: i32, along_x: bool, tau: f32) -> vec4<f32> {
    let n = vec2<i32>(shore_dims());
    if (i >= 0 && j >= 0 && i < n.x && j < n.y) {
        return shore_oriented(shore_cells[base + u32(j * n.x + i)], along_x);
    }
    var side = 0u;
    var edge = vec2<i32>(0, j);
    var mirrored = vec2<i32>(-i - 1, j);
    var inward = 1.0;
    if (i >= n.x) {
        side = 1u;
        edge = vec2<i32>(n.x - 1, j);
        mirrored = vec2<i32>(2 * n.x - 1 - i, j);
        inward = -1.0;
    } else if (j < 0) {
        side = 2u;
        edge = vec2<i32>(i, 0);
        mirrored = vec2<i32>(i, -j - 1);
    } else if (j >= n.y) {
        side = 3u;
        edge = vec2<i32>(i, n.y - 1);
        mirrored = vec2<i32>(i, 2 * n.y - 1 - j);
        inward = -1.0;
    }
    let kind = u32(switches.shore_edges[side]);
    if (kind == 0u) {
        let m = shore_oriented(shore_cells[base + u32(mirrored.y * n.x + mirrored.x)], along_x);
        return vec4<f32>(m.x, -m.y, m.z, m.w);
    }
    let e = shore_oriented(shore_cells[base + u32(edge.y * n.x + edge.x)], along_x);
    if (kind == 1u) {
        return e;
    }
    // The ghost's place along the edge: z on the west and east sides, x on the others.
    let along = (f32(select(i, j, side < 2u)) + 0.5) * switches.shore_grid.z;
    let g = shore_incoming(e.w, e.x, e.y, inward, switches.shore_grid.w, shore_rise(tau, along));
    return vec4<f32>(g.x, g.x * g.y, 0.0, e.w);
}

fn shore_faces(k: u32, second: bool) {
    let n = shore_dims();
    if (k >= (n.x + 1u) * (n.y + 1u)) {
        return;
    }
    let i = i32(k % (n.x + 1u));
    let j = i32(k / (n.x + 1u));
    let base = shore_state_base(second);
    let step = f32(u32(shore_cells[0].x));
    let tau = (step + select(0.0, 1.0, second)) * switches.shore_size.z;
    // Along x: the face between cells i − 1 and i of row j.
    if (j < i32(n.y)) {
        let c0 = shore_values(shore_cell(base, i - 2, j, true, tau));
        let c1 = shore_values(shore_cell(base, i - 1, j, true, tau));
        let c2 = shore_values(shore_cell(base, i, j, true, tau));
        let c3 = shore_values(shore_cell(base, i + 1, j, true, tau));
        let flux = shore_face_flux(shore_face(c0, c1, c2, 1.0), shore_face(c1, c2, c3, -1.0));
        shore_cells[shore_faces_x_base() + u32(j) * (n.x + 1u) + u32(i)] = flux;
    }
    // Along z: the face between cells j − 1 and j of column i.
    if (i < i32(n.x)) {
        let c0 = shore_values(shore_cell(base, i, j - 2, false, tau));
        let c1 = shore_values(shore_cell(base, i, j - 1, false, tau));
        let c2 = shore_values(shore_cell(base, i, j, false, tau));
        let c3 = shore_values(shore_cell(base, i, j + 1, false, tau));
        let flux = shore_face_flux(shore_face(c0, c1, c2, 1.0), shore_face(c1, c2, c3, -1.0));
        shore_cells[shore_faces_z_base() + u32(j) * n.x + u32(i)] = flux;
    }
    // Cell (i, j)'s bed sources from its own faces along each axis.
    if (i < i32(n.x) && j < i32(n.y)) {
        let xb = shore_values(shore_cell(base, i - 1, j, true, tau));
        let xh = shore_values(shore_cell(base, i, j, true, tau));
        let xa = shore_values(shore_cell(base, i + 1, j, true, tau));
        let zb = shore_values(shore_cell(base, i, j - 1, false, tau));
        let zh = shore_values(shore_cell(base, i, j, false, tau));
        let za = shore_values(shore_cell(base, i, j + 1, false, tau));
        let source_x = shore_bed_source(shore_face(xb, xh, xa, -1.0), shore_face(xb, xh, xa, 1.0));
        let source_z = shore_bed_source(shore_face(zb, zh, za, -1.0), shore_face(zb, zh, za, 1.0));
        shore_cells[shore_sources_base() + u32(j) * n.x + u32(i)] = vec4<f32>(source_x, source_z, 0.0, 0.0);
    }
}

fn shore_update(k: u32, second: bool) {
    let n = shore_dims();
    if (k >= n.x * n.y) {
        return;
    }
    let i = k % n.x;
    let j = k / n.x;
    let dx = switches.shore_grid.z;
    let dt = switches.shore_size.z;
    let xf = shore_faces_x_base() + j * (n.x + 1u) + i;
    let zf = shore_faces_z_base() + j * n.x + i;
    let west = shore_cells[xf];
    let east = shore_cells[xf + 1u];
    let south = shore_cells[zf];
    let north = shore_cells[zf + n.x];
    let source = shore_cells[shore_sources_base() + k];
    // The rates in scheme.rs's order: the x sweep's faces and source, then z's.
    let rate_h = ((west.x / dx - east.x / dx) + south.x / dx) - north.x / dx;
    let rate_qx = (((west.z / dx - east.y / dx) - source.x / dx) + south.w / dx) - north.w / dx;
    let rate_qz = (((west.w / dx - east.w / dx) + south.z / dx) - north.y / dx) - source.y / dx;
    let a = shore_cells[1u + k];
    var s: vec3<f32>;
    if (second) {
        let b = shore_cells[1u + n.x * n.y + k];
        s = 0.5 * (a.xyz + b.xyz + dt * vec3<f32>(rate_h, rate_qx, rate_qz));
    } else {
        s = a.xyz + dt * vec3<f32>(rate_h, rate_qx, rate_qz);
    }
    if (s.x <= SHORE_DRY_DEPTH_M) {
        s = vec3<f32>(max(s.x, 0.0), 0.0, 0.0);
    }
    let q = shore_capped(s.x, shore_bed_friction(s.x, s.yz, dt, switches.shore_steps.y), switches.shore_size.w);
    let out = vec4<f32>(s.x, q, a.w);
    if (second) {
        shore_cells[1u + k] = out;
        if (k == 0u) {
            shore_cells[0].x = f32((u32(shore_cells[0].x) + 1u) % max(u32(switches.shore_steps.x), 1u));
        }
    } else {
        shore_cells[1u + n.x * n.y + k] = out;
    }
}

@compute @workgroup_size(64)
fn shore_faces_first(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    shore_faces((wid.x + wid.y * groups.x) * 64u + lid, false);
}

@compute @workgroup_size(64)
fn shore_update_first(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    shore_update((wid.x + wid.y * groups.x) * 64u + lid, false);
}

@compute @workgroup_size(64)
fn shore_faces_second(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    shore_faces((wid.x + wid.y * groups.x) * 64u + lid, true);
}

@compute @workgroup_size(64)
fn shore_update_second(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    shore_update((wid.x + wid.y * groups.x) * 64u + lid, true);
}

// The shore's water at xz_m for the sea's draw: (its surface over the still
// level m — a dry cell's sunk SHORE_DRY_SINK_M under its bed or the level,
// whichever is lower —, its depth m, its velocity x, z m/s), bilinear between
// cell centres; w: how much of the sea it stands for (1 inside, 0 over
// SHORE_FADE_CELLS to the grid's sides; 0 without a shore).
fn shore_surface(xz_m: vec2<f32>) -> vec4<f32> {
    let n = vec2<f32>(shore_dims());
    let g = params.shore_grid;
    let p = (xz_m - g.xy) / g.z - 0.5;
    let pc = clamp(p, vec2<f32>(0.0), n - 1.0);
    let i0 = vec2<u32>(floor(pc));
    let f = pc - floor(pc);
    let nx = u32(n.x);
    let i1 = min(i0 + 1u, vec2<u32>(n) - 1u);
    let s00 = shore_drawn(shore[1u + i0.y * nx + i0.x]);
    let s10 = shore_drawn(shore[1u + i0.y * nx + i1.x]);
    let s01 = shore_drawn(shore[1u + i1.y * nx + i0.x]);
    let s11 = shore_drawn(shore[1u + i1.y * nx + i1.x]);
    return mix(mix(s00, s10, f.x), mix(s01, s11, f.x), f.y);
}

// A cell as drawn: (surface over the still level, depth, velocity x, z).
fn shore_drawn(c: vec4<f32>) -> vec4<f32> {
    let level = params.shore_grid.w;
    if (c.x > SHORE_DRAWN_WET_M) {
        return vec4<f32>(c.x + c.w - level, c.x, c.y / c.x, c.z / c.x);
    }
    return vec4<f32>(min(c.w - level, 0.0) - SHORE_DRY_SINK_M, 0.0, 0.0, 0.0);
}

// How much of the sea the shore stands for at xz_m (shore_surface).
fn shore_weight(xz_m: vec2<f32>) -> f32 {
    let n = vec2<f32>(shore_dims());
    let g = params.shore_grid;
    let p = (xz_m - g.xy) / g.z;
    let inside = min(min(p.x, n.x - p.x), min(p.y, n.y - p.y));
    return clamp(inside / SHORE_FADE_CELLS, 0.0, 1.0);
}

// The foam of the shore's water `s` (shore_surface): where it runs as fast as its
// waves (a bore's front, the swash running up and back: Froude number toward 1),
// none in water under 1 cm.
fn shore_foam(s: vec4<f32>) -> f32 {
    if (s.y <= 0.01) {
        return 0.0;
    }
    let froude = length(s.zw) / sqrt(SHORE_G * s.y);
    return smoothstep(0.5, 1.1, froude);
}
