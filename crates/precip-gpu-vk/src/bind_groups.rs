//! Descriptor set layouts from `precip_gpu::bind_groups`' tables (the wgpu
//! backend's `bind_groups.rs` makes its bind group layouts from the same tables).

use ash::vk;
use precip_gpu::bind_groups::{BindingKind, GroupLayout, Stages};
use precip_model::BackendError;

use crate::device::Device;
use crate::error::map_vk;

fn stages(s: Stages) -> vk::ShaderStageFlags {
    let draw = vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT;
    match s {
        Stages::Compute => vk::ShaderStageFlags::COMPUTE,
        Stages::Draw => draw,
        Stages::Fragment => vk::ShaderStageFlags::FRAGMENT,
        Stages::DrawAndCompute => draw | vk::ShaderStageFlags::COMPUTE,
    }
}

/// The descriptor type of `kind`.
#[must_use]
pub fn descriptor_type(kind: BindingKind) -> vk::DescriptorType {
    use vk::DescriptorType as T;
    match kind {
        BindingKind::Uniform { dynamic: true, .. } => T::UNIFORM_BUFFER_DYNAMIC,
        BindingKind::Uniform { .. } => T::UNIFORM_BUFFER,
        BindingKind::Storage { dynamic: true, .. } => T::STORAGE_BUFFER_DYNAMIC,
        BindingKind::Storage { .. } => T::STORAGE_BUFFER,
        BindingKind::Texture { .. } => T::SAMPLED_IMAGE,
        BindingKind::StorageTextureRgba16Float => T::STORAGE_IMAGE,
        BindingKind::Sampler { .. } => T::SAMPLER,
    }
}

/// The descriptor set layout of `group`.
pub fn set_layout(
    device: &Device,
    group: &GroupLayout,
) -> Result<vk::DescriptorSetLayout, BackendError> {
    let bindings: Vec<vk::DescriptorSetLayoutBinding<'_>> = group
        .bindings
        .iter()
        .map(|b| {
            vk::DescriptorSetLayoutBinding::default()
                .binding(b.binding)
                .descriptor_type(descriptor_type(b.kind))
                .descriptor_count(1)
                .stage_flags(stages(b.stages))
        })
        .collect();
    let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
    // SAFETY: a valid device and create info.
    let layout = unsafe { device.raw.create_descriptor_set_layout(&info, None) }
        .map_err(|e| map_vk("creating a descriptor set layout", e))?;
    device.name(layout, group.name);
    Ok(layout)
}
