//! [`Hal`]: the device calls of [`precip_gpu::Gpu`] on wgpu (Vulkan twin:
//! `precip_gpu_vk::gpu`). Nothing here knows what the buffers hold, which kernels
//! run or what a frame draws: the executor and renderer of `precip-gpu` decide;
//! [`Gpu::submit_frame`] turns their commands into wgpu passes ([`crate::frame`]).

use std::collections::HashMap;

use precip_gpu::bind_groups::{BindingKind, GroupLayout};
use precip_gpu::binding_limits::BindingLimits;
use precip_gpu::frame::{Draw, RenderPassRecipe};
use precip_gpu::frame_resources::{Sampler, TexelFormat, TextureUsage};
use precip_gpu::gpu::{BindingResource, Dispatch, FrameWork, Gpu, Target, TextureDesc};
use precip_gpu::resources::BufferUsage;
use precip_gpu::shaders::Program;
use precip_model::{BackendError, DeviceMemory};
use wgpu::util::DeviceExt;

use crate::bind_groups::bind_group_layout;
use crate::device::GpuDevice;
use crate::error::{NAME, map_scope_error};
use crate::frame::encode_pass;
use crate::pipelines::draw_pipeline;
use crate::query::Timestamps;
use crate::transfer::{read_buffer, read_texture};

/// The depth format of the shadow map and of the camera's depth buffer.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// How wgpu names the buffers of its indirect-call validation pool.
const WGPU_INDIRECT_VALIDATION_POOL: &str = "(wgpu internal) Indirect";

/// Runs `f` inside out-of-memory and validation error scopes; any captured error
/// becomes a [`BackendError`].
pub fn scoped<T>(
    gpu: &GpuDevice,
    operation: &str,
    f: impl FnOnce() -> T,
) -> Result<T, BackendError> {
    let memory = gpu.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = f();
    let validation_error = pollster::block_on(validation.pop());
    let memory_error = pollster::block_on(memory.pop());
    match memory_error.or(validation_error) {
        Some(error) => Err(map_scope_error(operation, &error)),
        None => Ok(value),
    }
}

/// The shader module of `program`, from its WGSL.
#[must_use]
pub fn shader_module(device: &wgpu::Device, program: Program) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(program.label()),
        source: wgpu::ShaderSource::Wgsl(program.source().into()),
    })
}

/// A texture and its view (3D: the wind volume; 2D: the frame's textures).
#[derive(Debug)]
pub struct Texture {
    /// The texture.
    pub texture: wgpu::Texture,
    /// Its view.
    pub view: wgpu::TextureView,
}

/// The device calls on wgpu.
#[derive(Debug)]
pub struct Hal {
    /// The device and queue.
    pub gpu: GpuDevice,
    /// A step's timestamp queries, where the adapter has them.
    pub timestamps: Option<Timestamps>,
    /// A frame's timestamp queries, where the adapter has them.
    pub frame_stamps: Option<Timestamps>,
    modules: HashMap<Program, wgpu::ShaderModule>,
}

impl Hal {
    /// The calls on `gpu`.
    #[must_use]
    pub fn new(gpu: GpuDevice) -> Self {
        Self {
            timestamps: Timestamps::for_steps(&gpu),
            frame_stamps: Timestamps::for_frames(&gpu),
            gpu,
            modules: HashMap::new(),
        }
    }

    fn module(&mut self, program: Program) -> &wgpu::ShaderModule {
        let device = &self.gpu.device;
        self.modules
            .entry(program)
            .or_insert_with(|| shader_module(device, program))
    }

    /// The layout of `layouts`' groups at 0, 1, ….
    fn pipeline_layout(
        &self,
        label: &str,
        layouts: &[&wgpu::BindGroupLayout],
    ) -> wgpu::PipelineLayout {
        let groups: Vec<Option<&wgpu::BindGroupLayout>> =
            layouts.iter().map(|l| Some(*l)).collect();
        self.gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &groups,
                immediate_size: 0,
            })
    }

    fn write_volume_texels(&self, texture: &wgpu::Texture, texels: &[u8]) {
        let size = texture.size();
        self.gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            texels,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(16 * size.width),
                rows_per_image: Some(size.height),
            },
            size,
        );
    }
}

