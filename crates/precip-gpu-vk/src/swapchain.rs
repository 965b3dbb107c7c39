//! A window's surface and swapchain (through raw-window-handle and ash-window): the
//! images and their views (the renderer draws into one with its own depth buffer),
//! the semaphores of acquire and present, and re-creation when the window's size changes or the
//! surface goes out of date. Replaced objects are retired, not waited for.
//!
//! Semaphores: acquire uses a ring of [`ACQUIRE_SEMAPHORES`] (a frame is submitted
//! only when at most one submission is pending, so the one used two frames ago has
//! been waited on); each image has its own "drawn" semaphore that its present waits
//! on, reused only when the image comes back from acquire.

use std::any::Any;
use std::sync::Arc;

use ash::vk;
use precip_model::BackendError;
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};

use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::retire::Retired;

/// Acquire semaphores in the ring.
pub const ACQUIRE_SEMAPHORES: usize = 3;

/// The images of one swapchain.
struct Chain {
    raw: vk::SwapchainKHR,
    images: Vec<vk::Image>,
    views: Vec<vk::ImageView>,
    /// Its images can be copied from (`TRANSFER_SRC`, where the surface allows it).
    copyable: bool,
    drawn: Vec<vk::Semaphore>,
    extent: (u32, u32),
}

impl Chain {
    fn destroy(self, device: &Device, loader: &ash::khr::swapchain::Device) {
        // SAFETY: no pending work uses these (the caller waited or retired them);
        // each is destroyed once, the swapchain after its views.
        unsafe {
            for v in self.views {
                device.raw.destroy_image_view(v, None);
            }
            for s in self.drawn {
                device.raw.destroy_semaphore(s, None);
            }
            loader.destroy_swapchain(self.raw, None);
        }
    }
}

/// A window's surface and its current swapchain.
pub struct WindowSurface {
    surface_loader: ash::khr::surface::Instance,
    loader: ash::khr::swapchain::Device,
    surface: vk::SurfaceKHR,
    chain: Option<Chain>,
    /// The swapchain's colour format.
    pub format: vk::Format,
    acquire: Vec<vk::Semaphore>,
    next_acquire: usize,
    /// The present mode in use.
    pub present_mode: vk::PresentModeKHR,
    /// Whether the next frame must re-create the swapchain first.
    pub stale: bool,
    /// The size the swapchain was last made for (the surface may have imposed
    /// another).
    requested: Option<(u32, u32)>,
    /// Keeps the window alive as long as the surface.
    _window: Arc<dyn Any + Send + Sync>,
}

impl std::fmt::Debug for WindowSurface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WindowSurface")
            .field("format", &self.format)
            .field("extent", &self.extent())
            .field("present_mode", &self.present_mode)
            .finish_non_exhaustive()
    }
}

/// The frame [`WindowSurface::acquire`] got.
#[derive(Debug, Clone, Copy)]
pub struct Acquired {
    /// The image's index.
    pub index: u32,
    /// The image.
    pub image: vk::Image,
    /// Its view.
    pub view: vk::ImageView,
    /// It can be copied from.
    pub copyable: bool,
    /// Signalled when it is ready to draw into.
    pub acquired: vk::Semaphore,
    /// To signal when it is drawn (present waits on it).
    pub drawn: vk::Semaphore,
}

fn semaphore(device: &Device) -> Result<vk::Semaphore, BackendError> {
    // SAFETY: a valid device.
    unsafe {
        device
            .raw
            .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
    }
    .map_err(|e| map_vk("creating a semaphore", e))
}

/// The surface format to draw into: an sRGB RGBA or BGRA format if there is one (the
/// frame's colours are linear, as in the offscreen target), else the first.
#[must_use]
pub fn pick_format(formats: &[vk::SurfaceFormatKHR]) -> Option<vk::SurfaceFormatKHR> {
    formats
        .iter()
        .find(|f| {
            matches!(
                f.format,
                vk::Format::B8G8R8A8_SRGB | vk::Format::R8G8B8A8_SRGB
            ) && f.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR
        })
        .or_else(|| formats.first())
        .copied()
}

