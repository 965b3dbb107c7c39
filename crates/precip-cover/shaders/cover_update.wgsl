// cover_update.wgsl: the cover kernel, the snow's drift (the wind factor, then two
// kernels an iteration) and the two kernels of an overland-flow iteration. Rust
// twin: precip_cover::CoverGrid::{step, drift_snow, flow_water}.
// Program: layout, deposit, water physics, cover, blowing, this file
// (precip_gpu::shaders::Program::CoverUpdate).

@group(0) @binding(0) var<uniform> cover_params: CoverStepParams;
@group(0) @binding(1) var<storage, read_write> cover: array<CoverTexel>;
@group(0) @binding(2) var<storage, read_write> deposits: array<atomic<u32>>;
// The cover tiles (precip_gpu::recipe::cover_tiles_bytes): for the water's list,
// then the snow's, the count of listed tiles; then, per tile, whether it is marked;
// whether it was listed the time before; then the list (each tile's x | z << 16).
@group(0) @binding(3) var<storage, read_write> cover_tiles: array<atomic<u32>>;
// The flow's and the drift's indirect dispatches (precip_gpu::recipe::
// COVER_TILE_DISPATCH_BYTES_PER_SET), bound in the listings' group only: per list,
// the workgroups (x, 1, 1) its listing writes, then the tiles a workgroup takes
// (the host's).
@group(0) @binding(4) var<storage, read_write> cover_tile_dispatch: array<u32>;

// The most workgroups of a dispatch along x (WebGPU's and Vulkan's least limit).
const MAX_COVER_TILE_WORKGROUPS: u32 = 65535u;

@compute @workgroup_size(64)
fn cover_update(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= cover_params.texel_count) {
        return;
    }
    // Read and clear this texel's landed water (fed by particles) or use the rate.
    let snow_units = atomicExchange(&deposits[DEPOSIT_CHANNELS * i + DEPOSIT_SNOW], 0u);
    let rain_units = atomicExchange(&deposits[DEPOSIT_CHANNELS * i + DEPOSIT_RAIN], 0u);
    let grain_units = atomicExchange(&deposits[DEPOSIT_CHANNELS * i + DEPOSIT_GRAINS], 0u);
    var texel = cover[i];
    // Grains come from particles alone, whatever the texel's feed.
    texel.dust_kg_m2 += f32(grain_units) / DEPOSIT_UNITS_PER_MM;
    var snow_mm = cover_params.snow_rate_mm_per_day * cover_params.dt_days;
    var rain_mm = cover_params.rain_rate_mm_per_day * cover_params.dt_days;
    if (texel.feed == COVER_FEED_PARTICLES) {
        snow_mm = f32(snow_units) / DEPOSIT_UNITS_PER_MM;
        rain_mm = f32(rain_units) / DEPOSIT_UNITS_PER_MM;
    }
    let t = update_texel(texel, snow_mm, rain_mm, cover_params);
    cover[i] = t;
    let g = cover_tiles_of(cover_params);
    mark_water_tile(tile_of_texel(i, g), t, g);
}

// water.rs: overland flow. Neighbour k of texel i: -x, +x, -z, +z.
fn neighbour_of(i: u32, k: u32, p: CoverStepParams) -> i32 {
    let nx = i32(p.texels_x);
    let nz = i32(p.texel_count / p.texels_x);
    let x = i32(i % p.texels_x);
    let z = i32(i / p.texels_x);
    var offsets = array<vec2<i32>, 4>(vec2<i32>(-1, 0), vec2<i32>(1, 0), vec2<i32>(0, -1), vec2<i32>(0, 1));
    let o = offsets[k];
    let a = x + o.x;
    let b = z + o.y;
    if (a < 0 || a >= nx || b < 0 || b >= nz) {
        return -1;
    }
    return a + nx * b;
}

