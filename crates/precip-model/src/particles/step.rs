//! One particle's step: the seeds' kinematics with physical acceleration, rotation,
//! landing and deposit, re-birth, and the camera volume's wrap.
//! WGSL twin: the `step_particles` kernel in `shaders/step_particles.wgsl`.
//!
//! ## Order within a step
//!
//! 1. Wind sampled at the step's predicted midpoint `P + ½·v·dt` (the old velocity
//!    carries it there; `P` itself where that lies under the ground map: a flake
//!    about to strike strikes with the air it is in) and the old time, turned to
//!    follow the ground near it
//!    ([`crate::physics::terrain_flow`]); velocity by [`drag_velocity`]; position
//!    `P' = P + ½(v + v')·dt`; age `t' = t + dt`; rotation advanced. The midpoint,
//!    not the old position: where the flow turns sharply (over a ridge, at a
//!    wall's top) a step of 0.5–1 m with the wind of its start carried flakes off
//!    their streamline, all one way (up over a crest), and a shadow of 20 m
//!    followed; from the midpoint the error changes sign with where in the step
//!    the turn lies (`tests/snowfall_footprint.rs`, steps of 1/50–1/20 s).
//! 2. World emitter particles gather water, `R·A/n` per second (R the intensity,
//!    A the emitter's ground area, n its particle count): over a long run the water
//!    landed equals `R·A·time` exactly, whatever the particles' speeds (each particle
//!    stands for 1/n of the emitter's flux for as long as it lives). Sand and dust
//!    the wind lifts from the ground ([`crate::physics::grain`], particles `[lift_from,
//!    world_count)`) gather the lifted flux over their count the same way, land in
//!    the cover's grains channel, and are re-born when they leave the map.
//!    If `P'` is at or below the ground map, the water is added to the cover texel
//!    there (fixed point, atomic) and the particle is re-born. A particle that was
//!    already below that surface at `P` came in from the side (blown against a wall
//!    or under an eave): it deposits at `P`, the wall's foot on the side it came from,
//!    not on the roof above — unless it is snow moving faster than the snow's
//!    transport threshold (`wall_rebound_speed_mps`, Li & Pomeroy's 10 m wind): a
//!    strong wind does not let flakes settle against a windward wall (its down-draft
//!    and the horseshoe vortex at the foot scour there), so the flake goes back to `P`
//!    and rises along the wall at its horizontal speed, and the flow carries it over. Below the lowest ground
//!    off the map, or at `t' ≥ t_max`, it is re-born without a deposit. A raindrop
//!    that strikes hard enough throws up a splash droplet in its place instead of
//!    being re-born ([`crate::physics::splash`]; on the cover grid only).
//! 3. Camera volume particles wrap through the box's sides and top; one that falls out
//!    of the bottom or reaches the ground is re-born just under the top (spread over
//!    one step's fall, so the flux in is continuous), at the same x, z; a raindrop
//!    that strikes the ground hard enough splashes first. Above the top they wrap
//!    by whole box heights, so one left far above (resting while the camera flew
//!    down) comes back into the box in one step.
//!
//! ## Resting particles
//!
//! A particle that nobody sees and that carries nothing is not stepped at all: the
//! camera volume's particles past the ones drawn (`m < 1`: it draws its first
//! `⌈n_sim·V⌉`, [`crate::drawing::multiplicity`]; at 0 mm/h none), and, while the
//! weather gives the sky nothing to carry or draw (0 mm/h, no grains from the sky),
//! the world emitter's sky-born particles `[0, lift_from)`. What is left is one
//! range, `[step_first, step_end)`, and a step runs over it alone: a dispatch of
//! its length, a loop over it on the CPU. Resting particles keep their state and
//! wake where they were when the weather wants them again. What lands is
//! unchanged: a resting world particle gathers no water, and the camera volume's
//! particles never deposit. The beams and the optics read the range too: what
//! rests is not in the air.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec2, Vec3};
use precip_cover::{CoverTexel, DepositBuffer, GridFrame};
use precip_wind::WindVolume;

