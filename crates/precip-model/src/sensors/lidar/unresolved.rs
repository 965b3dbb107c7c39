//! Strikes on the particles the backend does not simulate one by one, drawn per beam
//! from the weather's spectrum (Hahner et al. 2022 sample every flake this way).
//!
//! The camera volume holds the air's density of the sizes simulated one by one
//! ([`crate::Weather::simulated_number_density_per_m3`]) up to its budget; beyond it
//! the world emitter's particles are far sparser than the air's. So along each beam,
//! outside the camera volume at that density, and inside it at what the budget left
//! out, strikes are drawn as a Poisson process: a beam of radius `r(t) = a + k·t`
//! (`k = tan(divergence/2)`) meets particles of mean radius `ρ` at the rate
//! `λ(t) = n·π·(ρ + r(t))²`, whose integral `n·π·((c + k·t)³ − (c + k·t₀)³)/(3k)`
//! (`c = ρ + a`) is inverted in closed form for the first strike. Its kind and size
//! come from the same law particles are born with ([`crate::particles::kind::draw_species`]).
//! The draws are keyed by the seed, the beam's index and the simulation's clock, so
//! every backend, given the same hits, draws the same strikes. Host-side and O(beams):
//! the GPU does the O(beams × particles) part.

use glam::Vec3;

use crate::backend::setup::Setup;
use crate::particles::kind::draw_species;
use crate::particles::particle::ParticleKind;
use crate::particles::rng::{particle_key, random_unit};
use crate::particles::step::StepParams;
use crate::weather::Weather;

use super::Beam;

/// Keys drawn to find the species' mean radius.
const MEAN_RADIUS_SAMPLES: u32 = 256;
/// Seed offset of the strikes' random numbers (apart from the particles').
const STRIKE_SEED: u32 = 0x5EED_1DA2;

/// The air the simulated particles leave out, for one query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnresolvedAir {
    /// The air's number density of the sizes simulated one by one, per m³.
    pub density_per_m3: f32,
    /// What the camera volume leaves out of it inside the box, per m³.
    pub density_in_box_per_m3: f32,
    /// The camera volume's centre, m.
    pub box_centre_m: Vec3,
    /// Its half extent, m (zero: no camera volume).
    pub box_half_extent_m: Vec3,
    /// The species law (the weather's step parameters).
    pub species: StepParams,
    /// The seed and the clock, in one key.
    pub key: u32,
    /// A fog layer's droplets, far too many and too small to draw one by one: their
    /// extinction dims what lies behind ([`BeamQuery::answer`](super::BeamQuery::answer)).
    pub fog_layer: Option<crate::drawing::fog_layer::FogLayer>,
    /// The cloud layers and how far they have drifted, m: their extinction dims
    /// what lies behind them, too.
    pub cloud_layers: (crate::drawing::clouds::CloudLayers, glam::Vec2),
}

/// A strike drawn from the spectrum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledStrike {
    /// Range along the beam, m.
    pub range_m: f32,
    /// What it is.
    pub kind: ParticleKind,
    /// Its diameter, m.
    pub diameter_m: f32,
}

impl UnresolvedAir {
    /// The air of a configuration: `density_per_m3` of simulated sizes, a camera
    /// volume of `box_half_extent_m` around `box_centre_m` holding
    /// `box_particles`, the weather's `species`, keyed by `seed` and `time_s`.
    #[must_use]
    pub fn new(
        density_per_m3: f32,
        (box_centre_m, box_half_extent_m, box_particles): (Vec3, Vec3, u32),
        species: StepParams,
        seed: u32,
        time_s: f64,
    ) -> Self {
        let volume = 8.0 * box_half_extent_m.x * box_half_extent_m.y * box_half_extent_m.z;
        let in_box = if volume > 0.0 {
            box_particles as f32 / volume
        } else {
            0.0
        };
        Self {
            density_per_m3: density_per_m3.max(0.0),
            density_in_box_per_m3: (density_per_m3 - in_box).max(0.0),
            box_centre_m,
            box_half_extent_m,
            species,
            // Milliseconds of the clock: a new draw each frame, the same on every
            // backend at the same time.
            key: particle_key(seed ^ STRIKE_SEED, (time_s * 1000.0).round() as u32, 0),
            fog_layer: None,
            cloud_layers: (crate::drawing::clouds::CloudLayers::NONE, glam::Vec2::ZERO),
        }
    }

