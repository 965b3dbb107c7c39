// blowing.wgsl: when the wind lifts snow and how much it carries. Rust twin:
// precip_cover::blowing (Li & Pomeroy 1997 thresholds, Liston & Sturm 1998 after
// Kind 1981 for hardened snow and the surface's snow-holding depth, Pomeroy &
// Gray 1990 saltation flux).

const VON_KARMAN: f32 = 0.4;
const WIND_REFERENCE_HEIGHT_M: f32 = 10.0;
const SNOW_ROUGHNESS_M: f32 = 2.0e-4;
const GRAVITY_MPS2: f32 = 9.81;
const WET_SNOW_THRESHOLD_WIND_MPS: f32 = 9.9;
const WET_SNOW_LIQUID_FRACTION: f32 = 0.01;

fn friction_velocity_mps(wind_mps: f32) -> f32 {
    return VON_KARMAN * max(wind_mps, 0.0) / log(WIND_REFERENCE_HEIGHT_M / SNOW_ROUGHNESS_M);
}

fn dry_snow_threshold_wind_mps(air_temperature_c: f32) -> f32 {
    let t = clamp(air_temperature_c, -25.0, 0.0);
    return 9.43 + 0.18 * t + 0.0033 * t * t;
}

fn density_threshold_friction_velocity_mps(density_kg_m3: f32) -> f32 {
    let rho = clamp(density_kg_m3, 0.0, 917.0);
    if (rho <= 300.0) {
        return 0.10 * exp(0.003 * rho);
    }
    return 0.005 * exp(0.013 * rho);
}

fn threshold_friction_velocity_mps(air_temperature_c: f32, density_kg_m3: f32, wet: bool) -> f32 {
    var wind = dry_snow_threshold_wind_mps(air_temperature_c);
    if (wet || air_temperature_c > 0.0) {
        wind = WET_SNOW_THRESHOLD_WIND_MPS;
    }
    return max(friction_velocity_mps(wind), density_threshold_friction_velocity_mps(density_kg_m3));
}

fn air_density_kg_m3(air_temperature_c: f32) -> f32 {
    return 101325.0 / (287.05 * (clamp(air_temperature_c, -80.0, 60.0) + 273.15));
}

fn saltation_flux_kg_per_m_s(friction_velocity: f32, threshold_mps: f32, air_density: f32) -> f32 {
    let u = friction_velocity;
    let ut = max(threshold_mps, 0.0);
    if (u <= ut || u <= 0.0) {
        return 0.0;
    }
    return 0.68 * air_density * ut * (u * u - ut * ut) / (GRAVITY_MPS2 * u);
}

// Rust: precip_cover::Surface::snow_holding_depth_m (Liston & Sturm 1998; SnowModel's
// grassland and bare classes).
fn surface_snow_holding_depth_m(surface: u32) -> f32 {
    if (surface == 2u) {
        return 0.15;
    }
    return 0.01;
}

// Rust: precip_cover::blowing::movable_swe_mm.
fn movable_swe_mm(swe_mm: f32, depth_mm: f32, holding_depth_m: f32) -> f32 {
    let held_mm = holding_depth_m * 1000.0;
    if (!(depth_mm > held_mm) || !(swe_mm > 0.0)) {
        return 0.0;
    }
    return swe_mm * (1.0 - held_mm / depth_mm);
}
