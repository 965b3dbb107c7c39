//! precip's GPU work as data, shared by every GPU backend (`precip-gpu-wgpu`,
//! `precip-gpu-vk`). It holds no physics: the formulas live in `precip-model`,
//! `precip-wind` and `precip-cover`, each once in Rust and once in WGSL beside it.
//!
//! ## Map
//!
//! - [`shaders`]: the GPU programs, each the concatenation of WGSL files read from
//!   the crates of their Rust twins (`precip_model::wgsl`, `precip_wind::wgsl`,
//!   `precip_cover::wgsl`) and this crate's GPU-only files (`shaders/`: culling,
//!   splatting, the render passes, the cover's textures, test probes).
//! - [`bind_groups`]: every program's bind-group layouts as tables, from which each
//!   backend makes its layouts; [`binding_limits`]: what they need of a device,
//!   checked when a backend is made on one.
//! - [`recipe`]: the kernels of configure (`INIT_PASS`), of one sub-step
//!   (`SUBSTEP_PASSES`) and of the frame's compute passes, what each is dispatched
//!   over, the bindings' numbers, the buffers' byte sizes and the blocks the kernels
//!   write (`FrameDraws`).
//! - [`resources`]: the resources table of a configuration (every buffer with its
//!   size rule, usage and initial contents) and what fills each binding.
//! - [`gpu`]: [`Gpu`], the device calls a backend implements (buffers, textures,
//!   layouts, kernels, bind groups, dispatch, read-back, timestamps).
//! - [`executor`]: the plan run over a [`Gpu`], once for every backend:
//!   [`Kernels`] (a device's compute programs) and [`Simulation`] (configure,
//!   weather change, step, beam query, read-backs).
//! - [`frame`]: the frame as data: its passes in order, each a list of kernels or a
//!   render pass (attachments, draws and their pipeline state), and when it runs.
//!
//! The host state and the uniform blocks come from `precip_model::host`.
//! `docs/architecture.md` describes how a backend executes this plan, and the
//! walkthroughs for a new kernel, render pass or precipitation kind.
//!
//! # Example
//!
//! The plan is data a program can read: a sub-step's kernels, the frame's passes
//! and when each runs, and every program's WGSL, joined from the twins' files.
//!
//! ```
//! use precip_gpu::frame::FRAME_PASSES;
//! use precip_gpu::recipe::SUBSTEP_PASSES;
//! use precip_gpu::shaders::Program;
//!
//! // A sub-step moves the particles first.
//! assert_eq!(SUBSTEP_PASSES[1].entry_point, "step_particles");
//! for pass in &FRAME_PASSES {
//!     println!("{:>16}: {:?}", pass.name, pass.when);
//! }
//! let step = Program::StepParticles;
//! let wgsl = step.source();
//! assert!(step.entry_points().contains(&"birth_particles"));
//! assert!(wgsl.contains("// ---- kind.wgsl ----")); // the kinds' table is joined in
//! ```

pub mod backend;
pub mod bind_groups;
pub mod binding_limits;
pub mod executor;
pub mod frame;
pub mod frame_resources;
pub mod gpu;
pub mod recipe;
pub mod renderer;
pub mod resources;
pub mod scene;
pub mod shaders;

pub use backend::GpuBackend;
pub use executor::{Kernels, Prepared, Simulation};
pub use gpu::{BindingResource, Dispatch, Gpu};
pub use shaders::Program;
