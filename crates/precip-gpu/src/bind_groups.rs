//! Every bind group of the GPU programs as data, and the groups each entry point is
//! used with: both GPU backends build their bind group layouts (wgpu) and descriptor
//! set layouts (Vulkan) from these tables and nothing else, and a test checks them
//! against naga's reflection of the WGSL (`tests/shaders.rs`: every resource an entry
//! point uses is in its table with the same kind).
//!
//! Binding numbers are the `*_bindings` constants of [`crate::recipe`].

use precip_cover::CoverStepParams;

use crate::recipe::{Frames, cover_bindings as cv, cull_bindings as cb, render_bindings as rb};
use crate::recipe::{OpticsParams, optics_bindings as ob};
use crate::recipe::{beam_bindings as bb, render_passes, step_bindings as sb};
use crate::shaders::Program;
use precip_model::drawing::render::RenderParams;
use precip_model::particles::step::StepParams;
use precip_model::sensors::lidar::BeamParams;
use precip_wind::WindParams;

/// The stages a binding is visible to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stages {
    /// Compute kernels only.
    Compute,
    /// Vertex and fragment shaders.
    Draw,
    /// Fragment shaders only.
    Fragment,
    /// Vertex, fragment and compute (the frame's groups: the draws and the splat).
    DrawAndCompute,
}

/// How a texture is sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureSample {
    /// Float texels; filterable or not.
    Float {
        /// Through a filtering sampler.
        filterable: bool,
    },
    /// A depth texture.
    Depth,
}

/// What a binding is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BindingKind {
    /// A uniform block at least `min_bytes` long (0: any).
    Uniform {
        /// Smallest size, bytes.
        min_bytes: u64,
        /// Bound with a dynamic offset.
        dynamic: bool,
    },
    /// A storage buffer.
    Storage {
        /// Read-only.
        read_only: bool,
        /// Smallest size, bytes (0: any).
        min_bytes: u64,
        /// Bound with a dynamic offset.
        dynamic: bool,
    },
    /// A sampled texture.
    Texture {
        /// Its texels.
        sample: TextureSample,
        /// 3D (else 2D).
        volume: bool,
    },
    /// A write-only storage texture of RGBA16F texels (2D).
    StorageTextureRgba16Float,
    /// A sampler.
    Sampler {
        /// A comparison sampler (else filtering).
        comparison: bool,
    },
}

impl BindingKind {
    /// The bytes a buffer bound here sees from its offset: the block, for a uniform
    /// or a binding with a dynamic offset (which moves it through a ring of blocks);
    /// `None` (the whole buffer) for other storage.
    #[must_use]
    pub const fn block_bytes(self) -> Option<u64> {
        match self {
            Self::Uniform { min_bytes, .. }
            | Self::Storage {
                min_bytes,
                dynamic: true,
                ..
            } if min_bytes > 0 => Some(min_bytes),
            _ => None,
        }
    }
}

/// One binding of a group.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Binding {
    /// Its number.
    pub binding: u32,
    /// Its kind.
    pub kind: BindingKind,
    /// Where it is seen.
    pub stages: Stages,
}

/// A bind group's layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GroupLayout {
    /// A label for debuggers.
    pub name: &'static str,
    /// Its bindings.
    pub bindings: &'static [Binding],
}

impl GroupLayout {
    /// The kind of binding `binding`, if the group has it.
    #[must_use]
    pub fn kind_of(&self, binding: u32) -> Option<BindingKind> {
        self.bindings
            .iter()
            .find(|b| b.binding == binding)
            .map(|b| b.kind)
    }

    /// How many bindings take a dynamic offset (each the frame's `RenderParams`
    /// block, or a sub-step's uniform block).
    #[must_use]
    pub fn dynamic_bindings(&self) -> usize {
        self.bindings
            .iter()
            .filter(|b| {
                matches!(
                    b.kind,
                    BindingKind::Uniform { dynamic: true, .. }
                        | BindingKind::Storage { dynamic: true, .. }
                )
            })
            .count()
    }

    /// Whether a binding takes a dynamic offset.
    #[must_use]
    pub fn has_dynamic_binding(&self) -> bool {
        self.dynamic_bindings() > 0
    }
}

