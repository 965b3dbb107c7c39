//! Visibility and particle budgets derived from the weather.
//!
//! Extinction by particles large against the wavelength is twice their cross-section
//! (extinction efficiency 2), summed over the size spectrum; visibility is
//! Koschmieder's `V = 3.912/σ` (2 % contrast). Snow uses Gunn–Marshall in melted
//! diameter `d` and the seed's `ρ = C/D` to get the flake's real diameter
//! (`D² = ρ_w·d³/C`); rain uses Marshall–Palmer. The weather's sums run over the
//! particle kinds' rows ([`crate::particles::kind`]: each kind's share of the rate,
//! spectrum, extinction and count), so they name no kind.
//!
//! ## What is simulated one by one
//!
//! The particles simulated are the ones seen individually: flakes at least as large
//! as the smallest the seed's size law draws (half the mean diameter at the air's
//! temperature), drops in the drawn range `[0.3, 6]` mm. Their number per m³ is the
//! spectrum's tail above that size, `(N0/Λ)·(e^(−Λ·d_min) − e^(−Λ·d_max))`
//! ([`Weather::simulated_number_density_per_m3`]): 2 mm/h of dry snow at −5 °C holds
//! about 79 such flakes per m³ (of 1 137 in all); the rest are in the fog's extinction,
//! which sums the whole spectrum. A camera volume holds that density up to its budget
//! ([`Weather::simulated_particle_count`]).

use crate::particles::kind::ParticleKind;
use crate::physics::grain::{grain_extinction_per_m, settling_concentration_kg_m3};
use crate::physics::raindrop::{MARSHALL_PALMER_N0, marshall_palmer_slope_per_mm};
use crate::physics::snowfall::{gunn_marshall_intercept, gunn_marshall_slope_per_mm};
use crate::physics::snowflake::{WATER_DENSITY_KG_M3, snow_density_constant_kg_m2};
use crate::weather::Weather;

/// Visibility reported for clear air, m.
pub const CLEAR_AIR_VISIBILITY_M: f32 = 100_000.0;

/// Extinction coefficient of snow at `S` mm/h, per m:
/// `σ = (π/2)·(ρ_w/C)·10⁻⁹·N0·6/Λ⁴` (∫ N(d)·2·πD²/4 dd with `D² = ρ_w d³/C`, d in mm).
#[must_use]
pub fn snow_extinction_per_m(snow_rate_mm_per_h: f32, wet: bool) -> f32 {
    if snow_rate_mm_per_h <= 0.0 {
        return 0.0;
    }
    let n0 = gunn_marshall_intercept(snow_rate_mm_per_h);
    let slope = gunn_marshall_slope_per_mm(snow_rate_mm_per_h);
    std::f32::consts::FRAC_PI_2
        * (WATER_DENSITY_KG_M3 / snow_density_constant_kg_m2(wet))
        * 1.0e-9
        * n0
        * 6.0
        / slope.powi(4)
}

/// Extinction coefficient of rain at `R` mm/h, per m: `σ = π·10⁻⁶·N0/Λ³`.
#[must_use]
pub fn rain_extinction_per_m(rain_rate_mm_per_h: f32) -> f32 {
    if rain_rate_mm_per_h <= 0.0 {
        return 0.0;
    }
    std::f32::consts::PI * 1.0e-6 * MARSHALL_PALMER_N0
        / marshall_palmer_slope_per_mm(rain_rate_mm_per_h).powi(3)
}

/// Melted diameter of a flake of real diameter `diameter_m`, mm: `d = (C·D²/ρ_w)^⅓`
/// (the seed's `ρ = C/D`).
#[must_use]
pub fn melted_diameter_mm(diameter_m: f32, wet: bool) -> f32 {
    (snow_density_constant_kg_m2(wet) * diameter_m * diameter_m / WATER_DENSITY_KG_M3).cbrt()
        * 1.0e3
}