/// The swapchain's size: the surface's own when it has one, else `wanted` within
/// the surface's limits.
#[must_use]
pub fn pick_extent(caps: &vk::SurfaceCapabilitiesKHR, wanted: (u32, u32)) -> (u32, u32) {
    if caps.current_extent.width != u32::MAX {
        return (caps.current_extent.width, caps.current_extent.height);
    }
    (
        wanted
            .0
            .clamp(caps.min_image_extent.width, caps.max_image_extent.width),
        wanted
            .1
            .clamp(caps.min_image_extent.height, caps.max_image_extent.height),
    )
}

impl WindowSurface {
    /// A surface for `window` on `device` (whose instance has the window system's
    /// surface extensions and whose device has VK_KHR_swapchain).
    pub fn new<W>(device: &Device, window: Arc<W>) -> Result<Self, BackendError>
    where
        W: HasWindowHandle + HasDisplayHandle + Send + Sync + 'static,
    {
        if !device.swapchain {
            return Err(BackendError::NotSupported {
                backend: NAME,
                operation: "presenting to a window (the device lacks VK_KHR_swapchain, or is an engine's: present through the engine)",
            });
        }
        let handle_error = |e: raw_window_handle::HandleError| BackendError::Device {
            backend: NAME,
            message: format!("the window has no usable handle: {e}"),
        };
        let display = window.display_handle().map_err(handle_error)?.as_raw();
        let handle = window.window_handle().map_err(handle_error)?.as_raw();
        let instance = &device.instance;
        // SAFETY: the handles are live (the window is kept alive by `_window` for as
        // long as the surface), and the instance was created with the extensions
        // this display needs.
        let surface = unsafe {
            ash_window::create_surface(&instance.entry, &instance.raw, display, handle, None)
        }
        .map_err(|e| map_vk("creating the window's surface", e))?;
        let surface_loader = ash::khr::surface::Instance::new(&instance.entry, &instance.raw);
        // SAFETY: the surface and physical device are live.
        let supported = unsafe {
            surface_loader.get_physical_device_surface_support(
                device.physical,
                device.queue_family,
                surface,
            )
        };
        let formats = supported.and_then(|ok| {
            if ok {
                // SAFETY: as above.
                unsafe {
                    surface_loader.get_physical_device_surface_formats(device.physical, surface)
                }
            } else {
                Ok(Vec::new())
            }
        });
        let modes = formats.and_then(|f| {
            // SAFETY: as above.
            unsafe {
                surface_loader.get_physical_device_surface_present_modes(device.physical, surface)
            }
            .map(|m| (f, m))
        });
        let picked = modes
            .map_err(|e| map_vk("asking the surface what it takes", e))
            .and_then(|(formats, modes)| {
                let format = pick_format(&formats).ok_or(BackendError::NotSupported {
                    backend: NAME,
                    operation: "presenting to this window (its queue family cannot present to it)",
                })?;
                Ok((format, modes))
            });
        let (format, modes) = match picked {
            Ok(p) => p,
            Err(e) => {
                // SAFETY: the surface is unused and destroyed once.
                unsafe { surface_loader.destroy_surface(surface, None) };
                return Err(e);
            }
        };
        // FIFO is always there (vsync); mailbox when offered, for the lowest latency
        // without tearing.
        let present_mode = if modes.contains(&vk::PresentModeKHR::MAILBOX) {
            vk::PresentModeKHR::MAILBOX
        } else {
            vk::PresentModeKHR::FIFO
        };
        let mut acquire = Vec::with_capacity(ACQUIRE_SEMAPHORES);
        for _ in 0..ACQUIRE_SEMAPHORES {
            acquire.push(semaphore(device)?);
        }
        Ok(Self {
            loader: ash::khr::swapchain::Device::new(&instance.raw, &device.raw),
            surface_loader,
            surface,
            chain: None,
            format: format.format,
            acquire,
            next_acquire: 0,
            present_mode,
            stale: true,
            requested: None,
            _window: window,
        })
    }

