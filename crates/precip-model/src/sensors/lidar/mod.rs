//! LiDAR beams through the precipitation: for each beam, the first particle it
//! strikes and the hard target behind, with the target's two-way attenuation — the
//! approach of Hahner et al. (2022, *LiDAR Snowfall Simulation for Robust 3D Object
//! Detection*, CVPR), which samples snowflakes along each beam, done here against the
//! particles the backend simulates. WGSL twins in `shaders/lidar.wgsl`, side by side;
//! every backend runs the same query ([`crate::Backend::query_beams`]): the CPU
//! reference with [`query_on_cpu`], the GPU backends with the `query_beams` kernel.
//!
//! ## A beam
//!
//! A cone from `origin_m` along `direction`, of full divergence angle
//! `divergence_rad`, starting `aperture_radius_m` wide ([`BeamQuery`]): at range `t`
//! its radius is `r(t) = aperture + t·tan(divergence/2)`. A particle of diameter `D`
//! centred at `P` is struck when `P` lies ahead of the origin within the beam's reach
//! and its distance from the axis is at most `r(t) + D/2`, `t` the distance along the
//! axis ([`beam_strike_range_m`]); the first struck is the nearest such `t` (ties:
//! the lower particle index), and only if it is nearer than the hard target.
//!
//! ## The hard target
//!
//! The top-most surface of the scene, the ground map particles land on (nearest
//! texel, as they see it): the beam marches in steps of half the smallest texel side
//! (at most [`MAX_MARCH_STEPS`]) and the first step found under the surface is refined
//! by [`BISECTIONS`] halvings ([`hard_target_range_m`]). Off the map is open sky.
//!
//! ## What comes back
//!
//! [`BeamReturn`]: the particle's range, diameter and kind, and the share of the
//! beam's footprint at that range it covers (`min(1, (D/2)²/r(t)²)`; a sensor model
//! compares its echo with the target's, as Hahner et al. do); the target's range and
//! the two-way transmittance `e^(−2σr)` through the air's extinction in the query's
//! band ([`crate::sensors::optics`]; by default the weather's spectra: pass
//! [`crate::Backend::optics`]' live value to follow the particles), times a fog
//! layer's `e^(−2B·ℓ)` over the part `ℓ` of the path in it ([`fog_layer_two_way`])
//! and the cloud layers' `e^(−2τ)` over their optical depth along the path
//! ([`crate::drawing::clouds::CloudLayers::optical_depth`]).
//!
//! ## Cost
//!
//! Each beam could strike any particle. The kernel takes the beams 64 at a time
//! (a workgroup), bounds them by one cone ([`beam_group_bound`]: from the centre of
//! their origins, around their mean direction, as wide as the widest beam's angle
//! plus its divergence, padded by the origins' spread and the aperture) and tests
//! each particle against that cone once ([`group_may_strike`]); only the particles
//! inside are tested against the 64 beams. The bound is conservative (a proptest
//! checks that no particle a beam strikes is left out), so the answers are the CPU
//! reference's, which tests every pair. Beams that lie close together in the query
//! (a LiDAR's pattern, row by row) make narrow cones: a 1 024-step row's 64
//! neighbours span 22.5°.

use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::backend::error::BackendError;
use crate::particles::ground::GroundMap;
use crate::particles::particle::{Particle, ParticleKind, ParticleSource};
use crate::sensors::optics::Band;

pub mod unresolved;
pub mod water_echo;

pub use unresolved::{SampledStrike, UnresolvedAir};

/// The most beams one query takes.
pub const MAX_BEAMS: usize = 1 << 20;
/// The longest range a beam may have, m.
pub const MAX_RANGE_M: f32 = 10_000.0;
/// The widest divergence a beam may have, rad (full angle).
pub const MAX_DIVERGENCE_RAD: f32 = 0.1;
/// The widest aperture, m (radius).
pub const MAX_APERTURE_RADIUS_M: f32 = 0.5;
/// The most steps the hard target's march takes.
pub const MAX_MARCH_STEPS: u32 = 8192;
/// Halvings that refine the hard target's range.
pub const BISECTIONS: u32 = 16;
/// `BeamHit::particle_flags` of a beam that struck no particle.
pub const NO_PARTICLE: u32 = u32::MAX;
/// `BeamHit::particle_flags` the GPU backends fill the hits with before the kernel
/// runs: a hit still holding it was never written (the dispatch did not finish).
pub const UNWRITTEN: u32 = u32::MAX - 1;

