//! The wind volume: a 3D `R32G32B32A32_SFLOAT` image read with `textureLoad`.

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use precip_model::BackendError;

use crate::buffer::poisoned;
use crate::device::Device;
use crate::error::{map_allocation, map_vk};

/// A 3D image, its view and memory.
#[derive(Debug)]
pub struct Volume {
    /// The image.
    pub raw: vk::Image,
    /// Its view.
    pub view: vk::ImageView,
    allocation: Option<Allocation>,
    /// Texels.
    pub extent: UVec3,
}

/// The colour subresource of a single-level image.
pub const COLOUR: vk::ImageSubresourceRange = vk::ImageSubresourceRange {
    aspect_mask: vk::ImageAspectFlags::COLOR,
    base_mip_level: 0,
    level_count: 1,
    base_array_layer: 0,
    layer_count: 1,
};

impl Volume {
    /// A device-local volume of `extent` texels.
    pub fn new(device: &Device, extent: UVec3) -> Result<Self, BackendError> {
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_3D)
            .format(vk::Format::R32G32B32A32_SFLOAT)
            .extent(vk::Extent3D {
                width: extent.x,
                height: extent.y,
                depth: extent.z,
            })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        // SAFETY: a valid device and create info.
        let raw = unsafe { device.raw.create_image(&info, None) }
            .map_err(|e| map_vk("creating the wind volume", e))?;
        // SAFETY: `raw` was just created on this device.
        let requirements = unsafe { device.raw.get_image_memory_requirements(raw) };
        let allocation = device
            .allocator
            .lock()
            .map_err(|_| poisoned())?
            .allocate(&AllocationCreateDesc {
                name: "wind volume",
                requirements,
                location: MemoryLocation::GpuOnly,
                linear: false,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })
            .map_err(|e| map_allocation("memory for the wind volume", &e))?;
        // SAFETY: the allocation fits the image and is bound once.
        unsafe {
            device
                .raw
                .bind_image_memory(raw, allocation.memory(), allocation.offset())
        }
        .map_err(|e| map_vk("binding the wind volume's memory", e))?;
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(vk::ImageViewType::TYPE_3D)
            .format(vk::Format::R32G32B32A32_SFLOAT)
            .subresource_range(COLOUR);
        // SAFETY: a view of the image just created.
        let view = unsafe { device.raw.create_image_view(&view_info, None) }
            .map_err(|e| map_vk("creating the wind volume's view", e))?;
        device.name(raw, "precip wind volume");
        device.name(view, "precip wind volume view");
        Ok(Self {
            raw,
            view,
            allocation: Some(allocation),
            extent,
        })
    }

    /// Frees the view, image and memory (the device must be done with them).
    pub fn destroy(mut self, device: &Device) {
        // SAFETY: the caller guarantees no pending work uses the image.
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
