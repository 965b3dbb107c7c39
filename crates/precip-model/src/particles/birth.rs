//! Birth and re-birth of particles (docs/model.md §1): every property drawn from the
//! counter-based RNG, keyed by (seed, index, generation). WGSL twin: `shaders/birth.wgsl`.

use glam::{Vec2, Vec3};

use crate::particles::ground::GroundMap;
use crate::particles::kind::{draw_species, slowest_terminal_speed_mps, snow_kind};
use crate::particles::particle::{Particle, ParticleKind, ParticleSource, pack_flags, rotation0};
use crate::particles::rng::{draw, particle_key, random_unit};
use crate::particles::step::StepParams;
use crate::physics::drifting_snow::{
    CoverView, DRIFTING_SNOW_DIAMETER_M, DRIFTING_SNOW_REFERENCE_FLUX, ICE_DENSITY_KG_M3,
    PARKED_BELOW_FLOOR_M,
};
use crate::physics::grain::{
    LAUNCH_HEIGHT_M, LAUNCH_SPEED_PER_FRICTION_VELOCITY, grain_settling_speed_mps, rouse_height_m,
    rouse_number,
};
use crate::physics::snowflake::snowflake_diameter_m;

/// `f − ½` for draw `d`.
fn centred(key: u32, d: u32) -> f32 {
    random_unit(key, d) - 0.5
}

/// `(f − ½, f − ½, f − ½)` from draws `d, d+1, d+2`: the seeds' `V_rand`.
fn centred3(key: u32, d: u32) -> Vec3 {
    Vec3::new(centred(key, d), centred(key, d + 1), centred(key, d + 2))
}

/// Rotation at birth: `r0 = 2π·(f, f, f)` (packed, [`rotation0`]), `r = 4·k_rot·V_rand`
/// kept as magnitude `|r|` plus direction (increasing where the drawn `r ≥ 0`).
#[must_use]
pub fn draw_rotation(key: u32, amplitude_rad: f32) -> (u32, Vec3, [bool; 3]) {
    let r0 = rotation0::pack(Vec3::new(
        random_unit(key, draw::ROTATION0_X),
        random_unit(key, draw::ROTATION0_X + 1),
        random_unit(key, draw::ROTATION0_X + 2),
    ));
    let r = centred3(key, draw::ROTATION_X) * (4.0 * amplitude_rad);
    (r0, r.abs(), [r.x >= 0.0, r.y >= 0.0, r.z >= 0.0])
}

/// A newborn particle of `kind`, `diameter` and `speed` at `position_m` moving at
/// `velocity_mps`, with its drawn rotation: age 0, no water yet.
#[must_use]
fn newborn(
    position_m: Vec3,
    velocity_mps: Vec3,
    (kind, diameter, speed): (ParticleKind, f32, f32),
    (r0, r, increasing): (u32, Vec3, [bool; 3]),
    generation: u32,
    source: ParticleSource,
) -> Particle {
    Particle {
        position_m,
        age_s: 0.0,
        velocity_mps,
        terminal_speed_mps: speed,
        rotation_rad: r,
        flags: pack_flags(kind, source, increasing),
        diameter_m: diameter,
        water_kg: 0.0,
        generation,
        rotation0: r0,
    }
}

/// A newborn world particle (emitter or lifted) with the world's drawn rotation.
fn world_newborn(
    position_m: Vec3,
    velocity_mps: Vec3,
    species: (ParticleKind, f32, f32),
    (key, generation): (u32, u32),
    params: &StepParams,
) -> Particle {
    newborn(
        position_m,
        velocity_mps,
        species,
        draw_rotation(key, params.world_rotation.x),
        generation,
        ParticleSource::WorldEmitter,
    )
}

/// Tries of [`stationary_generation`] before the last is kept.
pub const STATIONARY_TRIES: u32 = 16;

