//! precip's [`Backend`](precip_model::Backend) over wgpu.
//!
//! ## Design
//!
//! This crate holds no physics and no plan: the executor of `precip-gpu`
//! (`precip_gpu::Simulation`) makes a configuration's resources from its tables and
//! runs configure, weather changes, steps and beam queries over [`gpu::Hal`]; the
//! frame's passes ([`precip_gpu::frame`]) are recorded by [`render`]. The uniform
//! blocks come from `precip_model::host::HostState`.
//!
//! - [`device`] — finding adapters and opening a device (or adopting the caller's).
//! - [`bind_groups`] — bind group layouts from `precip_gpu::bind_groups`' tables.
//! - [`gpu`] — [`gpu::Hal`], the device calls of `precip_gpu::Gpu`: buffers, the
//!   wind volume, layouts, kernels, bind groups, dispatches, read-back; the
//!   executor of `precip-gpu` runs configure, weather, step and beam queries over it.
//! - [`query`] — GPU timestamp queries per kernel, where the adapter has them.
//! - [`transfer`] — copying a buffer back (tests and tools; never the frame loop).
//! - [`error`] — pure conversions of wgpu errors into [`BackendError`](precip_model::BackendError).
//! - [`render`] — drawing: scene with cover, culling, sprites and tetrahedra, shadows,
//!   fog; offscreen targets and read-back.
//! - [`backend`] — [`WgpuBackend`].
//!
//! ## Frames
//!
//! `step(dt)` writes one uniform block per sub-step (a dynamic offset each), records
//! every sub-step's kernels in one compute pass and submits once (the executor's
//! recipe; `precip_gpu::Gpu::dispatch` on [`gpu::Hal`] records it). Nothing is read back while stepping.

pub mod backend;
pub mod bind_groups;
pub mod device;
pub mod error;
pub mod gpu;
pub mod query;
pub mod render;
pub mod transfer;

pub use backend::WgpuBackend;
pub use device::{GpuDevice, adapters};
