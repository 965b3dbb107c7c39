// step_particles.wgsl: the particle kernels. Rust twin: precip_model::particles::step::step_particle
// and precip_model::particles::birth::initial_particle.
//
// The Rust step deposits and re-births inline; here step_particles only appends the
// particle to the pending births (keeping the position the camera volume needs; a
// particle that landed on the cover grid is moved to its landing point and marked
// FLAG_LANDED), and birth_particles, dispatched right after it indirectly over that
// list alone, deposits the landed ones' water and re-births them with the same
// inputs (or, for a raindrop that struck hard enough, throws up its splash droplet:
// splash.wgsl; a camera-volume particle that reaches the ground is marked
// FLAG_LANDED too, at the ground, and deposits nothing). Same result (the deposits are integer sums, so their order does not
// matter); but the deposit's atomics and the large birth code run only for the few
// particles re-born, not under a mask for every particle (lavapipe executes both
// sides of a divergent branch). reset_births empties the list before each step.
// Program: layout, rng, physics, wind, ground, deposit, birth, this file
// (precip_gpu::shaders::Program::StepParticles).

@group(0) @binding(0) var<uniform> step_params: StepParams;
@group(0) @binding(1) var<uniform> frames: Frames;
@group(0) @binding(2) var<uniform> wind: WindParams;
@group(0) @binding(3) var wind_volume: texture_3d<f32>;
@group(0) @binding(4) var<storage, read> ground_height: array<f32>;
@group(0) @binding(5) var<storage, read_write> particles: array<Particle>;
@group(0) @binding(6) var<storage, read_write> deposits: array<atomic<u32>>;
@group(0) @binding(7) var<storage, read_write> pending: PendingBirths;
// The cover texels as words (precip_model::physics::drifting_snow::COVER_TEXEL_WORDS a texel):
// where snow is blowing, for drifting snow's births.
@group(0) @binding(9) var<storage, read> cover_words: array<f32>;

// Within this kernel only, never stored: the particle's life ends this step.
const STEP_ENDS: u32 = 1024u;

// Appends particle `index` to the pending births.
fn queue_birth(index: u32) {
    pending.indices[atomicAdd(&pending.count, 1u)] = index;
}

fn wrap_centred(x: f32, h: f32) -> f32 {
    return x - 2.0 * h * floor((x + h) / (2.0 * h));
}

fn step_in_camera_volume(index: u32, generation: u32, moved: Particle) -> Particle {
    var next = moved;
    let centre = step_params.camera_centre_m;
    let half = step_params.camera_half_extent_m;
    var local = next.position_m - centre;
    local.x = wrap_centred(local.x, half.x);
    local.z = wrap_centred(local.z, half.z);
    if (local.y > half.y) {
        local.y = wrap_centred(local.y, half.y);
    }
    let position = centre + local;
    let ground = ground_height_at(vec2<f32>(position.x, position.z));
    let grounded = ground.x > 0.0 && position.y <= ground.y;
    next.position_m = position;
    if (grounded) {
        // Where it struck: birth_particles splashes it there, or re-births it at
        // this x, z.
        next.position_m.y = ground.y;
        next.flags |= FLAG_LANDED;
    }
    if (local.y < -half.y || grounded) {
        next.flags |= STEP_ENDS;
    }
    return next;
}

// Where a step reads the particle's wind: the step's predicted midpoint, or the
// particle itself where the midpoint lies under the ground map. Rust: wind_probe_m.
fn wind_probe_m(particle: Particle) -> vec3<f32> {
    let midpoint = particle.position_m + particle.velocity_mps * (0.5 * step_params.dt_s);
    if (midpoint.y >= step_params.flow_ceiling_m) {
        return midpoint;
    }
    let ground = ground_height_at(vec2<f32>(midpoint.x, midpoint.z));
    if (ground.x > 0.0 && midpoint.y < ground.y) {
        return particle.position_m;
    }
    return midpoint;
}

