// birth.wgsl: birth and re-birth. Rust twins: precip_model::particles::birth and
// precip_model::physics::drifting_snow.
// Needs the globals `step_params: StepParams`, `cover_words: array<f32>` (drifting
// snow) and ground.wgsl.

fn centred(key: u32, d: u32) -> f32 {
    return random_unit(key, d) - 0.5;
}

fn centred3(key: u32, d: u32) -> vec3<f32> {
    return vec3<f32>(centred(key, d), centred(key, d + 1u), centred(key, d + 2u));
}

struct Species {
    kind: u32,
    diameter_m: f32,
    terminal_speed_mps: f32,
}

// Rust: precip_model::particles::kind::draw_species.
fn draw_species(key: u32) -> Species {
    if (step_params.species.grain_diameter_m > 0.0) {
        let diameter = step_params.species.grain_diameter_m * (0.5 + random_unit(key, DRAW_GRAIN_SIZE));
        return Species(KIND_GRAIN, diameter, grain_settling_speed_mps(diameter, step_params.species.grain_density_kg_m3));
    }
    let which = random_unit(key, DRAW_KIND);
    if (which < step_params.species.snow_fraction) {
        let wet = step_params.snow_is_wet != 0u;
        let diameter = snowflake_diameter_m(step_params.air_temperature_c, random_unit(key, DRAW_SNOW_SIZE));
        let speed = snow_terminal_speed_mps(wet, random_unit(key, DRAW_SNOW_SPEED));
        return Species(select(KIND_DRY_SNOW, KIND_WET_SNOW, wet), diameter, speed);
    }
    if (which < step_params.species.snow_fraction + step_params.species.hail_fraction) {
        let stone_mm = draw_hail_diameter_mm(key, step_params.species.hail_slope_per_mm);
        return Species(KIND_HAIL, stone_mm * 1.0e-3, hailstone_terminal_speed_mps(stone_mm));
    }
    let diameter_mm = draw_raindrop_diameter_mm(key, step_params.species.rain_slope_per_mm);
    return Species(KIND_RAIN, diameter_mm * 1.0e-3, raindrop_terminal_speed_mps(diameter_mm));
}

struct Rotation {
    r0: u32,
    magnitude: vec3<f32>,
    increasing_bits: u32,
}

fn draw_rotation(key: u32, amplitude_rad: f32) -> Rotation {
    let r0 = pack_rotation0(vec3<f32>(
        random_unit(key, DRAW_ROTATION0_X),
        random_unit(key, DRAW_ROTATION0_X + 1u),
        random_unit(key, DRAW_ROTATION0_X + 2u),
    ));
    let r = centred3(key, DRAW_ROTATION_X) * (4.0 * amplitude_rad);
    let bits = select(0u, 1u, r.x >= 0.0) | select(0u, 2u, r.y >= 0.0) | select(0u, 4u, r.z >= 0.0);
    return Rotation(r0, abs(r), bits);
}

fn pack_flags(kind: u32, camera_volume: bool, increasing_bits: u32) -> u32 {
    return (kind << FLAG_KIND_SHIFT) | select(0u, FLAG_CAMERA_VOLUME, camera_volume) | increasing_bits;
}

// Rust: newborn.
fn newborn(position_m: vec3<f32>, velocity_mps: vec3<f32>, species: Species, rotation: Rotation, generation: u32, camera_volume: bool) -> Particle {
    var p: Particle;
    p.position_m = position_m;
    p.age_s = 0.0;
    p.velocity_mps = velocity_mps;
    p.terminal_speed_mps = species.terminal_speed_mps;
    p.rotation_rad = rotation.magnitude;
    p.flags = pack_flags(species.kind, camera_volume, rotation.increasing_bits);
    p.diameter_m = species.diameter_m;
    p.water_kg = 0.0;
    p.generation = generation;
    p.rotation0 = rotation.r0;
    return p;
}

