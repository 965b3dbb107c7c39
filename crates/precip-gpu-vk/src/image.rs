//! Images with their memory from gpu-allocator and one view each: the wind volume
//! (3D, read with `textureLoad`), the shadow map and depth buffers, the offscreen
//! colour target, and the sampled textures (flake opacity, base colours).

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use precip_model::BackendError;

use crate::buffer::poisoned;
use crate::device::Device;
use crate::error::{map_allocation, map_vk};

/// The colour subresource of a single-level image.
pub const COLOUR: vk::ImageSubresourceRange = vk::ImageSubresourceRange {
    aspect_mask: vk::ImageAspectFlags::COLOR,
    base_mip_level: 0,
    level_count: 1,
    base_array_layer: 0,
    layer_count: 1,
};

/// The depth subresource of a single-level image.
pub const DEPTH: vk::ImageSubresourceRange = vk::ImageSubresourceRange {
    aspect_mask: vk::ImageAspectFlags::DEPTH,
    ..COLOUR
};

/// The depth format of the shadow map and of the camera's depth buffer (wgpu:
/// `Depth32Float`, `precip_gpu::recipe::render_bindings::SHADOW_FORMAT_NAME`).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

/// What an image is.
#[derive(Debug, Clone, Copy)]
pub struct ImageSpec<'a> {
    /// Debug name.
    pub name: &'a str,
    /// Texels (z = 1 for a 2D image).
    pub extent: UVec3,
    /// Format.
    pub format: vk::Format,
    /// Usage.
    pub usage: vk::ImageUsageFlags,
}

/// An image, its view and memory; [`Image::destroy`] frees them.
#[derive(Debug)]
pub struct Image {
    /// The image.
    pub raw: vk::Image,
    /// Its view (the whole image).
    pub view: vk::ImageView,
    allocation: Option<Allocation>,
    /// Texels.
    pub extent: UVec3,
    /// Format.
    pub format: vk::Format,
}

impl Image {
    /// A device-local single-level image as `spec` says (3D when `extent.z > 1`).
    pub fn new(device: &Device, spec: &ImageSpec<'_>) -> Result<Self, BackendError> {
        let volume = spec.extent.z > 1;
        let name = spec.name;
        let info = vk::ImageCreateInfo::default()
            .image_type(if volume {
                vk::ImageType::TYPE_3D
            } else {
                vk::ImageType::TYPE_2D
            })
            .format(spec.format)
            .extent(vk::Extent3D {
                width: spec.extent.x,
                height: spec.extent.y,
                depth: spec.extent.z,
            })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(spec.usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: a valid device and create info.
        let raw = unsafe { device.raw.create_image(&info, None) }
            .map_err(|e| map_vk(&format!("creating image {name}"), e))?;
        // SAFETY: `raw` was just created on this device.
        let requirements = unsafe { device.raw.get_image_memory_requirements(raw) };
        let allocation = device
            .allocator
            .lock()
            .map_err(|_| poisoned())
            .and_then(|mut a| {
                a.allocate(&AllocationCreateDesc {
                    name,
                    requirements,
                    location: MemoryLocation::GpuOnly,
                    linear: false,
                    allocation_scheme: AllocationScheme::GpuAllocatorManaged,
                })
                .map_err(|e| map_allocation(&format!("memory for {name}"), &e))
            });
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: the image is unused and destroyed once.
                unsafe { device.raw.destroy_image(raw, None) };
                return Err(e);
            }
        };
        let mut image = Self {
            raw,
            view: vk::ImageView::null(),
            allocation: Some(allocation),
            extent: spec.extent,
            format: spec.format,
        };
        let Some(a) = image.allocation.as_ref() else {
            return Err(poisoned());
        };
        // SAFETY: the allocation fits the image and is bound once.
        if let Err(e) = unsafe { device.raw.bind_image_memory(raw, a.memory(), a.offset()) } {
            image.destroy(device);
            return Err(map_vk(&format!("binding the memory of {name}"), e));
        }
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(if volume {
                vk::ImageViewType::TYPE_3D
            } else {
                vk::ImageViewType::TYPE_2D
            })
            .format(spec.format)
            .subresource_range(image.range());
        // SAFETY: a view of the image just created, of its own format.
        match unsafe { device.raw.create_image_view(&view_info, None) } {
            Ok(view) => image.view = view,
            Err(e) => {
                image.destroy(device);
                return Err(map_vk(&format!("creating the view of {name}"), e));
            }
        }
        device.name(raw, &format!("precip {name}"));
        device.name(image.view, &format!("precip {name} view"));
        Ok(image)
    }

    /// The wind volume: `R32G32B32A32_SFLOAT`, sampled, filled by a copy.
    pub fn volume(device: &Device, extent: UVec3) -> Result<Self, BackendError> {
        Self::new(
            device,
            &ImageSpec {
                name: "wind volume",
                extent,
                format: vk::Format::R32G32B32A32_SFLOAT,
                usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            },
        )
    }

    /// Its whole subresource (depth or colour).
    pub fn range(&self) -> vk::ImageSubresourceRange {
        if self.format == DEPTH_FORMAT {
            DEPTH
        } else {
            COLOUR
        }
    }

    /// Width and height.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        (self.extent.x, self.extent.y)
    }

    /// Frees the view, image and memory (the device must be done with them).
    pub fn destroy(mut self, device: &Device) {
        // SAFETY: the caller guarantees no pending work uses the image; null views are
        // ignored by Vulkan.
        unsafe {
            device.raw.destroy_image_view(self.view, None);
            device.raw.destroy_image(self.raw, None);
        }
        if let (Some(allocation), Ok(mut allocator)) =
            (self.allocation.take(), device.allocator.lock())
        {
            let _ = allocator.free(allocation);
        }
    }
}