/// One beam, as the GPU reads it (WGSL twin: `Beam` in `lidar.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Beam {
    /// Where it leaves the sensor, world m.
    pub origin_m: Vec3,
    /// Full divergence angle, rad, `[0, 0.1]`.
    pub divergence_rad: f32,
    /// Its direction (normalised by [`BeamQuery::validate`]).
    pub direction: Vec3,
    /// How far it looks, m, `(0, 10 000]`.
    pub max_range_m: f32,
}
const _: () = assert!(size_of::<Beam>() == 32);

impl Beam {
    /// A beam of no divergence from `origin_m` toward `direction`.
    #[must_use]
    pub fn ray(origin_m: Vec3, direction: Vec3, max_range_m: f32) -> Self {
        Self {
            origin_m,
            divergence_rad: 0.0,
            direction,
            max_range_m,
        }
    }
}

/// What the GPU writes for a beam (WGSL twin: `BeamHit`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct BeamHit {
    /// Range to the struck particle's centre along the beam, m (0 if none).
    pub particle_range_m: f32,
    /// Its diameter, m.
    pub particle_diameter_m: f32,
    /// Its flags ([`crate::particles::particle::flags`]), or [`NO_PARTICLE`].
    pub particle_flags: u32,
    /// Range to the hard target, m (negative: none within the beam's range).
    pub target_range_m: f32,
}
const _: () = assert!(size_of::<BeamHit>() == 16);

/// The query's uniform block (WGSL twin: `BeamParams`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct BeamParams {
    /// Beams in the query.
    pub beam_count: u32,
    /// The first particle in the air: particles `[particle_first, particle_end)`
    /// are, the others rest unseen (`precip_model::particles::step`, "Resting
    /// particles").
    pub particle_first: u32,
    /// The end of the particles in the air.
    pub particle_end: u32,
    /// The beams' aperture radius, m.
    pub aperture_radius_m: f32,
    /// The hard target's march step, m (before [`MAX_MARCH_STEPS`] lengthens it).
    pub march_step_m: f32,
    /// Unused (`0`).
    pub reserved0: u32,
    /// Unused (`0`).
    pub reserved1: u32,
    /// Unused (`0`).
    pub reserved2: u32,
}
const _: () = assert!(size_of::<BeamParams>() == 32);

/// Beams to cast, and in which band.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamQuery {
    /// The beams.
    pub beams: Vec<Beam>,
    /// The sensor's band: its extinction attenuates the target's return.
    pub band: Band,
    /// The beams' radius where they leave the sensor, m, `[0, 0.5]`.
    pub aperture_radius_m: f32,
    /// The air's extinction in the band, per m; `None`: the weather's spectra
    /// ([`crate::sensors::optics::Optics::of_weather`]).
    pub extinction_per_m: Option<f32>,
    /// Also draw strikes on the particles not simulated one by one
    /// ([`unresolved`]): where the simulation is sparser than the air (beyond the
    /// camera volume), so echoes come at the air's rate at every range.
    pub sample_unresolved: bool,
}

