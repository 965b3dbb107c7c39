//! Bind group layouts of the render and cull programs (bindings:
//! `precip_model::gpu::{render_bindings, cull_bindings}`).

use std::num::NonZeroU64;

use precip_model::gpu::{cull_bindings, render_bindings as rb};
use precip_model::render::RenderParams;

/// The layouts, made once per device.
#[derive(Debug)]
pub struct RenderLayouts {
    /// Group 0 of the render program: the frame.
    pub frame: wgpu::BindGroupLayout,
    /// Group 1: shadow map and flake opacity.
    pub light: wgpu::BindGroupLayout,
    /// Group 2: a mesh's material.
    pub material: wgpu::BindGroupLayout,
    /// Group 0 of the cull kernels.
    pub cull: wgpu::BindGroupLayout,
    /// Group 2 of the splat kernel: the camera's depth and the splat sums.
    pub splat: wgpu::BindGroupLayout,
    /// Group 2 of the splat's resolve draw: the splat sums.
    pub splat_resolve: wgpu::BindGroupLayout,
    /// Group 0 of the `cover_texture` kernel: the texels and the two storage views.
    pub cover_texture: wgpu::BindGroupLayout,
}

/// The cover textures' format (`precip_model::gpu::COVER_TEXTURE_FORMAT_NAME`).
pub const COVER_TEXTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Groups 0 and 1 serve the draws and the splat kernel.
const DRAW: wgpu::ShaderStages =
    wgpu::ShaderStages::VERTEX_FRAGMENT.union(wgpu::ShaderStages::COMPUTE);

fn entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::BindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty,
        count: None,
    }
}

fn uniform(size: usize) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Uniform,
        has_dynamic_offset: false,
        min_binding_size: NonZeroU64::new(size as u64),
    }
}

fn storage(read_only: bool) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only },
        has_dynamic_offset: false,
        min_binding_size: None,
    }
}

fn texture(sample_type: wgpu::TextureSampleType) -> wgpu::BindingType {
    wgpu::BindingType::Texture {
        sample_type,
        view_dimension: wgpu::TextureViewDimension::D2,
        multisampled: false,
    }
}

impl RenderLayouts {
    /// Creates the layouts.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Self {
        // Read-only storage, not uniform: see render_scene.wgsl.
        let params = wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: NonZeroU64::new(size_of::<RenderParams>() as u64),
        };
        let frame = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip render frame"),
            entries: &[
                entry(rb::PARAMS, DRAW, params),
                entry(rb::GROUND_HEIGHT, DRAW, storage(true)),
                entry(rb::PARTICLES, DRAW, storage(true)),
                entry(rb::DRAWN, DRAW, storage(true)),
                entry(
                    rb::COVER_A,
                    DRAW,
                    texture(wgpu::TextureSampleType::Float { filterable: true }),
                ),
                entry(
                    rb::COVER_B,
                    DRAW,
                    texture(wgpu::TextureSampleType::Float { filterable: true }),
                ),
                entry(
                    rb::COVER_SAMPLER,
                    DRAW,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                ),
            ],
        });
        let light = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip render light"),
            entries: &[
                entry(
                    rb::SHADOW_MAP,
                    DRAW,
                    texture(wgpu::TextureSampleType::Depth),
                ),
                entry(
                    rb::SHADOW_SAMPLER,
                    DRAW,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                ),
                entry(
                    rb::FLAKE_OPACITY,
                    DRAW,
                    texture(wgpu::TextureSampleType::Float { filterable: true }),
                ),
                entry(
                    rb::FLAKE_SAMPLER,
                    DRAW,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                ),
            ],
        });
        let material = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip render material"),
            entries: &[
                entry(
                    rb::MATERIAL,
                    wgpu::ShaderStages::VERTEX_FRAGMENT,
                    uniform(16),
                ),
                entry(
                    rb::BASE_COLOUR_TEXTURE,
                    wgpu::ShaderStages::VERTEX_FRAGMENT,
                    texture(wgpu::TextureSampleType::Float { filterable: true }),
                ),
                entry(
                    rb::MATERIAL_SAMPLER,
                    wgpu::ShaderStages::VERTEX_FRAGMENT,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                ),
            ],
        });
        let compute = wgpu::ShaderStages::COMPUTE;
        let cull = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip cull"),
            entries: &[
                entry(cull_bindings::PARAMS, compute, params),
                entry(cull_bindings::PARTICLES, compute, storage(true)),
                entry(cull_bindings::GROUP_COUNTS, compute, storage(false)),
                entry(cull_bindings::DRAWN, compute, storage(false)),
                entry(cull_bindings::DRAWS, compute, storage(false)),
            ],
        });
        let splat = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip splat"),
            entries: &[
                entry(
                    rb::SPLAT_SCENE_DEPTH,
                    compute,
                    texture(wgpu::TextureSampleType::Depth),
                ),
                entry(rb::SPLAT_SUMS, compute, storage(false)),
            ],
        });
        let splat_resolve = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip splat resolve"),
            entries: &[entry(
                rb::RESOLVED_SUMS,
                wgpu::ShaderStages::FRAGMENT,
                storage(false),
            )],
        });
        let written = wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: COVER_TEXTURE_FORMAT,
            view_dimension: wgpu::TextureViewDimension::D2,
        };
        let cover_texture = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip cover texture"),
            entries: &[
                entry(rb::COVER, compute, storage(true)),
                entry(rb::COVER_A_OUT, compute, written),
                entry(rb::COVER_B_OUT, compute, written),
            ],
        });
        Self {
            frame,
            light,
            material,
            cull,
            splat,
            splat_resolve,
            cover_texture,
        }
    }
}
