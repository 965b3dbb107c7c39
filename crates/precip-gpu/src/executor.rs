//! The executor: the simulation's part of the plan run over any [`Gpu`], written
//! once. [`Kernels`] are a device's compute programs (made once per device);
//! [`Simulation`] is one configuration: its buffers and wind volume made from the
//! resources table ([`crate::resources`]), its bind groups filled from the group
//! tables, and the recipes of configure (`init_particles`), a weather change (the
//! wind's block and volume), a step (every sub-step's blocks at their dynamic
//! offsets, then [`SUBSTEP_PASSES`] once per sub-step in one submission), a beam
//! query and the read-backs. Every resource goes back to the device through
//! [`Simulation::destroy`] / [`Kernels::destroy`], and on every error path.
//!
//! The frame ([`crate::renderer`]) reads the simulation's buffers through
//! [`Simulation::buffer`], and writes the terrain's windows round its camera into
//! the ground buffer ([`Simulation::upload_terrain_windows`]).

use precip_cover::{CoverGrid, GridFrame};
use precip_model::host::HostState;
use precip_model::particles::step::stepped_particles;
use precip_model::sensors::lidar::{Beam, BeamHit, BeamParams, BeamQuery, BeamReturn};
use precip_model::sensors::optics::{CrossSectionSums, Optics, OpticsPartial};
use precip_model::{BackendError, Camera, Particle, PassTiming, Setup, Weather};

use crate::bind_groups::GroupLayout;
use crate::gpu::{BindingResource, Dispatch, Gpu};
use crate::recipe::{
    COVER_TILES_PER_WORKGROUP, DispatchCounts, INIT_PASS, KernelPass, OPTICS_PASS, OpticsParams,
    SUBSTEP_PASSES, cover_tiles_all_marked, dispatch_size, substep_timings,
};
use crate::resources::{
    BEAM_GROUP, Bound, BufferUsage, COVER_GROUP, COVER_LISTING_GROUP, Contents, GroupFill,
    OPTICS_GROUP, STEP_GROUP, SimBuffer, simulation_buffers, uniform_stride,
};
use crate::shaders::Program;

/// A device's compute programs and their group layouts.
#[derive(Debug)]
pub struct Kernels<G: Gpu> {
    step_layout: G::GroupLayout,
    cover_layout: G::GroupLayout,
    cover_listing_layout: G::GroupLayout,
    beams_layout: G::GroupLayout,
    optics_layout: G::GroupLayout,
    init: G::Kernel,
    substep: Vec<(KernelPass, G::Kernel)>,
    query_beams: G::Kernel,
    optics_sums: G::Kernel,
}

/// Hands everything in `made` back to `gpu` (the error path of a constructor).
fn give_back<G: Gpu>(gpu: &mut G, layouts: Vec<G::GroupLayout>, kernels: Vec<G::Kernel>) {
    for k in kernels {
        gpu.destroy_kernel(k);
    }
    for l in layouts {
        gpu.destroy_group_layout(l);
    }
}

