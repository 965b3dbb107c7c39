//! The streaks of what the particle budget does not draw one by one (docs/model.md
//! (5.15b)): beyond the camera's volume, the air's flakes and drops are in the haze
//! — their mean — and, since they fall in a finite number, in a grain around it.
//!
//! A pixel spanning `p` rad sees, during an exposure `T`, the particles of the air
//! between the camera volume's reach `z₁` and what the pixel shows at `z₂` cross
//! it. A particle of area `a` at depth `z`, moving across the view at `v`, covers
//! its share `a/L²` of the pixel's footprint `L = p·z` for the share of the exposure
//! it spends there; its *ink* is that product. Over a Poisson number of them the
//! pixel's ink has the mean `n·a·(z₂ − z₁)` (the haze's geometric part) and the
//! variance
//!
//! `Var = Σ n·a²/(p²·u)·(H(z₂/u) − H(z₁/u))`, `u = v·T/p`,
//!
//! `H(w) = ln w − w/3` for `w ≤ 1` (the motion `v·T` longer than the footprint),
//! `H(w) = ½ − 1/w + 1/(6w²)` beyond (one continuous, smooth function; its
//! derivative is `∫ overlap²` of a moving point and the footprint, exact for a
//! point particle): [`unresolved_ink_variance`], summed over the weather's spectra
//! (Gunn–Marshall snow, Marshall–Palmer rain). The sizes simulated one by one are
//! there as far as the world emitter draws them: their share `1 − 1/m_world` is
//! unresolved; smaller ones entirely.
//!
//! The frame draws it as a zero-mean grain of that variance over the haze, the
//! pixel's colour moved toward the haze's by its ink's deviation: `C + (L − C)·δ`,
//! `δ = σ(z₂)·g`, `g` of unit variance, constant along a streak's length on screen
//! and new every exposure ([`streak_grain`]). The frame's block carries one size's
//! worth ([`UnresolvedStreaks`]: the sum's scale `C`, one speed's reach `ū` that
//! gives the sum's far limit, `z₁` and the streaks' length and direction on
//! screen); WGSL: `unresolved_streak_variance`, `streak_grain` (drawing.wgsl),
//! `with_unresolved_streaks` (render_scene.wgsl).
//!
//! What it is not: a drawn particle's own streak (the camera volume's and the
//! world emitter's particles draw those), or anything in front of `z₁`.

use glam::{Vec2, Vec3};

use crate::particles::kind::{ParticleKind, Spectrum};
use crate::weather::Weather;

/// Sizes each spectrum is summed over.
pub const UNRESOLVED_SIZES: u32 = 48;
/// The least reach `u` used, m (a still exposure: the frozen limit).
pub const LEAST_REACH_M: f32 = 1.0e-3;
/// The nearest the grain begins, m (a camera without a volume of its own).
pub const LEAST_NEAR_M: f32 = 2.0;

/// `H(w)` of the module docs.
#[must_use]
pub fn streak_h(w: f32) -> f32 {
    if w <= 1.0 {
        w.max(1.0e-12).ln() - w / 3.0
    } else {
        0.5 - 1.0 / w + 1.0 / (6.0 * w * w)
    }
}

/// The variance of one size's ink in a pixel of `pixel_rad` between `near_m` and
/// `far_m` for `n_per_m3` particles of area `area_m2` moving across the view at
/// `speed_mps` during `exposure_s`.
#[must_use]
pub fn unresolved_ink_variance(
    n_per_m3: f32,
    area_m2: f32,
    speed_mps: f32,
    exposure_s: f32,
    pixel_rad: f32,
    near_m: f32,
    far_m: f32,
) -> f32 {
    if far_m <= near_m || n_per_m3 <= 0.0 {
        return 0.0;
    }
    let u = (speed_mps * exposure_s / pixel_rad).max(LEAST_REACH_M);
    n_per_m3 * area_m2 * area_m2 / (pixel_rad * pixel_rad * u)
        * (streak_h(far_m / u) - streak_h(near_m / u))
}

