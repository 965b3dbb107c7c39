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
//!
//! The ground's albedo `ρ` is the cover's around the camera ([`drop_ground_albedo`]):
//! over fresh snow (0.8) a drop seen level shows 1.8 times the horizon's radiance,
//! over grass (0.2) 1.14.

use std::f32::consts::PI;

use glam::Vec2;
use precip_cover::{CoverGrid, CoverParams, ground_albedo};

/// Half the field of view of a falling drop, rad (165° in all: Garg & Nayar 2007).
pub const DROP_HALF_FIELD_RAD: f32 = 82.5 * PI / 180.0;

/// The share of the environment's radiance a drop passes on by refraction (Garg &
/// Nayar 2007: at least 94 % over the field of view, the rest reflected).
pub const DROP_REFRACTED_SHARE: f32 = 0.94;

/// The albedo of bare ground (grass 0.2–0.25, soil 0.1–0.2, asphalt 0.05–0.1) and of
/// ground off the cover grid. WGSL twin: `BARE_GROUND_ALBEDO`.
pub const BARE_GROUND_ALBEDO: f32 = 0.2;

/// The radius around the camera over which the ground the drops refract is averaged,
/// m ([`drop_ground_albedo`]). WGSL twin: `DROP_GROUND_RADIUS_M`.
pub const DROP_GROUND_RADIUS_M: f32 = 20.0;

/// Samples a side of the square lattice [`drop_ground_albedo`] reads within the
/// radius (those inside the disk count). WGSL twin: `DROP_GROUND_SAMPLES_PER_SIDE`.
pub const DROP_GROUND_SAMPLES_PER_SIDE: u32 = 16;

/// Lattice point `k` of [`drop_ground_albedo`] from the camera, m: the centres of
/// a [`DROP_GROUND_SAMPLES_PER_SIDE`]² grid over the square of half side
/// [`DROP_GROUND_RADIUS_M`], row by row. WGSL twin: `drop_ground_offset_m`.
#[must_use]
pub fn drop_ground_offset_m(k: u32) -> Vec2 {
    let n = DROP_GROUND_SAMPLES_PER_SIDE;
    let cell = (Vec2::new((k % n) as f32, (k / n) as f32) + 0.5) / n as f32;
    (cell * 2.0 - 1.0) * DROP_GROUND_RADIUS_M
}

/// The albedo of the ground the drops near the camera refract: the mean of the
/// cover's ground albedo ([`precip_cover::ground_albedo`], bare
/// [`BARE_GROUND_ALBEDO`]) over the lattice points within [`DROP_GROUND_RADIUS_M`]
/// of `camera_xz_m`, each at its texel (bare off the grid).
///
/// One number for every drop of a frame: the drops that show are within some metres
/// of the camera, and each refracts the ground over its whole lower field (out to
/// the horizon), not the point beneath it, so the mean around the camera stands for
/// what each sees; reading the cover under every drop cost a quarter of the
/// particle pass on lavapipe. On the GPU the `drop_ground` kernel computes it once
/// a frame (WGSL: cover_texture.wgsl, summed in another order: equal within
/// rounding).
#[must_use]
pub fn drop_ground_albedo(cover: &CoverGrid, camera_xz_m: Vec2, params: &CoverParams) -> f32 {
    let n = DROP_GROUND_SAMPLES_PER_SIDE;
    let (mut sum, mut count) = (0.0f32, 0.0f32);
    for k in 0..n * n {
        let offset = drop_ground_offset_m(k);
        if offset.length_squared() > DROP_GROUND_RADIUS_M * DROP_GROUND_RADIUS_M {
            continue;
        }
        sum += cover
            .frame
            .texel_index(camera_xz_m + offset)
            .and_then(|i| cover.texels.get(i))
            .map_or(BARE_GROUND_ALBEDO, |t| {
                ground_albedo(t, params, BARE_GROUND_ALBEDO)
            });
        count += 1.0;
    }
    sum / count
}

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

    #[test]
    fn the_drops_ground_is_the_cover_s_around_the_camera() {
        use precip_cover::{CoverFeed, GridFrame, generate_threshold_masks};
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(60.0), glam::UVec2::splat(60));
        let n = frame.texel_count();
        let masks = generate_threshold_masks(&frame, 7, 4.0);
        let mut cover = CoverGrid::new(
            frame,
            &vec![1.0; n],
            &masks,
            &vec![CoverFeed::WeatherRate; n],
        )
        .expect("a grid");
        let params = CoverParams::default();
        // Bare: the bare albedo wherever the camera stands, on or off the grid.
        for at in [Vec2::ZERO, Vec2::splat(25.0), Vec2::splat(1_000.0)] {
            let a = drop_ground_albedo(&cover, at, &params);
            assert!((a - BARE_GROUND_ALBEDO).abs() < 1e-6, "{at}: {a}");
        }
        // Half a metre of fresh snow on the west half of the grid (x < 0).
        for (i, t) in cover.texels.iter_mut().enumerate() {
            if frame.texel_centre(i).x < 0.0 {
                t.depth_mm = 500.0;
                t.swe_mm = 50.0;
                t.peak_swe_mm = 50.0;
            }
        }
        let west = drop_ground_albedo(&cover, Vec2::new(-28.0, 0.0), &params);
        let middle = drop_ground_albedo(&cover, Vec2::ZERO, &params);
        let east = drop_ground_albedo(&cover, Vec2::new(28.0, 0.0), &params);
        // From the west edge the disk is half on snow and half off the grid (bare);
        // from the middle half on snow; from the east edge on bare ground alone.
        assert!((east - BARE_GROUND_ALBEDO).abs() < 1e-6, "{east}");
        assert!(
            (middle - 0.5).abs() < 0.03,
            "half snow (0.8), half bare: {middle}"
        );
        assert!((west - middle).abs() < 0.05, "{west} against {middle}");
        // A drop seen level shows more light over the snow than over grass.
        assert!(drop_environment_factor(0.0, middle) > drop_environment_factor(0.0, east) + 0.2);
        // The lattice is symmetric about the camera and fills the disk.
        let inside = (0..DROP_GROUND_SAMPLES_PER_SIDE.pow(2))
            .map(drop_ground_offset_m)
            .filter(|o| o.length() <= DROP_GROUND_RADIUS_M)
            .collect::<Vec<_>>();
        assert!(inside.len() > 190 && inside.len() < 210, "{}", inside.len());
        assert!(inside.iter().sum::<Vec2>().length() < 1e-3);
    }
}