/// The value paired with `group`'s table in `pairs` (tables match by name): how a
/// backend maps a table to its layout or bind group.
#[must_use]
pub fn lookup<T, const N: usize>(group: &GroupLayout, pairs: [(&GroupLayout, T); N]) -> Option<T> {
    pairs
        .into_iter()
        .find(|(table, _)| table.name == group.name)
        .map(|(_, value)| value)
}

const fn binding(binding: u32, kind: BindingKind, stages: Stages) -> Binding {
    Binding {
        binding,
        kind,
        stages,
    }
}

const fn uniform(min_bytes: usize, dynamic: bool) -> BindingKind {
    BindingKind::Uniform {
        min_bytes: min_bytes as u64,
        dynamic,
    }
}

const fn storage(read_only: bool) -> BindingKind {
    BindingKind::Storage {
        read_only,
        min_bytes: 0,
        dynamic: false,
    }
}

/// `RenderParams` as read-only storage (the cull's block, the frame's switches: see
/// `render_bindings::PARAMS_SWITCHES`), one block per frame in flight at a dynamic
/// offset.
const RENDER_PARAMS: BindingKind = BindingKind::Storage {
    read_only: true,
    min_bytes: size_of::<RenderParams>() as u64,
    dynamic: true,
};

const FILTERED_2D: BindingKind = BindingKind::Texture {
    sample: TextureSample::Float { filterable: true },
    volume: false,
};

const DEPTH_2D: BindingKind = BindingKind::Texture {
    sample: TextureSample::Depth,
    volume: false,
};

const FILTERING: BindingKind = BindingKind::Sampler { comparison: false };

/// Group 0 of `StepParticles`.
pub const STEP: GroupLayout = GroupLayout {
    name: "precip step_particles",
    bindings: &[
        binding(
            sb::STEP_PARAMS,
            uniform(size_of::<StepParams>(), true),
            Stages::Compute,
        ),
        binding(
            sb::FRAMES,
            uniform(size_of::<Frames>(), false),
            Stages::Compute,
        ),
        binding(
            sb::WIND,
            uniform(size_of::<WindParams>(), false),
            Stages::Compute,
        ),
        binding(
            sb::WIND_VOLUME,
            BindingKind::Texture {
                sample: TextureSample::Float { filterable: false },
                volume: true,
            },
            Stages::Compute,
        ),
        binding(sb::GROUND_HEIGHT, storage(true), Stages::Compute),
        binding(sb::PARTICLES, storage(false), Stages::Compute),
        binding(sb::DEPOSITS, storage(false), Stages::Compute),
        binding(sb::PENDING_BIRTHS, storage(false), Stages::Compute),
        binding(sb::WAVES, storage(false), Stages::Compute),
        binding(sb::COVER, storage(true), Stages::Compute),
    ],
};

/// The cover kernels' bindings, the listings' last ([`COVER_LISTING`]).
const COVER_BINDINGS: &[Binding; 5] = &[
    binding(
        cv::COVER_PARAMS,
        uniform(size_of::<CoverStepParams>(), true),
        Stages::Compute,
    ),
    binding(cv::COVER, storage(false), Stages::Compute),
    binding(cv::DEPOSITS, storage(false), Stages::Compute),
    binding(cv::COVER_TILES, storage(false), Stages::Compute),
    binding(cv::COVER_TILE_DISPATCH, storage(false), Stages::Compute),
];

/// Group 0 of `CoverUpdate`.
pub const COVER_UPDATE: GroupLayout = GroupLayout {
    name: "precip cover_update",
    bindings: COVER_BINDINGS.split_at(4).0,
};

/// Group 0 of the cover tiles' listings: [`COVER_UPDATE`]'s bindings and the
/// indirect dispatches they write (`cover_bindings::COVER_TILE_DISPATCH`), which
/// the flow's and the drift's kernels read as their workgroups and so may not have
/// bound.
pub const COVER_LISTING: GroupLayout = GroupLayout {
    name: "precip cover listing",
    bindings: COVER_BINDINGS,
};

/// Group 0 of `CullParticles`.
pub const CULL: GroupLayout = GroupLayout {
    name: "precip cull",
    bindings: &[
        binding(cb::PARAMS, RENDER_PARAMS, Stages::Compute),
        binding(cb::PARTICLES, storage(true), Stages::Compute),
        binding(cb::GROUP_COUNTS, storage(false), Stages::Compute),
        binding(cb::DRAWN, storage(false), Stages::Compute),
        binding(cb::DRAWS, storage(false), Stages::Compute),
        binding(cb::DRAWN_KINDS, storage(false), Stages::Compute),
        binding(cb::SNOW_QUADS, storage(true), Stages::Compute),
    ],
};

