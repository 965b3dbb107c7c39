//! The frame run over any [`Gpu`], written once: [`Drawing`] is a device's frame
//! objects (the frame groups' layouts, the frame's kernels, and per colour format
//! one pipeline per draw of [`crate::frame::FRAME_PASSES`]); [`FrameState`] is one
//! configuration's (the buffers, textures, samplers and groups of
//! [`crate::frame_resources`], the scene, the target's depth buffer and splat sums,
//! the offscreen image, the ring of `RenderParams` blocks).
//!
//! A frame ([`FrameState::draw`]): the host decides it ([`FrameHost::decide`]: its
//! block, whether the shadow map is redrawn, the sky's colour), its block goes into
//! the next slot of the ring, and [`frame_plan`] is walked into a [`FrameWork`] —
//! each kernel with its groups and workgroups, each draw with its pipeline, groups
//! and draw call — which the backend submits ([`Gpu::submit_frame`]). What a pass
//! binds comes from `bind_groups::groups_of` and the resources tables; nothing of
//! it is written per backend.

use precip_model::drawing::clouds::CLOUD_MARCH_ALL;
use precip_model::drawing::water_mirror::MIRROR_DOWNSCALE;
use precip_model::scene::gpu_scene::{TileCull, TileRegion};
use precip_model::{
    BackendError, DrawnCounts, Image, Mirrors, ParticleResolution, PassTiming, View,
};

use crate::bind_groups::{GroupLayout, RENDER_MATERIAL, groups_of};
use crate::executor::Simulation;
use crate::frame::{
    self, ColourTarget, DepthTarget, DrawOf, FRAME_PASSES, FrameDecision, FrameHost, PassWork,
    SceneTiles, frame_plan,
};
use crate::frame_resources::{
    FRAME_GROUPS, FrameBound, FrameBuffer, FrameGroupFill, FrameTexture, Sampler, TARGET_GROUPS,
    TargetResource, TexelFormat, TextureUsage, frame_buffers, frame_textures, splat_sums_bytes,
    target_textures,
};
use crate::gpu::{
    Attachments, BindingResource, Command, FrameWork, Gpu, PassKind, RecordedPass, Target,
    TextureDesc,
};
use crate::recipe::{DispatchCounts, FrameDraws};
use crate::resources::BufferUsage;
use crate::scene::SceneGpu;
use crate::shaders::Program;

/// A bug in precip: a resource the tables name was not made.
fn missing(what: &str) -> BackendError {
    BackendError::Device {
        backend: "precip-gpu",
        message: format!("{what} of the frame is missing (a bug in precip: please report it)"),
    }
}

/// Finds the value paired with `key`.
fn find<'a, K: PartialEq, V>(pairs: &'a [(K, V)], key: &K) -> Option<&'a V> {
    pairs.iter().find(|(k, _)| k == key).map(|(_, v)| v)
}

/// Every group table the frame's kernels and draws bind, once each.
fn frame_tables() -> Vec<&'static GroupLayout> {
    let mut tables: Vec<&'static GroupLayout> = Vec::new();
    let entries = frame::kernels()
        .map(|k| (k.program, k.entry_point))
        .chain(frame::draws().map(|(_, d)| (Program::Render, d.entry_points.0)));
    for (program, entry) in entries {
        for table in groups_of(program, entry).unwrap_or(&[]) {
            if !tables.iter().any(|t| t.name == table.name) {
                tables.push(table);
            }
        }
    }
    tables
}