/// Particles per m³ of an exponential spectrum `N0·e^(−Λd)` between `from` and `to`
/// (mm): `(N0/Λ)·(e^(−Λ·from) − e^(−Λ·to))`.
#[must_use]
pub fn exponential_tail_per_m3(n0: f32, slope_per_mm: f32, from_mm: f32, to_mm: f32) -> f32 {
    if slope_per_mm > 0.0 && to_mm > from_mm {
        n0 / slope_per_mm * ((-slope_per_mm * from_mm).exp() - (-slope_per_mm * to_mm).exp())
    } else {
        0.0
    }
}

/// Koschmieder visibility `3.912/σ`, m, capped at [`CLEAR_AIR_VISIBILITY_M`].
#[must_use]
pub fn koschmieder_visibility_m(extinction_per_m: f32) -> f32 {
    if extinction_per_m > 3.912 / CLEAR_AIR_VISIBILITY_M {
        3.912 / extinction_per_m
    } else {
        CLEAR_AIR_VISIBILITY_M
    }
}

impl Weather {
    /// Extinction coefficient of the precipitation, per m (fog density follows it):
    /// snow and rain by their spectra, sand and dust by the mass concentration their
    /// settling rate holds in the air ([`crate::physics::grain`]).
    #[must_use]
    pub fn extinction_per_m(&self) -> f32 {
        ParticleKind::ALL
            .iter()
            .map(|k| k.extinction_in(self))
            .sum()
    }

    /// The sand's or dust's part of [`Weather::extinction_per_m`], per m: the mass
    /// concentration its settling rate holds, `C = F/w`, through `σ = 3·C/(ρ_p·d)`.
    #[must_use]
    pub fn grain_extinction_per_m(&self) -> f32 {
        self.grains().map_or(0.0, |g| {
            grain_extinction_per_m(
                settling_concentration_kg_m3(self.grain_rate_kg_per_m2_h(), &g),
                &g,
            )
        })
    }

    /// Grains per m³ in the air (sand and dust; 0 otherwise): the mass concentration
    /// over one mean grain's mass.
    #[must_use]
    pub fn grain_number_density_per_m3(&self) -> f32 {
        self.grains().map_or(0.0, |g| {
            let concentration = settling_concentration_kg_m3(self.grain_rate_kg_per_m2_h(), &g);
            let mass_kg = g.density_kg_m3 * std::f32::consts::FRAC_PI_6 * g.diameter_m.powi(3);
            concentration / mass_kg.max(f32::MIN_POSITIVE)
        })
    }

    /// Visibility in the precipitation, m.
    #[must_use]
    pub fn visibility_m(&self) -> f32 {
        koschmieder_visibility_m(self.extinction_per_m())
    }

    /// Physical number of particles per m³ (flakes plus drops).
    #[must_use]
    pub fn number_density_per_m3(&self) -> f32 {
        ParticleKind::ALL
            .iter()
            .map(|k| k.number_density_in(self))
            .sum()
    }

    /// Flakes and drops per m³ of the sizes simulated one by one (module docs): the
    /// Gunn–Marshall tail above the melted diameter of the smallest flake the seed's
    /// law draws, and Marshall–Palmer between the drawn drop sizes.
    #[must_use]
    pub fn simulated_number_density_per_m3(&self) -> f32 {
        ParticleKind::ALL
            .iter()
            .map(|k| k.spectrum_in(self).map_or(0.0, |s| s.simulated_per_m3()))
            .sum()
    }

    /// How many particles a volume of `volume_m3` holds in reality, of the sizes
    /// simulated one by one.
    #[must_use]
    pub fn physical_particle_count(&self, volume_m3: f32) -> f64 {
        f64::from(self.simulated_number_density_per_m3()) * f64::from(volume_m3.max(0.0))
    }

