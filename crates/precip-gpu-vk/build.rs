//! Compiles precip-gpu's WGSL programs to SPIR-V with naga (docs/architecture.md §4: WGSL is the
//! single source). One `.spv` per program in OUT_DIR, all entry points in each.
//!
//! Bounds checks: those wgpu compiles in ([`BOUNDS_CHECKS`]).
//!
//! Clip space is WGSL's (y up); the renderer flips it with a negative viewport
//! height (Vulkan 1.1), as wgpu does, so the shaders are written without a flip.

use naga::back::spv;
use naga::valid::{Capabilities, ValidationFlags, Validator};
use precip_gpu::shaders::Program;

/// The bounds checks wgpu compiles into the same WGSL on a Vulkan device without the
/// robustness extensions (wgpu-hal's `vulkan/adapter.rs`): array indices clamped,
/// buffer and image reads restricted to their resource. Decided here, not per device,
/// because the SPIR-V is compiled once at build time; so an out-of-range index reads
/// a valid element on every driver, as it does under wgpu.
const BOUNDS_CHECKS: naga::proc::BoundsCheckPolicies = naga::proc::BoundsCheckPolicies {
    index: naga::proc::BoundsCheckPolicy::Restrict,
    buffer: naga::proc::BoundsCheckPolicy::Restrict,
    image_load: naga::proc::BoundsCheckPolicy::Restrict,
    binding_array: naga::proc::BoundsCheckPolicy::Unchecked,
};

/// Programs this backend never runs: the drawing and ocean probes are wgpu test
/// kernels.
const NOT_ON_VULKAN: [Program; 2] = [Program::ProbeDrawing, Program::ProbeOcean];

fn main() {
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    // Every program of precip-gpu's plan but those this backend never runs, and a
    // table from each to its SPIR-V for `src/spirv.rs`: a new program needs nothing
    // here.
    let mut table = String::from(
        "// Written by build.rs: each program this backend runs, and its SPIR-V.\n\
         fn spirv_bytes(program: Program) -> Option<&'static [u8]> {\n    match program {\n",
    );
    for program in Program::ALL
        .into_iter()
        .filter(|p| !NOT_ON_VULKAN.contains(p))
    {
        table.push_str(&format!(
            "        Program::{program:?} => Some(include_bytes!(concat!(env!(\"OUT_DIR\"), \"/{program:?}.spv\"))),\n"
        ));
        let source = program.source();
        let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| {
            panic!("{program:?}: {}", e.emit_to_string(&source));
        });
        let info = Validator::new(ValidationFlags::all(), Capabilities::empty())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{program:?}: {}", e.emit_to_string(&source)));
        let options = spv::Options {
            lang_version: (1, 0),
            flags: spv::WriterFlags::empty(),
            bounds_check_policies: BOUNDS_CHECKS,
            ..spv::Options::default()
        };
        let words = spv::write_vec(&module, &info, &options, None)
            .unwrap_or_else(|e| panic!("{program:?}: SPIR-V: {e}"));
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        std::fs::write(out.join(format!("{program:?}.spv")), bytes).expect("write SPIR-V");
    }
    table.push_str("        _ => None,\n    }\n}\n");
    std::fs::write(out.join("spirv_table.rs"), table).expect("write the SPIR-V table");
    for shaders in [
        "../precip-model/shaders",
        "../precip-wind/shaders",
        "../precip-cover/shaders",
        "../precip-gpu/shaders",
    ] {
        println!("cargo:rerun-if-changed={shaders}");
    }
}