use crate::particles::birth::{birth_in_camera_volume, birth_in_world, is_lifted};
use crate::particles::ground::GroundMap;
use crate::particles::kind::SpeciesParams;
use crate::particles::particle::{Particle, ParticleSource, flags};
use crate::particles::rng::{draw, particle_key, random_unit};
use crate::physics::drag::drag_velocity;
use crate::physics::drifting_snow::CoverView;
use crate::physics::rotation::advance_rotation;
use crate::physics::splash::{splash_droplet, splashes};
use crate::physics::terrain_flow::terrain_following_wind;

/// Everything a step needs besides the buffers: the GPU's uniform block.
///
/// WGSL twin: `StepParams` in `shaders/layout.wgsl` (`tests/shaders.rs` in
/// precip-gpu checks every offset; the species block at its end grows with the
/// kinds' table).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct StepParams {
    /// World emitter: OCS → world.
    pub emitter_model: Mat4,
    /// World emitter: W, H, m.
    pub emitter_size_m: Vec2,
    /// World emitter: t_max, s.
    pub emitter_life_time_s: f32,
    /// World emitter: k_v, m/s.
    pub emitter_velocity_spread_mps: f32,
    /// World emitter: v0, m/s.
    pub emitter_velocity_mps: Vec3,
    /// Water each world particle gathers per second, kg/s.
    pub water_per_particle_kg_per_s: f32,
    /// Camera volume centre, m.
    pub camera_centre_m: Vec3,
    /// Step length, s (≤ [`crate::physics::drag::MAX_SUBSTEP_S`]).
    pub dt_s: f32,
    /// Camera volume half size, m.
    pub camera_half_extent_m: Vec3,
    /// Simulation time at the start of the step, s.
    pub time_s: f32,
    /// Mean wind, m/s.
    pub mean_wind_mps: Vec3,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// World emitter (k_rot rad, k_vel rad/s).
    pub world_rotation: Vec2,
    /// Camera volume (k_rot rad, k_vel rad/s).
    pub camera_rotation: Vec2,
    /// Seed of every random draw.
    pub seed: u32,
    /// Particles `[0, world_count)` belong to the world emitter.
    pub world_count: u32,
    /// All particles.
    pub particle_count: u32,
    /// 1 when the snow is wet.
    pub snow_is_wet: u32,
    /// Cover mm per kg landed in one cover texel: cover time scale / texel area.
    pub deposit_scale_mm_per_kg: f32,
    /// Below this height a particle off the ground map has left the scene, m.
    pub ground_floor_m: f32,
    /// World particles `[lift_from, world_count)` are lifted by the wind from
    /// erodible ground ([`crate::physics::grain`]); `world_count`: none are.
    pub lift_from: u32,
    /// Grains each lifted particle gathers per second, kg/s.
    pub lift_per_particle_kg_per_s: f32,
    /// Friction velocity u* of the wind over the erodible ground, m/s.
    pub friction_velocity_mps: f32,
    /// Top of the layer suspended grains are born in, m above the ground.
    pub lift_layer_top_m: f32,
    /// 1: the lifted grains are suspended (dust, born through the layer by the
    /// Rouse profile); 0: they saltate (sand, launched from the surface).
    pub grain_suspended: u32,
    /// Above this height the ground does not turn the wind, m
    /// ([`crate::physics::terrain_flow::flow_ceiling_m`]).
    pub flow_ceiling_m: f32,
    /// Lifted grains are born in the rectangle from this corner (min x, min z), m…
    pub lift_area_min_m: Vec2,
    /// … to this one (max x, max z), m: the erodible texels' bounds.
    pub lift_area_max_m: Vec2,
    /// A snowflake blown against a wall faster than this is carried up along it
    /// instead of settling at its foot, m/s (the snow's transport threshold).
    pub wall_rebound_speed_mps: f32,
    /// The first particle a step moves (module docs, "Resting particles"): 0, or
    /// `lift_from` while the sky-born world particles rest.
    pub step_first: u32,
    /// The end of the particles a step moves: the camera volume's drawn ones'
    /// (`PoolDrawing::camera_drawn_end`).
    pub step_end: u32,
    /// Unused (`0`).
    pub reserved2: u32,
    /// What the weather's kinds need to draw a newborn's species (the particle
    /// kinds' table, [`crate::particles::kind`]); last, 16-byte aligned.
    pub species: SpeciesParams,
}
const _: () = assert!(size_of::<StepParams>().is_multiple_of(16));

