//! Degree-day melt (seed 003, equations 10–13). WGSL twins in cover.wgsl.

use crate::params::CoverParams;

/// Snow albedo `A = 0.4·(1 + exp(−k_e·t))`, `t` days since fresh snow: 0.8 fresh,
/// tending to 0.4.
#[must_use]
pub fn snow_albedo(age_days: f32, albedo_decay_per_day: f32) -> f32 {
    0.4 * (1.0 + (-albedo_decay_per_day * age_days.max(0.0)).exp())
}

/// Transmission of sunlight through vegetation of density `C_v`: `k_v = exp(−4·C_v)`.
#[must_use]
pub fn vegetation_transmission(vegetation_density: f32) -> f32 {
    (-4.0 * vegetation_density).exp()
}

/// Melt factor `C_m = k_m·k_v·R_l·(1 − A)`, mm/(°C·day), for snow `age_days` old.
#[must_use]
pub fn melt_factor(params: &CoverParams, age_days: f32) -> f32 {
    params.melt_proportionality_mm_per_c_day
        * vegetation_transmission(params.vegetation_density)
        * params.solar_irradiance_factor
        * (1.0 - snow_albedo(age_days, params.albedo_decay_per_day))
}

/// Potential melt `M = C_m·(T_air − T_m)·t` over `dt_days`, mm of water; `0` when
/// `T_air ≤ T_m`.
#[must_use]
pub fn degree_day_melt_mm(
    params: &CoverParams,
    age_days: f32,
    air_temperature_c: f32,
    dt_days: f32,
) -> f32 {
    let excess = air_temperature_c - params.melt_threshold_c;
    if excess <= 0.0 {
        0.0
    } else {
        melt_factor(params, age_days) * excess * dt_days
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #[test]
        fn albedo_stays_in_0_4_to_0_8(age in 0.0f32..1.0e4, ke in 0.0f32..10.0) {
            let a = snow_albedo(age, ke);
            prop_assert!((0.4..=0.8).contains(&a));
        }

        #[test]
        fn no_melt_at_or_below_the_threshold(t in -60.0f32..=0.0, age in 0.0f32..100.0, dt in 0.0f32..10.0) {
            prop_assert!(degree_day_melt_mm(&CoverParams::default(), age, t, dt).abs() < f32::MIN_POSITIVE);
        }
    }

    #[test]
    fn fresh_snow_albedo_is_0_8_and_decays() {
        assert!((snow_albedo(0.0, 0.2) - 0.8).abs() < 1e-6);
        assert!(snow_albedo(5.0, 0.2) < snow_albedo(1.0, 0.2));
        assert!((snow_albedo(1000.0, 0.2) - 0.4).abs() < 1e-6);
    }

    #[test]
    fn vegetation_shades_the_melt_like_a_forest() {
        // Kuusisto 1980: 2.42 forest vs 3.51 open, a ratio of 0.69.
        let forest = CoverParams {
            vegetation_density: 0.09,
            ..CoverParams::default()
        };
        let ratio = melt_factor(&forest, 7.0) / melt_factor(&CoverParams::default(), 7.0);
        assert!((ratio - 2.42 / 3.51).abs() < 0.02, "{ratio}");
    }
}