fn water_outflow_of(i: u32, tau_s: f32, p: CoverStepParams) -> vec4<f32> {
    let t = cover[i];
    let d_mm = t.standing_mm;
    if (d_mm <= STILL_WATER_MM || t.surface == SURFACE_WATER) {
        return vec4<f32>(0.0);
    }
    let n = surface_water(t.surface).manning_n;
    let z_i = t.ground_m;
    var out = vec4<f32>(0.0);
    var drops = vec4<f32>(0.0);
    var faces_down = 0u;
    for (var k = 0u; k < 4u; k += 1u) {
        var dx = p.cell_z_m;
        if (k < 2u) {
            dx = p.cell_x_m;
        }
        let j = neighbour_of(i, k, p);
        var z_j = 0.0;
        var d_j_mm = 0.0;
        if (j >= 0) {
            let o = cover[u32(j)];
            z_j = o.ground_m;
            d_j_mm = o.standing_mm;
        } else {
            let opposite = neighbour_of(i, k ^ 1u, p);
            var z_o = z_i;
            if (opposite >= 0) {
                z_o = cover[u32(opposite)].ground_m;
            }
            z_j = min(z_i, 2.0 * z_i - z_o);
        }
        // From the differences (Rust: a kilometre up, z + d rounds to 0.06 mm).
        let drop_m = (z_i - z_j) + (d_mm - d_j_mm) * 1.0e-3;
        let h_flow = d_mm * 1.0e-3 - max(z_j - z_i, 0.0);
        if (drop_m <= LEVEL_WATER_M || h_flow <= 0.0) {
            continue;
        }
        out[k] = pow(h_flow, 5.0 / 3.0) * sqrt(drop_m / dx) * tau_s / (n * dx);
        if (j >= 0) {
            drops[k] = drop_m;
            faces_down += 1u;
        } else {
            drops[k] = 3.0e38;
        }
    }
    let share = 0.5 / f32(max(faces_down, 1u));
    var total = 0.0;
    for (var k = 0u; k < 4u; k += 1u) {
        out[k] = min(out[k], share * drops[k]) * 1.0e3;
        total += out[k];
    }
    if (total > d_mm) {
        out *= d_mm / total;
    }
    return out;
}

// The flow and the drift run over the tiles where they have work, not the whole
// grid (precip_gpu::recipe::COVER_TILE_SIDE): a tile is 8 x 8 texels, and each has
// its list (WATER_TILES, SNOW_TILES). Water and snow move at most a texel an
// iteration, and a texel starts to send only when it or a neighbour took or sent
// something, so between two lists what moves stays within COVER_TILE_REACH tiles of
// a marked tile; the tiles listed are those within that reach of one, and, for
// the snow, once more those listed the time before (they write their outflows back
// to zero). Every texel left out would neither send nor take anything: the
// exchange is the whole grid's, bit for bit, at the cost of the area where it has
// work.
//
// Water: cover_update marks the tiles where it leaves water that can flow (the
// weather's, the melt's, what evaporated or soaked away: it changed), so a
// sub-step's first list (before its first flow iteration alone: the recipe's
// FLOW_GROUPS) holds every wet tile; water_inflow marks the tiles where water moved
// (sent or taken), and the later lists hold those: water at rest, level to
// LEVEL_WATER_M, runs one iteration a sub-step. Snow: a tile is marked by
// snow_wind where a texel would send snow, and listed once a sub-step, before the
// drift's iterations. Every mark is cleared once its list is made.
const COVER_TILE_SIDE: u32 = 8u;
const COVER_TILE_REACH: i32 = 1;
const WATER_TILES: u32 = 0u;
const SNOW_TILES: u32 = 1u;

// The grid in texels and in tiles.
struct CoverTiles {
    texels_x: u32,
    texels_z: u32,
    tiles_x: u32,
    tiles_z: u32,
}

fn cover_tiles_of(p: CoverStepParams) -> CoverTiles {
    let texels_z = p.texel_count / p.texels_x;
    return CoverTiles(
        p.texels_x,
        texels_z,
        (p.texels_x + COVER_TILE_SIDE - 1u) / COVER_TILE_SIDE,
        (texels_z + COVER_TILE_SIDE - 1u) / COVER_TILE_SIDE,
    );
}

// Where list `list` starts in cover_tiles: its count; then, per tile, its mark;
// per tile, whether it was near a mark at the last listing (bit 0) and whether that
// listing listed it (bit 1); then the list.
fn tile_set_start(list: u32, g: CoverTiles) -> u32 {
    return list * (1u + 3u * g.tiles_x * g.tiles_z);
}

// The tile of texel `i`.
fn tile_of_texel(i: u32, g: CoverTiles) -> u32 {
    return (i % g.texels_x) / COVER_TILE_SIDE + g.tiles_x * ((i / g.texels_x) / COVER_TILE_SIDE);
}