    /// The current swapchain's size, if there is one.
    #[must_use]
    pub fn extent(&self) -> Option<(u32, u32)> {
        self.chain.as_ref().map(|c| c.extent)
    }

    /// Whether a frame of `wanted` px needs the swapchain re-created first: it is out
    /// of date, or was made for another size (a surface that imposes its own size
    /// is not re-created again for the same request).
    #[must_use]
    pub fn needs_rebuild(&self, wanted: (u32, u32)) -> bool {
        self.stale || self.chain.is_none() || self.requested != Some(wanted)
    }

    /// (Re-)creates the swapchain of `wanted` px; the old one is retired after the
    /// `submitted` submissions so far.
    pub fn rebuild(
        &mut self,
        device: &Device,
        wanted: (u32, u32),
        retired: &mut Retired,
        submitted: u64,
    ) -> Result<(), BackendError> {
        // SAFETY: the surface and physical device are live.
        let caps = unsafe {
            self.surface_loader
                .get_physical_device_surface_capabilities(device.physical, self.surface)
        }
        .map_err(|e| map_vk("asking the surface its size", e))?;
        let extent = pick_extent(&caps, wanted);
        self.requested = Some(wanted);
        if extent.0 == 0 || extent.1 == 0 {
            return Err(BackendError::InvalidView(
                "the window has no area (minimised): draw when it is shown".into(),
            ));
        }
        let mut images = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            images = images.min(caps.max_image_count);
        }
        let alpha = [
            vk::CompositeAlphaFlagsKHR::OPAQUE,
            vk::CompositeAlphaFlagsKHR::INHERIT,
            vk::CompositeAlphaFlagsKHR::PRE_MULTIPLIED,
            vk::CompositeAlphaFlagsKHR::POST_MULTIPLIED,
        ]
        .into_iter()
        .find(|a| caps.supported_composite_alpha.contains(*a))
        .unwrap_or(vk::CompositeAlphaFlagsKHR::OPAQUE);
        // Copied after the scene pass for the water's reflections, where it may be.
        let copyable = caps
            .supported_usage_flags
            .contains(vk::ImageUsageFlags::TRANSFER_SRC);
        let usage = if copyable {
            vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::TRANSFER_SRC
        } else {
            vk::ImageUsageFlags::COLOR_ATTACHMENT
        };
        let old = self.chain.take();
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(self.surface)
            .min_image_count(images)
            .image_format(self.format)
            .image_color_space(vk::ColorSpaceKHR::SRGB_NONLINEAR)
            .image_extent(vk::Extent2D {
                width: extent.0,
                height: extent.1,
            })
            .image_array_layers(1)
            .image_usage(usage)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(alpha)
            .present_mode(self.present_mode)
            .clipped(true)
            .old_swapchain(old.as_ref().map_or(vk::SwapchainKHR::null(), |c| c.raw));
        // SAFETY: the surface is live; the old swapchain (if any) is retired, not
        // destroyed, until the work using it has finished.
        let raw = unsafe { self.loader.create_swapchain(&info, None) };
        if let Some(old) = old {
            let loader = self.loader.clone();
            retired.retire(submitted, move |d| old.destroy(d, &loader));
        }
        let raw = raw.map_err(|e| map_vk("creating the swapchain", e))?;
        let mut chain = Chain {
            raw,
            images: Vec::new(),
            views: Vec::new(),
            copyable,
            drawn: Vec::new(),
            extent,
        };
        match self.fill(device, &mut chain) {
            Ok(()) => {
                device.name(raw, "precip swapchain");
                self.chain = Some(chain);
                self.stale = false;
                Ok(())
            }
            Err(e) => {
                chain.destroy(device, &self.loader);
                Err(e)
            }
        }
    }

    fn fill(&self, device: &Device, chain: &mut Chain) -> Result<(), BackendError> {
        // SAFETY: the swapchain is live.
        let images = unsafe { self.loader.get_swapchain_images(chain.raw) }
            .map_err(|e| map_vk("listing the swapchain's images", e))?;
        for image in images {
            let info = vk::ImageViewCreateInfo::default()
                .image(image)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(self.format)
                .subresource_range(crate::image::COLOUR);
            // SAFETY: a view of a live swapchain image in its own format.
            let view = unsafe { device.raw.create_image_view(&info, None) }
                .map_err(|e| map_vk("creating a swapchain image view", e))?;
            chain.images.push(image);
            chain.views.push(view);
            chain.drawn.push(semaphore(device)?);
        }
        Ok(())
    }

    /// The next image to draw into, or `None` when the swapchain is out of date (it
    /// is marked stale; re-create it and try again).
    pub fn acquire(&mut self) -> Result<Option<Acquired>, BackendError> {
        let Some(chain) = self.chain.as_ref() else {
            self.stale = true;
            return Ok(None);
        };
        let semaphore = self.acquire[self.next_acquire];
        // SAFETY: the swapchain and semaphore are live; the semaphore's previous
        // wait belongs to a finished submission (see the module docs).
        let acquired = unsafe {
            self.loader
                .acquire_next_image(chain.raw, u64::MAX, semaphore, vk::Fence::null())
        };
        match acquired {
            Ok((index, suboptimal)) => {
                self.next_acquire = (self.next_acquire + 1) % ACQUIRE_SEMAPHORES;
                self.stale |= suboptimal;
                let i = index as usize;
                Ok(Some(Acquired {
                    index,
                    image: chain.images[i],
                    view: chain.views[i],
                    copyable: chain.copyable,
                    acquired: semaphore,
                    drawn: chain.drawn[i],
                }))
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                self.stale = true;
                Ok(None)
            }
            Err(e) => Err(map_vk("acquiring a swapchain image", e)),
        }
    }

    /// Presents `frame` once it is drawn.
    pub fn present(&mut self, device: &Device, frame: &Acquired) -> Result<(), BackendError> {
        let Some(chain) = self.chain.as_ref() else {
            return Ok(());
        };
        let (swapchains, indices, waits) = ([chain.raw], [frame.index], [frame.drawn]);
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: the queue can present to this surface (checked at creation); the
        // image was acquired and its drawing signals `drawn`.
        match unsafe { self.loader.queue_present(device.queue, &info) } {
            Ok(suboptimal) => {
                self.stale |= suboptimal;
                Ok(())
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => {
                self.stale = true;
                Ok(())
            }
            Err(e) => Err(map_vk("presenting", e)),
        }
    }

    /// Frees the swapchain, semaphores and surface (the device must be idle).
    pub fn destroy(mut self, device: &Device) {
        if let Some(chain) = self.chain.take() {
            chain.destroy(device, &self.loader);
        }
        // SAFETY: the device is idle; each object is destroyed once, the surface
        // after its swapchain.
        unsafe {
            for s in self.acquire.drain(..) {
                device.raw.destroy_semaphore(s, None);
            }
            self.surface_loader.destroy_surface(self.surface, None);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_srgb_format_is_preferred_and_the_surface_size_wins() {
        let f = |format| vk::SurfaceFormatKHR {
            format,
            color_space: vk::ColorSpaceKHR::SRGB_NONLINEAR,
        };
        let picked = pick_format(&[f(vk::Format::B8G8R8A8_UNORM), f(vk::Format::B8G8R8A8_SRGB)]);
        assert_eq!(picked.map(|p| p.format), Some(vk::Format::B8G8R8A8_SRGB));
        assert_eq!(pick_format(&[]), None);
        let mut caps = vk::SurfaceCapabilitiesKHR {
            current_extent: vk::Extent2D {
                width: 640,
                height: 480,
            },
            min_image_extent: vk::Extent2D {
                width: 1,
                height: 1,
            },
            max_image_extent: vk::Extent2D {
                width: 4096,
                height: 4096,
            },
            ..Default::default()
        };
        assert_eq!(pick_extent(&caps, (800, 600)), (640, 480));
        caps.current_extent.width = u32::MAX;
        assert_eq!(pick_extent(&caps, (800, 600)), (800, 600));
        assert_eq!(pick_extent(&caps, (9000, 0)), (4096, 1));
    }
}
