//! Bind group layouts from `precip_gpu::bind_groups`' tables (the Vulkan backend's
//! `bind_groups.rs` makes its descriptor set layouts from the same tables).

use std::num::NonZeroU64;

use precip_gpu::bind_groups::{BindingKind, GroupLayout, Stages, TextureSample};

/// The cover textures' format (`precip_gpu::recipe::COVER_TEXTURE_FORMAT_NAME`).
pub const COVER_TEXTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

fn stages(s: Stages) -> wgpu::ShaderStages {
    match s {
        Stages::Compute => wgpu::ShaderStages::COMPUTE,
        Stages::Draw => wgpu::ShaderStages::VERTEX_FRAGMENT,
        Stages::Fragment => wgpu::ShaderStages::FRAGMENT,
        Stages::DrawAndCompute => wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE,
    }
}

fn binding_type(kind: BindingKind) -> wgpu::BindingType {
    match kind {
        BindingKind::Uniform { min_bytes, dynamic } => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: NonZeroU64::new(min_bytes),
        },
        BindingKind::Storage {
            read_only,
            min_bytes,
            dynamic,
        } => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: dynamic,
            min_binding_size: NonZeroU64::new(min_bytes),
        },
        BindingKind::Texture { sample, volume } => wgpu::BindingType::Texture {
            sample_type: match sample {
                TextureSample::Float { filterable } => {
                    wgpu::TextureSampleType::Float { filterable }
                }
                TextureSample::Depth => wgpu::TextureSampleType::Depth,
            },
            view_dimension: if volume {
                wgpu::TextureViewDimension::D3
            } else {
                wgpu::TextureViewDimension::D2
            },
            multisampled: false,
        },
        BindingKind::StorageTextureRgba16Float => wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: COVER_TEXTURE_FORMAT,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        BindingKind::Sampler { comparison } => wgpu::BindingType::Sampler(if comparison {
            wgpu::SamplerBindingType::Comparison
        } else {
            wgpu::SamplerBindingType::Filtering
        }),
    }
}

/// The layout of `group`.
#[must_use]
pub fn bind_group_layout(device: &wgpu::Device, group: &GroupLayout) -> wgpu::BindGroupLayout {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = group
        .bindings
        .iter()
        .map(|b| wgpu::BindGroupLayoutEntry {
            binding: b.binding,
            visibility: stages(b.stages),
            ty: binding_type(b.kind),
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(group.name),
        entries: &entries,
    })
}