/// Group 0 of the draws and the splat kernel: the frame.
pub const RENDER_FRAME: GroupLayout = GroupLayout {
    name: "precip render frame",
    bindings: &[
        binding(
            rb::PARAMS,
            uniform(size_of::<RenderParams>(), true),
            Stages::DrawAndCompute,
        ),
        binding(rb::PARAMS_SWITCHES, RENDER_PARAMS, Stages::DrawAndCompute),
        binding(rb::GROUND_HEIGHT, storage(true), Stages::DrawAndCompute),
        binding(rb::PARTICLES, storage(true), Stages::DrawAndCompute),
        binding(rb::DRAWN, storage(true), Stages::DrawAndCompute),
        binding(rb::COVER_A, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::COVER_B, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::COVER_C, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::COVER_SAMPLER, FILTERING, Stages::DrawAndCompute),
        binding(rb::WAVES, storage(true), Stages::DrawAndCompute),
        binding(rb::DROP_GROUND, storage(true), Stages::DrawAndCompute),
        binding(rb::CLOUD_MAP, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::CLOUD_DETAIL, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::CLOUD_SAMPLER, FILTERING, Stages::DrawAndCompute),
        binding(rb::CLOUD_SHADOW, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::OCEAN_DISPLACEMENT, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::OCEAN_SLOPE, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::SEA_DEPTH, FILTERED_2D, Stages::DrawAndCompute),
        // The draws' only: the splat kernel's stage holds as many storage buffers
        // as WebGPU allows one stage.
        binding(rb::SHORE, storage(true), Stages::Draw),
    ],
};

/// Group 0 of the shore's kernels: the frame's block (and its storage copy) and
/// the shore's buffer they step.
pub const SHORE_KERNEL: GroupLayout = GroupLayout {
    name: "precip shore",
    bindings: &[
        binding(
            rb::PARAMS,
            uniform(size_of::<RenderParams>(), true),
            Stages::Compute,
        ),
        binding(rb::PARAMS_SWITCHES, RENDER_PARAMS, Stages::Compute),
        binding(rb::SHORE_CELLS, storage(false), Stages::Compute),
    ],
};

/// Group 0 of the open sea's kernels: the frame's block (and its storage copy), the
/// spectra they transform and the atlases they write.
pub const OCEAN_KERNEL: GroupLayout = GroupLayout {
    name: "precip ocean",
    bindings: &[
        binding(
            rb::PARAMS,
            uniform(size_of::<RenderParams>(), true),
            Stages::Compute,
        ),
        binding(rb::PARAMS_SWITCHES, RENDER_PARAMS, Stages::Compute),
        binding(rb::OCEAN_SPECTRA, storage(false), Stages::Compute),
        binding(
            rb::OCEAN_DISPLACEMENT_OUT,
            BindingKind::StorageTextureRgba16Float,
            Stages::Compute,
        ),
        binding(
            rb::OCEAN_SLOPE_OUT,
            BindingKind::StorageTextureRgba16Float,
            Stages::Compute,
        ),
    ],
};

/// Group 0 of the `cloud_shadow_map` kernel: the frame's block (and its storage
/// copy), the coverage map and the shadow map it writes.
pub const CLOUD_SHADOW_KERNEL: GroupLayout = GroupLayout {
    name: "precip cloud shadow map",
    bindings: &[
        binding(
            rb::PARAMS,
            uniform(size_of::<RenderParams>(), true),
            Stages::Compute,
        ),
        binding(rb::PARAMS_SWITCHES, RENDER_PARAMS, Stages::Compute),
        binding(rb::CLOUD_MAP, FILTERED_2D, Stages::Compute),
        binding(rb::CLOUD_DETAIL, FILTERED_2D, Stages::Compute),
        binding(rb::CLOUD_SAMPLER, FILTERING, Stages::Compute),
        binding(
            rb::CLOUD_SHADOW_OUT,
            BindingKind::StorageTextureRgba16Float,
            Stages::Compute,
        ),
    ],
};

