//! A fog layer with a top: the air between the camera and what it sees, lit by the
//! sky and by the sun (docs/model.md (6.5)–(6.7)).
//!
//! *Source: Vyatkin's fog and scattered light (seed 002, its equations 14–16, after
//! Klassen 1987), generalised to any camera and path.* Below the layer's top `H` the
//! air holds fog of extinction `B = 3.912/V` (`V` the visibility in it); everywhere
//! it holds the precipitation's and the clear air's extinction `σ` (5.8). Along the
//! path from the camera to a point the light of the point is dimmed by
//! `T = e^(−σ·d − B·ℓ)` (`ℓ` the path's length below `H`: a straight line enters and
//! leaves the layer once), and two sources of scattered light add to it:
//!
//! - the sky's, scattered by fog and precipitation alike: `A·(1 − T)` (`A` the haze's
//!   colour, the sky's at the horizon), exactly as the uniform fog of (5.8);
//! - the sun's, scattered by the fog alone with the seed's angular function (16) and
//!   dimmed on its way down from the top by `e^(−B·(H − y)·cosec β)` (the seed's
//!   `e^(−B·H·cosec β)` for a point at the ground; `β` the sun's elevation):
//!   `J = ∫ T(s)·B·e^(−B·(H − y(s))·cosec β) ds · P(μ)/4` over the fog's part of the
//!   path, in units of the light a white surface facing the sun returns (a medium of
//!   albedo 1 returns `E·p(μ)` a metre per unit `B`, `p = P/4π` the normalised phase
//!   function, a white Lambertian surface `E/π`). The exponent is linear in `s`, so
//!   the integral is closed: `B·e^(a + k·s₀)·(e^(k·Δ) − 1)/k`.
//!
//! With the camera at the ground and the sun's dimming taken at the ground this is
//! the seed's (15): `I_c·e^(−B·H·cosec β)·S·(1 − e^(−B·h·cosec α))` (its division by
//! `B` turns the scattered light per unit extinction into a radiance).
//!
//! WGSL twins: `fog_layer_segment`, `fog_phase`, `air_path` (drawing.wgsl).

use glam::Vec3;

use crate::BackendError;

/// The fog droplets' asymmetry `l` in the seed's angular function (16): water
/// droplets of a few to tens of µm scatter visible light forward with `g ≈ 0.85`
/// (Mie theory for fog and cloud droplets; Hansen & Travis 1974).
pub const FOG_ASYMMETRY: f32 = 0.85;

/// The distance a path to the sky counts as, m (a fog's path ends where it leaves the
/// layer; one that never does is dark long before this).
pub const SKY_DISTANCE_M: f32 = 1.0e6;

/// The bottom of a fog layer seen directly, m: far below any ground.
pub const FOG_LAYER_BOTTOM_M: f32 = -1.0e9;

/// A layer of fog from the ground (and below) up to a top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FogLayer {
    /// Height of the fog's top, m (world `y`).
    pub top_m: f32,
    /// Visibility inside the fog, m (Koschmieder: `B = 3.912/V`); fog is below 1 km,
    /// mist to 5 km.
    pub visibility_m: f32,
}

impl FogLayer {
    /// Fog up to `top_m` in which one sees `visibility_m`.
    #[must_use]
    pub const fn new(top_m: f32, visibility_m: f32) -> Self {
        Self {
            top_m,
            visibility_m,
        }
    }

    /// The fog's extinction `B = 3.912/V`, per m.
    #[must_use]
    pub fn extinction_per_m(&self) -> f32 {
        3.912 / self.visibility_m
    }

    /// Checks the top (finite, within ±20 km) and the visibility (`[1, 100 000]` m).
    pub fn validate(&self) -> Result<(), BackendError> {
        if !(self.top_m.is_finite() && self.top_m.abs() <= 20_000.0) {
            return Err(BackendError::Setup {
                field: "render.fog_layer.top_m",
                problem: format!(
                    "= {} must be a height within ±20 000 m (world y)",
                    self.top_m
                ),
            });
        }
        let v = self.visibility_m;
        if !(v.is_finite() && (1.0..=100_000.0).contains(&v)) {
            return Err(BackendError::Setup {
                field: "render.fog_layer.visibility_m",
                problem: format!("= {v} must be in [1, 100000] m (fog is below 1 000 m)"),
            });
        }
        Ok(())
    }
}

