//! The kernels as data: which kernels configure, a sub-step and a frame's compute
//! passes run, in which order, over what ([`DispatchOver`]), with which bindings
//! (the `*_bindings` modules), and the byte sizes of the buffers they share, so the
//! wgpu and Vulkan backends cannot drift apart; and the blocks the kernels write
//! ([`FrameDraws`]). The host-side blocks and the dispatch arithmetic come from
//! `precip_model::host` and are re-exported here.

use bytemuck::{Pod, Zeroable};
use precip_cover::GridFrame;
use precip_sea::ocean::{OCEAN_CASCADES, OCEAN_N};

use crate::shaders::Program;

pub use precip_model::host::{
    Frames, MAX_WORKGROUPS_PER_DIMENSION, SceneVertex, WORKGROUP_SIZE, cull_groups, dispatch_size,
};

/// `drawIndirect`'s arguments.
///
/// WGSL twin: `DrawArgs` in `shaders/render_layout.wgsl` (16 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct DrawArgs {
    /// Vertices per instance.
    pub vertex_count: u32,
    /// Instances: drawn particles.
    pub instance_count: u32,
    /// First vertex.
    pub first_vertex: u32,
    /// First instance.
    pub first_instance: u32,
}
const _: () = assert!(size_of::<DrawArgs>() == 16);

/// What the cull kernels write each frame: the indirect draws and how many
/// particles the splat draws.
///
/// WGSL twin: `FrameDraws` in `shaders/render_layout.wgsl` (64 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct FrameDraws {
    /// Snow sprites (4-vertex strips) whose quads the frame keeps (the first
    /// [`SNOW_QUAD_CAPACITY`] instances at most, or as many as the buffer holds), at
    /// [`FrameDraws::SNOW_OFFSET`].
    pub snow: DrawArgs,
    /// Rain tetrahedra (6-vertex strips), at [`FrameDraws::RAIN_OFFSET`].
    pub rain: DrawArgs,
    /// Particles splatted (sub-pixel, in the view cone).
    pub splatted: u32,
    /// Particles drawn as sprites (the snow draw's instances are this times the
    /// copies each camera-volume flake is drawn with,
    /// `precip_model::drawing::multiplicity::snow_copies`).
    pub sprite_particles: u32,
    /// Unused.
    pub reserved: [u32; 2],
    /// The snow sprite instances beyond the kept quads, each corner making its own
    /// (`vs_snow_made`), at [`FrameDraws::SNOW_MADE_OFFSET`].
    pub snow_made: DrawArgs,
}
const _: () = assert!(size_of::<FrameDraws>() == 64);

impl FrameDraws {
    /// Byte offset of the snow draw in the buffer.
    pub const SNOW_OFFSET: u64 = 0;
    /// Byte offset of the rain draw.
    pub const RAIN_OFFSET: u64 = 16;
    /// Byte offset of the draw of the snow sprites beyond the kept quads.
    pub const SNOW_MADE_OFFSET: u64 = 48;
    /// Bytes of the buffer.
    pub const BYTES: u64 = size_of::<Self>() as u64;

    /// The counts, from the buffer's bytes (fewer bytes read as zeros).
    #[must_use]
    pub fn counts(bytes: &[u8]) -> precip_model::DrawnCounts {
        let mut draws = Self::zeroed();
        let n = bytes.len().min(size_of::<Self>());
        bytemuck::bytes_of_mut(&mut draws)[..n].copy_from_slice(&bytes[..n]);
        precip_model::DrawnCounts {
            sprites: draws.sprite_particles,
            streaks: draws.rain.instance_count,
            splats: draws.splatted,
        }
    }
}

/// What a kernel is dispatched over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DispatchOver {
    /// One invocation per particle.
    Particles,
    /// One invocation per particle a step moves (`StepParams::step_first` on:
    /// `precip_model::particles::step::stepped_particles`).
    SteppedParticles,
    /// One invocation per cover texel.
    CoverTexels,
    /// A single workgroup.
    OneWorkgroup,
    /// A list of particles: one invocation per [`LIST_ENTRIES_PER_INVOCATION`]
    /// particles, each walking the list (the pending births, binding
    /// [`step_bindings::PENDING_BIRTHS`]; the splat list, [`render_bindings::DRAWN`])
    /// with the dispatch's stride, to the list's count.
    ParticleList,
    /// One invocation per cell of the water bodies' wave grid.
    WaveCells,
    /// One invocation per texel of the clouds' shadow map
    /// ([`precip_model::drawing::clouds::CLOUD_SHADOW_MAP_PX`] squared).
    CloudShadowTexels,
    /// One invocation per point of the sea's cascades
    /// (`precip_sea::ocean::OCEAN_CASCADES` × `OCEAN_N`²).
    OceanPoints,
    /// One workgroup of [`WORKGROUP_SIZE`] (= `OCEAN_N / 2`) per line of a field of
    /// a cascade (cascades × 2 fields × `OCEAN_N` lines): the FFT's.
    OceanLines,
    /// One invocation per texel of the sea's atlases ([`OCEAN_ATLAS_PX`]).
    OceanTexels,
    /// One invocation per corner of the shore's cells (`(nx + 1)·(ny + 1)`): the
    /// faces after and above each, and each cell's bed source.
    ShoreFaces,
    /// One invocation per cell of the shore's grid.
    ShoreCells,
    /// The tiles of a [`CoverTileSet`] its last listing listed: one workgroup per
    /// listed cover tile ([`COVER_TILE_SIDE`]) on a GPU, per
    /// [`COVER_TILES_PER_WORKGROUP`] on a device that computes on the CPU, a texel
    /// an invocation, each workgroup taking a listed tile at a time with the
    /// dispatch's stride: the flow's and the drift's kernels. An indirect dispatch
    /// ([`DispatchOver::indirect_offset`]): the listing writes its workgroups into
    /// [`crate::resources::SimBuffer::CoverTileDispatch`], so the kernels cost what
    /// the tiles listed cost and nothing where none are (lavapipe runs a
    /// workgroup with nothing listed for about 1 µs, and a busy CPU's thread
    /// wake-ups make a dispatch of many of them dearer still).
    /// [`DispatchOver::invocations`] gives the most it may be.
    ListedCoverTiles(CoverTileSet),
}

/// What the dispatches of a configuration run over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DispatchCounts {
    /// Particles.
    pub particles: u32,
    /// Particles a step moves (the rest rest); the frame: all of them.
    pub stepped_particles: u32,
    /// Cover texels.
    pub cover_texels: u32,
    /// Wave cells.
    pub wave_cells: u32,
    /// Tiles of the cover grid ([`cover_tiles`]).
    pub cover_tiles: u32,
    /// Tiles a workgroup of the flow or the drift takes ([`COVER_TILES_PER_WORKGROUP`]
    /// on a device that computes on the CPU, else 1; 0 reads as 1).
    pub cover_tiles_per_workgroup: u32,
    /// The shore's cells (`nx·ny`; 0 without a shore).
    pub shore_cells: u32,
    /// The shore's cell corners (`(nx + 1)·(ny + 1)`; 0 without a shore).
    pub shore_faces: u32,
}

impl DispatchCounts {
    /// The counts of a configuration of `particles` particles, the cover grid
    /// `cover` and the wave grid `waves`, on a device that computes on the CPU or
    /// not (`on_cpu`).
    #[must_use]
    pub fn of(particles: u32, cover: &GridFrame, waves: &GridFrame, on_cpu: bool) -> Self {
        let (x, z) = cover_tiles(cover);
        Self {
            particles,
            stepped_particles: particles,
            cover_texels: u32::try_from(cover.texel_count()).unwrap_or(u32::MAX),
            wave_cells: u32::try_from(waves.texel_count()).unwrap_or(u32::MAX),
            cover_tiles: x.saturating_mul(z),
            cover_tiles_per_workgroup: if on_cpu { COVER_TILES_PER_WORKGROUP } else { 1 },
            shore_cells: 0,
            shore_faces: 0,
        }
    }
}

