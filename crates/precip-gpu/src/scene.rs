//! The scene on the GPU, made once per configuration over any [`Gpu`]: one vertex
//! and one index buffer for every mesh (tessellated for the snow's displacement,
//! `precip_model::scene::gpu_scene::PackedScene`), and per mesh a material group
//! (its base colour block, its base colour texture or a white texel, a repeating
//! sampler). [`SceneGpu::draw`] turns the scene into a draw's commands: fine
//! triangles near the camera, coarse beyond (`SceneLod::ranges`).

use glam::Vec3;
use precip_model::scene::gpu_scene::{PackedScene, SceneLod, TileCull};
use precip_model::{BackendError, Setup, TextureRgba8};

use crate::bind_groups::RENDER_MATERIAL;
use crate::frame::MeshesOf;
use crate::frame_resources::{Sampler, TexelFormat, TextureUsage};
use crate::gpu::{BindingResource, Command, Gpu, TextureDesc};
use crate::recipe::render_bindings as rb;
use crate::resources::BufferUsage;

/// One mesh's material.
#[derive(Debug)]
struct Material<G: Gpu> {
    colour: G::Buffer,
    texture: G::Texture,
    group: Option<G::BindGroup>,
    /// The mesh is a water body (tagged water).
    water_body: bool,
    /// The mesh is the sea (tagged `"water": "sea"`).
    sea: bool,
}

/// The uploaded scene.
#[derive(Debug)]
pub struct SceneGpu<G: Gpu> {
    vertices: Option<G::Buffer>,
    indices: Option<G::Buffer>,
    sampler: Option<G::Sampler>,
    materials: Vec<Material<G>>,
    lod: SceneLod,
}

impl<G: Gpu> SceneGpu<G> {
    /// Tessellates and uploads `setup`'s scene, if it has one; its material groups
    /// are made with `material_layout` (of [`RENDER_MATERIAL`]).
    pub fn upload(
        gpu: &mut G,
        setup: &Setup,
        material_layout: &G::GroupLayout,
    ) -> Result<Option<Self>, BackendError> {
        let Some(scene) = &setup.scene else {
            return Ok(None);
        };
        let packed = PackedScene::new(scene, &setup.render, &setup.ground)?;
        gpu.limits().check_packed_scene(&packed)?;
        let mut made = Self {
            vertices: None,
            indices: None,
            sampler: None,
            materials: Vec::new(),
            lod: packed.lod.clone(),
        };
        match made.fill(gpu, &packed, material_layout) {
            Ok(()) => Ok(Some(made)),
            Err(e) => {
                made.destroy(gpu);
                Err(e)
            }
        }
    }

    fn fill(
        &mut self,
        gpu: &mut G,
        packed: &PackedScene,
        material_layout: &G::GroupLayout,
    ) -> Result<(), BackendError> {
        let vertices: &[u8] = bytemuck::cast_slice(&packed.vertices);
        let indices: &[u8] = bytemuck::cast_slice(&packed.indices);
        self.vertices = Some(gpu.create_buffer(
            "precip scene vertices",
            vertices.len().max(4) as u64,
            BufferUsage::Vertices,
            (!vertices.is_empty()).then_some(vertices),
        )?);
        self.indices = Some(gpu.create_buffer(
            "precip scene indices",
            indices.len().max(4) as u64,
            BufferUsage::Indices,
            (!indices.is_empty()).then_some(indices),
        )?);
        let sampler = gpu.create_sampler(Sampler::LinearRepeat)?;
        let sampler = &*self.sampler.insert(sampler);
        let white = TextureRgba8 {
            width_px: 1,
            height_px: 1,
            rgba8: vec![255; 4],
        };
        for mesh in packed.scene.meshes.iter().take(packed.ranges.len()) {
            let colour = gpu.create_buffer(
                "precip material",
                16,
                BufferUsage::Uniform,
                Some(bytemuck::cast_slice(&mesh.material.base_colour)),
            )?;
            // Its size was checked against the device with the setup (DeviceLimits).
            let t = mesh.material.base_colour_texture.as_ref().unwrap_or(&white);
            let texture = match gpu.create_texture(&TextureDesc {
                label: "precip base colour",
                size: (t.width_px, t.height_px),
                format: TexelFormat::Rgba8UnormSrgb,
                usage: TextureUsage::Sampled,
                contents: Some(&t.rgba8),
            }) {
                Ok(texture) => texture,
                Err(e) => {
                    gpu.destroy_buffer(colour);
                    return Err(e);
                }
            };
            self.materials.push(Material {
                colour,
                texture,
                group: None,
                water_body: mesh.is_water_body(),
                sea: mesh.is_sea(),
            });
            let Some(material) = self.materials.last_mut() else {
                continue;
            };
            material.group = Some(gpu.bind_group(
                material_layout,
                &RENDER_MATERIAL,
                &[
                    (rb::MATERIAL, BindingResource::Buffer(&material.colour)),
                    (
                        rb::BASE_COLOUR_TEXTURE,
                        BindingResource::Texture(&material.texture),
                    ),
                    (rb::MATERIAL_SAMPLER, BindingResource::Sampler(sampler)),
                ],
            )?);
        }
        Ok(())
    }

    /// How far the fine triangles are drawn for `view`, m.
    #[must_use]
    pub fn detail_distance_m(&self, view: &precip_model::View) -> f32 {
        self.lod.detail_distance_m(view)
    }

    /// The commands drawing the meshes `which` picks, fine near `camera_m` and
    /// coarse beyond `detail_distance_m`, only the tiles `cull` may see; each mesh's
    /// material group bound at 2 when `with_materials`.
    pub fn draw<'a>(
        &'a self,
        commands: &mut Vec<Command<'a, G>>,
        (with_materials, which): (bool, MeshesOf),
        camera_m: Vec3,
        detail_distance_m: f32,
        cull: Option<TileCull>,
    ) {
        let (Some(vertices), Some(indices)) = (&self.vertices, &self.indices) else {
            return;
        };
        let picked = |m: &Material<G>| match which {
            MeshesOf::All => true,
            MeshesOf::WaterBodies => m.water_body && !m.sea,
            MeshesOf::Sea => m.sea,
            MeshesOf::AllButWaterBodies => !m.water_body,
        };
        if !self.materials.iter().any(picked) {
            return;
        }
        commands.push(Command::Meshes { vertices, indices });
        for (m, material) in self.materials.iter().enumerate() {
            if !picked(material) {
                continue;
            }
            if with_materials && let Some(group) = &material.group {
                commands.push(Command::Group {
                    index: 2,
                    group,
                    offsets: &[],
                });
            }
            for range in self.lod.ranges(m, camera_m, detail_distance_m, cull) {
                commands.push(Command::DrawIndexed(range));
            }
        }
    }

    /// Hands everything back to `gpu`.
    pub fn destroy(self, gpu: &mut G) {
        for m in self.materials {
            if let Some(g) = m.group {
                gpu.destroy_bind_group(g);
            }
            gpu.destroy_texture(m.texture);
            gpu.destroy_buffer(m.colour);
        }
        if let Some(s) = self.sampler {
            gpu.destroy_sampler(s);
        }
        for b in [self.vertices, self.indices].into_iter().flatten() {
            gpu.destroy_buffer(b);
        }
    }
}