// Rust: fall_drift_m (the mean wind's drift of a steady fall to the ground).
fn fall_drift_m(height_m: f32, ground_m: f32, terminal_speed_mps: f32) -> vec3<f32> {
    let fall_s = max(height_m - ground_m, 0.0) / max(terminal_speed_mps, 1.0e-3);
    return vec3<f32>(step_params.mean_wind_mps.x, 0.0, step_params.mean_wind_mps.z) * fall_s;
}

// The ground under world xz, the floor off the map.
fn ground_or_floor_m(xz_m: vec2<f32>) -> f32 {
    let g = ground_height_at(xz_m);
    return select(step_params.ground_floor_m, g.y, g.x > 0.0);
}

// The point on the emitter that a particle is aimed at.
fn emitter_aim_m(key: u32) -> vec3<f32> {
    let ocs = vec3<f32>(
        step_params.emitter_size_m.x * centred(key, DRAW_POSITION_U),
        step_params.emitter_size_m.y * centred(key, DRAW_POSITION_V),
        0.0,
    );
    return (step_params.emitter_model * vec4<f32>(ocs, 1.0)).xyz;
}

// Rust: birth_on_emitter (aimed: born up-wind of its point by its own fall's drift).
fn birth_on_emitter(index: u32, generation: u32) -> Particle {
    let key = particle_key(step_params.seed, index, generation);
    let velocity = step_params.emitter_velocity_mps
        + centred3(key, DRAW_VELOCITY_X) * (2.0 * step_params.emitter_velocity_spread_mps);
    let species = draw_species(key);
    let aim = emitter_aim_m(key);
    let ground_m = ground_or_floor_m(vec2<f32>(aim.x, aim.z));
    return newborn(
        aim - fall_drift_m(aim.y, ground_m, species.terminal_speed_mps),
        velocity,
        species,
        draw_rotation(key, step_params.world_rotation.x),
        generation,
        false,
    );
}

// Rust: precip_model::particles::birth::LIFT_TRIES.
const LIFT_TRIES: u32 = 4u;

// Rust: is_lifted.
fn is_lifted(index: u32) -> bool {
    return index >= step_params.lift_from && index < step_params.world_count;
}

// Rust: launch_speed_mps.
fn launch_speed_mps(key: u32) -> f32 {
    return LAUNCH_SPEED_PER_FRICTION_VELOCITY * step_params.friction_velocity_mps
        * (0.5 + random_unit(key, DRAW_LIFT_HEIGHT));
}

// Rust: initial_lifted (a saltating grain part-way through its first hop).
fn initial_lifted(index: u32) -> Particle {
    var p = birth_lifted(index, 0u);
    if (step_params.grain_suspended != 0u) {
        return p;
    }
    let key = particle_key(step_params.seed, index, 0u);
    let w0 = p.velocity_mps.y;
    let age = random_unit(key, DRAW_PREWARM) * 2.0 * w0 / GRAVITY_MPS2;
    p.position_m.y += w0 * age - 0.5 * GRAVITY_MPS2 * age * age;
    p.velocity_mps.y = w0 - GRAVITY_MPS2 * age;
    p.age_s = age;
    p.water_kg = step_params.lift_per_particle_kg_per_s * age;
    return p;
}

// Rust: precip_model::physics::drifting_snow.
const COVER_TEXEL_WORDS: u32 = 32u;
const COVER_WORD_DEPTH: u32 = 2u;
const COVER_WORD_SALTATION: u32 = 26u;
const DRIFTING_SNOW_REFERENCE_FLUX: f32 = 0.01;
const DRIFTING_SNOW_DIAMETER_M: f32 = 2.0e-4;
const ICE_DENSITY_KG_M3: f32 = 917.0;
const PARKED_BELOW_FLOOR_M: f32 = 1.0;

