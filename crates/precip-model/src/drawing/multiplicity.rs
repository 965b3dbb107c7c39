//! How many real particles each simulated one stands for when it is drawn (its
//! *multiplicity*, as in the super-droplet method of Shima et al. 2009, *Q. J. R.
//! Meteorol. Soc.* 135, 1307–1320), so the picture shows the weather's density
//! whatever the particle budget (docs/model.md (5.15)).
//!
//! A pool's particles sample the air it fills: the camera volume its box, the world
//! emitter the column between its rectangle and the ground. The air holds
//! `n_sim` particles per m³ of the sizes simulated one by one
//! ([`crate::Weather::simulated_number_density_per_m3`]), so a pool of `N` particles
//! filling `V` m³ stands for `m = n_sim·V/N` each:
//!
//! - `m < 1` (more particles than the air holds, e.g. a trace of drizzle): a
//!   particle is drawn only if its rank `r(i) ∈ [0, 1)` (a hash of its index, fixed
//!   for its life) is below `m`, so a share `m` of the pool is drawn, the same ones
//!   frame after frame; at 0 mm/h nothing is. The camera volume draws its first
//!   `⌈n_sim·V⌉` particles instead (`camera_drawn_end`): its particles are born at
//!   random places keyed by their index, so the first ones are as good a sample as
//!   any, and the ones not drawn form one range that the step leaves at rest
//!   ([`crate::particles::step`], "Resting particles").
//! - `m ≥ 1` (the budget is short of the air's count, e.g. a downpour): each drawn
//!   particle carries `m` particles' ink — its opacity × `m`, up to opaque — so the
//!   ink on screen, and with it the pixels a photograph's precipitation covers,
//!   follows the physical density (what the budget cannot hold one by one is drawn
//!   into the ones it holds). An opaque flake cannot carry more ink, so each of the
//!   camera volume's flakes drawn as a sprite is drawn as [`snow_copies`] copies,
//!   each at its own fixed offset in the box ([`snow_copy_position`]), moving with it,
//!   carrying `m/k` each: near flakes are as dense as the air's. A sub-pixel particle
//!   (splatted, or enlarged when the splat is off) carries its own ink only
//!   ([`resolved_weight`]): what it stands for beyond itself is in the haze, whose
//!   extinction is the whole air's (§6).
//!
//! Where both pools fill the same air (the camera box inside the emitter's column)
//! the camera volume draws it: a world particle inside the box is not drawn. Grains
//! and snow the wind lifts from the ground ([`crate::physics::grain`],
//! [`crate::physics::drifting_snow`]) stand for themselves (`m = 1`). What lands on
//! the cover is untouched: multiplicity is a drawing weight, the books stay as they
//! are.
//!
//! WGSL twins: `drawn_weight`, `multiplicity_rank` (drawing.wgsl), fed by
//! [`PoolDrawing`] through `RenderParams`.

use glam::Vec3;

use crate::Setup;
use crate::weather::Weather;

/// What drawing needs to weigh each particle by its pool (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoolDrawing {
    /// Particles `[0, world_count)` are the world emitter's.
    pub world_count: u32,
    /// World particles from this index on are lifted from the ground (`m = 1`).
    pub lift_from: u32,
    /// The multiplicity of the world emitter's sky-born particles.
    pub world_multiplicity: f32,
    /// The multiplicity of the camera volume's particles.
    pub camera_multiplicity: f32,
    /// The camera volume's box `(centre, half extent)`, m, if the setup has one.
    pub camera_box_m: Option<(Vec3, Vec3)>,
    /// Copies of each camera-volume flake drawn as a sprite ([`snow_copies`]).
    pub snow_copies: u32,
    /// The camera volume's particles `[world_count, camera_drawn_end)` are drawn:
    /// `⌈n_sim·V⌉` of them, at most all (`world_count` without a camera volume).
    pub camera_drawn_end: u32,
}

