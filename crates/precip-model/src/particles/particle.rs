//! [`Particle`]: one particle's state, the GPU's layout (seeds 000/001 plus physics).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

pub use crate::particles::kind::ParticleKind;

/// Which volume a particle belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParticleSource {
    /// The world emitter: falls onto the scene and feeds the cover.
    WorldEmitter,
    /// The camera volume: wraps around the camera, never ends.
    CameraVolume,
}

/// Bit layout of [`Particle::flags`] (WGSL twin: `FLAG_*` in layout.wgsl).
pub mod flags {
    /// Bits 0–2: the rotation offset of axis X/Y/Z is increasing.
    pub const ROTATION_INCREASING_X: u32 = 1 << 0;
    /// Bits 4–7: [`super::ParticleKind`] (four taken of sixteen: a new kind, say
    /// hail, needs no change of layout; `particle_kind` in kind.wgsl reads them).
    pub const KIND_SHIFT: u32 = 4;
    /// Mask of the kind bits after shifting.
    pub const KIND_MASK: u32 = 0b1111;
    /// Bit 8: the particle belongs to the camera volume.
    pub const CAMERA_VOLUME: u32 = 1 << 8;
    /// Bit 9: GPU only, between the `step_particles` and `birth_particles` kernels of
    /// one sub-step: the particle landed on the cover grid and its position is where
    /// its water goes; never set in a particle read back.
    pub const LANDED: u32 = 1 << 9;
    /// Bit 11: the particle is a splash droplet thrown up where its drop struck
    /// ([`crate::physics::splash`]); it splashes no further and is re-born when it lands.
    pub const SPLASH: u32 = 1 << 11;
}

/// One particle: the seeds' state `(t, P, v, r0, r)` plus what the physics needs, in
/// 64 bytes.
///
/// The step kernel reads and writes the first 48 bytes and the water (52 of 64); the
/// diameter, generation and initial rotation are for the drawing and the re-birth.
/// A split into hot and cold arrays would not move fewer bytes: with `vec3` rows of
/// 16 bytes the step's 52 bytes pad to 64 anyway, and every drawing kernel reads both
/// halves. What made room is the initial rotation `r0`, packed into one word (10 bits
/// an axis: 0.35° steps, drawn from the same random numbers on both sides, so the CPU
/// and the GPU store the same word), and the two reserved words, gone.
///
/// WGSL twin: `Particle` in `shaders/layout.wgsl` (64 bytes: three `vec3<f32>`+scalar
/// rows and four scalars).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct Particle {
    /// Centre P, world metres.
    pub position_m: Vec3,
    /// Age t since birth, s.
    pub age_s: f32,
    /// Velocity v, m/s.
    pub velocity_mps: Vec3,
    /// Terminal fall speed V_pmax in still air, m/s.
    pub terminal_speed_mps: f32,
    /// Rotation offsets |r| in `[0, 2·k_rot]`, rad; their directions are in `flags`.
    pub rotation_rad: Vec3,
    /// Kind, volume and rotation directions ([`flags`]).
    pub flags: u32,
    /// Diameter: the flake's, or the drop's, m.
    pub diameter_m: f32,
    /// Water this particle stands for, kg (= mm over 1 m²), gathered since birth.
    pub water_kg: f32,
    /// How many times this slot has been re-born (keys the random numbers).
    pub generation: u32,
    /// Initial rotation angles r0 about X, Y, Z ([`rotation0`]: 10 bits each).
    pub rotation0: u32,
}
const _: () = assert!(size_of::<Particle>() == 64);

/// The initial rotation `r0 = 2π·(f, f, f)` (seed 001) in one word: axis `a` in bits
/// `10a … 10a + 9` as `⌊1024·f⌋`, so angles in steps of 2π/1024.
///
/// WGSL twins: `pack_rotation0`, `rotation0_rad` in `shaders/layout.wgsl`.
pub mod rotation0 {
    use glam::Vec3;

    /// Steps per turn.
    pub const STEPS: u32 = 1024;
    /// Bits an axis.
    pub const BITS: u32 = 10;

    /// Packs three uniform numbers in `[0, 1)`.
    #[must_use]
    pub fn pack(units: Vec3) -> u32 {
        let step = |u: f32| ((u * STEPS as f32) as u32).min(STEPS - 1);
        step(units.x) | (step(units.y) << BITS) | (step(units.z) << (2 * BITS))
    }

    /// The angles, rad.
    #[must_use]
    pub fn unpack_rad(packed: u32) -> Vec3 {
        let mask = STEPS - 1;
        let turn = std::f32::consts::TAU / STEPS as f32;
        Vec3::new(
            (packed & mask) as f32,
            ((packed >> BITS) & mask) as f32,
            ((packed >> (2 * BITS)) & mask) as f32,
        ) * turn
    }
}

impl Particle {
    /// The particle's kind.
    #[must_use]
    pub const fn kind(&self) -> ParticleKind {
        ParticleKind::from_bits((self.flags >> flags::KIND_SHIFT) & flags::KIND_MASK)
    }

    /// The volume it belongs to.
    #[must_use]
    pub const fn source(&self) -> ParticleSource {
        if self.flags & flags::CAMERA_VOLUME != 0 {
            ParticleSource::CameraVolume
        } else {
            ParticleSource::WorldEmitter
        }
    }

