//! How water on the scene looks (docs/model.md §6, seed 004): wet surfaces, puddles,
//! rain rings and water bodies. WGSL twins, function by function, in
//! `shaders/water_look.wgsl`; `fs_scene` composes them.
//!
//! ## The model
//!
//! - **Reflection** — Fresnel's equations for unpolarised light at an air–water
//!   interface, `n = 1.333` ([`fresnel_unpolarised`]): 0.020 at normal incidence,
//!   rising to 1 at grazing incidence. Seed 004 weights the reflection by it.
//! - **Wet surfaces** (the film) darken by the seed's `R_d` (the cover's
//!   `wet_darkening`) and grow glossy: a share of the Fresnel reflection of the sky
//!   that grows with wetness ([`WET_GLOSS`]: a film fills the pores but follows the
//!   texture, so its mirror is blurred).
//! - **Puddles** — standing water covers the surface as it rises above the surface's
//!   roughness ([`puddle_cover`]: none below half of it, whole from 1.5 times; 1 mm
//!   on asphalt, 30 mm in turf: [`precip_cover::SurfaceWater::roughness_mm`]) and is
//!   a mirror: Fresnel reflection of the sky over what lies beneath.
//! - **Water bodies** — meshes marked as water (their vertices carry
//!   [`crate::scene::gpu_scene::WATER_BODY_ELIGIBILITY`]): the surface reflects by Fresnel, and what enters comes back
//!   as the upwelling of seed 004's four-flux model reduced to its deep-water limit:
//!   the bottom seen through `2·depth` of water attenuated by Beer–Lambert,
//!   `T = exp(−2·a·depth)`, per colour channel with the absorption of pure water
//!   (Pope & Fry 1997: ≈ 0.35, 0.06, 0.015 /m at 650, 550, 450 nm), over the water's
//!   own scattered colour ([`water_body_colour`]).
//! - **Rain rings** — drops striking standing water make circular capillary–gravity
//!   waves. Each drop's ring travels at the phase speed of the dispersion relation of
//!   deep-water waves, `c² = g/k + σ·k/ρ` ([`ripple_phase_speed_mps`]: 0.23 m/s at
//!   the 1.7 cm minimum, 0.24 m/s at the 2.5 cm wavelength drawn here), and fades
//!   with viscous damping. The drops are placed procedurally, one possible impact a
//!   cell of [`RING_CELL_M`] on two offset lattices, struck at the rate of the
//!   Marshall–Palmer flux of drops larger than 2 mm ([`ring_rate_per_m2_s`]),
//!   capped at one ring a cell at a time (seed 004 bump-maps its ripples the same
//!   way). On water bodies they stand for the capillary waves finer than the
//!   simulated height field's cells ([`crate::physics::water_waves`]), whose slopes add to
//!   theirs.

use glam::{Vec2, Vec3};

use crate::particles::rng::pcg_hash;

/// Refractive index of water (visible light, 20 °C).
pub const WATER_REFRACTIVE_INDEX: f32 = 1.333;

/// The largest share of the Fresnel reflection a fully wet film gives (a puddle
/// gives all of it).
pub const WET_GLOSS: f32 = 0.5;

/// Side of a rain-ring cell, m.
pub const RING_CELL_M: f32 = 0.15;

/// Wavelength of a drawn rain ring, m.
pub const RING_WAVELENGTH_M: f32 = 0.025;

/// Height of a fresh rain ring's crest, m.
pub const RING_AMPLITUDE_M: f32 = 1.5e-3;

/// Life of a rain ring, s (viscous damping of centimetre waves).
pub const RING_LIFE_S: f32 = 0.6;

/// Absorption of pure water, per m (red, green, blue; Pope & Fry 1997).
pub const WATER_ABSORPTION_PER_M: Vec3 = Vec3::new(0.35, 0.06, 0.015);

/// Colour of light scattered back from deep clear water (its upwelling, linear).
pub const DEEP_WATER_COLOUR: Vec3 = Vec3::new(0.01, 0.035, 0.045);

/// Fresnel reflectance of unpolarised light striking water from air at incidence
/// `cos_incidence` (the cosine between the normal and the direction to the viewer).
#[must_use]
pub fn fresnel_unpolarised(cos_incidence: f32, n: f32) -> f32 {
    let ci = cos_incidence.clamp(0.0, 1.0);
    let si2 = (1.0 - ci * ci).max(0.0);
    let ct = (1.0 - si2 / (n * n)).max(0.0).sqrt();
    let rs = (ci - n * ct) / (ci + n * ct);
    let rp = (n * ci - ct) / (n * ci + ct);
    (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0)
}

