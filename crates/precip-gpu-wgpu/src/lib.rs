//! precip's [`Backend`](precip_model::Backend) over wgpu.
//!
//! ## Design
//!
//! This crate holds no physics: it runs the WGSL programs of
//! [`precip_gpu::shaders`] in the order of the frame recipe in
//! [`precip_gpu::recipe`], with the uniform blocks precip-model builds. The CPU
//! reference runs the same functions in Rust, so the two can be compared.
//!
//! - [`device`] — finding adapters and opening a device (or adopting the caller's).
//! - [`bind_groups`] — bind group layouts from `precip_gpu::bind_groups`' tables.
//! - [`programs`] — shader modules and compute pipelines (vk: `programs`).
//! - [`resources`] — the buffers and the wind texture of one configuration.
//! - [`query`] — GPU timestamp queries per kernel, where the adapter has them.
//! - [`readback`] — copying a buffer back (tests and tools; never the frame loop).
//! - [`error`] — pure conversions of wgpu errors into [`BackendError`](precip_model::BackendError).
//! - [`render`] — drawing: scene with cover, culling, sprites and tetrahedra, shadows,
//!   fog; offscreen targets and read-back.
//! - [`beams`] — LiDAR beams: the `query_beams` kernel and its read-back.
//! - [`backend`] — [`WgpuBackend`].
//!
//! ## Frames
//!
//! `step(dt)` writes one uniform block per sub-step (a dynamic offset each), records
//! every sub-step's kernels in one compute pass and submits once. Nothing is read
//! back while stepping.

pub mod backend;
pub mod beams;
pub mod bind_groups;
pub mod device;
pub mod error;
pub mod programs;
pub mod query;
pub mod readback;
pub mod render;
pub mod resources;

pub use backend::WgpuBackend;
pub use device::{GpuDevice, adapters};
