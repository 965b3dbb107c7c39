//! [`Particle`]: one particle's state, the GPU's layout (seeds 000/001 plus physics).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// What a particle is.
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParticleKind {
    /// A dry snowflake.
    DrySnow = 0,
    /// A wet snowflake.
    WetSnow = 1,
    /// A raindrop.
    Rain = 2,
}

impl ParticleKind {
    /// Whether it is snow.
    #[must_use]
    pub const fn is_snow(self) -> bool {
        !matches!(self, Self::Rain)
    }
}

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
    /// Bits 4–5: [`super::ParticleKind`].
    pub const KIND_SHIFT: u32 = 4;
    /// Mask of the kind bits after shifting.
    pub const KIND_MASK: u32 = 0b11;
    /// Bit 8: the particle belongs to the camera volume.
    pub const CAMERA_VOLUME: u32 = 1 << 8;
    /// Bit 9: GPU only, between the `step_particles` and `birth_particles` kernels of
    /// one sub-step; never set in a particle read back.
    pub const PENDING_BIRTH: u32 = 1 << 9;
}

/// One particle: the seeds' state `(t, P, v, r0, r)` plus what the physics needs.
///
/// WGSL twin: `Particle` in `shaders/layout.wgsl` (80 bytes: four `vec3<f32>`+scalar
/// rows and four `u32`).
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
    /// Initial rotation angles r0 about X, Y, Z, rad.
    pub rotation0_rad: Vec3,
    /// Diameter: the flake's, or the drop's, m.
    pub diameter_m: f32,
    /// Rotation offsets |r| in `[0, 2·k_rot]`, rad; their directions are in `flags`.
    pub rotation_rad: Vec3,
    /// Water this particle stands for, kg (= mm over 1 m²), gathered since birth.
    pub water_kg: f32,
    /// How many times this slot has been re-born (keys the random numbers).
    pub generation: u32,
    /// Kind, volume and rotation directions ([`flags`]).
    pub flags: u32,
    /// Unused (`0`).
    pub reserved: [u32; 2],
}
const _: () = assert!(size_of::<Particle>() == 80);

impl Particle {
    /// The particle's kind.
    #[must_use]
    pub const fn kind(&self) -> ParticleKind {
        match (self.flags >> flags::KIND_SHIFT) & flags::KIND_MASK {
            0 => ParticleKind::DrySnow,
            1 => ParticleKind::WetSnow,
            _ => ParticleKind::Rain,
        }
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

    /// Drawing angles `α = r0 + (|r| − k_rot)` about X, Y, Z (seed 001), rad.
    #[must_use]
    pub fn drawing_angles_rad(&self, rotation_amplitude_rad: f32) -> Vec3 {
        self.rotation0_rad + (self.rotation_rad - Vec3::splat(rotation_amplitude_rad))
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
        assert_eq!(std::mem::offset_of!(Particle, rotation0_rad), 32);
        assert_eq!(std::mem::offset_of!(Particle, diameter_m), 44);
        assert_eq!(std::mem::offset_of!(Particle, rotation_rad), 48);
        assert_eq!(std::mem::offset_of!(Particle, water_kg), 60);
        assert_eq!(std::mem::offset_of!(Particle, generation), 64);
        assert_eq!(std::mem::offset_of!(Particle, flags), 68);
    }

    #[test]
    fn flags_round_trip() {
        for kind in [
            ParticleKind::DrySnow,
            ParticleKind::WetSnow,
            ParticleKind::Rain,
        ] {
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
}
