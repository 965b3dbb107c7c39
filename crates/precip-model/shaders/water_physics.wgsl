// water_physics.wgsl: water's constants and the numbers built from them, shared by
// the programs that need them. Rust twins: precip_model::physics::snowflake::WATER_DENSITY_KG_M3,
// precip_model::physics::splash::{SURFACE_TENSION_N_M, VISCOSITY_PA_S, weber_number},
// precip_model::drawing::water_look::ripple_phase_speed_mps.

const WATER_DENSITY_KG_M3: f32 = 1000.0;
const SURFACE_TENSION_N_M: f32 = 0.0728;
const VISCOSITY_PA_S: f32 = 1.0e-3;

// We = ρ·D·v²/σ.
fn weber_number(diameter_m: f32, speed_mps: f32) -> f32 {
    return WATER_DENSITY_KG_M3 * max(diameter_m, 0.0) * speed_mps * speed_mps / SURFACE_TENSION_N_M;
}

// c² = g/k + σk/ρ (deep-water capillary–gravity waves).
fn ripple_phase_speed_mps(wavelength_m: f32) -> f32 {
    let k = 6.283185307 / max(wavelength_m, 1.0e-4);
    return sqrt(9.81 / k + SURFACE_TENSION_N_M * k / WATER_DENSITY_KG_M3);
}
