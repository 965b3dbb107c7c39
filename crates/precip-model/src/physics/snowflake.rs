//! Snowflakes (seed 003, docs/model.md §2): size from temperature, density, mass, terminal
//! speed. WGSL twins in `shaders/physics.wgsl`.

/// Density of liquid water, kg/m³.
pub const WATER_DENSITY_KG_M3: f32 = 1000.0;

/// Temperature above which the mean flake diameter is fixed at 4 cm, °C.
const WARM_FLAKE_LIMIT_C: f32 = -0.061;

/// Mean snowflake diameter, m: `0.015·|T|^−0.35` for `T ≤ −0.061 °C`, else `0.04`.
#[must_use]
pub fn mean_snowflake_diameter_m(air_temperature_c: f32) -> f32 {
    if air_temperature_c <= WARM_FLAKE_LIMIT_C {
        0.015 * air_temperature_c.abs().powf(-0.35)
    } else {
        0.04
    }
}

/// One flake's diameter, m: the mean scaled by `0.5 + f` (±50 %), `f ∈ [0, 1)`.
#[must_use]
pub fn snowflake_diameter_m(air_temperature_c: f32, f: f32) -> f32 {
    mean_snowflake_diameter_m(air_temperature_c) * (0.5 + f)
}

/// The seed's `C` in `ρ = C/D`, kg/m²: 0.170 dry, 0.724 wet.
#[must_use]
pub const fn snow_density_constant_kg_m2(wet: bool) -> f32 {
    if wet { 0.724 } else { 0.170 }
}

/// Flake density `ρ = C/D`, kg/m³.
#[must_use]
pub fn snowflake_density_kg_m3(diameter_m: f32, wet: bool) -> f32 {
    snow_density_constant_kg_m2(wet) / diameter_m
}

/// Flake mass `m = ρ·π·D³/6`, kg.
#[must_use]
pub fn snowflake_mass_kg(diameter_m: f32, wet: bool) -> f32 {
    snowflake_density_kg_m3(diameter_m, wet) * std::f32::consts::PI * diameter_m.powi(3) / 6.0
}

/// Range of the terminal speed `V_pmax` drawn per flake, m/s.
#[must_use]
pub const fn snow_terminal_speed_range_mps(wet: bool) -> (f32, f32) {
    if wet { (1.0, 2.0) } else { (0.5, 1.5) }
}

/// One flake's terminal speed `V_pmax`, m/s, `f ∈ [0, 1)` across its range.
#[must_use]
pub fn snow_terminal_speed_mps(wet: bool, f: f32) -> f32 {
    let (lo, hi) = snow_terminal_speed_range_mps(wet);
    lo + (hi - lo) * f
}

/// Diameter of the flake whose melted drop has diameter `melted_m`, m:
/// mass `C·D²·π/6 = ρ_w·d³·π/6` gives `D = sqrt(ρ_w·d³ / C)`.
#[must_use]
pub fn snowflake_diameter_from_melted_m(melted_m: f32, wet: bool) -> f32 {
    (WATER_DENSITY_KG_M3 * melted_m.powi(3) / snow_density_constant_kg_m2(wet)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diameter_from_temperature_is_continuous_at_the_switch() {
        let below = mean_snowflake_diameter_m(-0.0611);
        assert!((below - 0.04).abs() < 2e-4, "{below}");
        assert!((mean_snowflake_diameter_m(-10.0) - 0.015 * 10f32.powf(-0.35)).abs() < 1e-7);
        assert!(
            mean_snowflake_diameter_m(-20.0) < mean_snowflake_diameter_m(-2.0),
            "colder, smaller"
        );
        assert!(
            (snowflake_diameter_m(-5.0, 0.0) / mean_snowflake_diameter_m(-5.0) - 0.5).abs() < 1e-6
        );
    }

    #[test]
    fn density_and_mass() {
        let d = 0.01;
        assert!((snowflake_density_kg_m3(d, false) - 17.0).abs() < 1e-3);
        let m = snowflake_mass_kg(d, true);
        assert!((m - 72.4 * std::f32::consts::PI * 1e-6 / 6.0).abs() < 1e-9);
        // The melted-diameter relation inverts the mass.
        let melted = (6.0 * m / (std::f32::consts::PI * WATER_DENSITY_KG_M3)).cbrt();
        assert!((snowflake_diameter_from_melted_m(melted, true) - d).abs() < 1e-6);
    }

    #[test]
    fn terminal_speeds_span_the_seeds_ranges() {
        assert!((snow_terminal_speed_mps(false, 0.0) - 0.5).abs() < 1e-6);
        assert!(snow_terminal_speed_mps(false, 0.999_999) <= 1.5);
        assert!((snow_terminal_speed_mps(true, 0.0) - 1.0).abs() < 1e-6);
    }
}
