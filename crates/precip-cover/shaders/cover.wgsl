// cover.wgsl: the snow cover and surface water model. Rust twins:
// precip_cover::{snowpack, melt, update, surface, water}.

struct CoverStepParams {
    melt_threshold_c: f32,
    melt_proportionality_mm_per_c_day: f32,
    solar_irradiance_factor: f32,
    vegetation_density: f32,
    albedo_decay_per_day: f32,
    refreeze_factor_mm_per_c_day: f32,
    water_holding_fraction: f32,
    cover_depletion_exponent: f32,
    settled_density_kg_m3: f32,
    compaction_time_days: f32,
    wet_darkening: f32,
    wetting_mm: f32,
    mask_edge: f32,
    snow_rate_mm_per_day: f32,
    rain_rate_mm_per_day: f32,
    air_temperature_c: f32,
    relative_humidity: f32,
    wind_speed_mps: f32,
    dt_days: f32,
    flow_iteration_s: f32,
    cell_x_m: f32,
    cell_z_m: f32,
    texel_count: u32,
    texels_x: u32,
    wind_x_mps: f32,
    wind_z_mps: f32,
    snow_repose_tan: f32,
    drift_iteration_s: f32,
    origin_x_m: f32,
    origin_z_m: f32,
    reserved: vec2<u32>,
}

struct CoverTexel {
    swe_mm: f32,
    liquid_mm: f32,
    depth_mm: f32,
    age_days: f32,
    peak_swe_mm: f32,
    wetness: f32,
    runoff_mm: f32,
    deposited_mm: f32,
    eligibility: f32,
    accumulation_mask: f32,
    melt_mask: f32,
    feed: u32,
    film_mm: f32,
    standing_mm: f32,
    infiltrated_mm: f32,
    evaporated_mm: f32,
    net_inflow_mm: f32,
    ground_m: f32,
    surface: u32,
    moving_density_kg_m3: f32,
    outflow_mm: vec4<f32>,
    drifted_mm: f32,
    wind_factor: f32,
    saltation_kg_per_m_s: f32,
    edge_drifted_mm: f32,
    dust_kg_m2: f32,
    reserved1: array<u32, 3>,
}

const COVER_FEED_PARTICLES: u32 = 1u;
const BARE_SWE_MM: f32 = 1.0e-6;
const HOURS_PER_DAY: f32 = 24.0;

// surface.rs
const SURFACE_SOIL: u32 = 0u;
const SURFACE_ASPHALT: u32 = 1u;
const SURFACE_GRASS: u32 = 2u;
const SURFACE_ROOF: u32 = 3u;
const SURFACE_WATER: u32 = 4u;
const SURFACE_SAND: u32 = 5u;

struct SurfaceWater {
    film_capacity_mm: f32,
    infiltration_mm_per_h: f32,
    manning_n: f32,
    roughness_mm: f32,
}

fn surface_water(surface: u32) -> SurfaceWater {
    switch surface {
        case 1u: { return SurfaceWater(0.5, 0.0, 0.015, 1.0); }
        case 2u: { return SurfaceWater(2.0, 10.0, 0.15, 30.0); }
        case 3u: { return SurfaceWater(0.3, 0.0, 0.012, 0.5); }
        case 4u: { return SurfaceWater(0.0, 0.0, 0.03, 0.0); }
        case 5u: { return SurfaceWater(0.5, 210.0, 0.02, 2.0); }
        default: { return SurfaceWater(1.0, 3.4, 0.03, 5.0); }
    }
}

// water.rs
const STILL_WATER_MM: f32 = 1.0e-4;
// Rust: precip_cover::water::LEVEL_WATER_M (surfaces this close are level: no flow).
const LEVEL_WATER_M: f32 = 1.0e-4;

fn saturation_vapour_pressure_hpa(air_temperature_c: f32) -> f32 {
    let t = clamp(air_temperature_c, -60.0, 60.0);
    return 6.1094 * exp(17.625 * t / (t + 243.04));
}

fn evaporation_mm_per_day(air_temperature_c: f32, relative_humidity: f32, wind_speed_mps: f32) -> f32 {
    let wind = 0.26 * (1.0 + 0.54 * max(wind_speed_mps, 0.0));
    return wind * saturation_vapour_pressure_hpa(air_temperature_c) * (1.0 - clamp(relative_humidity, 0.0, 1.0));
}

// snowpack.rs
fn new_snow_density(air_temperature_c: f32) -> f32 {
    let above = max(air_temperature_c + 15.0, 0.0);
    return clamp(50.0 + 1.7 * above * sqrt(above), 50.0, 250.0);
}

fn compacted_density(density_kg_m3: f32, settled_kg_m3: f32, tau_days: f32, dt_days: f32) -> f32 {
    if (density_kg_m3 >= settled_kg_m3) {
        return density_kg_m3;
    }
    return settled_kg_m3 + (density_kg_m3 - settled_kg_m3) * exp(-dt_days / tau_days);
}

// melt.rs
fn snow_albedo(age_days: f32, albedo_decay_per_day: f32) -> f32 {
    return 0.4 * (1.0 + exp(-albedo_decay_per_day * max(age_days, 0.0)));
}