impl BeamQuery {
    /// Checks every beam and field, and normalises the directions.
    pub fn validate(&self) -> Result<Vec<Beam>, BackendError> {
        fn bad<T>(problem: String) -> Result<T, BackendError> {
            Err(BackendError::InvalidBeams(problem))
        }
        if self.beams.is_empty() || self.beams.len() > MAX_BEAMS {
            return bad(format!(
                "{} beams given: give 1 to {MAX_BEAMS}",
                self.beams.len()
            ));
        }
        if !(self.aperture_radius_m.is_finite()
            && (0.0..=MAX_APERTURE_RADIUS_M).contains(&self.aperture_radius_m))
        {
            return bad(format!(
                "aperture_radius_m {} must be in [0, {MAX_APERTURE_RADIUS_M}] m",
                self.aperture_radius_m
            ));
        }
        if let Some(e) = self.extinction_per_m
            && !(e.is_finite() && e >= 0.0)
        {
            return bad(format!(
                "extinction_per_m {e} must be finite and not negative"
            ));
        }
        self.beams
            .iter()
            .enumerate()
            .map(|(i, b)| {
                if !(b.origin_m.is_finite() && b.origin_m.abs().max_element() <= 1.0e7) {
                    return bad(format!(
                        "beam {i}: origin_m must be finite, within ±10 000 km"
                    ));
                }
                if !b.direction.is_finite() || b.direction.length_squared() < 1.0e-12 {
                    return bad(format!("beam {i}: direction must be finite and not zero"));
                }
                if !(b.divergence_rad.is_finite()
                    && (0.0..=MAX_DIVERGENCE_RAD).contains(&b.divergence_rad))
                {
                    return bad(format!(
                        "beam {i}: divergence_rad {} must be in [0, {MAX_DIVERGENCE_RAD}]",
                        b.divergence_rad
                    ));
                }
                if !(b.max_range_m.is_finite()
                    && b.max_range_m > 0.0
                    && b.max_range_m <= MAX_RANGE_M)
                {
                    return bad(format!(
                        "beam {i}: max_range_m {} must be in (0, {MAX_RANGE_M}] m",
                        b.max_range_m
                    ));
                }
                Ok(Beam {
                    direction: b.direction.normalize(),
                    ..*b
                })
            })
            .collect()
    }

    /// The uniform block for `beams` (validated) over the particles in the air,
    /// `particles` (`precip_model::particles::step::stepped_particles`), and `ground`.
    #[must_use]
    pub fn params(
        &self,
        beams: &[Beam],
        particles: std::ops::Range<u32>,
        ground: &GroundMap,
    ) -> BeamParams {
        BeamParams {
            beam_count: beams.len() as u32,
            particle_first: particles.start,
            particle_end: particles.end,
            aperture_radius_m: self.aperture_radius_m,
            march_step_m: march_step_m(ground),
            reserved0: 0,
            reserved1: 0,
            reserved2: 0,
        }
    }

    /// The air's extinction in the query's band, per m: its own, or `weather`'s
    /// spectra's.
    #[must_use]
    pub fn extinction_in(&self, weather: &crate::Weather) -> f32 {
        self.extinction_per_m.unwrap_or_else(|| {
            crate::sensors::optics::Optics::of_weather(weather)
                .band(self.band)
                .extinction_per_m
        })
    }

    /// The hits a GPU backend starts from: one per beam, each [`UNWRITTEN`].
    #[must_use]
    pub fn unwritten_hits(beam_count: usize) -> Vec<BeamHit> {
        vec![
            BeamHit {
                particle_range_m: 0.0,
                particle_diameter_m: 0.0,
                particle_flags: UNWRITTEN,
                target_range_m: -1.0,
            };
            beam_count
        ]
    }

