//! precip's [`Backend`](precip_model::Backend) over wgpu.
//!
//! ## Design
//!
//! This crate holds no physics, no plan and no frame: `precip_gpu::GpuBackend`
//! runs configure, weather changes, steps, beam queries and frames over
//! [`gpu::Hal`], the device calls of `precip_gpu::Gpu` on wgpu. The Vulkan backend
//! (`precip-gpu-vk`) has the same files with the same jobs.
//!
//! # Example
//!
//! Snow over flat ground, a second of it, one frame read back (without an adapter
//! it says so and stops):
//!
//! ```
//! use precip_gpu_wgpu::WgpuBackend;
//! use precip_model::{Backend, Setup, View};
//!
//! # fn main() -> Result<(), precip_model::BackendError> {
//! let mut setup = Setup::over_flat_ground(20.0, 16, 8.0, 2_000);
//! setup.weather.intensity_mm_per_h = 2.0; // mm/h of water, dry snow at −5 °C
//! let mut gpu = match WgpuBackend::new() {
//!     Ok(gpu) => gpu,
//!     Err(e) => {
//!         println!("no GPU here: {e}");
//!         return Ok(());
//!     }
//! };
//! gpu.configure(&setup)?;
//! for _ in 0..30 {
//!     gpu.step(1.0 / 30.0)?;
//! }
//! gpu.render(&View { camera: setup.camera, width_px: 64, height_px: 36 })?;
//! let image = gpu.read_image()?;
//! assert_eq!(image.rgba8.len(), 64 * 36 * 4);
//! # Ok(())
//! # }
//! ```
//!
//! - [`device`] — finding adapters and opening a device (or adopting the caller's).
//! - [`bind_groups`] — bind group layouts from `precip_gpu::bind_groups`' tables.
//! - [`gpu`] — [`gpu::Hal`]: buffers, textures, samplers, layouts, kernels, draw
//!   pipelines, bind groups, dispatches, frames, read-back.
//! - [`frame`] — a frame's commands into wgpu compute and render passes.
//! - [`pipelines`] — render pipelines from the frame's draws.
//! - [`query`] — GPU timestamp queries per kernel and per pass, where the adapter
//!   has them.
//! - [`transfer`] — copying a buffer or texture back (read-backs, tests and tools;
//!   never the frame loop).
//! - [`error`] — pure conversions of wgpu errors into [`BackendError`](precip_model::BackendError).
//! - [`backend`] — [`WgpuBackend`]: opening a device, drawing into a window surface.
//!
//! ## Frames
//!
//! `step(dt)` writes one uniform block per sub-step (a dynamic offset each), records
//! every sub-step's kernels in one compute pass and submits once; `render` writes
//! the frame's block and submits the frame's passes in one command buffer, each
//! pass timed where the adapter can. Nothing is read back while stepping or drawing.

pub mod backend;
pub mod bind_groups;
pub mod device;
pub mod error;
pub mod frame;
pub mod gpu;
pub mod pipelines;
pub mod query;
pub mod transfer;

pub use backend::WgpuBackend;
pub use device::{GpuDevice, adapters};