/// One size class of the air: particles per m³, area m², velocity m/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SizeClass {
    /// Particles per m³ in the class, unresolved.
    pub n_per_m3: f32,
    /// A particle's area, m².
    pub area_m2: f32,
    /// Its velocity, m/s: its fall and the mean wind (its length is taken as the
    /// speed across the view).
    pub velocity_mps: Vec3,
}

/// The weather's unresolved flakes and drops in [`UNRESOLVED_SIZES`] classes a
/// spectrum: the whole spectrum, the sizes simulated one by one at the share
/// `unresolved_share` the world emitter leaves undrawn.
#[must_use]
pub fn unresolved_size_classes(weather: &Weather, unresolved_share: f32) -> Vec<SizeClass> {
    let wind = weather.wind.mean_wind_mps;
    let moving = |fall: f32| Vec3::new(wind.x, -fall, wind.z);
    let share = unresolved_share.clamp(0.0, 1.0);
    let mut classes = Vec::new();
    // Each exponential spectrum N0·e^(−Λd) (d mm) over its support, midpoints; grains
    // of one size are in the haze's extinction only.
    for kind in ParticleKind::ALL {
        let Some(Spectrum::Exponential {
            n0_per_m3_mm: n0,
            slope_per_mm: slope,
            support_mm: (from_mm, to_mm),
            simulated_from_mm,
            ..
        }) = kind.spectrum_in(weather)
        else {
            continue;
        };
        // Over the sizes that exist, to 8 mean sizes past the first.
        let width = ((from_mm + 8.0 / slope).min(to_mm) - from_mm) / UNRESOLVED_SIZES as f32;
        for k in 0..UNRESOLVED_SIZES {
            let d = from_mm + (k as f32 + 0.5) * width;
            let n = n0 * (-slope * d).exp() * width;
            let diameter_m = kind.diameter_at_spectral_size_m(d);
            classes.push(SizeClass {
                n_per_m3: n * if d >= simulated_from_mm { share } else { 1.0 },
                area_m2: std::f32::consts::FRAC_PI_4 * diameter_m * diameter_m,
                velocity_mps: moving(kind.fall_speed_at_spectral_size_mps(d)),
            });
        }
    }
    classes
}

/// The variance of the unresolved ink between `near_m` and `far_m`, summed over
/// `classes` (the reference the frame's one-size form is tested against).
#[must_use]
pub fn unresolved_ink_variance_of(
    classes: &[SizeClass],
    exposure_s: f32,
    pixel_rad: f32,
    near_m: f32,
    far_m: f32,
) -> f32 {
    classes
        .iter()
        .map(|c| {
            unresolved_ink_variance(
                c.n_per_m3,
                c.area_m2,
                c.velocity_mps.length(),
                exposure_s,
                pixel_rad,
                near_m,
                far_m,
            )
        })
        .sum()
}

/// What the frame draws the grain with (module docs): the block's
/// `RenderParams::unresolved_streaks` and `streak_direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnresolvedStreaks {
    /// `C`: the sum's scale, so that `Var(z) = C·(H(z/ū) − H(z₁/ū))`.
    pub scale: f32,
    /// `ū`, m.
    pub reach_m: f32,
    /// `z₁`, m: where the grain begins.
    pub near_m: f32,
    /// The streaks' length on screen at the variance's weighted depth, px (at least 1).
    pub length_px: f32,
    /// The particles' variance-weighted velocity, m/s (their direction on screen).
    pub velocity_mps: Vec3,
}

impl UnresolvedStreaks {
    /// No grain.
    pub const NONE: Self = Self {
        scale: 0.0,
        reach_m: 1.0,
        near_m: LEAST_NEAR_M,
        length_px: 1.0,
        velocity_mps: Vec3::ZERO,
    };