fn vegetation_transmission(vegetation_density: f32) -> f32 {
    return exp(-4.0 * vegetation_density);
}

fn melt_factor(p: CoverStepParams, age_days: f32) -> f32 {
    return p.melt_proportionality_mm_per_c_day
        * vegetation_transmission(p.vegetation_density)
        * p.solar_irradiance_factor
        * (1.0 - snow_albedo(age_days, p.albedo_decay_per_day));
}

fn degree_day_melt_mm(p: CoverStepParams, age_days: f32, air_temperature_c: f32, dt_days: f32) -> f32 {
    let excess = air_temperature_c - p.melt_threshold_c;
    if (excess <= 0.0) {
        return 0.0;
    }
    return melt_factor(p, age_days) * excess * dt_days;
}

// update.rs: one texel, one step.
fn update_texel(texel: CoverTexel, snow_mm: f32, rain_mm: f32, p: CoverStepParams) -> CoverTexel {
    var t = texel;
    let air = p.air_temperature_c;
    let dt_days = p.dt_days;
    let water = surface_water(t.surface);
    let eligibility = clamp(t.eligibility, 0.0, 1.0);
    t.deposited_mm += snow_mm + rain_mm;

    let snow_kept = snow_mm * eligibility;
    var to_surface_mm = snow_mm - snow_kept;
    if (snow_kept > 0.0) {
        let swe_total = t.swe_mm + snow_kept;
        t.age_days *= t.swe_mm / swe_total;
        t.depth_mm += snow_kept * WATER_DENSITY_KG_M3 / new_snow_density(air);
        t.swe_mm = swe_total;
    }

    if (t.swe_mm > 0.0) {
        t.liquid_mm += rain_mm;
    } else {
        to_surface_mm += rain_mm;
    }

    let potential = degree_day_melt_mm(p, t.age_days, air, dt_days);
    if (potential > 0.0) {
        let melt = min(potential, t.swe_mm);
        if (t.swe_mm > 0.0) {
            t.depth_mm -= t.depth_mm * (melt / t.swe_mm);
        }
        t.swe_mm -= melt;
        t.liquid_mm += melt;
    } else {
        let cold = max(p.melt_threshold_c - air, 0.0);
        let refreeze = min(t.liquid_mm, p.refreeze_factor_mm_per_c_day * cold * dt_days);
        t.liquid_mm -= refreeze;
        t.swe_mm += refreeze;
    }

    let capacity = p.water_holding_fraction * t.swe_mm;
    if (t.liquid_mm > capacity) {
        to_surface_mm += t.liquid_mm - capacity;
        t.liquid_mm = capacity;
    }

    if (t.swe_mm > BARE_SWE_MM && t.depth_mm > 0.0) {
        let density = t.swe_mm * WATER_DENSITY_KG_M3 / t.depth_mm;
        let settled = compacted_density(density, p.settled_density_kg_m3, p.compaction_time_days, dt_days);
        t.depth_mm = t.swe_mm * WATER_DENSITY_KG_M3 / settled;
    }

    t.peak_swe_mm = max(t.peak_swe_mm, t.swe_mm);
    t.age_days += dt_days;

    if (t.swe_mm <= BARE_SWE_MM) {
        to_surface_mm += t.swe_mm + t.liquid_mm;
        t.swe_mm = 0.0;
        t.liquid_mm = 0.0;
        t.depth_mm = 0.0;
        t.age_days = 0.0;
        t.peak_swe_mm = 0.0;
    }

    if (t.surface == SURFACE_WATER) {
        t.runoff_mm += to_surface_mm;
    } else {
        t.film_mm += to_surface_mm;
        let excess = max(t.film_mm - water.film_capacity_mm, 0.0);
        t.film_mm -= excess;
        t.standing_mm += excess;
        let soak = min(water.infiltration_mm_per_h * HOURS_PER_DAY * dt_days, t.standing_mm + t.film_mm);
        let soak_standing = min(soak, t.standing_mm);
        let soak_film = clamp(soak - soak_standing, 0.0, t.film_mm);
        t.standing_mm -= soak_standing;
        t.film_mm -= soak_film;
        t.infiltrated_mm += soak_standing + soak_film;
        if (t.swe_mm <= 0.0) {
            let dry = min(evaporation_mm_per_day(air, p.relative_humidity, p.wind_speed_mps) * dt_days, t.standing_mm + t.film_mm);
            let dry_standing = min(dry, t.standing_mm);
            let dry_film = clamp(dry - dry_standing, 0.0, t.film_mm);
            t.standing_mm -= dry_standing;
            t.film_mm -= dry_film;
            t.evaporated_mm += dry_standing + dry_film;
        }
    }
    var film = 0.0;
    if (water.film_capacity_mm > 0.0) {
        film = t.film_mm / water.film_capacity_mm;
    }
    t.wetness = clamp(film + (t.standing_mm + t.liquid_mm) / p.wetting_mm, 0.0, 1.0);
    return t;
}