/// The most ink one drawn particle carries, in particles: beyond it the image
/// saturates anyway (a streak or sprite at `m·opacity ≥ 1` is opaque).
pub const MAX_MULTIPLICITY: f32 = 1.0e6;

/// The most copies a camera-volume flake is drawn as (the frame's sprite cost grows
/// with them; beyond, each copy carries more than one flake's ink).
pub const MAX_SNOW_COPIES: u32 = 4;

/// Copies of each camera-volume flake drawn as a sprite at multiplicity `m`:
/// `clamp(⌈m⌉, 1, MAX_SNOW_COPIES)`.
#[must_use]
pub fn snow_copies(multiplicity: f32) -> u32 {
    if multiplicity > 1.0 {
        (multiplicity.ceil() as u32).min(MAX_SNOW_COPIES)
    } else {
        1
    }
}

/// Where copy `copy` of camera-volume particle `index` at `position_m` is drawn:
/// copy 0 where it is; copy `c > 0` moved by a fixed offset drawn from the index and
/// the copy (uniform over the box) and wrapped into the box, so copies fill the box
/// evenly and move with their particle. WGSL twin: `snow_copy_position`
/// (particle_lists.wgsl).
#[must_use]
pub fn snow_copy_position(
    (centre_m, half_m): (Vec3, Vec3),
    index: u32,
    copy: u32,
    position_m: Vec3,
) -> Vec3 {
    if copy == 0 {
        return position_m;
    }
    let key = index ^ copy.wrapping_mul(0x68e3_1da4);
    let offset = Vec3::new(
        multiplicity_rank(key),
        multiplicity_rank(key ^ 0x1b87_3593),
        multiplicity_rank(key ^ 0xcc9e_2d51),
    ) * 2.0
        * half_m;
    let q = position_m + offset - centre_m;
    let wrapped = q - 2.0 * half_m * ((q + half_m) / (2.0 * half_m)).floor();
    centre_m + wrapped
}

impl Setup {
    /// How this setup's pools are drawn under `weather` with the camera volume
    /// centred at `camera_centre_m` (module docs).
    #[must_use]
    pub fn pool_drawing(&self, weather: &Weather, camera_centre_m: Vec3) -> PoolDrawing {
        let (world_count, camera_count) = self.particle_counts();
        let n_sim = f64::from(weather.simulated_number_density_per_m3());
        let lift_from = self.grain_lift(weather, world_count).lift_from;
        let per = |physical: f64, count: u32| -> f32 {
            if count == 0 || physical.is_nan() || physical <= 0.0 {
                0.0
            } else {
                ((physical / f64::from(count)) as f32).min(MAX_MULTIPLICITY)
            }
        };
        let world_multiplicity = match &self.world_emitter {
            Some(e) => {
                let column_m3 = f64::from(e.emitter.horizontal_area_m2())
                    * f64::from(self.world_column_height_m());
                per(n_sim * column_m3, lift_from)
            }
            None => 0.0,
        };
        let (camera_multiplicity, camera_box_m, camera_drawn): (f32, Option<(Vec3, Vec3)>, u32) =
            match &self.camera_volume {
                Some(c) if camera_count > 0 => {
                    let in_the_air = n_sim * f64::from(c.volume.volume_m3());
                    let drawn = if in_the_air.is_nan() || in_the_air <= 0.0 {
                        0
                    } else {
                        in_the_air.ceil().min(f64::from(camera_count)) as u32
                    };
                    (
                        per(in_the_air, camera_count),
                        Some((camera_centre_m, c.volume.half_extent_m)),
                        drawn,
                    )
                }
                _ => (0.0, None, 0),
            };
        PoolDrawing {
            world_count,
            lift_from,
            world_multiplicity,
            camera_multiplicity,
            camera_box_m,
            snow_copies: snow_copies(camera_multiplicity),
            camera_drawn_end: world_count + camera_drawn,
        }
    }

