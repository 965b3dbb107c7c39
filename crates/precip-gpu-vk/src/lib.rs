//! precip's [`Backend`](precip_model::Backend) on raw Vulkan (ash 0.38 +
//! gpu-allocator), for engines that own a `VkDevice` and for the lowest overhead.
//!
//! ## Design
//!
//! The same WGSL as every backend: the build script compiles precip-model's programs
//! to SPIR-V with naga; the kernels, their order, bindings and dispatch sizes come
//! from `precip_model::gpu`, so this backend and the wgpu one cannot drift apart.
//! One file per Vulkan concept, in the spirit of wgpu-hal's `vulkan/` and kajiya:
//!
//! - [`instance`] — loader, validation layer, debug messenger (messages kept).
//! - [`device`] — physical device choice, queue, allocator, command pool.
//! - [`buffer`], [`image`] — memory through gpu-allocator.
//! - [`commands`] — submission with a fence, one in flight; compute barriers.
//! - [`spirv`], [`programs`] — modules, set and pipeline layouts, compute pipelines.
//! - [`resources`] — one configuration's buffers, wind volume, descriptor sets, uploads.
//! - [`query`] — timestamps per kernel.
//! - [`error`] — pure `vk::Result` → `BackendError` conversions.
//! - [`backend`] — [`VkBackend`].
//!
//! ## State
//!
//! The simulation runs (configure, weather, camera, step, read-back, timings), on
//! precip's own device or the caller's ([`VkBackend::on_external_device`]), with the
//! validation layer clean in tests. Rendering and swapchains are still to come:
//! `render` and `read_image` return `NotSupported`.

#![expect(
    unsafe_code,
    reason = "raw Vulkan through ash is unsafe by nature; every block says why it is sound (// SAFETY:)"
)]

pub mod backend;
pub mod buffer;
pub mod commands;
pub mod device;
pub mod error;
pub mod image;
pub mod instance;
pub mod programs;
pub mod query;
pub mod render;
pub mod resources;
pub mod retire;
pub mod spirv;

pub use backend::VkBackend;
