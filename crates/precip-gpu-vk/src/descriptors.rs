//! Descriptor pools sized for the sets they hold, set allocation, and the pieces of a
//! descriptor write (buffer, image and sampler infos), shared by the simulation's
//! sets, the frame's and the materials'.

use ash::vk;
use precip_model::BackendError;

use crate::buffer::Buffer;
use crate::device::Device;
use crate::error::map_vk;

/// A pool for `max_sets` sets needing `sizes` descriptors of each type in all.
pub fn pool(
    device: &Device,
    name: &str,
    sizes: &[(vk::DescriptorType, u32)],
    max_sets: u32,
) -> Result<vk::DescriptorPool, BackendError> {
    let sizes: Vec<vk::DescriptorPoolSize> = sizes
        .iter()
        .map(|&(ty, descriptor_count)| vk::DescriptorPoolSize {
            ty,
            descriptor_count,
        })
        .collect();
    let info = vk::DescriptorPoolCreateInfo::default()
        .max_sets(max_sets)
        .pool_sizes(&sizes);
    // SAFETY: a valid device and create info.
    let pool = unsafe { device.raw.create_descriptor_pool(&info, None) }
        .map_err(|e| map_vk(&format!("creating the {name} descriptor pool"), e))?;
    device.name(pool, &format!("precip {name}"));
    Ok(pool)
}

/// One set per layout from `pool` (which must have room for them).
pub fn allocate(
    device: &Device,
    pool: vk::DescriptorPool,
    layouts: &[vk::DescriptorSetLayout],
) -> Result<Vec<vk::DescriptorSet>, BackendError> {
    let info = vk::DescriptorSetAllocateInfo::default()
        .descriptor_pool(pool)
        .set_layouts(layouts);
    // SAFETY: the pool and layouts are live; a pool without room returns an error
    // (out of pool memory), mapped like any other.
    unsafe { device.raw.allocate_descriptor_sets(&info) }
        .map_err(|e| map_vk("allocating descriptor sets", e))
}

/// The head of a write of `binding` of `set`, of type `ty` (add the infos).
pub fn write(
    set: vk::DescriptorSet,
    binding: u32,
    ty: vk::DescriptorType,
) -> vk::WriteDescriptorSet<'static> {
    vk::WriteDescriptorSet::default()
        .dst_set(set)
        .dst_binding(binding)
        .descriptor_type(ty)
}

/// The first `range` bytes of `buffer` (`vk::WHOLE_SIZE` for all of it).
pub fn buffer_info(buffer: &Buffer, range: u64) -> [vk::DescriptorBufferInfo; 1] {
    [vk::DescriptorBufferInfo {
        buffer: buffer.raw,
        offset: 0,
        range,
    }]
}

/// An image view read or written in `layout`.
pub fn image_info(view: vk::ImageView, layout: vk::ImageLayout) -> [vk::DescriptorImageInfo; 1] {
    [vk::DescriptorImageInfo {
        sampler: vk::Sampler::null(),
        image_view: view,
        image_layout: layout,
    }]
}

/// A sampler on its own.
pub fn sampler_info(sampler: vk::Sampler) -> [vk::DescriptorImageInfo; 1] {
    [vk::DescriptorImageInfo {
        sampler,
        image_view: vk::ImageView::null(),
        image_layout: vk::ImageLayout::UNDEFINED,
    }]
}
