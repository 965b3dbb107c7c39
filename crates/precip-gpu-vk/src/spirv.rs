//! The SPIR-V the build script compiled from precip-gpu's WGSL programs (one module per
//! program, every entry point in it).

use precip_gpu::shaders::Program;

include!(concat!(env!("OUT_DIR"), "/spirv_table.rs"));

/// The SPIR-V words of `program`, or `None` for programs this backend does not run.
#[must_use]
pub fn words(program: Program) -> Option<Vec<u32>> {
    let bytes = spirv_bytes(program)?;
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
        let mut compiled = 0;
        for program in Program::ALL {
            let Some(w) = words(program) else { continue };
            compiled += 1;
            assert_eq!(w[0], 0x0723_0203, "{program:?}");
        }
        assert_eq!(
            compiled,
            Program::ALL.len() - 2,
            "all but the drawing and ocean probes"
        );
    }
}
