//! Sand and dust: how fast grains fall, when the wind lifts them, how much it lifts,
//! where a lifted grain starts, and how far one sees through what the air holds.
//! WGSL twins (the per-particle parts): the `grain.rs` section of
//! `shaders/physics.wgsl`.
//!
//! ## Fall
//!
//! A grain falls at the speed where drag balances its weight. Fine dust is in the
//! Stokes regime, `w = (ρ_p − ρ_a)·g·d²/(18·μ)` (Stokes 1851): 10 µm of quartz
//! falls at 7.9 mm/s. Sand is not (a 0.2 mm grain's Reynolds number is about 20), so
//! the fall speed of every grain is Ferguson & Church's (2004, *J. Sediment. Res.*
//! 74(6)) law, which tends to Stokes for fine grains and to a constant drag
//! coefficient for coarse ones: `w = R·g·d²/(C₁·ν + √(0.75·C₂·R·g·d³))` with
//! `R = (ρ_p − ρ_a)/ρ_a`, `C₁ = 18`, `C₂ = 1.0` (natural, angular grains).
//!
//! ## Threshold
//!
//! The wind moves a bed of grains once its friction velocity passes Bagnold's (1941,
//! *The Physics of Blown Sand and Desert Dunes*, ch. 7) fluid threshold
//! `u*_t = A·√((ρ_p − ρ_a)/ρ_a·g·d)`, `A = 0.1`: 0.21 m/s for 0.2 mm quartz. The law
//! holds for grains coarser than about 0.1 mm; finer dust clings to the bed
//! (cohesion) and is not lifted by the wind itself but thrown up by saltating
//! sand's impacts (Gillette 1981; Shao, Raupach & Findlater 1993, *J. Geophys.
//! Res.* 98(D7)), so its threshold is that of the finest saltators
//! ([`SALTATOR_MIN_DIAMETER_M`]).
//!
//! ## Flux
//!
//! Above the threshold the horizontal saltation flux is White's (1979, *J. Geophys.
//! Res.* 84(B8)) `Q = 2.61·(ρ_a/g)·u*³·(1 − u*_t/u*)·(1 + u*_t/u*)²`, kg/(m·s).
//! The mass lifted per second and m² of erodible ground is `F = α·Q`: for sand,
//! `α = 1/ℓ` with `ℓ` the mean hop ([`SALTATION_HOP_M`]: grains hop of the order of
//! a metre in a strong wind, Bagnold ch. 3); for dust, the sandblasting efficiency of
//! Marticorena & Bergametti (1995, *J. Geophys. Res.* 100(D8)),
//! `α = 10^(0.134·clay% − 6)` per cm, for a soil of [`DUST_SOIL_CLAY_PERCENT`] clay.
//!
//! ## Where a lifted grain starts
//!
//! Sand saltates: it leaves the surface upward at `w₀ = 2·u*·(0.5 + f)` (lift-off
//! speeds of the order of u*, widely spread: Anderson & Haff 1988, *Science* 241)
//! and the wind and its weight carry it back: hops of a few centimetres and a metre
//! or two in a 12 m/s wind. Dust is suspended when its fall speed is below the turbulence's
//! (`w/u* < 1`, Bagnold's criterion): the eddies spread it through the surface layer
//! with the Rouse (1937) profile `c(z) ∝ z^(−P)`, `P = w/(κ·u*)`, and a dust particle
//! starts at a height drawn from that profile, at the mean wind's speed.
//!
//! ## Seeing through it
//!
//! Grains are large against visible light, so each removes twice its cross-section
//! (extinction efficiency 2): for a mass concentration `C` of grains of diameter `d`,
//! `σ = 2·(π d²/4)·C/(ρ_p·π d³/6) = 3·C/(ρ_p·d)`; visibility is Koschmieder's
//! `3.912/σ`. A dust haze of 20 mg/m³ of 10 µm dust sees 1.7 km; Chepil &
//! Woodruff's (1957, *Am. J. Sci.* 255) field fit `C = 56·V^(−1.25)` mg/m³ (V in km)
//! gives 28 mg/m³ for 1.7 km.

use crate::physics::snowflake::WATER_DENSITY_KG_M3;