// Texel `lane` (0..63, row by row) of the tile at `tile_xz`, or -1 off the grid.
fn cover_tile_texel(tile_xz: vec2<u32>, lane: u32, g: CoverTiles) -> i32 {
    let x = tile_xz.x * COVER_TILE_SIDE + (lane & (COVER_TILE_SIDE - 1u));
    let z = tile_xz.y * COVER_TILE_SIDE + lane / COVER_TILE_SIDE;
    if (x >= g.texels_x || z >= g.texels_z) {
        return -1;
    }
    return i32(x + g.texels_x * z);
}

// Marks tile `tile` of list `list`.
fn mark_cover_tile(list: u32, tile: u32, g: CoverTiles) {
    let at = tile_set_start(list, g) + 1u + tile;
    // Most of a busy tile's texels mark it: a load where the mark is there already
    // costs less than 64 stores to one word.
    if (atomicLoad(&cover_tiles[at]) == 0u) {
        atomicStore(&cover_tiles[at], 1u);
    }
}

// Marks tile `tile` as holding water if texel `t`'s standing water can flow
// (precip_cover::water::water_outflow_of sends none otherwise).
fn mark_water_tile(tile: u32, t: CoverTexel, g: CoverTiles) {
    if (t.standing_mm > STILL_WATER_MM && t.surface != SURFACE_WATER) {
        mark_cover_tile(WATER_TILES, tile, g);
    }
}

var<workgroup> tiles_listed: atomic<u32>;

// Lists the tiles of `list` the next iterations run over, then clears the marks: one
// workgroup, each lane a tile in 64.
fn list_cover_tiles(list: u32, lane: u32) {
    let g = cover_tiles_of(cover_params);
    let start = tile_set_start(list, g);
    let count = g.tiles_x * g.tiles_z;
    let tiles_x = i32(g.tiles_x);
    let tiles_z = i32(g.tiles_z);
    if (lane == 0u) {
        atomicStore(&tiles_listed, 0u);
    }
    workgroupBarrier();
    for (var tile = lane; tile < count; tile += 64u) {
        let tx = i32(tile) % tiles_x;
        let tz = i32(tile) / tiles_x;
        var near = 0u;
        for (var dz = -COVER_TILE_REACH; dz <= COVER_TILE_REACH; dz += 1) {
            for (var dx = -COVER_TILE_REACH; dx <= COVER_TILE_REACH; dx += 1) {
                let x = tx + dx;
                let z = tz + dz;
                if (x >= 0 && x < tiles_x && z >= 0 && z < tiles_z) {
                    near |= atomicLoad(&cover_tiles[start + 1u + u32(x + tiles_x * z)]);
                }
            }
        }
        // Snow: once more the tiles near a mark at the last listing, so they write
        // their outflows back to zero. Water needs not: a texel whose outflows were
        // not zero at the last iteration marked its tile.
        var before = 0u;
        if (list == SNOW_TILES) {
            before = atomicLoad(&cover_tiles[start + 1u + count + tile]) & 1u;
        }
        let listed = near | before;
        atomicStore(&cover_tiles[start + 1u + count + tile], near | (listed << 1u));
        if (listed != 0u) {
            let k = atomicAdd(&tiles_listed, 1u);
            atomicStore(&cover_tiles[start + 1u + 2u * count + k], u32(tx) | (u32(tz) << 16u));
        }
    }
    storageBarrier();
    workgroupBarrier();
    for (var tile = lane; tile < count; tile += 64u) {
        atomicStore(&cover_tiles[start + 1u + tile], 0u);
    }
    if (lane == 0u) {
        let listed = atomicLoad(&tiles_listed);
        atomicStore(&cover_tiles[start], listed);
        // The iterations after this listing run a workgroup per `per` tiles listed
        // (each walks the list with the dispatch's stride), none when none are.
        let d = 4u * list;
        let per = max(cover_tile_dispatch[d + 3u], 1u);
        cover_tile_dispatch[d] = min((listed + per - 1u) / per, MAX_COVER_TILE_WORKGROUPS);
        cover_tile_dispatch[d + 1u] = 1u;
        cover_tile_dispatch[d + 2u] = 1u;
    }
}