/// The generation a camera-volume particle starts in, so the volume starts as it
/// will stay: births draw species as they fall through a plane (the flux), but the
/// air holds each in proportion to the time it takes to cross, `∝ 1/v` (a length-
/// biased renewal process). Generation `g` is kept with probability `v_slowest / v_g`
/// (`u·v_g < v_slowest`), the first kept of [`STATIONARY_TRIES`], else the last.
/// Started with the births' mix instead, the volume fills top-down with a denser
/// band of newborns for the `height / v_slowest` seconds the mix takes to settle
/// (`⟨v⟩·⟨1/v⟩` ≈ 1.10 times denser for dry snow).
///
/// WGSL twin: `stationary_generation` in `shaders/birth.wgsl`.
#[must_use]
pub fn stationary_generation(index: u32, params: &StepParams) -> u32 {
    let slowest = slowest_terminal_speed_mps(params);
    for generation in 0..STATIONARY_TRIES {
        let key = particle_key(params.seed, index, generation);
        let (_, _, speed) = draw_species(key, params);
        if random_unit(key, draw::STATIONARY) * speed < slowest {
            return generation;
        }
    }
    STATIONARY_TRIES - 1
}

/// How far the mean wind carries a particle falling at `terminal_speed_mps` from
/// `height_m` down to `ground_m`: `Δ = u_h·(y − y_g)/V_t` (horizontal).
///
/// WGSL twin: `fall_drift_m` in `shaders/birth.wgsl`.
#[must_use]
pub fn fall_drift_m(
    height_m: f32,
    ground_m: f32,
    terminal_speed_mps: f32,
    params: &StepParams,
) -> Vec3 {
    let fall_s = (height_m - ground_m).max(0.0) / terminal_speed_mps.max(1.0e-3);
    Vec3::new(params.mean_wind_mps.x, 0.0, params.mean_wind_mps.z) * fall_s
}

/// The ground under `at_m`, the map's floor off it, m.
fn ground_or_floor_m(ground: &GroundMap, at_m: Vec3, params: &StepParams) -> f32 {
    ground
        .height_at(Vec2::new(at_m.x, at_m.z))
        .unwrap_or(params.ground_floor_m)
}

/// The point on the emitter a particle of `key` is aimed at (its OCS draw).
fn emitter_aim_m(key: u32, params: &StepParams) -> Vec3 {
    params.emitter_model.transform_point3(Vec3::new(
        params.emitter_size_m.x * centred(key, draw::POSITION_U),
        params.emitter_size_m.y * centred(key, draw::POSITION_V),
        0.0,
    ))
}

/// Tries of a lifted grain for erodible ground before the last point is kept.
pub const LIFT_TRIES: u32 = 4;

/// Whether world particle `index` is one the wind lifts from the ground.
#[must_use]
pub const fn is_lifted(index: u32, params: &StepParams) -> bool {
    index >= params.lift_from && index < params.world_count
}

/// A grain the wind lifts from erodible ground ([`crate::physics::grain`]).
///
/// Where: a point drawn in the rectangle around the map's erodible texels
/// (`lift_area_min_m … lift_area_max_m`), kept with probability its erodibility, up
/// to [`LIFT_TRIES`] tries (the last is kept). How: sand leaves the surface at
/// [`LAUNCH_HEIGHT_M`] straight up at [`launch_speed_mps`]; dust starts at a height of the
/// Rouse profile through the layer up to `lift_layer_top_m`, moving with the mean
/// wind at its fall speed.
///
/// In snow weather the lifted particles are drifting snow instead
/// ([`birth_drifting_snow`]).
#[must_use]
pub fn birth_lifted(
    index: u32,
    generation: u32,
    params: &StepParams,
    ground: &GroundMap,
    cover: &CoverView<'_>,
) -> Particle {
    let key = particle_key(params.seed, index, generation);
    if params.species.grain_diameter_m <= 0.0 {
        return birth_drifting_snow(key, generation, params, ground, cover);
    }
    let species = draw_species(key, params);
    let (at, _) = lift_point(key, params, |at| ground.erodibility_at(at));
    let ground_m = ground.height_at(at).unwrap_or(params.ground_floor_m);
    let (height_m, velocity) = if params.grain_suspended != 0 {
        let rouse = rouse_number(species.2, params.friction_velocity_mps);
        (
            rouse_height_m(
                rouse,
                params.lift_layer_top_m,
                random_unit(key, draw::LIFT_HEIGHT),
            ),
            params.mean_wind_mps - Vec3::Y * species.2,
        )
    } else {
        (LAUNCH_HEIGHT_M, Vec3::Y * launch_speed_mps(key, params))
    };
    world_newborn(
        Vec3::new(at.x, ground_m + height_m, at.y),
        velocity,
        species,
        (key, generation),
        params,
    )
}

