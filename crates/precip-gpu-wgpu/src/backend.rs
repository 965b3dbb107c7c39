//! [`WgpuBackend`]: precip's `Backend` over wgpu — `precip_gpu::GpuBackend` run
//! over [`Hal`], with how a device is opened and how a window surface's texture is
//! drawn into ([`WgpuBackend::render_to`]). Vulkan twin: `precip_gpu_vk::backend`.

use precip_gpu::GpuBackend;
use precip_model::{BackendError, View};

use crate::device::GpuDevice;
use crate::gpu::Hal;

/// precip on wgpu.
#[derive(Debug)]
pub struct WgpuBackend(GpuBackend<Hal>);

precip_gpu::delegate_backend!(WgpuBackend, Hal);

impl WgpuBackend {
    /// Opens a device on the default adapter.
    pub fn new() -> Result<Self, BackendError> {
        Self::with_device(GpuDevice::new_headless()?)
    }

    /// Opens a device on `adapter`.
    pub fn on_adapter(adapter: &wgpu::Adapter) -> Result<Self, BackendError> {
        Self::with_device(GpuDevice::open(adapter)?)
    }

    /// Runs on a device the caller owns (its compute programs are compiled here).
    pub fn with_device(gpu: GpuDevice) -> Result<Self, BackendError> {
        GpuBackend::new(Hal::new(gpu)).map(Self)
    }

    /// The device.
    #[must_use]
    pub fn device(&self) -> &GpuDevice {
        &self.0.gpu().gpu
    }

    /// Draws a frame for `view` into the caller's `target` (a window surface's texture
    /// view, of `view`'s size, made with `RENDER_ATTACHMENT`); the caller presents it.
    /// `read_image` still reads the last offscreen `render`.
    pub fn render_to(
        &mut self,
        view: &View,
        target: &wgpu::TextureView,
    ) -> Result<(), BackendError> {
        let texture = target.texture();
        let size = texture.size();
        if (size.width, size.height) != (view.width_px, view.height_px) {
            return Err(BackendError::InvalidView(format!(
                "the target is {}×{} px but the view asks for {}×{}: give the view the target's size",
                size.width, size.height, view.width_px, view.height_px
            )));
        }
        if !texture
            .usage()
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        {
            return Err(BackendError::InvalidView(
                "the target texture lacks RENDER_ATTACHMENT usage".into(),
            ));
        }
        self.0.draw(view, Some(target))
    }
}