// Whether the last listing of `list` listed the tile of texel `j`: only a listed
// texel's outflows are this exchange's (the flow and the drift share the field, so
// an unlisted texel may hold the other's last outflows; on the whole grid, as the
// CPU runs it, an unlisted texel sends nothing).
fn cover_texel_listed(list: u32, j: u32, g: CoverTiles) -> bool {
    let count = g.tiles_x * g.tiles_z;
    return (atomicLoad(&cover_tiles[tile_set_start(list, g) + 1u + count + tile_of_texel(j, g)]) & 2u) != 0u;
}

// Lists the tiles the next group of flow iterations runs over (the recipe's
// FLOW_GROUPS).
@compute @workgroup_size(64)
fn water_tiles_list(@builtin(local_invocation_index) lane: u32) {
    list_cover_tiles(WATER_TILES, lane);
}

// Lists the tiles the drift's iterations of this sub-step run over.
@compute @workgroup_size(64)
fn snow_tiles_list(@builtin(local_invocation_index) lane: u32) {
    list_cover_tiles(SNOW_TILES, lane);
}

// How many tiles of `list` are listed.
fn listed_cover_tiles(list: u32, g: CoverTiles) -> u32 {
    return atomicLoad(&cover_tiles[tile_set_start(list, g)]);
}

// The `k`th tile of `list` listed: (x, z) in tiles.
fn listed_cover_tile(list: u32, k: u32, g: CoverTiles) -> vec2<u32> {
    let packed = atomicLoad(&cover_tiles[tile_set_start(list, g) + 1u + 2u * g.tiles_x * g.tiles_z + k]);
    return vec2<u32>(packed & 0xffffu, packed >> 16u);
}

// One flow iteration, first pass: every listed texel's four outflows (its own
// field only). A workgroup takes a listed tile at a time.
@compute @workgroup_size(64)
fn water_outflow(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let p = cover_params;
    let g = cover_tiles_of(p);
    let listed = listed_cover_tiles(WATER_TILES, g);
    for (var k = group.x + group.y * groups.x; k < listed; k += groups.x * groups.y) {
        let texel = cover_tile_texel(listed_cover_tile(WATER_TILES, k, g), lane, g);
        if (texel >= 0) {
            let i = u32(texel);
            cover[i].outflow_mm = water_outflow_of(i, p.flow_iteration_s, p);
        }
    }
}

// Second pass: every listed texel sends its outflows and takes its neighbours'
// toward it (precip_cover::water::{water_inflow_of, apply_flow}), and marks its
// tile if water is left on it.
@compute @workgroup_size(64)
fn water_inflow(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let p = cover_params;
    let g = cover_tiles_of(p);
    let listed = listed_cover_tiles(WATER_TILES, g);
    for (var k = group.x + group.y * groups.x; k < listed; k += groups.x * groups.y) {
        let tile = listed_cover_tile(WATER_TILES, k, g);
        let texel = cover_tile_texel(tile, lane, g);
        if (texel >= 0) {
            let i = u32(texel);
            var t = cover[i];
            var out_inside = 0.0;
            var out_edge = 0.0;
            var inflow = 0.0;
            for (var n = 0u; n < 4u; n += 1u) {
                let j = neighbour_of(i, n, p);
                if (j >= 0) {
                    out_inside += t.outflow_mm[n];
                    if (cover_texel_listed(WATER_TILES, u32(j), g)) {
                        inflow += cover[u32(j)].outflow_mm[n ^ 1u];
                    }
                } else {
                    out_edge += t.outflow_mm[n];
                }
            }
            t.net_inflow_mm += inflow - out_inside;
            t.runoff_mm += out_edge;
            if (t.surface == SURFACE_WATER) {
                t.runoff_mm += inflow;
            } else {
                t.standing_mm = max(t.standing_mm + inflow - out_inside - out_edge, 0.0);
            }
            cover[i] = t;
            // Its tile is listed again while its water moves: a texel that sent or
            // took nothing this iteration is level with its neighbours (or dry),
            // and stays so until a neighbour's water moves (whose mark reaches it).
            if (out_inside + out_edge > 0.0 || inflow > 0.0) {
                mark_cover_tile(WATER_TILES, tile.x + g.tiles_x * tile.y, g);
            }
        }
    }
}

