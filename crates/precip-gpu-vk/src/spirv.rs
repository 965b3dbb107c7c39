//! The SPIR-V the build script compiled from precip-gpu's WGSL programs (one module per
//! program, every entry point in it).

use precip_gpu::shaders::Program;

/// The programs the build script compiles.
#[cfg(test)]
pub const COMPILED: [Program; 7] = include!("compiled_programs.in");

/// The SPIR-V words of `program`, or `None` for programs this backend does not run.
#[must_use]
pub fn words(program: Program) -> Option<Vec<u32>> {
    let bytes: &[u8] = match program {
        Program::StepParticles => include_bytes!(concat!(env!("OUT_DIR"), "/StepParticles.spv")),
        Program::CoverUpdate => include_bytes!(concat!(env!("OUT_DIR"), "/CoverUpdate.spv")),
        Program::ProbeRng => include_bytes!(concat!(env!("OUT_DIR"), "/ProbeRng.spv")),
        Program::Render => include_bytes!(concat!(env!("OUT_DIR"), "/Render.spv")),
        Program::CullParticles => include_bytes!(concat!(env!("OUT_DIR"), "/CullParticles.spv")),
        Program::QueryBeams => include_bytes!(concat!(env!("OUT_DIR"), "/QueryBeams.spv")),
        Program::OpticsSums => include_bytes!(concat!(env!("OUT_DIR"), "/OpticsSums.spv")),
        Program::ProbeDrawing => return None,
    };
    Some(
        bytes
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_module_starts_with_the_spirv_magic() {
        for program in COMPILED {
            let w = words(program).expect("compiled");
            assert_eq!(w[0], 0x0723_0203, "{program:?}");
        }
    }
}
