//! [`update_texel`]: the cover kernel, CPU form (WGSL twin: `update_texel` in
//! `shaders/cover.wgsl`).

use crate::melt::degree_day_melt_mm;
use crate::params::CoverParams;
use crate::snowpack::{compacted_density, new_snow_density};
use crate::surface::Surface;
use crate::texel::CoverTexel;
use crate::water::evaporation_mm_per_day;

/// Density of liquid water, kg/m³: converts mm of water to mm of snow.
const WATER_DENSITY_KG_M3: f32 = 1000.0;

/// Below this SWE (mm) a texel counts as bare and its remains melt onto the surface.
const BARE_SWE_MM: f32 = 1.0e-6;

/// Hours per day.
const HOURS_PER_DAY: f32 = 24.0;

/// What reaches one texel over one cover step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverInput {
    /// Snow arriving, mm of water (deposits, or the rate times the step: `D_s = C_a·t`).
    pub snow_mm: f32,
    /// Rain arriving, mm.
    pub rain_mm: f32,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Relative humidity of the air, `[0, 1]` (evaporation).
    pub relative_humidity: f32,
    /// Mean wind speed near the ground, m/s (evaporation).
    pub wind_speed_mps: f32,
    /// Length of the step, days of cover time.
    pub dt_days: f32,
}

