// render_terrain.wgsl: the terrain drawn as a geometry clipmap (Losasso & Hoppe 2004)
// from its pyramid's windows round the camera, which follow the ground map's words
// in `ground_height` (RenderParams::terrain_levels.z, terrain_windows). Rust twins:
// precip_model::scene::terrain::{clipmap_centre, ClipmapWindows::vertex} and
// precip_model::scene::slope_eligibility. Its vertices go through the scene's
// `scene_varying` (the snow raises them) and its fragments are the scene's.

const CLIPMAP_QUADS: i32 = 48;
const CLIPMAP_MORPH_QUADS: i32 = 8;
// Rust: CLIPMAP_GRID_VERTICES ((CLIPMAP_QUADS + 1)²) and CLIPMAP_LEVEL_VERTICES (the
// grid's, then the edge quads' six each: precip_model::scene::terrain::clipmap_indices).
const CLIPMAP_GRID_VERTICES: u32 = 2401u;
const CLIPMAP_LEVEL_VERTICES: u32 = 2977u;
// Rust: CLIPMAP_WINDOW_SAMPLES.
const CLIPMAP_WINDOW_SAMPLES: i32 = 64;
// Rust: precip_model::scene::{FULL_SNOW_SLOPE_DEG, NO_SNOW_SLOPE_DEG} as cosines.
const FULL_SNOW_COS: f32 = 0.8660254;
const NO_SNOW_COS: f32 = 0.64278764;
// Rust: precip_model::scene::terrain::TERRAIN_GRASS_SLOPE_DEG as a cosine.
const TERRAIN_GRASS_COS: f32 = 0.90630776;
// The cosine between a bent normal and the view (terrain_facing_normal; Rust:
// TERRAIN_EDGE_ON).
const TERRAIN_EDGE_ON: f32 = 0.001;
// Rows of the terrain's colour ramp (Rust: precip_model::scene::land_cover::LAND_CLASSES).
const LAND_CLASSES: f32 = 12.0;

// The land class drawn at world (x, z) of the terrain's land cover, which spans the
// terrain's extent (0, no data, without one or off it): of the four pixels round
// the point, the class with the most bilinear weight (land_class_pick), so borders
// between classes run smoothly, not along the pixels' edges. Rust twin:
// precip_model::scene::LandCover::drawn_class_at of the GPU's copy
// (LandCover::gpu_copy, every f-th pixel of a large raster).
fn land_class_at(xz_m: vec2<f32>) -> u32 {
    if (params.land_cover.w == 0u) {
        return 0u;
    }
    let uv = (xz_m - params.land_cover_extent.xy) / params.land_cover_extent.zw;
    if (any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0))) {
        return 0u;
    }
    let n = params.land_cover.xy;
    let t = uv * vec2<f32>(n) - 0.5;
    let base = floor(t);
    let last = vec2<i32>(n) - 1;
    let p0 = clamp(vec2<i32>(base), vec2<i32>(0), last);
    let p1 = clamp(vec2<i32>(base) + 1, vec2<i32>(0), last);
    let row0 = params.land_cover.z + u32(p0.y) * n.x;
    let row1 = params.land_cover.z + u32(p1.y) * n.x;
    let corners = vec4<u32>(
        u32(ground_height[row0 + u32(p0.x)]),
        u32(ground_height[row0 + u32(p1.x)]),
        u32(ground_height[row1 + u32(p0.x)]),
        u32(ground_height[row1 + u32(p1.x)]),
    );
    return min(land_class_pick(corners, t - base), 11u);
}

// The far cover's texel for land class `land` where the normal's up component is
// `up` (Rust: Terrain::surface_at and far_cover_slot): the class's surface, else
// grass up to TERRAIN_GRASS_SLOPE_DEG and soil beyond.
fn terrain_far_slot(land: u32, up: f32) -> u32 {
    if (land == 0u) {
        return select(0u, 1u, up < TERRAIN_GRASS_COS);
    }
    return u32(params.land_classes[land].y);
}