    /// The height of the column the world emitter's particles fill, m: from its
    /// rectangle's centre down to the mean height of the ground map (at least 1 m).
    #[must_use]
    pub fn world_column_height_m(&self) -> f32 {
        let Some(e) = &self.world_emitter else {
            return 0.0;
        };
        let heights = &self.ground.height_m;
        let mean_ground = if heights.is_empty() {
            0.0
        } else {
            (heights.iter().map(|&h| f64::from(h)).sum::<f64>() / heights.len() as f64) as f32
        };
        (e.emitter.point(0.0, 0.0).y - mean_ground).max(1.0)
    }
}

/// A particle's rank in `[0, 1)`: an integer hash of its index (the same bits in
/// WGSL), fixed for its life, so the same particles are drawn frame after frame.
#[must_use]
pub fn multiplicity_rank(index: u32) -> f32 {
    let mut h = index.wrapping_mul(0x9e37_79b9);
    h ^= h >> 16;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^= h >> 16;
    (h >> 8) as f32 / 16_777_216.0
}

/// The multiplicity of particle `index` at `position_m` (module docs): 0 for a world
/// particle inside the camera volume's box.
#[must_use]
pub fn particle_multiplicity(pools: &PoolDrawing, index: u32, position_m: Vec3) -> f32 {
    if index >= pools.world_count {
        return pools.camera_multiplicity;
    }
    if index >= pools.lift_from {
        return 1.0;
    }
    if let Some((centre, half)) = pools.camera_box_m
        && ((position_m - centre).abs() - half).max_element() < 0.0
    {
        return 0.0;
    }
    pools.world_multiplicity
}

/// How much ink particle `index` at `position_m` is drawn with, in particles (0: not
/// drawn): a camera-volume particle below `camera_drawn_end` carries `max(m, 1)`,
/// one above it none; a world particle [`drawn_weight`] of its
/// [`particle_multiplicity`]. WGSL twin: `particle_weight` (particle_lists.wgsl).
#[must_use]
pub fn particle_weight(pools: &PoolDrawing, index: u32, position_m: Vec3) -> f32 {
    if index >= pools.world_count {
        return if index < pools.camera_drawn_end {
            pools.camera_multiplicity.max(1.0)
        } else {
            0.0
        };
    }
    drawn_weight(index, particle_multiplicity(pools, index, position_m))
}

/// How much ink particle `index` of multiplicity `m` is drawn with, in particles: 0
/// (not drawn) when its rank is at or above `m < 1`, else `max(m, 1)`.
/// WGSL twin: `drawn_weight` (drawing.wgsl).
#[must_use]
pub fn drawn_weight(index: u32, multiplicity: f32) -> f32 {
    if multiplicity_rank(index) < multiplicity {
        multiplicity.max(1.0)
    } else {
        0.0
    }
}