    /// The grain of `classes` seen by pixels of `pixel_rad` over `exposure_s` from
    /// `near_m` on: its far limit exact, one reach for every size.
    #[must_use]
    pub fn of(classes: &[SizeClass], exposure_s: f32, pixel_rad: f32, near_m: f32) -> Self {
        let near_m = near_m.max(LEAST_NEAR_M);
        let reaches: Vec<(f32, f32, Vec3)> = classes
            .iter()
            .filter(|c| c.n_per_m3 > 0.0)
            .map(|c| {
                let u = (c.velocity_mps.length() * exposure_s / pixel_rad).max(LEAST_REACH_M);
                let scale = c.n_per_m3 * c.area_m2 * c.area_m2 / (pixel_rad * pixel_rad * u);
                (scale * (0.5 - streak_h(near_m / u)), u, c.velocity_mps)
            })
            .collect();
        let far: f32 = reaches.iter().map(|r| r.0).sum();
        if far <= 0.0 || !far.is_finite() {
            return Self::NONE;
        }
        // The variance-weighted reach and velocity; the scale that keeps the far
        // limit.
        let reach_m = reaches.iter().map(|r| r.0 * r.1).sum::<f32>() / far;
        let velocity_mps = reaches.iter().map(|r| r.0 * r.2).sum::<Vec3>() / far;
        let scale = far / (0.5 - streak_h(near_m / reach_m));
        // The length on screen where half the variance lies nearer: `u/z` px.
        let half = streak_depth_of_half(reach_m, near_m);
        Self {
            scale,
            reach_m,
            near_m,
            length_px: (reach_m / half).max(1.0),
            velocity_mps,
        }
    }

    /// `Var(z)`: the ink's variance from `near_m` to `far_m` (WGSL:
    /// `unresolved_streak_variance`).
    #[must_use]
    pub fn variance(&self, far_m: f32) -> f32 {
        if far_m <= self.near_m {
            return 0.0;
        }
        self.scale * (streak_h(far_m / self.reach_m) - streak_h(self.near_m / self.reach_m))
    }
}

/// The depth nearer than which half of the far variance lies, for one reach.
fn streak_depth_of_half(reach_m: f32, near_m: f32) -> f32 {
    let target = 0.5 * (0.5 + streak_h(near_m / reach_m));
    // H rises monotonically: bisect w in [near/u, 1e6].
    let (mut lo, mut hi) = ((near_m / reach_m).ln(), 1.0e6f32.ln());
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if streak_h(mid.exp()) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (0.5 * (lo + hi)).exp() * reach_m
}

/// A grain value of unit variance and zero mean for `pixel` (px), constant along
/// streaks `length_px` long in the unit screen direction `along`, one pixel wide,
/// new for each `exposure` number (WGSL: `streak_grain`): the sum of three uniforms
/// (ten bits each of one hash), centred and scaled.
#[must_use]
pub fn streak_grain(pixel: Vec2, along: Vec2, length_px: f32, exposure: u32) -> f32 {
    let w = pixel.dot(along);
    let c = pixel.perp_dot(along);
    let column = c.floor() as i32 as u32;
    let offset = hash_unit(crate::particles::rng::pcg_hash(column ^ 0x5bd1_e995));
    let cell = (w / length_px.max(1.0) + offset).floor() as i32 as u32;
    let h = crate::particles::rng::pcg_hash(
        column.wrapping_mul(0x9e37_79b1) ^ cell.wrapping_mul(0x85eb_ca77) ^ exposure,
    );
    // Three uniforms of ten bits each from the one hash.
    let part = |shift: u32| ((h >> shift) & 1023) as f32 / 1023.0;
    2.0 * (part(0) + part(10) + part(20) - 1.5)
}

