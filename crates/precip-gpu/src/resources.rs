//! The resources table of the simulation: every buffer a configuration allocates,
//! its size rule, usage and initial contents ([`simulation_buffers`]), the wind
//! volume, and which resource fills each binding of the simulation's bind groups
//! ([`STEP_GROUP`], [`COVER_GROUP`], [`COVER_LISTING_GROUP`], [`BEAM_GROUP`]). The executor
//! ([`crate::executor`]) creates and binds them from these tables on every backend;
//! a backend only says how a buffer or a binding is made on its device.

use precip_cover::{CoverGrid, CoverStepParams, DepositBuffer};
use precip_model::backend::MAX_SUBSTEPS;
use precip_model::host::HostState;
use precip_model::particles::step::StepParams;
use precip_model::physics::water_waves::initial_waves;
use precip_model::{GroundMap, Particle};

use crate::bind_groups::{BEAMS, COVER_LISTING, COVER_UPDATE, GroupLayout, OPTICS, STEP};
use crate::recipe::{beam_bindings as bb, cover_bindings as cv, pending_births_bytes};
use crate::recipe::{cover_tile_dispatch_words, cover_tiles_bytes};
use crate::recipe::{optics_bindings as ob, step_bindings as sb};

/// A buffer of a configuration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SimBuffer {
    /// `array<Particle>`, filled by `init_particles`.
    Particles,
    /// `array<CoverTexel>`, from the setup's initial cover.
    Cover,
    /// Landed water, [`precip_cover::DEPOSIT_CHANNELS`] words per cover texel, zeroed.
    Deposits,
    /// The particles to re-birth this sub-step ([`pending_births_bytes`]).
    PendingBirths,
    /// Ground heights ([`GroundMap::gpu_words`]), then the terrain's windows
    /// (`precip_model::scene::terrain::TerrainPyramid::window`, a copy per frame
    /// slot) if the scene stands on one.
    Ground,
    /// The water bodies' waves ([`initial_waves`]).
    Waves,
    /// [`precip_model::host::Frames`].
    Frames,
    /// [`precip_model::wind::WindParams`].
    WindParams,
    /// One [`StepParams`] per sub-step at the uniform stride, a ring of them per slot.
    StepBlocks,
    /// One [`CoverStepParams`] per sub-step, as [`SimBuffer::StepBlocks`].
    CoverBlocks,
    /// The cover tiles the flow and the drift run over ([`cover_tiles_bytes`]),
    /// zeroed.
    CoverTiles,
    /// The flow's and the drift's indirect dispatches, written by their listings
    /// ([`cover_tile_dispatch_words`]).
    CoverTileDispatch,
}

impl SimBuffer {
    /// Every buffer, in the order they are made.
    pub const ALL: [Self; 12] = [
        Self::Particles,
        Self::Cover,
        Self::Deposits,
        Self::PendingBirths,
        Self::Ground,
        Self::Waves,
        Self::Frames,
        Self::WindParams,
        Self::StepBlocks,
        Self::CoverBlocks,
        Self::CoverTiles,
        Self::CoverTileDispatch,
    ];

    /// A label for debuggers.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            Self::Particles => "precip particles",
            Self::Cover => "precip cover",
            Self::Deposits => "precip deposits",
            Self::PendingBirths => "precip pending births",
            Self::Ground => "precip ground heights",
            Self::Waves => "precip waves",
            Self::Frames => "precip frames",
            Self::WindParams => "precip wind params",
            Self::StepBlocks => "precip step params",
            Self::CoverBlocks => "precip cover params",
            Self::CoverTiles => "precip cover tiles",
            Self::CoverTileDispatch => "precip cover tile dispatch",
        }
    }
}

/// How a buffer is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BufferUsage {
    /// Read and written by kernels and draws, filled and read back by copies: kept
    /// in device memory.
    Storage,
    /// Uniform blocks the host writes between submissions: kept where the host can
    /// write them.
    Uniform,
    /// Blocks the host writes each frame, read as uniform blocks and as storage
    /// (the frame's `RenderParams`).
    FrameBlocks,
    /// Storage also read as indirect draw arguments (and copied back).
    Indirect,
    /// The scene's vertices, filled once.
    Vertices,
    /// The scene's `u32` indices, filled once.
    Indices,
}

/// What a new buffer holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Contents {
    /// These bytes (as long as the buffer).
    Bytes(Vec<u8>),
    /// Zeros.
    Zeroed,
    /// Whatever: a kernel or the host writes it before anything reads it.
    Undefined,
}

/// One row of the table: a buffer with its size, usage and contents.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BufferSpec {
    /// Which.
    pub buffer: SimBuffer,
    /// Bytes.
    pub bytes: u64,
    /// Usage.
    pub usage: BufferUsage,
    /// Initial contents.
    pub contents: Contents,
}