/// The share of a surface under open water at `puddle_ratio`, its standing water
/// over the depth that tops its texture ([`precip_cover::CoverTexel::puddle_ratio`]).
#[must_use]
pub fn puddle_cover(puddle_ratio: f32) -> f32 {
    let t = ((puddle_ratio - 0.5) / (1.5 - 0.5)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Phase speed of a deep-water capillary–gravity wave of `wavelength_m`, m/s:
/// `c² = g/k + σk/ρ`, σ = 0.0728 N/m, ρ = 1000 kg/m³ (WGSL twin in
/// `water_physics.wgsl`).
#[must_use]
pub fn ripple_phase_speed_mps(wavelength_m: f32) -> f32 {
    let k = std::f32::consts::TAU / wavelength_m.max(1.0e-4);
    (9.81 / k
        + crate::physics::splash::SURFACE_TENSION_N_M * k
            / crate::physics::snowflake::WATER_DENSITY_KG_M3)
        .sqrt()
}

/// Drops larger than 2 mm striking a square metre each second under rain of
/// `rain_mm_per_h`: the Marshall–Palmer spectrum `N0·e^(−ΛD)`, `N0` = 8000
/// m⁻³mm⁻¹, `Λ = 4.1·R^−0.21` mm⁻¹, times their fall speed (≈ 7 m/s above 2 mm).
#[must_use]
pub fn ring_rate_per_m2_s(rain_mm_per_h: f32) -> f32 {
    if rain_mm_per_h <= 0.0 {
        return 0.0;
    }
    let lambda = 4.1 * rain_mm_per_h.powf(-0.21);
    8000.0 * (-2.0 * lambda).exp() / lambda * 7.0
}

/// The slope (∂h/∂x, ∂h/∂z) of the rain rings at world `xz_m` and time `time_s`
/// under a strike rate of `rate_per_m2_s` (unitless).
#[must_use]
pub fn ring_slope(xz_m: Vec2, time_s: f32, rate_per_m2_s: f32) -> Vec2 {
    if rate_per_m2_s <= 0.0 {
        return Vec2::ZERO;
    }
    // One strike a cell every `period` s on average, never two rings at once.
    let period = (1.0 / (rate_per_m2_s * RING_CELL_M * RING_CELL_M)).max(RING_LIFE_S);
    let mut slope = Vec2::ZERO;
    for layer in 0..2u32 {
        let shifted = xz_m / RING_CELL_M + Vec2::splat(0.5 * layer as f32);
        let cell = shifted.floor();
        let key = pcg_hash(pcg_hash(cell.x as i32 as u32 ^ (layer << 30)) ^ (cell.y as i32 as u32));
        let phase = (key >> 8) as f32 / 16_777_216.0;
        let t = time_s / period + phase;
        let cycle = t.floor() as i32 as u32;
        let age_s = (t - t.floor()) * period;
        if age_s > RING_LIFE_S {
            continue;
        }
        let strike = pcg_hash(key ^ cycle);
        let centre = Vec2::new(
            0.2 + 0.6 * ((strike & 0xffff) as f32 / 65_536.0),
            0.2 + 0.6 * ((strike >> 16) as f32 / 65_536.0),
        );
        slope += ring_wave_slope((shifted - cell - centre) * RING_CELL_M, age_s);
    }
    slope
}

/// The slope of one ring `age_s` after its drop struck, at `offset_m` from where it
/// struck: a wave packet of [`RING_WAVELENGTH_M`] whose crest has travelled at the
/// phase speed, fading over [`RING_LIFE_S`].
#[must_use]
pub fn ring_wave_slope(offset_m: Vec2, age_s: f32) -> Vec2 {
    let speed = ripple_phase_speed_mps(RING_WAVELENGTH_M);
    let k = std::f32::consts::TAU / RING_WAVELENGTH_M;
    let r = offset_m.length();
    let front = r - speed * age_s;
    let envelope = (-(front / RING_WAVELENGTH_M).powi(2)).exp()
        * (1.0 - age_s / RING_LIFE_S).max(0.0)
        * RING_AMPLITUDE_M;
    // ∂/∂r of envelope·cos(k·front), the envelope's own slope neglected beside k's.
    let dh_dr = -envelope * k * (k * front).sin();
    if r > 1.0e-5 {
        offset_m / r * dh_dr
    } else {
        Vec2::ZERO
    }
}

/// The sky seen in a mirror along unit direction `dir`: the CIE standard overcast
/// sky (Moon & Spencer 1942), `L(θ) = L_z·(1 + 2 sin θ)/3`, scaled so its horizon
/// is `horizon` (the fog's colour); below the horizon, the horizon.
#[must_use]
pub fn overcast_sky(horizon: Vec3, dir: Vec3) -> Vec3 {
    (horizon * (1.0 + 2.0 * dir.y.max(0.0))).min(Vec3::ONE)
}

/// What a water body shows of its inside: the bottom (`bottom_colour`, linear)
/// through `2·depth_m` of water over the deep water's scattered colour.
#[must_use]
pub fn water_body_colour(bottom_colour: Vec3, depth_m: f32) -> Vec3 {
    let t = (-2.0 * depth_m.max(0.0) * WATER_ABSORPTION_PER_M).exp();
    bottom_colour * t + DEEP_WATER_COLOUR * (Vec3::ONE - t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_is_two_per_cent_head_on_and_total_at_grazing() {
        let head_on = fresnel_unpolarised(1.0, WATER_REFRACTIVE_INDEX);
        assert!((head_on - 0.0204).abs() < 5e-4, "{head_on}");
        let at_60 = fresnel_unpolarised(0.5, WATER_REFRACTIVE_INDEX);
        assert!((at_60 - 0.059).abs() < 3e-3, "60°: {at_60}");
        let grazing = fresnel_unpolarised(0.0, WATER_REFRACTIVE_INDEX);
        assert!(grazing > 0.999, "{grazing}");
        let mut last = 0.0;
        for i in 0..=90 {
            let f = fresnel_unpolarised((90 - i) as f32 * 0.01745, WATER_REFRACTIVE_INDEX);
            assert!(f + 1e-6 >= last, "monotonic toward grazing");
            last = f;
        }
    }

    #[test]
    fn ripples_travel_at_the_dispersion_relations_phase_speed() {
        let c_min = (1..400)
            .map(|i| ripple_phase_speed_mps(i as f32 * 1.0e-4))
            .fold(f32::INFINITY, f32::min);
        assert!((c_min - 0.231).abs() < 0.003, "minimum phase speed {c_min}");
        assert!(
            (ripple_phase_speed_mps(1.0) - 1.249).abs() < 0.01,
            "gravity waves"
        );
        // A ring's crest, followed through time, moves at c: the radius where the
        // slope peaks, 0.1 s and 0.3 s after the strike.
        let peak = |age: f32| {
            (1..2000)
                .map(|i| i as f32 * 1.0e-4)
                .max_by(|a, b| {
                    let sa = ring_wave_slope(Vec2::new(*a, 0.0), age).length();
                    let sb = ring_wave_slope(Vec2::new(*b, 0.0), age).length();
                    sa.total_cmp(&sb)
                })
                .unwrap_or(0.0)
        };
        let measured = (peak(0.3) - peak(0.1)) / 0.2;
        let c = ripple_phase_speed_mps(RING_WAVELENGTH_M);
        println!("ring crest speed {measured:.3} m/s, phase speed {c:.3} m/s");
        assert!((c - 0.239).abs() < 0.002, "{c}");
        assert!((measured - c).abs() < 0.05 * c, "{measured} vs {c}");
        // Rings appear where it rains and nowhere when it does not.
        let struck = (0..400)
            .filter(|i| ring_slope(Vec2::new(0.37, 1.21), *i as f32 * 0.05, 50.0).length() > 0.0)
            .count();
        assert!(struck > 0);
        assert!(ring_slope(Vec2::new(0.37, 1.21), 3.0, 0.0).length() < f32::MIN_POSITIVE);
    }

    #[test]
    fn puddles_cover_as_the_water_rises_above_the_roughness() {
        assert!(puddle_cover(0.4).abs() < f32::MIN_POSITIVE);
        assert!((puddle_cover(2.0) - 1.0).abs() < f32::MIN_POSITIVE);
        assert!(puddle_cover(1.0) > 0.2 && puddle_cover(1.0) < 0.8);
    }

    #[test]
    fn more_rain_strikes_more_rings_and_clear_water_shows_blue_green_depths() {
        assert!(ring_rate_per_m2_s(0.0).abs() < f32::MIN_POSITIVE);
        assert!(ring_rate_per_m2_s(40.0) > 10.0 * ring_rate_per_m2_s(1.0));
        let shallow = water_body_colour(Vec3::splat(0.3), 0.05);
        let deep = water_body_colour(Vec3::splat(0.3), 100.0);
        assert!((shallow - Vec3::splat(0.3)).length() < 0.05, "{shallow}");
        assert!((deep - DEEP_WATER_COLOUR).length() < 0.02, "{deep}");
        let mid = water_body_colour(Vec3::splat(0.3), 2.0);
        assert!(mid.x < mid.y && mid.y < mid.z, "red goes first: {mid}");
    }
}