impl DispatchOver {
    /// Invocations of a dispatch over this (before rounding up to workgroups).
    #[must_use]
    pub const fn invocations(self, counts: DispatchCounts) -> u32 {
        match self {
            Self::Particles => counts.particles,
            Self::SteppedParticles => counts.stepped_particles,
            Self::CoverTexels => counts.cover_texels,
            Self::OneWorkgroup => 1,
            Self::CloudShadowTexels => {
                precip_model::drawing::clouds::CLOUD_SHADOW_MAP_PX
                    * precip_model::drawing::clouds::CLOUD_SHADOW_MAP_PX
            }
            // A list holds particles in the air only (births come from the ones
            // stepped, the splat's from the ones drawn).
            Self::ParticleList => list_invocations(counts.stepped_particles),
            Self::WaveCells => counts.wave_cells,
            Self::OceanPoints => (OCEAN_CASCADES * OCEAN_N * OCEAN_N) as u32,
            Self::OceanLines => (OCEAN_CASCADES * 2 * OCEAN_N) as u32 * WORKGROUP_SIZE,
            Self::OceanTexels => OCEAN_ATLAS_PX[0] * OCEAN_ATLAS_PX[1],
            Self::ShoreFaces => counts.shore_faces,
            Self::ShoreCells => counts.shore_cells,
            Self::ListedCoverTiles(_) => {
                let per_workgroup = match counts.cover_tiles_per_workgroup {
                    0 => 1,
                    n => n,
                };
                counts
                    .cover_tiles
                    .div_ceil(per_workgroup)
                    .saturating_mul(WORKGROUP_SIZE)
            }
        }
    }

    /// Where an indirect dispatch over this finds its workgroups in
    /// [`crate::resources::SimBuffer::CoverTileDispatch`], bytes; `None` for a
    /// dispatch of [`DispatchOver::invocations`].
    #[must_use]
    pub const fn indirect_offset(self) -> Option<u64> {
        match self {
            Self::ListedCoverTiles(set) => Some(set as u64 * COVER_TILE_DISPATCH_BYTES_PER_SET),
            _ => None,
        }
    }
}

/// Bytes of one [`CoverTileSet`]'s entry in
/// [`crate::resources::SimBuffer::CoverTileDispatch`]: the indirect dispatch's
/// workgroups `(x, 1, 1)` the set's listing writes, then the tiles a workgroup takes
/// (the host's, [`cover_tile_dispatch_words`]). WGSL twin: `cover_tile_dispatch`
/// of `precip-cover/shaders/cover_update.wgsl`.
pub const COVER_TILE_DISPATCH_BYTES_PER_SET: u64 = 16;

/// [`crate::resources::SimBuffer::CoverTileDispatch`] before any listing: for each
/// [`CoverTileSet`] no workgroups, and the tiles a workgroup takes
/// (`tiles_per_workgroup`, [`DispatchCounts::cover_tiles_per_workgroup`]; 0 reads as 1).
#[must_use]
pub fn cover_tile_dispatch_words(tiles_per_workgroup: u32) -> Vec<u32> {
    [0, 1, 1, tiles_per_workgroup.max(1)].repeat(COVER_TILE_SETS as usize)
}

/// Side of a cover tile, texels. The cover's exchanges between neighbours, the
/// overland flow and the snow's drift, run only over the tiles where they have
/// work, each from its own list of tiles (a [`CoverTileSet`]): the tiles within
/// [`COVER_TILE_REACH`] of a marked tile, and, one list more, those listed the time
/// before, so they write their outflows back to zero.
///
/// - **Water** is listed before each group of [`FLOW_GROUPS`]; the cover kernel
///   marks the tiles where it leaves water that can flow, each inflow the tiles
///   where water moved (the first list holds every wet tile, the later ones where
///   water moves), and the water needs no list more: a texel that sent something
///   in a group's last iteration marked its tile.
/// - **Snow** is listed once a sub-step, before its
///   [`precip_cover::SNOW_DRIFT_ITERATIONS`] iterations; the wind's kernel
///   (`snow_wind`) marks the tiles where a texel would send snow (the wind lifts
///   it, or it stands steeper than its repose).
///
/// Each list clears its marks. Water and snow move at most a texel an iteration,
/// and a texel starts to send only when it or a neighbour took or sent something
/// (a slide opens where a neighbour's snow left): so between two lists what moves
/// stays within the reach of a mark, every texel left out would neither send nor
/// take anything, and the exchange is the whole grid's, bit for bit, at a cost
/// that follows the area where it has work. WGSL twin: `COVER_TILE_SIDE` in
/// `precip-cover/shaders/cover_update.wgsl`.
pub const COVER_TILE_SIDE: u32 = 8;

/// Tiles a workgroup of the flow or the drift takes, one after the other, on a
/// device that computes on the CPU ([`DispatchOver::ListedCoverTiles`]). There each
/// workgroup has a cost of its own even when it has nothing to do (lavapipe: about
/// 1 µs, so that one workgroup per tile of a 320² grid costs 1.4 ms a dispatch, the
/// whole of the flow's cost where little water stands): a few tiles each keeps that
/// small. A GPU wants the parallelism instead (H200, the same grid fully wet:
/// 1.6 GPU ms a frame at 8 tiles a workgroup, against 1.3 for the whole grid), so
/// it gets one tile a workgroup.
pub const COVER_TILES_PER_WORKGROUP: u32 = 8;

/// The flow's iterations of a sub-step in groups, each after a list of the water
/// tiles: the first list holds every tile where water stands (the cover kernel
/// marks them), the later ones the tiles where water moved
/// (`water_inflow` marks them), so water at rest, level to
/// [`precip_cover::water::LEVEL_WATER_M`], runs one iteration of
/// [`precip_cover::WATER_FLOW_ITERATIONS`] a sub-step and water on the move all of
/// them. A group is at most [`COVER_TILE_REACH`] tiles of iterations (water moves
/// a texel an iteration).
pub const FLOW_GROUPS: [u32; 3] = [1, 8, 7];

/// Tiles water or snow can reach from a marked tile before the next list (a texel
/// an iteration: a group of [`FLOW_GROUPS`] or [`precip_cover::SNOW_DRIFT_ITERATIONS`]
/// texels). WGSL twin: `COVER_TILE_REACH`.
pub const COVER_TILE_REACH: u32 = 1;

const _: () = assert!(COVER_TILE_SIDE * COVER_TILE_SIDE == WORKGROUP_SIZE);
const _: () = {
    let mut k = 0;
    let mut iterations = 0;
    while k < FLOW_GROUPS.len() {
        assert!(FLOW_GROUPS[k] >= 1 && FLOW_GROUPS[k] <= COVER_TILE_REACH * COVER_TILE_SIDE);
        iterations += FLOW_GROUPS[k];
        k += 1;
    }
    assert!(iterations == precip_cover::WATER_FLOW_ITERATIONS);
};
const _: () = assert!(precip_cover::SNOW_DRIFT_ITERATIONS <= COVER_TILE_REACH * COVER_TILE_SIDE);

/// Which list of cover tiles: the flow's or the drift's. WGSL twins: `WATER_TILES`,
/// `SNOW_TILES`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoverTileSet {
    /// The tiles where standing water can flow.
    Water = 0,
    /// The tiles where snow can drift or slide.
    Snow = 1,
}

/// Lists of cover tiles in the buffer ([`CoverTileSet`]).
pub const COVER_TILE_SETS: u64 = 2;

/// The tiles of the cover grid `cover`: across x, across z.
#[must_use]
pub fn cover_tiles(cover: &GridFrame) -> (u32, u32) {
    (
        cover.texels.x.div_ceil(COVER_TILE_SIDE),
        cover.texels.y.div_ceil(COVER_TILE_SIDE),
    )
}

/// Bytes of the cover tiles' buffer (`u32` words): for each [`CoverTileSet`] in
/// turn, the count of listed tiles, then per tile whether it is marked, then per
/// tile whether the last listing found it near a mark (bit 0) and whether it
/// listed it (bit 1: an exchange takes only listed texels' outflows, as the flow
/// and the drift share the field), then the list (each tile's x | z << 16). WGSL
/// twin: binding `cover_tiles` of `cover_update.wgsl`.
#[must_use]
pub fn cover_tiles_bytes(cover: &GridFrame) -> u64 {
    let (x, z) = cover_tiles(cover);
    4 * COVER_TILE_SETS * (1 + 3 * u64::from(x) * u64::from(z))
}

/// The cover tiles' buffer with every tile of both lists marked and nothing
/// listed: the next listing lists every tile, as after a cover grid's move
/// (`precip_model::host::cover_window`), when any texel may hold water or snow
/// to move.
#[must_use]
pub fn cover_tiles_all_marked(cover: &GridFrame) -> Vec<u32> {
    let (x, z) = cover_tiles(cover);
    let tiles = (x * z) as usize;
    let mut set = vec![0u32; 1 + 3 * tiles];
    set[1..=tiles].fill(1);
    let words = set.repeat(COVER_TILE_SETS as usize);
    debug_assert_eq!(4 * words.len() as u64, cover_tiles_bytes(cover));
    words
}

/// Particles per invocation of a kernel over a list (see [`DispatchOver::ParticleList`]).
///
/// The step appends each particle to re-birth to a list (a count, then one `u32`
/// index each; `reset_births` empties it before each step), and the cull lists the
/// particles to splat; the birth and splat kernels run over `⌈particles / 16⌉`
/// invocations that walk their list, so they cost what the particles listed cost,
/// densely: on lavapipe, which executes both sides of a divergent branch under a
/// mask (a loop ends when no lane is left), the full-size birth kernel cost 27–41 ms
/// at 10⁶ particles for a few thousand births. A fixed dispatch rather than an
/// indirect one, because WebGPU forbids a buffer as indirect arguments and as
/// writable storage in one dispatch (the list would need a copy every sub-step).
pub const LIST_ENTRIES_PER_INVOCATION: u32 = 16;