impl<G: Gpu> Kernels<G> {
    /// Compiles the init, sub-step and beam kernels on `gpu`.
    pub fn new(gpu: &mut G) -> Result<Self, BackendError> {
        let mut layouts = Vec::new();
        for table in [
            STEP_GROUP.layout,
            COVER_GROUP.layout,
            COVER_LISTING_GROUP.layout,
            BEAM_GROUP.layout,
            OPTICS_GROUP.layout,
        ] {
            match gpu.group_layout(table) {
                Ok(l) => layouts.push(l),
                Err(e) => {
                    give_back(gpu, layouts, Vec::new());
                    return Err(e);
                }
            }
        }
        let mut kernels = Vec::new();
        let wanted = std::iter::once(INIT_PASS).chain(SUBSTEP_PASSES).chain([
            KernelPass {
                program: Program::QueryBeams,
                entry_point: "query_beams",
                over: crate::recipe::DispatchOver::OneWorkgroup,
                when: crate::recipe::KernelWhen::Always,
            },
            OPTICS_PASS,
        ]);
        for kernel in wanted {
            let layout = match kernel.program {
                Program::CoverUpdate if is_cover_listing(kernel.entry_point) => &layouts[2],
                Program::CoverUpdate => &layouts[1],
                Program::QueryBeams => &layouts[3],
                Program::OpticsSums => &layouts[4],
                _ => &layouts[0],
            };
            match gpu.kernel(kernel.program, kernel.entry_point, &[layout]) {
                Ok(k) => kernels.push(k),
                Err(e) => {
                    give_back(gpu, layouts, kernels);
                    return Err(e);
                }
            }
        }
        let optics_sums = kernels.pop();
        let query_beams = kernels.pop();
        let mut kernels = kernels.into_iter();
        let init = kernels.next();
        let substep: Vec<_> = SUBSTEP_PASSES.iter().copied().zip(kernels).collect();
        let mut layouts = layouts.into_iter();
        match (
            layouts.next(),
            layouts.next(),
            layouts.next(),
            layouts.next(),
            layouts.next(),
            init,
            query_beams,
            optics_sums,
        ) {
            (
                Some(step_layout),
                Some(cover_layout),
                Some(cover_listing_layout),
                Some(beams_layout),
                Some(optics_layout),
                Some(init),
                Some(query_beams),
                Some(optics_sums),
            ) if substep.len() == SUBSTEP_PASSES.len() => Ok(Self {
                step_layout,
                cover_layout,
                cover_listing_layout,
                beams_layout,
                optics_layout,
                init,
                substep,
                query_beams,
                optics_sums,
            }),
            _ => Err(BackendError::Device {
                backend: "precip-gpu",
                message:
                    "a kernel went missing while compiling (a bug in precip: please report it)"
                        .into(),
            }),
        }
    }

    /// Hands every kernel and layout back to `gpu`.
    pub fn destroy(self, gpu: &mut G) {
        let kernels = [self.init, self.query_beams, self.optics_sums]
            .into_iter()
            .chain(self.substep.into_iter().map(|(_, k)| k))
            .collect();
        give_back(
            gpu,
            vec![
                self.step_layout,
                self.cover_layout,
                self.cover_listing_layout,
                self.beams_layout,
                self.optics_layout,
            ],
            kernels,
        );
    }

    fn layout_of(&self, fill: &GroupFill) -> &G::GroupLayout {
        if fill.layout.name == COVER_GROUP.layout.name {
            &self.cover_layout
        } else if fill.layout.name == COVER_LISTING_GROUP.layout.name {
            &self.cover_listing_layout
        } else if fill.layout.name == BEAM_GROUP.layout.name {
            &self.beams_layout
        } else if fill.layout.name == OPTICS_GROUP.layout.name {
            &self.optics_layout
        } else {
            &self.step_layout
        }
    }
}

/// The buffers of an on-demand query (a beam query's params, beams and hits; an
/// optics query's params and partials).
struct QueryBuffers<'a, G: Gpu> {
    params: &'a G::Buffer,
    input: Option<&'a G::Buffer>,
    output: &'a G::Buffer,
}

/// One configuration on a device: its host state and its device resources.
#[derive(Debug)]
pub struct Simulation<G: Gpu> {
    host: HostState,
    /// In the order of [`SimBuffer::ALL`].
    buffers: Vec<G::Buffer>,
    wind: G::Volume,
    step_group: G::BindGroup,
    cover_group: G::BindGroup,
    /// The cover tiles' listings' group ([`COVER_LISTING_GROUP`]).
    cover_listing_group: G::BindGroup,
    particle_count: u32,
    cover_texel_count: u32,
    wave_frame: GridFrame,
    /// The device computes on the CPU ([`Gpu::rasterises_on_cpu`]).
    on_cpu: bool,
    uniform_stride: u64,
    steps_submitted: u64,
    /// The kernels the last step dispatched, in order (its timings' names).
    last_step: Vec<&'static str>,
    /// Each frame slot's terrain windows as written: every level's origin
    /// (`None`: not written yet).
    terrain_windows: Vec<Vec<Option<glam::IVec2>>>,
}

/// A setup checked and computed on the host ([`Simulation::prepare`]).
#[derive(Debug)]
pub struct Prepared {
    host: HostState,
    cover: CoverGrid,
}

/// A configuration's resources while they are being made: handed back on an error.
struct Made<G: Gpu> {
    buffers: Vec<G::Buffer>,
    wind: Option<G::Volume>,
    groups: Vec<G::BindGroup>,
}