// drift.rs: snow moved by the wind and by gravity.
const SNOW_DRIFT_ITERATIONS: u32 = 8u;
const WIND_PACKED_DENSITY_KG_M3: f32 = 300.0;
const WAKE_LENGTH_RATIO: f32 = 12.0;
const SHELTER_REACH_M: f32 = 60.0;
const SHELTER_SAMPLES: u32 = 128u;
const SHELTER_RELIEF_M: f32 = 0.3;
const TERRAIN_SPAN_M: f32 = 3.0;
const TERRAIN_SAMPLES: u32 = 16u;
const FULL_CURVATURE: f32 = 0.05;
const NO_SNOW_MM: f32 = 1.0e-6;

fn texel_surface_m(t: CoverTexel) -> f32 {
    return t.ground_m + t.depth_mm * 1.0e-3;
}

// The surface height at world xz: the nearest texel's (off the grid, the edge's).
fn snow_surface_at(xz: vec2<f32>, fallback: f32) -> f32 {
    let p = cover_params;
    let texels = vec2<f32>(f32(p.texels_x), f32(p.texel_count / p.texels_x));
    let t = (xz - vec2<f32>(p.origin_x_m, p.origin_z_m)) / vec2<f32>(p.cell_x_m, p.cell_z_m);
    let cell = clamp(floor(t), vec2<f32>(0.0), max(texels - 1.0, vec2<f32>(0.0)));
    let index = u32(cell.x) + p.texels_x * u32(cell.y);
    if (index >= p.texel_count) {
        return fallback;
    }
    return texel_surface_m(cover[index]);
}

fn cover_texel_centre(i: u32) -> vec2<f32> {
    let p = cover_params;
    let ij = vec2<f32>(f32(i % p.texels_x), f32(i / p.texels_x));
    return vec2<f32>(p.origin_x_m, p.origin_z_m) + (ij + 0.5) * vec2<f32>(p.cell_x_m, p.cell_z_m);
}

fn snow_wind_factor_of(i: u32, wind_mps: vec2<f32>) -> f32 {
    let speed = length(wind_mps);
    if (speed <= 0.0) {
        return 1.0;
    }
    let dir = wind_mps / speed;
    let p = cover_texel_centre(i);
    let h = texel_surface_m(cover[i]);
    let cell = max(min(cover_params.cell_x_m, cover_params.cell_z_m), 1.0e-3);
    let steps = clamp(u32(ceil(TERRAIN_SPAN_M / cell)), 1u, TERRAIN_SAMPLES);
    var up = 0.0;
    var down = 0.0;
    for (var k = 1u; k <= steps; k += 1u) {
        let d = TERRAIN_SPAN_M * f32(k) / f32(steps);
        up += snow_surface_at(p - dir * d, h);
        down += snow_surface_at(p + dir * d, h);
    }
    up /= f32(steps);
    down /= f32(steps);
    let reach = TERRAIN_SPAN_M * f32(steps + 1u) / f32(2u * steps);
    let slope = clamp((h - up) / reach, -0.5, 0.5);
    let curvature = clamp((h - 0.5 * (up + down)) / (2.0 * reach) / FULL_CURVATURE * 0.5, -0.5, 0.5);
    let terrain = 1.0 + 0.5 * slope + 0.5 * curvature;
    let samples = clamp(u32(ceil(SHELTER_REACH_M / cell)), 1u, SHELTER_SAMPLES);
    let spacing = SHELTER_REACH_M / f32(samples);
    var shelter = 0.0;
    for (var k = 1u; k <= samples; k += 1u) {
        let d = spacing * f32(k);
        shelter = max(shelter, (snow_surface_at(p - dir * d, h) - h - SHELTER_RELIEF_M) / d);
    }
    let wake = WAKE_LENGTH_RATIO * shelter;
    return terrain / (1.0 + wake * wake);
}

// Every texel's wind factor, once a step before the drift's iterations; marks the
// tiles where a texel would send snow in the first of them.
@compute @workgroup_size(64)
fn snow_wind(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= cover_params.texel_count) {
        return;
    }
    let wind = vec2<f32>(cover_params.wind_x_mps, cover_params.wind_z_mps);
    var t = cover[i];
    t.wind_factor = snow_wind_factor_of(i, wind);
    cover[i].wind_factor = t.wind_factor;
    let send = snow_send_of(i, t);
    if (any(send.outflow_mm > vec4<f32>(0.0))) {
        let g = cover_tiles_of(cover_params);
        mark_cover_tile(SNOW_TILES, tile_of_texel(i, g), g);
    }
}