/// Air density, kg/m³ (ISA, sea level).
pub const AIR_DENSITY_KG_M3: f32 = 1.225;
/// Kinematic viscosity of air at 15 °C, m²/s.
pub const AIR_KINEMATIC_VISCOSITY_M2_S: f32 = 1.46e-5;
/// Density of quartz, the common mineral of sand and dust, kg/m³.
pub const QUARTZ_DENSITY_KG_M3: f32 = 2650.0;
/// Von Kármán's constant.
pub const VON_KARMAN: f32 = 0.4;
/// Gravity, m/s².
const GRAVITY_MPS2: f32 = 9.81;
/// Bagnold's threshold coefficient `A` for the fluid threshold.
pub const BAGNOLD_A: f32 = 0.1;
/// White's (1979) saltation-flux coefficient.
pub const WHITE_FLUX_COEFFICIENT: f32 = 2.61;
/// The finest grains that saltate and bombard the bed, m: Bagnold's law holds above.
pub const SALTATOR_MIN_DIAMETER_M: f32 = 1.0e-4;
/// Mean length of a sand grain's hop, m.
pub const SALTATION_HOP_M: f32 = 1.0;
/// Clay in the soil dust comes from, % (a sandy loam).
pub const DUST_SOIL_CLAY_PERCENT: f32 = 10.0;
/// Lift-off speed of a saltating grain over the friction velocity.
pub const LAUNCH_SPEED_PER_FRICTION_VELOCITY: f32 = 2.0;
/// Lowest height a suspended grain is born at, m (the Rouse profile's reference).
pub const SUSPENSION_REFERENCE_HEIGHT_M: f32 = 0.1;
/// Height a saltating grain leaves the surface from, m.
pub const LAUNCH_HEIGHT_M: f32 = 0.02;
/// Roughness length of loose sand, m (Bagnold's `k` for a flat sand bed is d/30;
/// with ripples and the saltation layer it rises to about 1 mm, Owen 1964).
pub const SAND_ROUGHNESS_M: f32 = 1.0e-3;
/// The height the weather's wind is given at, m.
pub const WIND_REFERENCE_HEIGHT_M: f32 = 10.0;

/// Sand or dust: the grains' size and material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grain {
    /// Mean diameter, m (grains are drawn within ±50 %).
    pub diameter_m: f32,
    /// Density, kg/m³.
    pub density_kg_m3: f32,
}

impl Grain {
    /// Medium sand: 0.2 mm quartz.
    pub const SAND: Self = Self {
        diameter_m: 2.0e-4,
        density_kg_m3: QUARTZ_DENSITY_KG_M3,
    };
    /// Mineral dust: 10 µm quartz.
    pub const DUST: Self = Self {
        diameter_m: 1.0e-5,
        density_kg_m3: QUARTZ_DENSITY_KG_M3,
    };

    /// Whether its grains stay suspended in a wind of friction velocity `u*`
    /// (`w/u* < 1`).
    #[must_use]
    pub fn is_suspended_by(&self, friction_velocity_mps: f32) -> bool {
        grain_settling_speed_mps(self.diameter_m, self.density_kg_m3) < friction_velocity_mps
    }
}

/// Stokes' fall speed of a sphere of `diameter_m` and density `density_kg_m3` in
/// air, m/s: `w = (ρ_p − ρ_a)·g·d²/(18·ρ_a·ν)`.
#[must_use]
pub fn stokes_settling_speed_mps(diameter_m: f32, density_kg_m3: f32) -> f32 {
    let d = diameter_m.max(0.0);
    (density_kg_m3 - AIR_DENSITY_KG_M3).max(0.0) * GRAVITY_MPS2 * d * d
        / (18.0 * AIR_DENSITY_KG_M3 * AIR_KINEMATIC_VISCOSITY_M2_S)
}

/// A grain's fall speed in still air, m/s (Ferguson & Church 2004; module docs).
/// WGSL twin: `grain_settling_speed_mps`.
#[must_use]
pub fn grain_settling_speed_mps(diameter_m: f32, density_kg_m3: f32) -> f32 {
    let d = diameter_m.max(0.0);
    let r = (density_kg_m3 - AIR_DENSITY_KG_M3).max(0.0) / AIR_DENSITY_KG_M3;
    let c1 = 18.0;
    let c2 = 1.0;
    let denominator =
        c1 * AIR_KINEMATIC_VISCOSITY_M2_S + (0.75 * c2 * r * GRAVITY_MPS2 * d * d * d).sqrt();
    r * GRAVITY_MPS2 * d * d / denominator.max(f32::MIN_POSITIVE)
}

/// Bagnold's fluid threshold friction velocity of a bed of grains, m/s.
#[must_use]
pub fn bagnold_threshold_friction_velocity_mps(diameter_m: f32, density_kg_m3: f32) -> f32 {
    let r = (density_kg_m3 - AIR_DENSITY_KG_M3).max(0.0) / AIR_DENSITY_KG_M3;
    BAGNOLD_A * (r * GRAVITY_MPS2 * diameter_m.max(0.0)).sqrt()
}