/// A unit `[0, 1)` from a hash's upper 24 bits.
fn hash_unit(h: u32) -> f32 {
    (h >> 8) as f32 / 16_777_216.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::rng::pcg_hash;
    use crate::weather::PrecipitationKind::{DrySnow as Snow, Rain};

    /// A random unit from a counter.
    struct Draws(u32);
    impl Draws {
        fn next(&mut self) -> f32 {
            self.0 = self.0.wrapping_add(1);
            hash_unit(pcg_hash(self.0.wrapping_mul(0x2545_f491)))
        }
        /// A Poisson count of mean `mean` (Knuth's product of uniforms, by pieces).
        fn poisson(&mut self, mean: f32) -> u32 {
            let mut count = 0;
            let mut left = mean;
            while left > 0.0 {
                let step = left.min(20.0);
                left -= step;
                let limit = (-step).exp();
                let mut product = self.next();
                while product > limit {
                    count += 1;
                    product *= self.next();
                }
            }
            count
        }
    }

    /// Monte Carlo: point particles of one size placed at random in the air between
    /// `near` and `far` in front of one pixel, moving across it during the exposure;
    /// the pixel's ink's mean and variance over many exposures.
    fn simulate(
        n: f32,
        area: f32,
        speed: f32,
        exposure: f32,
        p: f32,
        near: f32,
        far: f32,
    ) -> (f32, f32) {
        let motion = speed * exposure;
        let mut draws = Draws(7);
        // Angles θx from −(motion/near) − p to p (all that can reach the pixel), θy
        // over the pixel; depth with density ∝ z².
        let span_x = motion / near + 2.0 * p;
        let volume = (far.powi(3) - near.powi(3)) / 3.0 * span_x * p;
        let trials = 100_000;
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for _ in 0..trials {
            let mut ink = 0.0f32;
            for _ in 0..draws.poisson(n * volume) {
                let z = (near.powi(3) + draws.next() * (far.powi(3) - near.powi(3))).cbrt();
                let start = -(motion / near) - p + draws.next() * span_x;
                let travel = motion / z;
                let inside = if travel > 0.0 {
                    ((start + travel).min(p) - start.max(0.0)).max(0.0) / travel
                } else if (0.0..p).contains(&start) {
                    1.0
                } else {
                    0.0
                };
                ink += area / (p * z).powi(2) * inside;
            }
            sum += f64::from(ink);
            sum2 += f64::from(ink) * f64::from(ink);
        }
        let mean = sum / f64::from(trials);
        (
            (mean) as f32,
            (sum2 / f64::from(trials) - mean * mean) as f32,
        )
    }

    #[test]
    fn the_variance_is_what_moving_particles_give_a_pixel() {
        // A pixel of 2 mrad; one size of 8 mm² moving 0.5, 6 and 0 m/s over 1/60 s,
        // from 10 to 40 m: the motion shorter than the footprint, both (u = 17 m), longer (u = 50 m:
        // both pieces of H), and none.
        for speed in [0.5f32, 2.0, 6.0, 0.0] {
            let (n, area, t, p, near, far) = (30.0, 8.0e-6, 1.0 / 60.0, 2.0e-3, 10.0, 40.0);
            let (mean, variance) = simulate(n, area, speed, t, p, near, far);
            let want_mean = n * area * (far - near);
            let want = unresolved_ink_variance(n, area, speed, t, p, near, far);
            println!("{speed} m/s: mean {mean} ({want_mean}), variance {variance} ({want})");
            assert!(
                (mean / want_mean - 1.0).abs() < 0.03,
                "{speed} m/s: mean {mean} against {want_mean}"
            );
            assert!(
                (variance / want - 1.0).abs() < 0.08,
                "{speed} m/s: variance {variance} against {want}"
            );
        }
    }

    #[test]
    fn h_is_continuous_and_smooth_where_its_pieces_meet() {
        let (a, b) = (streak_h(1.0 - 1e-4), streak_h(1.0 + 1e-4));
        assert!((a - b).abs() < 1e-3, "{a} {b}");
        let slope = |w: f32| (streak_h(w + 1e-3) - streak_h(w - 1e-3)) / 2e-3;
        assert!((slope(0.99) - slope(1.01)).abs() < 0.02);
        // Far away the pixel sees nothing more; a still exposure is the frozen limit.
        assert!((streak_h(1.0e6) - 0.5).abs() < 1e-5);
        let frozen = unresolved_ink_variance(1.0, 1.0e-5, 0.0, 0.0, 1.0e-3, 10.0, 20.0);
        let want = 1.0e-10 / 1.0e-6 * (1.0 / 10.0 - 1.0 / 20.0);
        assert!(
            (frozen / want - 1.0).abs() < 0.01,
            "{frozen} against {want}"
        );
    }

    fn weather(kind: crate::weather::PrecipitationKind, rate: f32, wind: f32) -> Weather {
        let mut w = Weather {
            kind,
            intensity_mm_per_h: rate,
            air_temperature_c: if kind == Rain { 10.0 } else { -5.0 },
            ..Weather::default()
        };
        w.wind.mean_wind_mps = Vec3::new(wind, 0.0, 0.0);
        w
    }

    #[test]
    fn one_reach_stands_for_the_spectrum_within_ten_percent_at_every_depth() {
        for w in [
            weather(Rain, 1.0, 0.0),
            weather(Rain, 40.0, 5.0),
            weather(Snow, 0.5, 0.0),
            weather(Snow, 6.0, 14.0),
        ] {
            let classes = unresolved_size_classes(&w, 1.0);
            let (t, p, near) = (1.0 / 60.0, 1.0e-3, 15.0);
            let frame = UnresolvedStreaks::of(&classes, t, p, near);
            for far in [20.0f32, 40.0, 80.0, 200.0, 1_000.0, 1.0e5] {
                let exact = unresolved_ink_variance_of(&classes, t, p, near, far);
                let one = frame.variance(far);
                assert!(
                    (one / exact - 1.0).abs() < 0.1,
                    "{:?} {}: at {far} m {one} against {exact}",
                    w.kind,
                    w.intensity_mm_per_h
                );
            }
            assert!(frame.length_px >= 1.0);
        }
    }

    #[test]
    fn the_grain_follows_the_weather_and_none_falls_from_a_dry_sky() {
        let (t, p, near) = (1.0 / 60.0, 1.0e-3, 15.0);
        let std = |w: &Weather| {
            let frame = UnresolvedStreaks::of(&unresolved_size_classes(w, 1.0), t, p, near);
            frame.variance(1.0e5).sqrt()
        };
        assert!(std(&weather(Rain, 0.0, 0.0)) == 0.0);
        assert!(std(&weather(Snow, 0.0, 0.0)) == 0.0);
        let rain: Vec<f32> = [0.1, 1.0, 10.0, 40.0]
            .iter()
            .map(|&r| std(&weather(Rain, r, 0.0)))
            .collect();
        assert!(rain.windows(2).all(|w| w[1] > w[0]), "{rain:?}");
        // Big slow flakes carry far more grain than drops (a blizzard's snow against a
        // downpour's rain), and what the world emitter draws is taken out.
        let blizzard = std(&weather(Snow, 6.0, 14.0));
        assert!(blizzard > 3.0 * rain[3], "{blizzard} against {}", rain[3]);
        let half = UnresolvedStreaks::of(
            &unresolved_size_classes(&weather(Snow, 6.0, 14.0), 0.0),
            t,
            p,
            near,
        )
        .variance(1.0e5)
        .sqrt();
        assert!(half < 0.5 * blizzard, "{half} against {blizzard}");
        println!("std of the ink beyond 15 m: rain 0.1–40 mm/h {rain:?}, blizzard {blizzard}");
    }

    #[test]
    fn the_grain_has_unit_variance_and_runs_along_the_streaks() {
        let along = Vec2::new(0.3, 0.95).normalize();
        let length = 6.0;
        let n = 200;
        let mut values = Vec::new();
        let (mut same, mut across) = (0.0f32, 0.0f32);
        for y in 0..n {
            for x in 0..n {
                let p = Vec2::new(x as f32, y as f32) + 0.5;
                let g = streak_grain(p, along, length, 3);
                values.push(g);
                same += g * streak_grain(p + along * 0.5 * length * 0.5, along, length, 3);
                across += g * streak_grain(p + along.perp() * 1.5, along, length, 3);
            }
        }
        let m = values.len() as f32;
        let mean = values.iter().sum::<f32>() / m;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / m;
        assert!(
            mean.abs() < 0.02 && (var - 1.0).abs() < 0.03,
            "{mean} {var}"
        );
        // A quarter of a streak along: mostly the same streak; a pixel and a half
        // across: another column.
        assert!(same / m > 0.6, "along {}", same / m);
        assert!((across / m).abs() < 0.05, "across {}", across / m);
        // A new exposure, a new grain.
        let again: f32 = (0..1000)
            .map(|i| {
                let p = Vec2::new(i as f32 * 1.7, 3.0);
                streak_grain(p, along, length, 3) * streak_grain(p, along, length, 4)
            })
            .sum::<f32>()
            / 1000.0;
        assert!(again.abs() < 0.1, "{again}");
    }
}
