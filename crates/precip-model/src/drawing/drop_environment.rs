//! The light a raindrop shows: the environment it refracts over its field of view
//! (docs/model.md (5.8)).
//!
//! A falling drop is a wide-angle lens: through it the camera sees, upside down, the
//! environment over a cone of about 165° around the viewing direction, at about
//! 94 % of its radiance (the rest is lost to reflection and internal reflection),
//! plus a faint specular reflection of the other side (Garg & Nayar, *Photorealistic
//! rendering of rain streaks*, SIGGRAPH 2006; *Vision and rain*, IJCV 2007). A streak
//! is therefore nearly as bright as the *mean* of that cone, not as what lies
//! directly behind it: bright against a dark background, all but gone against the
//! sky.
//!
//! Our environment is an overcast sky of the CIE shape `L(y) = L_h·(1 + 2y)` above
//! the horizon (`y` the direction's sine of elevation, `L_h` the horizon's
//! radiance: the scene's `overcast_sky`) and the ground below it, a Lambertian
//! surface of albedo `ρ` under that sky: its radiance is `ρ·E/π` with
//! `E = 7π·L_h/3` (the CIE sky's irradiance on level ground), `7ρ/3·L_h`. Fresh snow
//! (`ρ ≈ 0.8`) is brighter than the horizon; grass (`ρ ≈ 0.2`) half as bright.
//!
//! The mean over the cone of half-angle `α` around a direction of elevation sine `s`
//! is closed-form. The part above the horizon has solid angle
//! `U = 2[π − arccos(s/sin α) − cos α·φ₀]` (two spherical caps' intersection), with
//! `φ₀ = arccos(−s·cos α/(sin α·cos e))` the half-range of the cone's rim above the
//! horizon; the integral of `y` over it, by Stokes's theorem on the sphere (the rim's
//! arc and the horizon's chord, of half-angle `ψ₀ = arccos(cos α/cos e)`), is
//! `Y = ψ₀ + sin²α·s·φ₀ − cos α·sin α·cos e·sin φ₀`. Over the cone's solid angle
//! `Ω = 2π(1 − cos α)` the sky gives `(U + 2Y)/Ω` of `L_h`, the ground
//! `(1 − U/Ω)·7ρ/3`. WGSL twin: `drop_environment_factor` in `shaders/drawing.wgsl`.

use std::f32::consts::PI;

/// Half the field of view of a falling drop, rad (165° in all: Garg & Nayar 2007).
pub const DROP_HALF_FIELD_RAD: f32 = 82.5 * PI / 180.0;

/// The share of the environment's radiance a drop passes on by refraction (Garg &
/// Nayar 2007: at least 94 % over the field of view, the rest reflected).
pub const DROP_REFRACTED_SHARE: f32 = 0.94;

/// The albedo of the ground the renderer's drops see (grass 0.2–0.25, soil
/// 0.1–0.2, asphalt 0.05–0.1). Snow on it is not counted: reading the cover under
/// every drop cost a quarter of the particle pass on lavapipe. WGSL twin:
/// `BARE_GROUND_ALBEDO`.
pub const BARE_GROUND_ALBEDO: f32 = 0.2;

/// The radiance of level Lambertian ground of albedo 1 under the CIE overcast sky,
/// in units of the horizon's radiance: `E/π` with `E = 7π/3·L_h`.
pub const OVERCAST_GROUND_RADIANCE_PER_ALBEDO: f32 = 7.0 / 3.0;

/// The parts of a drop's field of view, looking along a direction of elevation sine
/// `sin_elevation`: the sky's mean radiance over the field in units of the
/// horizon's (CIE overcast: `1 + 2y` above the horizon, nothing below), and the
/// share of the field below the horizon.
#[must_use]
pub fn drop_field_shares(sin_elevation: f32) -> (f32, f32) {
    let s = sin_elevation.clamp(-1.0, 1.0);
    let (sin_a, cos_a) = DROP_HALF_FIELD_RAD.sin_cos();
    let solid_angle = 2.0 * PI * (1.0 - cos_a);
    let cos_e = (1.0 - s * s).max(0.0).sqrt();
    // Wholly above or below the horizon: |e| ≥ α, i.e. cos e ≤ cos α.
    if cos_e <= cos_a {
        return if s > 0.0 {
            // ∫ y over a whole cap: π·sin²α·s.
            (
                (solid_angle + 2.0 * PI * sin_a * sin_a * s) / solid_angle,
                0.0,
            )
        } else {
            (0.0, 1.0)
        };
    }
    let rim = (-s * cos_a / (sin_a * cos_e)).clamp(-1.0, 1.0).acos();
    let chord = (cos_a / cos_e).clamp(-1.0, 1.0).acos();
    let upper = 2.0 * (PI - (s / sin_a).clamp(-1.0, 1.0).acos() - cos_a * rim);
    let first_moment = chord + sin_a * sin_a * s * rim - cos_a * sin_a * cos_e * rim.sin();
    (
        (upper + 2.0 * first_moment) / solid_angle,
        (1.0 - upper / solid_angle).clamp(0.0, 1.0),
    )
}