impl<G: Gpu> Made<G> {
    fn give_back(self, gpu: &mut G) {
        for g in self.groups {
            gpu.destroy_bind_group(g);
        }
        for b in self.buffers {
            gpu.destroy_buffer(b);
        }
        if let Some(w) = self.wind {
            gpu.destroy_volume(w);
        }
    }
}

impl<G: Gpu> Simulation<G> {
    /// Checks `setup` against the device's limits and computes its host state and
    /// initial cover, before anything of the last configuration is let go: a refused
    /// setup leaves the backend as it was.
    pub fn prepare(gpu: &G, setup: &Setup) -> Result<Prepared, BackendError> {
        gpu.limits().check_setup(setup)?;
        Ok(Prepared {
            host: HostState::configure(setup)?,
            cover: setup.initial_cover()?,
        })
    }

    /// Makes the configuration `prepared` describes and runs `init_particles`.
    pub fn configure(
        gpu: &mut G,
        kernels: &Kernels<G>,
        prepared: Prepared,
    ) -> Result<Self, BackendError> {
        let (host, cover) = (&prepared.host, &prepared.cover);
        let mut made = Made::<G> {
            buffers: Vec::new(),
            wind: None,
            groups: Vec::new(),
        };
        match Self::make(gpu, kernels, host, cover, &mut made) {
            Ok(parts) => {
                let (buffers, wind, mut groups) = match made {
                    Made {
                        buffers,
                        wind: Some(wind),
                        groups,
                    } if groups.len() == 3 => (buffers, wind, groups),
                    incomplete => {
                        incomplete.give_back(gpu);
                        return Err(BackendError::Device {
                            backend: "precip-gpu",
                            message: "a resource went missing while configuring (a bug in precip: please report it)".into(),
                        });
                    }
                };
                let cover_listing_group = groups.remove(2);
                let (cover_group, step_group) = (groups.remove(1), groups.remove(0));
                let cover_texel_count = cover.texels.len() as u32;
                let wave_frame = host.frames().waves;
                let mut sim = Self {
                    host: prepared.host,
                    buffers,
                    wind,
                    step_group,
                    cover_group,
                    cover_listing_group,
                    particle_count: parts.0,
                    cover_texel_count,
                    wave_frame,
                    on_cpu: gpu.rasterises_on_cpu(),
                    uniform_stride: parts.1,
                    steps_submitted: 0,
                    last_step: Vec::new(),
                    terrain_windows: Vec::new(),
                };
                match sim.init(gpu, kernels) {
                    Ok(()) => Ok(sim),
                    Err(e) => {
                        sim.destroy(gpu);
                        Err(e)
                    }
                }
            }
            Err(e) => {
                made.give_back(gpu);
                Err(e)
            }
        }
    }

    /// Fills `made` with the buffers, the volume and the three groups (step, cover,
    /// the cover's listings);
    /// returns the particle count and the uniform stride.
    fn make(
        gpu: &mut G,
        kernels: &Kernels<G>,
        host: &HostState,
        cover: &CoverGrid,
        made: &mut Made<G>,
    ) -> Result<(u32, u64), BackendError> {
        let stride = uniform_stride(gpu.uniform_alignment());
        let tiles_per_workgroup = if gpu.rasterises_on_cpu() {
            COVER_TILES_PER_WORKGROUP
        } else {
            1
        };
        let specs = simulation_buffers(host, cover, stride, gpu.slots(), tiles_per_workgroup);
        for spec in &specs {
            let zeros;
            let contents = match &spec.contents {
                Contents::Bytes(b) => Some(b.as_slice()),
                Contents::Zeroed => {
                    zeros = vec![0u8; spec.bytes as usize];
                    Some(zeros.as_slice())
                }
                Contents::Undefined => None,
            };
            made.buffers.push(gpu.create_buffer(
                spec.buffer.label(),
                spec.bytes,
                spec.usage,
                contents,
            )?);
        }
        let wind = host.wind();
        let n = wind.spec.texels;
        made.wind =
            Some(gpu.create_volume("precip wind volume", [n.x, n.y, n.z], wind.as_bytes())?);
        for fill in [&STEP_GROUP, &COVER_GROUP, &COVER_LISTING_GROUP] {
            let group =
                Self::fill_group(gpu, kernels, fill, &made.buffers, made.wind.as_ref(), None)?;
            made.groups.push(group);
        }
        let (world, camera) = host.setup().particle_counts();
        Ok((world + camera, stride))
    }