// Snow eligibility from a unit normal: 1 up to 30°, 0 from 50°, smooth between.
fn slope_eligibility(normal: vec3<f32>) -> f32 {
    let t = clamp((normal.y - NO_SNOW_COS) / (FULL_SNOW_COS - NO_SNOW_COS), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

fn terrain_level_samples(k: u32) -> vec2<i32> {
    let row = params.terrain_samples[k / 2u];
    return vec2<i32>(select(row.xy, row.zw, (k & 1u) == 1u));
}

fn terrain_level_spacing_m(k: u32) -> f32 {
    return params.terrain.z * f32(1u << k);
}

// Level k's window origin: two i16 in a word, x low. Rust twin:
// ClipmapRows::window_origin.
fn terrain_window_origin(k: u32) -> vec2<i32> {
    let w = params.terrain_windows[k / 4u][k % 4u];
    return vec2<i32>(i32(w << 16u) >> 16u, i32(w) >> 16u);
}

// Level k's height at its sample g, m: its window's sample (which holds the
// level's, clamped to the level), g clamped to the window. Rust twin:
// ClipmapWindows::height.
fn terrain_height(k: u32, g: vec2<i32>) -> f32 {
    let p = clamp(g - terrain_window_origin(k), vec2<i32>(0), vec2<i32>(CLIPMAP_WINDOW_SAMPLES - 1));
    let level = params.terrain_levels.z + k * u32(CLIPMAP_WINDOW_SAMPLES * CLIPMAP_WINDOW_SAMPLES);
    return ground_height[level + u32(p.x + CLIPMAP_WINDOW_SAMPLES * p.y)];
}

// Level k's normal at its sample g (central differences).
fn terrain_level_normal(k: u32, g: vec2<i32>) -> vec3<f32> {
    let dx = terrain_height(k, g - vec2<i32>(1, 0)) - terrain_height(k, g + vec2<i32>(1, 0));
    let dz = terrain_height(k, g - vec2<i32>(0, 1)) - terrain_height(k, g + vec2<i32>(0, 1));
    return normalize(vec3<f32>(dx, 2.0 * terrain_level_spacing_m(k), dz));
}

// The snapped centre of level k in its own samples (an even sample).
fn clipmap_centre(k: u32, camera_xz_m: vec2<f32>) -> vec2<i32> {
    let t = vec2<i32>(floor((camera_xz_m - params.terrain.xy) / terrain_level_spacing_m(k)));
    return (t >> vec2<u32>(1u)) * 2;
}

struct TerrainPoint {
    position_m: vec3<f32>,
    normal: vec3<f32>,
    drawn: bool,
}

// Edge quad m of a level: its quad in the level's CLIPMAP_QUADS² (the ring of side
// CLIPMAP_QUADS / 2 + 1 from quad CLIPMAP_QUADS / 4: bottom row, top row, left and
// right columns). Rust twin: clipmap_edge_quad.
fn clipmap_edge_quad(m: i32) -> vec2<i32> {
    let lo = CLIPMAP_QUADS / 4;
    let side = CLIPMAP_QUADS / 2 + 1;
    let hi = lo + side - 1;
    if (m < side) {
        return vec2<i32>(lo + m, lo);
    }
    if (m < 2 * side) {
        return vec2<i32>(lo + m - side, hi);
    }
    if (m < 3 * side - 2) {
        return vec2<i32>(lo, lo + 1 + m - 2 * side);
    }
    return vec2<i32>(hi, lo + 1 + m - (3 * side - 2));
}

// Vertex number v of the clipmap's indexed draw from level `first`
// (params.terrain_levels.x, the water's mirror's .w; the index buffer is
// precip_model::scene::terrain::clipmap_indices): its position and normal,
// blended into the next level's over the level's last CLIPMAP_MORPH_QUADS quads;
// not drawn where it is a grid vertex only the hole's quads use, or an edge quad's
// inside the finer level. Samples off the terrain are clamped to its edge (a quad
// wholly off it collapses).
fn clipmap_vertex(v: u32, camera_xz_m: vec2<f32>, first: u32) -> TerrainPoint {
    var out: TerrainPoint;
    out.drawn = false;
    out.normal = vec3<f32>(0.0, 1.0, 0.0);
    let levels = params.terrain_levels.y;
    let k = first + v / CLIPMAP_LEVEL_VERTICES;
    if (k >= levels) {
        return out;
    }
    let local = v % CLIPMAP_LEVEL_VERTICES;
    let centre = clipmap_centre(k, camera_xz_m);
    var ij: vec2<i32>;
    if (local < CLIPMAP_GRID_VERTICES) {
        ij = vec2<i32>(i32(local % u32(CLIPMAP_QUADS + 1)), i32(local / u32(CLIPMAP_QUADS + 1)));
        let lo = CLIPMAP_QUADS / 4 + 1;
        let hi = 3 * CLIPMAP_QUADS / 4;
        if (k > first && all(ij >= vec2<i32>(lo)) && all(ij <= vec2<i32>(hi))) {
            return out;
        }
    } else {
        let e = i32(local - CLIPMAP_GRID_VERTICES);
        let a = clipmap_edge_quad(e / 6);
        if (k > first) {
            let q = centre + a - vec2<i32>(CLIPMAP_QUADS / 2);
            let inner = clipmap_centre(k - 1u, camera_xz_m) / 2;
            let lo = inner - vec2<i32>(CLIPMAP_QUADS / 4);
            let hi = inner + vec2<i32>(CLIPMAP_QUADS / 4);
            if (all(q >= lo) && all(q + 1 <= hi)) {
                return out;
            }
        }
        // Two triangles a quad: corners (0,0) (0,1) (1,0), (1,0) (0,1) (1,1).
        let c = e % 6;
        ij = a + vec2<i32>(
            select(0, 1, c == 2 || c == 3 || c == 5),
            select(0, 1, c == 1 || c == 4 || c == 5),
        );
    }
    let last = terrain_level_samples(k) - 1;
    if (any(last < vec2<i32>(1))) {
        return out;
    }
    let g = clamp(centre + ij - vec2<i32>(CLIPMAP_QUADS / 2), vec2<i32>(0), last);
    var height = terrain_height(k, g);
    var normal = terrain_level_normal(k, g);
    if (k + 1u < levels) {
        let d = f32(max(abs(g.x - centre.x), abs(g.y - centre.y)));
        let start = f32(CLIPMAP_QUADS / 2 - CLIPMAP_MORPH_QUADS);
        let alpha = clamp((d - start) / f32(CLIPMAP_MORPH_QUADS), 0.0, 1.0);
        if (alpha > 0.0) {
            let c0 = g >> vec2<u32>(1u);
            let c1 = (g + 1) >> vec2<u32>(1u);
            let coarse = 0.25 * (terrain_height(k + 1u, c0) + terrain_height(k + 1u, vec2<i32>(c1.x, c0.y))
                + terrain_height(k + 1u, vec2<i32>(c0.x, c1.y)) + terrain_height(k + 1u, c1));
            height = height + (coarse - height) * alpha;
            let coarse_normal = terrain_level_normal(k + 1u, c0);
            normal = normalize(normal + (coarse_normal - normal) * alpha);
        }
    }
    let xz = params.terrain.xy + vec2<f32>(g) * terrain_level_spacing_m(k);
    out.position_m = vec3<f32>(xz.x, height, xz.y);
    out.normal = normal;
    out.drawn = true;
    return out;
}

// The terrain as a scene vertex: its slope picks the colour along the terrain's
// ramp (Rust: precip_model::scene::terrain::terrain_ramp_u; the land class picks
// the row, per fragment, in fs_terrain) and its snow eligibility. Off the grid it
// is raised by its place's grass far cover whatever its class (the class's texel
// shades it, per fragment): a vertex stage that writes a module-scope private
// (far_cover_slot) made lavapipe grow by ~450 KiB a frame.
fn terrain_scene_vertex(p: TerrainPoint) -> SceneVertex {
    var vertex: SceneVertex;
    vertex.position_m = p.position_m;
    vertex.normal = p.normal;
    let steep = clamp((1.0 - p.normal.y) * 2.0, 0.0, 1.0);
    vertex.uv = vec2<f32>((0.5 + 15.0 * steep) / 16.0, 0.5 / LAND_CLASSES);
    vertex.eligibility = slope_eligibility(p.normal);
    return vertex;
}

// Off the frustum: every vertex of a quad not drawn lands on this one point.
const TERRAIN_NOT_DRAWN: vec4<f32> = vec4<f32>(2.0, 2.0, 2.0, 1.0);

// Vertex v of the clipmap from level `first` through `view_proj`.
fn terrain_varying_of(v: u32, first: u32, view_proj: mat4x4<f32>) -> SceneVarying {
    let p = clipmap_vertex(v, params.camera_m_cone_cos.xz, first);
    var out = scene_varying(terrain_scene_vertex(p), view_proj);
    if (!p.drawn) {
        out.clip = TERRAIN_NOT_DRAWN;
    }
    return out;
}

@vertex
fn vs_terrain(@builtin(vertex_index) v: u32) -> SceneVarying {
    return terrain_varying_of(v, params.terrain_levels.x, params.view_proj);
}

// A terrain fragment: its land class drawn (land_class_at; Rust:
// LandCover::drawn_class_at over LandCover::gpu_copy) picks the
// ramp's row, the share of its snow seen from above and the far cover it reads.
// The class is looked up up to 1.5 pixels (at most 15 m) off the point (smooth
// noise, as the cover's cover_warp_m), so the borders between classes wind instead
// of following the raster's pixels (the ground map's classes, on the CPU, are the
// pixels').
@fragment
fn fs_terrain(in: SceneVarying) -> @location(0) vec4<f32> {
    var v = terrain_varying(in);
    v.normal = terrain_facing_normal(v.normal, normalize_or_zero(params.camera_m_cone_cos.xyz - in.world_m));
    return scene_fragment(v, true);
}

// The terrain reflected about the water bodies' level, into the mirror image
// (render_reflections.wgsl's fs_mirror, its fragments the terrain's).
@vertex
fn vs_terrain_mirror(@builtin(vertex_index) v: u32) -> SceneVarying {
    return terrain_varying_of(v, params.terrain_levels.w, params.mirror_view_proj);
}

@fragment
fn fs_terrain_mirror(in: SceneVarying) -> @location(0) vec4<f32> {
    return mirror_fragment(terrain_varying(in));
}

// A height field is seen from above only: where the normal interpolated over a
// face seen edge-on turns away from the viewer (a crest's outline against the
// ground behind it), it is bent to lie across the view, not flipped as a mesh's
// underside is (surface_look), which lit every crest's outline dark. (The water's
// mirror sees the terrain from the reflected camera, below the shore: there a
// face seen from below is one, and is left to surface_look.) Rust twin:
// precip_model::scene::terrain::facing_normal.
fn terrain_facing_normal(normal: vec3<f32>, to_viewer: vec3<f32>) -> vec3<f32> {
    let n = normalize_or_zero(normal);
    let d = dot(n, to_viewer);
    if (d >= 0.0) {
        return n;
    }
    return normalize_or_zero(n - (d - TERRAIN_EDGE_ON) * to_viewer);
}

// A terrain fragment's varyings with its land class's row, snow share and far
// cover texel (fs_terrain above).
fn terrain_varying(in: SceneVarying) -> SceneVarying {
    var land = 0u;
    if (params.land_cover.w != 0u) {
        let pixel_m = params.land_cover_extent.zw / max(vec2<f32>(params.land_cover.xy), vec2<f32>(1.0));
        land = land_class_at(in.surface_m.xz + cover_warp_m(in.surface_m.xz, min(3.0 * pixel_m, vec2<f32>(30.0))));
    }
    let row = params.land_classes[land];
    var v = in;
    v.uv.y = row.z;
    v.eligibility = in.eligibility * row.x;
    far_cover_slot = terrain_far_slot(land, normalize_or_zero(in.normal).y);
    return v;
}

@vertex
fn vs_terrain_shadow(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let p = clipmap_vertex(v, params.camera_m_cone_cos.xz, params.terrain_levels.x);
    if (!p.drawn) {
        return TERRAIN_NOT_DRAWN;
    }
    return params.sun_view_proj * vec4<f32>(displaced(terrain_scene_vertex(p)), 1.0);
}