    /// The simulated count for a volume under a budget, and the fraction of the
    /// physical count ([`Weather::physical_particle_count`]) it is (1 when the budget
    /// covers reality).
    #[must_use]
    pub fn simulated_particle_count(&self, volume_m3: f32, budget: u32) -> (u32, f32) {
        let physical = self.physical_particle_count(volume_m3);
        if physical <= 0.0 {
            return (0, 1.0);
        }
        let count = physical.min(f64::from(budget));
        (count.round() as u32, (count / physical) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::snowflake::mean_snowflake_diameter_m;
    use crate::weather::PrecipitationKind;

    #[test]
    fn one_mm_per_hour_of_dry_snow_hides_things_beyond_half_a_kilometre_or_so() {
        // docs/model.md §7: 0.4–1.2 km.
        let w = Weather {
            intensity_mm_per_h: 1.0,
            ..Weather::default()
        };
        let v = w.visibility_m();
        assert!((400.0..=1200.0).contains(&v), "{v} m");
    }

    #[test]
    fn heavier_precipitation_sees_less_and_clear_air_sees_far() {
        let light = Weather {
            kind: PrecipitationKind::Rain,
            intensity_mm_per_h: 1.0,
            air_temperature_c: 10.0,
            ..Weather::default()
        };
        let heavy = Weather {
            intensity_mm_per_h: 50.0,
            ..light
        };
        assert!(heavy.visibility_m() < light.visibility_m());
        assert!(
            (500.0..3_000.0).contains(&heavy.visibility_m()),
            "{}",
            heavy.visibility_m()
        );
        let none = Weather {
            intensity_mm_per_h: 0.0,
            ..light
        };
        assert!((none.visibility_m() - CLEAR_AIR_VISIBILITY_M).abs() < 1.0);
    }

    #[test]
    fn the_flakes_seen_one_by_one_are_the_spectrum_above_the_smallest_drawn() {
        // 2 mm/h at −5 °C: the seed's mean flake is 8.5 mm, the smallest drawn 4.27 mm,
        // a melted 1.458 mm; Gunn–Marshall holds 1 137 flakes per m³, 79.1 above that.
        let w = Weather {
            intensity_mm_per_h: 2.0,
            air_temperature_c: -5.0,
            ..Weather::default()
        };
        let smallest = 0.5 * mean_snowflake_diameter_m(-5.0);
        assert!((smallest - 0.00427).abs() < 2e-5, "{smallest}");
        let d = melted_diameter_mm(smallest, false);
        assert!((d - 1.458).abs() < 0.002, "{d}");
        assert!((w.number_density_per_m3() - 1137.2).abs() < 1.0);
        let n = w.simulated_number_density_per_m3();
        assert!((n - 79.1).abs() < 0.5, "{n}");
        // Above a melted 2 mm: about 30 per m³ (the figure).
        let above_2mm = exponential_tail_per_m3(
            gunn_marshall_intercept(2.0),
            gunn_marshall_slope_per_mm(2.0),
            2.0,
            f32::INFINITY,
        );
        assert!((above_2mm - 29.2).abs() < 0.5, "{above_2mm}");
        // Rain at 5 mm/h: Marshall–Palmer's 2 736 per m³ less the drops under 0.3 mm.
        let rain = Weather {
            kind: PrecipitationKind::Rain,
            intensity_mm_per_h: 5.0,
            air_temperature_c: 10.0,
            ..Weather::default()
        };
        let slope = marshall_palmer_slope_per_mm(5.0);
        let expected = 8000.0 / slope * ((-slope * 0.3f32).exp() - (-slope * 6.0f32).exp());
        assert!((rain.simulated_number_density_per_m3() - expected).abs() < 1.0);
        assert!((rain.number_density_per_m3() - 2736.0).abs() < 2.0);
    }

    #[test]
    fn budgets_are_documented_fractions() {
        let w = Weather::default();
        let volume = 100.0 * 100.0 * 50.0;
        let (count, fraction) = w.simulated_particle_count(volume, 100_000);
        assert_eq!(count, 100_000);
        let physical = w.physical_particle_count(volume);
        assert!((f64::from(fraction) - 1.0e5 / physical).abs() < 1e-6);
        let (small, f1) = w.simulated_particle_count(1.0, 100_000);
        assert!(small < 2_000 && (f1 - 1.0).abs() < 1e-6);
    }
}