/// The friction velocity at which the wind starts lifting `grain` from a bed: its
/// own Bagnold threshold, or for dust finer than the saltators that of the finest
/// saltating sand that throws it up (module docs).
#[must_use]
pub fn lift_threshold_friction_velocity_mps(grain: &Grain) -> f32 {
    bagnold_threshold_friction_velocity_mps(
        grain.diameter_m.max(SALTATOR_MIN_DIAMETER_M),
        grain.density_kg_m3,
    )
}

/// The friction velocity of a wind of `wind_mps` at [`WIND_REFERENCE_HEIGHT_M`]
/// over loose sand (log profile: `u* = κ·U/ln(z/z₀)`), m/s.
#[must_use]
pub fn sand_friction_velocity_mps(wind_mps: f32) -> f32 {
    VON_KARMAN * wind_mps.max(0.0) / (WIND_REFERENCE_HEIGHT_M / SAND_ROUGHNESS_M).ln()
}

/// White's horizontal saltation flux at friction velocity `u*` over a bed of
/// threshold `u*_t`, kg/(m·s); 0 at or below the threshold.
#[must_use]
pub fn saltation_flux_kg_per_m_s(friction_velocity_mps: f32, threshold_mps: f32) -> f32 {
    let u = friction_velocity_mps;
    if !(u > threshold_mps && u > 0.0) {
        return 0.0;
    }
    let ratio = threshold_mps / u;
    WHITE_FLUX_COEFFICIENT * AIR_DENSITY_KG_M3 / GRAVITY_MPS2
        * u
        * u
        * u
        * (1.0 - ratio)
        * (1.0 + ratio)
        * (1.0 + ratio)
}

/// Marticorena & Bergametti's sandblasting efficiency for a soil of `clay_percent`
/// clay, per m.
#[must_use]
pub fn sandblasting_efficiency_per_m(clay_percent: f32) -> f32 {
    // 10^(0.134·clay − 6) per cm, × 100 cm/m.
    10f32.powf(0.134 * clay_percent.clamp(0.0, 20.0) - 6.0) * 100.0
}

/// The mass of `grain` the wind lifts per second and m² of erodible ground at
/// friction velocity `u*`, kg/(m²·s) (module docs: `F = α·Q`).
#[must_use]
pub fn lifted_flux_kg_per_m2_s(grain: &Grain, friction_velocity_mps: f32) -> f32 {
    let q = saltation_flux_kg_per_m_s(
        friction_velocity_mps,
        lift_threshold_friction_velocity_mps(grain),
    );
    if grain.diameter_m < SALTATOR_MIN_DIAMETER_M {
        sandblasting_efficiency_per_m(DUST_SOIL_CLAY_PERCENT) * q
    } else {
        q / SALTATION_HOP_M
    }
}

/// Where a suspended grain is born: the height above the ground with fraction
/// `f ∈ [0, 1)` of the Rouse profile `c ∝ z^(−P)` below it, between
/// [`SUSPENSION_REFERENCE_HEIGHT_M`] and `top_m`, m.
/// WGSL twin: `rouse_height_m`.
#[must_use]
pub fn rouse_height_m(rouse_number: f32, top_m: f32, f: f32) -> f32 {
    let a = SUSPENSION_REFERENCE_HEIGHT_M;
    let b = top_m.max(a);
    let e = 1.0 - rouse_number;
    if e.abs() < 1.0e-3 {
        return a * (b / a).powf(f);
    }
    (a.powf(e) + f * (b.powf(e) - a.powf(e))).powf(1.0 / e)
}

/// The Rouse number `P = w/(κ·u*)` of grains falling at `settling_mps` in a wind of
/// friction velocity `u*`. WGSL twin: `rouse_number`.
#[must_use]
pub fn rouse_number(settling_mps: f32, friction_velocity_mps: f32) -> f32 {
    settling_mps / (VON_KARMAN * friction_velocity_mps.max(1.0e-3))
}

/// Extinction coefficient of `mass_concentration_kg_m3` of `grain` in the air, per m:
/// `σ = 3·C/(ρ_p·d)`.
#[must_use]
pub fn grain_extinction_per_m(mass_concentration_kg_m3: f32, grain: &Grain) -> f32 {
    3.0 * mass_concentration_kg_m3.max(0.0)
        / (grain.density_kg_m3 * grain.diameter_m).max(f32::MIN_POSITIVE)
}

/// The mass concentration of grains that settle at `flux_kg_per_m2_h` (kg/(m²·h),
/// which is the number of mm/h of water) through still air, kg/m³: `C = F/w`.
#[must_use]
pub fn settling_concentration_kg_m3(flux_kg_per_m2_h: f32, grain: &Grain) -> f32 {
    let w = grain_settling_speed_mps(grain.diameter_m, grain.density_kg_m3);
    flux_kg_per_m2_h.max(0.0) / 3600.0 / w.max(1.0e-6)
}

