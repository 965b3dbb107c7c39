// physics.wgsl: snowflakes, raindrops, hailstones, grains, drag and rotation.
// Rust twins, function for function: precip_model::physics::{snowflake, raindrop,
// hail, grain, drag, rotation}.

const GRAVITY_MPS2: f32 = 9.81;
const GRAVITY: vec3<f32> = vec3<f32>(0.0, -9.81, 0.0);

// snowflake.rs
fn mean_snowflake_diameter_m(air_temperature_c: f32) -> f32 {
    if (air_temperature_c <= -0.061) {
        return 0.015 * pow(abs(air_temperature_c), -0.35);
    }
    return 0.04;
}

fn snowflake_diameter_m(air_temperature_c: f32, f: f32) -> f32 {
    return mean_snowflake_diameter_m(air_temperature_c) * (0.5 + f);
}

fn snow_terminal_speed_mps(wet: bool, f: f32) -> f32 {
    var lo = 0.5;
    var hi = 1.5;
    if (wet) {
        lo = 1.0;
        hi = 2.0;
    }
    return lo + (hi - lo) * f;
}

// raindrop.rs
const RAIN_DIAMETER_MIN_MM: f32 = 0.3;
const RAIN_DIAMETER_MAX_MM: f32 = 6.0;
const RAIN_DIAMETER_TRIES: u32 = 32u;

fn raindrop_terminal_speed_mps(diameter_mm: f32) -> f32 {
    let d = clamp(diameter_mm, RAIN_DIAMETER_MIN_MM, RAIN_DIAMETER_MAX_MM);
    return 9.65 - 10.3 * exp(-0.6 * d);
}

fn truncated_exponential_mm(from_mm: f32, to_mm: f32, slope_per_mm: f32, f: f32) -> f32 {
    let span = to_mm - from_mm;
    let tail = 1.0 - exp(-slope_per_mm * span);
    return from_mm - log(1.0 - f * tail) / slope_per_mm;
}

fn marshall_palmer_diameter_mm(slope_per_mm: f32, f: f32) -> f32 {
    return truncated_exponential_mm(RAIN_DIAMETER_MIN_MM, RAIN_DIAMETER_MAX_MM, slope_per_mm, f);
}

fn draw_raindrop_diameter_mm(key: u32, slope_per_mm: f32) -> f32 {
    let v_max = raindrop_terminal_speed_mps(RAIN_DIAMETER_MAX_MM);
    var d = RAIN_DIAMETER_MIN_MM;
    for (var k = 0u; k < RAIN_DIAMETER_TRIES; k++) {
        d = marshall_palmer_diameter_mm(slope_per_mm, random_unit(key, DRAW_RAIN_DIAMETER + 2u * k));
        if (random_unit(key, DRAW_RAIN_DIAMETER + 2u * k + 1u) * v_max < raindrop_terminal_speed_mps(d)) {
            break;
        }
    }
    return d;
}

// hail.rs (the spectrum's Λ is solved on the host: SpeciesParams.hail_slope_per_mm)
const HAIL_DIAMETER_MIN_MM: f32 = 5.0;
const HAIL_DIAMETER_MAX_MM: f32 = 50.0;
const HAIL_DIAMETER_TRIES: u32 = 32u;

fn hailstone_terminal_speed_mps(diameter_mm: f32) -> f32 {
    let d = clamp(diameter_mm, HAIL_DIAMETER_MIN_MM, HAIL_DIAMETER_MAX_MM);
    return 11.45 * sqrt(0.1 * d);
}

fn hail_diameter_mm(slope_per_mm: f32, f: f32) -> f32 {
    return truncated_exponential_mm(HAIL_DIAMETER_MIN_MM, HAIL_DIAMETER_MAX_MM, slope_per_mm, f);
}

fn draw_hail_diameter_mm(key: u32, slope_per_mm: f32) -> f32 {
    let v_max = hailstone_terminal_speed_mps(HAIL_DIAMETER_MAX_MM);
    var d = HAIL_DIAMETER_MIN_MM;
    for (var k = 0u; k < HAIL_DIAMETER_TRIES; k++) {
        d = hail_diameter_mm(slope_per_mm, random_unit(key, DRAW_RAIN_DIAMETER + 2u * k));
        if (random_unit(key, DRAW_RAIN_DIAMETER + 2u * k + 1u) * v_max < hailstone_terminal_speed_mps(d)) {
            break;
        }
    }
    return d;
}

// drag.rs: backward Euler of a = g + k·|V_f|·V_f, closed form.
fn drag_velocity(velocity_mps: vec3<f32>, wind_mps: vec3<f32>, terminal_speed_mps: f32, dt_s: f32) -> vec3<f32> {
    let k = GRAVITY_MPS2 / (terminal_speed_mps * terminal_speed_mps);
    let b = wind_mps - velocity_mps - GRAVITY * dt_s;
    let b_len = length(b);
    if (b_len <= 0.0) {
        return wind_mps;
    }
    let w_len = 2.0 * b_len / (1.0 + sqrt(1.0 + 4.0 * dt_s * k * b_len));
    return wind_mps - b * (w_len / b_len);
}

// rotation.rs: returns (|r'|, increasing' as 0/1).
fn advance_rotation(magnitude_rad: f32, increasing: bool, amplitude_rad: f32, speed_rad_per_s: f32, dt_s: f32) -> vec2<f32> {
    let step = speed_rad_per_s * dt_s;
    var moved = magnitude_rad - step;
    if (increasing) {
        moved = magnitude_rad + step;
    }
    let top = 2.0 * amplitude_rad;
    if (moved > top) {
        return vec2<f32>(top, 0.0);
    } else if (moved < 0.0) {
        return vec2<f32>(0.0, 1.0);
    }
    return vec2<f32>(moved, select(0.0, 1.0, increasing));
}

// grain.rs
const AIR_DENSITY_KG_M3: f32 = 1.225;
const AIR_KINEMATIC_VISCOSITY_M2_S: f32 = 1.46e-5;
const VON_KARMAN: f32 = 0.4;
const SUSPENSION_REFERENCE_HEIGHT_M: f32 = 0.1;
const LAUNCH_HEIGHT_M: f32 = 0.02;
const LAUNCH_SPEED_PER_FRICTION_VELOCITY: f32 = 2.0;

fn grain_settling_speed_mps(diameter_m: f32, density_kg_m3: f32) -> f32 {
    let d = max(diameter_m, 0.0);
    let r = max(density_kg_m3 - AIR_DENSITY_KG_M3, 0.0) / AIR_DENSITY_KG_M3;
    let c1 = 18.0;
    let c2 = 1.0;
    let denominator = c1 * AIR_KINEMATIC_VISCOSITY_M2_S + sqrt(0.75 * c2 * r * GRAVITY_MPS2 * d * d * d);
    return r * GRAVITY_MPS2 * d * d / max(denominator, 1.17549435e-38);
}

fn rouse_number(settling_mps: f32, friction_velocity_mps: f32) -> f32 {
    return settling_mps / (VON_KARMAN * max(friction_velocity_mps, 1.0e-3));
}

fn rouse_height_m(rouse: f32, top_m: f32, f: f32) -> f32 {
    let a = SUSPENSION_REFERENCE_HEIGHT_M;
    let b = max(top_m, a);
    let e = 1.0 - rouse;
    if (abs(e) < 1.0e-3) {
        return a * pow(b / a, f);
    }
    return pow(pow(a, e) + f * (pow(b, e) - pow(a, e)), 1.0 / e);
}