/// A point in the lift area (`lift_area_min_m … lift_area_max_m`) kept with
/// probability `weight(point)`, up to [`LIFT_TRIES`] tries; the last when none is
/// kept (and `false`).
fn lift_point(key: u32, params: &StepParams, weight: impl Fn(Vec2) -> f32) -> (Vec2, bool) {
    let span = params.lift_area_max_m - params.lift_area_min_m;
    let mut at = params.lift_area_min_m;
    for t in 0..LIFT_TRIES {
        let d = draw::LIFT + 3 * t;
        at =
            params.lift_area_min_m + span * Vec2::new(random_unit(key, d), random_unit(key, d + 1));
        if random_unit(key, d + 2) < weight(at) {
            return (at, true);
        }
    }
    (at, false)
}

/// A drifting snow grain ([`crate::physics::drifting_snow`]): from a point where the cover's
/// snow is blowing (kept with probability `min(1, Q/Q_ref)`), a 0.2 mm ice grain
/// (its fall speed; drawn at the size of the weather's smallest flakes) born over
/// the snow's surface at a height of the Rouse profile up to
/// `lift_layer_top_m`, moving with the mean wind; where none is found, parked under
/// the ground map's floor for a step. It carries no mass.
#[must_use]
pub fn birth_drifting_snow(
    key: u32,
    generation: u32,
    params: &StepParams,
    ground: &GroundMap,
    cover: &CoverView<'_>,
) -> Particle {
    let (at, found) = lift_point(key, params, |at| {
        (cover.blowing_snow_at(at).0 / DRIFTING_SNOW_REFERENCE_FLUX).min(1.0)
    });
    let f = random_unit(key, draw::GRAIN_SIZE);
    let speed = grain_settling_speed_mps(DRIFTING_SNOW_DIAMETER_M * (0.5 + f), ICE_DENSITY_KG_M3);
    // Drawn as the smallest flakes: each stands for a cloud of grains too small to
    // see one by one.
    let diameter = snowflake_diameter_m(params.air_temperature_c, 0.5 * f);
    let kind = snow_kind(params);
    let position = if found {
        let surface_m =
            ground.height_at(at).unwrap_or(params.ground_floor_m) + cover.blowing_snow_at(at).1;
        let rouse = rouse_number(speed, params.friction_velocity_mps);
        let height = rouse_height_m(
            rouse,
            params.lift_layer_top_m,
            random_unit(key, draw::LIFT_HEIGHT),
        );
        Vec3::new(at.x, surface_m + height, at.y)
    } else {
        Vec3::new(at.x, params.ground_floor_m - PARKED_BELOW_FLOOR_M, at.y)
    };
    world_newborn(
        position,
        params.mean_wind_mps - Vec3::Y * speed,
        (kind, diameter, speed),
        (key, generation),
        params,
    )
}

/// A saltating grain's lift-off speed, m/s: `w₀ = 2·u*·(0.5 + f)` (lift-off speeds
/// spread widely about their mean; the spread also keeps grains launched together
/// from hopping in step).
#[must_use]
pub fn launch_speed_mps(key: u32, params: &StepParams) -> f32 {
    LAUNCH_SPEED_PER_FRICTION_VELOCITY
        * params.friction_velocity_mps
        * (0.5 + random_unit(key, draw::LIFT_HEIGHT))
}

/// A lifted grain as the run starts: a saltating one part-way through its first
/// hop (a point of the vacuum trajectory of its lift-off speed, at a fraction of
/// its flight time drawn with the pre-warm draw, carrying what it gathered so far),
/// so the grains of the first frames do not all leave the surface together; a
/// suspended one as [`birth_lifted`] places it.
#[must_use]
pub fn initial_lifted(index: u32, params: &StepParams, ground: &GroundMap) -> Particle {
    // No snow lies at the start: drifting-snow slots wait for it.
    let no_cover = CoverView {
        frame: &ground.frame,
        texels: &[],
    };
    let mut p = birth_lifted(index, 0, params, ground, &no_cover);
    if params.grain_suspended != 0 {
        return p;
    }
    let key = particle_key(params.seed, index, 0);
    let w0 = p.velocity_mps.y;
    let g = crate::physics::drag::GRAVITY_MPS2;
    let age = random_unit(key, draw::PREWARM) * 2.0 * w0 / g;
    p.position_m.y += w0 * age - 0.5 * g * age * age;
    p.velocity_mps.y = w0 - g * age;
    p.age_s = age;
    p.water_kg = params.lift_per_particle_kg_per_s * age;
    p
}