    /// The returns of `hits` for this query's `beams` (validated) in `weather`, with
    /// strikes drawn from `air` where [`BeamQuery::sample_unresolved`]; an error
    /// naming the backend if a hit was never written or one is missing.
    pub fn answer(
        &self,
        backend: &'static str,
        beams: &[Beam],
        hits: &[BeamHit],
        weather: &crate::Weather,
        air: &UnresolvedAir,
    ) -> Result<Vec<BeamReturn>, BackendError> {
        let unwritten = hits
            .iter()
            .filter(|h| h.particle_flags == UNWRITTEN)
            .count();
        if hits.len() != beams.len() || unwritten > 0 {
            return Err(BackendError::Device {
                backend,
                message: format!(
                    "the beam query left {unwritten} of {} beams unanswered ({} hits read back): the device did not finish the kernel; cast fewer beams at once",
                    beams.len(),
                    hits.len()
                ),
            });
        }
        let mut returns = Self::returns(
            beams,
            hits,
            self.aperture_radius_m,
            self.extinction_in(weather),
        );
        if let Some(fog) = air.fog_layer {
            for (beam, r) in beams.iter().zip(&mut returns) {
                if let Some(t) = r.target.as_mut() {
                    t.two_way_transmittance *= fog_layer_two_way(beam, t.range_m, &fog);
                }
            }
        }
        let (clouds, drift) = air.cloud_layers;
        if !clouds.is_empty() {
            let map = crate::drawing::clouds::cloud_noise();
            for (beam, r) in beams.iter().zip(&mut returns) {
                if let Some(t) = r.target.as_mut() {
                    let tau = clouds.optical_depth(
                        map,
                        drift,
                        beam.origin_m,
                        beam.direction.normalize_or_zero(),
                        t.range_m,
                    );
                    t.two_way_transmittance *= (-2.0 * tau).exp();
                }
            }
        }
        if self.sample_unresolved {
            let mean_radius_m = air.mean_radius_m();
            for (i, (beam, r)) in beams.iter().zip(&mut returns).enumerate() {
                let limit = r
                    .particle
                    .map_or(f32::INFINITY, |p| p.range_m)
                    .min(r.target.map_or(f32::INFINITY, |t| t.range_m));
                if let Some(s) =
                    air.strike(i as u32, beam, self.aperture_radius_m, mean_radius_m, limit)
                {
                    r.particle = Some(ParticleEcho {
                        range_m: s.range_m,
                        diameter_m: s.diameter_m,
                        kind: s.kind,
                        origin: EchoOrigin::Spectrum,
                        footprint_share: footprint_share(
                            beam,
                            self.aperture_radius_m,
                            s.range_m,
                            s.diameter_m,
                        ),
                    });
                }
            }
        }
        Ok(returns)
    }

    /// The returns of `hits` (one per beam, as [`query_on_cpu`] or the kernel wrote
    /// them), the target attenuated by `extinction_per_m`.
    #[must_use]
    pub fn returns(
        beams: &[Beam],
        hits: &[BeamHit],
        aperture_radius_m: f32,
        extinction_per_m: f32,
    ) -> Vec<BeamReturn> {
        beams
            .iter()
            .zip(hits)
            .map(|(beam, hit)| BeamReturn::of(beam, hit, aperture_radius_m, extinction_per_m))
            .collect()
    }
}

/// What a fog layer lets through out to `range_m` along `beam` and back:
/// `e^(−2B·ℓ)`, `ℓ` the part of the path below the layer's top (fog droplets'
/// extinction efficiency is 2 from the visible to 1.5 µm: size parameters of 20 and
/// more, so one `B` serves every band).
#[must_use]
pub fn fog_layer_two_way(
    beam: &Beam,
    range_m: f32,
    fog: &crate::drawing::fog_layer::FogLayer,
) -> f32 {
    let (s0, s1) = crate::drawing::fog_layer::fog_layer_segment(
        beam.origin_m.y,
        beam.direction.normalize_or_zero().y,
        range_m,
        crate::drawing::fog_layer::FOG_LAYER_BOTTOM_M,
        fog.top_m,
    );
    (-2.0 * fog.extinction_per_m() * (s1 - s0)).exp()
}

/// Where a struck particle comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EchoOrigin {
    /// A simulated particle of the camera volume.
    CameraVolume,
    /// A simulated particle of the world emitter.
    WorldEmitter,
    /// Drawn from the spectrum where the simulation is sparser than the air
    /// ([`unresolved`]).
    Spectrum,
}

/// The share of the beam's footprint at `range_m` a particle of `diameter_m` covers.
#[must_use]
pub fn footprint_share(beam: &Beam, aperture_radius_m: f32, range_m: f32, diameter_m: f32) -> f32 {
    let radius = beam_radius_m(beam, aperture_radius_m, range_m);
    let half = 0.5 * diameter_m;
    if radius > 0.0 {
        (half * half / (radius * radius)).min(1.0)
    } else {
        1.0
    }
}

