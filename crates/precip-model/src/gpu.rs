//! What both GPU backends share besides the WGSL: the per-frame recipe (which
//! kernels, in which order, with which bindings and dispatch sizes), as data, so the
//! wgpu and Vulkan backends cannot drift apart; and the uniform blocks not owned by
//! another module.

use bytemuck::{Pod, Zeroable};
use precip_cover::GridFrame;

use crate::shaders::Program;

/// Invocations per workgroup of every kernel (`@workgroup_size(64)`).
pub const WORKGROUP_SIZE: u32 = 64;

/// Most workgroups along one dispatch dimension (WebGPU's guaranteed minimum).
pub const MAX_WORKGROUPS_PER_DIMENSION: u32 = 65_535;

/// The two grids the particle kernels read.
///
/// WGSL twin: `Frames` in `shaders/layout.wgsl` (64 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Frames {
    /// The ground height map's grid.
    pub ground: GridFrame,
    /// The cover grid (deposit texels).
    pub cover: GridFrame,
}
const _: () = assert!(size_of::<Frames>() == 64);

/// Workgroups `(x, y)` covering `count` invocations in a 2D dispatch (WGSL:
/// `linear_index`), so counts beyond 65535 × 64 fit.
#[must_use]
pub fn dispatch_size(count: u32) -> (u32, u32) {
    let groups = count.div_ceil(WORKGROUP_SIZE).max(1);
    if groups <= MAX_WORKGROUPS_PER_DIMENSION {
        (groups, 1)
    } else {
        let y = groups.div_ceil(MAX_WORKGROUPS_PER_DIMENSION);
        (groups.div_ceil(y), y)
    }
}

/// What a kernel is dispatched over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DispatchOver {
    /// One invocation per particle.
    Particles,
    /// One invocation per cover texel.
    CoverTexels,
}

/// One kernel of the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KernelPass {
    /// The program it is in.
    pub program: Program,
    /// Its entry point.
    pub entry_point: &'static str,
    /// Its dispatch.
    pub over: DispatchOver,
}

/// Initialisation (configure): pre-warmed particles.
pub const INIT_PASS: KernelPass = KernelPass {
    program: Program::StepParticles,
    entry_point: "init_particles",
    over: DispatchOver::Particles,
};

/// One sub-step, in order: the particles move and deposit (marking those to re-birth),
/// the marked ones are re-born, then the cover takes the deposits (or the rate),
/// melts and ages. Sub-steps repeat this with their own uniform blocks (dynamic
/// offsets).
pub const SUBSTEP_PASSES: [KernelPass; 3] = [
    KernelPass {
        program: Program::StepParticles,
        entry_point: "step_particles",
        over: DispatchOver::Particles,
    },
    KernelPass {
        program: Program::StepParticles,
        entry_point: "birth_particles",
        over: DispatchOver::Particles,
    },
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "cover_update",
        over: DispatchOver::CoverTexels,
    },
];

/// Bindings of [`Program::StepParticles`], group 0.
pub mod step_bindings {
    /// `StepParams`, uniform, dynamic offset.
    pub const STEP_PARAMS: u32 = 0;
    /// `Frames`, uniform.
    pub const FRAMES: u32 = 1;
    /// `WindParams`, uniform.
    pub const WIND: u32 = 2;
    /// The wind volume, `texture_3d<f32>` (`Rgba32Float`, read with `textureLoad`).
    pub const WIND_VOLUME: u32 = 3;
    /// Ground heights, `array<f32>`, read-only storage.
    pub const GROUND_HEIGHT: u32 = 4;
    /// Particles, `array<Particle>`, read-write storage.
    pub const PARTICLES: u32 = 5;
    /// Deposits, `array<atomic<u32>>`, read-write storage.
    pub const DEPOSITS: u32 = 6;
}

/// Bindings of [`Program::CoverUpdate`], group 0.
pub mod cover_bindings {
    /// `CoverStepParams`, uniform, dynamic offset.
    pub const COVER_PARAMS: u32 = 0;
    /// Cover texels, read-write storage.
    pub const COVER: u32 = 1;
    /// Deposits, read-write storage.
    pub const DEPOSITS: u32 = 2;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kernel_of_the_recipe_is_an_entry_point_of_its_program() {
        for kernel in SUBSTEP_PASSES.iter().chain([&INIT_PASS]) {
            assert!(
                kernel.program.entry_points().contains(&kernel.entry_point),
                "{kernel:?}"
            );
        }
        let in_recipe = |name: &str| {
            SUBSTEP_PASSES
                .iter()
                .chain([&INIT_PASS])
                .any(|k| k.entry_point == name)
        };
        for program in [Program::StepParticles, Program::CoverUpdate] {
            for name in program.entry_points() {
                assert!(in_recipe(name), "{name} of {program:?} is never dispatched");
            }
        }
    }

    #[test]
    fn dispatch_covers_every_count() {
        for count in [
            0u32, 1, 64, 65, 4_194_240, 4_194_241, 10_000_000, 67_108_864,
        ] {
            let (x, y) = dispatch_size(count);
            assert!(x <= MAX_WORKGROUPS_PER_DIMENSION && y <= MAX_WORKGROUPS_PER_DIMENSION);
            assert!(
                u64::from(x) * u64::from(y) * 64 >= u64::from(count),
                "{count}"
            );
        }
    }
}
