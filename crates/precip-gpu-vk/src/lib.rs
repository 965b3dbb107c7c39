//! precip's [`Backend`](precip_model::Backend) on raw Vulkan (ash 0.38 +
//! gpu-allocator), for engines that own a `VkDevice` and for the lowest overhead.
//!
//! ## Design
//!
//! The same WGSL as every backend: the build script compiles precip-gpu's programs
//! to SPIR-V with naga. What a configuration allocates, how it is bound, what
//! configure, a weather change, a step, a beam query and a frame run is
//! `precip_gpu::GpuBackend`'s, over this crate's `gpu` calls, as on wgpu, so the
//! two cannot drift apart.
//! One file per Vulkan concept, in the spirit of wgpu-hal's `vulkan/` and kajiya:
//!
//! - `instance` — loader, validation layer, debug messenger (messages kept).
//! - `device` — physical device choice, queue, allocator, command pool.
//! - `buffer`, `image` — memory through gpu-allocator.
//! - `commands` — submissions behind fences (with semaphores for a swapchain);
//!   barriers.
//! - `descriptors` — pools sized for their sets, allocation, write infos.
//! - `spirv`, `programs` — modules, pipeline layouts, compute pipelines.
//! - `pipelines` — graphics pipelines from the frame's draws.
//! - `gpu` — `Hal`, the device calls of `precip_gpu::Gpu` (wgpu twin:
//!   `precip_gpu_wgpu::gpu`), and the submissions in flight.
//! - `transfer` — uploads, read-backs, image fills and layout changes, each
//!   waited for (a configuration's).
//! - `uploads` — the frames' writes of device-local buffers, staged and carried by
//!   the next submission (what wgpu's queue does for wgpu).
//! - `query` — timestamps per kernel and per pass.
//! - `frame` — a frame's commands into a command buffer: render passes,
//!   framebuffers, layouts, barriers.
//! - `swapchain` — a window's surface and swapchain (raw-window-handle, ash-window).
//! - `retire` — deferred release of objects in-flight work may still use.
//! - `error` — pure `vk::Result` → `BackendError` conversions.
//! - `backend` — [`VkBackend`].
//!
//! ## Public surface
//!
//! The modules are the crate's own: what a caller gets is [`VkBackend`] (the
//! `Backend`, presentation into a window: [`Presented`]), the
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
//!
//! # Example
//!
//! Rain over flat ground on precip's own Vulkan device, one frame read back
//! (without a Vulkan device it says so and stops):
//!
//! ```
//! use precip_gpu_vk::VkBackend;
//! use precip_model::{Backend, PrecipitationKind, Setup, View};
//!
//! # fn main() -> Result<(), precip_model::BackendError> {
//! let mut setup = Setup::over_flat_ground(20.0, 16, 8.0, 2_000);
//! setup.weather.kind = PrecipitationKind::Rain;
//! setup.weather.air_temperature_c = 12.0;
//! setup.weather.intensity_mm_per_h = 8.0;
//! let mut vk = match VkBackend::new(false) {
//!     Ok(vk) => vk,
//!     Err(e) => {
//!         println!("no Vulkan device here: {e}");
//!         return Ok(());
//!     }
//! };
//! vk.configure(&setup)?;
//! vk.step(0.5)?;
//! vk.render(&View { camera: setup.camera, width_px: 64, height_px: 36 })?;
//! assert_eq!(vk.read_image()?.rgba8.len(), 64 * 36 * 4);
//! # Ok(())
//! # }
//! ```

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
mod frame;
mod gpu;
mod image;
mod instance;
mod pipelines;
mod programs;
mod query;
mod retire;
mod spirv;
mod swapchain;
mod transfer;
mod uploads;

pub use backend::{Presented, VkBackend};
pub use device::ExternalDevice;
pub use instance::{Instance, Messages};
