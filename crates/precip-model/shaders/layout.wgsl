// layout.wgsl: every struct that crosses between Rust and the GPU, and grid lookups.
// Rust twins: precip_model::particles::particle::Particle, precip_model::particles::step::StepParams,
// precip_cover::GridFrame, precip_model::host::Frames, precip_wind::WindParams.

// 64 bytes; the step reads and writes the first 48 and the water.
struct Particle {
    position_m: vec3<f32>,
    age_s: f32,
    velocity_mps: vec3<f32>,
    terminal_speed_mps: f32,
    rotation_rad: vec3<f32>,
    flags: u32,
    diameter_m: f32,
    water_kg: f32,
    generation: u32,
    // r0, 10 bits an axis (Rust: precip_model::particles::particle::rotation0).
    rotation0: u32,
}

// Rust: precip_model::particles::particle::rotation0::pack.
fn pack_rotation0(units: vec3<f32>) -> u32 {
    let steps = min(vec3<u32>(units * 1024.0), vec3<u32>(1023u));
    return steps.x | (steps.y << 10u) | (steps.z << 20u);
}

// Rust: precip_model::particles::particle::rotation0::unpack_rad.
fn rotation0_rad(packed: u32) -> vec3<f32> {
    let steps = vec3<u32>(packed, packed >> 10u, packed >> 20u) & vec3<u32>(1023u);
    return vec3<f32>(steps) * (6.2831855 / 1024.0);
}

// Particle.flags (Rust: precip_model::particles::particle::flags).
const FLAG_ROTATION_INCREASING_X: u32 = 1u;
const FLAG_KIND_SHIFT: u32 = 4u;
const FLAG_KIND_MASK: u32 = 15u;
const FLAG_CAMERA_VOLUME: u32 = 256u;
// Set by step_particles on a particle that landed on the cover grid (its position is
// then the landing point), read by birth_particles within the same sub-step.
const FLAG_LANDED: u32 = 512u;
const FLAG_SPLASH: u32 = 2048u;
// The kinds (KIND_*) and SpeciesParams: kind.wgsl.

struct StepParams {
    emitter_model: mat4x4<f32>,
    emitter_size_m: vec2<f32>,
    emitter_life_time_s: f32,
    emitter_velocity_spread_mps: f32,
    emitter_velocity_mps: vec3<f32>,
    water_per_particle_kg_per_s: f32,
    camera_centre_m: vec3<f32>,
    dt_s: f32,
    camera_half_extent_m: vec3<f32>,
    time_s: f32,
    mean_wind_mps: vec3<f32>,
    air_temperature_c: f32,
    world_rotation: vec2<f32>,
    camera_rotation: vec2<f32>,
    seed: u32,
    world_count: u32,
    particle_count: u32,
    snow_is_wet: u32,
    deposit_scale_mm_per_kg: f32,
    ground_floor_m: f32,
    lift_from: u32,
    lift_per_particle_kg_per_s: f32,
    friction_velocity_mps: f32,
    lift_layer_top_m: f32,
    grain_suspended: u32,
    flow_ceiling_m: f32,
    lift_area_min_m: vec2<f32>,
    lift_area_max_m: vec2<f32>,
    wall_rebound_speed_mps: f32,
    step_first: u32,
    step_end: u32,
    reserved2: u32,
    species: SpeciesParams,
}

// The particles to re-birth this sub-step (Rust: precip_gpu::recipe::pending_births_bytes).
struct PendingBirths {
    count: atomic<u32>,
    indices: array<u32>,
}

struct GridFrame {
    origin_m: vec2<f32>,
    size_m: vec2<f32>,
    texels: vec2<u32>,
    reserved: vec2<u32>,
}

struct Frames {
    ground: GridFrame,
    cover: GridFrame,
    waves: GridFrame,
}

struct WindParams {
    mean_wind_mps: vec3<f32>,
    gust_factor: f32,
    extent_m: vec3<f32>,
    reserved0: f32,
    texels: vec3<u32>,
    reserved1: u32,
}

// Rust: GridFrame::texel_index. -1 outside the grid (NaN lands outside).
fn grid_texel_index(frame: GridFrame, xz_m: vec2<f32>) -> i32 {
    let t = ((xz_m - frame.origin_m) / frame.size_m) * vec2<f32>(frame.texels);
    let f = floor(t);
    let inside = f.x >= 0.0 && f.y >= 0.0 && f.x < f32(frame.texels.x) && f.y < f32(frame.texels.y);
    if (!inside) {
        return -1;
    }
    return i32(u32(f.x) + frame.texels.x * u32(f.y));
}

// The linear index of an invocation in a 2D dispatch (Rust: gpu::dispatch_size).
fn linear_index(id: vec3<u32>, workgroups: vec3<u32>) -> u32 {
    return id.x + id.y * workgroups.x * 64u;
}