    /// The bind group `fill` describes, from `buffers` (in [`SimBuffer::ALL`]'s order),
    /// the wind volume and a beam query's buffers.
    fn fill_group(
        gpu: &mut G,
        kernels: &Kernels<G>,
        fill: &GroupFill,
        buffers: &[G::Buffer],
        wind: Option<&G::Volume>,
        query: Option<&QueryBuffers<'_, G>>,
    ) -> Result<G::BindGroup, BackendError> {
        let missing = |what: &str| BackendError::Device {
            backend: "precip-gpu",
            message: format!(
                "{}: {what} is not made yet (a bug in precip: please report it)",
                fill.layout.name
            ),
        };
        let mut entries = Vec::with_capacity(fill.bound.len());
        for &(binding, bound) in fill.bound {
            let resource = match bound {
                Bound::Buffer(b) => BindingResource::Buffer(
                    buffers.get(index_of(b)).ok_or_else(|| missing(b.label()))?,
                ),
                Bound::WindVolume => {
                    BindingResource::Volume(wind.ok_or_else(|| missing("the wind volume"))?)
                }
                Bound::BeamParams | Bound::OpticsParams => {
                    BindingResource::Buffer(query.ok_or_else(|| missing("the query"))?.params)
                }
                Bound::Beams => BindingResource::Buffer(
                    query
                        .and_then(|q| q.input)
                        .ok_or_else(|| missing("the beams"))?,
                ),
                Bound::BeamHits | Bound::OpticsPartials => {
                    BindingResource::Buffer(query.ok_or_else(|| missing("the query"))?.output)
                }
            };
            entries.push((binding, resource));
        }
        gpu.bind_group(kernels.layout_of(fill), fill.layout, &entries)
    }

