//! precip's [`Backend`](precip_model::Backend) on raw Vulkan (ash 0.38 +
//! gpu-allocator), for engines that own a `VkDevice` and for the lowest overhead.
//!
//! ## Design
//!
//! The same WGSL as every backend: the build script compiles precip-gpu's programs
//! to SPIR-V with naga. What a configuration allocates, how it is bound and what
//! configure, a weather change, a step and a beam query run is the executor's
//! (`precip_gpu::Simulation`), over this crate's [`gpu`] calls, as on wgpu; the
//! frame's passes come from `precip_gpu::frame`, so the two cannot drift apart.
//! One file per Vulkan concept, in the spirit of wgpu-hal's `vulkan/` and kajiya:
//!
//! - [`instance`] — loader, validation layer, debug messenger (messages kept).
//! - [`device`] — physical device choice, queue, allocator, command pool.
//! - [`buffer`], [`image`] — memory through gpu-allocator.
//! - [`commands`] — submissions behind fences (with semaphores for a swapchain);
//!   barriers.
//! - [`descriptors`] — pools sized for their sets, allocation, write infos.
//! - [`spirv`], [`programs`] — modules, pipeline layouts, compute pipelines.
//! - [`gpu`] — `Hal`, the device calls of `precip_gpu::Gpu` (wgpu twin:
//!   `precip_gpu_wgpu::gpu`), and the submissions in flight.
//! - [`transfer`] — uploads, read-backs, image fills and layout changes.
//! - [`query`] — timestamps per kernel.
//! - [`render`] — drawing: layouts, render passes, pipelines, samplers, the scene,
//!   the frame's resources, offscreen targets, timestamps per pass, the frame's
//!   command recording.
//! - [`swapchain`] — a window's surface and swapchain (raw-window-handle, ash-window).
//! - [`retire`] — deferred release of objects in-flight work may still use.
//! - [`error`] — pure `vk::Result` → `BackendError` conversions.
//! - [`backend`] — [`VkBackend`].
//!
//! ## Public surface
//!
//! The modules are the crate's own: what a caller gets is [`VkBackend`] (the
//! `Backend`, presentation into a window: [`Presented`], [`SwapchainFrame`]), the
//! external-device handshake ([`ExternalDevice`], `VkBackend::on_external_device`),
//! and [`Instance`] with its validation [`Messages`]. No raw handle of precip's own
//! device leaves the crate.

//! ## State
//!
//! Everything the wgpu backend does — simulation, rendering offscreen with
//! read-back — plus presenting straight into a window's swapchain
//! ([`VkBackend::for_display`], [`VkBackend::attach_window`], [`VkBackend::present`]),
//! on precip's own device or the caller's ([`VkBackend::on_external_device`]; an
//! engine's device renders offscreen, its engine presents). The validation layer is
//! clean in every test, and the frames equal wgpu's bit for bit on lavapipe.

#![expect(
    unsafe_code,
    reason = "raw Vulkan through ash is unsafe by nature; every block says why it is sound (// SAFETY:)"
)]

mod backend;
mod bind_groups;
mod buffer;
mod commands;
mod descriptors;
mod device;
mod error;
mod gpu;
mod image;
mod instance;
mod programs;
mod query;
mod render;
mod retire;
mod spirv;
mod swapchain;
mod transfer;

pub use backend::{Presented, SwapchainFrame, VkBackend};
pub use device::ExternalDevice;
pub use instance::{Instance, Messages};
