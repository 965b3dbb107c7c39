//! The wind sampler that the particle kernel mirrors (shaders/wind.wgsl).
//!
//! Manual trilinear interpolation with periodic wrap over `textureLoad`ed texels; the
//! order of operations is the WGSL one, so the CPU reference and the GPU read the
//! same wind to within float rounding.

use glam::{IVec3, Vec3};

use crate::volume::{WindTexel, WindVolume};

/// The interpolated gust at a point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WindSample {
    /// `sin α` in `[0, 1]`.
    pub sin_alpha: f32,
    /// Vertical gust, m/s.
    pub vertical_mps: f32,
}

impl WindVolume {
    /// The gust at world position `position_m` and time `time_s`.
    ///
    /// Frozen turbulence: the pattern drifts with the mean wind, so the volume is read
    /// at `position − mean·time`, wrapped into one period, then in texel space where
    /// texel centres sit at integers.
    #[must_use]
    pub fn sample(&self, position_m: Vec3, time_s: f32) -> WindSample {
        let extent = self.spec.extent_m;
        let drifted = position_m - self.field.mean_wind_mps * time_s;
        let wrapped = drifted - extent * (drifted / extent).floor();
        let texel_space = wrapped / self.spec.cell_m() - 0.5;
        let base = texel_space.floor();
        let f = texel_space - base;
        let b: IVec3 = base.as_ivec3();
        let load = |dx: i32, dy: i32, dz: i32| -> WindTexel {
            self.texel_wrapped(b.x + dx, b.y + dy, b.z + dz)
        };
        let lerp = |a: WindTexel, c: WindTexel, t: f32| WindTexel {
            sin_alpha: a.sin_alpha + (c.sin_alpha - a.sin_alpha) * t,
            vertical_mps: a.vertical_mps + (c.vertical_mps - a.vertical_mps) * t,
            reserved: [0.0; 2],
        };
        let x00 = lerp(load(0, 0, 0), load(1, 0, 0), f.x);
        let x10 = lerp(load(0, 1, 0), load(1, 1, 0), f.x);
        let x01 = lerp(load(0, 0, 1), load(1, 0, 1), f.x);
        let x11 = lerp(load(0, 1, 1), load(1, 1, 1), f.x);
        let y0 = lerp(x00, x10, f.y);
        let y1 = lerp(x01, x11, f.y);
        let t = lerp(y0, y1, f.z);
        WindSample {
            sin_alpha: t.sin_alpha,
            vertical_mps: t.vertical_mps,
        }
    }

    /// The wind velocity `V̄_w + μ·V̄_w·sin α + (0, w, 0)` in m/s (docs/model.md §3).
    #[must_use]
    pub fn velocity_mps(&self, position_m: Vec3, time_s: f32) -> Vec3 {
        let s = self.sample(position_m, time_s);
        wind_velocity(self.field.mean_wind_mps, self.field.gust_factor, s)
    }
}

/// `V_w = V̄_w + μ·V̄_w·sin α + (0, w, 0)`. WGSL twin: `wind_velocity` in wind.wgsl.
#[must_use]
pub fn wind_velocity(mean_wind_mps: Vec3, gust_factor: f32, sample: WindSample) -> Vec3 {
    mean_wind_mps
        + mean_wind_mps * (gust_factor * sample.sin_alpha)
        + Vec3::new(0.0, sample.vertical_mps, 0.0)
}

#[cfg(test)]
mod tests {
    use glam::UVec3;
    use proptest::prelude::*;

    use super::*;
    use crate::{WindField, WindVolumeSpec};

    fn small_spec() -> WindVolumeSpec {
        WindVolumeSpec {
            texels: UVec3::new(16, 8, 12),
            extent_m: Vec3::new(64.0, 32.0, 48.0),
        }
    }

    fn gusty(seed: u32) -> WindField {
        WindField {
            mean_wind_mps: Vec3::new(8.0, 0.0, -3.0),
            gust_factor: 0.05,
            noise_scale_m: 16.0,
            octaves: 3,
            vertical_gust_mps: 0.8,
            seed,
        }
    }

    fn volume(seed: u32) -> WindVolume {
        WindVolume::bake(&gusty(seed), &small_spec()).expect("valid")
    }