    /// The air of a configured backend: `setup`'s camera volume around `camera_m`,
    /// `weather`'s density of the simulated sizes and its species law `species` (the
    /// backend's step parameters), at the clock `time_s`.
    #[must_use]
    pub fn of_configuration(
        setup: &Setup,
        weather: &Weather,
        species: StepParams,
        camera_m: Vec3,
        time_s: f64,
    ) -> Self {
        // The camera volume's particles in the air: the ones drawn (the rest rest).
        let (half_extent, particles) = setup.camera_volume.map_or((Vec3::ZERO, 0), |c| {
            (
                c.volume.half_extent_m,
                species
                    .step_end
                    .saturating_sub(species.world_count)
                    .min(c.particle_count),
            )
        });
        Self {
            fog_layer: setup.render.fog_layer,
            cloud_layers: (
                setup.render.cloud_layers,
                crate::drawing::clouds::cloud_drift_m(weather.wind.mean_wind_mps, time_s as f32),
            ),
            ..Self::new(
                weather.simulated_number_density_per_m3(),
                (camera_m, half_extent, particles),
                species,
                setup.seed,
                time_s,
            )
        }
    }

    /// The species' mean radius, m.
    #[must_use]
    pub fn mean_radius_m(&self) -> f32 {
        let sum: f32 = (0..MEAN_RADIUS_SAMPLES)
            .map(|i| draw_species(particle_key(self.key, i, 1), &self.species).1)
            .sum();
        0.5 * sum / MEAN_RADIUS_SAMPLES as f32
    }

    /// The first strike along beam `index` (its direction normalised) before
    /// `limit_m`, if one is drawn; `mean_radius_m` from [`Self::mean_radius_m`].
    #[must_use]
    pub fn strike(
        &self,
        index: u32,
        beam: &Beam,
        aperture_radius_m: f32,
        mean_radius_m: f32,
        limit_m: f32,
    ) -> Option<SampledStrike> {
        let limit = limit_m.min(beam.max_range_m);
        if limit.is_nan()
            || limit <= 0.0
            || (self.density_per_m3 <= 0.0 && self.density_in_box_per_m3 <= 0.0)
        {
            return None;
        }
        let key = particle_key(self.key, index, 2);
        // The cumulative rate to reach: an exponential draw.
        let mut wanted = -(1.0 - random_unit(key, 0)).ln();
        let (t_in, t_out) = self.box_span(beam);
        let c = mean_radius_m + aperture_radius_m;
        let k = (0.5 * beam.divergence_rad).tan();
        for (from, to, density) in [
            (0.0, t_in.min(limit), self.density_per_m3),
            (
                t_in.min(limit),
                t_out.min(limit),
                self.density_in_box_per_m3,
            ),
            (t_out.min(limit), limit, self.density_per_m3),
        ] {
            if to <= from || density <= 0.0 {
                continue;
            }
            let piece = swept_count(density, c, k, from, to);
            if piece < wanted {
                wanted -= piece;
                continue;
            }
            let range_m = if k > 0.0 {
                let r0 = c + k * from;
                ((r0 * r0 * r0 + 3.0 * k * wanted / (density * std::f32::consts::PI)).cbrt() - c)
                    / k
            } else {
                from + wanted / (density * std::f32::consts::PI * c * c)
            };
            let (kind, diameter_m, _) = draw_species(key, &self.species);
            return Some(SampledStrike {
                range_m: range_m.clamp(from, to),
                kind,
                diameter_m,
            });
        }
        None
    }

    /// Where the beam is inside the camera volume's box: `(t_in, t_out)`, both ∞
    /// when it never is (slab method).
    fn box_span(&self, beam: &Beam) -> (f32, f32) {
        if self.box_half_extent_m.min_element() <= 0.0 {
            return (f32::INFINITY, f32::INFINITY);
        }
        let lo = self.box_centre_m - self.box_half_extent_m - beam.origin_m;
        let hi = self.box_centre_m + self.box_half_extent_m - beam.origin_m;
        let (mut t_in, mut t_out) = (0.0f32, f32::INFINITY);
        for axis in 0..3 {
            let d = beam.direction[axis];
            if d.abs() < 1.0e-12 {
                if lo[axis] > 0.0 || hi[axis] < 0.0 {
                    return (f32::INFINITY, f32::INFINITY);
                }
                continue;
            }
            let (a, b) = (lo[axis] / d, hi[axis] / d);
            t_in = t_in.max(a.min(b));
            t_out = t_out.min(a.max(b));
        }
        if t_in <= t_out {
            (t_in, t_out)
        } else {
            (f32::INFINITY, f32::INFINITY)
        }
    }
}

/// Particles the beam sweeps between `from` and `to`: `∫ n·π·(c + k·t)² dt`.
fn swept_count(density_per_m3: f32, c: f32, k: f32, from: f32, to: f32) -> f32 {
    let pi_n = density_per_m3 * std::f32::consts::PI;
    if k > 0.0 {
        let (a, b) = (c + k * from, c + k * to);
        pi_n * (b * b * b - a * a * a) / (3.0 * k)
    } else {
        pi_n * c * c * (to - from)
    }
}

#[cfg(test)]
mod tests {
    use bytemuck::Zeroable as _;

    use super::*;