/// Bytes between two sub-steps' uniform blocks: the larger block rounded up to the
/// device's dynamic-offset alignment.
#[must_use]
pub fn uniform_stride(alignment: u64) -> u64 {
    let block = size_of::<StepParams>().max(size_of::<CoverStepParams>()) as u64;
    let alignment = alignment.max(16);
    block.div_ceil(alignment) * alignment
}

/// The buffers of a configuration of `host`'s setup with its initial `cover`, uniform
/// blocks at `stride` bytes, in `slots` rings (submissions in flight at once), the
/// flow and the drift taking `tiles_per_workgroup` cover tiles a workgroup
/// ([`crate::recipe::DispatchCounts::cover_tiles_per_workgroup`]).
#[must_use]
pub fn simulation_buffers(
    host: &HostState,
    cover: &CoverGrid,
    stride: u64,
    slots: u32,
    tiles_per_workgroup: u32,
) -> Vec<BufferSpec> {
    let setup = host.setup();
    let (world, camera) = setup.particle_counts();
    let particle_count = world + camera;
    let frames = host.frames();
    let ground: &GroundMap = &setup.ground;
    let blocks = stride * u64::from(MAX_SUBSTEPS) * u64::from(slots.max(1));
    SimBuffer::ALL
        .iter()
        .map(|&buffer| {
            let bytes = |b: Vec<u8>| (b.len() as u64, BufferUsage::Storage, Contents::Bytes(b));
            let (size, usage, contents) = match buffer {
                SimBuffer::Particles => (
                    u64::from(particle_count) * size_of::<Particle>() as u64,
                    BufferUsage::Storage,
                    Contents::Undefined,
                ),
                SimBuffer::Cover => bytes(bytemuck::cast_slice(&cover.texels).to_vec()),
                SimBuffer::Deposits => (
                    DepositBuffer::bytes_for(cover.texels.len()) as u64,
                    BufferUsage::Storage,
                    Contents::Zeroed,
                ),
                SimBuffer::PendingBirths => (
                    pending_births_bytes(particle_count),
                    BufferUsage::Storage,
                    Contents::Undefined,
                ),
                SimBuffer::Ground => {
                    // The ground map's words, then the terrain's windows (the
                    // clipmap's, render_terrain.wgsl: written by each frame,
                    // Simulation::upload_terrain_windows) and its land cover, then
                    // the far cover's two regions (render_scene.wgsl's far_row).
                    let mut words = ground.gpu_words();
                    if host.terrain_pyramid().is_some() {
                        words.resize(words.len() + host.terrain_window_words() as usize, 0.0);
                        if let Some(classes) = host.land_cover_samples() {
                            words.extend_from_slice(classes);
                        }
                    }
                    debug_assert_eq!(words.len() as u32, host.far_cover_first_word());
                    words.extend(host.far_cover().initial_words());
                    bytes(bytemuck::cast_slice(&words).to_vec())
                }
                SimBuffer::Waves => {
                    bytes(bytemuck::cast_slice(&initial_waves(&frames.waves, ground)).to_vec())
                }
                SimBuffer::Frames => (
                    size_of_val(&frames) as u64,
                    BufferUsage::Uniform,
                    Contents::Bytes(bytemuck::bytes_of(&frames).to_vec()),
                ),
                SimBuffer::WindParams => {
                    let params = host.wind_params();
                    (
                        size_of_val(&params) as u64,
                        BufferUsage::Uniform,
                        Contents::Bytes(bytemuck::bytes_of(&params).to_vec()),
                    )
                }
                SimBuffer::StepBlocks | SimBuffer::CoverBlocks => {
                    (blocks, BufferUsage::Uniform, Contents::Undefined)
                }
                SimBuffer::CoverTiles => (
                    cover_tiles_bytes(&cover.frame),
                    BufferUsage::Storage,
                    Contents::Zeroed,
                ),
                SimBuffer::CoverTileDispatch => {
                    let words = cover_tile_dispatch_words(tiles_per_workgroup);
                    (
                        4 * words.len() as u64,
                        BufferUsage::Indirect,
                        Contents::Bytes(bytemuck::cast_slice(&words).to_vec()),
                    )
                }
            };
            BufferSpec {
                buffer,
                bytes: size.max(4),
                usage,
                contents,
            }
        })
        .collect()
}

/// What fills a binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// A buffer of the configuration.
    Buffer(SimBuffer),
    /// The wind volume (3D `Rgba32Float`).
    WindVolume,
    /// A beam query's [`precip_model::sensors::lidar::BeamParams`].
    BeamParams,
    /// A beam query's beams.
    Beams,
    /// A beam query's hits.
    BeamHits,
    /// An optics query's [`crate::recipe::OpticsParams`].
    OpticsParams,
    /// An optics query's per-workgroup partials.
    OpticsPartials,
}

/// A bind group as data: its layout's table and what fills each binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GroupFill {
    /// The layout.
    pub layout: &'static GroupLayout,
    /// Binding number and what fills it, one per binding of the layout.
    pub bound: &'static [(u32, Bound)],
}

