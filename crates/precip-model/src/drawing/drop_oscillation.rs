//! A falling drop oscillates (docs/model.md (5.4b)): its shape rings at the
//! fundamental (n = 2) mode of a liquid sphere, `ω² = 8σ/(ρ_w·r³)` (Rayleigh 1879,
//! *On the capillary phenomena of jets*, Proc. R. Soc. 29; the frequencies Garg &
//! Nayar 2006 render rain streaks with), and the light it refracts toward the camera
//! brightens and dims with it: along a streak exposed for `T` the drop's brightness
//! goes through `f·T` cycles, `1 + A·cos(2π(φ + f·t))`, `φ` its phase. The contrast
//! `A` is a look: Garg & Nayar's rendered streak database shows bright and dark
//! bands of about this depth for 1–3 mm drops; precip has no such database.
//!
//! WGSL twins: `drop_oscillation_hz`, `drop_oscillation_brightness` (drawing.wgsl),
//! used by the rain streak (render_particles.wgsl).

use crate::physics::snowflake::WATER_DENSITY_KG_M3;

/// Surface tension of water against air near 10 °C, N/m (0.0742 at 10 °C, 0.0728
/// at 20 °C).
pub const WATER_SURFACE_TENSION_N_PER_M: f32 = 0.074;
/// How deep the brightness of an oscillating drop swings about its mean (a look).
pub const DROP_OSCILLATION_CONTRAST: f32 = 0.25;

/// The fundamental oscillation frequency of a drop of `diameter_m`, Hz:
/// `√(8σ/(ρ_w·r³))/2π`. Numbers: 1 mm 346 Hz, 2 mm 122 Hz, 4 mm 43 Hz.
#[must_use]
pub fn drop_oscillation_hz(diameter_m: f32) -> f32 {
    let r = 0.5 * diameter_m.max(1.0e-5);
    (8.0 * WATER_SURFACE_TENSION_N_PER_M / (WATER_DENSITY_KG_M3 * r * r * r)).sqrt()
        / std::f32::consts::TAU
}

/// The brightness of an oscillating drop, relative to its mean, at `cycles` (its
/// phase plus the cycles it went through): `1 + A·cos(2π·cycles)`.
#[must_use]
pub fn drop_oscillation_brightness(cycles: f32) -> f32 {
    1.0 + DROP_OSCILLATION_CONTRAST * (std::f32::consts::TAU * cycles).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_drops_ring_fast_large_ones_slowly() {
        let hz = |mm: f32| drop_oscillation_hz(mm * 1.0e-3);
        assert!((hz(1.0) - 346.0).abs() < 2.0, "{}", hz(1.0));
        assert!((hz(2.0) - 122.0).abs() < 1.0, "{}", hz(2.0));
        assert!((hz(4.0) - 43.3).abs() < 0.5, "{}", hz(4.0));
        // f ∝ D^(−3/2).
        assert!((hz(1.0) / hz(4.0) - 8.0).abs() < 1e-3);
        // A 2 mm drop in a 1/60 s exposure: two cycles along its streak.
        assert!((hz(2.0) / 60.0 - 2.0).abs() < 0.05);
        // The brightness swings ±A about 1 and averages 1 over a cycle.
        let mean: f32 = (0..1000)
            .map(|k| drop_oscillation_brightness(k as f32 / 1000.0))
            .sum::<f32>()
            / 1000.0;
        assert!((mean - 1.0).abs() < 1e-4);
        assert!((drop_oscillation_brightness(0.0) - 1.25).abs() < 1e-6);
        assert!((drop_oscillation_brightness(0.5) - 0.75).abs() < 1e-6);
    }
}
