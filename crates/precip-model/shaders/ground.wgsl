// ground.wgsl: how the ground turns the particles' wind (Rust twin: precip_model::physics::terrain_flow);
// after ground_map.wgsl.

// Rust: precip_model::physics::terrain_flow (FLOW_LATTICE_M, TERRAIN_FLOW_*; the
// ceiling, flow_ceiling_m, comes in step_params).
const FLOW_LATTICE_M: f32 = 1.5;
const TERRAIN_FLOW_LOOKAHEAD_SAMPLES: u32 = 8u;
const TERRAIN_FLOW_MAX_CLIMB: f32 = 1.0;
const TERRAIN_FLOW_WAKE_REACH_M: f32 = 18.0;
const TERRAIN_FLOW_WAKE_SAMPLES: u32 = 12u;
// Rust: precip_cover::drift::WAKE_LENGTH_RATIO.
const FLOW_WAKE_LENGTH_RATIO: f32 = 12.0;

// The ground at xz + offset, `fallback` off the map.
fn ground_or(xz_m: vec2<f32>, offset_m: vec2<f32>, fallback: f32) -> f32 {
    let g = ground_height_at(xz_m + offset_m);
    return select(fallback, g.y, g.x > 0.0);
}

// The ground where the air along the wind through xz comes onto the map, read half
// a texel inside its up-wind edge. Rust: inflow_ground_m.
fn inflow_ground_m(direction: vec2<f32>, xz: vec2<f32>, here_m: f32) -> f32 {
    let low = frames.ground.origin_m;
    let high = low + frames.ground.size_m;
    var to_edge = vec2<f32>(1.0e30, 1.0e30);
    if (direction.x > 0.0) {
        to_edge.x = (xz.x - low.x) / direction.x;
    } else if (direction.x < 0.0) {
        to_edge.x = (xz.x - high.x) / direction.x;
    }
    if (direction.y > 0.0) {
        to_edge.y = (xz.y - low.y) / direction.y;
    } else if (direction.y < 0.0) {
        to_edge.y = (xz.y - high.y) / direction.y;
    }
    let to_edge_m = max(min(to_edge.x, to_edge.y), 0.0);
    let cell = frames.ground.size_m / vec2<f32>(frames.ground.texels);
    let inside_m = 0.5 * min(cell.x, cell.y);
    return ground_or(xz, -direction * max(to_edge_m - inside_m, 0.0), here_m);
}

// The dividing streamline's height G and slope G' along the wind, from the ground
// at a lattice fixed in the world along it. Rust: dividing_streamline.
fn dividing_streamline(direction: vec2<f32>, xz: vec2<f32>, here_m: f32) -> vec2<f32> {
    let s = dot(xz, direction);
    let past = s - floor(s / FLOW_LATTICE_M) * FLOW_LATTICE_M;
    let behind_m = ground_or(xz, -direction * past, here_m);
    let ahead_m = ground_or(xz, direction * (FLOW_LATTICE_M - past), here_m);
    let ground_slope = (ahead_m - behind_m) / FLOW_LATTICE_M;
    let ground_m = behind_m + past * ground_slope;
    var top_m = ground_m;
    var slope = ground_slope;
    for (var k = 1u; k <= TERRAIN_FLOW_LOOKAHEAD_SAMPLES; k++) {
        let d = FLOW_LATTICE_M * f32(k) - past;
        var h = ahead_m;
        if (k > 1u) {
            h = ground_or(xz, direction * d, here_m);
        }
        let g = h - TERRAIN_FLOW_MAX_CLIMB * d;
        if (g > top_m) {
            top_m = g;
            slope = TERRAIN_FLOW_MAX_CLIMB;
        }
    }
    for (var k = 0u; k < TERRAIN_FLOW_WAKE_SAMPLES; k++) {
        let e = FLOW_LATTICE_M * f32(k) + past;
        var h = behind_m;
        if (k > 0u) {
            h = ground_or(xz, -direction * e, here_m);
        }
        let within_reach = (h - ground_m) / TERRAIN_FLOW_WAKE_REACH_M;
        var descent = 1.0 / FLOW_WAKE_LENGTH_RATIO;
        var descent_slope = 1.0 / FLOW_WAKE_LENGTH_RATIO;
        if (within_reach > 1.0 / FLOW_WAKE_LENGTH_RATIO) {
            descent = within_reach;
            descent_slope = within_reach - e * ground_slope / TERRAIN_FLOW_WAKE_REACH_M;
        }
        let g = h - descent * e;
        if (g > top_m) {
            top_m = g;
            slope = -descent_slope;
        }
    }
    return vec2<f32>(top_m, slope);
}

// The wind turned to follow the ground near it: a divergence-free channel flow
// between the dividing streamline G and the ceiling T, still air under G.
// Rust: terrain_following_wind.
fn terrain_following_wind(wind_mps: vec3<f32>, position_m: vec3<f32>) -> vec3<f32> {
    let ceiling_m = step_params.flow_ceiling_m;
    // Above the ceiling (the highest ground plus 10 m or the map's relief) nothing
    // changes: skip the reads.
    if (position_m.y >= ceiling_m) {
        return wind_mps;
    }
    let xz = vec2<f32>(position_m.x, position_m.z);
    let here = ground_height_at(xz);
    if (here.x == 0.0) {
        return wind_mps;
    }
    let horizontal = vec2<f32>(wind_mps.x, wind_mps.z);
    let speed = length(horizontal);
    if (speed < 1.0e-3) {
        let fade = clamp((position_m.y - here.y) / (ceiling_m - here.y), 0.0, 1.0);
        return vec3<f32>(wind_mps.x, wind_mps.y * fade, wind_mps.z);
    }
    let direction = horizontal / speed;
    let streamline = dividing_streamline(direction, xz, here.y);
    let top_m = streamline.x;
    let base_m = inflow_ground_m(direction, xz, here.y);
    let depth_m = ceiling_m - top_m;
    let along_mps = speed * (ceiling_m - base_m) / depth_m;
    if (position_m.y >= top_m) {
        let up = (position_m.y - top_m) / depth_m;
        let rise_mps = along_mps * streamline.y * (1.0 - up) + wind_mps.y * up;
        return vec3<f32>(direction.x * along_mps, rise_mps, direction.y * along_mps);
    }
    return vec3<f32>(0.0, 0.0, 0.0);
}
