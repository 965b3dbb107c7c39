//! The scene on the GPU: one vertex and one index buffer for all meshes (tessellated
//! for the snow's displacement, as the wgpu backend does), and per mesh a material
//! block, a base-colour texture and their descriptor set.

use std::ops::Range;

use ash::vk;
use glam::{UVec3, Vec3};
use gpu_allocator::MemoryLocation;
use precip_gpu::recipe::{SceneVertex, render_bindings as rb};
use precip_model::GroundMap;
use precip_model::scene::gpu_scene::{PackedScene, SceneLod};
use precip_model::{BackendError, RenderSettings, Scene, TextureRgba8};

use super::Renderer;
use crate::buffer::Buffer;
use crate::descriptors::{self, image_info, sampler_info, write};
use crate::device::Device;
use crate::image::{Image, ImageSpec};
use crate::transfer::{upload, upload_image};

/// One mesh's draw.
#[derive(Debug)]
pub struct MeshDraw {
    /// Set 2: its material.
    pub material: vk::DescriptorSet,
}

/// The uploaded scene.
#[derive(Debug)]
pub struct SceneGpu {
    /// `SceneVertex` of every mesh.
    pub vertices: Buffer,
    /// `u32` indices, each mesh's offset by its first vertex.
    pub indices: Buffer,
    /// The meshes.
    pub meshes: Vec<MeshDraw>,
    /// What to draw of each mesh by distance.
    pub lod: SceneLod,
    materials: Vec<(Buffer, Image)>,
    pool: vk::DescriptorPool,
}

fn too_big(what: &str) -> BackendError {
    BackendError::Setup {
        field: "scene",
        problem: format!(
            "its {what} exceed what one GPU buffer holds: raise render.tessellation_edge_m or lower render.max_scene_triangles"
        ),
    }
}

fn texture(device: &Device, texture: Option<&TextureRgba8>) -> Result<Image, BackendError> {
    let white = TextureRgba8 {
        width_px: 1,
        height_px: 1,
        rgba8: vec![255; 4],
    };
    let t = texture.unwrap_or(&white);
    // Its size was checked against the device with the setup (DeviceLimits).
    let image = Image::new(
        device,
        &ImageSpec {
            name: "base colour",
            extent: UVec3::new(t.width_px, t.height_px, 1),
            format: vk::Format::R8G8B8A8_SRGB,
            usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
        },
    )?;
    if let Err(e) = upload_image(device, &image, &t.rgba8) {
        image.destroy(device);
        return Err(e);
    }
    Ok(image)
}