/// Advances one texel by one step: input, melt or refreeze, drainage, settling,
/// ageing; then the surface's water: what reaches it (rain on bare ground, melt
/// drained from the pack, snow where none may lie) fills the film, the rest stands;
/// standing water, then the film, infiltrates and evaporates. Every amount of water
/// moves between the books' columns, so [`CoverTexel::imbalance_mm`] stays zero.
/// Overland flow is a separate pass ([`crate::water`]).
#[must_use]
pub fn update_texel(texel: CoverTexel, input: CoverInput, params: &CoverParams) -> CoverTexel {
    let mut t = texel;
    let surface = Surface::from_raw(t.surface);
    let water = surface.water();
    let eligibility = t.eligibility.clamp(0.0, 1.0);
    t.deposited_mm += input.snow_mm + input.rain_mm;

    // Snow: the eligible share settles, the rest melts on contact (heated paving,
    // water) and reaches the surface.
    let snow_kept = input.snow_mm * eligibility;
    let mut to_surface_mm = input.snow_mm - snow_kept;
    if snow_kept > 0.0 {
        let swe_total = t.swe_mm + snow_kept;
        t.age_days *= t.swe_mm / swe_total;
        t.depth_mm += snow_kept * WATER_DENSITY_KG_M3 / new_snow_density(input.air_temperature_c);
        t.swe_mm = swe_total;
    }

    // Rain: held by a pack, else on the surface.
    if t.swe_mm > 0.0 {
        t.liquid_mm += input.rain_mm;
    } else {
        to_surface_mm += input.rain_mm;
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
    } else {
        let cold = (params.melt_threshold_c - input.air_temperature_c).max(0.0);
        let refreeze = t
            .liquid_mm
            .min(params.refreeze_factor_mm_per_c_day * cold * input.dt_days);
        t.liquid_mm -= refreeze;
        t.swe_mm += refreeze;
    }

    // Drainage: the pack holds a fraction of its SWE as liquid; the rest drains to
    // the surface beneath.
    let capacity = params.water_holding_fraction * t.swe_mm;
    if t.liquid_mm > capacity {
        to_surface_mm += t.liquid_mm - capacity;
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
    t.age_days += input.dt_days;

    if t.swe_mm <= BARE_SWE_MM {
        to_surface_mm += t.swe_mm + t.liquid_mm;
        t.swe_mm = 0.0;
        t.liquid_mm = 0.0;
        t.depth_mm = 0.0;
        t.age_days = 0.0;
        t.peak_swe_mm = 0.0;
    }

    // The surface's water.
    if surface == Surface::Water {
        t.runoff_mm += to_surface_mm;
    } else {
        t.film_mm += to_surface_mm;
        let excess = (t.film_mm - water.film_capacity_mm).max(0.0);
        t.film_mm -= excess;
        t.standing_mm += excess;
        let soak = (water.infiltration_mm_per_h * HOURS_PER_DAY * input.dt_days)
            .min(t.standing_mm + t.film_mm);
        let from_standing = soak.min(t.standing_mm);
        let from_film = (soak - from_standing).clamp(0.0, t.film_mm);
        t.standing_mm -= from_standing;
        t.film_mm -= from_film;
        t.infiltrated_mm += from_standing + from_film;
        // A snow pack shields the surface from the air.
        if t.swe_mm <= 0.0 {
            let dry = (evaporation_mm_per_day(
                input.air_temperature_c,
                input.relative_humidity,
                input.wind_speed_mps,
            ) * input.dt_days)
                .min(t.standing_mm + t.film_mm);
            let from_standing = dry.min(t.standing_mm);
            let from_film = (dry - from_standing).clamp(0.0, t.film_mm);
            t.standing_mm -= from_standing;
            t.film_mm -= from_film;
            t.evaporated_mm += from_standing + from_film;
        }
    }
    t.wetness = surface_wetness(&t, water.film_capacity_mm, params.wetting_mm);
    t
}

/// Wetness in `[0, 1]`: the film over its capacity, plus standing water and the
/// pack's liquid over `wetting_mm`.
fn surface_wetness(t: &CoverTexel, film_capacity_mm: f32, wetting_mm: f32) -> f32 {
    let film = if film_capacity_mm > 0.0 {
        t.film_mm / film_capacity_mm
    } else {
        0.0
    };
    (film + (t.standing_mm + t.liquid_mm) / wetting_mm).clamp(0.0, 1.0)
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
        t.imbalance_mm().abs() <= 1e-4 * f64::from(t.deposited_mm).max(1.0)
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
                    ..CoverInput::default()
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
                    ..CoverInput::default()
                },
                &CoverParams::default(),
            );
            assert!(t.swe_mm.abs() < f32::MIN_POSITIVE && t.depth_mm.abs() < f32::MIN_POSITIVE);
        }
        let melted_on_contact = t.surface_water_mm() + t.infiltrated_mm + t.evaporated_mm;
        assert!((melted_on_contact - 250.0).abs() < 1e-3, "{t:?}");
        assert!(books_balance(&t));
    }

    #[test]
    fn default_degree_day_factor_is_that_of_seasonal_snow() {
        // A deep fresh pack melting for two weeks at +3 °C (a spring melt period):
        // the melt per degree-day must lie in 2.5–4 mm/(°C·day) (docs/model.md §7).
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
                    ..CoverInput::default()
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
    fn rain_wets_bare_ground_and_what_the_film_cannot_hold_stands() {
        let asphalt = CoverTexel {
            surface: Surface::Asphalt as u32,
            ..eligible()
        };
        let t = update_texel(
            asphalt,
            CoverInput {
                rain_mm: 2.0,
                air_temperature_c: 8.0,
                relative_humidity: 1.0,
                dt_days: 0.001,
                ..CoverInput::default()
            },
            &CoverParams::default(),
        );
        assert!(t.wetness > 0.99, "{t:?}");
        assert!(
            (t.film_mm - 0.5).abs() < 1e-6,
            "the film holds 0.5 mm on asphalt"
        );
        assert!((t.standing_mm - 1.5).abs() < 1e-6, "the rest stands");
        assert!(t.runoff_mm.abs() < f32::MIN_POSITIVE && books_balance(&t));
    }

    #[test]
    fn soil_soaks_up_at_its_conductivity_and_a_wet_film_dries_in_its_time() {
        let soil = CoverTexel {
            standing_mm: 10.0,
            film_mm: 1.0,
            deposited_mm: 11.0,
            ..eligible()
        };
        let params = CoverParams::default();
        // One hour, saturated air: 3.4 mm soak in (Rawls et al. 1983, loam).
        let t = update_texel(
            soil,
            CoverInput {
                air_temperature_c: 10.0,
                relative_humidity: 1.0,
                dt_days: 1.0 / 24.0,
                ..CoverInput::default()
            },
            &params,
        );
        assert!(
            (t.infiltrated_mm - 3.4).abs() < 1e-4,
            "{}",
            t.infiltrated_mm
        );
        assert!(t.evaporated_mm.abs() < f32::MIN_POSITIVE && books_balance(&t));
        // A wet asphalt film at 18 °C, 70 %, 2 m/s dries in film / E = 0.5 / 3.35 days.
        let mut film = CoverTexel {
            surface: Surface::Asphalt as u32,
            film_mm: 0.5,
            deposited_mm: 0.5,
            ..eligible()
        };
        let e = evaporation_mm_per_day(18.0, 0.7, 2.0);
        let expected_days = 0.5 / e;
        let dt = 0.001;
        let mut days = 0.0;
        while film.film_mm > 0.0 && days < 1.0 {
            film = update_texel(
                film,
                CoverInput {
                    air_temperature_c: 18.0,
                    relative_humidity: 0.7,
                    wind_speed_mps: 2.0,
                    dt_days: dt,
                    ..CoverInput::default()
                },
                &params,
            );
            days += dt;
        }
        println!(
            "0.5 mm on asphalt dried in {:.2} h (E = {e:.2} mm/day)",
            days * 24.0
        );
        assert!(
            (days - expected_days).abs() <= dt + 1e-4,
            "{days} vs {expected_days}"
        );
        assert!(film.wetness.abs() < f32::MIN_POSITIVE && books_balance(&film));
    }

    #[test]
    fn snow_and_rain_on_a_water_body_join_it_and_build_no_cover() {
        let pond = CoverTexel {
            surface: Surface::Water as u32,
            eligibility: 0.0,
            ..eligible()
        };
        let t = update_texel(
            pond,
            CoverInput {
                snow_mm: 3.0,
                rain_mm: 1.0,
                air_temperature_c: -2.0,
                dt_days: 0.01,
                ..CoverInput::default()
            },
            &CoverParams::default(),
        );
        assert!(t.swe_mm.abs() < f32::MIN_POSITIVE && t.depth_mm.abs() < f32::MIN_POSITIVE);
        assert!(t.surface_water_mm().abs() < f32::MIN_POSITIVE);
        assert!((t.runoff_mm - 4.0).abs() < 1e-6 && books_balance(&t));
    }

    proptest! {
        #[test]
        fn water_is_conserved_and_never_negative(
            steps in proptest::collection::vec((0.0f32..5.0, 0.0f32..3.0, -20.0f32..15.0, 0.0f32..0.5), 1..80),
            eligibility in 0.0f32..=1.0,
            surface in 0u32..5,
            humidity in 0.0f32..=1.0,
        ) {
            let params = CoverParams::default();
            let mut t = CoverTexel { eligibility, surface, ..eligible() };
            let mut given = 0.0f64;
            for (snow, rain, temp, dt) in steps {
                given += f64::from(snow) + f64::from(rain);
                t = update_texel(t, CoverInput { snow_mm: snow, rain_mm: rain, air_temperature_c: temp, relative_humidity: humidity, wind_speed_mps: 3.0, dt_days: dt }, &params);
                prop_assert!(t.swe_mm >= 0.0 && t.liquid_mm >= 0.0 && t.depth_mm >= 0.0 && t.runoff_mm >= 0.0);
                prop_assert!(t.film_mm >= 0.0 && t.standing_mm >= 0.0 && t.infiltrated_mm >= 0.0 && t.evaporated_mm >= 0.0);
                prop_assert!((0.0..=1.0).contains(&t.wetness));
                prop_assert!(books_balance(&t), "{t:?}");
                prop_assert!((f64::from(t.deposited_mm) - given).abs() <= 1e-4 * given.max(1.0));
            }
        }
    }
}
