//! Presenting to a window on [`VkBackend`]: a backend whose instance has the window
//! system's surface extensions ([`VkBackend::for_display`]), a window attached
//! ([`VkBackend::attach_window`]), then a frame drawn straight into a swapchain image
//! and presented ([`VkBackend::present`]).

use std::sync::Arc;

use ash::vk;
use precip_model::{BackendError, View};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};

use super::VkBackend;
use crate::commands::{Semaphores, submit_synced};
use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::gpu::SwapchainImage;
use crate::instance::Instance;
use crate::swapchain::WindowSurface;
use crate::transfer::FRAMES_IN_FLIGHT;
use precip_gpu::Gpu;
use precip_model::Backend;

/// What [`VkBackend::present`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Presented {
    /// A frame of this size (the swapchain's) went to the window.
    Frame {
        /// Width, px.
        width_px: u32,
        /// Height, px.
        height_px: u32,
    },
    /// The surface was out of date twice in a row (a resize in progress): no frame.
    Skipped,
}

impl VkBackend {
    /// Opens its own instance, with the surface extensions windows of `display` need,
    /// and a device with VK_KHR_swapchain.
    pub fn for_display(
        validation: bool,
        display: &impl HasDisplayHandle,
    ) -> Result<Self, BackendError> {
        let raw = display
            .display_handle()
            .map_err(|e| BackendError::Device {
                backend: NAME,
                message: format!("the display has no usable handle: {e}"),
            })?
            .as_raw();
        let extensions = ash_window::enumerate_required_extensions(raw)
            .map_err(|e| map_vk("finding the display's surface extensions", e))?;
        Self::on(Device::new(Instance::with_extensions(
            validation, extensions,
        )?)?)
    }

    /// Attaches `window` (kept alive by the backend until it is dropped or another
    /// window is attached): [`VkBackend::present`] draws into it.
    pub fn attach_window<W>(&mut self, window: Arc<W>) -> Result<(), BackendError>
    where
        W: HasWindowHandle + HasDisplayHandle + Send + Sync + 'static,
    {
        let surface = WindowSurface::new(&self.0.gpu().device, window)?;
        if let Some(old) = self.1.replace(surface) {
            let hal = self.0.gpu_mut();
            hal.settle()?;
            hal.device.wait_idle()?;
            old.destroy(&hal.device);
        }
        Ok(())
    }

    /// The attached window's swapchain format and present mode.
    #[must_use]
    pub fn window_format(&self) -> Option<(vk::Format, vk::PresentModeKHR)> {
        self.1.as_ref().map(|w| (w.format, w.present_mode))
    }

    /// Draws a frame for `view`'s camera into the attached window and presents it.
    /// The swapchain follows `view`'s size (re-created, the old one retired, when it
    /// changes); the frame has the swapchain's size, which the surface may impose.
    pub fn present(&mut self, view: &View) -> Result<Presented, BackendError> {
        self.weather().map_err(|_| BackendError::NotConfigured {
            operation: "present",
        })?;
        let Some(format) = self.1.as_ref().map(|w| w.format) else {
            return Err(BackendError::NotConfigured {
                operation: "present (attach a window first)",
            });
        };
        precip_model::drawing::render::validate_view(view)?;
        // The acquire semaphore about to be reused was waited on by a frame that is
        // not the latest submission, so this wait finishes it.
        self.0.gpu_mut().wait_until(FRAMES_IN_FLIGHT - 1)?;
        let wanted = (view.width_px, view.height_px);
        for _attempt in 0..2 {
            let (Some(window), hal) = (self.1.as_mut(), self.0.gpu_mut()) else {
                break;
            };
            if window.needs_rebuild(wanted) {
                window.rebuild(&hal.device, wanted, &mut hal.retired, hal.submitted)?;
            }
            let Some(frame) = window.acquire()? else {
                continue;
            };
            let (width_px, height_px) = window.extent().unwrap_or(wanted);
            let sized = View {
                width_px,
                height_px,
                ..*view
            };
            let image = SwapchainImage {
                image: frame.image,
                view: frame.view,
                copyable: frame.copyable,
                format,
                acquired: frame.acquired,
                drawn: frame.drawn,
            };
            let drawn = self.0.draw(&sized, Some(&image));
            if let Err(e) = drawn {
                // The image was acquired but not drawn: consume its acquire semaphore
                // with an empty submission, so the ring can reuse it, and re-create
                // the swapchain next time (the image is never presented).
                let waits = [(frame.acquired, vk::PipelineStageFlags::ALL_COMMANDS)];
                let semaphores = Semaphores {
                    wait: &waits,
                    signal: &[],
                };
                let hal = self.0.gpu_mut();
                if let Ok(f) = submit_synced(&hal.device, semaphores, |_| {}) {
                    hal.track(f);
                }
                if let Some(window) = self.1.as_mut() {
                    window.stale = true;
                }
                return Err(e);
            }
            if let Some(window) = self.1.as_mut() {
                window.present(&self.0.gpu().device, &frame)?;
            }
            return Ok(Presented::Frame {
                width_px,
                height_px,
            });
        }
        Ok(Presented::Skipped)
    }
}