impl SceneGpu {
    /// Tessellates and uploads `scene` (prepared: complete attributes).
    pub fn upload(
        device: &Device,
        renderer: &Renderer,
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
            device.limits().check_packed_scene(&packed)?;
            packed
        };
        let mesh_count = u32::try_from(ranges.len().max(1)).map_err(|_| too_big("meshes"))?;
        use vk::DescriptorType as T;
        let pool = descriptors::pool(
            device,
            "materials",
            &[
                (T::UNIFORM_BUFFER, mesh_count),
                (T::SAMPLED_IMAGE, mesh_count),
                (T::SAMPLER, mesh_count),
            ],
            mesh_count,
        )?;
        let mut gpu = Self {
            vertices: Buffer::new(
                device,
                "scene vertices",
                16,
                vk::BufferUsageFlags::VERTEX_BUFFER,
                MemoryLocation::GpuOnly,
            )?,
            indices: Buffer::new(
                device,
                "scene indices",
                16,
                vk::BufferUsageFlags::INDEX_BUFFER,
                MemoryLocation::GpuOnly,
            )?,
            meshes: Vec::with_capacity(ranges.len()),
            materials: Vec::with_capacity(ranges.len()),
            lod,
            pool,
        };
        // From here on `gpu` owns what is made, so an error frees it all.
        match gpu.fill(device, renderer, &scene, ranges, &vertices, &indices) {
            Ok(()) => Ok(gpu),
            Err(e) => {
                gpu.destroy(device);
                Err(e)
            }
        }
    }

    fn fill(
        &mut self,
        device: &Device,
        renderer: &Renderer,
        scene: &Scene,
        ranges: Vec<Range<u32>>,
        vertices: &[SceneVertex],
        indices: &[u32],
    ) -> Result<(), BackendError> {
        let copy_usage = vk::BufferUsageFlags::TRANSFER_DST;
        for (buffer, name, usage, bytes) in [
            (
                &mut self.vertices,
                "scene vertices",
                vk::BufferUsageFlags::VERTEX_BUFFER,
                bytemuck::cast_slice::<SceneVertex, u8>(vertices),
            ),
            (
                &mut self.indices,
                "scene indices",
                vk::BufferUsageFlags::INDEX_BUFFER,
                bytemuck::cast_slice::<u32, u8>(indices),
            ),
        ] {
            let new = Buffer::new(
                device,
                name,
                bytes.len() as u64,
                usage | copy_usage,
                MemoryLocation::GpuOnly,
            )?;
            std::mem::replace(buffer, new).destroy(device);
            upload(device, buffer, bytes)?;
        }
        for mesh in scene.meshes.iter().take(ranges.len()) {
            let image = texture(device, mesh.material.base_colour_texture.as_ref())?;
            let mut colour = match Buffer::new(
                device,
                "material",
                16,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            ) {
                Ok(b) => b,
                Err(e) => {
                    image.destroy(device);
                    return Err(e);
                }
            };
            let written = colour.write(0, bytemuck::cast_slice(&mesh.material.base_colour));
            let (colour_raw, view) = (colour.raw, image.view);
            self.materials.push((colour, image));
            written?;
            let set = descriptors::allocate(device, self.pool, &[renderer.layouts.material])?[0];
            let buffer = [vk::DescriptorBufferInfo {
                buffer: colour_raw,
                offset: 0,
                range: 16,
            }];
            let image = image_info(view);
            let sampler = sampler_info(renderer.samplers.material);
            let write = |b, ty| write(set, b, ty);
            let writes = [
                write(rb::MATERIAL, vk::DescriptorType::UNIFORM_BUFFER).buffer_info(&buffer),
                write(rb::BASE_COLOUR_TEXTURE, vk::DescriptorType::SAMPLED_IMAGE)
                    .image_info(&image),
                write(rb::MATERIAL_SAMPLER, vk::DescriptorType::SAMPLER).image_info(&sampler),
            ];
            // SAFETY: the buffer, view and sampler are live and of the bindings' types.
            unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
            self.meshes.push(MeshDraw { material: set });
        }
        Ok(())
    }

    /// Records every mesh's draw, fine near `camera_m` and coarse beyond
    /// `detail_distance_m` (`SceneLod::ranges`); set 2 (materials) only when
    /// `with_materials`.
    pub fn draw(
        &self,
        device: &Device,
        cb: vk::CommandBuffer,
        layout: vk::PipelineLayout,
        with_materials: bool,
        (camera_m, detail_distance_m): (Vec3, f32),
    ) {
        // SAFETY: `cb` is recording inside a render pass with a scene pipeline bound;
        // the buffers and sets are live.
        unsafe {
            device
                .raw
                .cmd_bind_vertex_buffers(cb, 0, &[self.vertices.raw], &[0]);
            device
                .raw
                .cmd_bind_index_buffer(cb, self.indices.raw, 0, vk::IndexType::UINT32);
            for (m, mesh) in self.meshes.iter().enumerate() {
                if with_materials {
                    device.raw.cmd_bind_descriptor_sets(
                        cb,
                        vk::PipelineBindPoint::GRAPHICS,
                        layout,
                        2,
                        &[mesh.material],
                        &[],
                    );
                }
                for range in self.lod.ranges(m, camera_m, detail_distance_m) {
                    device
                        .raw
                        .cmd_draw_indexed(cb, range.end - range.start, 1, range.start, 0, 0);
                }
            }
        }
    }

    /// Frees everything (no pending work may use it).
    pub fn destroy(self, device: &Device) {
        // SAFETY: no pending work uses the pool's sets; destroyed once.
        unsafe { device.raw.destroy_descriptor_pool(self.pool, None) };
        self.vertices.destroy(device);
        self.indices.destroy(device);
        for (b, i) in self.materials {
            b.destroy(device);
            i.destroy(device);
        }
    }
}