/// The first particle a beam struck.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleEcho {
    /// Range to its centre, m.
    pub range_m: f32,
    /// Its diameter, m.
    pub diameter_m: f32,
    /// What it is.
    pub kind: ParticleKind,
    /// Where it comes from.
    pub origin: EchoOrigin,
    /// The share of the beam's footprint at its range it covers, `(0, 1]`.
    pub footprint_share: f32,
}

/// The hard target behind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetEcho {
    /// Range, m.
    pub range_m: f32,
    /// `e^(−2σr)`: what the air lets through, out and back.
    pub two_way_transmittance: f32,
    /// What it is made of: the ground map's surface where the beam meets it
    /// ([`label_targets`]; water echoes as [`water_echo`] says).
    pub surface: precip_cover::Surface,
}

/// Labels each target of `returns` (one per beam of `beams`) with the surface of
/// `ground` where its beam meets it: what the backends do after
/// [`BeamQuery::answer`].
pub fn label_targets(returns: &mut [BeamReturn], beams: &[Beam], ground: &GroundMap) {
    for (r, beam) in returns.iter_mut().zip(beams) {
        if let Some(t) = r.target.as_mut() {
            let at = beam.origin_m + beam.direction.normalize_or_zero() * t.range_m;
            t.surface = ground.surface_at(Vec2::new(at.x, at.z));
        }
    }
}

/// One beam's answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamReturn {
    /// The first particle struck before the target, if any.
    pub particle: Option<ParticleEcho>,
    /// The hard target within range, if any.
    pub target: Option<TargetEcho>,
}

impl BeamReturn {
    fn of(beam: &Beam, hit: &BeamHit, aperture_radius_m: f32, extinction_per_m: f32) -> Self {
        let particle = (hit.particle_flags != NO_PARTICLE).then(|| {
            let probe = Particle {
                flags: hit.particle_flags,
                ..Particle::zeroed()
            };
            ParticleEcho {
                range_m: hit.particle_range_m,
                diameter_m: hit.particle_diameter_m,
                kind: probe.kind(),
                origin: match probe.source() {
                    ParticleSource::CameraVolume => EchoOrigin::CameraVolume,
                    ParticleSource::WorldEmitter => EchoOrigin::WorldEmitter,
                },
                footprint_share: footprint_share(
                    beam,
                    aperture_radius_m,
                    hit.particle_range_m,
                    hit.particle_diameter_m,
                ),
            }
        });
        let target = (hit.target_range_m >= 0.0).then(|| TargetEcho {
            range_m: hit.target_range_m,
            two_way_transmittance: (-2.0 * extinction_per_m * hit.target_range_m).exp(),
            surface: precip_cover::Surface::default(),
        });
        Self { particle, target }
    }

    /// Where the echo a sensor reports lies: the particle's if its echo is the
    /// stronger, else the target's (Hahner et al.'s choice between the two peaks),
    /// with reflectances `particle_reflectance` and `target_reflectance` (the target
    /// seen through the particle's footprint share and the air's transmittance); both
    /// echoes fall off as `1/r²`.
    #[must_use]
    pub fn strongest_echo_m(
        &self,
        particle_reflectance: f32,
        target_reflectance: f32,
    ) -> Option<(f32, bool)> {
        let from_particle = self.particle.map(|p| {
            (
                particle_reflectance * p.footprint_share / p.range_m.max(0.1).powi(2),
                p.range_m,
            )
        });
        let blocked = self.particle.map_or(0.0, |p| p.footprint_share);
        let from_target = self.target.map(|t| {
            (
                target_reflectance * t.two_way_transmittance * (1.0 - blocked)
                    / t.range_m.max(0.1).powi(2),
                t.range_m,
            )
        });
        match (from_particle, from_target) {
            (Some(p), Some(t)) if p.0 >= t.0 => Some((p.1, true)),
            (Some(_), Some(t)) | (None, Some(t)) => Some((t.1, false)),
            (Some(p), None) => Some((p.1, true)),
            (None, None) => None,
        }
    }
}