impl Gpu for Hal {
    type Buffer = wgpu::Buffer;
    type Volume = Texture;
    type GroupLayout = wgpu::BindGroupLayout;
    type BindGroup = wgpu::BindGroup;
    type Kernel = wgpu::ComputePipeline;
    type Texture = Texture;
    type Sampler = wgpu::Sampler;
    type DrawPipeline = wgpu::RenderPipeline;
    type Surface = wgpu::TextureView;
    type ColourFormat = wgpu::TextureFormat;

    fn name(&self) -> &'static str {
        NAME
    }

    fn describe(&self) -> String {
        self.gpu.describe()
    }

    /// Precip's allocations and wgpu's fixed ones; not wgpu's indirect-call
    /// validation pool, whose 1 MiB buffers wgpu adds while more frames are in flight
    /// than it has buffers for and keeps for reuse (bounded by the frames in flight,
    /// freed with the device): its size follows the host's timing, not our frames.
    fn device_memory(&self) -> Option<DeviceMemory> {
        self.gpu.device.generate_allocator_report().map(|r| {
            let (allocations, allocated_bytes) = r
                .allocations
                .iter()
                .filter(|a| !a.name.starts_with(WGPU_INDIRECT_VALIDATION_POOL))
                .fold((0, 0), |(n, bytes), a| (n + 1, bytes + a.size));
            DeviceMemory {
                allocations,
                allocated_bytes,
                reserved_bytes: r.total_reserved_bytes,
            }
        })
    }

    fn limits(&self) -> precip_model::DeviceLimits {
        self.gpu.limits()
    }

    fn binding_limits(&self) -> BindingLimits {
        let limits = self.gpu.device.limits();
        BindingLimits {
            bind_groups: limits.max_bind_groups,
            storage_buffers_per_stage: limits.max_storage_buffers_per_shader_stage,
            uniform_buffers_per_stage: limits.max_uniform_buffers_per_shader_stage,
            sampled_textures_per_stage: limits.max_sampled_textures_per_shader_stage,
            samplers_per_stage: limits.max_samplers_per_shader_stage,
            storage_textures_per_stage: limits.max_storage_textures_per_shader_stage,
            dynamic_uniform_buffers: limits.max_dynamic_uniform_buffers_per_pipeline_layout,
            dynamic_storage_buffers: limits.max_dynamic_storage_buffers_per_pipeline_layout,
        }
    }

    fn uniform_alignment(&self) -> u64 {
        let limits = self.gpu.device.limits();
        u64::from(
            limits
                .min_uniform_buffer_offset_alignment
                .max(limits.min_storage_buffer_offset_alignment),
        )
    }

    fn slots(&self) -> u32 {
        1
    }

    fn create_buffer(
        &mut self,
        label: &'static str,
        bytes: u64,
        usage: BufferUsage,
        contents: Option<&[u8]>,
    ) -> Result<wgpu::Buffer, BackendError> {
        let usage = match usage {
            BufferUsage::Storage => {
                wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC
            }
            BufferUsage::Uniform => wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            BufferUsage::FrameBlocks => {
                wgpu::BufferUsages::UNIFORM
                    | wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
            }
            BufferUsage::Indirect => {
                wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::INDIRECT
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST
            }
            BufferUsage::Vertices => wgpu::BufferUsages::VERTEX,
            BufferUsage::Indices => wgpu::BufferUsages::INDEX,
        };
        let device = &self.gpu.device;
        scoped(&self.gpu, label, || match contents {
            Some(contents) => device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            }),
            None => device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            }),
        })
    }

    fn write_buffer(
        &mut self,
        buffer: &mut wgpu::Buffer,
        offset: u64,
        bytes: &[u8],
    ) -> Result<(), BackendError> {
        scoped(&self.gpu, "writing a buffer", || {
            self.gpu.queue.write_buffer(buffer, offset, bytes);
        })
    }

    fn read_buffer(&mut self, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, BackendError> {
        read_buffer(&self.gpu, buffer, bytes)
    }

    fn create_volume(
        &mut self,
        label: &'static str,
        [x, y, z]: [u32; 3],
        texels: &[u8],
    ) -> Result<Texture, BackendError> {
        let device = &self.gpu.device;
        let texture = scoped(&self.gpu, label, || {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: x,
                    height: y,
                    depth_or_array_layers: z,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D3,
                format: wgpu::TextureFormat::Rgba32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            })
        })?;
        self.write_volume_texels(&texture, texels);
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Ok(Texture { texture, view })
    }

    fn write_volume(&mut self, volume: &Texture, texels: &[u8]) -> Result<(), BackendError> {
        scoped(&self.gpu, "writing the wind volume", || {
            self.write_volume_texels(&volume.texture, texels);
        })
    }

    fn group_layout(&mut self, table: &GroupLayout) -> Result<wgpu::BindGroupLayout, BackendError> {
        scoped(&self.gpu, table.name, || {
            bind_group_layout(&self.gpu.device, table)
        })
    }

    fn kernel(
        &mut self,
        program: Program,
        entry_point: &'static str,
        layouts: &[&wgpu::BindGroupLayout],
    ) -> Result<wgpu::ComputePipeline, BackendError> {
        let module = self.module(program).clone();
        // The layout inside the scope too: one over the device's limits is a
        // validation error there, not a panic in wgpu's default handler.
        scoped(&self.gpu, entry_point, || {
            let layout = self.pipeline_layout(entry_point, layouts);
            self.gpu
                .device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry_point),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some(entry_point),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    cache: None,
                })
        })
    }

    fn create_texture(&mut self, desc: &TextureDesc<'_>) -> Result<Texture, BackendError> {
        let usage = match desc.usage {
            TextureUsage::DepthAttachment => {
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
            }
            TextureUsage::StorageAndSampled => {
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
            }
            TextureUsage::Sampled => {
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST
            }
            TextureUsage::ColourTarget => {
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC
            }
            TextureUsage::CopyOfTarget => {
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST
            }
            TextureUsage::DrawnThenSampled => {
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING
            }
        };
        let descriptor = wgpu::TextureDescriptor {
            label: Some(desc.label),
            size: wgpu::Extent3d {
                width: desc.size.0,
                height: desc.size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: texel_format(desc.format),
            usage,
            view_formats: &[],
        };
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let texture = scoped(&self.gpu, desc.label, || match desc.contents {
            Some(texels) => device.create_texture_with_data(
                queue,
                &descriptor,
                wgpu::util::TextureDataOrder::LayerMajor,
                texels,
            ),
            None => device.create_texture(&descriptor),
        })?;
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        Ok(Texture { texture, view })
    }

    fn read_texture(&mut self, texture: &Texture) -> Result<Vec<u8>, BackendError> {
        read_texture(&self.gpu, &texture.texture)
    }

    fn create_sampler(&mut self, sampler: Sampler) -> Result<wgpu::Sampler, BackendError> {
        let address = match sampler {
            Sampler::LinearRepeat => wgpu::AddressMode::Repeat,
            Sampler::LinearClamp | Sampler::ShadowComparison => wgpu::AddressMode::ClampToEdge,
        };
        scoped(&self.gpu, "a sampler", || {
            self.gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("precip sampler"),
                address_mode_u: address,
                address_mode_v: address,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                compare: (sampler == Sampler::ShadowComparison)
                    .then_some(wgpu::CompareFunction::LessEqual),
                ..Default::default()
            })
        })
    }

    fn draw_pipeline(
        &mut self,
        draw: &Draw,
        _pass: &RenderPassRecipe,
        layouts: &[&wgpu::BindGroupLayout],
        colour: Option<wgpu::TextureFormat>,
    ) -> Result<wgpu::RenderPipeline, BackendError> {
        let module = self.module(Program::Render).clone();
        scoped(&self.gpu, draw.entry_points.0, || {
            let layout = self.pipeline_layout(draw.entry_points.0, layouts);
            draw_pipeline(&self.gpu.device, &module, &layout, draw, colour)
        })
    }

    fn colour_format(&self, target: Target<'_, Self>) -> wgpu::TextureFormat {
        match target {
            Target::Texture(t) => t.texture.format(),
            Target::Surface(view) => view.texture().format(),
        }
    }

    fn rasterises_on_cpu(&self) -> bool {
        self.gpu.info.device_type == wgpu::DeviceType::Cpu
    }

    fn copy_format(&self, target: Target<'_, Self>) -> Option<TexelFormat> {
        let texture = match target {
            Target::Texture(t) => &t.texture,
            Target::Surface(view) => view.texture(),
        };
        if !texture.usage().contains(wgpu::TextureUsages::COPY_SRC) {
            return None;
        }
        match texture.format() {
            wgpu::TextureFormat::Rgba8UnormSrgb => Some(TexelFormat::Rgba8UnormSrgb),
            wgpu::TextureFormat::Bgra8UnormSrgb => Some(TexelFormat::Bgra8UnormSrgb),
            _ => None,
        }
    }

    fn texture_size(&self, texture: &Texture) -> (u32, u32) {
        (texture.texture.width(), texture.texture.height())
    }

    fn bind_group(
        &mut self,
        layout: &wgpu::BindGroupLayout,
        table: &GroupLayout,
        entries: &[(u32, BindingResource<'_, Self>)],
    ) -> Result<wgpu::BindGroup, BackendError> {
        let mut bound = Vec::with_capacity(entries.len());
        for (binding, resource) in entries {
            let kind = table.kind_of(*binding);
            let resource = match (resource, kind) {
                (
                    BindingResource::Buffer(buffer),
                    Some(k @ (BindingKind::Uniform { .. } | BindingKind::Storage { .. })),
                ) => wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer,
                    offset: 0,
                    size: k.block_bytes().and_then(wgpu::BufferSize::new),
                }),
                (
                    BindingResource::Volume(texture) | BindingResource::Texture(texture),
                    Some(BindingKind::Texture { .. }),
                )
                | (
                    BindingResource::StorageTexture(texture),
                    Some(BindingKind::StorageTextureRgba16Float),
                ) => wgpu::BindingResource::TextureView(&texture.view),
                (BindingResource::Sampler(sampler), Some(BindingKind::Sampler { .. })) => {
                    wgpu::BindingResource::Sampler(sampler)
                }
                _ => {
                    return Err(BackendError::Device {
                        backend: NAME,
                        message: format!(
                            "{} binding {binding}: the resource does not fit its kind {kind:?} (a bug in precip: please report it)",
                            table.name
                        ),
                    });
                }
            };
            bound.push(wgpu::BindGroupEntry {
                binding: *binding,
                resource,
            });
        }
        scoped(&self.gpu, table.name, || {
            self.gpu
                .device
                .create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(table.name),
                    layout,
                    entries: &bound,
                })
        })
    }

    fn free_slot(&mut self, _slot: u32) -> Result<(), BackendError> {
        // Queue writes are ordered with submissions: one slot, always free.
        Ok(())
    }

    fn settle(&mut self) -> Result<(), BackendError> {
        // Queue writes are ordered with submissions: nothing to wait for.
        Ok(())
    }

    fn dispatch(
        &mut self,
        dispatches: &[Dispatch<'_, Self>],
        timed: bool,
    ) -> Result<(), BackendError> {
        let gpu = &self.gpu;
        let timestamps = self.timestamps.as_mut().filter(|_| timed);
        let written = scoped(gpu, "dispatching kernels", || {
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("precip kernels"),
                });
            let mut written = 0;
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("precip kernels"),
                    timestamp_writes: None,
                });
                let mut stamp = |pass: &mut wgpu::ComputePass<'_>| {
                    if let Some(t) = &timestamps
                        && written < t.capacity()
                    {
                        pass.write_timestamp(&t.set, written);
                        written += 1;
                    }
                };
                stamp(&mut pass);
                for d in dispatches {
                    pass.set_pipeline(d.kernel);
                    let offsets: &[u32] = match &d.offset {
                        Some(o) => std::slice::from_ref(o),
                        None => &[],
                    };
                    pass.set_bind_group(0, d.group, offsets);
                    match d.indirect {
                        Some((buffer, offset)) => pass.dispatch_workgroups_indirect(buffer, offset),
                        None => pass.dispatch_workgroups(d.workgroups.0, d.workgroups.1, 1),
                    }
                    stamp(&mut pass);
                }
            }
            if let Some(t) = &timestamps {
                encoder.resolve_query_set(&t.set, 0..written, t.resolve_buffer(), 0);
            }
            gpu.queue.submit([encoder.finish()]);
            written
        })?;
        if let Some(t) = timestamps {
            t.written = written;
        }
        // Free finished work without waiting for the GPU.
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        Ok(())
    }

    fn kernel_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError> {
        match &self.timestamps {
            Some(t) => t.elapsed_ms(&self.gpu).map(Some),
            None => Ok(None),
        }
    }

    fn submit_frame(
        &mut self,
        frame: &FrameWork<'_, Self>,
        target: Target<'_, Self>,
    ) -> Result<(), BackendError> {
        let gpu = &self.gpu;
        let stamps = self.frame_stamps.as_ref();
        let colour = match target {
            Target::Texture(t) => &t.view,
            Target::Surface(view) => view,
        };
        scoped(gpu, "drawing a frame", || {
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("precip frame"),
                });
            for (index, pass) in (0u32..).zip(&frame.passes) {
                if pass.runs {
                    encode_pass(&mut encoder, pass, index, stamps, colour);
                }
            }
            if let Some(s) = stamps {
                encoder.resolve_query_set(&s.set, 0..s.capacity(), s.resolve_buffer(), 0);
            }
            gpu.queue.submit([encoder.finish()]);
        })?;
        if let Some(s) = self.frame_stamps.as_mut() {
            s.written = s.capacity();
        }
        // Free finished work without waiting for the GPU.
        let _ = self.gpu.device.poll(wgpu::PollType::Poll);
        Ok(())
    }

    fn frame_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError> {
        match &self.frame_stamps {
            Some(s) if s.written > 0 => s.pairs_ms(&self.gpu).map(Some),
            _ => Ok(None),
        }
    }

    fn forget_times(&mut self) {
        for s in [&mut self.timestamps, &mut self.frame_stamps]
            .into_iter()
            .flatten()
        {
            s.written = 0;
        }
    }

    fn has_timestamps(&self) -> bool {
        self.timestamps.is_some() || self.frame_stamps.is_some()
    }

    fn destroy_buffer(&mut self, buffer: wgpu::Buffer) {
        buffer.destroy();
    }

    fn destroy_volume(&mut self, volume: Texture) {
        volume.texture.destroy();
    }

    fn destroy_texture(&mut self, texture: Texture) {
        texture.texture.destroy();
    }
}

/// The wgpu format of `format`.
fn texel_format(format: TexelFormat) -> wgpu::TextureFormat {
    match format {
        TexelFormat::Depth32Float => DEPTH_FORMAT,
        TexelFormat::Rgba16Float => wgpu::TextureFormat::Rgba16Float,
        TexelFormat::R8Unorm => wgpu::TextureFormat::R8Unorm,
        TexelFormat::Rgba8Unorm => wgpu::TextureFormat::Rgba8Unorm,
        TexelFormat::Rgba8UnormSrgb => wgpu::TextureFormat::Rgba8UnormSrgb,
        TexelFormat::Bgra8UnormSrgb => wgpu::TextureFormat::Bgra8UnormSrgb,
    }
}
