//! The per-configuration resources of drawing: the frame's uniform block, the cull
//! lists and indirect draws, the shadow map, the flake texture, the cover's two
//! filtered textures and the bind groups.

use precip_gpu::recipe::{
    DRAWN_LIST_BYTES_PER_PARTICLE, FrameDraws, GROUP_COUNT_BYTES, cull_bindings as cb, cull_groups,
    render_bindings as rb,
};
use precip_model::drawing::render::RenderParams;
use precip_model::drawing::{FLAKE_TEXTURE_PX, snowflake_opacity};

use precip_model::Setup;

use super::layouts::RenderLayouts;
use super::pipelines::DEPTH_FORMAT;
use crate::bind_groups::COVER_TEXTURE_FORMAT;
use crate::device::GpuDevice;
use crate::gpu::Hal;
use precip_gpu::Simulation;
use precip_gpu::resources::SimBuffer;

/// What drawing adds to a configuration.
#[derive(Debug)]
pub struct FrameResources {
    /// `RenderParams`.
    pub params: wgpu::Buffer,
    /// [`FrameDraws`]: the two indirect draws and the splat count.
    pub draws: wgpu::Buffer,
    /// Workgroups of the cull kernels.
    pub cull_groups: u32,
    /// The shadow map's view (a depth attachment in the shadow pass).
    pub shadow_view: wgpu::TextureView,
    /// Group 0 of the draws.
    pub frame_group: wgpu::BindGroup,
    /// Group 1 of the draws.
    pub light_group: wgpu::BindGroup,
    /// Group 0 of the cull kernels.
    pub cull_group: wgpu::BindGroup,
    /// Group 0 of the `cover_texture` kernel.
    pub cover_texture_group: wgpu::BindGroup,
    /// Cover texels (the `cover_texture` kernel's dispatch).
    pub cover_texels: u32,
    /// The cover's two filtered textures (A, B).
    pub cover_textures: [wgpu::Texture; 3],
}

fn storage(gpu: &GpuDevice, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: wgpu::BufferUsages::STORAGE | usage,
        mapped_at_creation: false,
    })
}

fn bind(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

impl FrameResources {
    /// Allocates drawing's resources beside the simulation's `sim`.
    #[must_use]
    pub fn new(
        gpu: &GpuDevice,
        layouts: &RenderLayouts,
        sim: &Simulation<Hal>,
        setup: &Setup,
    ) -> Self {
        let shadow_map_px = setup.render.shadow_map_px;
        let device = &gpu.device;
        let count = sim.particle_count();
        let groups = cull_groups(count);
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("precip render params"),
            size: size_of::<RenderParams>() as u64,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::UNIFORM
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group_counts = storage(
            gpu,
            "precip cull groups",
            u64::from(groups) * GROUP_COUNT_BYTES,
            wgpu::BufferUsages::empty(),
        );
        let drawn = storage(
            gpu,
            "precip drawn",
            u64::from(count) * DRAWN_LIST_BYTES_PER_PARTICLE,
            wgpu::BufferUsages::empty(),
        );
        let drawn_kinds = storage(
            gpu,
            "precip drawn kinds",
            u64::from(count) * 4,
            wgpu::BufferUsages::empty(),
        );
        let draws = storage(
            gpu,
            "precip draws",
            FrameDraws::BYTES,
            wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC,
        );
        let shadow = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("precip shadow map"),
            size: wgpu::Extent3d {
                width: shadow_map_px,
                height: shadow_map_px,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let shadow_view = shadow.create_view(&wgpu::TextureViewDescriptor::default());
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("precip shadow"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let flake = wgpu::util::DeviceExt::create_texture_with_data(
            device,
            &gpu.queue,
            &wgpu::TextureDescriptor {
                label: Some("precip flake opacity"),
                size: wgpu::Extent3d {
                    width: FLAKE_TEXTURE_PX,
                    height: FLAKE_TEXTURE_PX,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::R8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &snowflake_opacity(FLAKE_TEXTURE_PX),
        );
        let flake_view = flake.create_view(&wgpu::TextureViewDescriptor::default());
        let flake_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("precip flake"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let texels = setup.cover.frame.texels;
        let cover_texture = |label| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: texels.x,
                    height: texels.y,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: COVER_TEXTURE_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let cover_textures = [
            cover_texture("precip cover a"),
            cover_texture("precip cover b"),
            cover_texture("precip cover c"),
        ];
        let [cover_a, cover_b, cover_c] = cover_textures
            .each_ref()
            .map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()));
        let cover_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("precip cover"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let view = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("precip render frame"),
            layout: &layouts.frame,
            entries: &[
                bind(rb::PARAMS, &params),
                bind(rb::PARAMS_SWITCHES, &params),
                bind(rb::GROUND_HEIGHT, sim.buffer(SimBuffer::Ground)),
                bind(rb::WAVES, sim.buffer(SimBuffer::Waves)),
                bind(rb::PARTICLES, sim.buffer(SimBuffer::Particles)),
                bind(rb::DRAWN, &drawn),
                view(rb::COVER_A, &cover_a),
                view(rb::COVER_B, &cover_b),
                view(rb::COVER_C, &cover_c),
                wgpu::BindGroupEntry {
                    binding: rb::COVER_SAMPLER,
                    resource: wgpu::BindingResource::Sampler(&cover_sampler),
                },
            ],
        });
        let cover_texture_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("precip cover texture"),
            layout: &layouts.cover_texture,
            entries: &[
                bind(rb::COVER, sim.buffer(SimBuffer::Cover)),
                view(rb::COVER_A_OUT, &cover_a),
                view(rb::COVER_B_OUT, &cover_b),
                view(rb::COVER_C_OUT, &cover_c),
            ],
        });
        let light_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("precip render light"),
            layout: &layouts.light,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: rb::SHADOW_MAP,
                    resource: wgpu::BindingResource::TextureView(&shadow_view),
                },
                wgpu::BindGroupEntry {
                    binding: rb::SHADOW_SAMPLER,
                    resource: wgpu::BindingResource::Sampler(&shadow_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: rb::FLAKE_OPACITY,
                    resource: wgpu::BindingResource::TextureView(&flake_view),
                },
                wgpu::BindGroupEntry {
                    binding: rb::FLAKE_SAMPLER,
                    resource: wgpu::BindingResource::Sampler(&flake_sampler),
                },
            ],
        });
        let cull_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("precip cull"),
            layout: &layouts.cull,
            entries: &[
                bind(cb::PARAMS, &params),
                bind(cb::PARTICLES, sim.buffer(SimBuffer::Particles)),
                bind(cb::GROUP_COUNTS, &group_counts),
                bind(cb::DRAWN, &drawn),
                bind(cb::DRAWS, &draws),
                bind(cb::DRAWN_KINDS, &drawn_kinds),
            ],
        });
        Self {
            params,
            draws,
            cull_groups: groups,
            shadow_view,
            frame_group,
            light_group,
            cull_group,
            cover_texture_group,
            cover_texels: texels.x * texels.y,
            cover_textures,
        }
    }
}
