//! The buffers, texture and bind groups of one configuration.

use precip_gpu::recipe::{
    DispatchCounts, Frames, cover_bindings, pending_births_bytes, step_bindings,
};
use precip_model::backend::MAX_SUBSTEPS;
use precip_model::cover::GridFrame;
use precip_model::cover::{CoverGrid, CoverStepParams, CoverTexel, DepositBuffer};
use precip_model::particles::step::StepParams;
use precip_model::physics::water_waves::initial_waves;
use precip_model::wind::{WindParams, WindVolume};
use precip_model::{GroundMap, Particle};
use wgpu::util::DeviceExt;

use crate::device::GpuDevice;
use crate::programs::Programs;

/// Everything a configuration allocates on the device.
#[derive(Debug)]
pub struct Resources {
    /// Particles, `array<Particle>`.
    pub particles: wgpu::Buffer,
    /// How many.
    pub particle_count: u32,
    /// Cover texels, `array<CoverTexel>`.
    pub cover: wgpu::Buffer,
    /// How many.
    pub cover_texel_count: u32,
    /// Landed water, two `u32` per cover texel.
    pub deposits: wgpu::Buffer,
    /// The particles to re-birth this sub-step and the birth kernel's indirect
    /// dispatch (`precip_gpu::recipe::pending_births_bytes`).
    pub pending_births: wgpu::Buffer,
    /// Ground heights, `array<f32>`.
    pub ground: wgpu::Buffer,
    /// The water bodies' waves (`precip_model::physics::water_waves`).
    pub waves: wgpu::Buffer,
    /// Their grid.
    pub wave_frame: GridFrame,
    /// The wind volume, 3D `Rgba32Float`.
    pub wind_texture: wgpu::Texture,
    /// `WindParams`.
    pub wind_params: wgpu::Buffer,
    /// `Frames`.
    pub frames: wgpu::Buffer,
    /// One `StepParams` per sub-step at `uniform_stride`.
    pub step_uniforms: wgpu::Buffer,
    /// One `CoverStepParams` per sub-step at `uniform_stride`.
    pub cover_uniforms: wgpu::Buffer,
    /// Bytes between sub-steps' uniform blocks (the device's offset alignment).
    pub uniform_stride: u64,
    /// Group 0 of `step_particles` / `init_particles`.
    pub step_bind_group: wgpu::BindGroup,
    /// Group 0 of `cover_update`.
    pub cover_bind_group: wgpu::BindGroup,
}

fn storage_buffer(gpu: &GpuDevice, label: &str, contents: &[u8]) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
        })
}

/// The first `size` bytes of `buffer` (a dynamic-offset uniform window).
fn sized(buffer: &wgpu::Buffer, size: usize) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: 0,
        size: wgpu::BufferSize::new(size as u64),
    })
}

fn uniform_buffer(gpu: &GpuDevice, label: &str, size: u64) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Writes the volume's texels into the 3D texture.
pub fn upload_wind(gpu: &GpuDevice, texture: &wgpu::Texture, volume: &WindVolume) {
    let n = volume.spec.texels;
    gpu.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        volume.as_bytes(),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(16 * n.x),
            rows_per_image: Some(n.y),
        },
        wgpu::Extent3d {
            width: n.x,
            height: n.y,
            depth_or_array_layers: n.z,
        },
    );
}