/// A world particle's (re-)birth: lifted from the ground ([`birth_lifted`]) or on
/// the emitter ([`birth_on_emitter`]) by its index.
#[must_use]
pub fn birth_in_world(
    index: u32,
    generation: u32,
    params: &StepParams,
    ground: &GroundMap,
    cover: &CoverView<'_>,
) -> Particle {
    if is_lifted(index, params) {
        birth_lifted(index, generation, params, ground, cover)
    } else {
        birth_on_emitter(index, generation, params, ground)
    }
}

/// A particle born on the world emitter (docs/model.md §1):
/// `P = M_model·(W(f − ½), H(f − ½), 0, 1) − Δ`, `v = v0 + 2·k_v·V_rand`.
///
/// The emitter's rectangle is aimed: its footprint is where its particles *land*.
/// Each is born up-wind of its point by the drift `Δ` ([`fall_drift_m`]) of its own
/// steady fall (its terminal speed through the mean wind) down to the ground there
/// (the ground map's; off it, its floor), so in any wind the
/// footprint gets the weather's flux evenly, for every species alike. Born straight
/// over it, the slow flakes of a 14 m/s blizzard falling 20 m drift some 300 m: an
/// emitter shifted up-wind by one mean drift delivered 17 % of the snowfall to the
/// scene, most of it near the up-wind edge.
#[must_use]
pub fn birth_on_emitter(
    index: u32,
    generation: u32,
    params: &StepParams,
    ground: &GroundMap,
) -> Particle {
    let key = particle_key(params.seed, index, generation);
    let velocity = params.emitter_velocity_mps
        + centred3(key, draw::VELOCITY_X) * (2.0 * params.emitter_velocity_spread_mps);
    let species = draw_species(key, params);
    let aim = emitter_aim_m(key, params);
    let ground_m = ground_or_floor_m(ground, aim, params);
    world_newborn(
        aim - fall_drift_m(aim.y, ground_m, species.2, params),
        velocity,
        species,
        (key, generation),
        params,
    )
}

/// A particle born in the camera volume at `position_m`, already falling at its
/// terminal speed through the mean wind (so no band of accelerating particles shows).
#[must_use]
pub fn birth_in_camera_volume(
    index: u32,
    generation: u32,
    params: &StepParams,
    position_m: Vec3,
) -> Particle {
    let key = particle_key(params.seed, index, generation);
    let species = draw_species(key, params);
    newborn(
        position_m,
        params.mean_wind_mps - Vec3::Y * species.2,
        species,
        draw_rotation(key, params.camera_rotation.x),
        generation,
        ParticleSource::CameraVolume,
    )
}

/// The particle a slot starts with at configure time, pre-warmed so the air is
/// already in steady state (no curtain falling from the emitter on the first frame).
///
/// World emitter: born at generation 0, then moved a random fraction of its fall
/// (down to the ground where it is aimed, at most `t_max`) along its steady path — terminal
/// speed through the mean wind — carrying the water it gathered on the way. Camera
/// volume: uniform in the box.
#[must_use]
pub fn initial_particle(index: u32, params: &StepParams, ground: &GroundMap) -> Particle {
    let key = particle_key(params.seed, index, 0);
    if is_lifted(index, params) {
        return initial_lifted(index, params, ground);
    }
    if index < params.world_count {
        let mut p = birth_on_emitter(index, 0, params, ground);
        // Down to the ground where it is aimed, under the emitter's point.
        let ground_m = ground_or_floor_m(ground, emitter_aim_m(key, params), params);
        let fall_s = ((p.position_m.y - ground_m).max(0.0) / p.terminal_speed_mps)
            .min(params.emitter_life_time_s);
        let age = random_unit(key, draw::PREWARM) * fall_s;
        p.velocity_mps = params.mean_wind_mps - Vec3::Y * p.terminal_speed_mps;
        p.position_m += p.velocity_mps * age;
        p.age_s = age;
        p.water_kg = params.water_per_particle_kg_per_s * age;
        p
    } else {
        let offset = Vec3::new(
            centred(key, draw::VOLUME_X),
            centred(key, draw::VOLUME_X + 1),
            centred(key, draw::VOLUME_X + 2),
        ) * (2.0 * params.camera_half_extent_m);
        let generation = stationary_generation(index, params);
        birth_in_camera_volume(index, generation, params, params.camera_centre_m + offset)
    }
}