impl StepParams {
    /// This block for one sub-step: the per-sub-step fields set, the rest (weather,
    /// emitter, grids; computed once per configure or weather change) kept.
    #[must_use]
    pub fn at(self, camera_centre_m: Vec3, dt_s: f32, time_s: f32) -> Self {
        Self {
            camera_centre_m,
            dt_s,
            time_s,
            ..self
        }
    }
}

/// The buffers and fields a step reads and the deposit buffer it adds to.
#[derive(Debug, Clone, Copy)]
pub struct StepInputs<'a> {
    /// The uniform block.
    pub params: &'a StepParams,
    /// The wind.
    pub wind: &'a WindVolume,
    /// The ground.
    pub ground: &'a GroundMap,
    /// The cover grid's frame (deposit texels).
    pub cover_frame: &'a GridFrame,
    /// The cover's texels as the step starts (where snow is blowing, for drifting
    /// snow's births; empty: none).
    pub cover_texels: &'a [CoverTexel],
    /// Landed water, fixed point.
    pub deposits: &'a DepositBuffer,
}

impl StepInputs<'_> {
    /// The cover as births read it.
    #[must_use]
    pub fn cover(&self) -> CoverView<'_> {
        CoverView {
            frame: self.cover_frame,
            texels: self.cover_texels,
        }
    }
}

/// What happened to a particle in a step (for tests and statistics).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepEvent {
    /// It moved.
    Moved,
    /// It landed and deposited its water, then was re-born.
    Landed,
    /// It struck a surface (depositing its water, from the world emitter) and threw
    /// up a splash droplet in its place ([`crate::physics::splash`]).
    Splashed,
    /// It was re-born without a deposit (t_max, left the scene, left the camera box).
    Reborn,
}

/// The particles a step moves, `[step_first, step_end)` (module docs, "Resting
/// particles").
#[must_use]
pub fn stepped_particles(params: &StepParams) -> std::ops::Range<u32> {
    params.step_first..params.step_end.max(params.step_first)
}