// Whether the wind blows out of a texel through face k (-x, +x, -z, +z), or
// (outward == false) into it.
fn faces_wind(k: u32, wind_mps: vec2<f32>, outward: bool) -> bool {
    var component = wind_mps.y;
    if (k < 2u) {
        component = wind_mps.x;
    }
    if ((k % 2u == 0u) == outward) {
        return component < 0.0;
    }
    return component > 0.0;
}

fn face_wind_component(k: u32, wind_mps: vec2<f32>) -> f32 {
    if (k < 2u) {
        return abs(wind_mps.x);
    }
    return abs(wind_mps.y);
}

fn face_spacing_m(k: u32, p: CoverStepParams) -> f32 {
    if (k < 2u) {
        return p.cell_x_m;
    }
    return p.cell_z_m;
}

// What texel `i` (its state `t`) sends in a drift iteration
// (precip_cover::drift::snow_outflow_of).
struct SnowSend {
    outflow_mm: vec4<f32>,
    moving_density_kg_m3: f32,
    saltation_kg_per_m_s: f32,
}

fn snow_send_of(i: u32, t: CoverTexel) -> SnowSend {
    let p = cover_params;
    var send = SnowSend(vec4<f32>(0.0), 0.0, 0.0);
    if (t.swe_mm <= NO_SNOW_MM || t.depth_mm <= 0.0) {
        return send;
    }
    let density = t.swe_mm * 1000.0 / t.depth_mm;
    let wind_mps = vec2<f32>(p.wind_x_mps, p.wind_z_mps);
    let speed = length(wind_mps);
    let h_i = texel_surface_m(t);
    let wet = t.liquid_mm > WET_SNOW_LIQUID_FRACTION * t.swe_mm;
    let threshold = threshold_friction_velocity_mps(p.air_temperature_c, density, wet);
    var flux = saltation_flux_kg_per_m_s(
        friction_velocity_mps(speed * t.wind_factor),
        threshold,
        air_density_kg_m3(p.air_temperature_c),
    );
    var wind = vec4<f32>(0.0);
    var excess = vec4<f32>(0.0);
    var faces_down = 0u;
    for (var k = 0u; k < 4u; k += 1u) {
        let dx = face_spacing_m(k, p);
        let j = neighbour_of(i, k, p);
        if (faces_wind(k, wind_mps, true) && speed > 0.0) {
            wind[k] = flux * face_wind_component(k, wind_mps) / speed * p.drift_iteration_s / dx;
        }
        if (j >= 0) {
            let rest = max(texel_surface_m(cover[u32(j)]) + p.snow_repose_tan * dx, t.ground_m + 0.5 * p.snow_repose_tan * dx);
            excess[k] = max(h_i - rest, 0.0);
            if (excess[k] > 0.0) {
                faces_down += 1u;
            }
        }
    }
    let share = 0.5 / f32(max(faces_down, 1u));
    let slide = share * excess * density;
    // The wind takes only what lies above the surface's snow-holding depth, in the
    // share of the texel where snow may lie (none where it passes in transit).
    var wind_total = wind.x + wind.y + wind.z + wind.w;
    if (wind_total > 0.0) {
        let holding_m = surface_snow_holding_depth_m(t.surface) * clamp(t.eligibility, 0.0, 1.0);
        let movable = movable_swe_mm(t.swe_mm, t.depth_mm, holding_m);
        let held = min(movable / wind_total, 1.0);
        wind *= held;
        flux *= held;
        wind_total = wind.x + wind.y + wind.z + wind.w;
    }
    let slide_total = slide.x + slide.y + slide.z + slide.w;
    let total = wind_total + slide_total;
    if (total <= 0.0) {
        return send;
    }
    let scale = min(t.swe_mm / total, 1.0);
    flux *= scale;
    let wind_density = max(density, WIND_PACKED_DENSITY_KG_M3);
    let volume = wind_total / wind_density + slide_total / density;
    send.outflow_mm = (wind + slide) * scale;
    send.moving_density_kg_m3 = total / volume;
    if (wind_total > 0.0) {
        send.saltation_kg_per_m_s = flux;
    }
    return send;
}