/// Group 1 of the sky's draw: the clouds' image A (of the clouds' pass into B:
/// the frame before's).
pub const CLOUD_IMAGE: GroupLayout = GroupLayout {
    name: "precip cloud image",
    bindings: &[binding(rb::CLOUD_IMAGE, FILTERED_2D, Stages::Draw)],
};

/// The same table bound to the clouds' image B (the images alternate by frame).
pub const CLOUD_IMAGE_B: GroupLayout = GroupLayout {
    name: "precip cloud image b",
    ..CLOUD_IMAGE
};

/// Group 2 of the clouds' passes: the pixels the frame marched
/// (`TargetResource::CloudFresh`).
pub const CLOUD_FRESH: GroupLayout = GroupLayout {
    name: "precip cloud fresh image",
    bindings: &[binding(rb::CLOUD_FRESH, FILTERED_2D, Stages::Draw)],
};

/// Group 1: light and the flake's opacity.
pub const RENDER_LIGHT: GroupLayout = GroupLayout {
    name: "precip render light",
    bindings: &[
        binding(rb::SHADOW_MAP, DEPTH_2D, Stages::DrawAndCompute),
        binding(
            rb::SHADOW_SAMPLER,
            BindingKind::Sampler { comparison: true },
            Stages::DrawAndCompute,
        ),
        binding(rb::FLAKE_OPACITY, FILTERED_2D, Stages::DrawAndCompute),
        binding(rb::FLAKE_SAMPLER, FILTERING, Stages::DrawAndCompute),
    ],
};

/// Group 2 of the scene's draws: a mesh's material.
pub const RENDER_MATERIAL: GroupLayout = GroupLayout {
    name: "precip render material",
    bindings: &[
        binding(rb::MATERIAL, uniform(16, false), Stages::Draw),
        binding(rb::BASE_COLOUR_TEXTURE, FILTERED_2D, Stages::Draw),
        binding(rb::MATERIAL_SAMPLER, FILTERING, Stages::Draw),
    ],
};

/// Group 2 of the splat kernel: the camera's depth and the sums.
pub const SPLAT: GroupLayout = GroupLayout {
    name: "precip splat",
    bindings: &[
        binding(rb::SPLAT_SCENE_DEPTH, DEPTH_2D, Stages::Compute),
        binding(rb::SPLAT_SUMS, storage(false), Stages::Compute),
        binding(rb::SPLAT_DRAWS, storage(true), Stages::Compute),
    ],
};

/// Group 2 of the splat's resolve draw: the sums.
pub const SPLAT_RESOLVE: GroupLayout = GroupLayout {
    name: "precip splat resolve",
    bindings: &[binding(rb::RESOLVED_SUMS, storage(false), Stages::Fragment)],
};

/// Group 2 of the reduced particles' draws: the camera's depth, which their
/// fragments test themselves, and the snow quads their sprites' corners read.
pub const PARTICLE_DEPTH: GroupLayout = GroupLayout {
    name: "precip particle depth",
    bindings: &[
        binding(rb::PARTICLE_SCENE_DEPTH, DEPTH_2D, Stages::Fragment),
        binding(rb::SNOW_QUADS, storage(true), Stages::Draw),
    ],
};

/// Group 2 of the snow sprites' draw: the frame's snow quads, read by each corner.
pub const SNOW_QUADS: GroupLayout = GroupLayout {
    name: "precip snow quads",
    bindings: &[binding(rb::SNOW_QUADS, storage(true), Stages::Draw)],
};

/// Group 2 of the kernel that makes the snow quads: the frame's draws (their
/// count) and the quads.
pub const SNOW_QUADS_KERNEL: GroupLayout = GroupLayout {
    name: "precip snow quads kernel",
    bindings: &[
        binding(rb::SPLAT_DRAWS, storage(true), Stages::Compute),
        binding(rb::SNOW_QUADS_OUT, storage(false), Stages::Compute),
    ],
};

/// Group 2 of the composite draw: the splat's sums (it resolves them) and the
/// particles' image.
pub const PARTICLE_IMAGE: GroupLayout = GroupLayout {
    name: "precip particle image",
    bindings: &[
        binding(rb::RESOLVED_SUMS, storage(false), Stages::Fragment),
        binding(rb::PARTICLE_IMAGE, FILTERED_2D, Stages::Fragment),
    ],
};