/// Advances particle `index` by one step (see the module docs); the step calls it
/// for [`stepped_particles`] only.
#[must_use]
pub fn step_particle(
    index: u32,
    particle: &Particle,
    inputs: &StepInputs<'_>,
) -> (Particle, StepEvent) {
    let params = inputs.params;
    let dt = params.dt_s;
    let probe = wind_probe_m(particle, inputs.ground, params);
    let wind = terrain_following_wind(
        inputs.wind.velocity_mps(probe, params.time_s),
        probe,
        inputs.ground,
        params.flow_ceiling_m,
    );
    let velocity = drag_velocity(particle.velocity_mps, wind, particle.terminal_speed_mps, dt);
    let position = particle.position_m + (particle.velocity_mps + velocity) * (0.5 * dt);

    let source = particle.source();
    let rotation = match source {
        ParticleSource::WorldEmitter => params.world_rotation,
        ParticleSource::CameraVolume => params.camera_rotation,
    };
    let mut rotation_rad = particle.rotation_rad;
    let mut bits = particle.flags & !(0b111 * flags::ROTATION_INCREASING_X);
    for axis in 0..3 {
        let (m, increasing) = advance_rotation(
            particle.rotation_rad[axis],
            particle.rotation_increasing(axis as u32),
            rotation.x,
            rotation.y,
            dt,
        );
        rotation_rad[axis] = m;
        if increasing {
            bits |= flags::ROTATION_INCREASING_X << axis;
        }
    }
    let mut next = Particle {
        position_m: position,
        age_s: particle.age_s + dt,
        velocity_mps: velocity,
        rotation_rad,
        flags: bits,
        ..*particle
    };

    match source {
        ParticleSource::WorldEmitter => {
            let lifted = is_lifted(index, params);
            next.water_kg += if lifted {
                params.lift_per_particle_kg_per_s
            } else {
                params.water_per_particle_kg_per_s
            } * dt;
            let xz = Vec2::new(position.x, position.z);
            match inputs.ground.height_at(xz) {
                Some(ground_m)
                    if position.y <= ground_m
                        && rebounds_off_a_wall(particle, &next, ground_m, params) =>
                {
                    // Carried up along the wall from where it was (step 2).
                    let speed = Vec2::new(next.velocity_mps.x, next.velocity_mps.z).length();
                    next.position_m = particle.position_m;
                    next.velocity_mps = Vec3::new(0.0, speed.max(next.velocity_mps.y), 0.0);
                }
                Some(ground_m) if position.y <= ground_m => {
                    let channel = next.kind().deposit_channel();
                    let water_mm = next.water_kg * params.deposit_scale_mm_per_kg;
                    let from_side = particle.position_m.y < ground_m;
                    let at = if from_side {
                        Vec2::new(particle.position_m.x, particle.position_m.z)
                    } else {
                        xz
                    };
                    // Water landing off the cover grid fell outside the scene: not kept.
                    let kept = inputs
                        .deposits
                        .add_at(inputs.cover_frame, at, channel, water_mm);
                    if kept && splashes(&next) {
                        let surface_m = Vec3::new(at.x, ground_m, at.y);
                        return (
                            splash_droplet(params.seed, index, &next, surface_m),
                            StepEvent::Splashed,
                        );
                    }
                    return (
                        birth_in_world(
                            index,
                            particle.generation.wrapping_add(1),
                            params,
                            inputs.ground,
                            &inputs.cover(),
                        ),
                        StepEvent::Landed,
                    );
                }
                // Below the floor off the map, or a lifted grain blown off it (it
                // started on the map: what leaves it is gone).
                None if position.y < params.ground_floor_m || lifted => {
                    return (
                        birth_in_world(
                            index,
                            particle.generation.wrapping_add(1),
                            params,
                            inputs.ground,
                            &inputs.cover(),
                        ),
                        StepEvent::Reborn,
                    );
                }
                _ => {}
            }
            if next.age_s >= params.emitter_life_time_s {
                return (
                    birth_in_world(
                        index,
                        particle.generation.wrapping_add(1),
                        params,
                        inputs.ground,
                        &inputs.cover(),
                    ),
                    StepEvent::Reborn,
                );
            }
            (next, StepEvent::Moved)
        }
        ParticleSource::CameraVolume => {
            step_in_camera_volume(index, particle.generation, next, inputs)
        }
    }
}

/// Where a step reads the particle's wind (module docs, step 1): the step's
/// predicted midpoint `P + ½·v·dt`, or `P` itself where the midpoint lies under the
/// ground map (a flake about to strike strikes with the air it is in).
fn wind_probe_m(particle: &Particle, ground: &GroundMap, params: &StepParams) -> Vec3 {
    let midpoint = particle.position_m + particle.velocity_mps * (0.5 * params.dt_s);
    if midpoint.y >= params.flow_ceiling_m {
        return midpoint;
    }
    match ground.height_at(Vec2::new(midpoint.x, midpoint.z)) {
        Some(ground_m) if midpoint.y < ground_m => particle.position_m,
        _ => midpoint,
    }
}