/// The seed's angular scattering function (16): `S(μ) = (1 − l)²/(1 + l² −
/// 2l·cos μ)^(3/2)`, `μ` the scattering angle.
#[must_use]
pub fn seed_angular_function(cos_mu: f32, l: f32) -> f32 {
    let d = 1.0 + l * l - 2.0 * l * cos_mu.clamp(-1.0, 1.0);
    (1.0 - l) * (1.0 - l) / (d * d.sqrt())
}

/// The seed's (16) scaled to a mean of 1 over the sphere: `S·(1 + l)/(1 − l)`, which
/// is `4π` times the Henyey–Greenstein phase function of asymmetry `l`.
#[must_use]
pub fn fog_phase(cos_mu: f32, l: f32) -> f32 {
    seed_angular_function(cos_mu, l) * (1.0 + l) / (1.0 - l)
}

/// The part `[s₀, s₁]` of a path from height `camera_y_m` going up by `dir_y` a
/// metre (`dir_y` the unit direction's `y`) for `length_m` that lies between
/// `bottom_m` and `top_m`; `s₀ = s₁` when none does.
#[must_use]
pub fn fog_layer_segment(
    camera_y_m: f32,
    dir_y: f32,
    length_m: f32,
    bottom_m: f32,
    top_m: f32,
) -> (f32, f32) {
    let (mut s0, mut s1) = (0.0f32, length_m);
    if dir_y.abs() < 1.0e-6 {
        if camera_y_m >= top_m || camera_y_m <= bottom_m {
            return (0.0, 0.0);
        }
    } else {
        let to_top = (top_m - camera_y_m) / dir_y;
        let to_bottom = (bottom_m - camera_y_m) / dir_y;
        let (enter, leave) = if dir_y > 0.0 {
            (to_bottom, to_top)
        } else {
            (to_top, to_bottom)
        };
        s0 = s0.max(enter);
        s1 = s1.min(leave);
    }
    if s1 <= s0 { (0.0, 0.0) } else { (s0, s1) }
}

/// What the air does to the light of a point `distance_m` along `dir` from the
/// camera: it passes `transmittance` of it and adds `sun` × the light a white surface
/// facing the sun returns (the sky's share is `A·(1 − transmittance)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AirPath {
    /// `T = e^(−σ·d − B·ℓ)`.
    pub transmittance: f32,
    /// The sun's light scattered toward the camera by the fog on the path, `J`.
    pub sun: f32,
}

/// `(e^x − 1)/x`, exact near 0.
fn exp_minus_one_over(x: f32) -> f32 {
    if x.abs() < 1.0e-4 {
        1.0 + 0.5 * x
    } else {
        x.exp_m1() / x
    }
}