/// The radiance a drop shows by refraction, in units of the horizon sky's, looking
/// along a direction of elevation sine `sin_elevation` over ground of albedo
/// `ground_albedo`: [`DROP_REFRACTED_SHARE`] of the mean of sky and ground over its
/// field ([`drop_field_shares`]).
#[must_use]
pub fn drop_environment_factor(sin_elevation: f32, ground_albedo: f32) -> f32 {
    let (sky, below) = drop_field_shares(sin_elevation);
    DROP_REFRACTED_SHARE
        * (sky + below * ground_albedo.max(0.0) * OVERCAST_GROUND_RADIANCE_PER_ALBEDO)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shares by brute force: the cone sampled in solid angle.
    fn quadrature(sin_elevation: f32) -> (f32, f32) {
        let e = sin_elevation.clamp(-1.0, 1.0).asin();
        let centre = glam::Vec3::new(e.cos(), e.sin(), 0.0);
        let up = glam::Vec3::new(-e.sin(), e.cos(), 0.0);
        let side = glam::Vec3::Z;
        let (rings, spokes) = (400, 400);
        let (mut sky, mut below, mut total) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..rings {
            let theta = (i as f32 + 0.5) / rings as f32 * DROP_HALF_FIELD_RAD;
            for j in 0..spokes {
                let phi = (j as f32 + 0.5) / spokes as f32 * 2.0 * PI;
                let w = f64::from(theta.sin());
                let d = theta.cos() * centre + theta.sin() * (phi.cos() * up + phi.sin() * side);
                total += w;
                if d.y > 0.0 {
                    sky += w * f64::from(1.0 + 2.0 * d.y);
                } else {
                    below += w;
                }
            }
        }
        ((sky / total) as f32, (below / total) as f32)
    }

    #[test]
    fn the_closed_form_is_the_mean_over_the_field() {
        for k in 0..=40 {
            let s = -1.0 + 0.05 * k as f32;
            let (sky, below) = drop_field_shares(s);
            let (want_sky, want_below) = quadrature(s);
            assert!(
                (sky - want_sky).abs() < 2e-3 && (below - want_below).abs() < 2e-3,
                "sin e = {s}: closed form ({sky}, {below}), quadrature ({want_sky}, {want_below})"
            );
        }
    }

    #[test]
    fn a_drop_seen_level_shows_half_sky_half_ground_and_snow_brightens_it() {
        let (sky, below) = drop_field_shares(0.0);
        assert!((below - 0.5).abs() < 1e-5, "{below}");
        // The upper half's mean 1 + 2y: y averages 0.48 over it.
        assert!((sky - 0.5 * (1.0 + 2.0 * 0.4797)).abs() < 2e-3, "{sky}");
        // Seen level over grass (ρ = 0.2) the drop shows 1.14 of the horizon's
        // radiance: a little brighter than the sky behind it, 2.4 times the grass
        // (7/3·0.2 = 0.47) behind it. Over fresh snow, brighter; looking up,
        // brighter still (the zenith is 3 times the horizon).
        let grass = drop_environment_factor(0.0, 0.2);
        assert!(
            (grass - 0.94 * (sky + 0.5 * 0.2 * 7.0 / 3.0)).abs() < 1e-5,
            "{grass}"
        );
        assert!((1.1..1.2).contains(&grass), "{grass}");
        assert!(grass / (0.2 * OVERCAST_GROUND_RADIANCE_PER_ALBEDO) > 2.0);
        assert!(drop_environment_factor(0.0, 0.8) > grass + 0.5);
        assert!(drop_environment_factor(1.0, 0.2) > 2.0);
        assert!((drop_environment_factor(-1.0, 0.2) - 0.94 * 0.2 * 7.0 / 3.0).abs() < 1e-6);
    }
}