// Rust: CoverView::blowing_snow_at: (saltation kg/(m·s), snow depth m), zeros off
// the grid.
fn blowing_snow_at(xz_m: vec2<f32>) -> vec2<f32> {
    let i = grid_texel_index(frames.cover, xz_m);
    if (i < 0 || u32(i) * COVER_TEXEL_WORDS >= arrayLength(&cover_words)) {
        return vec2<f32>(0.0);
    }
    let base = u32(i) * COVER_TEXEL_WORDS;
    return vec2<f32>(cover_words[base + COVER_WORD_SALTATION], cover_words[base + COVER_WORD_DEPTH] * 1.0e-3);
}

// Rust: lift_point: (x, z, 1) kept, or (x, z, 0) for the last try; weighted by the
// blowing snow (`snow`) or by the erodibility.
fn lift_point(key: u32, snow: bool) -> vec3<f32> {
    let span = step_params.lift_area_max_m - step_params.lift_area_min_m;
    var at = step_params.lift_area_min_m;
    for (var t = 0u; t < LIFT_TRIES; t++) {
        let d = DRAW_LIFT + 3u * t;
        at = step_params.lift_area_min_m + span * vec2<f32>(random_unit(key, d), random_unit(key, d + 1u));
        var weight = 0.0;
        if (snow) {
            weight = min(blowing_snow_at(at).x / DRIFTING_SNOW_REFERENCE_FLUX, 1.0);
        } else {
            weight = erodibility_at(at);
        }
        if (random_unit(key, d + 2u) < weight) {
            return vec3<f32>(at, 1.0);
        }
    }
    return vec3<f32>(at, 0.0);
}

// Rust: birth_drifting_snow.
fn birth_drifting_snow(key: u32, generation: u32) -> Particle {
    let found = lift_point(key, true);
    let at = found.xy;
    let f = random_unit(key, DRAW_GRAIN_SIZE);
    let speed = grain_settling_speed_mps(DRIFTING_SNOW_DIAMETER_M * (0.5 + f), ICE_DENSITY_KG_M3);
    // Drawn as the smallest flakes (Rust: birth_drifting_snow).
    let diameter = snowflake_diameter_m(step_params.air_temperature_c, 0.5 * f);
    let kind = select(KIND_DRY_SNOW, KIND_WET_SNOW, step_params.snow_is_wet != 0u);
    var position = vec3<f32>(at.x, step_params.ground_floor_m - PARKED_BELOW_FLOOR_M, at.y);
    if (found.z > 0.5) {
        let surface_m = ground_or_floor_m(at) + blowing_snow_at(at).y;
        let rouse = rouse_number(speed, step_params.friction_velocity_mps);
        position.y = surface_m + rouse_height_m(rouse, step_params.lift_layer_top_m, random_unit(key, DRAW_LIFT_HEIGHT));
    }
    return newborn(
        position,
        step_params.mean_wind_mps - vec3<f32>(0.0, 1.0, 0.0) * speed,
        Species(kind, diameter, speed),
        draw_rotation(key, step_params.world_rotation.x),
        generation,
        false,
    );
}

// Rust: birth_lifted (a grain the wind lifts from erodible ground; in snow weather,
// drifting snow).
fn birth_lifted(index: u32, generation: u32) -> Particle {
    let key = particle_key(step_params.seed, index, generation);
    if (step_params.species.grain_diameter_m <= 0.0) {
        return birth_drifting_snow(key, generation);
    }
    let species = draw_species(key);
    let at = lift_point(key, false).xy;
    let ground_m = ground_or_floor_m(at);
    var height_m = LAUNCH_HEIGHT_M;
    var velocity = vec3<f32>(0.0, launch_speed_mps(key), 0.0);
    if (step_params.grain_suspended != 0u) {
        let rouse = rouse_number(species.terminal_speed_mps, step_params.friction_velocity_mps);
        height_m = rouse_height_m(rouse, step_params.lift_layer_top_m, random_unit(key, DRAW_LIFT_HEIGHT));
        velocity = step_params.mean_wind_mps - vec3<f32>(0.0, 1.0, 0.0) * species.terminal_speed_mps;
    }
    return newborn(
        vec3<f32>(at.x, ground_m + height_m, at.y),
        velocity,
        species,
        draw_rotation(key, step_params.world_rotation.x),
        generation,
        false,
    );
}

