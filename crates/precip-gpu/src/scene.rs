//! The scene on the GPU, made once per configuration over any [`Gpu`]: one vertex
//! and one index buffer for every mesh (tessellated for the snow's displacement,
//! `precip_model::scene::gpu_scene::PackedScene`), and per mesh a material group
//! (its base colour block, its base colour texture or a white texel, a repeating
//! sampler). [`SceneGpu::draw`] turns the scene into a draw's commands: fine
//! triangles near the camera, coarse beyond (`SceneLod::ranges`).

use glam::Vec3;
use precip_model::scene::gpu_scene::{PackedScene, SceneLod, TileCull, TileRegion};
use precip_model::scene::terrain::terrain_ramp;
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

impl<G: Gpu> Material<G> {
    /// A material of `base_colour` (linear RGBA) over `texture`; `(water_body, sea)`.
    fn new(
        gpu: &mut G,
        base_colour: [f32; 4],
        texture: &TextureRgba8,
        (water_body, sea): (bool, bool),
    ) -> Result<Self, BackendError> {
        let colour = gpu.create_buffer(
            "precip material",
            16,
            BufferUsage::Uniform,
            Some(bytemuck::cast_slice(&base_colour)),
        )?;
        match gpu.create_texture(&TextureDesc {
            label: "precip base colour",
            size: (texture.width_px, texture.height_px),
            format: TexelFormat::Rgba8UnormSrgb,
            usage: TextureUsage::Sampled,
            contents: Some(&texture.rgba8),
        }) {
            Ok(texture) => Ok(Self {
                colour,
                texture,
                group: None,
                water_body,
                sea,
            }),
            Err(e) => {
                gpu.destroy_buffer(colour);
                Err(e)
            }
        }
    }

    /// Makes its group (of [`RENDER_MATERIAL`]) with `sampler`.
    fn bind(
        &mut self,
        gpu: &mut G,
        layout: &G::GroupLayout,
        sampler: &G::Sampler,
    ) -> Result<(), BackendError> {
        self.group = Some(gpu.bind_group(
            layout,
            &RENDER_MATERIAL,
            &[
                (rb::MATERIAL, BindingResource::Buffer(&self.colour)),
                (
                    rb::BASE_COLOUR_TEXTURE,
                    BindingResource::Texture(&self.texture),
                ),
                (rb::MATERIAL_SAMPLER, BindingResource::Sampler(sampler)),
            ],
        )?);
        Ok(())
    }

    fn destroy(self, gpu: &mut G) {
        if let Some(g) = self.group {
            gpu.destroy_bind_group(g);
        }
        gpu.destroy_texture(self.texture);
        gpu.destroy_buffer(self.colour);
    }
}

/// The uploaded scene.
#[derive(Debug)]
pub struct SceneGpu<G: Gpu> {
    vertices: Option<G::Buffer>,
    indices: Option<G::Buffer>,
    sampler: Option<G::Sampler>,
    materials: Vec<Material<G>>,
    /// The terrain's material (its slope's colours), where the scene stands on one.
    terrain: Option<Material<G>>,
    /// The terrain's clipmap's indices, every level the pyramid may have
    /// (`precip_model::scene::terrain::clipmap_indices`), where it stands on one.
    terrain_indices: Option<G::Buffer>,
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
            terrain: None,
            terrain_indices: None,
            lod: packed.lod.clone(),
        };
        match made.fill(gpu, &packed, material_layout, scene.terrain().is_some()) {
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
        on_terrain: bool,
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
            // Its size was checked against the device with the setup (DeviceLimits).
            let t = mesh.material.base_colour_texture.as_ref().unwrap_or(&white);
            self.materials.push(Material::new(
                gpu,
                mesh.material.base_colour,
                t,
                (mesh.is_water_body(), mesh.is_sea()),
            )?);
            if let Some(material) = self.materials.last_mut() {
                material.bind(gpu, material_layout, sampler)?;
            }
        }
        if on_terrain {
            let ramp = terrain_ramp();
            let terrain = self
                .terrain
                .insert(Material::new(gpu, [1.0; 4], &ramp, (false, false))?);
            terrain.bind(gpu, material_layout, sampler)?;
            let indices = precip_model::scene::terrain::clipmap_indices(
                precip_model::scene::terrain::MAX_TERRAIN_LEVELS as u32,
            );
            self.terrain_indices = Some(gpu.create_buffer(
                "precip terrain clipmap indices",
                (indices.len() * 4) as u64,
                BufferUsage::Indices,
                Some(bytemuck::cast_slice(&indices)),
            )?);
        }
        Ok(())
    }

    /// The commands drawing the terrain's clipmap (its first `indices` indices),
    /// its material group bound at 2 when `with_material`.
    pub fn draw_terrain<'a>(
        &'a self,
        commands: &mut Vec<Command<'a, G>>,
        with_material: bool,
        indices: u32,
    ) {
        let (Some(terrain), Some(terrain_indices), Some(vertices)) =
            (&self.terrain, &self.terrain_indices, &self.vertices)
        else {
            return;
        };
        if indices == 0 {
            return;
        }
        if with_material && let Some(group) = &terrain.group {
            commands.push(Command::Group {
                index: 2,
                group,
                offsets: &[],
            });
        }
        // The clipmap's vertices come from storage: the scene's vertex buffer is
        // bound beside its indices only because the command binds both.
        commands.push(Command::Meshes {
            vertices,
            indices: terrain_indices,
        });
        commands.push(Command::DrawIndexed(0..indices));
    }

    /// How far the fine triangles are drawn for `view`, m.
    #[must_use]
    pub fn detail_distance_m(&self, view: &precip_model::View) -> f32 {
        self.lod.detail_distance_m(view)
    }

    /// The commands drawing the meshes `which` picks, fine near `camera_m` and
    /// coarse beyond `detail_distance_m`, only the tiles `cull` may see and `region`
    /// takes (all without them), nearest first; each mesh's material group bound at
    /// 2 when `with_materials`.
    pub fn draw<'a>(
        &'a self,
        commands: &mut Vec<Command<'a, G>>,
        (with_materials, which): (bool, MeshesOf),
        camera_m: Vec3,
        detail_distance_m: f32,
        within: (Option<TileCull>, Option<TileRegion>),
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
        // Nearest first (SceneLod::front_to_back: what they hide is not shaded),
        // each mesh's material bound when the draws come to it.
        let meshes = (0..self.materials.len()).filter(|&m| picked(&self.materials[m]));
        let mut bound = None;
        for range in self
            .lod
            .front_to_back(meshes, camera_m, detail_distance_m, within)
        {
            if with_materials
                && bound != Some(range.mesh)
                && let Some(group) = &self.materials[range.mesh].group
            {
                commands.push(Command::Group {
                    index: 2,
                    group,
                    offsets: &[],
                });
                bound = Some(range.mesh);
            }
            commands.push(Command::DrawIndexed(range.indices));
        }
    }

    /// Hands everything back to `gpu`.
    pub fn destroy(self, gpu: &mut G) {
        for m in self.materials.into_iter().chain(self.terrain) {
            m.destroy(gpu);
        }
        if let Some(s) = self.sampler {
            gpu.destroy_sampler(s);
        }
        for b in [self.vertices, self.indices, self.terrain_indices]
            .into_iter()
            .flatten()
        {
            gpu.destroy_buffer(b);
        }
    }
}