/// The hard target's march step for `ground`: half its smallest texel side, m.
#[must_use]
pub fn march_step_m(ground: &GroundMap) -> f32 {
    let texel = ground.frame.size_m / ground.frame.texels.as_vec2();
    0.5 * texel.min_element()
}

/// The beam's radius at `range_m`, m: `aperture + range·tan(divergence/2)`.
///
/// WGSL twin: `beam_radius_m`.
#[must_use]
pub fn beam_radius_m(beam: &Beam, aperture_radius_m: f32, range_m: f32) -> f32 {
    aperture_radius_m + range_m * (0.5 * beam.divergence_rad).tan()
}

/// The range along `beam` (its direction normalised) at which it strikes a particle
/// of `diameter_m` centred at `centre_m`, or `None` (module docs).
///
/// WGSL twin: `beam_strike_range_m`.
#[must_use]
pub fn beam_strike_range_m(
    beam: &Beam,
    aperture_radius_m: f32,
    centre_m: Vec3,
    diameter_m: f32,
) -> Option<f32> {
    let relative = centre_m - beam.origin_m;
    let t = relative.dot(beam.direction);
    if !(t > 0.0 && t <= beam.max_range_m) {
        return None;
    }
    let off_axis = relative - beam.direction * t;
    let reach = 0.5 * diameter_m + beam_radius_m(beam, aperture_radius_m, t);
    (off_axis.dot(off_axis) <= reach * reach).then_some(t)
}

/// Whether `point_m` is at or under the ground map's surface.
fn under_ground(ground: &GroundMap, point_m: Vec3) -> bool {
    ground
        .height_at(Vec2::new(point_m.x, point_m.z))
        .is_some_and(|h| point_m.y <= h)
}

/// The range at which `beam` (its direction normalised) meets the ground map's
/// surface, marching in `march_step_m` (longer where the range needs more than
/// [`MAX_MARCH_STEPS`]) and refining by bisection; `None` within its range.
///
/// WGSL twin: `hard_target_range_m`.
#[must_use]
pub fn hard_target_range_m(beam: &Beam, ground: &GroundMap, march_step_m: f32) -> Option<f32> {
    if under_ground(ground, beam.origin_m) {
        return Some(0.0);
    }
    let step = march_step_m.max(beam.max_range_m / MAX_MARCH_STEPS as f32);
    let steps = (beam.max_range_m / step).ceil() as u32;
    let mut before = 0.0f32;
    for i in 1..=steps {
        let t = (i as f32 * step).min(beam.max_range_m);
        if under_ground(ground, beam.origin_m + beam.direction * t) {
            let (mut above, mut below) = (before, t);
            for _ in 0..BISECTIONS {
                let middle = 0.5 * (above + below);
                if under_ground(ground, beam.origin_m + beam.direction * middle) {
                    below = middle;
                } else {
                    above = middle;
                }
            }
            return Some(below);
        }
        before = t;
    }
    None
}

/// Slack of the group bound's angle, rad (GPU `acos` is not exact).
pub const GROUP_ANGLE_SLACK_RAD: f32 = 1.0e-3;
/// Slack of the group bound's distances: this plus [`GROUP_RELATIVE_SLACK`] of the
/// distance, m.
pub const GROUP_DISTANCE_SLACK_M: f32 = 1.0e-3;
/// Relative slack of the group bound's distances.
pub const GROUP_RELATIVE_SLACK: f32 = 1.0e-4;

/// A cone enclosing everything a group of beams can strike ([`beam_group_bound`]).
///
/// WGSL twin: `BeamGroupBound`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamGroupBound {
    /// The centre of the beams' origins, m.
    pub apex_m: Vec3,
    /// Their mean direction (normalised).
    pub axis: Vec3,
    /// The widest angle of a beam from the axis plus its half divergence, rad.
    pub half_angle_rad: f32,
    /// How far a struck particle's centre may lie outside the cone: the origins'
    /// spread plus the aperture, m (add the particle's radius).
    pub pad_m: f32,
    /// How far from the apex a struck particle's centre may lie, m (add the pad and
    /// the particle's radius).
    pub reach_m: f32,
}

