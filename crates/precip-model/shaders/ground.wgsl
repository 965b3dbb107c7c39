// ground.wgsl: how the ground turns the particles' wind (Rust twin: precip_model::physics::terrain_flow);
// after ground_map.wgsl.

// Rust: precip_model::physics::terrain_flow (TERRAIN_FLOW_SPAN_M, TERRAIN_FLOW_DEPTH_M).
const TERRAIN_FLOW_SPAN_M: f32 = 2.0;
const TERRAIN_FLOW_DEPTH_M: f32 = 10.0;
const TERRAIN_FLOW_LOOKAHEAD_M: f32 = 12.0;
const TERRAIN_FLOW_LOOKAHEAD_SAMPLES: u32 = 8u;
const TERRAIN_FLOW_MAX_CLIMB: f32 = 1.0;
const TERRAIN_FLOW_WAKE_REACH_M: f32 = 36.0;
const TERRAIN_FLOW_WAKE_SAMPLES: u32 = 12u;
// Rust: precip_cover::drift::{WAKE_LENGTH_RATIO, SHELTER_RELIEF_M}.
const FLOW_WAKE_LENGTH_RATIO: f32 = 12.0;
const FLOW_SHELTER_RELIEF_M: f32 = 0.3;

// The ground's height at xz + offset, `fallback` off the map.
fn ground_or(xz_m: vec2<f32>, offset_m: vec2<f32>, fallback: f32) -> f32 {
    let g = ground_height_at(xz_m + offset_m);
    return select(fallback, g.y, g.x > 0.0);
}

// Rust: steepest_sight_line (max over the samples of (H − level)/d, 0 if none above).
fn steepest_sight_line(xz: vec2<f32>, direction: vec2<f32>, level_m: f32, reach_m: f32, samples: u32) -> f32 {
    let spacing = reach_m / f32(samples);
    var steepest = 0.0;
    for (var k = 1u; k <= samples; k++) {
        let d = spacing * f32(k);
        let h = ground_height_at(xz + direction * d);
        if (h.x > 0.0) {
            steepest = max(steepest, (h.y - level_m) / d);
        }
    }
    return steepest;
}

// Rust: climb_over_what_is_ahead (the slope the flow climbs before an obstacle).
fn climb_over_what_is_ahead(direction: vec2<f32>, position_m: vec3<f32>) -> f32 {
    let xz = vec2<f32>(position_m.x, position_m.z);
    return min(steepest_sight_line(xz, direction, position_m.y, TERRAIN_FLOW_LOOKAHEAD_M, TERRAIN_FLOW_LOOKAHEAD_SAMPLES), TERRAIN_FLOW_MAX_CLIMB);
}

// Rust: shelter_up_wind (Winstral's S_x for a particle).
fn shelter_up_wind(direction: vec2<f32>, position_m: vec3<f32>) -> f32 {
    let xz = vec2<f32>(position_m.x, position_m.z);
    return steepest_sight_line(xz, -direction, position_m.y + FLOW_SHELTER_RELIEF_M, TERRAIN_FLOW_WAKE_REACH_M, TERRAIN_FLOW_WAKE_SAMPLES);
}

// The wind turned to follow the ground near it: u' = u − w·(u·n)·n (Jackson & Hunt
// 1975's no-penetration condition, fading over TERRAIN_FLOW_DEPTH_M), climbing over
// what is ahead. Rust: terrain_following_wind.
fn terrain_following_wind(wind_mps: vec3<f32>, position_m: vec3<f32>) -> vec3<f32> {
    // Above the highest ground plus the flow's depth nothing changes: skip the reads.
    if (position_m.y >= step_params.flow_ceiling_m) {
        return wind_mps;
    }
    let xz = vec2<f32>(position_m.x, position_m.z);
    let here = ground_height_at(xz);
    if (here.x == 0.0) {
        return wind_mps;
    }
    let weight = clamp(1.0 - (position_m.y - here.y) / TERRAIN_FLOW_DEPTH_M, 0.0, 1.0);
    var along_ground = wind_mps;
    if (weight > 0.0) {
        let s = TERRAIN_FLOW_SPAN_M;
        let normal = normalize(vec3<f32>(
            (ground_or(xz, vec2<f32>(-s, 0.0), here.y) - ground_or(xz, vec2<f32>(s, 0.0), here.y)) / (2.0 * s),
            1.0,
            (ground_or(xz, vec2<f32>(0.0, -s), here.y) - ground_or(xz, vec2<f32>(0.0, s), here.y)) / (2.0 * s),
        ));
        along_ground = wind_mps - normal * (weight * dot(wind_mps, normal));
    }
    let horizontal = vec2<f32>(along_ground.x, along_ground.z);
    let speed = length(horizontal);
    if (speed < 1.0e-3) {
        return along_ground;
    }
    let direction = horizontal / speed;
    let wake = FLOW_WAKE_LENGTH_RATIO * shelter_up_wind(direction, position_m);
    let slowed = 1.0 / (1.0 + wake * wake);
    let climb = climb_over_what_is_ahead(direction, position_m);
    var rise_mps = along_ground.y;
    if (climb > 0.0) {
        rise_mps = max(along_ground.y, speed * slowed * climb);
    }
    return vec3<f32>(along_ground.x * slowed, rise_mps, along_ground.z * slowed);
}
