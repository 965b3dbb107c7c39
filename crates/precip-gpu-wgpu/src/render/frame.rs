//! The per-configuration resources of drawing, made from the frame's resources
//! table (`precip_gpu::frame_resources`): its buffers, textures and samplers, and
//! its groups filled as the table says; and the target's (depth buffer, splat sums)
//! in [`super::target`] from the same table. Vulkan twin:
//! `precip_gpu_vk::render::frame`.

use precip_gpu::Simulation;
use precip_gpu::bind_groups::{BindingKind, GroupLayout};
use precip_gpu::frame_resources::{
    FRAME_GROUPS, FrameBound, FrameBuffer, FrameBufferUsage, FrameGroupFill, FrameTexture, Sampler,
    TargetResource, TexelFormat, TextureUsage, frame_buffers, frame_textures,
};
use precip_gpu::recipe::cull_groups;
use precip_model::{BackendError, Setup};
use wgpu::util::DeviceExt;

use super::layouts::RenderLayouts;
use crate::device::GpuDevice;
use crate::error::NAME;
use crate::gpu::Hal;

/// What drawing adds to a configuration.
#[derive(Debug)]
pub struct FrameResources {
    buffers: Vec<(FrameBuffer, wgpu::Buffer)>,
    textures: Vec<(FrameTexture, wgpu::Texture, wgpu::TextureView)>,
    samplers: Vec<(Sampler, wgpu::Sampler)>,
    groups: Vec<(&'static str, wgpu::BindGroup)>,
    /// Workgroups of the cull kernels.
    pub cull_groups: u32,
    /// Cover texels (the `cover_texture` kernel's dispatch).
    pub cover_texels: u32,
}

/// A resource the tables name that was not made (a bug in precip).
#[must_use]
pub fn missing(what: &str) -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: format!("{what} of the frame is missing (a bug in precip: please report it)"),
    }
}

/// The wgpu format of `format`.
#[must_use]
pub fn texel_format(format: TexelFormat) -> wgpu::TextureFormat {
    match format {
        TexelFormat::Depth32Float => wgpu::TextureFormat::Depth32Float,
        TexelFormat::Rgba16Float => wgpu::TextureFormat::Rgba16Float,
        TexelFormat::R8Unorm => wgpu::TextureFormat::R8Unorm,
    }
}

/// What the frame's group entries resolve against besides the frame's own.
pub struct Bindable<'a> {
    /// The simulation's buffers.
    pub sim: &'a Simulation<Hal>,
    /// The target's depth view and splat sums, for the target's groups.
    pub target: Option<(&'a wgpu::TextureView, &'a wgpu::Buffer)>,
}

