// cover_update.wgsl: the cover kernel and the two kernels of an overland-flow
// iteration. Rust twin: precip_cover::CoverGrid::{step, flow_water}.
// Program: layout, deposit, cover, this file (precip_model::shaders::Program::CoverUpdate).

@group(0) @binding(0) var<uniform> cover_params: CoverStepParams;
@group(0) @binding(1) var<storage, read_write> cover: array<CoverTexel>;
@group(0) @binding(2) var<storage, read_write> deposits: array<atomic<u32>>;

@compute @workgroup_size(64)
fn cover_update(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= cover_params.texel_count) {
        return;
    }
    // Read and clear this texel's landed water (fed by particles) or use the rate.
    let snow_units = atomicExchange(&deposits[2u * i + DEPOSIT_SNOW], 0u);
    let rain_units = atomicExchange(&deposits[2u * i + DEPOSIT_RAIN], 0u);
    let texel = cover[i];
    var snow_mm = cover_params.snow_rate_mm_per_day * cover_params.dt_days;
    var rain_mm = cover_params.rain_rate_mm_per_day * cover_params.dt_days;
    if (texel.feed == COVER_FEED_PARTICLES) {
        snow_mm = f32(snow_units) / DEPOSIT_UNITS_PER_MM;
        rain_mm = f32(rain_units) / DEPOSIT_UNITS_PER_MM;
    }
    cover[i] = update_texel(texel, snow_mm, rain_mm, cover_params);
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
    let h_i = z_i + d_mm * 1.0e-3;
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
        var h_j = 0.0;
        if (j >= 0) {
            let o = cover[u32(j)];
            z_j = o.ground_m;
            h_j = o.ground_m + o.standing_mm * 1.0e-3;
        } else {
            let opposite = neighbour_of(i, k ^ 1u, p);
            var z_o = z_i;
            if (opposite >= 0) {
                z_o = cover[u32(opposite)].ground_m;
            }
            z_j = min(z_i, 2.0 * z_i - z_o);
            h_j = z_j;
        }
        let drop_m = h_i - h_j;
        let h_flow = h_i - max(z_i, z_j);
        if (drop_m <= 0.0 || h_flow <= 0.0) {
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

// One flow iteration, first pass: every texel's four outflows (its own field only).
@compute @workgroup_size(64)
fn water_outflow(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= cover_params.texel_count) {
        return;
    }
    cover[i].outflow_mm = water_outflow_of(i, cover_params.flow_iteration_s, cover_params);
}

// Second pass: every texel sends its outflows and takes its neighbours' toward it
// (precip_cover::water::{water_inflow_of, apply_flow}).
@compute @workgroup_size(64)
fn water_inflow(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= cover_params.texel_count) {
        return;
    }
    var t = cover[i];
    var out_inside = 0.0;
    var out_edge = 0.0;
    var inflow = 0.0;
    for (var k = 0u; k < 4u; k += 1u) {
        let j = neighbour_of(i, k, cover_params);
        if (j >= 0) {
            out_inside += t.outflow_mm[k];
            inflow += cover[u32(j)].outflow_mm[k ^ 1u];
        } else {
            out_edge += t.outflow_mm[k];
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
}