    /// Whether rotation axis `axis` (0 = X, 1 = Y, 2 = Z) is increasing.
    #[must_use]
    pub const fn rotation_increasing(&self, axis: u32) -> bool {
        self.flags & (flags::ROTATION_INCREASING_X << axis) != 0
    }

    /// Initial rotation angles r0 about X, Y, Z, rad.
    #[must_use]
    pub fn rotation0_rad(&self) -> Vec3 {
        rotation0::unpack_rad(self.rotation0)
    }

    /// Drawing angles `α = r0 + (|r| − k_rot)` about X, Y, Z (seed 001), rad.
    #[must_use]
    pub fn drawing_angles_rad(&self, rotation_amplitude_rad: f32) -> Vec3 {
        self.rotation0_rad() + (self.rotation_rad - Vec3::splat(rotation_amplitude_rad))
    }
}

/// Packs the flags word.
#[must_use]
pub const fn pack_flags(kind: ParticleKind, source: ParticleSource, increasing: [bool; 3]) -> u32 {
    let mut bits = (kind as u32) << flags::KIND_SHIFT;
    if matches!(source, ParticleSource::CameraVolume) {
        bits |= flags::CAMERA_VOLUME;
    }
    if increasing[0] {
        bits |= flags::ROTATION_INCREASING_X;
    }
    if increasing[1] {
        bits |= flags::ROTATION_INCREASING_X << 1;
    }
    if increasing[2] {
        bits |= flags::ROTATION_INCREASING_X << 2;
    }
    bits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_is_pinned() {
        assert_eq!(std::mem::offset_of!(Particle, position_m), 0);
        assert_eq!(std::mem::offset_of!(Particle, age_s), 12);
        assert_eq!(std::mem::offset_of!(Particle, velocity_mps), 16);
        assert_eq!(std::mem::offset_of!(Particle, terminal_speed_mps), 28);
        assert_eq!(std::mem::offset_of!(Particle, rotation_rad), 32);
        assert_eq!(std::mem::offset_of!(Particle, flags), 44);
        assert_eq!(std::mem::offset_of!(Particle, diameter_m), 48);
        assert_eq!(std::mem::offset_of!(Particle, water_kg), 52);
        assert_eq!(std::mem::offset_of!(Particle, generation), 56);
        assert_eq!(std::mem::offset_of!(Particle, rotation0), 60);
    }

    #[test]
    fn rotation0_packs_each_axis_to_a_1024th_of_a_turn() {
        let units = Vec3::new(0.0, 0.5, 0.999_999_9);
        let packed = rotation0::pack(units);
        assert_eq!(packed & 1023, 0);
        assert_eq!((packed >> 10) & 1023, 512);
        assert_eq!(packed >> 20, 1023);
        let rad = rotation0::unpack_rad(packed);
        let turn = std::f32::consts::TAU;
        assert!((rad - units * turn).abs().max_element() <= turn / 1024.0);
        assert!(rad.x.abs() < f32::EPSILON);
        assert!((rad.y - std::f32::consts::PI).abs() < 1e-6);
    }

    #[test]
    fn flags_round_trip() {
        for kind in ParticleKind::ALL {
            for source in [ParticleSource::WorldEmitter, ParticleSource::CameraVolume] {
                for bits in 0..8u32 {
                    let inc = [bits & 1 != 0, bits & 2 != 0, bits & 4 != 0];
                    let p = Particle {
                        flags: pack_flags(kind, source, inc),
                        ..Particle::default()
                    };
                    assert_eq!(p.kind(), kind);
                    assert_eq!(p.source(), source);
                    for axis in 0..3 {
                        assert_eq!(p.rotation_increasing(axis), inc[axis as usize]);
                    }
                }
            }
        }
    }

    /// The value of `const NAME: u32 = …u;` in layout.wgsl.
    fn wgsl_const(name: &str) -> u32 {
        crate::wgsl::u32_const(crate::wgsl::LAYOUT, name)
    }

    #[test]
    fn the_flag_bits_are_the_wgsl_twins() {
        assert_eq!(wgsl_const("FLAG_KIND_SHIFT"), flags::KIND_SHIFT);
        assert_eq!(wgsl_const("FLAG_KIND_MASK"), flags::KIND_MASK);
        assert_eq!(wgsl_const("FLAG_CAMERA_VOLUME"), flags::CAMERA_VOLUME);
        assert_eq!(wgsl_const("FLAG_LANDED"), flags::LANDED);
        assert_eq!(wgsl_const("FLAG_SPLASH"), flags::SPLASH);
        assert_eq!(
            wgsl_const("FLAG_ROTATION_INCREASING_X"),
            flags::ROTATION_INCREASING_X
        );
        // The kind's bits lie between the rotation's and the camera volume's.
        let kind_bits = flags::KIND_MASK << flags::KIND_SHIFT;
        assert_eq!(kind_bits & (flags::ROTATION_INCREASING_X * 0b111), 0);
        assert_eq!(
            kind_bits & (flags::CAMERA_VOLUME | flags::LANDED | flags::SPLASH),
            0
        );
    }
}