    /// `init_particles` over every particle, with the host's init block; the first
    /// step writes the same blocks, so this is waited for.
    fn init(&mut self, gpu: &mut G, kernels: &Kernels<G>) -> Result<(), BackendError> {
        gpu.free_slot(0)?;
        let block = self.host.init_block();
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::StepBlocks),
            0,
            bytemuck::bytes_of(&block),
        )?;
        gpu.dispatch(
            &[Dispatch {
                kernel: &kernels.init,
                group: &self.step_group,
                offset: Some(0),
                workgroups: dispatch_size(self.particle_count),
                indirect: None,
            }],
            false,
        )?;
        gpu.settle()
    }

    /// Takes a new weather (validated) and uploads what it changed: the wind's
    /// block, and its volume when it was baked again. A refused weather changes
    /// nothing.
    pub fn set_weather(&mut self, gpu: &mut G, weather: &Weather) -> Result<(), BackendError> {
        // Validated and applied on the host first (a refused weather changes nothing),
        // without copying the host state: hosts send a weather every frame.
        let change = self.host.set_weather(weather)?;
        gpu.settle()?;
        if change.wind_rebaked {
            gpu.write_volume(&self.wind, self.host.wind().as_bytes())?;
        }
        let params = self.host.wind_params();
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::WindParams),
            0,
            bytemuck::bytes_of(&params),
        )
    }

    /// Moves the camera (validated).
    pub fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        self.host.set_camera(camera)
    }

    /// Draws rain and snow at `resolution` from the next frame on.
    pub fn set_particle_resolution(&mut self, resolution: precip_model::ParticleResolution) {
        self.host.set_particle_resolution(resolution);
    }

    /// Keeps a stale shadow map for up to `frames` frames (validated).
    pub fn set_shadow_refresh_frames(&mut self, frames: u32) -> Result<(), BackendError> {
        self.host.set_shadow_refresh_frames(frames)
    }

    /// Takes the sun's direction and the clear air's haze
    /// ([`HostState::set_atmosphere`]).
    pub fn set_atmosphere(
        &mut self,
        to_sun: Option<glam::Vec3>,
        clear_air_extinction_per_m: Option<f32>,
    ) -> Result<(), BackendError> {
        self.host.set_atmosphere(to_sun, clear_air_extinction_per_m)
    }

    /// Takes cloud layers ([`HostState::set_cloud_layers`]).
    pub fn set_cloud_layers(
        &mut self,
        cloud_layers: precip_model::drawing::clouds::CloudLayers,
    ) -> Result<(), BackendError> {
        self.host.set_cloud_layers(cloud_layers)
    }

    /// Takes a fog layer or none ([`HostState::set_fog_layer`]).
    pub fn set_fog_layer(
        &mut self,
        fog_layer: Option<precip_model::drawing::fog_layer::FogLayer>,
    ) -> Result<(), BackendError> {
        self.host.set_fog_layer(fog_layer)
    }

    /// A step of `dt_s` (validated): every sub-step's blocks uploaded into the next
    /// slot's ring, the sub-steps' kernels submitted at once (timed where the device
    /// can), and the host's clock moved.
    pub fn step(
        &mut self,
        gpu: &mut G,
        kernels: &Kernels<G>,
        dt_s: f32,
    ) -> Result<(), BackendError> {
        let mut steps = self.host.substeps(dt_s)?;
        // The cover grid follows the camera over a terrain (host::cover_window);
        // the step's blocks then from the moved setup (its emitter, its floor).
        if let Some(shift) = self.host.cover_grid_move() {
            self.move_cover_grid(gpu, shift)?;
            steps = self.host.substeps(dt_s)?;
        }
        let slots = u64::from(gpu.slots().max(1));
        let slot = (self.steps_submitted % slots) as u32;
        gpu.free_slot(slot)?;
        let stride = self.uniform_stride;
        let base = u64::from(slot) * stride * u64::from(precip_model::backend::MAX_SUBSTEPS);
        let mut step_bytes = vec![0u8; (stride as usize) * steps.blocks.len()];
        let mut cover_bytes = step_bytes.clone();
        for (k, blocks) in steps.blocks.iter().enumerate() {
            let at = k * stride as usize;
            let (step, cover) = (
                bytemuck::bytes_of(&blocks.step),
                bytemuck::bytes_of(&blocks.cover),
            );
            step_bytes[at..at + step.len()].copy_from_slice(step);
            cover_bytes[at..at + cover.len()].copy_from_slice(cover);
        }
        gpu.write_buffer(self.buffer_mut(SimBuffer::StepBlocks), base, &step_bytes)?;
        gpu.write_buffer(self.buffer_mut(SimBuffer::CoverBlocks), base, &cover_bytes)?;
        let counts = DispatchCounts {
            stepped_particles: steps
                .blocks
                .first()
                .map_or(0, |b| stepped_particles(&b.step).len() as u32),
            ..self.dispatch_counts()
        };
        // An idle feature's kernels are not dispatched (`KernelWhen`).
        let activity = self.host.activity();
        let substep: Vec<_> = kernels
            .substep
            .iter()
            .filter(|(pass, _)| pass.when.holds(activity))
            .collect();
        let mut dispatches = Vec::with_capacity(steps.blocks.len() * substep.len());
        for k in 0..steps.blocks.len() as u64 {
            let offset = u32::try_from(base + k * stride).map_err(|_| BackendError::Device {
                backend: "precip-gpu",
                message: "a uniform offset beyond 4 GiB (a bug in precip: please report it)".into(),
            })?;
            for (pass, kernel) in &substep {
                let group = match pass.program {
                    Program::CoverUpdate if is_cover_listing(pass.entry_point) => {
                        &self.cover_listing_group
                    }
                    Program::CoverUpdate => &self.cover_group,
                    _ => &self.step_group,
                };
                let indirect = pass
                    .over
                    .indirect_offset()
                    .map(|at| (self.buffer(SimBuffer::CoverTileDispatch), at));
                dispatches.push(Dispatch {
                    kernel,
                    group,
                    offset: Some(offset),
                    workgroups: dispatch_size(pass.over.invocations(counts)),
                    indirect,
                });
            }
        }
        gpu.dispatch(&dispatches, true)?;
        self.last_step = substep.iter().map(|(p, _)| p.entry_point).collect();
        self.steps_submitted += 1;
        self.host.advance(&steps);
        // A far step's rows go to the region of the ground buffer no frame in
        // flight reads (precip_model::host::FarCover).
        if let Some((word, rows)) = self.host.take_far_cover_upload() {
            gpu.write_buffer(
                self.buffer_mut(SimBuffer::Ground),
                u64::from(word) * 4,
                bytemuck::cast_slice(&rows),
            )?;
        }
        Ok(())
    }

    /// Moves the cover grid to `shift` cover texels from where it was configured
    /// (`precip_model::host::cover_window`): waits for the device, reads the
    /// cover back, moves it on the host as every backend does
    /// ([`HostState::move_cover_grid`]), and writes what the move changed — the
    /// cover, the ground map's words, the grids' block, every cover tile marked
    /// (the far cover's rows go with the step's upload). The deposits are empty
    /// between steps (the cover kernel takes them). A write that fails leaves
    /// the device's grid behind the host's: configure again.
    fn move_cover_grid(&mut self, gpu: &mut G, shift: glam::IVec2) -> Result<(), BackendError> {
        gpu.settle()?;
        let cover = self.read_cover(gpu)?;
        let moved = self.host.move_cover_grid(shift, &cover)?;
        let ground = self.host.setup().ground.gpu_words();
        let frames = self.host.frames();
        let tiles = cover_tiles_all_marked(&moved.frame);
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::Cover),
            0,
            bytemuck::cast_slice(&moved.texels),
        )?;
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::Ground),
            0,
            bytemuck::cast_slice(&ground),
        )?;
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::Frames),
            0,
            bytemuck::bytes_of(&frames),
        )?;
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::CoverTiles),
            0,
            bytemuck::cast_slice(&tiles),
        )
    }

    /// Places the terrain's windows of the frame in `slot` (of [`Gpu::slots`]) in
    /// that slot's words and writes those whose place moved since the slot's last
    /// frame, of the levels from the first `params` draws (the scene's or the
    /// mirror's) to the last, each `precip_model::scene::terrain::CLIPMAP_WINDOW_WORDS`
    /// heights, in one write. A camera at rest writes nothing. The caller has freed the slot
    /// ([`Gpu::free_slot`]): no frame in flight reads its words.
    pub fn upload_terrain_windows(
        &mut self,
        gpu: &mut G,
        slot: u32,
        params: &mut precip_model::drawing::render::RenderParams,
    ) -> Result<(), BackendError> {
        use precip_model::scene::terrain::{CLIPMAP_WINDOW_SLOTS, CLIPMAP_WINDOW_WORDS};
        let Some(pyramid) = self.host.terrain_pyramid().cloned() else {
            return Ok(());
        };
        if slot >= CLIPMAP_WINDOW_SLOTS {
            return Err(BackendError::Device {
                backend: "precip-gpu",
                message: format!(
                    "frame slot {slot} has no terrain windows (CLIPMAP_WINDOW_SLOTS is {CLIPMAP_WINDOW_SLOTS}: a bug in precip, please report it)"
                ),
            });
        }
        let levels = pyramid.levels.len();
        if self.terrain_windows.is_empty() {
            self.terrain_windows = vec![vec![None; levels]; CLIPMAP_WINDOW_SLOTS as usize];
        }
        let first_word = params.terrain_levels.z + slot * pyramid.window_words();
        params.terrain_levels.z = first_word;
        let rows = params.clipmap_rows();
        let first_drawn = params.terrain_levels.x.min(params.terrain_levels.w) as usize;
        let written = &self.terrain_windows[slot as usize];
        // The levels whose window moved, written in one piece from the first to
        // the last of them (a backend's write may wait for the device: vk's).
        let moved: Vec<usize> = (first_drawn..levels)
            .filter(|&k| written[k] != Some(rows.window_origin(k)))
            .collect();
        let (Some(&low), Some(&high)) = (moved.first(), moved.last()) else {
            return Ok(());
        };
        let mut words = Vec::with_capacity((high - low + 1) * CLIPMAP_WINDOW_WORDS as usize);
        for k in low..=high {
            words.extend(pyramid.window(k, rows.window_origin(k)));
        }
        let at = u64::from(first_word + low as u32 * CLIPMAP_WINDOW_WORDS) * 4;
        gpu.write_buffer(
            self.buffer_mut(SimBuffer::Ground),
            at,
            bytemuck::cast_slice(&words),
        )?;
        // Taken as written only once written (a failed write is tried again).
        for k in low..=high {
            self.terrain_windows[slot as usize][k] = Some(rows.window_origin(k));
        }
        Ok(())
    }

    /// The last step's time per kernel it dispatched, from the device's timestamps.
    pub fn step_timings(&self, gpu: &mut G) -> Result<Vec<PassTiming>, BackendError> {
        Ok(match gpu.kernel_times_ms()? {
            Some(ms) if !self.last_step.is_empty() && ms.len() >= self.last_step.len() => {
                substep_timings(&self.last_step, ms)
            }
            _ => Vec::new(),
        })
    }

    /// The returns of `query` (validated) on the backend named `backend`: each
    /// beam's first strike among the particles and the ground (`query_beams`), and
    /// what the air beyond the simulated particles returns.
    pub fn query_beams(
        &self,
        gpu: &mut G,
        kernels: &Kernels<G>,
        backend: &'static str,
        query: &BeamQuery,
    ) -> Result<Vec<BeamReturn>, BackendError> {
        let beams = query.validate()?;
        let params = query.params(
            &beams,
            self.host.particles_in_the_air(),
            &self.host.setup().ground,
        );
        let hits = self.first_strikes(gpu, kernels, &params, &beams)?;
        let mut returns = query.answer(
            backend,
            &beams,
            &hits,
            self.host.weather(),
            &self.host.unresolved_air(),
        )?;
        precip_model::sensors::lidar::label_targets(
            &mut returns,
            &beams,
            &self.host.setup().ground,
        );
        Ok(returns)
    }

    /// Each beam's first strike: `query_beams` over the particles and the ground.
    fn first_strikes(
        &self,
        gpu: &mut G,
        kernels: &Kernels<G>,
        params: &BeamParams,
        beams: &[Beam],
    ) -> Result<Vec<BeamHit>, BackendError> {
        let beam_bytes: &[u8] = bytemuck::cast_slice(beams);
        let hits_bytes = (beams.len() * size_of::<BeamHit>()) as u64;
        // Filled with UNWRITTEN: a hit the kernel never wrote is found, not read as one.
        let unwritten = BeamQuery::unwritten_hits(beams.len());
        let mut made: Vec<G::Buffer> = Vec::with_capacity(3);
        let result = (|| {
            made.push(gpu.create_buffer(
                "precip beam params",
                size_of::<BeamParams>() as u64,
                BufferUsage::Uniform,
                Some(bytemuck::bytes_of(params)),
            )?);
            made.push(gpu.create_buffer(
                "precip beams",
                beam_bytes.len() as u64,
                BufferUsage::Storage,
                Some(beam_bytes),
            )?);
            made.push(gpu.create_buffer(
                "precip beam hits",
                hits_bytes,
                BufferUsage::Storage,
                Some(bytemuck::cast_slice(&unwritten)),
            )?);
            let [p, b, h] = &made[..] else {
                return Err(BackendError::Device {
                    backend: "precip-gpu",
                    message: "the beam query lost a buffer (a bug in precip: please report it)"
                        .into(),
                });
            };
            let query = QueryBuffers {
                params: p,
                input: Some(b),
                output: h,
            };
            let group =
                Self::fill_group(gpu, kernels, &BEAM_GROUP, &self.buffers, None, Some(&query))?;
            let ran = gpu.dispatch(
                &[Dispatch {
                    kernel: &kernels.query_beams,
                    group: &group,
                    offset: None,
                    workgroups: dispatch_size(params.beam_count),
                    indirect: None,
                }],
                false,
            );
            let read = ran.and_then(|()| gpu.read_buffer(h, hits_bytes));
            gpu.destroy_bind_group(group);
            Ok(bytemuck::pod_collect_to_vec(&read?))
        })();
        for b in made {
            gpu.destroy_buffer(b);
        }
        result
    }

    /// The optics of the air now ([`Optics::from_sums`]): the camera volume's
    /// cross-sections summed on the device by `optics_sums` (one partial per
    /// workgroup, 32 bytes, read back and added in order), in place of reading every
    /// particle back.
    pub fn optics(&self, gpu: &mut G, kernels: &Kernels<G>) -> Result<Optics, BackendError> {
        let (x, y) = dispatch_size(self.particle_count);
        let groups = u64::from(x) * u64::from(y);
        let partial_bytes = groups * size_of::<OpticsPartial>() as u64;
        let params = OpticsParams {
            // The camera volume's particles that rest are not in the air.
            particle_count: self.host.particles_in_the_air().end,
            ..OpticsParams::default()
        };
        let mut made: Vec<G::Buffer> = Vec::with_capacity(2);
        let result = (|| {
            made.push(gpu.create_buffer(
                "precip optics params",
                size_of::<OpticsParams>() as u64,
                BufferUsage::Uniform,
                Some(bytemuck::bytes_of(&params)),
            )?);
            made.push(gpu.create_buffer(
                "precip optics partials",
                partial_bytes,
                BufferUsage::Storage,
                None,
            )?);
            let [p, partials] = &made[..] else {
                return Err(BackendError::Device {
                    backend: "precip-gpu",
                    message: "the optics query lost a buffer (a bug in precip: please report it)"
                        .into(),
                });
            };
            let query = QueryBuffers {
                params: p,
                input: None,
                output: partials,
            };
            let group = Self::fill_group(
                gpu,
                kernels,
                &OPTICS_GROUP,
                &self.buffers,
                None,
                Some(&query),
            )?;
            let ran = gpu.dispatch(
                &[Dispatch {
                    kernel: &kernels.optics_sums,
                    group: &group,
                    offset: None,
                    workgroups: (x, y),
                    indirect: None,
                }],
                false,
            );
            let read = ran.and_then(|()| gpu.read_buffer(partials, partial_bytes));
            gpu.destroy_bind_group(group);
            let partials: Vec<OpticsPartial> = bytemuck::pod_collect_to_vec(&read?);
            Ok(self.host.with_layers(Optics::from_sums(
                self.host.weather(),
                &CrossSectionSums::of_partials(&partials),
            )))
        })();
        for b in made {
            gpu.destroy_buffer(b);
        }
        result
    }

    /// Every particle, read back.
    pub fn read_particles(&self, gpu: &mut G) -> Result<Vec<Particle>, BackendError> {
        let bytes = gpu.read_buffer(
            self.buffer(SimBuffer::Particles),
            u64::from(self.particle_count) * size_of::<Particle>() as u64,
        )?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// The cover, read back.
    pub fn read_cover(&self, gpu: &mut G) -> Result<CoverGrid, BackendError> {
        let bytes = gpu.read_buffer(
            self.buffer(SimBuffer::Cover),
            u64::from(self.cover_texel_count) * size_of::<precip_cover::CoverTexel>() as u64,
        )?;
        Ok(CoverGrid {
            frame: self.host.setup().cover.frame,
            texels: bytemuck::pod_collect_to_vec(&bytes),
        })
    }

    /// The host state (setup, weather, camera, clock, blocks).
    #[must_use]
    pub fn host(&self) -> &HostState {
        &self.host
    }

    /// A buffer of the configuration (for the frame's bindings).
    #[must_use]
    pub fn buffer(&self, buffer: SimBuffer) -> &G::Buffer {
        &self.buffers[index_of(buffer)]
    }

    fn buffer_mut(&mut self, buffer: SimBuffer) -> &mut G::Buffer {
        &mut self.buffers[index_of(buffer)]
    }

    /// Particles.
    #[must_use]
    pub fn particle_count(&self) -> u32 {
        self.particle_count
    }

    /// The water bodies' wave grid.
    #[must_use]
    pub fn wave_frame(&self) -> GridFrame {
        self.wave_frame
    }

    /// What the dispatches run over.
    #[must_use]
    pub fn dispatch_counts(&self) -> DispatchCounts {
        DispatchCounts::of(
            self.particle_count,
            &self.host.setup().cover.frame,
            &self.wave_frame,
            self.on_cpu,
        )
    }

    /// Hands every resource back to `gpu`.
    pub fn destroy(self, gpu: &mut G) {
        Made::<G> {
            buffers: self.buffers,
            wind: Some(self.wind),
            groups: vec![self.step_group, self.cover_group, self.cover_listing_group],
        }
        .give_back(gpu);
    }
}

/// Where `buffer` is in [`SimBuffer::ALL`].
fn index_of(buffer: SimBuffer) -> usize {
    SimBuffer::ALL
        .iter()
        .position(|&b| b == buffer)
        .unwrap_or_default()
}

/// The table a group of the simulation was made from (for backends that look a
/// layout up by its table).
#[must_use]
pub fn simulation_tables() -> [&'static GroupLayout; 4] {
    [
        STEP_GROUP.layout,
        COVER_GROUP.layout,
        COVER_LISTING_GROUP.layout,
        BEAM_GROUP.layout,
    ]
}

/// Whether a cover kernel lists tiles (and writes the indirect dispatches of the
/// iterations after it): it runs with [`COVER_LISTING_GROUP`].
fn is_cover_listing(entry_point: &str) -> bool {
    matches!(entry_point, "water_tiles_list" | "snow_tiles_list")
}