/// Bytes of the pending births for `particle_count` particles: the count, then an
/// index per particle (each is re-born at most once a sub-step).
///
/// WGSL twin: `PendingBirths` in `shaders/layout.wgsl`.
#[must_use]
pub fn pending_births_bytes(particle_count: u32) -> u64 {
    4 + 4 * u64::from(particle_count.max(1))
}

/// Invocations of a kernel over a list of at most `particle_count` particles.
#[must_use]
pub const fn list_invocations(particle_count: u32) -> u32 {
    let n = particle_count.div_ceil(LIST_ENTRIES_PER_INVOCATION);
    if n == 0 { 1 } else { n }
}

/// One kernel of the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KernelPass {
    /// The program it is in.
    pub program: Program,
    /// Its entry point.
    pub entry_point: &'static str,
    /// Its dispatch.
    pub over: DispatchOver,
    /// When it is dispatched.
    pub when: KernelWhen,
}

/// When a kernel of the step is dispatched: always, or only while the feature it
/// serves may have work ([`precip_model::host::Activity`], decided on the host), so
/// an idle feature costs nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelWhen {
    /// Every time its pass runs.
    Always,
    /// While some texel may hold snow (the drift).
    WhileSnowMayLie,
    /// While some texel may hold standing water (the flow).
    WhileWaterMayStand,
}

impl KernelWhen {
    /// Whether a kernel with this condition runs under `activity`.
    #[must_use]
    pub const fn holds(self, activity: precip_model::host::Activity) -> bool {
        match self {
            Self::Always => true,
            Self::WhileSnowMayLie => activity.snow_may_lie,
            Self::WhileWaterMayStand => activity.water_may_stand,
        }
    }
}

/// Initialisation (configure): pre-warmed particles.
pub const INIT_PASS: KernelPass = KernelPass {
    program: Program::StepParticles,
    entry_point: "init_particles",
    over: DispatchOver::Particles,
    when: KernelWhen::Always,
};

/// The kernels of one sub-step before the snow's drift.
const SUBSTEP_HEAD: [KernelPass; 7] = [
    KernelPass {
        program: Program::StepParticles,
        entry_point: "reset_births",
        over: DispatchOver::OneWorkgroup,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::StepParticles,
        entry_point: "step_particles",
        over: DispatchOver::SteppedParticles,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::StepParticles,
        entry_point: "wave_excite",
        over: DispatchOver::ParticleList,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::StepParticles,
        entry_point: "birth_particles",
        over: DispatchOver::ParticleList,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "cover_update",
        over: DispatchOver::CoverTexels,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "snow_wind",
        over: DispatchOver::CoverTexels,
        when: KernelWhen::WhileSnowMayLie,
    },
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "snow_tiles_list",
        over: DispatchOver::OneWorkgroup,
        when: KernelWhen::WhileSnowMayLie,
    },
];

/// One iteration of the snow's drift over the listed tiles: every texel's
/// outflows, then every texel's exchange ([`precip_cover::drift`]).
const DRIFT_ITERATION: [KernelPass; 2] = [
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "snow_outflow",
        over: DispatchOver::ListedCoverTiles(CoverTileSet::Snow),
        when: KernelWhen::WhileSnowMayLie,
    },
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "snow_inflow",
        over: DispatchOver::ListedCoverTiles(CoverTileSet::Snow),
        when: KernelWhen::WhileSnowMayLie,
    },
];

/// Before each group of [`FLOW_GROUPS`]: the list of the tiles its iterations
/// run over ([`COVER_TILE_SIDE`]).
const FLOW_LIST: KernelPass = KernelPass {
    program: Program::CoverUpdate,
    entry_point: "water_tiles_list",
    over: DispatchOver::OneWorkgroup,
    when: KernelWhen::WhileWaterMayStand,
};

/// One iteration of overland flow over the listed tiles: every texel's outflows,
/// then every texel's exchange ([`precip_cover::water`]).
const FLOW_ITERATION: [KernelPass; 2] = [
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "water_outflow",
        over: DispatchOver::ListedCoverTiles(CoverTileSet::Water),
        when: KernelWhen::WhileWaterMayStand,
    },
    KernelPass {
        program: Program::CoverUpdate,
        entry_point: "water_inflow",
        over: DispatchOver::ListedCoverTiles(CoverTileSet::Water),
        when: KernelWhen::WhileWaterMayStand,
    },
];

/// The water bodies' waves, after the flow: the next heights, then the shift.
const SUBSTEP_TAIL: [KernelPass; 2] = [
    KernelPass {
        program: Program::StepParticles,
        entry_point: "wave_step",
        over: DispatchOver::WaveCells,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::StepParticles,
        entry_point: "wave_shift",
        over: DispatchOver::WaveCells,
        when: KernelWhen::Always,
    },
];

/// Drift kernels a sub-step.
const DRIFT_KERNELS: usize = DRIFT_ITERATION.len() * precip_cover::SNOW_DRIFT_ITERATIONS as usize;

/// Flow kernels a sub-step, the lists included.
const FLOW_KERNELS: usize =
    FLOW_GROUPS.len() + FLOW_ITERATION.len() * precip_cover::WATER_FLOW_ITERATIONS as usize;

/// The `k`th of the flow's kernels a sub-step: a list before each group of
/// [`FLOW_GROUPS`], then the group's iterations.
const fn flow_kernel(k: usize) -> KernelPass {
    let mut group = 0;
    let mut start = 0;
    while group < FLOW_GROUPS.len() {
        let len = 1 + FLOW_ITERATION.len() * FLOW_GROUPS[group] as usize;
        if k < start + len {
            let in_group = k - start;
            return if in_group == 0 {
                FLOW_LIST
            } else {
                FLOW_ITERATION[(in_group - 1) % FLOW_ITERATION.len()]
            };
        }
        start += len;
        group += 1;
    }
    FLOW_LIST
}

/// Kernels of one sub-step.
pub const SUBSTEP_KERNELS: usize =
    SUBSTEP_HEAD.len() + DRIFT_KERNELS + FLOW_KERNELS + SUBSTEP_TAIL.len();

/// One sub-step, in order: the pending births are emptied, the particles move
/// (listing those to re-birth, a landed one at its landing point), the landed ones
/// strike the water bodies' waves, the listed ones deposit their water and are
/// re-born (or splash), the cover takes the deposits (or the rate), melts, ages and
/// wets, the wind's factor over the ground is read (marking where snow can move),
/// snow drifts and slides over the tiles listed then
/// ([`precip_cover::SNOW_DRIFT_ITERATIONS`] iterations of two kernels), standing
/// water flows ([`precip_cover::WATER_FLOW_ITERATIONS`] iterations of two kernels,
/// over the water tiles listed before each group of [`FLOW_GROUPS`]),
/// and the waves advance ([`precip_model::physics::water_waves`]). Sub-steps repeat this with their
/// own uniform blocks (dynamic offsets).
pub const SUBSTEP_PASSES: [KernelPass; SUBSTEP_KERNELS] = {
    let mut passes = [SUBSTEP_HEAD[0]; SUBSTEP_KERNELS];
    let head = SUBSTEP_HEAD.len();
    let mut k = 0;
    while k < SUBSTEP_KERNELS {
        passes[k] = if k < head {
            SUBSTEP_HEAD[k]
        } else if k < head + DRIFT_KERNELS {
            DRIFT_ITERATION[(k - head) % DRIFT_ITERATION.len()]
        } else if k < head + DRIFT_KERNELS + FLOW_KERNELS {
            flow_kernel(k - head - DRIFT_KERNELS)
        } else {
            SUBSTEP_TAIL[k - head - DRIFT_KERNELS - FLOW_KERNELS]
        };
        k += 1;
    }
    passes
};

