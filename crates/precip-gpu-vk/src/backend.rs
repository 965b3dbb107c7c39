//! [`VkBackend`]: precip's `Backend` on raw Vulkan — `precip_gpu::GpuBackend` run
//! over [`Hal`], with how a device is opened (its own instance, a display's, or the
//! caller's device) and how a frame goes to a window ([`present`]). wgpu twin:
//! `precip_gpu_wgpu::backend`.
//!
//! ## Submissions
//!
//! Steps and frames are submitted without waiting ([`crate::gpu`]); at most
//! `FRAMES_IN_FLIGHT` are pending when the next one writes its uniform blocks.

use precip_gpu::{Gpu, GpuBackend};
use precip_model::BackendError;

use crate::device::Device;
use crate::gpu::Hal;
use crate::instance::Instance;

mod present;

pub use present::Presented;

/// precip on Vulkan.
#[derive(Debug)]
pub struct VkBackend(GpuBackend<Hal>, Option<crate::swapchain::WindowSurface>);

precip_gpu::delegate_backend!(VkBackend, Hal);

impl VkBackend {
    /// Opens its own instance (with the validation layer when `validation`) and
    /// device.
    pub fn new(validation: bool) -> Result<Self, BackendError> {
        Self::on(Device::new(Instance::new(validation)?)?)
    }

    fn on(device: Device) -> Result<Self, BackendError> {
        Ok(Self(GpuBackend::new(Hal::new(device)?)?, None))
    }

    /// Runs on a device the caller owns (an engine's renderer): precip makes its
    /// own allocator and command pool on it and destroys only those.
    ///
    /// # Safety
    /// `external` must hold live objects created from one another as its fields say,
    /// the queue must not be used by another thread while precip submits, and the
    /// device and instance must outlive the backend.
    pub unsafe fn on_external_device(
        external: crate::device::ExternalDevice,
    ) -> Result<Self, BackendError> {
        // SAFETY: the caller's guarantees are `Device::external`'s.
        let device = unsafe { Device::external(external) }?;
        Self::on(device)
    }

    fn hal(&self) -> &Hal {
        self.0.gpu()
    }

    /// The validation layer's messages since the last call (empty without it).
    #[must_use]
    pub fn validation_messages(&self) -> Vec<String> {
        self.hal().device.instance.take_messages()
    }

    /// The validation layer's log, shared (tests read it after the backend is gone).
    #[must_use]
    pub fn validation_log(&self) -> crate::Messages {
        self.hal().device.instance.messages.clone()
    }

    /// The device (tests inside the crate).
    #[cfg(test)]
    #[must_use]
    pub(crate) fn device(&self) -> &Device {
        &self.hal().device
    }

    /// The device's name.
    #[must_use]
    pub fn device_name(&self) -> String {
        self.hal().device.name_of_device()
    }
}

impl Drop for VkBackend {
    /// The window's swapchain and surface go before the device.
    fn drop(&mut self) {
        let hal = self.0.gpu_mut();
        let _ = hal.settle();
        let _ = hal.device.wait_idle();
        hal.retired.release_all(&hal.device);
        if let Some(window) = self.1.take() {
            window.destroy(&self.0.gpu().device);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::VkBackend;

    #[test]
    fn the_messenger_reports_a_misuse() {
        // A negative control: the validation-clean checks of the tests mean something
        // only if a real validation error reaches the log.
        let vk = match VkBackend::new(true) {
            Ok(vk) => vk,
            Err(e) => {
                assert!(
                    std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
                    "PRECIP_REQUIRE_GPU=1 but {e}"
                );
                eprintln!("SKIPPED the_messenger_reports_a_misuse: {e}");
                return;
            }
        };
        let device = &vk.device().raw;
        let info = ash::vk::BufferCreateInfo::default()
            .size(0)
            .usage(ash::vk::BufferUsageFlags::STORAGE_BUFFER);
        // SAFETY: deliberately invalid (size 0) to provoke the validation layer;
        // lavapipe still returns a handle or an error, and either is cleaned up here.
        let made = unsafe { device.create_buffer(&info, None) };
        if let Ok(buffer) = made {
            // SAFETY: the buffer is unused and destroyed once.
            unsafe { device.destroy_buffer(buffer, None) };
        }
        let messages = vk.validation_messages();
        assert!(
            messages.iter().any(|m| m.contains("size")),
            "the layer should report a zero-size buffer: {messages:?}"
        );
    }
}