// A drift iteration, first pass: every listed texel's outflows (its own fields
// only). A workgroup takes a listed tile at a time.
@compute @workgroup_size(64)
fn snow_outflow(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let g = cover_tiles_of(cover_params);
    let listed = listed_cover_tiles(SNOW_TILES, g);
    for (var k = group.x + group.y * groups.x; k < listed; k += groups.x * groups.y) {
        let texel = cover_tile_texel(listed_cover_tile(SNOW_TILES, k, g), lane, g);
        if (texel >= 0) {
            let i = u32(texel);
            let send = snow_send_of(i, cover[i]);
            cover[i].outflow_mm = send.outflow_mm;
            cover[i].moving_density_kg_m3 = send.moving_density_kg_m3;
            cover[i].saltation_kg_per_m_s = send.saltation_kg_per_m_s;
        }
    }
}

// Second pass: every listed texel sends its outflows and takes its neighbours'
// toward it (precip_cover::drift::{snow_inflow_of, apply_drift}).
@compute @workgroup_size(64)
fn snow_inflow(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let g = cover_tiles_of(cover_params);
    let listed = listed_cover_tiles(SNOW_TILES, g);
    for (var k = group.x + group.y * groups.x; k < listed; k += groups.x * groups.y) {
        let texel = cover_tile_texel(listed_cover_tile(SNOW_TILES, k, g), lane, g);
        if (texel >= 0) {
            take_drift(u32(texel));
        }
    }
}

// Texel i's exchange in a drift iteration.
fn take_drift(i: u32) {
    let p = cover_params;
    let g = cover_tiles_of(p);
    var t = cover[i];
    let wind_mps = vec2<f32>(p.wind_x_mps, p.wind_z_mps);
    let speed = length(wind_mps);
    var out_inside = 0.0;
    var out_edge = 0.0;
    var in_mm = 0.0;
    var in_edge_mm = 0.0;
    var in_depth_mm = 0.0;
    for (var k = 0u; k < 4u; k += 1u) {
        let j = neighbour_of(i, k, p);
        if (j >= 0) {
            out_inside += t.outflow_mm[k];
            let o = cover[u32(j)];
            let arriving = select(0.0, o.outflow_mm[k ^ 1u], cover_texel_listed(SNOW_TILES, u32(j), g));
            if (arriving > 0.0) {
                in_mm += arriving;
                in_depth_mm += arriving * 1000.0 / o.moving_density_kg_m3;
            }
        } else {
            out_edge += t.outflow_mm[k];
            if (faces_wind(k, wind_mps, false) && speed > 0.0 && t.saltation_kg_per_m_s > 0.0) {
                let arriving = t.saltation_kg_per_m_s * face_wind_component(k, wind_mps) / speed
                    * p.drift_iteration_s / face_spacing_m(k, p);
                in_mm += arriving;
                in_edge_mm += arriving;
                in_depth_mm += arriving * 1000.0 / t.moving_density_kg_m3;
            }
        }
    }
    let out = out_inside + out_edge;
    if (out > 0.0 && t.swe_mm > 0.0) {
        t.depth_mm = max(t.depth_mm * (1.0 - out / t.swe_mm), 0.0);
        t.swe_mm = max(t.swe_mm - out, 0.0);
        t.peak_swe_mm = max(t.peak_swe_mm - out, t.swe_mm);
    }
    // Snow passes on where the wind here lifts fresh wind-packed snow, even where
    // none may lie; elsewhere the eligible share stays and the rest melts.
    var eligibility = clamp(t.eligibility, 0.0, 1.0);
    let in_transit = friction_velocity_mps(speed * t.wind_factor)
        > threshold_friction_velocity_mps(p.air_temperature_c, WIND_PACKED_DENSITY_KG_M3, false);
    if (in_transit) {
        eligibility = 1.0;
    }
    let kept = in_mm * eligibility;
    if (kept > 0.0) {
        let swe = t.swe_mm + kept;
        t.age_days *= t.swe_mm / swe;
        t.swe_mm = swe;
        t.depth_mm += in_depth_mm * eligibility;
        t.peak_swe_mm += kept;
    }
    let melted = in_mm - kept;
    if (t.surface == SURFACE_WATER) {
        t.runoff_mm += melted;
    } else {
        t.standing_mm += melted;
    }
    t.drifted_mm += in_mm - out;
    t.edge_drifted_mm += in_edge_mm - out_edge;
    if (t.swe_mm <= NO_SNOW_MM) {
        t.depth_mm = 0.0;
    }
    cover[i] = t;
}