    #[test]
    fn exact_at_texel_centres() {
        let v = volume(7);
        let cell = v.spec.cell_m();
        for (i, j, k) in [(0, 0, 0), (3, 5, 7), (15, 7, 11), (8, 1, 2)] {
            let centre = (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * cell;
            let s = v.sample(centre, 0.0);
            let t = v.texel_wrapped(i, j, k);
            assert!((s.sin_alpha - t.sin_alpha).abs() < 1e-5, "{i},{j},{k}");
            assert!(
                (s.vertical_mps - t.vertical_mps).abs() < 1e-5,
                "{i},{j},{k}"
            );
        }
    }

    #[test]
    fn texels_hold_the_documented_ranges_and_vary() {
        let v = volume(3);
        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
        for t in &v.texels {
            assert!((0.0..=1.0).contains(&t.sin_alpha));
            assert!(t.vertical_mps.abs() <= 0.8 + 1e-6);
            lo = lo.min(t.sin_alpha);
            hi = hi.max(t.sin_alpha);
        }
        assert!(hi - lo > 0.3, "noise too flat: {lo}..{hi}");
    }

    #[test]
    fn the_seam_is_as_smooth_as_the_inside() {
        // The periodic blend: the jump across the wrap is no larger than typical steps.
        let v = volume(11);
        let n = v.spec.texels.as_ivec3();
        let mut inner = 0.0f32;
        let mut seam = 0.0f32;
        for j in 0..n.y {
            for k in 0..n.z {
                for i in 0..n.x - 1 {
                    inner = inner.max(
                        (v.texel_wrapped(i + 1, j, k).sin_alpha
                            - v.texel_wrapped(i, j, k).sin_alpha)
                            .abs(),
                    );
                }
                seam = seam.max(
                    (v.texel_wrapped(0, j, k).sin_alpha - v.texel_wrapped(n.x - 1, j, k).sin_alpha)
                        .abs(),
                );
            }
        }
        assert!(
            seam <= inner * 1.5 + 1e-3,
            "seam step {seam} vs inner step {inner}"
        );
    }

    #[test]
    fn a_hand_built_volume_with_missing_texels_does_not_panic() {
        let mut v = volume(1);
        v.texels.truncate(10);
        let _ = v.sample(Vec3::new(40.0, 20.0, 30.0), 1.0);
        v.spec.texels = UVec3::ZERO;
        assert_eq!(v.sample(Vec3::ONE, 0.0), WindSample::default());
    }

    #[test]
    fn calm_air_has_no_horizontal_gust() {
        let v = WindVolume::bake(&WindField::calm(), &small_spec()).expect("valid");
        let w = v.velocity_mps(Vec3::new(3.0, 4.0, 5.0), 2.0);
        assert!(w.length() < 1e-6);
    }

    #[test]
    fn rebake_only_when_noise_changes() {
        let a = gusty(1);
        let b = WindField {
            mean_wind_mps: Vec3::X,
            ..a
        };
        assert!(!a.needs_rebake(&b));
        assert!(a.needs_rebake(&WindField { seed: 2, ..a }));

        let v = WindVolume::bake(&a, &small_spec()).expect("valid");
        let (same, rebaked) = v.for_field(&b).expect("valid");
        assert!(!rebaked && same.texels == v.texels);
        assert_eq!(same.field.mean_wind_mps, Vec3::X);
        let (other, rebaked) = v.for_field(&WindField { seed: 2, ..a }).expect("valid");
        assert!(rebaked && other.texels != v.texels);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn periodic(x in -500.0f32..500.0, y in -200.0f32..200.0, z in -500.0f32..500.0, a in -3i32..3, b in -3i32..3, c in -3i32..3) {
            let v = volume(5);
            let p = Vec3::new(x, y, z);
            let shift = Vec3::new(a as f32, b as f32, c as f32) * v.spec.extent_m;
            let s0 = v.sample(p, 0.0);
            let s1 = v.sample(p + shift, 0.0);
            prop_assert!((s0.sin_alpha - s1.sin_alpha).abs() < 2e-3);
            prop_assert!((s0.vertical_mps - s1.vertical_mps).abs() < 2e-3);
        }

        #[test]
        fn continuous(x in -100.0f32..100.0, y in -50.0f32..50.0, z in -100.0f32..100.0, dx in -1.0f32..1.0, dy in -1.0f32..1.0, dz in -1.0f32..1.0) {
            // A step of h metres changes the gust by at most h/cell times the largest
            // texel-to-texel difference (trilinear is Lipschitz), plus rounding.
            let v = volume(5);
            let h = 0.01f32;
            let p = Vec3::new(x, y, z);
            let q = p + Vec3::new(dx, dy, dz) * h;
            let cell = v.spec.cell_m().min_element();
            let bound = 3.0 * h / cell + 1e-4;
            let (s0, s1) = (v.sample(p, 0.0), v.sample(q, 0.0));
            prop_assert!((s0.sin_alpha - s1.sin_alpha).abs() <= bound);
            prop_assert!((s0.vertical_mps - s1.vertical_mps).abs() <= bound * 2.0 * 0.8);
        }

        #[test]
        fn gust_is_bounded_by_mu_times_mean(x in -300.0f32..300.0, y in 0.0f32..100.0, z in -300.0f32..300.0, t in 0.0f32..100.0) {
            let v = volume(9);
            let w = v.velocity_mps(Vec3::new(x, y, z), t);
            let mean = v.field.mean_wind_mps;
            let horizontal_gust = (w - mean - Vec3::new(0.0, v.sample(Vec3::new(x, y, z), t).vertical_mps, 0.0)).length();
            prop_assert!(horizontal_gust <= v.field.gust_factor * mean.length() * (1.0 + 1e-5) + 1e-6);
        }

        #[test]
        fn frozen_turbulence_moves_with_the_mean_wind(x in -100.0f32..100.0, z in -100.0f32..100.0, t in 0.0f32..30.0) {
            let v = volume(4);
            let p = Vec3::new(x, 10.0, z);
            let a = v.sample(p, 0.0);
            let b = v.sample(p + v.field.mean_wind_mps * t, t);
            prop_assert!((a.sin_alpha - b.sin_alpha).abs() < 2e-3);
        }
    }

    #[test]
    fn deterministic_per_seed_and_different_across_seeds() {
        assert_eq!(volume(21).texels, volume(21).texels);
        let (a, b) = (volume(21), volume(22));
        let differing = a
            .texels
            .iter()
            .zip(&b.texels)
            .filter(|(x, y)| x != y)
            .count();
        assert!(
            differing > a.texels.len() / 2,
            "only {differing} texels differ"
        );
    }
}