/// The bound of `beams` (validated, at least one) of `aperture_radius_m`.
///
/// WGSL twin: `beam_group_bound` (over the workgroup's 64 beams).
#[must_use]
pub fn beam_group_bound(beams: &[Beam], aperture_radius_m: f32) -> BeamGroupBound {
    let n = beams.len().max(1) as f32;
    let apex = beams.iter().map(|b| b.origin_m).sum::<Vec3>() / n;
    let mean = beams.iter().map(|b| b.direction).sum::<Vec3>();
    let axis = if mean.length_squared() > 1.0e-6 {
        mean.normalize()
    } else {
        beams.first().map_or(Vec3::Y, |b| b.direction)
    };
    let (mut half_angle, mut spread, mut reach) = (0.0f32, 0.0f32, 0.0f32);
    for b in beams {
        let angle = b.direction.dot(axis).clamp(-1.0, 1.0).acos() + 0.5 * b.divergence_rad;
        half_angle = half_angle.max(angle);
        let offset = (b.origin_m - apex).length();
        spread = spread.max(offset);
        reach = reach.max(offset + b.max_range_m * (1.0 + (0.5 * b.divergence_rad).tan()));
    }
    BeamGroupBound {
        apex_m: apex,
        axis,
        half_angle_rad: half_angle + GROUP_ANGLE_SLACK_RAD,
        pad_m: spread + aperture_radius_m,
        reach_m: reach,
    }
}

/// Whether a particle of `diameter_m` at `centre_m` may be struck by a beam of the
/// group `bound` encloses: within the pad of the cone and the reach of the apex.
///
/// WGSL twin: `group_may_strike`.
#[must_use]
pub fn group_may_strike(bound: &BeamGroupBound, centre_m: Vec3, diameter_m: f32) -> bool {
    let v = centre_m - bound.apex_m;
    let distance = v.length();
    let pad =
        bound.pad_m + 0.5 * diameter_m + GROUP_DISTANCE_SLACK_M + GROUP_RELATIVE_SLACK * distance;
    if distance > bound.reach_m + pad {
        return false;
    }
    if distance <= pad || bound.half_angle_rad >= std::f32::consts::FRAC_PI_2 {
        return true;
    }
    let angle = (v.dot(bound.axis) / distance).clamp(-1.0, 1.0).acos();
    let outside = angle - bound.half_angle_rad;
    if outside <= 0.0 {
        return true;
    }
    if outside >= std::f32::consts::FRAC_PI_2 {
        return distance <= pad;
    }
    distance * outside.sin() <= pad
}

/// The reference answer: each validated beam against every particle in the air
/// (`params`' range of `particles`) and the ground.
#[must_use]
pub fn query_on_cpu(
    beams: &[Beam],
    params: &BeamParams,
    particles: &[Particle],
    ground: &GroundMap,
) -> Vec<BeamHit> {
    beams
        .par_iter()
        .map(|beam| {
            let target = hard_target_range_m(beam, ground, params.march_step_m);
            let mut hit = BeamHit {
                particle_range_m: 0.0,
                particle_diameter_m: 0.0,
                particle_flags: NO_PARTICLE,
                target_range_m: target.unwrap_or(-1.0),
            };
            let end = (params.particle_end as usize).min(particles.len());
            let start = (params.particle_first as usize).min(end);
            for p in &particles[start..end] {
                let Some(t) =
                    beam_strike_range_m(beam, params.aperture_radius_m, p.position_m, p.diameter_m)
                else {
                    continue;
                };
                let nearer = hit.particle_flags == NO_PARTICLE || t < hit.particle_range_m;
                if nearer && target.is_none_or(|target| t < target) {
                    hit.particle_range_m = t;
                    hit.particle_diameter_m = p.diameter_m;
                    hit.particle_flags = p.flags;
                }
            }
            hit
        })
        .collect()
}

#[cfg(test)]
mod tests;
