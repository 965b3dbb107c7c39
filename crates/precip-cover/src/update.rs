//! [`update_texel`]: the cover kernel, CPU form (WGSL twin: `cover_update` in
//! `shaders/cover.wgsl`).

use crate::melt::degree_day_melt_mm;
use crate::params::CoverParams;
use crate::snowpack::{compacted_density, new_snow_density};
use crate::texel::CoverTexel;

/// Density of liquid water, kg/m³: converts mm of water to mm of snow.
const WATER_DENSITY_KG_M3: f32 = 1000.0;

/// Below this SWE (mm) a texel counts as bare and its remains run off.
const BARE_SWE_MM: f32 = 1.0e-6;

/// What reaches one texel over one cover step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverInput {
    /// Snow arriving, mm of water (deposits, or the rate times the step: `D_s = C_a·t`).
    pub snow_mm: f32,
    /// Rain arriving, mm.
    pub rain_mm: f32,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Length of the step, days of cover time.
    pub dt_days: f32,
}

/// Advances one texel by one step: input, melt or refreeze, drainage, settling,
/// wetness, ageing. Every amount of water moves between the books' columns, so
/// `deposited = swe + liquid + runoff` holds after the step if it held before.
#[must_use]
pub fn update_texel(texel: CoverTexel, input: CoverInput, params: &CoverParams) -> CoverTexel {
    let mut t = texel;
    let eligibility = t.eligibility.clamp(0.0, 1.0);
    t.deposited_mm += input.snow_mm + input.rain_mm;

    // Snow: the eligible share settles, the rest runs off (walls, heated roads).
    let snow_kept = input.snow_mm * eligibility;
    t.runoff_mm += input.snow_mm - snow_kept;
    if snow_kept > 0.0 {
        let swe_total = t.swe_mm + snow_kept;
        t.age_days *= t.swe_mm / swe_total;
        t.depth_mm += snow_kept * WATER_DENSITY_KG_M3 / new_snow_density(input.air_temperature_c);
        t.swe_mm = swe_total;
    }

    // Rain: held by a pack, runs off bare ground.
    let mut wetting_mm = input.rain_mm;
    if t.swe_mm > 0.0 {
        t.liquid_mm += input.rain_mm;
    } else {
        t.runoff_mm += input.rain_mm;
    }

    // Melt with heat, refreeze without (seed 003: melt stops when the heat runs out).
    let potential = degree_day_melt_mm(params, t.age_days, input.air_temperature_c, input.dt_days);
    if potential > 0.0 {
        let melt = potential.min(t.swe_mm);
        if t.swe_mm > 0.0 {
            t.depth_mm -= t.depth_mm * (melt / t.swe_mm);
        }
        t.swe_mm -= melt;
        t.liquid_mm += melt;
        wetting_mm += melt;
    } else {
        let cold = (params.melt_threshold_c - input.air_temperature_c).max(0.0);
        let refreeze = t
            .liquid_mm
            .min(params.refreeze_factor_mm_per_c_day * cold * input.dt_days);
        t.liquid_mm -= refreeze;
        t.swe_mm += refreeze;
    }

    // Drainage: the pack holds a fraction of its SWE as liquid.
    let capacity = params.water_holding_fraction * t.swe_mm;
    if t.liquid_mm > capacity {
        t.runoff_mm += t.liquid_mm - capacity;
        t.liquid_mm = capacity;
    }

    // Settling toward the settled density.
    if t.swe_mm > BARE_SWE_MM && t.depth_mm > 0.0 {
        let density = t.swe_mm * WATER_DENSITY_KG_M3 / t.depth_mm;
        let settled = compacted_density(
            density,
            params.settled_density_kg_m3,
            params.compaction_time_days,
            input.dt_days,
        );
        t.depth_mm = t.swe_mm * WATER_DENSITY_KG_M3 / settled;
    }

    t.peak_swe_mm = t.peak_swe_mm.max(t.swe_mm);
    t.wetness = (t.wetness + wetting_mm / params.wetting_mm).clamp(0.0, 1.0)
        * (-input.dt_days / params.drying_time_days).exp();
    t.age_days += input.dt_days;

    if t.swe_mm <= BARE_SWE_MM {
        t.runoff_mm += t.swe_mm + t.liquid_mm;
        t.swe_mm = 0.0;
        t.liquid_mm = 0.0;
        t.depth_mm = 0.0;
        t.age_days = 0.0;
        t.peak_swe_mm = 0.0;
    }
    t
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn eligible() -> CoverTexel {
        CoverTexel {
            eligibility: 1.0,
            accumulation_mask: 0.5,
            melt_mask: 0.5,
            ..CoverTexel::default()
        }
    }

    fn books_balance(t: &CoverTexel) -> bool {
        let stored = f64::from(t.swe_mm) + f64::from(t.liquid_mm) + f64::from(t.runoff_mm);
        (stored - f64::from(t.deposited_mm)).abs() <= 1e-4 * f64::from(t.deposited_mm).max(1.0)
    }

    #[test]
    fn rate_accumulation_is_ds_equals_ca_times_t() {
        let mut t = eligible();
        let rate_mm_per_day = 24.0;
        for _ in 0..100 {
            t = update_texel(
                t,
                CoverInput {
                    snow_mm: rate_mm_per_day * 0.01,
                    rain_mm: 0.0,
                    air_temperature_c: -5.0,
                    dt_days: 0.01,
                },
                &CoverParams::default(),
            );
        }
        assert!((t.swe_mm - 24.0).abs() < 1e-3, "{}", t.swe_mm);
        assert!(
            t.depth_mm > 24.0 * 1000.0 / 350.0,
            "depth from new-snow density, settling toward 350"
        );
        assert!(
            t.age_days < 0.6,
            "mass-weighted age of snow fallen over the last day: {}",
            t.age_days
        );
    }

    #[test]
    fn ineligible_texels_never_hold_snow() {
        let mut t = CoverTexel {
            eligibility: 0.0,
            ..eligible()
        };
        for _ in 0..50 {
            t = update_texel(
                t,
                CoverInput {
                    snow_mm: 5.0,
                    rain_mm: 0.0,
                    air_temperature_c: -10.0,
                    dt_days: 0.1,
                },
                &CoverParams::default(),
            );
            assert!(t.swe_mm.abs() < f32::MIN_POSITIVE && t.depth_mm.abs() < f32::MIN_POSITIVE);
        }
        assert!((t.runoff_mm - 250.0).abs() < 1e-3);
    }

    #[test]
    fn default_degree_day_factor_is_that_of_seasonal_snow() {
        // A deep fresh pack melting for two weeks at +3 °C (a spring melt period):
        // the melt per degree-day must lie in 2.5–4 mm/(°C·day) (MODEL.md §7).
        let params = CoverParams::default();
        let mut t = CoverTexel {
            swe_mm: 500.0,
            depth_mm: 2000.0,
            peak_swe_mm: 500.0,
            deposited_mm: 500.0,
            ..eligible()
        };
        let days = 14.0;
        let dt = 0.01;
        let steps = (days / dt) as usize;
        let mut melted = 0.0f64;
        for _ in 0..steps {
            let before = t.swe_mm;
            t = update_texel(
                t,
                CoverInput {
                    snow_mm: 0.0,
                    rain_mm: 0.0,
                    air_temperature_c: 3.0,
                    dt_days: dt,
                },
                &params,
            );
            melted += f64::from(before - t.swe_mm);
        }
        let factor = melted / (3.0 * f64::from(days));
        println!("effective degree-day factor over 14 days at +3 °C: {factor:.3} mm/(°C·day)");
        assert!(
            (2.5..=4.0).contains(&factor),
            "effective degree-day factor {factor}"
        );
    }

    #[test]
    fn melt_water_refreezes_when_the_heat_runs_out() {
        let params = CoverParams::default();
        let mut t = CoverTexel {
            swe_mm: 50.0,
            depth_mm: 200.0,
            peak_swe_mm: 50.0,
            deposited_mm: 50.0,
            age_days: 10.0,
            ..eligible()
        };
        t = update_texel(
            t,
            CoverInput {
                air_temperature_c: 2.0,
                dt_days: 0.5,
                ..CoverInput::default()
            },
            &params,
        );
        assert!(t.liquid_mm > 0.0, "melt water held");
        let held = t.liquid_mm;
        let swe = t.swe_mm;
        t = update_texel(
            t,
            CoverInput {
                air_temperature_c: -5.0,
                dt_days: 0.1,
                ..CoverInput::default()
            },
            &params,
        );
        assert!(
            t.liquid_mm < held && t.swe_mm > swe,
            "refroze: liquid {} swe {}",
            t.liquid_mm,
            t.swe_mm
        );
        assert!(books_balance(&t));
    }

    #[test]
    fn rain_wets_and_runs_off_bare_ground() {
        let t = update_texel(
            eligible(),
            CoverInput {
                rain_mm: 2.0,
                air_temperature_c: 8.0,
                dt_days: 0.001,
                ..CoverInput::default()
            },
            &CoverParams::default(),
        );
        assert!(t.wetness > 0.9 && (t.runoff_mm - 2.0).abs() < 1e-6);
    }

    proptest! {
        #[test]
        fn water_is_conserved_and_never_negative(
            steps in proptest::collection::vec((0.0f32..5.0, 0.0f32..3.0, -20.0f32..15.0, 0.0f32..0.5), 1..80),
            eligibility in 0.0f32..=1.0,
        ) {
            let params = CoverParams::default();
            let mut t = CoverTexel { eligibility, ..eligible() };
            let mut given = 0.0f64;
            for (snow, rain, temp, dt) in steps {
                given += f64::from(snow) + f64::from(rain);
                t = update_texel(t, CoverInput { snow_mm: snow, rain_mm: rain, air_temperature_c: temp, dt_days: dt }, &params);
                prop_assert!(t.swe_mm >= 0.0 && t.liquid_mm >= 0.0 && t.depth_mm >= 0.0 && t.runoff_mm >= 0.0);
                prop_assert!((0.0..=1.0).contains(&t.wetness));
                prop_assert!(books_balance(&t), "{t:?}");
                prop_assert!((f64::from(t.deposited_mm) - given).abs() <= 1e-4 * given.max(1.0));
            }
        }
    }
}