/// Group 3 of the scene's draw (fragment): the frame before's scene and depth, for
/// the water's reflections, and the water bodies' mirror image.
pub const REFLECTIONS: GroupLayout = GroupLayout {
    name: "precip reflections",
    bindings: &[
        binding(rb::SCENE_COPY, FILTERED_2D, Stages::Fragment),
        binding(rb::DEPTH_COPY, DEPTH_2D, Stages::Fragment),
        binding(rb::MIRROR_IMAGE, FILTERED_2D, Stages::Fragment),
    ],
};

/// Group 0 of the `cover_texture` and `drop_ground` kernels.
pub const COVER_TEXTURE: GroupLayout = GroupLayout {
    name: "precip cover texture",
    bindings: &[
        binding(
            rb::PARAMS,
            uniform(size_of::<RenderParams>(), true),
            Stages::Compute,
        ),
        binding(rb::COVER, storage(true), Stages::Compute),
        binding(rb::DROP_GROUND_OUT, storage(false), Stages::Compute),
        binding(
            rb::COVER_A_OUT,
            BindingKind::StorageTextureRgba16Float,
            Stages::Compute,
        ),
        binding(
            rb::COVER_B_OUT,
            BindingKind::StorageTextureRgba16Float,
            Stages::Compute,
        ),
        binding(
            rb::COVER_C_OUT,
            BindingKind::StorageTextureRgba16Float,
            Stages::Compute,
        ),
    ],
};

/// Group 0 of `query_beams`.
pub const BEAMS: GroupLayout = GroupLayout {
    name: "precip query_beams",
    bindings: &[
        binding(
            bb::PARAMS,
            uniform(size_of::<BeamParams>(), false),
            Stages::Compute,
        ),
        binding(
            bb::FRAMES,
            uniform(size_of::<Frames>(), false),
            Stages::Compute,
        ),
        binding(bb::GROUND_HEIGHT, storage(true), Stages::Compute),
        binding(bb::PARTICLES, storage(true), Stages::Compute),
        binding(bb::BEAMS, storage(true), Stages::Compute),
        binding(bb::HITS, storage(false), Stages::Compute),
    ],
};

/// Group 0 of `optics_sums`.
pub const OPTICS: GroupLayout = GroupLayout {
    name: "precip optics_sums",
    bindings: &[
        binding(
            ob::PARAMS,
            uniform(size_of::<OpticsParams>(), false),
            Stages::Compute,
        ),
        binding(ob::PARTICLES, storage(true), Stages::Compute),
        binding(ob::PARTIALS, storage(false), Stages::Compute),
    ],
};

