//! Counter-based random numbers: the same bits in Rust and WGSL (`shaders/rng.wgsl`).
//!
//! Every random number is a pure function of (seed, particle index, generation, draw
//! number): no state is carried between threads or frames, so any backend, in any
//! order, draws the same numbers. The hash is the PCG-based integer hash of Jarzynski &
//! Olano (2020, "Hash Functions for GPU Rendering"); keys are folded in one at a
//! time. A uniform float is `(h >> 8) · 2⁻²⁴`: 24 bits, exactly representable, in `[0, 1)`.

/// PCG hash of one `u32` (WGSL twin: `pcg_hash`).
#[must_use]
pub const fn pcg_hash(input: u32) -> u32 {
    let state = input.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// The particle's key: seed, index and generation folded (WGSL twin: `particle_key`).
#[must_use]
pub const fn particle_key(seed: u32, index: u32, generation: u32) -> u32 {
    pcg_hash(pcg_hash(pcg_hash(seed) ^ index) ^ generation)
}

/// The random `u32` number `draw` of a key (WGSL twin: `random_u32`).
#[must_use]
pub const fn random_u32(key: u32, draw: u32) -> u32 {
    pcg_hash(key ^ draw)
}

/// Uniform float in `[0, 1)` from 24 hash bits (WGSL twin: `random_unit`).
#[must_use]
pub fn random_unit(key: u32, draw: u32) -> f32 {
    (random_u32(key, draw) >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Named draw numbers: each random decision of a particle's life has its own, so
/// adding one never shifts the others. Shared with the WGSL (`DRAW_*`).
pub mod draw {
    /// Position on the emitter, OCS X.
    pub const POSITION_U: u32 = 0;
    /// Position on the emitter, OCS Y.
    pub const POSITION_V: u32 = 1;
    /// Velocity spread, X (then Y = +1, Z = +2).
    pub const VELOCITY_X: u32 = 2;
    /// Initial rotation r0, X (then +1, +2).
    pub const ROTATION0_X: u32 = 5;
    /// Rotation offset r, X (then +1, +2).
    pub const ROTATION_X: u32 = 8;
    /// Snow or rain, for sleet.
    pub const KIND: u32 = 11;
    /// Snowflake size within ±50 %.
    pub const SNOW_SIZE: u32 = 12;
    /// Snowflake terminal speed within its range.
    pub const SNOW_SPEED: u32 = 13;
    /// First of the raindrop diameter draws (two per try, up to 14 + 2·32 = 78).
    pub const RAIN_DIAMETER: u32 = 14;
    /// A grain's size within ±50 % of the weather's ([`crate::physics::grain`]).
    pub const GRAIN_SIZE: u32 = 79;
    /// Where in the suspended layer a lifted dust grain starts, or how fast a
    /// saltating sand grain leaves the surface.
    pub const LIFT_HEIGHT: u32 = 80;
    /// First of a lifted grain's tries for erodible ground: three draws a try
    /// (X, Z, acceptance), [`crate::particles::birth::LIFT_TRIES`] tries (81 … 92).
    pub const LIFT: u32 = 81;
    /// Camera-volume position, X (then +1, +2).
    pub const VOLUME_X: u32 = 100;
    /// Pre-warm: how far along its fall a particle starts.
    pub const PREWARM: u32 = 103;
    /// Whether a camera-volume particle starts in this generation
    /// ([`crate::particles::birth::stationary_generation`]).
    pub const STATIONARY: u32 = 104;
    /// A splash droplet's direction round the vertical ([`crate::physics::splash`]).
    pub const SPLASH_AZIMUTH: u32 = 105;
    /// A splash droplet's elevation.
    pub const SPLASH_ELEVATION: u32 = 106;
    /// A splash droplet's speed.
    pub const SPLASH_SPEED: u32 = 107;
}

// Draw numbers never overlap: each decision has its own stream.
const _: () = {
    let last_rain = draw::RAIN_DIAMETER + 2 * crate::physics::raindrop::RAIN_DIAMETER_TRIES - 1;
    assert!(last_rain < draw::GRAIN_SIZE && draw::GRAIN_SIZE < draw::LIFT_HEIGHT);
    assert!(draw::LIFT_HEIGHT < draw::LIFT);
    assert!(draw::LIFT + 3 * crate::particles::birth::LIFT_TRIES <= draw::VOLUME_X);
    assert!(draw::VOLUME_X + 2 < draw::PREWARM);
    assert!(draw::PREWARM < draw::STATIONARY && draw::STATIONARY < draw::SPLASH_AZIMUTH);
    assert!(draw::SNOW_SPEED < draw::RAIN_DIAMETER && draw::ROTATION_X + 2 < draw::KIND);
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_for_the_wgsl_twin() {
        // Computed independently (Python, arbitrary-precision integers masked to 32 bits).
        assert_eq!(pcg_hash(0), 129_708_002);
        assert_eq!(pcg_hash(1), 2_831_084_092);
        assert_eq!(pcg_hash(2), 2_055_130_248);
        assert_eq!(pcg_hash(u32::MAX), 3_861_530_882);
        assert_eq!(random_u32(particle_key(1, 2, 3), 4), 1_693_730_102);
        assert_eq!(random_u32(particle_key(0, 0, 0), 0), 2_368_882_721);
        assert_eq!(random_u32(particle_key(42, 1000, 7), 13), 3_805_727_567);
        // 0.886 089 98…: (3 805 727 567 >> 8) · 2⁻²⁴, bits from Python's struct.
        assert_eq!(
            random_unit(particle_key(42, 1000, 7), 13).to_bits(),
            1_063_442_123
        );
    }

    #[test]
    fn uniform_floats_fill_the_unit_interval_evenly() {
        let mut bins = [0u32; 10];
        let n = 100_000;
        for i in 0..n {
            let f = random_unit(particle_key(7, i, 0), 0);
            assert!((0.0..1.0).contains(&f));
            bins[(f * 10.0) as usize] += 1;
        }
        for b in bins {
            assert!(
                (f64::from(b) / f64::from(n) - 0.1).abs() < 0.005,
                "{bins:?}"
            );
        }
    }
}