/// Whether world particle `next` (at `particle` before the step), below the ground
/// `ground_m` where it moved, struck a wall and rebounds: snow that came in from
/// the side faster than [`StepParams::wall_rebound_speed_mps`].
fn rebounds_off_a_wall(
    particle: &Particle,
    next: &Particle,
    ground_m: f32,
    params: &StepParams,
) -> bool {
    let from_side = particle.position_m.y < ground_m;
    let speed = Vec2::new(next.velocity_mps.x, next.velocity_mps.z).length();
    from_side && next.kind().is_snow() && speed > params.wall_rebound_speed_mps
}

/// Wraps `x` into `[−h, h)`.
fn wrap_centred(x: f32, h: f32) -> f32 {
    x - 2.0 * h * ((x + h) / (2.0 * h)).floor()
}

/// The camera volume's wrap and re-birth (step 3 of the module docs).
fn step_in_camera_volume(
    index: u32,
    generation: u32,
    mut next: Particle,
    inputs: &StepInputs<'_>,
) -> (Particle, StepEvent) {
    let params = inputs.params;
    let centre = params.camera_centre_m;
    let half = params.camera_half_extent_m;
    let mut local = next.position_m - centre;
    local.x = wrap_centred(local.x, half.x);
    local.z = wrap_centred(local.z, half.z);
    if local.y > half.y {
        local.y = wrap_centred(local.y, half.y);
    }
    let position = centre + local;
    let xz = Vec2::new(position.x, position.z);
    let ground_m = inputs.ground.height_at(xz);
    let grounded = ground_m.is_some_and(|g| position.y <= g);
    if let Some(g) = ground_m.filter(|_| grounded && splashes(&next)) {
        let surface_m = Vec3::new(position.x, g, position.z);
        return (
            splash_droplet(params.seed, index, &next, surface_m),
            StepEvent::Splashed,
        );
    }
    if local.y < -half.y || grounded {
        let new_generation = generation.wrapping_add(1);
        let key = particle_key(params.seed, index, new_generation);
        let mut born = birth_in_camera_volume(index, new_generation, params, position);
        born.position_m.y = centre.y + half.y
            - random_unit(key, draw::PREWARM) * born.terminal_speed_mps * params.dt_s;
        return (born, StepEvent::Reborn);
    }
    next.position_m = position;
    (next, StepEvent::Moved)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_is_pinned() {
        assert_eq!(std::mem::offset_of!(StepParams, emitter_size_m), 64);
        assert_eq!(std::mem::offset_of!(StepParams, emitter_velocity_mps), 80);
        assert_eq!(std::mem::offset_of!(StepParams, camera_centre_m), 96);
        assert_eq!(std::mem::offset_of!(StepParams, camera_half_extent_m), 112);
        assert_eq!(std::mem::offset_of!(StepParams, mean_wind_mps), 128);
        assert_eq!(std::mem::offset_of!(StepParams, world_rotation), 144);
        assert_eq!(std::mem::offset_of!(StepParams, air_temperature_c), 140);
        assert_eq!(std::mem::offset_of!(StepParams, seed), 160);
        assert_eq!(std::mem::offset_of!(StepParams, snow_is_wet), 172);
        assert_eq!(std::mem::offset_of!(StepParams, ground_floor_m), 180);
        assert_eq!(std::mem::offset_of!(StepParams, flow_ceiling_m), 204);
        assert_eq!(std::mem::offset_of!(StepParams, lift_area_max_m), 216);
        assert_eq!(
            std::mem::offset_of!(StepParams, wall_rebound_speed_mps),
            224
        );
        assert_eq!(std::mem::offset_of!(StepParams, species), 240);
    }

    #[test]
    fn wrap_is_centred_and_periodic() {
        assert!((wrap_centred(11.0, 10.0) + 9.0).abs() < 1e-5);
        assert!((wrap_centred(-10.5, 10.0) - 9.5).abs() < 1e-5);
        assert!((wrap_centred(3.0, 10.0) - 3.0).abs() < 1e-6);
        assert!((wrap_centred(10.0, 10.0) + 10.0).abs() < 1e-6);
    }
}
