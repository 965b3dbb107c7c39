// rng.wgsl: counter-based random numbers, bit for bit the Rust precip_model::particles::rng.

fn pcg_hash(input: u32) -> u32 {
    let state = input * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn particle_key(seed: u32, index: u32, generation: u32) -> u32 {
    return pcg_hash(pcg_hash(pcg_hash(seed) ^ index) ^ generation);
}

fn random_u32(key: u32, draw: u32) -> u32 {
    return pcg_hash(key ^ draw);
}

fn random_unit(key: u32, draw: u32) -> f32 {
    return f32(random_u32(key, draw) >> 8u) * (1.0 / 16777216.0);
}

// Rust: precip_model::particles::rng::draw.
const DRAW_POSITION_U: u32 = 0u;
const DRAW_POSITION_V: u32 = 1u;
const DRAW_VELOCITY_X: u32 = 2u;
const DRAW_ROTATION0_X: u32 = 5u;
const DRAW_ROTATION_X: u32 = 8u;
const DRAW_KIND: u32 = 11u;
const DRAW_SNOW_SIZE: u32 = 12u;
const DRAW_SNOW_SPEED: u32 = 13u;
const DRAW_RAIN_DIAMETER: u32 = 14u;
const DRAW_GRAIN_SIZE: u32 = 79u;
const DRAW_LIFT_HEIGHT: u32 = 80u;
const DRAW_LIFT: u32 = 81u;
const DRAW_VOLUME_X: u32 = 100u;
const DRAW_PREWARM: u32 = 103u;
const DRAW_STATIONARY: u32 = 104u;