/// The groups (0, 1, …) an entry point of `program` runs with; `None` for a test
/// probe's or an unknown entry point.
#[must_use]
pub fn groups_of(program: Program, entry_point: &str) -> Option<&'static [GroupLayout]> {
    Some(match (program, entry_point) {
        (Program::StepParticles, _) => &[STEP],
        (Program::CoverUpdate, "water_tiles_list" | "snow_tiles_list") => &[COVER_LISTING],
        (Program::CoverUpdate, _) => &[COVER_UPDATE],
        (Program::CullParticles, _) => &[CULL],
        (Program::QueryBeams, _) => &[BEAMS],
        (Program::OpticsSums, _) => &[OPTICS],
        (Program::Render, "cover_texture" | "drop_ground") => &[COVER_TEXTURE],
        (Program::Render, "cloud_shadow_map") => &[CLOUD_SHADOW_KERNEL],
        (
            Program::Render,
            "ocean_spectrum" | "ocean_fft_rows" | "ocean_fft_columns" | "ocean_resolve",
        ) => &[OCEAN_KERNEL],
        (
            Program::Render,
            "shore_faces_first"
            | "shore_update_first"
            | "shore_faces_second"
            | "shore_update_second",
        ) => &[SHORE_KERNEL],
        (Program::Render, "splat_particles") => &[RENDER_FRAME, RENDER_LIGHT, SPLAT],
        (Program::Render, "snow_quads_write") => &[RENDER_FRAME, RENDER_LIGHT, SNOW_QUADS_KERNEL],
        (Program::Render, e) if e == render_passes::SHADOW.0 => &[RENDER_FRAME],
        (Program::Render, e) if e == render_passes::TERRAIN_SHADOW.0 => &[RENDER_FRAME],
        (Program::Render, "vs_sky" | "fs_sky" | "vs_clouds_all" | "fs_clouds_all") => {
            &[RENDER_FRAME]
        }
        // The sky reads the image its frame made; the clouds' pass the other and
        // the pixels the frame marched; the march the size of the images.
        (
            Program::Render,
            "vs_sky_clouds" | "fs_sky_clouds" | "vs_clouds_fresh" | "fs_clouds_fresh",
        ) => &[RENDER_FRAME, CLOUD_IMAGE],
        (Program::Render, "vs_sky_clouds_b" | "fs_sky_clouds_b") => &[RENDER_FRAME, CLOUD_IMAGE_B],
        (Program::Render, "vs_clouds_b" | "fs_clouds_b") => {
            &[RENDER_FRAME, CLOUD_IMAGE, CLOUD_FRESH]
        }
        (Program::Render, "vs_clouds" | "fs_clouds") => &[RENDER_FRAME, CLOUD_IMAGE_B, CLOUD_FRESH],
        (
            Program::Render,
            "vs_mirror" | "fs_mirror" | "vs_terrain_mirror" | "fs_terrain_mirror",
        ) => &[RENDER_FRAME, RENDER_LIGHT, RENDER_MATERIAL],
        (
            Program::Render,
            "vs_scene"
            | "fs_scene"
            | "fs_scene_on_grid"
            | "vs_terrain"
            | "fs_terrain"
            | "fs_water_body"
            | "fs_water_body_planar"
            | "vs_sea"
            | "fs_sea",
        ) => &[RENDER_FRAME, RENDER_LIGHT, RENDER_MATERIAL, REFLECTIONS],
        (Program::Render, "vs_splat_resolve" | "fs_splat_resolve") => {
            &[RENDER_FRAME, RENDER_LIGHT, SPLAT_RESOLVE]
        }
        (Program::Render, "vs_snow" | "fs_snow" | "vs_snow_made" | "fs_snow_made") => {
            &[RENDER_FRAME, RENDER_LIGHT, SNOW_QUADS]
        }
        (Program::Render, "vs_rain" | "fs_rain") => &[RENDER_FRAME, RENDER_LIGHT],
        (
            Program::Render,
            "vs_snow_reduced"
            | "vs_snow_made_reduced"
            | "fs_snow_made_reduced"
            | "fs_snow_reduced"
            | "vs_rain_reduced"
            | "fs_rain_reduced",
        ) => &[RENDER_FRAME, RENDER_LIGHT, PARTICLE_DEPTH],
        (Program::Render, "vs_particles_composite" | "fs_particles_composite") => {
            &[RENDER_FRAME, RENDER_LIGHT, PARTICLE_IMAGE]
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::binding_limits::FRAME_PROGRAMS;

    #[test]
    fn only_the_listings_bind_the_dispatches_they_write() {
        let binds_dispatch = |g: &GroupLayout| {
            g.bindings
                .iter()
                .any(|b| b.binding == cv::COVER_TILE_DISPATCH)
        };
        for entry in Program::CoverUpdate.entry_points() {
            let groups = groups_of(Program::CoverUpdate, entry).expect("a cover kernel's groups");
            let listing = entry.ends_with("_tiles_list");
            assert_eq!(groups.iter().any(binds_dispatch), listing, "{entry}");
        }
        assert_eq!(
            COVER_LISTING.bindings.len(),
            COVER_UPDATE.bindings.len() + 1
        );
    }

    #[test]
    fn every_entry_point_of_the_frame_has_its_groups_and_no_binding_is_listed_twice() {
        for program in FRAME_PROGRAMS {
            for entry in program.entry_points() {
                let groups = groups_of(program, entry)
                    .unwrap_or_else(|| panic!("{program:?} {entry} has no groups"));
                for g in groups {
                    let mut numbers: Vec<u32> = g.bindings.iter().map(|b| b.binding).collect();
                    numbers.sort_unstable();
                    numbers.dedup();
                    assert_eq!(numbers.len(), g.bindings.len(), "{}", g.name);
                    // Every dynamic binding of a group is the frame's or the
                    // sub-step's block: the backends give each the block's offset,
                    // from an array of two.
                    assert!(g.dynamic_bindings() <= 2, "{}", g.name);
                }
            }
        }
    }
}
