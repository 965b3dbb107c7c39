//! The scene on the GPU: one vertex and one index buffer for all meshes (tessellated
//! for the snow's displacement), and a material bind group per mesh.

use glam::Vec3;
use precip_gpu::recipe::render_bindings as rb;
use precip_model::GroundMap;
use precip_model::scene::gpu_scene::{PackedScene, SceneLod};
use precip_model::{BackendError, RenderSettings, Scene, TextureRgba8};
use wgpu::util::DeviceExt;

use super::layouts::RenderLayouts;
use crate::device::GpuDevice;

/// One mesh's draw.
#[derive(Debug)]
pub struct MeshDraw {
    /// Group 2: its material.
    pub material: wgpu::BindGroup,
}

/// The uploaded scene.
#[derive(Debug)]
pub struct SceneGpu {
    /// `SceneVertex` of every mesh.
    pub vertices: wgpu::Buffer,
    /// `u32` indices, each mesh's offset by its first vertex.
    pub indices: wgpu::Buffer,
    /// The meshes.
    pub meshes: Vec<MeshDraw>,
    /// Triangles drawn (after tessellation).
    pub triangles: u64,
    /// What to draw of each mesh by distance.
    pub lod: SceneLod,
}

fn texture_of(
    gpu: &GpuDevice,
    texture: Option<&TextureRgba8>,
) -> Result<wgpu::Texture, BackendError> {
    let white = TextureRgba8 {
        width_px: 1,
        height_px: 1,
        rgba8: vec![255; 4],
    };
    let t = texture.unwrap_or(&white);
    // Its size was checked against the device with the setup (DeviceLimits).
    Ok(gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("precip base colour"),
            size: wgpu::Extent3d {
                width: t.width_px,
                height: t.height_px,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &t.rgba8,
    ))
}

impl SceneGpu {
    /// Tessellates and uploads `scene` (prepared: complete attributes).
    pub fn upload(
        gpu: &GpuDevice,
        layouts: &RenderLayouts,
        scene: &Scene,
        settings: &RenderSettings,
        ground: &GroundMap,
    ) -> Result<Self, BackendError> {
        let PackedScene {
            scene,
            vertices,
            indices,
            ranges,
            lod,
        } = {
            let packed = PackedScene::new(scene, settings, ground)?;
            gpu.limits().check_packed_scene(&packed)?;
            packed
        };
        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("precip material"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let mut meshes = Vec::with_capacity(ranges.len());
        for mesh in scene.meshes.iter().take(ranges.len()) {
            let texture = texture_of(gpu, mesh.material.base_colour_texture.as_ref())?;
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            let colour = gpu
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("precip material"),
                    contents: bytemuck::cast_slice(&mesh.material.base_colour),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
            let material = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("precip material"),
                layout: &layouts.material,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: rb::MATERIAL,
                        resource: colour.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: rb::BASE_COLOUR_TEXTURE,
                        resource: wgpu::BindingResource::TextureView(&view),
                    },
                    wgpu::BindGroupEntry {
                        binding: rb::MATERIAL_SAMPLER,
                        resource: wgpu::BindingResource::Sampler(&sampler),
                    },
                ],
            });
            meshes.push(MeshDraw { material });
        }
        let init = |label, contents: &[u8], usage| {
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage,
                })
        };
        Ok(Self {
            vertices: init(
                "precip scene vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: init(
                "precip scene indices",
                bytemuck::cast_slice(&indices),
                wgpu::BufferUsages::INDEX,
            ),
            triangles: indices.len() as u64 / 3,
            meshes,
            lod,
        })
    }

    /// Draws every mesh, fine near `camera_m` and coarse beyond
    /// `detail_distance_m` (`SceneLod::ranges`); group 2 (materials) only when
    /// `with_materials`.
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        with_materials: bool,
        camera_m: Vec3,
        detail_distance_m: f32,
    ) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        for (m, mesh) in self.meshes.iter().enumerate() {
            if with_materials {
                pass.set_bind_group(2, &mesh.material, &[]);
            }
            for range in self.lod.ranges(m, camera_m, detail_distance_m) {
                pass.draw_indexed(range, 0, 0..1);
            }
        }
    }
}