// Rust: birth_in_world.
fn birth_in_world(index: u32, generation: u32) -> Particle {
    if (is_lifted(index)) {
        return birth_lifted(index, generation);
    }
    return birth_on_emitter(index, generation);
}

fn birth_in_camera_volume(index: u32, generation: u32, position_m: vec3<f32>) -> Particle {
    let key = particle_key(step_params.seed, index, generation);
    let species = draw_species(key);
    return newborn(
        position_m,
        step_params.mean_wind_mps - vec3<f32>(0.0, 1.0, 0.0) * species.terminal_speed_mps,
        species,
        draw_rotation(key, step_params.camera_rotation.x),
        generation,
        true,
    );
}

// Rust: precip_model::particles::birth::STATIONARY_TRIES.
const STATIONARY_TRIES: u32 = 16u;

// Rust: slowest_terminal_speed_mps.
fn slowest_terminal_speed_mps() -> f32 {
    if (step_params.species.grain_diameter_m > 0.0) {
        return grain_settling_speed_mps(0.5 * step_params.species.grain_diameter_m, step_params.species.grain_density_kg_m3);
    }
    let species = step_params.species;
    var slowest = 3.4e38;
    if (species.snow_fraction > 0.0) {
        slowest = min(slowest, snow_terminal_speed_mps(step_params.snow_is_wet != 0u, 0.0));
    }
    if (species.hail_fraction > 0.0) {
        slowest = min(slowest, hailstone_terminal_speed_mps(HAIL_DIAMETER_MIN_MM));
    }
    if (species.snow_fraction + species.hail_fraction < 1.0) {
        slowest = min(slowest, raindrop_terminal_speed_mps(RAIN_DIAMETER_MIN_MM));
    }
    return slowest;
}

// Rust: stationary_generation (the volume starts as it will stay: species ∝ 1/v).
fn stationary_generation(index: u32) -> u32 {
    let slowest = slowest_terminal_speed_mps();
    for (var generation = 0u; generation < STATIONARY_TRIES; generation++) {
        let key = particle_key(step_params.seed, index, generation);
        let species = draw_species(key);
        if (random_unit(key, DRAW_STATIONARY) * species.terminal_speed_mps < slowest) {
            return generation;
        }
    }
    return STATIONARY_TRIES - 1u;
}

fn initial_particle(index: u32) -> Particle {
    let key = particle_key(step_params.seed, index, 0u);
    if (is_lifted(index)) {
        return initial_lifted(index);
    }
    if (index < step_params.world_count) {
        var p = birth_on_emitter(index, 0u);
        // Down to the ground where it is aimed, under the emitter's point.
        let aim = emitter_aim_m(key);
        let ground_m = ground_or_floor_m(vec2<f32>(aim.x, aim.z));
        let fall_s = min(max(p.position_m.y - ground_m, 0.0) / p.terminal_speed_mps, step_params.emitter_life_time_s);
        let age = random_unit(key, DRAW_PREWARM) * fall_s;
        p.velocity_mps = step_params.mean_wind_mps - vec3<f32>(0.0, 1.0, 0.0) * p.terminal_speed_mps;
        p.position_m += p.velocity_mps * age;
        p.age_s = age;
        p.water_kg = step_params.water_per_particle_kg_per_s * age;
        return p;
    }
    let offset = vec3<f32>(
        centred(key, DRAW_VOLUME_X),
        centred(key, DRAW_VOLUME_X + 1u),
        centred(key, DRAW_VOLUME_X + 2u),
    ) * (2.0 * step_params.camera_half_extent_m);
    let generation = stationary_generation(index);
    return birth_in_camera_volume(index, generation, step_params.camera_centre_m + offset);
}
