//! Blowing snow: when the wind lifts snow, and how much it carries (WGSL twins in
//! `shaders/blowing.wgsl`, same names).
//!
//! ## Friction velocity
//!
//! The weather's mean wind is taken at the meteorological reference height
//! `z_ref = 10 m` over a snow surface of roughness `z0`; the neutral log law gives
//! the friction velocity
//!
//! ```text
//! u* = κ · U(z_ref) / ln(z_ref / z0),      κ = 0.4,  z0 = 2·10⁻⁴ m
//! ```
//!
//! (`z0` of a snow field 10⁻⁴–10⁻³ m; 2·10⁻⁴ is SnowTran-3D's, Liston & Sturm 1998,
//! *J. Glaciology* 44). The ground map changes `U` locally ([`crate::drift`]: the
//! wind's speed-up over crests and shelter behind obstacles).
//!
//! ## Threshold
//!
//! Snow moves when `u*` exceeds a threshold that the snow's temperature, wetness
//! and age set; the larger of two measured thresholds applies:
//!
//! - Li & Pomeroy (1997, *J. Applied Meteorology* 36), from 16 prairie stations: dry
//!   snow moves above the 10 m wind `U_t = 9.43 + 0.18·T + 0.0033·T²` m/s (T the air
//!   temperature, °C, fitted over −25…0 °C), wet snow above 9.9 m/s (their mean);
//!   both turned into `u*_t` by the log law above.
//! - Age hardens snow by sintering and settling, which the pack's density records:
//!   `u*_t = 0.10·exp(0.003·ρ)` for ρ ≤ 300 kg/m³, `0.005·exp(0.013·ρ)` above
//!   (Liston & Sturm 1998 after Kind 1981): fresh 100 kg/m³ snow 0.13 m/s,
//!   wind-packed 350 kg/m³ 0.47 m/s.
//!
//! ## What the surface holds
//!
//! Snow lying among grass blades or the clods of a field is sheltered by them: only
//! the depth above the surface's snow-holding depth can be lifted
//! ([`crate::Surface::snow_holding_depth_m`] times the texel's eligibility: where
//! no snow may lie, snow in transit is not held; Liston & Sturm 1998), so the
//! wind moves `SWE·(1 − h_v/h)` of a pack `h` deep at most, none while `h ≤ h_v`
//! ([`movable_swe_mm`]). Snow blown onto turf stays there until it fills it.
//!
//! ## Saltation flux
//!
//! Pomeroy & Gray (1990, *Water Resources Research* 26) give the mass carried in
//! saltation across a unit width, kg/(m·s):
//!
//! ```text
//! Q_salt = 0.68 · ρ_air · u*_t · (u*² − u*_t²) / (g · u*)      (0 when u* ≤ u*_t)
//! ```
//!
//! Suspension (which adds as much again above ~15 m/s and sublimates) is not
//! modelled: all moved snow stays in the books.

/// The share of a pack's SWE the wind can move, mm: the SWE above the surface's
/// snow-holding depth `holding_depth_m` of a pack `swe_mm` of water `depth_mm` deep
/// (none at or below it). WGSL twin: same name (blowing.wgsl).
#[must_use]
pub fn movable_swe_mm(swe_mm: f32, depth_mm: f32, holding_depth_m: f32) -> f32 {
    let held_mm = holding_depth_m * 1000.0;
    // NaN compares false: nothing moves.
    if depth_mm > held_mm && swe_mm > 0.0 {
        swe_mm * (1.0 - held_mm / depth_mm)
    } else {
        0.0
    }
}

/// von Kármán's constant κ.
pub const VON_KARMAN: f32 = 0.4;
/// Height of the weather's wind, m (the meteorological 10 m).
pub const WIND_REFERENCE_HEIGHT_M: f32 = 10.0;
/// Aerodynamic roughness `z0` of a snow surface, m (Liston & Sturm 1998).
pub const SNOW_ROUGHNESS_M: f32 = 2.0e-4;
/// Standard gravity, m/s².
pub const GRAVITY_MPS2: f32 = 9.81;
/// The 10 m wind above which wet snow moves, m/s (Li & Pomeroy 1997's mean).
pub const WET_SNOW_THRESHOLD_WIND_MPS: f32 = 9.9;
/// Liquid water, as a fraction of the pack's SWE, above which snow counts as wet.
pub const WET_SNOW_LIQUID_FRACTION: f32 = 0.01;

/// Friction velocity `u*` of a wind of `wind_mps` at [`WIND_REFERENCE_HEIGHT_M`]
/// over snow (neutral log law), m/s.
#[must_use]
pub fn friction_velocity_mps(wind_mps: f32) -> f32 {
    VON_KARMAN * wind_mps.max(0.0) / (WIND_REFERENCE_HEIGHT_M / SNOW_ROUGHNESS_M).ln()
}

/// The 10 m wind above which dry snow moves at `air_temperature_c`, m/s
/// (Li & Pomeroy 1997; the fit's range −25…0 °C, clamped).
#[must_use]
pub fn dry_snow_threshold_wind_mps(air_temperature_c: f32) -> f32 {
    let t = air_temperature_c.clamp(-25.0, 0.0);
    9.43 + 0.18 * t + 0.0033 * t * t
}

/// Threshold friction velocity of snow hardened to `density_kg_m3`, m/s (Liston &
/// Sturm 1998 after Kind 1981).
#[must_use]
pub fn density_threshold_friction_velocity_mps(density_kg_m3: f32) -> f32 {
    let rho = density_kg_m3.clamp(0.0, 917.0);
    if rho <= 300.0 {
        0.10 * (0.003 * rho).exp()
    } else {
        0.005 * (0.013 * rho).exp()
    }
}