/// A water-equivalent mm is a kg/m²: grains share the deposits' scale.
const _: () = assert!(WATER_DENSITY_KG_M3 == 1000.0);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ten_micron_dust_falls_at_eight_millimetres_a_second() {
        let stokes = stokes_settling_speed_mps(1.0e-5, QUARTZ_DENSITY_KG_M3);
        let fall = grain_settling_speed_mps(1.0e-5, QUARTZ_DENSITY_KG_M3);
        assert!((stokes - 8.0e-3).abs() < 0.4e-3, "Stokes {stokes} m/s");
        assert!(
            (fall - stokes).abs() < 0.02 * stokes,
            "{fall} vs Stokes {stokes}"
        );
    }

    #[test]
    fn sand_falls_metres_a_second_well_below_stokes() {
        // Measured fall speeds of 0.2 mm quartz in air: about 1.5 m/s.
        let fall = grain_settling_speed_mps(2.0e-4, QUARTZ_DENSITY_KG_M3);
        assert!((1.1..1.8).contains(&fall), "{fall} m/s");
        assert!(fall < 0.5 * stokes_settling_speed_mps(2.0e-4, QUARTZ_DENSITY_KG_M3));
    }

    #[test]
    fn bagnold_threshold_of_fifth_millimetre_quartz_is_a_fifth_metre_a_second() {
        let u = bagnold_threshold_friction_velocity_mps(2.0e-4, QUARTZ_DENSITY_KG_M3);
        assert!((u - 0.2).abs() < 0.015, "{u} m/s");
        // Dust is thrown up by the finest saltators: its threshold is theirs.
        let dust = lift_threshold_friction_velocity_mps(&Grain::DUST);
        assert!((0.12..0.2).contains(&dust), "{dust} m/s");
    }

    #[test]
    fn the_flux_starts_at_the_threshold_and_grows_as_the_cube() {
        assert!(saltation_flux_kg_per_m_s(0.2, 0.21).abs() < f32::MIN_POSITIVE);
        let q1 = saltation_flux_kg_per_m_s(1.0, 0.2);
        let q2 = saltation_flux_kg_per_m_s(2.0, 0.2);
        assert!(q1 > 0.0 && (q2 / q1 - 8.0).abs() < 1.0, "{q1} {q2}");
        // Measured at u* = 0.5 m/s over 0.25 mm sand: a few hundredths of kg/(m·s).
        let q = saltation_flux_kg_per_m_s(0.5, 0.21);
        assert!((0.01..0.1).contains(&q), "{q}");
        // A 14 m/s wind over sand is well above the threshold.
        let u = sand_friction_velocity_mps(14.0);
        assert!(u > 0.5 && u < 0.8, "{u}");
        assert!(lifted_flux_kg_per_m2_s(&Grain::SAND, u) > 0.0);
        assert!(lifted_flux_kg_per_m2_s(&Grain::DUST, u) > 0.0);
        assert!(lifted_flux_kg_per_m2_s(&Grain::SAND, 0.1).abs() < f32::MIN_POSITIVE);
    }

    #[test]
    fn rouse_heights_span_the_layer_and_follow_the_profile() {
        for p in [0.04, 1.0, 3.0] {
            let low = rouse_height_m(p, 20.0, 0.0);
            let high = rouse_height_m(p, 20.0, 1.0);
            assert!((low - SUSPENSION_REFERENCE_HEIGHT_M).abs() < 1e-4);
            assert!((high - 20.0).abs() < 0.5, "{p}: {high}");
        }
        // Nearly uniform for dust, crowded near the ground for heavy grains.
        assert!(rouse_height_m(0.04, 20.0, 0.5) > 7.0);
        assert!(rouse_height_m(3.0, 20.0, 0.5) < 0.2);
        // Dust is suspended in a strong wind, sand is not.
        let u = sand_friction_velocity_mps(14.0);
        assert!(Grain::DUST.is_suspended_by(u) && !Grain::SAND.is_suspended_by(u));
    }

    #[test]
    fn a_dust_haze_of_twenty_milligrams_sees_under_two_kilometres() {
        let sigma = grain_extinction_per_m(20.0e-6, &Grain::DUST);
        let visibility = 3.912 / sigma;
        assert!((visibility - 1_730.0).abs() < 50.0, "{visibility} m");
        // Chepil & Woodruff's field fit for that visibility, within a factor of 1.5.
        let fit_mg = 56.0 * (visibility / 1000.0).powf(-1.25);
        assert!((fit_mg / 20.0 - 1.0).abs() < 0.5, "{fit_mg} mg/m³");
        let c = settling_concentration_kg_m3(1.0, &Grain::SAND);
        assert!((c - 1.0 / 3600.0 / 1.35).abs() < 0.3 * c);
    }
}