/// The ink a drawn particle of weight `weight` ([`drawn_weight`]) carries: all of it
/// when it is `resolved` (drawn at least `min_px`), at most its own when it is
/// sub-pixel (module docs). WGSL twin: `resolved_weight` (particle_lists.wgsl).
#[must_use]
pub fn resolved_weight(weight: f32, resolved: bool) -> f32 {
    if resolved { weight } else { weight.min(1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::setup::{CameraVolumeSetup, EmitterSetup};
    use crate::{CameraVolume, PrecipitationKind, WorldEmitter};

    fn setup(intensity_mm_per_h: f32, kind: PrecipitationKind) -> Setup {
        let mut s = Setup::over_flat_ground(40.0, 16, 10.0, 20_000);
        s.weather.kind = kind;
        s.weather.intensity_mm_per_h = intensity_mm_per_h;
        s.world_emitter = Some(EmitterSetup {
            emitter: WorldEmitter::horizontal(Vec3::new(0.0, 10.0, 0.0), 40.0, 40.0, 10.0),
            particle_count: 20_000,
        });
        s.camera_volume = Some(CameraVolumeSetup {
            volume: CameraVolume {
                half_extent_m: Vec3::new(8.0, 6.0, 8.0),
                ..CameraVolume::default()
            },
            particle_count: 10_000,
        });
        s
    }

    #[test]
    fn multiplicity_is_the_air_s_count_over_the_pool_s() {
        let s = setup(2.0, PrecipitationKind::DrySnow);
        let p = s.pool_drawing(&s.weather, Vec3::new(0.0, 2.0, 0.0));
        let n = f64::from(s.weather.simulated_number_density_per_m3());
        let camera = n * 3072.0 / 10_000.0;
        assert!(
            (f64::from(p.camera_multiplicity) / camera - 1.0).abs() < 1e-4,
            "{p:?}"
        );
        let column = n * 1600.0 * f64::from(s.world_column_height_m()) / 20_000.0;
        assert!(
            (f64::from(p.world_multiplicity) / column - 1.0).abs() < 1e-4,
            "{p:?}"
        );
        // None in the air: nothing drawn.
        let dry = Weather {
            intensity_mm_per_h: 0.0,
            ..s.weather
        };
        let p0 = s.pool_drawing(&dry, Vec3::ZERO);
        assert_eq!((p0.world_multiplicity, p0.camera_multiplicity), (0.0, 0.0));
    }

    #[test]
    fn the_camera_volume_draws_the_air_s_count_of_its_first_particles_and_the_rest_rest() {
        for (mm_per_h, kind) in [
            (0.0, PrecipitationKind::Rain),
            (0.01, PrecipitationKind::Rain),
            (0.3, PrecipitationKind::DrySnow),
            (40.0, PrecipitationKind::Rain),
        ] {
            let s = setup(mm_per_h, kind);
            let p = s.pool_drawing(&s.weather, Vec3::ZERO);
            let in_the_air = f64::from(s.weather.simulated_number_density_per_m3()) * 3072.0;
            let drawn = p.camera_drawn_end - p.world_count;
            assert_eq!(
                drawn,
                in_the_air.ceil().min(10_000.0) as u32,
                "{mm_per_h}: {p:?}"
            );
            let weights: Vec<f32> = (p.world_count..p.world_count + 10_000)
                .map(|i| particle_weight(&p, i, Vec3::ZERO))
                .collect();
            let inked = weights.iter().filter(|&&w| w > 0.0).count() as u32;
            assert_eq!(inked, drawn, "{mm_per_h} mm/h");
            assert!(weights[..drawn as usize].iter().all(|&w| w >= 1.0));
            // The step moves exactly the drawn ones of the camera volume; at 0 mm/h
            // none of the sky's either.
            let step = s.step_params(&s.weather, Vec3::ZERO, 0.01, 0.0);
            let moved = crate::particles::step::stepped_particles(&step);
            assert_eq!(moved.end, p.camera_drawn_end, "{mm_per_h} mm/h");
            assert_eq!(
                moved.start == p.lift_from,
                mm_per_h == 0.0,
                "{mm_per_h} mm/h"
            );
        }
    }

    #[test]
    fn multiplicity_follows_the_intensity_as_the_air_s_density_does() {
        for kind in [PrecipitationKind::Rain, PrecipitationKind::DrySnow] {
            let s = setup(1.0, kind);
            let at = |mm_per_h: f32| {
                let w = Weather {
                    intensity_mm_per_h: mm_per_h,
                    ..s.weather
                };
                let p = s.pool_drawing(&w, Vec3::ZERO);
                let n = w.simulated_number_density_per_m3();
                (p.camera_multiplicity / n, p.world_multiplicity / n)
            };
            let (c1, w1) = at(0.01);
            for r in [0.1, 1.0, 10.0, 40.0] {
                let (c, w) = at(r);
                assert!(
                    (c / c1 - 1.0).abs() < 1e-4 && (w / w1 - 1.0).abs() < 1e-4,
                    "{kind:?} {r}"
                );
            }
        }
    }

    #[test]
    fn world_particles_in_the_camera_box_and_lifted_ones_are_weighed_apart() {
        let s = setup(2.0, PrecipitationKind::DrySnow);
        let p = PoolDrawing {
            lift_from: 15_000,
            ..s.pool_drawing(&s.weather, Vec3::ZERO)
        };
        assert!(particle_multiplicity(&p, 0, Vec3::new(1.0, 1.0, 1.0)).abs() < f32::MIN_POSITIVE);
        assert!(
            (particle_multiplicity(&p, 0, Vec3::new(9.0, 1.0, 1.0)) - p.world_multiplicity).abs()
                < 1e-6
        );
        assert!((particle_multiplicity(&p, 15_000, Vec3::ZERO) - 1.0).abs() < 1e-6);
        assert!(
            (particle_multiplicity(&p, 20_000, Vec3::ZERO) - p.camera_multiplicity).abs() < 1e-6
        );
    }

    proptest::proptest! {
        #[test]
        fn the_drawn_share_is_the_multiplicity(m in 0.0f32..1.0, start in 0u32..1_000_000) {
            let n = 20_000u32;
            let drawn = (start..start + n).filter(|&i| drawn_weight(i, m) > 0.0).count() as f32;
            // Binomial: 4.5 standard deviations of n·m·(1 − m).
            let sd = (n as f32 * m * (1.0 - m)).sqrt();
            proptest::prop_assert!((drawn - n as f32 * m).abs() <= 4.5 * sd + 1.0, "{drawn} of {n} at {m}");
        }

        #[test]
        fn above_one_every_particle_carries_its_multiplicity(m in 1.0f32..1000.0, i in 0u32..u32::MAX) {
            proptest::prop_assert!((drawn_weight(i, m) - m).abs() < 1e-6);
        }
    }

    #[test]
    fn copies_fill_the_box_evenly_and_move_with_their_flake() {
        let centre = Vec3::new(3.0, 2.0, -1.0);
        let half = Vec3::new(8.0, 6.0, 8.0);
        let mut octants = [0u32; 8];
        for i in 0..20_000u32 {
            let p = snow_copy_position((centre, half), i, 1 + i % 3, centre);
            let q = p - centre;
            assert!((q.abs() - half).max_element() <= 1e-4, "{q}");
            octants[usize::from(q.x > 0.0)
                + 2 * usize::from(q.y > 0.0)
                + 4 * usize::from(q.z > 0.0)] += 1;
            // A flake moved by less than the box moves its copy by the same (mod the box).
            let moved =
                snow_copy_position((centre, half), i, 1 + i % 3, centre + Vec3::splat(0.25));
            let d = moved - p;
            let d = d - 2.0 * half * ((d + half) / (2.0 * half)).floor();
            assert!((d - Vec3::splat(0.25)).length() < 1e-3, "{d}");
        }
        for o in octants {
            assert!((2_300..=2_700).contains(&o), "{octants:?}");
        }
        assert_eq!(
            snow_copy_position((centre, half), 7, 0, Vec3::ONE),
            Vec3::ONE
        );
        assert_eq!(
            (
                snow_copies(0.3),
                snow_copies(1.0),
                snow_copies(2.5),
                snow_copies(40.0)
            ),
            (1, 1, 3, MAX_SNOW_COPIES)
        );
    }

    #[test]
    fn a_sub_pixel_particle_carries_its_own_ink_only() {
        assert!((resolved_weight(40.0, true) - 40.0).abs() < f32::EPSILON);
        assert!((resolved_weight(40.0, false) - 1.0).abs() < f32::EPSILON);
        assert!((resolved_weight(0.5, false) - 0.5).abs() < f32::EPSILON);
        assert!(resolved_weight(0.0, true).abs() < f32::EPSILON);
    }

    #[test]
    fn ranks_are_spread_evenly() {
        let mut bins = [0u32; 10];
        for i in 0..100_000u32 {
            bins[(multiplicity_rank(i) * 10.0) as usize] += 1;
        }
        for b in bins {
            assert!((9_500..=10_500).contains(&b), "{bins:?}");
        }
    }
}
