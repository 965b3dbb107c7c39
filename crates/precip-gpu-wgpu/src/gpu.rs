//! [`Hal`]: the device calls of [`precip_gpu::Gpu`] on wgpu (Vulkan twin:
//! `precip_gpu_vk::gpu`). Nothing here knows what the buffers hold or which kernels
//! run: the executor of `precip-gpu` decides.

use std::collections::HashMap;

use precip_gpu::bind_groups::{BindingKind, GroupLayout};
use precip_gpu::gpu::{BindingResource, Dispatch, Gpu};
use precip_gpu::resources::BufferUsage;
use precip_gpu::shaders::Program;
use precip_model::BackendError;
use wgpu::util::DeviceExt;

use crate::bind_groups::bind_group_layout;
use crate::device::GpuDevice;
use crate::error::map_scope_error;
use crate::query::Timestamps;
use crate::transfer::read_buffer;

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

/// A 3D texture and its view.
#[derive(Debug)]
pub struct Volume {
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
    /// Timestamp queries, where the adapter has them.
    pub timestamps: Option<Timestamps>,
    modules: HashMap<Program, wgpu::ShaderModule>,
}

impl Hal {
    /// The calls on `gpu`.
    #[must_use]
    pub fn new(gpu: GpuDevice) -> Self {
        Self {
            timestamps: Timestamps::new(&gpu),
            gpu,
            modules: HashMap::new(),
        }
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
    type Volume = Volume;
    type GroupLayout = wgpu::BindGroupLayout;
    type BindGroup = wgpu::BindGroup;
    type Kernel = wgpu::ComputePipeline;

    fn limits(&self) -> precip_model::DeviceLimits {
        self.gpu.limits()
    }

    fn uniform_alignment(&self) -> u64 {
        u64::from(self.gpu.device.limits().min_uniform_buffer_offset_alignment)
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
    ) -> Result<Volume, BackendError> {
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
        Ok(Volume { texture, view })
    }

    fn write_volume(&mut self, volume: &Volume, texels: &[u8]) -> Result<(), BackendError> {
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
        layout: &wgpu::BindGroupLayout,
    ) -> Result<wgpu::ComputePipeline, BackendError> {
        let device = &self.gpu.device;
        let module = self
            .modules
            .entry(program)
            .or_insert_with(|| shader_module(device, program));
        scoped(&self.gpu, entry_point, || {
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(entry_point),
                bind_group_layouts: &[Some(layout)],
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some(entry_point),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        })
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
                (BindingResource::Buffer(buffer), Some(BindingKind::Uniform { min_bytes, .. })) => {
                    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(min_bytes),
                    })
                }
                (BindingResource::Buffer(buffer), Some(BindingKind::Storage { .. })) => {
                    buffer.as_entire_binding()
                }
                (BindingResource::Volume(volume), Some(BindingKind::Texture { .. })) => {
                    wgpu::BindingResource::TextureView(&volume.view)
                }
                _ => {
                    return Err(BackendError::Device {
                        backend: crate::error::NAME,
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
                    pass.dispatch_workgroups(d.workgroups.0, d.workgroups.1, 1);
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

    fn destroy_buffer(&mut self, buffer: wgpu::Buffer) {
        buffer.destroy();
    }

    fn destroy_volume(&mut self, volume: Volume) {
        volume.texture.destroy();
    }

    fn destroy_bind_group(&mut self, _group: wgpu::BindGroup) {}

    fn destroy_kernel(&mut self, _kernel: wgpu::ComputePipeline) {}

    fn destroy_group_layout(&mut self, _layout: wgpu::BindGroupLayout) {}
}