impl FrameResources {
    /// Allocates drawing's resources beside the simulation's `sim`, from the table.
    pub fn new(
        gpu: &GpuDevice,
        layouts: &RenderLayouts,
        sim: &Simulation<Hal>,
        setup: &Setup,
    ) -> Result<Self, BackendError> {
        let device = &gpu.device;
        let count = sim.particle_count();
        let buffers = frame_buffers(count)
            .iter()
            .map(|spec| {
                let usage = match spec.usage {
                    FrameBufferUsage::Params => {
                        wgpu::BufferUsages::UNIFORM
                            | wgpu::BufferUsages::STORAGE
                            | wgpu::BufferUsages::COPY_DST
                    }
                    FrameBufferUsage::Storage => wgpu::BufferUsages::STORAGE,
                    FrameBufferUsage::Indirect => {
                        wgpu::BufferUsages::STORAGE
                            | wgpu::BufferUsages::INDIRECT
                            | wgpu::BufferUsages::COPY_SRC
                    }
                };
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(spec.label),
                    size: spec.bytes,
                    usage,
                    mapped_at_creation: false,
                });
                (spec.buffer, buffer)
            })
            .collect();
        let textures = frame_textures(setup)
            .into_iter()
            .map(|spec| {
                let usage = match spec.usage {
                    TextureUsage::DepthAttachment => {
                        wgpu::TextureUsages::RENDER_ATTACHMENT
                            | wgpu::TextureUsages::TEXTURE_BINDING
                    }
                    TextureUsage::StorageAndSampled => {
                        wgpu::TextureUsages::STORAGE_BINDING
                            | wgpu::TextureUsages::TEXTURE_BINDING
                            | wgpu::TextureUsages::COPY_SRC
                    }
                    TextureUsage::Sampled => {
                        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST
                    }
                };
                let descriptor = wgpu::TextureDescriptor {
                    label: Some(spec.label),
                    size: wgpu::Extent3d {
                        width: spec.size[0],
                        height: spec.size[1],
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: texel_format(spec.format),
                    usage,
                    view_formats: &[],
                };
                let texture = match &spec.contents {
                    Some(texels) => device.create_texture_with_data(
                        &gpu.queue,
                        &descriptor,
                        wgpu::util::TextureDataOrder::LayerMajor,
                        texels,
                    ),
                    None => device.create_texture(&descriptor),
                };
                let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
                (spec.texture, texture, view)
            })
            .collect();
        let samplers = [Sampler::LinearClamp, Sampler::ShadowComparison]
            .into_iter()
            .map(|kind| {
                let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
                    label: Some("precip frame sampler"),
                    mag_filter: wgpu::FilterMode::Linear,
                    min_filter: wgpu::FilterMode::Linear,
                    compare: (kind == Sampler::ShadowComparison)
                        .then_some(wgpu::CompareFunction::LessEqual),
                    ..Default::default()
                });
                (kind, sampler)
            })
            .collect();
        let texels = setup.cover.frame.texels;
        let mut frame = Self {
            buffers,
            textures,
            samplers,
            groups: Vec::new(),
            cull_groups: cull_groups(count),
            cover_texels: texels.x * texels.y,
        };
        frame.groups = frame.bind_groups(
            device,
            layouts,
            &FRAME_GROUPS,
            &Bindable { sim, target: None },
        )?;
        Ok(frame)
    }

    /// The groups `fills` describe, by table name.
    pub fn bind_groups(
        &self,
        device: &wgpu::Device,
        layouts: &RenderLayouts,
        fills: &[FrameGroupFill],
        with: &Bindable<'_>,
    ) -> Result<Vec<(&'static str, wgpu::BindGroup)>, BackendError> {
        fills
            .iter()
            .map(|fill| {
                let layout = layouts
                    .of(fill.layout)
                    .ok_or_else(|| missing(fill.layout.name))?;
                Ok((
                    fill.layout.name,
                    self.bind_group(device, layout, fill, with)?,
                ))
            })
            .collect()
    }

    /// The group `fill` describes, on `layout`.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        fill: &FrameGroupFill,
        with: &Bindable<'_>,
    ) -> Result<wgpu::BindGroup, BackendError> {
        let mut entries = Vec::with_capacity(fill.bound.len());
        for &(binding, bound) in fill.bound {
            let block = fill
                .layout
                .kind_of(binding)
                .and_then(BindingKind::block_bytes)
                .and_then(wgpu::BufferSize::new);
            let buffer = |buffer| {
                wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer,
                    offset: 0,
                    size: block,
                })
            };
            let resource = match bound {
                FrameBound::Sim(b) => buffer(with.sim.buffer(b)),
                FrameBound::Buffer(b) => buffer(self.buffer(b)?),
                FrameBound::Texture(t) | FrameBound::StorageTexture(t) => {
                    wgpu::BindingResource::TextureView(self.view(t)?)
                }
                FrameBound::Sampler(s) => wgpu::BindingResource::Sampler(self.sampler(s)?),
                FrameBound::Target(TargetResource::CameraDepth) => {
                    wgpu::BindingResource::TextureView(
                        with.target.ok_or_else(|| missing("the depth buffer"))?.0,
                    )
                }
                FrameBound::Target(TargetResource::SplatSums) => {
                    buffer(with.target.ok_or_else(|| missing("the splat sums"))?.1)
                }
            };
            entries.push(wgpu::BindGroupEntry { binding, resource });
        }
        Ok(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(fill.layout.name),
            layout,
            entries: &entries,
        }))
    }

    /// A buffer of the frame.
    pub fn buffer(&self, buffer: FrameBuffer) -> Result<&wgpu::Buffer, BackendError> {
        self.buffers
            .iter()
            .find(|(b, _)| *b == buffer)
            .map(|(_, b)| b)
            .ok_or_else(|| missing("a buffer"))
    }

    /// A texture of the frame.
    pub fn texture(&self, texture: FrameTexture) -> Result<&wgpu::Texture, BackendError> {
        self.textures
            .iter()
            .find(|(t, ..)| *t == texture)
            .map(|(_, t, _)| t)
            .ok_or_else(|| missing("a texture"))
    }

    /// A texture's view.
    pub fn view(&self, texture: FrameTexture) -> Result<&wgpu::TextureView, BackendError> {
        self.textures
            .iter()
            .find(|(t, ..)| *t == texture)
            .map(|(.., v)| v)
            .ok_or_else(|| missing("a texture"))
    }

    fn sampler(&self, sampler: Sampler) -> Result<&wgpu::Sampler, BackendError> {
        self.samplers
            .iter()
            .find(|(s, _)| *s == sampler)
            .map(|(_, s)| s)
            .ok_or_else(|| missing("a sampler"))
    }

    /// The group made for `table`, if it is one of the configuration's.
    #[must_use]
    pub fn group(&self, table: &GroupLayout) -> Option<&wgpu::BindGroup> {
        self.groups
            .iter()
            .find(|(name, _)| *name == table.name)
            .map(|(_, g)| g)
    }
}