/// Threshold friction velocity `u*_t` of a pack: the larger of Li & Pomeroy's
/// (temperature, wetness) and the density's (age), m/s.
#[must_use]
pub fn threshold_friction_velocity_mps(
    air_temperature_c: f32,
    density_kg_m3: f32,
    wet: bool,
) -> f32 {
    let wind = if wet || air_temperature_c > 0.0 {
        WET_SNOW_THRESHOLD_WIND_MPS
    } else {
        dry_snow_threshold_wind_mps(air_temperature_c)
    };
    friction_velocity_mps(wind).max(density_threshold_friction_velocity_mps(density_kg_m3))
}

/// Density of dry air at `air_temperature_c` and sea-level pressure, kg/m³.
#[must_use]
pub fn air_density_kg_m3(air_temperature_c: f32) -> f32 {
    // p / (R_d·T): 101 325 Pa / (287.05 J/(kg·K) · T).
    101_325.0 / (287.05 * (air_temperature_c.clamp(-80.0, 60.0) + 273.15))
}

/// Saltation mass flux across a unit width, kg/(m·s) (Pomeroy & Gray 1990); zero
/// at or below the threshold.
#[must_use]
pub fn saltation_flux_kg_per_m_s(
    friction_velocity_mps: f32,
    threshold_mps: f32,
    air_density_kg_m3: f32,
) -> f32 {
    let (u, ut) = (friction_velocity_mps, threshold_mps.max(0.0));
    if u <= ut || u <= 0.0 {
        return 0.0;
    }
    0.68 * air_density_kg_m3 * ut * (u * u - ut * ut) / (GRAVITY_MPS2 * u)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn only_the_snow_above_the_holding_depth_can_move() {
        // 10 cm of snow on a 15 cm lawn: held; 30 cm: the top half moves.
        assert!(movable_swe_mm(10.0, 100.0, 0.15) <= 0.0);
        assert!(movable_swe_mm(10.0, 150.0, 0.15) <= 0.0);
        assert!((movable_swe_mm(30.0, 300.0, 0.15) - 15.0).abs() < 1.0e-5);
        // Bare ground holds 1 cm.
        assert!((movable_swe_mm(10.0, 100.0, 0.01) - 9.0).abs() < 1.0e-5);
        assert!(movable_swe_mm(0.0, 0.0, 0.01) <= 0.0);
        assert!(movable_swe_mm(f32::NAN, 100.0, 0.01) <= 0.0);
        assert!(movable_swe_mm(10.0, f32::NAN, 0.01) <= 0.0);
    }

    #[test]
    fn li_and_pomeroys_thresholds() {
        // 9.43 m/s at 0 °C, 7.75 at −12 °C, lowest near −25 °C.
        assert!((dry_snow_threshold_wind_mps(0.0) - 9.43).abs() < 1e-4);
        assert!((dry_snow_threshold_wind_mps(-12.0) - 7.7452).abs() < 1e-3);
        assert!(dry_snow_threshold_wind_mps(-25.0) < dry_snow_threshold_wind_mps(-10.0));
        // As friction velocities over snow: 0.35 m/s at 0 °C (the 0.25–0.4 of
        // Kind 1981's dry snow), more for wet or hardened snow.
        let dry = threshold_friction_velocity_mps(0.0, 100.0, false);
        assert!((0.33..0.37).contains(&dry), "{dry}");
        assert!(threshold_friction_velocity_mps(-5.0, 100.0, true) > dry);
        let packed = threshold_friction_velocity_mps(-12.0, 350.0, false);
        assert!((0.45..0.50).contains(&packed), "{packed}");
    }

    #[test]
    fn kinds_density_threshold_is_continuous_at_300() {
        let below = density_threshold_friction_velocity_mps(299.999);
        let above = density_threshold_friction_velocity_mps(300.001);
        assert!((below - above).abs() < 2e-3, "{below} {above}");
    }

    #[test]
    fn pomeroy_and_grays_flux() {
        // A 14 m/s blizzard at −12 °C over fresh snow: u* 0.52, u*_t 0.29,
        // Q ≈ 9 g/(m·s) in saltation (Pomeroy & Gray's Fig. 8 range 1–20 g/(m·s)).
        let u = friction_velocity_mps(14.0);
        let ut = threshold_friction_velocity_mps(-12.0, 70.0, false);
        let q = saltation_flux_kg_per_m_s(u, ut, air_density_kg_m3(-12.0));
        assert!((0.50..0.53).contains(&u), "{u}");
        assert!((0.0085..0.0100).contains(&q), "{q}");
        assert!(saltation_flux_kg_per_m_s(ut, ut, 1.3).abs() < f32::MIN_POSITIVE);
        assert!(saltation_flux_kg_per_m_s(0.9 * ut, ut, 1.3).abs() < f32::MIN_POSITIVE);
    }

    proptest! {
        #[test]
        fn flux_grows_with_the_wind_and_vanishes_below_the_threshold(
            a in 0.0f32..1.5, b in 0.0f32..1.5, ut in 0.05f32..1.0,
        ) {
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            let q_lo = saltation_flux_kg_per_m_s(lo, ut, 1.3);
            let q_hi = saltation_flux_kg_per_m_s(hi, ut, 1.3);
            prop_assert!(q_lo >= 0.0 && q_lo <= q_hi + 1e-9);
            if hi <= ut {
                prop_assert!(q_hi <= 0.0);
            }
        }
    }
}