impl Resources {
    /// Allocates and uploads everything but the particles (the init kernel fills them).
    #[must_use]
    pub fn new(
        gpu: &GpuDevice,
        programs: &Programs,
        particle_count: u32,
        ground: &GroundMap,
        cover: &CoverGrid,
        frames: &Frames,
        wind: &WindVolume,
    ) -> Self {
        let device = &gpu.device;
        let particles = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("precip particles"),
            size: u64::from(particle_count) * size_of::<Particle>() as u64,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::VERTEX,
            mapped_at_creation: false,
        });
        let cover_buffer = storage_buffer(
            gpu,
            "precip cover",
            bytemuck::cast_slice::<CoverTexel, u8>(&cover.texels),
        );
        let deposits = storage_buffer(
            gpu,
            "precip deposits",
            &vec![0u8; DepositBuffer::bytes_for(cover.texels.len())],
        );
        let waves = storage_buffer(
            gpu,
            "precip waves",
            bytemuck::cast_slice(&initial_waves(&frames.waves, ground)),
        );
        let pending_births = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("precip pending births"),
            size: pending_births_bytes(particle_count),
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let ground_buffer = storage_buffer(
            gpu,
            "precip ground heights",
            bytemuck::cast_slice(&ground.gpu_words()),
        );
        let n = wind.spec.texels;
        let wind_texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("precip wind volume"),
            size: wgpu::Extent3d {
                width: n.x,
                height: n.y,
                depth_or_array_layers: n.z,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D3,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        upload_wind(gpu, &wind_texture, wind);
        let wind_view = wind_texture.create_view(&wgpu::TextureViewDescriptor::default());
        let wind_params = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("precip wind params"),
                contents: bytemuck::bytes_of(&wind.gpu_params()),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
        let frames_buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("precip frames"),
                contents: bytemuck::bytes_of(frames),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let alignment = u64::from(device.limits().min_uniform_buffer_offset_alignment);
        let largest = size_of::<StepParams>().max(size_of::<CoverStepParams>()) as u64;
        let uniform_stride = largest.div_ceil(alignment) * alignment;
        let step_uniforms = uniform_buffer(
            gpu,
            "precip step params",
            uniform_stride * u64::from(MAX_SUBSTEPS),
        );
        let cover_uniforms = uniform_buffer(
            gpu,
            "precip cover params",
            uniform_stride * u64::from(MAX_SUBSTEPS),
        );

        let step_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("precip step_particles"),
            layout: &programs.step_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: step_bindings::STEP_PARAMS,
                    resource: sized(&step_uniforms, size_of::<StepParams>()),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::FRAMES,
                    resource: frames_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::WIND,
                    resource: wind_params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::WIND_VOLUME,
                    resource: wgpu::BindingResource::TextureView(&wind_view),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::GROUND_HEIGHT,
                    resource: ground_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::PARTICLES,
                    resource: particles.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::DEPOSITS,
                    resource: deposits.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::WAVES,
                    resource: waves.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::COVER,
                    resource: cover_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: step_bindings::PENDING_BIRTHS,
                    resource: pending_births.as_entire_binding(),
                },
            ],
        });
        let cover_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("precip cover_update"),
            layout: &programs.cover_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: cover_bindings::COVER_PARAMS,
                    resource: sized(&cover_uniforms, size_of::<CoverStepParams>()),
                },
                wgpu::BindGroupEntry {
                    binding: cover_bindings::COVER,
                    resource: cover_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: cover_bindings::DEPOSITS,
                    resource: deposits.as_entire_binding(),
                },
            ],
        });
        Self {
            particles,
            particle_count,
            cover: cover_buffer,
            cover_texel_count: cover.texels.len() as u32,
            deposits,
            pending_births,
            ground: ground_buffer,
            waves,
            wave_frame: frames.waves,
            wind_texture,
            wind_params,
            frames: frames_buffer,
            step_uniforms,
            cover_uniforms,
            uniform_stride,
            step_bind_group,
            cover_bind_group,
        }
    }

    /// What the sub-step's dispatches run over.
    #[must_use]
    pub fn dispatch_counts(&self) -> DispatchCounts {
        DispatchCounts::of(
            self.particle_count,
            self.cover_texel_count,
            &self.wave_frame,
        )
    }

    /// Writes the wind's uniform block (mean wind changes without a re-bake).
    pub fn write_wind_params(&self, gpu: &GpuDevice, params: &WindParams) {
        gpu.queue
            .write_buffer(&self.wind_params, 0, bytemuck::bytes_of(params));
    }
}