    /// The step parameters of 2 mm/h of dry snow at −5 °C.
    fn snow() -> StepParams {
        let weather = Weather {
            intensity_mm_per_h: 2.0,
            ..Weather::default()
        };
        let setup = Setup::over_flat_ground(40.0, 8, 10.0, 10);
        setup.step_params(&weather, Vec3::ZERO, 0.05, 0.0)
    }

    fn fan(count: u32, divergence_rad: f32) -> Vec<Beam> {
        (0..count)
            .map(|i| {
                let a = i as f32 * 2.399_963;
                let y = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
                let r = (1.0 - y * y).sqrt();
                Beam {
                    divergence_rad,
                    ..Beam::ray(Vec3::ZERO, Vec3::new(r * a.cos(), y, r * a.sin()), 100.0)
                }
            })
            .collect()
    }

    #[test]
    fn strikes_in_open_air_are_poisson() {
        let air = UnresolvedAir::new(80.0, (Vec3::ZERO, Vec3::ZERO, 0), snow(), 3, 1.25);
        let mean = air.mean_radius_m();
        // The seed's flakes at −5 °C: 4.3–12.8 mm, mean radius about 4.3 mm.
        assert!((0.003..0.006).contains(&mean), "{mean}");
        let (aperture, divergence) = (0.01f32, 3.0e-3f32);
        let beams = fan(20_000, divergence);
        let ranges: Vec<f32> = beams
            .iter()
            .enumerate()
            .map(|(i, b)| {
                air.strike(i as u32, b, aperture, mean, f32::INFINITY)
                    .map_or(f32::INFINITY, |s| s.range_m)
            })
            .collect();
        for r in [1.0f32, 5.0, 15.0] {
            let expected =
                (-swept_count(80.0, mean + aperture, (0.5 * divergence).tan(), 0.0, r)).exp();
            let clear = ranges.iter().filter(|&&t| t > r).count() as f32 / ranges.len() as f32;
            let sigma = (expected * (1.0 - expected) / ranges.len() as f32).sqrt();
            println!("P(no strike within {r} m) = {clear:.4}, Poisson {expected:.4} ± {sigma:.4}");
            assert!(
                (clear - expected).abs() < 4.0 * sigma + 1e-3,
                "{r} m: {clear} vs {expected}"
            );
        }
    }

    #[test]
    fn a_full_camera_volume_leaves_nothing_to_draw_inside_it_and_limits_hold() {
        // 80 per m³ around the origin, a 10 m box holding all of them.
        let air = UnresolvedAir::new(80.0, (Vec3::ZERO, Vec3::splat(5.0), 80_000), snow(), 3, 0.0);
        assert!(air.density_in_box_per_m3 < 1e-3);
        let mean = air.mean_radius_m();
        for (i, beam) in fan(2_000, 3.0e-3).iter().enumerate() {
            if let Some(s) = air.strike(i as u32, beam, 0.01, mean, f32::INFINITY) {
                // Out of the box: at least 5 m away along some axis.
                let at = beam.direction * s.range_m;
                assert!(at.abs().max_element() >= 5.0 - 1e-3, "{at}");
                assert_eq!(s.kind, ParticleKind::DrySnow);
            }
            let near = air.strike(i as u32, beam, 0.01, mean, 4.0);
            assert!(near.is_none(), "nothing to draw before 4 m");
        }
    }

    #[test]
    fn the_same_clock_draws_the_same_strikes_and_rain_draws_drops() {
        let mut rain = snow();
        rain.species.snow_fraction = 0.0;
        rain.species.rain_slope_per_mm =
            crate::physics::raindrop::marshall_palmer_slope_per_mm(10.0);
        let a = UnresolvedAir::new(500.0, (Vec3::ZERO, Vec3::ZERO, 0), rain, 9, 2.0);
        let b = UnresolvedAir::new(500.0, (Vec3::ZERO, Vec3::ZERO, 0), rain, 9, 2.0);
        let later = UnresolvedAir::new(500.0, (Vec3::ZERO, Vec3::ZERO, 0), rain, 9, 2.1);
        let beams = fan(500, 0.0);
        let draw = |air: &UnresolvedAir| -> Vec<Option<SampledStrike>> {
            let mean = air.mean_radius_m();
            beams
                .iter()
                .enumerate()
                .map(|(i, beam)| air.strike(i as u32, beam, 0.02, mean, 100.0))
                .collect()
        };
        let (x, y, z) = (draw(&a), draw(&b), draw(&later));
        assert_eq!(x, y);
        assert_ne!(x, z);
        assert!(
            x.iter()
                .flatten()
                .all(|s| s.kind == ParticleKind::Rain && (3.0e-4..=6.0e-3).contains(&s.diameter_m))
        );
        assert!(x.iter().flatten().count() > 100);
        // No air, no strikes.
        let none = UnresolvedAir::new(
            0.0,
            (Vec3::ZERO, Vec3::ZERO, 0),
            StepParams::zeroed(),
            1,
            0.0,
        );
        assert!(none.strike(0, &beams[0], 0.0, 0.001, 100.0).is_none());
    }
}