/// The pipelines of every draw for one colour format, by vertex entry point.
type Pipelines<G> = Vec<(&'static str, <G as Gpu>::DrawPipeline)>;

/// A device's frame objects: layouts, kernels, and draw pipelines per colour format.
#[derive(Debug)]
pub struct Drawing<G: Gpu> {
    layouts: Vec<(&'static str, G::GroupLayout)>,
    kernels: Vec<(&'static str, G::Kernel)>,
    pipelines: Vec<(G::ColourFormat, Pipelines<G>)>,
}

impl<G: Gpu> Drawing<G> {
    /// The frame groups' layouts and the frame's kernels on `gpu`.
    pub fn new(gpu: &mut G) -> Result<Self, BackendError> {
        let mut made = Self {
            layouts: Vec::new(),
            kernels: Vec::new(),
            pipelines: Vec::new(),
        };
        match made.fill(gpu) {
            Ok(()) => Ok(made),
            Err(e) => {
                made.destroy(gpu);
                Err(e)
            }
        }
    }

    fn fill(&mut self, gpu: &mut G) -> Result<(), BackendError> {
        for table in frame_tables() {
            let layout = gpu.group_layout(table)?;
            self.layouts.push((table.name, layout));
        }
        for k in frame::kernels() {
            let layouts = self.layouts_of(k.program, k.entry_point)?;
            let kernel = gpu.kernel(k.program, k.entry_point, &layouts)?;
            self.kernels.push((k.entry_point, kernel));
        }
        Ok(())
    }

    /// The layouts of `entry_point`'s groups, at 0, 1, ….
    fn layouts_of(
        &self,
        program: Program,
        entry_point: &str,
    ) -> Result<Vec<&G::GroupLayout>, BackendError> {
        groups_of(program, entry_point)
            .unwrap_or(&[])
            .iter()
            .map(|t| find(&self.layouts, &t.name).ok_or_else(|| missing(t.name)))
            .collect()
    }

    /// The layout of `table`.
    fn layout(&self, table: &GroupLayout) -> Result<&G::GroupLayout, BackendError> {
        find(&self.layouts, &table.name).ok_or_else(|| missing(table.name))
    }

    /// Makes the draws' pipelines for a frame target of `format` (and the images
    /// of `image_format`: the particles' and the mirror's), if not made yet.
    pub fn prepare(
        &mut self,
        gpu: &mut G,
        format: G::ColourFormat,
        image_format: G::ColourFormat,
    ) -> Result<(), BackendError> {
        if self.pipelines.iter().any(|(f, _)| *f == format) {
            return Ok(());
        }
        let mut made: Pipelines<G> = Vec::new();
        for (pass, draw) in frame::draws() {
            let PassWork::Render(recipe) = &pass.work else {
                continue;
            };
            // Draws of one key share their pipeline (the same entry points and state).
            if made.iter().any(|(k, _)| *k == draw.key()) {
                continue;
            }
            let pipeline = self
                .layouts_of(Program::Render, draw.entry_points.0)
                .and_then(|layouts| {
                    let colour = match recipe.colour_target {
                        ColourTarget::Frame => format,
                        ColourTarget::Particles
                        | ColourTarget::Mirror
                        | ColourTarget::Clouds
                        | ColourTarget::CloudsB
                        | ColourTarget::CloudsFresh => image_format,
                    };
                    gpu.draw_pipeline(draw, recipe, &layouts, recipe.colour.map(|_| colour))
                });
            match pipeline {
                Ok(p) => made.push((draw.key(), p)),
                Err(e) => {
                    for (_, p) in made {
                        gpu.destroy_draw_pipeline(p);
                    }
                    return Err(e);
                }
            }
        }
        self.pipelines.push((format, made));
        Ok(())
    }

    /// Hands everything back to `gpu`.
    pub fn destroy(self, gpu: &mut G) {
        for (_, pipelines) in self.pipelines {
            for (_, p) in pipelines {
                gpu.destroy_draw_pipeline(p);
            }
        }
        for (_, k) in self.kernels {
            gpu.destroy_kernel(k);
        }
        for (_, l) in self.layouts {
            gpu.destroy_group_layout(l);
        }
    }
}

/// The textures a target of one size and format adds
/// ([`crate::frame_resources::target_textures`]).
#[derive(Debug)]
struct TargetTextures<G: Gpu> {
    made: Vec<(TargetResource, G::Texture)>,
}

impl<G: Gpu> TargetTextures<G> {
    /// Those of a `size` target copying to `copy_format`, the particles drawn at
    /// `particles`, the water bodies mirrored or not (`mirrors`); on an error, those
    /// made are handed back.
    fn new(
        gpu: &mut G,
        size: (u32, u32),
        copy_format: TexelFormat,
        particles: ParticleResolution,
        mirrors: bool,
    ) -> Result<Self, BackendError> {
        let mut made = Self { made: Vec::new() };
        for spec in target_textures(size, copy_format, particles, mirrors) {
            let desc = TextureDesc {
                label: spec.label,
                size: spec.size,
                format: spec.format,
                usage: spec.usage,
                contents: None,
            };
            match gpu.create_texture(&desc) {
                Ok(t) => made.made.push((spec.resource, t)),
                Err(e) => {
                    made.destroy(gpu);
                    return Err(e);
                }
            }
        }
        Ok(made)
    }

    /// The texture of `resource`.
    fn get(&self, resource: TargetResource) -> Result<&G::Texture, BackendError> {
        find(&self.made, &resource).ok_or_else(|| missing("a target texture"))
    }

    fn destroy(self, gpu: &mut G) {
        for (_, t) in self.made {
            gpu.destroy_texture(t);
        }
    }
}

/// What a target of one size and format adds: its textures, the splat sums and
/// the groups that bind them ([`TARGET_GROUPS`]).
#[derive(Debug)]
struct TargetState<G: Gpu> {
    size: (u32, u32),
    copy_format: TexelFormat,
    particle_resolution: ParticleResolution,
    textures: TargetTextures<G>,
    sums: G::Buffer,
    groups: Vec<(&'static str, G::BindGroup)>,
}

impl<G: Gpu> TargetState<G> {
    fn destroy(self, gpu: &mut G) {
        for (_, g) in self.groups {
            gpu.destroy_bind_group(g);
        }
        self.textures.destroy(gpu);
        gpu.destroy_buffer(self.sums);
    }
}

/// The target's resources for [`TARGET_GROUPS`]: its textures and the splat sums.
type TargetBound<'a, G> = (&'a TargetTextures<G>, &'a <G as Gpu>::Buffer);

/// What drawing holds for one configuration.
#[derive(Debug)]
pub struct FrameState<G: Gpu> {
    buffers: Vec<(FrameBuffer, G::Buffer)>,
    textures: Vec<(FrameTexture, G::Texture)>,
    samplers: Vec<(Sampler, G::Sampler)>,
    groups: Vec<(&'static str, G::BindGroup)>,
    scene: Option<SceneGpu<G>>,
    target: Option<TargetState<G>>,
    offscreen: Option<G::Texture>,
    rendered: bool,
    host: FrameHost,
    frames_drawn: u64,
    params_stride: u64,
    cover_texels: u32,
    /// The shore's cells and cell corners (0, 0 without a shore).
    shore_cells: (u32, u32),
    /// Which passes of [`FRAME_PASSES`] the last frame ran.
    ran: [bool; FRAME_PASSES.len()],
    /// The last frame's camera (world → clip) where it copied its scene and depth
    /// for this frame's reflections (forgotten when the target is made again).
    history: Option<glam::Mat4>,
    /// What the clouds' image the last frame marched holds (forgotten when the
    /// target is made again or a frame draws no clouds).
    cloud_history: Option<CloudHistory>,
    /// Which water mirrors the scene.
    mirrors: Mirrors,
    /// The resolution rain and snow are drawn at.
    particle_resolution: ParticleResolution,
}

/// The farthest the camera may move in a frame and still reuse the clouds' image
/// of the frame before, m (beyond, every tile is marched).
const CLOUD_HISTORY_REACH_M: f32 = 100.0;

/// What the clouds' image a frame marched holds.
#[derive(Debug, Clone, Copy)]
struct CloudHistory {
    /// Its camera, world → clip.
    view_proj: glam::Mat4,
    /// It is image B.
    in_b: bool,
    /// Its layers (`RenderParams::clouds`).
    layers: [glam::Vec4; precip_model::drawing::clouds::MAX_CLOUD_LAYERS],
    /// The clouds' drift then, m.
    drift_m: glam::Vec2,
    /// Its camera's position, m.
    camera_m: glam::Vec3,
}

/// What a frame group's entries resolve against.
struct Bindable<'a, G: Gpu> {
    state: &'a FrameState<G>,
    sim: &'a Simulation<G>,
    /// The target's resources (for [`TARGET_GROUPS`]).
    target: Option<TargetBound<'a, G>>,
}

impl<'a, G: Gpu> Bindable<'a, G> {
    fn resource(&self, bound: FrameBound) -> Result<BindingResource<'a, G>, BackendError> {
        let state = self.state;
        let texture = |t| find(&state.textures, &t).ok_or_else(|| missing("a texture"));
        Ok(match bound {
            FrameBound::Sim(b) => BindingResource::Buffer(self.sim.buffer(b)),
            FrameBound::Buffer(b) => BindingResource::Buffer(
                find(&state.buffers, &b).ok_or_else(|| missing("a buffer"))?,
            ),
            FrameBound::Texture(t) => BindingResource::Texture(texture(t)?),
            FrameBound::StorageTexture(t) => BindingResource::StorageTexture(texture(t)?),
            FrameBound::Sampler(s) => BindingResource::Sampler(
                find(&state.samplers, &s).ok_or_else(|| missing("a sampler"))?,
            ),
            FrameBound::Target(resource) => {
                let (textures, sums) = self.target.ok_or_else(|| missing("the target"))?;
                match resource {
                    TargetResource::SplatSums => BindingResource::Buffer(sums),
                    texture => BindingResource::Texture(textures.get(texture)?),
                }
            }
        })
    }

    /// The groups `fills` describe, by table name; on an error, those made are
    /// handed back.
    fn groups(
        &self,
        gpu: &mut G,
        drawing: &Drawing<G>,
        fills: &[FrameGroupFill],
    ) -> Result<Vec<(&'static str, G::BindGroup)>, BackendError> {
        let mut made = Vec::with_capacity(fills.len());
        for fill in fills {
            let group = drawing.layout(fill.layout).and_then(|layout| {
                let entries = fill
                    .bound
                    .iter()
                    .map(|&(binding, bound)| Ok((binding, self.resource(bound)?)))
                    .collect::<Result<Vec<_>, BackendError>>()?;
                gpu.bind_group(layout, fill.layout, &entries)
            });
            match group {
                Ok(g) => made.push((fill.layout.name, g)),
                Err(e) => {
                    for (_, g) in made {
                        gpu.destroy_bind_group(g);
                    }
                    return Err(e);
                }
            }
        }
        Ok(made)
    }
}

impl<G: Gpu> FrameState<G> {
    /// Allocates drawing's resources beside `sim`'s, from the tables, and uploads
    /// its scene; on an error, hands back what it made.
    pub fn new(
        gpu: &mut G,
        drawing: &Drawing<G>,
        sim: &Simulation<G>,
    ) -> Result<Self, BackendError> {
        let setup = sim.host().setup();
        let texels = setup.cover.frame.texels;
        let mut made = Self {
            buffers: Vec::new(),
            textures: Vec::new(),
            samplers: Vec::new(),
            groups: Vec::new(),
            scene: None,
            target: None,
            offscreen: None,
            rendered: false,
            host: FrameHost::new(setup),
            frames_drawn: 0,
            params_stride: 0,
            cover_texels: texels.x * texels.y,
            shore_cells: (0, 0),
            ran: [false; FRAME_PASSES.len()],
            history: None,
            cloud_history: None,
            mirrors: setup.render.mirrors,
            particle_resolution: setup.render.particle_resolution,
        };
        match made.fill(gpu, drawing, sim) {
            Ok(()) => Ok(made),
            Err(e) => {
                made.destroy(gpu);
                Err(e)
            }
        }
    }

    fn fill(
        &mut self,
        gpu: &mut G,
        drawing: &Drawing<G>,
        sim: &Simulation<G>,
    ) -> Result<(), BackendError> {
        let setup = sim.host().setup();
        if let Some(grid) = self.host.shore_grid() {
            let (nx, ny) = (grid.bathymetry.nx as u32, grid.bathymetry.ny as u32);
            self.shore_cells = (nx * ny, (nx + 1) * (ny + 1));
        }
        for spec in frame_buffers(
            sim.particle_count(),
            self.host.shore(),
            setup.render.snow_quads,
        ) {
            let bytes = if spec.usage == BufferUsage::FrameBlocks {
                let align = gpu.uniform_alignment().max(16);
                self.params_stride = spec.bytes.div_ceil(align) * align;
                self.params_stride * u64::from(gpu.slots().max(1))
            } else {
                spec.bytes
            };
            let buffer =
                gpu.create_buffer(spec.label, bytes, spec.usage, spec.contents.as_deref())?;
            self.buffers.push((spec.buffer, buffer));
        }
        for spec in frame_textures(setup) {
            let texture = gpu.create_texture(&TextureDesc {
                label: spec.label,
                size: (spec.size[0], spec.size[1]),
                format: spec.format,
                usage: spec.usage,
                contents: spec.contents.as_deref(),
            })?;
            self.textures.push((spec.texture, texture));
        }
        for kind in [
            Sampler::LinearClamp,
            Sampler::ShadowComparison,
            Sampler::LinearRepeat,
        ] {
            let sampler = gpu.create_sampler(kind)?;
            self.samplers.push((kind, sampler));
        }
        let groups = Bindable {
            state: &*self,
            sim,
            target: None,
        }
        .groups(gpu, drawing, &FRAME_GROUPS)?;
        self.groups = groups;
        self.scene = SceneGpu::upload(gpu, setup, drawing.layout(&RENDER_MATERIAL)?)?;
        Ok(())
    }

    /// Draws rain and snow at `resolution` from the next frame on (its image made
    /// again then).
    pub fn set_particle_resolution(&mut self, resolution: ParticleResolution) {
        self.particle_resolution = resolution;
    }

    /// Hands everything back to `gpu`.
    pub fn destroy(self, gpu: &mut G) {
        if let Some(t) = self.target {
            t.destroy(gpu);
        }
        if let Some(s) = self.scene {
            s.destroy(gpu);
        }
        if let Some(t) = self.offscreen {
            gpu.destroy_texture(t);
        }
        for (_, g) in self.groups {
            gpu.destroy_bind_group(g);
        }
        for (_, s) in self.samplers {
            gpu.destroy_sampler(s);
        }
        for (_, t) in self.textures {
            gpu.destroy_texture(t);
        }
        for (_, b) in self.buffers {
            gpu.destroy_buffer(b);
        }
    }

    /// Makes the offscreen image of a `size` frame (when no surface is given),
    /// replacing one of another size.
    fn prepare_offscreen(&mut self, gpu: &mut G, size: (u32, u32)) -> Result<(), BackendError> {
        if self
            .offscreen
            .as_ref()
            .is_none_or(|t| gpu.texture_size(t) != size)
        {
            if let Some(old) = self.offscreen.take() {
                gpu.destroy_texture(old);
            }
            self.rendered = false;
            self.offscreen = Some(gpu.create_texture(&TextureDesc {
                label: "precip image",
                size,
                format: TexelFormat::Rgba8UnormSrgb,
                usage: TextureUsage::ColourTarget,
                contents: None,
            })?);
        }
        Ok(())
    }

    /// Makes the target's resources for a `size` frame whose copies are
    /// `copy_format`, replacing those of another size or format.
    fn prepare_target(
        &mut self,
        gpu: &mut G,
        drawing: &Drawing<G>,
        sim: &Simulation<G>,
        size: (u32, u32),
        copy_format: TexelFormat,
    ) -> Result<(), BackendError> {
        if self.target.as_ref().is_some_and(|t| {
            t.size == size
                && t.copy_format == copy_format
                && t.particle_resolution == self.particle_resolution
        }) {
            return Ok(());
        }
        if let Some(old) = self.target.take() {
            old.destroy(gpu);
        }
        let textures = TargetTextures::new(
            gpu,
            size,
            copy_format,
            self.particle_resolution,
            self.host.mirrors_water(),
        )?;
        let bytes = splat_sums_bytes(size);
        // Zero at first: the resolve zeroes what it reads after that.
        let zeros = vec![0u8; bytes as usize];
        let sums = match gpu.create_buffer(
            "precip splat sums",
            bytes,
            BufferUsage::Storage,
            Some(&zeros),
        ) {
            Ok(s) => s,
            Err(e) => {
                textures.destroy(gpu);
                return Err(e);
            }
        };
        let groups = Bindable {
            state: &*self,
            sim,
            target: Some((&textures, &sums)),
        }
        .groups(gpu, drawing, &TARGET_GROUPS);
        self.history = None;
        self.cloud_history = None;
        match groups {
            Ok(groups) => {
                self.target = Some(TargetState {
                    size,
                    copy_format,
                    particle_resolution: self.particle_resolution,
                    textures,
                    sums,
                    groups,
                });
                Ok(())
            }
            Err(e) => {
                textures.destroy(gpu);
                gpu.destroy_buffer(sums);
                Err(e)
            }
        }
    }

    /// Draws a frame of `sim` for `view` into `surface`, or into the offscreen image
    /// when `None`.
    pub fn draw(
        &mut self,
        gpu: &mut G,
        drawing: &mut Drawing<G>,
        sim: &mut Simulation<G>,
        view: &View,
        surface: Option<&G::Surface>,
    ) -> Result<(), BackendError> {
        gpu.limits().check_view(view)?;
        let size = (view.width_px, view.height_px);
        if surface.is_none() {
            self.prepare_offscreen(gpu, size)?;
        }
        let copy_format = {
            let target = match (surface, &self.offscreen) {
                (Some(s), _) => Target::Surface(s),
                (None, Some(t)) => Target::Texture(t),
                (None, None) => return Err(missing("the offscreen image")),
            };
            gpu.copy_format(target)
        };
        self.prepare_target(
            gpu,
            drawing,
            sim,
            size,
            copy_format.unwrap_or(TexelFormat::Rgba8UnormSrgb),
        )?;
        let mut decision = self.host.decide(sim, view);
        decision.conditions.water_shows &= copy_format.is_some();
        // The water reflects the frame before where its copies are there; the
        // ground's puddles too where the settings and the device say so.
        if let Some(previous) = self.history.take() {
            decision.params.previous_view_proj = previous;
            decision.params.water_look.y = 1.0;
            decision.conditions.ground_mirrors = match self.mirrors {
                Mirrors::Auto => !gpu.rasterises_on_cpu(),
                Mirrors::WaterBodies => false,
                Mirrors::AllWater => true,
            };
        }
        self.reuse_clouds(&mut decision, view);
        let slot = (self.frames_drawn % u64::from(gpu.slots().max(1))) as u32;
        gpu.free_slot(slot)?;
        sim.upload_terrain_windows(gpu, slot, &mut decision.params)?;
        let offset = u64::from(slot) * self.params_stride;
        let params = self
            .buffers
            .iter_mut()
            .find(|(b, _)| *b == FrameBuffer::RenderParams)
            .map(|(_, b)| b)
            .ok_or_else(|| missing("the frame's block"))?;
        gpu.write_buffer(params, offset, bytemuck::bytes_of(&decision.params))?;
        let target = match (surface, &self.offscreen) {
            (Some(s), _) => Target::Surface(s),
            (None, Some(t)) => Target::Texture(t),
            (None, None) => return Err(missing("the offscreen image")),
        };
        let format = gpu.colour_format(target);
        // The images' format (the particles' and the mirror's are alike).
        let image_format = {
            let image = self
                .target
                .as_ref()
                .ok_or_else(|| missing("the target"))?
                .textures
                .get(TargetResource::ParticleImage)?;
            gpu.colour_format(Target::Texture(image))
        };
        drawing.prepare(gpu, format, image_format)?;
        let offset = u32::try_from(offset).map_err(|_| missing("a frame block below 4 GiB"))?;
        let offsets = [offset; 2];
        let work = self.record(drawing, format, &decision, &offsets, view, sim)?;
        gpu.submit_frame(&work, target)?;
        let mut ran = [false; FRAME_PASSES.len()];
        for (r, pass) in ran.iter_mut().zip(&work.passes) {
            *r = pass.runs;
        }
        drop(work);
        self.ran = ran;
        self.history = decision
            .conditions
            .water_shows
            .then_some(decision.params.view_proj);
        self.cloud_history = decision.conditions.clouds.then_some(CloudHistory {
            view_proj: decision.params.view_proj,
            in_b: decision.conditions.clouds_into_b,
            layers: decision.params.clouds,
            drift_m: glam::Vec2::new(decision.params.cloud_drift.x, decision.params.cloud_drift.y),
            camera_m: view.camera.position_m,
        });
        self.frames_drawn += 1;
        if surface.is_none() {
            self.rendered = true;
        }
        Ok(())
    }

    /// Which clouds' image the frame makes (the other than the last frame's) and
    /// which of its pixels it marches: one per 4 × 4 block (slot `cloud_shadow.y`
    /// of [`CLOUD_MARCH_ALL`], into the fresh image, `clouds_fresh`) where the
    /// other holds the frame before's clouds of the same layers seen from nearby
    /// (its camera in `previous_view_proj`, the clouds' drift since in
    /// `cloud_shadow.zw`); every pixel otherwise, or from inside a layer
    /// (render_clouds.wgsl).
    fn reuse_clouds(&self, decision: &mut FrameDecision, view: &View) {
        let params = &mut decision.params;
        let camera_m = view.camera.position_m;
        let drift_m = glam::Vec2::new(params.cloud_drift.x, params.cloud_drift.y);
        decision.conditions.clouds_into_b = self.cloud_history.is_some_and(|h| !h.in_b);
        let inside = params
            .clouds
            .iter()
            .any(|layer| layer.y > layer.x && (layer.x..=layer.y).contains(&camera_m.y));
        let reusable = self.cloud_history.filter(|h| {
            h.layers == params.clouds
                && h.camera_m.distance(camera_m) < CLOUD_HISTORY_REACH_M
                && !inside
        });
        params.cloud_shadow.y = match reusable {
            Some(h) => {
                params.previous_view_proj = h.view_proj;
                let moved = drift_m - h.drift_m;
                params.cloud_shadow.z = moved.x;
                params.cloud_shadow.w = moved.y;
                params.cloud_drift.w = precip_model::drawing::clouds::cloud_march_round_offset(
                    self.frames_drawn / u64::from(CLOUD_MARCH_ALL),
                );
                (self.frames_drawn % u64::from(CLOUD_MARCH_ALL)) as f32
            }
            None => CLOUD_MARCH_ALL as f32,
        };
        decision.conditions.clouds_fresh = reusable.is_some();
    }

    /// The frame plan under `decision` as commands.
    fn record<'a>(
        &'a self,
        drawing: &'a Drawing<G>,
        format: G::ColourFormat,
        decision: &FrameDecision,
        offsets: &'a [u32; 2],
        view: &View,
        sim: &Simulation<G>,
    ) -> Result<FrameWork<'a, G>, BackendError> {
        let target = self.target.as_ref().ok_or_else(|| missing("the target"))?;
        let pipelines =
            find(&drawing.pipelines, &format).ok_or_else(|| missing("a draw pipeline"))?;
        let draws = find(&self.buffers, &FrameBuffer::Draws).ok_or_else(|| missing("draws"))?;
        let shadow_map = find(&self.textures, &FrameTexture::ShadowMap)
            .ok_or_else(|| missing("the shadow map"))?;
        let counts = DispatchCounts {
            particles: sim.particle_count(),
            stepped_particles: sim.particle_count(),
            cover_texels: self.cover_texels,
            wave_cells: 0,
            cover_tiles: 0,
            cover_tiles_per_workgroup: 0,
            shore_cells: self.shore_cells.0,
            shore_faces: self.shore_cells.1,
        };
        let detail = (
            view.camera.position_m,
            self.scene
                .as_ref()
                .map_or(0.0, |s| s.detail_distance_m(view)),
        );
        // The last pass that runs and draws into the frame's target leaves it ready
        // to be read or presented.
        let last_colour = frame_plan(decision.conditions)
            .filter(|p| {
                p.runs
                    && matches!(p.pass.work, PassWork::Render(r)
                        if r.colour.is_some() && r.colour_target == ColourTarget::Frame)
            })
            .map(|p| p.index)
            .last();
        let sky = decision.sky_colour;
        // Binds each of `tables` at its index (a material group is bound per mesh).
        let bind = |commands: &mut Vec<Command<'a, G>>,
                    tables: &[GroupLayout]|
         -> Result<(), BackendError> {
            for (index, table) in tables.iter().enumerate() {
                if table.name == RENDER_MATERIAL.name {
                    continue;
                }
                let group = find(&self.groups, &table.name)
                    .or_else(|| find(&target.groups, &table.name))
                    .ok_or_else(|| missing(table.name))?;
                commands.push(Command::Group {
                    index: index as u32,
                    group,
                    offsets: &offsets[..table.dynamic_bindings().min(2)],
                });
            }
            Ok(())
        };
        let mut passes = Vec::with_capacity(FRAME_PASSES.len());
        for planned in frame_plan(decision.conditions) {
            let mut commands = Vec::new();
            let kind = match &planned.pass.work {
                PassWork::Kernels(_) => {
                    for k in planned.kernels(counts) {
                        let kernel = find(&drawing.kernels, &k.kernel.entry_point)
                            .ok_or_else(|| missing(k.kernel.entry_point))?;
                        commands.push(Command::Kernel(kernel));
                        bind(&mut commands, k.groups)?;
                        commands.push(Command::Dispatch(k.workgroups.0, k.workgroups.1));
                    }
                    PassKind::Compute
                }
                PassWork::Render(recipe) => {
                    for d in planned.draws() {
                        if !d.draw.when.holds(decision.conditions) {
                            continue;
                        }
                        let key = d.draw.key();
                        let pipeline = find(pipelines, &key).ok_or_else(|| missing(key))?;
                        commands.push(Command::Pipeline(pipeline));
                        bind(&mut commands, d.groups)?;
                        match d.draw.of {
                            DrawOf::SceneMeshes {
                                materials,
                                which,
                                tiles,
                            } => {
                                if let Some(scene) = &self.scene {
                                    scene.draw(
                                        &mut commands,
                                        (materials, which),
                                        detail.0,
                                        detail.1,
                                        (
                                            Some(tile_cull(recipe.depth, decision)),
                                            tile_region(tiles, decision),
                                        ),
                                    );
                                }
                            }
                            DrawOf::FullScreenTriangle => commands.push(Command::Draw(3)),
                            DrawOf::TerrainClipmap { materials, mirror } => {
                                if let Some(scene) = &self.scene {
                                    let rows = decision.params.clipmap_rows();
                                    scene.draw_terrain(
                                        &mut commands,
                                        materials,
                                        if mirror {
                                            rows.mirror_indices()
                                        } else {
                                            rows.indices()
                                        },
                                    );
                                }
                            }
                            DrawOf::Indirect { offset } => {
                                commands.push(Command::DrawIndirect(draws, offset));
                            }
                        }
                    }
                    let textures = &target.textures;
                    let image = recipe.colour_target.target_resource();
                    PassKind::Render(Attachments {
                        depth: match recipe.depth.target_resource() {
                            Some(r) => textures.get(r)?,
                            None => shadow_map,
                        },
                        colour: image.map(|r| textures.get(r)).transpose()?,
                        clear_colour: match image {
                            None => [sky.x, sky.y, sky.z, 1.0],
                            Some(_) => [0.0; 4],
                        },
                        // The mirror only over the water's rectangle, in its image's
                        // pixels.
                        scissor: match (recipe.colour_target, decision.mirror_rect_px) {
                            (ColourTarget::Mirror, Some(rect)) => {
                                Some(mirror_scissor(rect, target.size))
                            }
                            _ => None,
                        },
                        recipe,
                        depth_written: recipe.draws.iter().any(|d| d.depth_write),
                        colour_last: last_colour == Some(planned.index),
                    })
                }
                PassWork::CopyTarget => PassKind::CopyTarget {
                    colour: target.textures.get(TargetResource::SceneCopy)?,
                    depth: (
                        target.textures.get(TargetResource::CameraDepth)?,
                        target.textures.get(TargetResource::DepthCopy)?,
                    ),
                },
            };
            passes.push(RecordedPass {
                name: planned.pass.name,
                runs: planned.runs,
                kind,
                commands,
            });
        }
        Ok(FrameWork { passes })
    }

    /// The offscreen image of the last frame drawn into it.
    pub fn read_image(&self, gpu: &mut G) -> Result<Image, BackendError> {
        match &self.offscreen {
            Some(t) if self.rendered => {
                let (width_px, height_px) = gpu.texture_size(t);
                Ok(Image {
                    width_px,
                    height_px,
                    rgba8: gpu.read_texture(t)?,
                })
            }
            _ => Err(BackendError::NothingRendered),
        }
    }

    /// What the last frame drew (the cull's counts, read back).
    pub fn drawn(&self, gpu: &mut G) -> Result<DrawnCounts, BackendError> {
        let draws = find(&self.buffers, &FrameBuffer::Draws).ok_or_else(|| missing("draws"))?;
        Ok(FrameDraws::counts(
            &gpu.read_buffer(draws, FrameDraws::BYTES)?,
        ))
    }

    /// The albedo of the ground the last frame's drops refracted and of the land
    /// beyond the scene (the `drop_ground` kernel's,
    /// [`precip_model::drawing::drop_ground_albedo`],
    /// [`precip_model::drawing::far_ground::far_ground_albedo`]); `None` before a
    /// frame.
    pub fn drop_ground_albedo(&self, gpu: &mut G) -> Result<Option<[f32; 2]>, BackendError> {
        if self.frames_drawn == 0 {
            return Ok(None);
        }
        let buffer = find(&self.buffers, &FrameBuffer::DropGround)
            .ok_or_else(|| missing("the drops' ground"))?;
        let bytes = gpu.read_buffer(buffer, 8)?;
        let at = |i: usize| {
            bytes
                .get(4 * i..4 * i + 4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        };
        Ok(at(0).zip(at(1)).map(|(near, land)| [near, land]))
    }

    /// The last frame's time per pass that ran.
    pub fn timings(&self, gpu: &mut G) -> Result<Vec<PassTiming>, BackendError> {
        let Some(ms) = gpu.frame_times_ms()? else {
            return Ok(Vec::new());
        };
        Ok(FRAME_PASSES
            .iter()
            .zip(self.ran)
            .zip(ms)
            .filter(|((_, ran), _)| *ran)
            .map(|((pass, _), milliseconds)| PassTiming {
                pass: pass.name,
                milliseconds,
            })
            .collect())
    }

    /// The sea's atlases as the last frame wrote them (`crate::recipe::OCEAN_ATLAS_PX`,
    /// rows in order): per texel `(λ·Dx, h, λ·Dz, 0)` m and `(∂h/∂x, ∂h/∂z, J, 0)`
    /// (render_ocean.wgsl); `None` before a frame.
    pub fn sea_atlases(&self, gpu: &mut G) -> Result<Option<[Vec<[f32; 4]>; 2]>, BackendError> {
        if self.frames_drawn == 0 {
            return Ok(None);
        }
        let mut texels = |t: FrameTexture| -> Result<Vec<[f32; 4]>, BackendError> {
            let texture = find(&self.textures, &t).ok_or_else(|| missing("a sea atlas"))?;
            Ok(gpu
                .read_texture(texture)?
                .chunks_exact(8)
                .map(|h| {
                    std::array::from_fn(|i| {
                        f16_to_f32(u16::from_le_bytes([h[2 * i], h[2 * i + 1]]))
                    })
                })
                .collect())
        };
        Ok(Some([
            texels(FrameTexture::OceanDisplacement)?,
            texels(FrameTexture::OceanSlope)?,
        ]))
    }

    /// The shore's water as the last frame left it (`None` before a frame or
    /// without a shore; [`precip_model::drawing::shore`]).
    pub fn shore_state(
        &self,
        gpu: &mut G,
    ) -> Result<Option<precip_model::drawing::shore::ShoreGridState>, BackendError> {
        let Some(grid) = self.host.shore_grid() else {
            return Ok(None);
        };
        if self.frames_drawn == 0 {
            return Ok(None);
        }
        let buffer =
            find(&self.buffers, &FrameBuffer::Shore).ok_or_else(|| missing("the shore"))?;
        let bytes = gpu.read_buffer(buffer, (grid.buffer_vec4s() * 16) as u64)?;
        let words: Vec<[f32; 4]> = bytes
            .chunks_exact(16)
            .map(|c| {
                std::array::from_fn(|i| {
                    f32::from_le_bytes([c[4 * i], c[4 * i + 1], c[4 * i + 2], c[4 * i + 3]])
                })
            })
            .collect();
        Ok(grid
            .state_of_buffer(&words)
            .map(|state| precip_model::drawing::shore::ShoreGridState {
                grid: grid.clone(),
                state,
            }))
    }

    /// The cover's three filtered textures as the last frame wrote them: per texel
    /// `[depth mm, SWE mm, peak SWE mm, wetness, accumulation mask, melt mask, age
    /// days, puddle ratio, sand and dust kg/m², the surface's roughness length under
    /// snow m, 0, 0]`, rows of the cover grid in order; `None` before a frame.
    pub fn cover_textures(&self, gpu: &mut G) -> Result<Option<Vec<[f32; 12]>>, BackendError> {
        if self.frames_drawn == 0 {
            return Ok(None);
        }
        let mut halves = |t: FrameTexture| -> Result<Vec<f32>, BackendError> {
            let texture = find(&self.textures, &t).ok_or_else(|| missing("a cover texture"))?;
            Ok(gpu
                .read_texture(texture)?
                .chunks_exact(2)
                .map(|h| f16_to_f32(u16::from_le_bytes([h[0], h[1]])))
                .collect())
        };
        let a = halves(FrameTexture::CoverA)?;
        let b = halves(FrameTexture::CoverB)?;
        let c = halves(FrameTexture::CoverC)?;
        Ok(Some(
            a.chunks_exact(4)
                .zip(b.chunks_exact(4))
                .zip(c.chunks_exact(4))
                .map(|((a, b), c)| {
                    [
                        a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], c[0], c[1], c[2], c[3],
                    ]
                })
                .collect(),
        ))
    }
}

/// Where the tiles a draw takes lie: on the cover grid's interior, off it, or
/// anywhere (None).
fn tile_region(tiles: SceneTiles, decision: &FrameDecision) -> Option<TileRegion> {
    let rect_m = precip_model::host::grid_interior_m(&decision.params.cover);
    match tiles {
        SceneTiles::All => None,
        SceneTiles::OnTheGridInterior => Some(TileRegion {
            rect_m,
            inside: true,
        }),
        SceneTiles::OffTheGridInterior => Some(TileRegion {
            rect_m,
            inside: false,
        }),
    }
}

/// What the scene's draws into `depth` may see of the tiles: the sun's view for the
/// shadow map; the camera's for the frame; the mirror's within the water's
/// rectangle and above its level for the mirror.
fn tile_cull(depth: DepthTarget, decision: &FrameDecision) -> TileCull {
    let p = &decision.params;
    match depth {
        DepthTarget::ShadowMap => TileCull::whole(p.sun_view_proj),
        DepthTarget::Camera
        | DepthTarget::Particles
        | DepthTarget::Clouds
        | DepthTarget::CloudsFresh => TileCull::whole(p.view_proj),
        DepthTarget::Mirror => {
            let whole = TileCull::whole(p.mirror_view_proj);
            match (decision.mirror_rect_px, decision.target_px) {
                (Some([x, y, w, h]), (width, height)) if width > 0 && height > 0 => {
                    let ndc_x = |px: u32| 2.0 * px as f32 / width as f32 - 1.0;
                    let ndc_y = |px: u32| 1.0 - 2.0 * px as f32 / height as f32;
                    TileCull {
                        ndc: [ndc_x(x), ndc_y(y + h), ndc_x(x + w), ndc_y(y)],
                        floor_m: p.mirror.x,
                        ..whole
                    }
                }
                _ => whole,
            }
        }
    }
}

/// The mirror image's pixels (the target's over [`MIRROR_DOWNSCALE`], rounded up) that
/// hold the target's rectangle `rect` (`x, y, width, height` px).
fn mirror_scissor([x, y, width, height]: [u32; 4], target: (u32, u32)) -> [u32; 4] {
    let d = MIRROR_DOWNSCALE;
    let size = (target.0.div_ceil(d), target.1.div_ceil(d));
    let (x0, y0) = ((x / d).min(size.0), (y / d).min(size.1));
    let x1 = (x + width).div_ceil(d).clamp(x0, size.0);
    let y1 = (y + height).div_ceil(d).clamp(y0, size.1);
    [x0, y0, x1 - x0, y1 - y0]
}

/// An IEEE half (binary16) as `f32`.
fn f16_to_f32(bits: u16) -> f32 {
    let sign = if bits & 0x8000 == 0 { 1.0 } else { -1.0 };
    let exponent = i32::from((bits >> 10) & 0x1f);
    let mantissa = f32::from(bits & 0x3ff);
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        31 if mantissa == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halves_decode() {
        assert!((f16_to_f32(0x3c00) - 1.0).abs() < f32::EPSILON);
        assert!((f16_to_f32(0xc000) + 2.0).abs() < f32::EPSILON);
        assert!((f16_to_f32(0x7bff) - 65504.0).abs() < f32::EPSILON);
        assert!((f16_to_f32(0x0001) - 2f32.powi(-24)).abs() < f32::EPSILON);
        assert!(f16_to_f32(0x7c00).is_infinite() && f16_to_f32(0x7e00).is_nan());
    }

    #[test]
    fn every_frame_table_is_named_once_and_includes_the_material() {
        let tables = frame_tables();
        for (i, t) in tables.iter().enumerate() {
            assert!(tables[..i].iter().all(|u| u.name != t.name), "{}", t.name);
        }
        assert!(tables.iter().any(|t| t.name == RENDER_MATERIAL.name));
        for fill in FRAME_GROUPS.iter().chain(&TARGET_GROUPS) {
            assert!(tables.iter().any(|t| t.name == fill.layout.name));
        }
    }
}