/// The air between the camera at `camera_m` and the point `distance_m` along the
/// unit direction `dir`: extinction `extinction_per_m` (σ) everywhere, fog of
/// extinction `fog_per_m` (B) between `bottom_m` and `top_m`, the sun toward
/// `to_sun` (unit; its light counted only where it is above the horizon).
#[must_use]
#[expect(
    clippy::too_many_arguments,
    reason = "the WGSL twin's argument list, one number each"
)]
pub fn air_path(
    camera_m: Vec3,
    dir: Vec3,
    distance_m: f32,
    extinction_per_m: f32,
    fog_per_m: f32,
    bottom_m: f32,
    top_m: f32,
    to_sun: Vec3,
) -> AirPath {
    let (s0, s1) = fog_layer_segment(camera_m.y, dir.y, distance_m, bottom_m, top_m);
    let in_fog = s1 - s0;
    let transmittance = (-extinction_per_m * distance_m.max(0.0) - fog_per_m * in_fog).exp();
    let sin_sun = to_sun.y.max(0.05);
    // The exponent along the fog's part, a + k·s: the camera's dimming and the sun's
    // from the top.
    let k = -extinction_per_m - fog_per_m + fog_per_m * dir.y / sin_sun;
    let a = fog_per_m * s0 - fog_per_m * (top_m - camera_m.y) / sin_sun;
    let along = (a + k * s0).exp() * in_fog * exp_minus_one_over(k * in_fog);
    let phase = fog_phase(dir.dot(to_sun), FOG_ASYMMETRY);
    let sun = if to_sun.y > 0.0 {
        fog_per_m * along * phase / 4.0
    } else {
        0.0
    };
    AirPath { transmittance, sun }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    const DOWN: f32 = FOG_LAYER_BOTTOM_M;

    #[test]
    fn the_phase_function_averages_one_over_the_sphere() {
        for l in [0.0f32, 0.3, 0.6, FOG_ASYMMETRY, 0.95] {
            // ∫ P dΩ/4π = ½∫₋₁¹ P(μ) dμ, midpoint rule in cos μ.
            let n = 200_000;
            let mean: f64 = (0..n)
                .map(|i| {
                    let c = -1.0 + 2.0 * (f64::from(i) + 0.5) / f64::from(n);
                    f64::from(fog_phase(c as f32, l))
                })
                .sum::<f64>()
                / f64::from(n);
            assert!((mean - 1.0).abs() < 2e-3, "l = {l}: mean {mean}");
        }
        // The seed's own form: 1/(1 − l) forward, (1 − l)²/(1 + l)³ back.
        let l = 0.5;
        assert!((seed_angular_function(1.0, l) - 2.0).abs() < 1e-5);
        assert!((seed_angular_function(-1.0, l) - 0.25 / 3.375).abs() < 1e-5);
    }

    #[test]
    fn a_uniform_slab_dims_as_beer_lambert() {
        // Camera at 2 m inside fog up to 50 m of visibility 100 m, looking level 80 m.
        let fog = FogLayer::new(50.0, 100.0);
        let b = fog.extinction_per_m();
        let p = air_path(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::X,
            80.0,
            0.0,
            b,
            DOWN,
            50.0,
            Vec3::Y,
        );
        assert!((p.transmittance - (-b * 80.0).exp()).abs() < 1e-6);
        // At the visibility: 2 %.
        let at_v = air_path(Vec3::ZERO, Vec3::X, 100.0, 0.0, b, DOWN, 50.0, Vec3::Y);
        assert!((at_v.transmittance - 0.02).abs() < 1e-3, "{at_v:?}");
        // Slanting up through the top at 45°: only the part below it counts.
        let up = Vec3::new(1.0, 1.0, 0.0).normalize();
        let p = air_path(Vec3::ZERO, up, 200.0, 0.0, b, DOWN, 50.0, Vec3::Y);
        let inside = 50.0 * 2f32.sqrt();
        assert!((p.transmittance - (-b * inside).exp()).abs() < 1e-6);
    }

    #[test]
    fn above_the_top_the_air_is_clear() {
        let b = FogLayer::new(10.0, 50.0).extinction_per_m();
        // Camera at 100 m looking level: no fog at all, whatever the distance.
        let p = air_path(
            Vec3::new(0.0, 100.0, 0.0),
            Vec3::X,
            5_000.0,
            1e-5,
            b,
            DOWN,
            10.0,
            Vec3::Y,
        );
        assert!((p.transmittance - (-1e-5f32 * 5_000.0).exp()).abs() < 1e-6);
        assert!(p.sun.abs() < f32::MIN_POSITIVE, "{p:?}");
        // Looking down at the ground 100 m below: only the last 10 m are in fog.
        let p = air_path(
            Vec3::new(0.0, 100.0, 0.0),
            Vec3::NEG_Y,
            100.0,
            0.0,
            b,
            DOWN,
            10.0,
            Vec3::Y,
        );
        assert!((p.transmittance - (-b * 10.0).exp()).abs() < 1e-5);
    }

    /// The sun's share by midpoint quadrature of its definition.
    fn sun_by_quadrature(
        camera: Vec3,
        dir: Vec3,
        d: f32,
        sigma: f32,
        b: f32,
        top: f32,
        to_sun: Vec3,
    ) -> f64 {
        let n = 100_000;
        let ds = f64::from(d) / f64::from(n);
        let phase = f64::from(fog_phase(dir.dot(to_sun), FOG_ASYMMETRY));
        let mut optical = 0.0f64;
        let mut sum = 0.0f64;
        for i in 0..n {
            let s = (f64::from(i) + 0.5) * ds;
            let y = f64::from(camera.y) + s * f64::from(dir.y);
            let fog = if y < f64::from(top) {
                f64::from(b)
            } else {
                0.0
            };
            let mid = optical + (f64::from(sigma) + fog) * ds * 0.5;
            let sun_dim = (-fog * (f64::from(top) - y) / f64::from(to_sun.y)).exp();
            sum += (-mid).exp() * fog * sun_dim * ds;
            optical += (f64::from(sigma) + fog) * ds;
        }
        sum * phase / 4.0
    }

    #[test]
    fn the_sun_s_scattered_light_is_its_integral() {
        let to_sun = Vec3::new(0.3, 0.5, -0.2).normalize();
        for (camera, dir, d) in [
            (
                Vec3::new(0.0, 2.0, 0.0),
                Vec3::new(1.0, 0.05, 0.0).normalize(),
                300.0f32,
            ),
            (Vec3::new(0.0, 2.0, 0.0), to_sun, 200.0),
            (
                Vec3::new(0.0, 60.0, 0.0),
                Vec3::new(0.4, -1.0, 0.1).normalize(),
                70.0,
            ),
            (
                Vec3::new(0.0, 5.0, 0.0),
                Vec3::new(0.0, 0.9, 1.0).normalize(),
                400.0,
            ),
        ] {
            let p = air_path(camera, dir, d, 2e-3, 0.04, DOWN, 30.0, to_sun);
            let q = sun_by_quadrature(camera, dir, d, 2e-3, 0.04, 30.0, to_sun);
            assert!(
                (f64::from(p.sun) - q).abs() < 1e-3 * q.max(1e-3),
                "{camera} {dir}: closed {} quadrature {q}",
                p.sun
            );
        }
    }

    #[test]
    fn at_the_ground_it_is_the_seed_s_equation_fifteen() {
        // Camera at the ground in thick fog (H = 40 m), looking level toward a point
        // 30 m off whose path stays near the ground: the sun dimmed from the top at
        // the ground, e^(−B·H·cosec β), times (1 − e^(−B·d)) times S/4 scaled.
        let b = 0.05f32;
        let to_sun = Vec3::new(0.0, 0.6, 0.8);
        let p = air_path(Vec3::ZERO, Vec3::Z, 30.0, 0.0, b, DOWN, 40.0, to_sun);
        let seed =
            (-b * 40.0 / 0.6).exp() * (1.0 - (-b * 30.0).exp()) * fog_phase(0.8, FOG_ASYMMETRY)
                / 4.0;
        assert!((p.sun - seed).abs() < 1e-6, "{} against {seed}", p.sun);
    }

    #[test]
    fn a_thin_layer_or_no_fog_scatters_no_sun() {
        let p = air_path(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::X,
            100.0,
            1e-3,
            0.0,
            DOWN,
            50.0,
            Vec3::Y,
        );
        assert!(p.sun.abs() < f32::MIN_POSITIVE, "{p:?}");
        assert!((p.transmittance - (-0.1f32).exp()).abs() < 1e-6);
    }

    #[test]
    fn fog_layers_are_checked() {
        assert!(FogLayer::new(30.0, 200.0).validate().is_ok());
        assert!(FogLayer::new(f32::NAN, 200.0).validate().is_err());
        assert!(FogLayer::new(30.0, 0.0).validate().is_err());
        assert!(FogLayer::new(30.0, 1e9).validate().is_err());
    }

    proptest! {
        #[test]
        fn the_segment_lies_in_the_layer_and_in_the_path(
            y in -50.0f32..150.0, dy in -1.0f32..1.0, len in 0.0f32..500.0,
            top in 0.0f32..100.0,
        ) {
            let (s0, s1) = fog_layer_segment(y, dy, len, DOWN, top);
            prop_assert!(s0 <= s1 && s0 >= 0.0 && s1 <= len);
            if s1 > s0 {
                let mid = y + 0.5 * (s0 + s1) * dy;
                prop_assert!(mid <= top + 1e-2);
            }
        }

        #[test]
        fn transmittance_falls_with_distance(d1 in 0.0f32..400.0, extra in 0.0f32..400.0, dy in -0.5f32..0.5) {
            let dir = Vec3::new(1.0, dy, 0.0).normalize();
            let near = air_path(Vec3::new(0.0, 10.0, 0.0), dir, d1, 1e-3, 0.03, DOWN, 40.0, Vec3::Y);
            let far = air_path(Vec3::new(0.0, 10.0, 0.0), dir, d1 + extra, 1e-3, 0.03, DOWN, 40.0, Vec3::Y);
            prop_assert!(far.transmittance <= near.transmittance + 1e-6);
            prop_assert!(far.sun + 1e-6 >= near.sun);
        }
    }
}