fn step_particle(index: u32, particle: Particle) -> Particle {
    let dt = step_params.dt_s;
    let probe = wind_probe_m(particle);
    let wind_mps = terrain_following_wind(wind_velocity_at(probe, step_params.time_s), probe);
    let velocity = drag_velocity(particle.velocity_mps, wind_mps, particle.terminal_speed_mps, dt);
    let position = particle.position_m + (particle.velocity_mps + velocity) * (0.5 * dt);

    let camera = (particle.flags & FLAG_CAMERA_VOLUME) != 0u;
    let rotation = select(step_params.world_rotation, step_params.camera_rotation, camera);
    // Written out per axis (no dynamic indexing into a vector, which some drivers
    // spill to memory).
    let rx = advance_rotation(particle.rotation_rad.x, (particle.flags & FLAG_ROTATION_INCREASING_X) != 0u, rotation.x, rotation.y, dt);
    let ry = advance_rotation(particle.rotation_rad.y, (particle.flags & (FLAG_ROTATION_INCREASING_X << 1u)) != 0u, rotation.x, rotation.y, dt);
    let rz = advance_rotation(particle.rotation_rad.z, (particle.flags & (FLAG_ROTATION_INCREASING_X << 2u)) != 0u, rotation.x, rotation.y, dt);
    let rotation_rad = vec3<f32>(rx.x, ry.x, rz.x);
    let bits = (particle.flags & ~(7u * FLAG_ROTATION_INCREASING_X))
        | select(0u, FLAG_ROTATION_INCREASING_X, rx.y > 0.5)
        | select(0u, FLAG_ROTATION_INCREASING_X << 1u, ry.y > 0.5)
        | select(0u, FLAG_ROTATION_INCREASING_X << 2u, rz.y > 0.5);
    var next = particle;
    next.position_m = position;
    next.age_s = particle.age_s + dt;
    next.velocity_mps = velocity;
    next.rotation_rad = rotation_rad;
    next.flags = bits;

    if (camera) {
        return step_in_camera_volume(index, particle.generation, next);
    }
    let lifted = is_lifted(index);
    next.water_kg += select(step_params.water_per_particle_kg_per_s, step_params.lift_per_particle_kg_per_s, lifted) * dt;
    let xz = vec2<f32>(position.x, position.z);
    let ground = ground_height_at(xz);
    var landed = ground.x > 0.0 && position.y <= ground.y;
    // Rust: rebounds_off_a_wall (snow blown against a wall faster than its transport
    // threshold rises along it from where it was).
    let speed_h = length(velocity.xz);
    let is_snow = kind_is_snow(particle_kind(particle.flags));
    if (landed && particle.position_m.y < ground.y && is_snow && speed_h > step_params.wall_rebound_speed_mps) {
        landed = false;
        next.position_m = particle.position_m;
        next.velocity_mps = vec3<f32>(0.0, max(speed_h, velocity.y), 0.0);
    }
    if (landed) {
        // Already below this surface before the step: it came in from the side (a
        // wall, an eave) and deposits where it was, at the wall's foot. Water landing
        // off the cover grid fell outside the scene: not kept.
        let from_side = particle.position_m.y < ground.y;
        let at = select(xz, particle.position_m.xz, from_side);
        if (grid_texel_index(frames.cover, at) >= 0) {
            next.position_m = vec3<f32>(at.x, ground.y, at.y);
            next.flags |= FLAG_LANDED;
        }
    }
    // Below the floor off the map, or a lifted grain blown off it.
    let left_scene = ground.x == 0.0 && (position.y < step_params.ground_floor_m || lifted);
    if (landed || left_scene || next.age_s >= step_params.emitter_life_time_s) {
        next.flags |= STEP_ENDS;
    }
    return next;
}

@compute @workgroup_size(64)
fn step_particles(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    // Over the particles that do not rest (precip_model::particles::step::stepped_particles).
    let i = step_params.step_first + linear_index(id, groups);
    if (i >= step_params.step_end) {
        return;
    }
    var next = step_particle(i, particles[i]);
    let ends = (next.flags & STEP_ENDS) != 0u;
    next.flags &= ~STEP_ENDS;
    particles[i] = next;
    if (ends) {
        queue_birth(i);
    }
}

// Empties the pending births before a step (one workgroup).
@compute @workgroup_size(64)
fn reset_births(@builtin(local_invocation_index) lane: u32) {
    if (lane == 0u) {
        atomicStore(&pending.count, 0u);
    }
}

// Re-birth of the particles step_particles marked (Rust: the birth calls inside
// step_particle).
fn birth_particle(index: u32, particle: Particle) -> Particle {
    let generation = particle.generation + 1u;
    if ((particle.flags & FLAG_CAMERA_VOLUME) != 0u) {
        let key = particle_key(step_params.seed, index, generation);
        var born = birth_in_camera_volume(index, generation, particle.position_m);
        born.position_m.y = step_params.camera_centre_m.y + step_params.camera_half_extent_m.y
            - random_unit(key, DRAW_PREWARM) * born.terminal_speed_mps * step_params.dt_s;
        return born;
    }
    return birth_in_world(index, generation);
}

// Deposits a landed particle's water where it landed (Rust: the deposit in
// step_particle).
fn deposit_landed(particle: Particle) {
    let channel = kind_deposit_channel(particle_kind(particle.flags));
    let water_mm = particle.water_kg * step_params.deposit_scale_mm_per_kg;
    let texel = grid_texel_index(frames.cover, particle.position_m.xz);
    if (texel >= 0) {
        atomicAdd(&deposits[DEPOSIT_CHANNELS * u32(texel) + channel], deposit_units(water_mm));
    }
}

// Over the pending births only: each invocation walks the list with the dispatch's
// stride (precip_gpu::recipe::LIST_ENTRIES_PER_INVOCATION).
@compute @workgroup_size(64)
fn birth_particles(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let lanes = groups.x * groups.y * 64u;
    let count = atomicLoad(&pending.count);
    for (var k = linear_index(id, groups); k < count; k += lanes) {
        let i = pending.indices[k];
        let particle = particles[i];
        let landed = (particle.flags & FLAG_LANDED) != 0u;
        if (landed && (particle.flags & FLAG_CAMERA_VOLUME) == 0u) {
            deposit_landed(particle);
        }
        if (landed && splashes(particle)) {
            particles[i] = splash_droplet(i, particle, particle.position_m);
        } else {
            particles[i] = birth_particle(i, particle);
        }
    }
}

@compute @workgroup_size(64)
fn init_particles(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= step_params.particle_count) {
        return;
    }
    particles[i] = initial_particle(i);
}