/// Per-kernel timings of a step from the time each dispatch took, in dispatch order
/// (sub-step after sub-step, each dispatching `kernels` in order): summed per kernel
/// entry point, in the order of `kernels` (a kernel dispatched many times — the
/// flow's — is one entry). Kernels the step did not dispatch are not reported.
#[must_use]
pub fn substep_timings(
    kernels: &[&'static str],
    elapsed_ms: impl IntoIterator<Item = f64>,
) -> Vec<precip_model::PassTiming> {
    let mut passes: Vec<precip_model::PassTiming> = Vec::new();
    for &kernel in kernels {
        if !passes.iter().any(|p| p.pass == kernel) {
            passes.push(precip_model::PassTiming {
                pass: kernel,
                milliseconds: 0.0,
            });
        }
    }
    for (&name, ms) in kernels.iter().cycle().zip(elapsed_ms) {
        if let Some(p) = passes.iter_mut().find(|p| p.pass == name) {
            p.milliseconds += ms;
        }
    }
    passes
}

/// The features a frame's GPU time goes to, each with the kernels and passes that
/// serve it (every kernel of [`SUBSTEP_PASSES`] and pass of
/// [`crate::frame::FRAME_PASSES`] is in exactly one): what the viewer's summary and
/// the report add up into each feature's share of the frame.
pub const FEATURES: [(&str, &[&str]); 8] = [
    (
        "particles",
        &[
            "reset_births",
            "step_particles",
            "birth_particles",
            "cull_particles",
            "splat_particles",
            "snow_quads",
            "particles",
            "particles_reduced",
            "particles_composite",
        ],
    ),
    ("cover", &["cover_update", "cover_texture", "drop_ground"]),
    (
        "drift",
        &[
            "snow_wind",
            "snow_tiles_list",
            "snow_outflow",
            "snow_inflow",
        ],
    ),
    (
        "water",
        &[
            "water_tiles_list",
            "water_outflow",
            "water_inflow",
            "wave_excite",
            "wave_step",
            "wave_shift",
            "scene_copy",
            "water_mirror",
        ],
    ),
    (
        "sky",
        &["cloud_shadow", "clouds_fresh", "clouds", "clouds_b"],
    ),
    ("sea", &["ocean", "shore"]),
    ("scene", &["scene"]),
    ("shadow", &["shadow"]),
];

/// Each feature's milliseconds and share of the total, from per-pass milliseconds
/// (`(pass, ms)`; a pass of no feature counts in the total as `other`), in
/// [`FEATURES`]' order, features that took no time left out.
#[must_use]
pub fn feature_shares(passes: &[(&str, f64)]) -> Vec<(&'static str, f64, f64)> {
    let total: f64 = passes.iter().map(|(_, ms)| ms.max(0.0)).sum();
    let mut shares: Vec<(&'static str, f64, f64)> = FEATURES
        .iter()
        .map(|(feature, names)| {
            let ms = passes
                .iter()
                .filter(|(pass, _)| names.contains(pass))
                .map(|(_, ms)| ms.max(0.0))
                .sum();
            (*feature, ms, 0.0)
        })
        .collect();
    let other = passes
        .iter()
        .filter(|(pass, _)| !FEATURES.iter().any(|(_, names)| names.contains(pass)))
        .map(|(_, ms)| ms.max(0.0))
        .sum();
    shares.push(("other", other, 0.0));
    shares.retain(|(_, ms, _)| *ms > 0.0);
    for s in &mut shares {
        s.2 = if total > 0.0 { s.1 / total } else { 0.0 };
    }
    shares
}

/// [`feature_shares`] in words: `particles 50 %, scene 36 %, cover <1 %, …`.
#[must_use]
pub fn feature_shares_text(passes: &[(&str, f64)]) -> String {
    feature_shares(passes)
        .iter()
        .map(|(feature, _, share)| {
            if *share < 0.005 {
                format!("{feature} <1 %")
            } else {
                format!("{feature} {:.0} %", 100.0 * share)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// What a kernel's bytes are counted per.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BytesPer {
    /// Every particle of the dispatch.
    Particle,
    /// Every particle re-born (a few per sub-step).
    Birth,
    /// Every particle drawn that way (a sprite or streak, or a splat).
    Drawn,
}

/// Bytes of particle state and per-particle lists a kernel reads and writes, counted
/// from its WGSL: a whole [`precip_model::Particle`] is 64 bytes, a word 4 (the wind volume,
/// ground map, cover and uniform blocks, small and cached, are not counted). The
/// report turns them into bytes per second with the kernels' measured times.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KernelBytes {
    /// The entry point.
    pub entry_point: &'static str,
    /// Counted per.
    pub per: BytesPer,
    /// Bytes read.
    pub read: u32,
    /// Bytes written.
    pub written: u32,
}

const PARTICLE_BYTES: u32 = size_of::<precip_model::Particle>() as u32;

/// The bytes each particle kernel and draw moves ([`KernelBytes`]).
pub const KERNEL_BYTES: [KernelBytes; 9] = [
    // The particle, read and written whole (52 of its 64 bytes change).
    KernelBytes {
        entry_point: "step_particles",
        per: BytesPer::Particle,
        read: PARTICLE_BYTES,
        written: PARTICLE_BYTES,
    },
    // The step's append (a word), the index read back, the particle read (flags,
    // water, position) and written new.
    KernelBytes {
        entry_point: "birth_particles",
        per: BytesPer::Birth,
        read: 4 + PARTICLE_BYTES,
        written: 4 + PARTICLE_BYTES,
    },
    // Position, velocity, flags and diameter span the particle's four rows; its class
    // and rank are written as one word (`drawn_kinds`).
    KernelBytes {
        entry_point: "cull_count",
        per: BytesPer::Particle,
        read: PARTICLE_BYTES,
        written: 4,
    },
    // The class word; the index of each particle drawn or splatted.
    KernelBytes {
        entry_point: "cull_write",
        per: BytesPer::Particle,
        read: 4,
        written: 0,
    },
    KernelBytes {
        entry_point: "cull_write",
        per: BytesPer::Drawn,
        read: 0,
        written: 4,
    },
    // The splat list's entry, the particle, and four pixels' sums (4 words each,
    // read and written by the atomics).
    KernelBytes {
        entry_point: "splat_particles",
        per: BytesPer::Drawn,
        read: 4 + PARTICLE_BYTES + 4 * 16,
        written: 4 * 16,
    },
    // A sprite's index and particle read, its quad written (once a copy: counted
    // once a drawn sprite here).
    KernelBytes {
        entry_point: "snow_quads_write",
        per: BytesPer::Drawn,
        read: 4 + PARTICLE_BYTES,
        written: SNOW_QUAD_BYTES as u32,
    },
    // The quad, once an instance (its 4 vertices hit the cache for the rest).
    KernelBytes {
        entry_point: "vs_snow",
        per: BytesPer::Drawn,
        read: SNOW_QUAD_BYTES as u32,
        written: 0,
    },
    // The index and the particle, once an instance (its 6 vertices hit the cache
    // for the rest).
    KernelBytes {
        entry_point: "vs_rain",
        per: BytesPer::Drawn,
        read: 4 + PARTICLE_BYTES,
        written: 0,
    },
];

/// Bytes read plus written per particle by the kernels of one sub-step over all
/// particles (re-births, a few per sub-step, not counted).
#[must_use]
pub fn step_bytes_per_particle() -> u64 {
    KERNEL_BYTES
        .iter()
        .filter(|k| k.per == BytesPer::Particle)
        .filter(|k| {
            SUBSTEP_PASSES
                .iter()
                .any(|p| p.entry_point == k.entry_point)
        })
        .map(|k| u64::from(k.read + k.written))
        .sum()
}

/// The culling kernels of a frame, in order; `cull_scan` runs as one workgroup,
/// the others over the particles' workgroups (the same count `dispatch_size` gives).
pub const CULL_PASSES: [KernelPass; 3] = [
    KernelPass {
        program: Program::CullParticles,
        entry_point: "cull_count",
        over: DispatchOver::Particles,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::CullParticles,
        entry_point: "cull_scan",
        over: DispatchOver::OneWorkgroup,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::CullParticles,
        entry_point: "cull_write",
        over: DispatchOver::Particles,
        when: KernelWhen::Always,
    },
];

/// The draws of a frame, in order, each a vertex and fragment entry point of
/// [`Program::Render`]. The shadow pass writes depth only (no fragment stage).
pub mod render_passes {
    /// Sun's depth: the scene's displaced geometry.
    pub const SHADOW: (&str, Option<&str>) = ("vs_shadow", None);
    /// The scene with its cover.
    pub const SCENE: (&str, Option<&str>) = ("vs_scene", Some("fs_scene"));
    /// The same where only the cover grid's own cover shows (no far cover read).
    pub const SCENE_ON_GRID: (&str, Option<&str>) = ("vs_scene", Some("fs_scene_on_grid"));
    /// The terrain's clipmap with its cover (render_terrain.wgsl): its vertices
    /// pulled from the pyramid by their index, its fragments the scene's.
    pub const TERRAIN: (&str, Option<&str>) = ("vs_terrain", Some("fs_terrain"));
    /// Sun's depth: the terrain's clipmap.
    pub const TERRAIN_SHADOW: (&str, Option<&str>) = ("vs_terrain_shadow", None);
    /// The water bodies, mirroring the scene (render_reflections.wgsl).
    pub const WATER_BODIES: (&str, Option<&str>) = ("vs_scene", Some("fs_water_body"));
    /// The water bodies where the planar mirror is drawn: its image sampled.
    pub const WATER_BODIES_PLANAR: (&str, Option<&str>) =
        ("vs_scene", Some("fs_water_body_planar"));
    /// The open sea: its still surface moved by the waves, shaded by their slopes
    /// and foam (render_ocean.wgsl).
    pub const SEA: (&str, Option<&str>) = ("vs_sea", Some("fs_sea"));
    /// The scene but the water bodies, reflected about their level, into the
    /// mirror image.
    pub const MIRROR: (&str, Option<&str>) = ("vs_mirror", Some("fs_mirror"));
    /// The terrain's clipmap reflected about the water bodies' level, into the
    /// mirror image.
    pub const TERRAIN_MIRROR: (&str, Option<&str>) =
        ("vs_terrain_mirror", Some("fs_terrain_mirror"));
    /// Snow sprites: triangle strip of 4 vertices per drawn particle, indirect draw 0.
    pub const SNOW: (&str, Option<&str>) = ("vs_snow", Some("fs_snow"));
    /// Snow sprites beyond the kept quads, each corner making its own.
    pub const SNOW_MADE: (&str, Option<&str>) = ("vs_snow_made", Some("fs_snow_made"));
    /// Rain tetrahedra: a strip of 6 vertices per drawn particle, indirect draw 1.
    pub const RAIN: (&str, Option<&str>) = ("vs_rain", Some("fs_rain"));
    /// The overcast sky behind the scene: one triangle of 3 vertices at the far plane,
    /// after the meshes, where nothing stands.
    pub const SKY: (&str, Option<&str>) = ("vs_sky", Some("fs_sky"));
    /// The sky under a drawn cloud layer: the clear sky and the clouds' image.
    pub const SKY_CLOUDS: (&str, Option<&str>) = ("vs_sky_clouds", Some("fs_sky_clouds"));
    /// The same over the clouds' image B (the images alternate by frame).
    pub const SKY_CLOUDS_B: (&str, Option<&str>) = ("vs_sky_clouds_b", Some("fs_sky_clouds_b"));
    /// The cloud layer marched into the clouds' image: one triangle of 3 vertices
    /// covering it.
    pub const CLOUDS: (&str, Option<&str>) = ("vs_clouds", Some("fs_clouds"));
    /// The same into the clouds' image B, reading A as the frame before's.
    pub const CLOUDS_B: (&str, Option<&str>) = ("vs_clouds_b", Some("fs_clouds_b"));
    /// Every pixel of the clouds' image marched (no history), into A or B.
    pub const CLOUDS_ALL: (&str, Option<&str>) = ("vs_clouds_all", Some("fs_clouds_all"));
    /// The one pixel of each 4 × 4 block of the clouds' image the frame marches,
    /// into the clouds' fresh image: one triangle of 3 vertices covering it.
    pub const CLOUDS_FRESH: (&str, Option<&str>) = ("vs_clouds_fresh", Some("fs_clouds_fresh"));
    /// The splat sums blended over the frame: one triangle of 3 vertices covering the
    /// target, no depth test (the splat kernel tested each particle), alpha blending;
    /// first in the particles' pass.
    pub const SPLAT_RESOLVE: (&str, Option<&str>) = ("vs_splat_resolve", Some("fs_splat_resolve"));
    /// Snow sprites into the particles' image (reduced resolution), each fragment's
    /// opacity scaled by the share of the frame's pixels under it where it stands in
    /// front of the scene.
    pub const SNOW_REDUCED: (&str, Option<&str>) = ("vs_snow_reduced", Some("fs_snow_reduced"));
    /// The same beyond the kept quads.
    pub const SNOW_MADE_REDUCED: (&str, Option<&str>) =
        ("vs_snow_made_reduced", Some("fs_snow_made_reduced"));
    /// Rain streaks into the particles' image, likewise.
    pub const RAIN_REDUCED: (&str, Option<&str>) = ("vs_rain_reduced", Some("fs_rain_reduced"));
    /// The splat's sums resolved and the particles' image over them, over the frame:
    /// one triangle of 3 vertices covering the target, the image filtered,
    /// premultiplied.
    pub const PARTICLES_COMPOSITE: (&str, Option<&str>) =
        ("vs_particles_composite", Some("fs_particles_composite"));
}

/// The sea's atlases' size, px: each cascade's `OCEAN_N`² square with a border
/// texel each side, side by side (render_ocean.wgsl `OCEAN_ATLAS_SIDE`).
pub const OCEAN_ATLAS_PX: [u32; 2] = [
    (OCEAN_CASCADES * (OCEAN_N + 2)) as u32,
    (OCEAN_N + 2) as u32,
];

/// The sea's spectra: per cascade two fields of `OCEAN_N`² `vec4<f32>`, bytes.
pub const OCEAN_SPECTRA_BYTES: u64 = (OCEAN_CASCADES * 2 * OCEAN_N * OCEAN_N * 16) as u64;

// The FFT takes a line of OCEAN_N points in one workgroup, a butterfly an
// invocation.
const _: () = assert!(OCEAN_N as u32 == 2 * WORKGROUP_SIZE);

/// The open sea's kernels, in order (render_ocean.wgsl): the spectra at the frame's
/// time, the inverse FFT's rows and columns, the surfaces into the atlases.
pub const OCEAN_PASSES: [KernelPass; 4] = [
    KernelPass {
        program: Program::Render,
        entry_point: "ocean_spectrum",
        over: DispatchOver::OceanPoints,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::Render,
        entry_point: "ocean_fft_rows",
        over: DispatchOver::OceanLines,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::Render,
        entry_point: "ocean_fft_columns",
        over: DispatchOver::OceanLines,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::Render,
        entry_point: "ocean_resolve",
        over: DispatchOver::OceanTexels,
        when: KernelWhen::Always,
    },
];

/// One step of the shore (render_shore.wgsl): Heun's two stages, each the faces'
/// fluxes and the cells' bed sources from a state, then the cells updated.
const SHORE_STEP: [KernelPass; 4] = [
    KernelPass {
        program: Program::Render,
        entry_point: "shore_faces_first",
        over: DispatchOver::ShoreFaces,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::Render,
        entry_point: "shore_update_first",
        over: DispatchOver::ShoreCells,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::Render,
        entry_point: "shore_faces_second",
        over: DispatchOver::ShoreFaces,
        when: KernelWhen::Always,
    },
    KernelPass {
        program: Program::Render,
        entry_point: "shore_update_second",
        over: DispatchOver::ShoreCells,
        when: KernelWhen::Always,
    },
];

/// Kernels of a frame's shore pass.
const SHORE_KERNELS: usize =
    SHORE_STEP.len() * precip_model::drawing::shore::SHORE_STEPS_PER_FRAME as usize;

/// `N` kernels of shore steps, one after the other.
const fn shore_steps<const N: usize>() -> [KernelPass; N] {
    let mut passes = [SHORE_STEP[0]; N];
    let mut k = 0;
    while k < N {
        passes[k] = SHORE_STEP[k % SHORE_STEP.len()];
        k += 1;
    }
    passes
}

/// The frame's shore: [`precip_model::drawing::shore::SHORE_STEPS_PER_FRAME`] steps
/// of the shallow-water equations over the shore's grid, while the scene has one.
pub const SHORE_PASSES: [KernelPass; SHORE_KERNELS] = shore_steps();

/// The clouds' shadow map: the share of the sun's light through every layer over
/// the land around the camera ([`render_bindings::CLOUD_SHADOW`]), while a layer is
/// drawn, before any draw.
pub const CLOUD_SHADOW_PASS: KernelPass = KernelPass {
    program: Program::Render,
    entry_point: "cloud_shadow_map",
    over: DispatchOver::CloudShadowTexels,
    when: KernelWhen::Always,
};

/// The cover texels into the three filtered textures the surfaces read
/// ([`render_bindings::COVER_A`], [`render_bindings::COVER_B`],
/// [`render_bindings::COVER_C`]): first in a frame.
pub const COVER_TEXTURE_PASS: KernelPass = KernelPass {
    program: Program::Render,
    entry_point: "cover_texture",
    over: DispatchOver::CoverTexels,
    when: KernelWhen::Always,
};

/// The albedo of the ground the drops refract, averaged around the camera over the
/// cover ([`render_bindings::DROP_GROUND`]): one workgroup, after
/// [`COVER_TEXTURE_PASS`], before any draw.
pub const DROP_GROUND_PASS: KernelPass = KernelPass {
    program: Program::Render,
    entry_point: "drop_ground",
    over: DispatchOver::OneWorkgroup,
    when: KernelWhen::Always,
};

/// The format of the cover textures (filterable everywhere, a storage format in
/// WebGPU and Vulkan).
pub const COVER_TEXTURE_FORMAT_NAME: &str = "Rgba16Float";

/// The splat of sub-pixel particles: after the scene's pass (it reads the scene's
/// depth) and the cull kernels, before the particles' pass, whose first draw
/// ([`render_passes::SPLAT_RESOLVE`]) blends the sums over the frame.
pub const SPLAT_PASS: KernelPass = KernelPass {
    program: Program::Render,
    entry_point: "splat_particles",
    over: DispatchOver::ParticleList,
    when: KernelWhen::Always,
};

/// Each snow sprite instance's quad, once a frame, after the cull and before the
/// particles' passes, whose corners read it (`snow_quads_write`,
/// render_particles.wgsl): over the list of drawn sprites' instances, walked as the
/// splat walks its own.
pub const SNOW_QUADS_PASS: KernelPass = KernelPass {
    program: Program::Render,
    entry_point: "snow_quads_write",
    over: DispatchOver::ParticleList,
    when: KernelWhen::Always,
};

/// Bytes of one snow quad (centre, two sides, stretch, colour and opacity; 56 of
/// them used, the struct's alignment pads it to 64). WGSL twin: `SnowQuad` in
/// `shaders/render_layout.wgsl`.
pub const SNOW_QUAD_BYTES: u64 = 64;

/// The most snow quads a frame keeps: the sprite instances beyond make their quads
/// in each corner's vertex shader instead (as they all did before the quads were
/// kept), so the buffer stays bounded at 10⁷ particles (64 MiB at most).
pub const SNOW_QUAD_CAPACITY: u64 = 1 << 20;

/// Bytes of the snow quads for `particle_count` particles: a quad for each sprite
/// instance a frame may draw (each particle × the most copies,
/// `precip_model::drawing::multiplicity::MAX_SNOW_COPIES`), up to
/// [`SNOW_QUAD_CAPACITY`]; at least one (the least a binding of them holds).
#[must_use]
pub fn snow_quad_bytes(particle_count: u32) -> u64 {
    let instances =
        u64::from(particle_count) * u64::from(precip_model::drawing::multiplicity::MAX_SNOW_COPIES);
    instances.clamp(1, SNOW_QUAD_CAPACITY) * SNOW_QUAD_BYTES
}

/// The passes of a frame as data, and their timed names
/// ([`crate::frame`]).
pub use crate::frame::{FRAME_PASSES, TIMED_RENDER_PASSES, cloud_passes};

/// Bytes of the cull kernels' per-workgroup counts (`vec4<u32>` each).
pub const GROUP_COUNT_BYTES: u64 = 16;

/// Bytes of the splat sums per pixel of the target (4 × u32: Σa·r, Σa·g, Σa·b, Σa).
pub const SPLAT_BYTES_PER_PIXEL: u64 = 16;

/// Bindings of [`Program::CullParticles`], group 0.
pub mod cull_bindings {
    /// `RenderParams`, read-only storage (see `render_bindings::PARAMS`).
    pub const PARAMS: u32 = 0;
    /// Particles, read-only storage.
    pub const PARTICLES: u32 = 1;
    /// Per-workgroup counts (sprites, streaks, splats, 0), then offsets:
    /// `array<vec4<u32>>`, one per cull workgroup.
    pub const GROUP_COUNTS: u32 = 2;
    /// The drawn lists: `array<u32>` of 3 × particle count (N): sprites from 0,
    /// streaks from N, splats from 2N ([`super::DRAWN_LIST_BYTES_PER_PARTICLE`]).
    pub const DRAWN: u32 = 3;
    /// The two indirect draws and the splat count, [`super::FrameDraws`].
    pub const DRAWS: u32 = 4;
    /// How each particle is drawn this frame, `array<u32>` of the particle count,
    /// written by `cull_count`: the class (`DRAWN_*`) in bits 0–7, the particle's
    /// rank among its workgroup's particles of that class from bit 8 (counted by
    /// the workgroup's first lane), so `cull_write` places it with no barrier.
    pub const DRAWN_KINDS: u32 = 5;
    /// The frame's snow quads (read-only storage, never read: `cull_scan` takes
    /// their capacity, `arrayLength`, to split the snow draw between the kept quads
    /// and the instances beyond).
    pub const SNOW_QUADS: u32 = 6;
}

/// Bytes of the drawn lists per particle: three `u32` lists (sprites, streaks,
/// splats), each as long as the particles.
pub const DRAWN_LIST_BYTES_PER_PARTICLE: u64 = 12;

/// Bindings of [`Program::Render`].
pub mod render_bindings {
    /// Group 0 (the frame; vertex, fragment and the splat kernel): `RenderParams`, a
    /// uniform block at a dynamic offset.
    pub const PARAMS: u32 = 0;
    /// Group 0: the same `RenderParams` block as read-only storage, read only by the
    /// branches that depend on nothing but the block (the displacement switch, the
    /// counts: culling on, splat width). Mesa's lavapipe up to 23.1 "inlines" the
    /// uniforms such a branch tests: it recompiles the shader at every draw and keeps
    /// every variant until the device is destroyed (1.8 MB a frame measured); storage
    /// is never inlined. Reading all of the block from storage instead cost lavapipe
    /// 3× in the scene pass (125 → 38 ms at 1280×720).
    pub const PARAMS_SWITCHES: u32 = 11;
    /// Group 0 of the `cover_texture` kernel only (its own group): cover texels,
    /// read-only storage.
    pub const COVER: u32 = 1;
    /// Group 0: ground heights, read-only storage.
    pub const GROUND_HEIGHT: u32 = 2;
    /// Group 0: particles, read-only storage.
    pub const PARTICLES: u32 = 3;
    /// Group 0: the drawn lists, read-only storage (see [`super::cull_bindings::DRAWN`]).
    pub const DRAWN: u32 = 4;
    /// Group 0: the cover's first texture (depth mm, SWE mm, peak SWE mm, wetness),
    /// `texture_2d<f32>`, [`super::COVER_TEXTURE_FORMAT_NAME`].
    pub const COVER_A: u32 = 5;
    /// Group 0: the second (accumulation mask, melt mask, age days, 0).
    pub const COVER_B: u32 = 6;
    /// Group 0: their sampler (linear, clamped to the edge).
    pub const COVER_SAMPLER: u32 = 7;
    /// Group 0 of the `cover_texture` kernel: [`COVER_A`] as a write-only storage
    /// texture.
    pub const COVER_A_OUT: u32 = 8;
    /// Group 0 of the `cover_texture` kernel: [`COVER_B`] as a write-only storage
    /// texture.
    pub const COVER_B_OUT: u32 = 9;
    /// Group 1 (light): the shadow map, `texture_depth_2d`.
    pub const SHADOW_MAP: u32 = 0;
    /// Group 1: its comparison sampler (less-equal, linear).
    pub const SHADOW_SAMPLER: u32 = 1;
    /// Group 1: the flake's opacity, `texture_2d<f32>` (R8).
    pub const FLAKE_OPACITY: u32 = 2;
    /// Group 1: its sampler (linear, clamped).
    pub const FLAKE_SAMPLER: u32 = 3;
    /// Group 2 (material): `Material { base_colour: vec4 }`, uniform.
    pub const MATERIAL: u32 = 0;
    /// Group 2: base-colour texture (sRGB).
    pub const BASE_COLOUR_TEXTURE: u32 = 1;
    /// Group 2: its sampler (linear, repeat).
    pub const MATERIAL_SAMPLER: u32 = 2;
    /// The shadow map's format.
    pub const SHADOW_FORMAT_NAME: &str = "Depth32Float";
    /// Group 2 of the splat kernel (its own group, numbered apart from the material's
    /// bindings): the camera's depth buffer, `texture_depth_2d`, read with
    /// `textureLoad`.
    pub const SPLAT_SCENE_DEPTH: u32 = 3;
    /// Group 2 of the splat kernel: the splat sums, `array<atomic<u32>>`, read-write
    /// storage of [`super::SPLAT_BYTES_PER_PIXEL`] per pixel of the target.
    pub const SPLAT_SUMS: u32 = 4;
    /// Group 2 of the resolve draw (fragment): the same sums as plain `array<u32>`
    /// (one fragment per pixel reads and zeroes its own: no atomics needed).
    pub const RESOLVED_SUMS: u32 = 5;
    /// Group 2 of the splat kernel: the frame's [`super::FrameDraws`] (the splat
    /// list's count), read-only storage.
    pub const SPLAT_DRAWS: u32 = 6;
    /// Group 2 of the reduced particles' draws (fragment): the camera's depth
    /// buffer, the binding [`SPLAT_SCENE_DEPTH`] of the splat kernel's group.
    pub const PARTICLE_SCENE_DEPTH: u32 = SPLAT_SCENE_DEPTH;
    /// Group 2 of the composite draw (fragment): the particles' image,
    /// `texture_2d<f32>` (`Rgba16Float`, premultiplied), read through
    /// [`COVER_SAMPLER`].
    pub const PARTICLE_IMAGE: u32 = 7;
    /// Group 2 of the snow sprites' draws (vertex; the reduced ones' with
    /// [`PARTICLE_SCENE_DEPTH`]): the frame's snow quads, `array<SnowQuad>`,
    /// read-only storage ([`super::SNOW_QUAD_BYTES`] each).
    pub const SNOW_QUADS: u32 = 9;
    /// Group 2 of the kernel that makes them (`snow_quads_write`, with
    /// [`SPLAT_DRAWS`] for their count): the same quads, read-write storage.
    pub const SNOW_QUADS_OUT: u32 = 10;
    /// Group 3 of the scene's draw: the frame before as its scene pass left it
    /// (`scene_copy` pass), `texture_2d<f32>`, read with `textureLoad` by the water's
    /// reflections.
    pub const SCENE_COPY: u32 = 0;
    /// Group 3 of the scene's draw: the frame before's depth, `texture_depth_2d`.
    pub const DEPTH_COPY: u32 = 1;
    /// Group 3 of the scene's draw: the water bodies' mirror image, `texture_2d<f32>`
    /// (`Rgba16Float`, alpha 0 where the sky shows), read through
    /// [`COVER_SAMPLER`].
    pub const MIRROR_IMAGE: u32 = 2;
    /// Group 0: the water bodies' waves (`array<i32>`, as
    /// [`super::step_bindings::WAVES`]), read-only storage.
    pub const WAVES: u32 = 12;
    /// Group 0: the cover's third texture (sand and dust settled, kg/m²; 0, 0, 0).
    pub const COVER_C: u32 = 13;
    /// Group 0 of the `cover_texture` kernel: [`COVER_C`] as a write-only storage
    /// texture.
    pub const COVER_C_OUT: u32 = 14;
    /// Group 0: the albedo of the ground the drops refract
    /// ([`precip_model::drawing::drop_ground_albedo`]), one `f32` the `drop_ground`
    /// kernel writes each frame, read-only storage.
    pub const DROP_GROUND: u32 = 15;
    /// Group 0 of the `cover_texture` and `drop_ground` kernels: [`DROP_GROUND`],
    /// read-write.
    pub const DROP_GROUND_OUT: u32 = 16;
    /// Group 0: the clouds' coverage map
    /// ([`precip_model::drawing::clouds::cloud_coverage_map`]), `texture_2d<f32>`
    /// (`R8Unorm`).
    pub const CLOUD_MAP: u32 = 17;
    /// Group 0: its sampler (linear, repeating: the map tiles).
    pub const CLOUD_SAMPLER: u32 = 18;
    /// Group 0: the clouds' detail, the slices of a tiling 3D noise side by side
    /// ([`precip_model::drawing::clouds::cloud_detail_atlas_texels`]),
    /// `texture_2d<f32>` (`Rgba8Unorm`), read through [`CLOUD_SAMPLER`].
    pub const CLOUD_DETAIL: u32 = 21;
    /// Group 0: the clouds' shadow map
    /// ([`precip_model::drawing::clouds::cloud_shadow_map`]), `texture_2d<f32>`
    /// (`Rgba16Float`, the share in `r`), read through [`COVER_SAMPLER`].
    pub const CLOUD_SHADOW: u32 = 19;
    /// Group 0 of the `cloud_shadow_map` kernel: [`CLOUD_SHADOW`] as a write-only
    /// storage texture.
    pub const CLOUD_SHADOW_OUT: u32 = 20;
    /// The sea's displacement atlas (λ·Dx, h, λ·Dz) m, as the sea's draw reads it.
    pub const OCEAN_DISPLACEMENT: u32 = 22;
    /// The sea's slope atlas (∂h/∂x, ∂h/∂z, the Jacobian).
    pub const OCEAN_SLOPE: u32 = 23;
    /// The sea's spectra the ocean kernels transform in place.
    pub const OCEAN_SPECTRA: u32 = 24;
    /// The displacement atlas as `ocean_resolve` writes it.
    pub const OCEAN_DISPLACEMENT_OUT: u32 = 25;
    /// The slope atlas as `ocean_resolve` writes it.
    pub const OCEAN_SLOPE_OUT: u32 = 26;
    /// The water's depth under the sea's level over the ground grid.
    pub const SEA_DEPTH: u32 = 27;
    /// The shore's buffer (`precip_model::drawing::shore::ShoreGrid::initial_buffer`:
    /// a header, two states, faces, sources; `array<vec4<f32>>`) as the sea's draw
    /// reads it, read-only storage (vertex and fragment stages).
    pub const SHORE: u32 = 28;
    /// The same buffer as the shore's kernels step it, read-write storage.
    pub const SHORE_CELLS: u32 = 29;
    /// Group 1 of the sky's draw (its own group, numbered apart from the light's
    /// bindings): the clouds' image, `texture_2d<f32>` (`Rgba16Float`: their light,
    /// premultiplied, and opacity), read through [`COVER_SAMPLER`].
    pub const CLOUD_IMAGE: u32 = 4;
    /// Group 2 of the clouds' passes (numbered apart from the material's and the
    /// splat's bindings): the clouds' fresh image, `texture_2d<f32>`
    /// (`Rgba16Float`), read with `textureLoad`.
    pub const CLOUD_FRESH: u32 = 8;
}

/// One input of the `probe_drawing` test kernel (64 bytes). WGSL: `ProbeDrawing`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct ProbeDrawing {
    /// Particle centre, m.
    pub centre_m: [f32; 3],
    /// Sprite side, m.
    pub side_m: f32,
    /// Camera, m.
    pub camera_m: [f32; 3],
    /// Sprite spin, rad.
    pub spin_rad: f32,
    /// Drop velocity, m/s.
    pub velocity_mps: [f32; 3],
    /// Sprite tumble.
    pub tumble: f32,
    /// Tetrahedron height, m.
    pub h_m: f32,
    /// Tetrahedron base side, m.
    pub a_m: f32,
    /// The cover probe's snow density, kg/m³, and depletion exponent (with `h_m` as
    /// the depth, `a_m` as the roughness length, `tumble` as the mask and the
    /// centre's x, z as the place: `precip_cover::shading`).
    pub cover: [f32; 2],
}
const _: () = assert!(size_of::<ProbeDrawing>() == 64);

/// Bindings of [`Program::QueryBeams`], group 0 (`shaders/lidar.wgsl`).
pub mod beam_bindings {
    /// [`precip_model::sensors::lidar::BeamParams`].
    pub const PARAMS: u32 = 0;
    /// [`super::Frames`].
    pub const FRAMES: u32 = 1;
    /// The ground map's words ([`precip_model::GroundMap::gpu_words`]).
    pub const GROUND_HEIGHT: u32 = 2;
    /// The particles, read only.
    pub const PARTICLES: u32 = 3;
    /// The beams ([`precip_model::sensors::lidar::Beam`]).
    pub const BEAMS: u32 = 4;
    /// One [`precip_model::sensors::lidar::BeamHit`] per beam, written.
    pub const HITS: u32 = 5;
}

/// Bindings of [`Program::OpticsSums`], group 0 (`shaders/optics_sums.wgsl`).
pub mod optics_bindings {
    /// [`super::OpticsParams`], uniform.
    pub const PARAMS: u32 = 0;
    /// The particles, read only.
    pub const PARTICLES: u32 = 1;
    /// One `precip_model::sensors::optics::OpticsPartial` per workgroup, written.
    pub const PARTIALS: u32 = 2;
}

/// The `optics_sums` kernel's block.
///
/// WGSL twin: `OpticsParams` in `shaders/optics_sums.wgsl` (16 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct OpticsParams {
    /// Particles.
    pub particle_count: u32,
    /// Unused.
    pub reserved0: u32,
    /// Unused.
    pub reserved1: u32,
    /// Unused.
    pub reserved2: u32,
}
const _: () = assert!(size_of::<OpticsParams>() == 16);

/// The on-demand query of `Backend::optics`: the camera volume's cross-sections
/// summed per workgroup (one `OpticsPartial` each), over every particle.
pub const OPTICS_PASS: KernelPass = KernelPass {
    program: Program::OpticsSums,
    entry_point: "optics_sums",
    over: DispatchOver::Particles,
    when: KernelWhen::Always,
};

/// Bindings of [`Program::StepParticles`], group 0.
pub mod step_bindings {
    /// `StepParams`, uniform, dynamic offset.
    pub const STEP_PARAMS: u32 = 0;
    /// `Frames`, uniform.
    pub const FRAMES: u32 = 1;
    /// `WindParams`, uniform.
    pub const WIND: u32 = 2;
    /// The wind volume, `texture_3d<f32>` (`Rgba32Float`, read with `textureLoad`).
    pub const WIND_VOLUME: u32 = 3;
    /// Ground heights, `array<f32>`, read-only storage.
    pub const GROUND_HEIGHT: u32 = 4;
    /// Particles, `array<Particle>`, read-write storage.
    pub const PARTICLES: u32 = 5;
    /// Deposits, `array<atomic<u32>>`, read-write storage.
    pub const DEPOSITS: u32 = 6;
    /// The pending births (a count, then `array<u32>` of particle indices:
    /// [`super::pending_births_bytes`]), read-write storage.
    pub const PENDING_BIRTHS: u32 = 7;
    /// The water bodies' waves: `array<atomic<i32>>`,
    /// [`precip_model::physics::water_waves::WAVE_WORDS_PER_CELL`] a cell, read-write storage.
    pub const WAVES: u32 = 8;
    /// The cover texels as words (`array<f32>`, [`precip_model::physics::drifting_snow`]'s word
    /// offsets), read-only storage: where snow is blowing, for drifting snow's births.
    pub const COVER: u32 = 9;
}

/// Bindings of [`Program::CoverUpdate`], group 0.
pub mod cover_bindings {
    /// `CoverStepParams`, uniform, dynamic offset.
    pub const COVER_PARAMS: u32 = 0;
    /// Cover texels, read-write storage.
    pub const COVER: u32 = 1;
    /// Deposits, read-write storage.
    pub const DEPOSITS: u32 = 2;
    /// The cover tiles ([`super::cover_tiles_bytes`]), read-write storage.
    pub const COVER_TILES: u32 = 3;
    /// The flow's and the drift's indirect dispatches
    /// ([`super::COVER_TILE_DISPATCH_BYTES_PER_SET`]), read-write storage: in the
    /// listings' group only ([`crate::bind_groups::COVER_LISTING`]), as a buffer
    /// may not be written in the dispatch that reads it as its workgroups.
    pub const COVER_TILE_DISPATCH: u32 = 4;
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_flow_takes_a_tile_a_workgroup_on_a_gpu_and_eight_on_a_cpu() {
        use super::{
            CoverTileSet, DispatchCounts, DispatchOver, GridFrame, WORKGROUP_SIZE,
            cover_tiles_bytes,
        };
        let cover = GridFrame::centred(
            glam::Vec2::ZERO,
            glam::Vec2::splat(100.0),
            glam::UVec2::new(321, 160),
        );
        let waves = cover;
        // 41 x 20 tiles, the last column partial.
        let gpu = DispatchCounts::of(1, &cover, &waves, false);
        let cpu = DispatchCounts::of(1, &cover, &waves, true);
        assert_eq!(gpu.cover_tiles, 820);
        let groups =
            |c| DispatchOver::ListedCoverTiles(CoverTileSet::Water).invocations(c) / WORKGROUP_SIZE;
        assert_eq!(groups(gpu), 820);
        assert_eq!(groups(cpu), 103);
        assert_eq!(cover_tiles_bytes(&cover), 4 * 2 * (1 + 3 * 820));
    }

    #[test]
    fn the_flow_and_the_drift_take_their_workgroups_from_their_listing() {
        use super::{
            COVER_TILE_DISPATCH_BYTES_PER_SET, COVER_TILE_SETS, CoverTileSet, DispatchOver,
            cover_tile_dispatch_words,
        };
        let water = DispatchOver::ListedCoverTiles(CoverTileSet::Water).indirect_offset();
        let snow = DispatchOver::ListedCoverTiles(CoverTileSet::Snow).indirect_offset();
        assert_eq!(water, Some(0));
        assert_eq!(snow, Some(COVER_TILE_DISPATCH_BYTES_PER_SET));
        assert_eq!(DispatchOver::CoverTexels.indirect_offset(), None);
        // Every flow and drift kernel is dispatched by its listing, no other.
        for pass in SUBSTEP_PASSES {
            let listed = [
                "water_outflow",
                "water_inflow",
                "snow_outflow",
                "snow_inflow",
            ];
            assert_eq!(
                pass.over.indirect_offset().is_some(),
                listed.contains(&pass.entry_point),
                "{}",
                pass.entry_point
            );
        }
        // Nothing to dispatch before a listing; the tiles a workgroup takes last.
        let words = cover_tile_dispatch_words(8);
        assert_eq!(words, [0, 1, 1, 8, 0, 1, 1, 8]);
        assert_eq!(
            4 * words.len() as u64,
            COVER_TILE_SETS * COVER_TILE_DISPATCH_BYTES_PER_SET
        );
        assert_eq!(cover_tile_dispatch_words(0)[3], 1);
    }

    #[test]
    fn every_kernel_and_pass_serves_one_feature_and_the_shares_add_up() {
        let names = SUBSTEP_PASSES
            .iter()
            .map(|k| k.entry_point)
            .chain(FRAME_PASSES.iter().map(|p| p.name));
        for name in names {
            let owners = FEATURES.iter().filter(|(_, n)| n.contains(&name)).count();
            assert_eq!(owners, 1, "{name} serves {owners} features");
        }
        let shares = feature_shares(&[
            ("step_particles", 30.0),
            ("scene", 50.0),
            ("snow_outflow", 5.0),
            ("water_inflow", 0.0),
            ("mystery", 15.0),
        ]);
        let names: Vec<_> = shares.iter().map(|s| s.0).collect();
        assert_eq!(names, ["particles", "drift", "scene", "other"]);
        let total: f64 = shares.iter().map(|s| s.2).sum();
        assert!((total - 1.0).abs() < 1e-12);
        assert!((shares[2].2 - 0.5).abs() < 1e-12);
    }

    use super::*;

    #[test]
    fn the_snow_quads_hold_each_particle_s_copies_up_to_their_capacity() {
        let copies = u64::from(precip_model::drawing::multiplicity::MAX_SNOW_COPIES);
        assert_eq!(snow_quad_bytes(1_000), 1_000 * copies * SNOW_QUAD_BYTES);
        assert_eq!(
            snow_quad_bytes(10_000_000),
            SNOW_QUAD_CAPACITY * SNOW_QUAD_BYTES
        );
        assert_eq!(snow_quad_bytes(0), SNOW_QUAD_BYTES);
        // Made after the cull (they read its lists and counts), read by the
        // particles' passes.
        let at = |name: &str| FRAME_PASSES.iter().position(|p| p.name == name);
        let quads = at("snow_quads").expect("a pass");
        assert!(at("cull_particles").is_some_and(|c| c < quads));
        for drawn in ["particles", "particles_reduced"] {
            assert!(at(drawn).is_some_and(|p| p > quads), "{drawn}");
        }
    }

    #[test]
    fn the_step_moves_the_particle_once_each_way() {
        assert_eq!(step_bytes_per_particle(), 128);
        for k in KERNEL_BYTES {
            assert!(
                SUBSTEP_PASSES
                    .iter()
                    .chain(&CULL_PASSES)
                    .chain([&SPLAT_PASS, &SNOW_QUADS_PASS])
                    .any(|p| p.entry_point == k.entry_point)
                    || [render_passes::SNOW.0, render_passes::RAIN.0].contains(&k.entry_point),
                "{k:?} names no kernel or draw of the frame"
            );
        }
    }

    #[test]
    fn every_kernel_of_the_recipe_is_an_entry_point_of_its_program() {
        for kernel in SUBSTEP_PASSES.iter().chain([&INIT_PASS]) {
            assert!(
                kernel.program.entry_points().contains(&kernel.entry_point),
                "{kernel:?}"
            );
        }
        let in_recipe = |name: &str| {
            SUBSTEP_PASSES
                .iter()
                .chain([&INIT_PASS])
                .any(|k| k.entry_point == name)
        };
        for kernel in CULL_PASSES {
            assert!(kernel.program.entry_points().contains(&kernel.entry_point));
        }
        for kernel in [SPLAT_PASS, COVER_TEXTURE_PASS] {
            assert!(kernel.program.entry_points().contains(&kernel.entry_point));
        }
        for (vs, fs) in [
            render_passes::SHADOW,
            render_passes::SCENE,
            render_passes::SNOW,
            render_passes::SNOW_MADE,
            render_passes::SNOW_REDUCED,
            render_passes::SNOW_MADE_REDUCED,
            render_passes::RAIN,
            render_passes::SPLAT_RESOLVE,
        ] {
            assert!(Program::Render.entry_points().contains(&vs));
            assert!(fs.is_none_or(|f| Program::Render.entry_points().contains(&f)));
        }
        for program in [Program::StepParticles, Program::CoverUpdate] {
            for name in program.entry_points() {
                assert!(in_recipe(name), "{name} of {program:?} is never dispatched");
            }
        }
    }
}