/// Group 0 of the particle kernels.
pub const STEP_GROUP: GroupFill = GroupFill {
    layout: &STEP,
    bound: &[
        (sb::STEP_PARAMS, Bound::Buffer(SimBuffer::StepBlocks)),
        (sb::FRAMES, Bound::Buffer(SimBuffer::Frames)),
        (sb::WIND, Bound::Buffer(SimBuffer::WindParams)),
        (sb::WIND_VOLUME, Bound::WindVolume),
        (sb::GROUND_HEIGHT, Bound::Buffer(SimBuffer::Ground)),
        (sb::PARTICLES, Bound::Buffer(SimBuffer::Particles)),
        (sb::DEPOSITS, Bound::Buffer(SimBuffer::Deposits)),
        (sb::PENDING_BIRTHS, Bound::Buffer(SimBuffer::PendingBirths)),
        (sb::WAVES, Bound::Buffer(SimBuffer::Waves)),
        (sb::COVER, Bound::Buffer(SimBuffer::Cover)),
    ],
};

/// What fills the cover kernels' bindings, the listings' last
/// ([`COVER_LISTING_GROUP`]).
const COVER_BOUND: &[(u32, Bound); 5] = &[
    (cv::COVER_PARAMS, Bound::Buffer(SimBuffer::CoverBlocks)),
    (cv::COVER, Bound::Buffer(SimBuffer::Cover)),
    (cv::DEPOSITS, Bound::Buffer(SimBuffer::Deposits)),
    (cv::COVER_TILES, Bound::Buffer(SimBuffer::CoverTiles)),
    (
        cv::COVER_TILE_DISPATCH,
        Bound::Buffer(SimBuffer::CoverTileDispatch),
    ),
];

/// Group 0 of the cover kernels.
pub const COVER_GROUP: GroupFill = GroupFill {
    layout: &COVER_UPDATE,
    bound: COVER_BOUND.split_at(4).0,
};

/// Group 0 of the cover tiles' listings (`water_tiles_list`, `snow_tiles_list`):
/// the cover kernels' bindings and the indirect dispatches they write for the
/// iterations after them.
pub const COVER_LISTING_GROUP: GroupFill = GroupFill {
    layout: &COVER_LISTING,
    bound: COVER_BOUND,
};

/// Group 0 of the `query_beams` kernel.
pub const BEAM_GROUP: GroupFill = GroupFill {
    layout: &BEAMS,
    bound: &[
        (bb::PARAMS, Bound::BeamParams),
        (bb::FRAMES, Bound::Buffer(SimBuffer::Frames)),
        (bb::GROUND_HEIGHT, Bound::Buffer(SimBuffer::Ground)),
        (bb::PARTICLES, Bound::Buffer(SimBuffer::Particles)),
        (bb::BEAMS, Bound::Beams),
        (bb::HITS, Bound::BeamHits),
    ],
};

/// Group 0 of the `optics_sums` kernel.
pub const OPTICS_GROUP: GroupFill = GroupFill {
    layout: &OPTICS,
    bound: &[
        (ob::PARAMS, Bound::OpticsParams),
        (ob::PARTICLES, Bound::Buffer(SimBuffer::Particles)),
        (ob::PARTIALS, Bound::OpticsPartials),
    ],
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_binding_of_each_group_is_filled_once() {
        for fill in [
            STEP_GROUP,
            COVER_GROUP,
            COVER_LISTING_GROUP,
            BEAM_GROUP,
            OPTICS_GROUP,
        ] {
            assert_eq!(
                fill.bound.len(),
                fill.layout.bindings.len(),
                "{}",
                fill.layout.name
            );
            for b in fill.layout.bindings {
                let n = fill.bound.iter().filter(|(k, _)| *k == b.binding).count();
                assert_eq!(n, 1, "{} binding {}", fill.layout.name, b.binding);
            }
        }
    }

    #[test]
    fn the_table_sizes_every_buffer_from_the_configuration() {
        let setup = precip_model::Setup::over_flat_ground(20.0, 8, 10.0, 300);
        let host = HostState::configure(&setup).expect("a valid setup");
        let cover = setup.initial_cover().expect("a cover");
        let specs = simulation_buffers(&host, &cover, uniform_stride(256), 2, 8);
        assert_eq!(specs.len(), SimBuffer::ALL.len());
        let bytes = |b: SimBuffer| specs.iter().find(|s| s.buffer == b).map(|s| s.bytes);
        assert_eq!(bytes(SimBuffer::Particles), Some(300 * 64));
        // A block a sub-step at the device's alignment, two rings.
        let stride = uniform_stride(256);
        assert!(stride >= size_of::<StepParams>() as u64 && stride.is_multiple_of(256));
        assert_eq!(
            bytes(SimBuffer::StepBlocks),
            Some(stride * u64::from(MAX_SUBSTEPS) * 2)
        );
        for s in &specs {
            if let Contents::Bytes(b) = &s.contents {
                assert_eq!(b.len() as u64, s.bytes, "{:?}", s.buffer);
            }
        }
    }
}
