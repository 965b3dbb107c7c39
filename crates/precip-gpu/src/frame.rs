//! A frame as data: its passes in order, each a list of compute kernels or a render
//! pass (attachments, how they load and store, draws with their pipeline state),
//! when it runs, and its timestamps. [`frame_plan`] is the frame as the renderer
//! ([`crate::renderer`]) walks it into commands for every backend: which passes run
//! under this frame's [`FrameConditions`], each kernel with its groups and
//! workgroups, each draw with its groups; the draws' pipelines are made from
//! [`Draw`]. A new pass is WGSL plus an entry here.
//!
//! Timestamps: each pass is bracketed by two, at its start and its end, on both
//! backends (`2·i`, `2·i + 1` for pass `i`), so per-pass times compare; a pass that
//! does not run (the shadow map kept by [`precip_model::drawing::shadow_cache`]) is not reported.

use glam::Vec3;
use precip_model::drawing::render::{RenderParams, haze_colour};
use precip_model::drawing::shadow_cache::ShadowCache;
use precip_model::drawing::shore::{ShoreFrames, ShoreGrid};
use precip_model::drawing::water_mirror::{WaterLevel, frame_mirror, water_levels};
use precip_model::{ParticleResolution, Setup, View};

use crate::bind_groups::{GroupLayout, groups_of};
use crate::executor::Simulation;
use crate::frame_resources::TargetResource;
use crate::gpu::Gpu;
use crate::recipe::{
    CLOUD_SHADOW_PASS, COVER_TEXTURE_PASS, CULL_PASSES, DROP_GROUND_PASS, DispatchCounts,
    FrameDraws, KernelPass, OCEAN_PASSES, SHORE_PASSES, SNOW_QUADS_PASS, SPLAT_PASS, dispatch_size,
    render_passes,
};
use crate::shaders::Program;

/// How a render pass starts with an attachment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AttachmentLoad {
    /// Cleared: depth to 1 (far), colour to the sky's colour.
    Clear,
    /// As the last pass left it.
    Load,
}

/// Which depth buffer a render pass uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthTarget {
    /// The sun's shadow map (`RenderSettings::shadow_map_px` square).
    ShadowMap,
    /// The camera's depth buffer, the frame target's size.
    Camera,
    /// The particles' image's depth buffer ([`ColourTarget::Particles`]'s size):
    /// cleared and never written, so every fragment passes (the draws test the
    /// scene's depth themselves).
    Particles,
    /// The water mirror's depth buffer ([`ColourTarget::Mirror`]'s size).
    Mirror,
    /// The clouds' image's depth buffer ([`ColourTarget::Clouds`]'s size): cleared,
    /// then written (depth 0) where the frame before's image is reused, so the
    /// march that follows shades only the rest.
    Clouds,
    /// The clouds' fresh image's depth buffer ([`ColourTarget::CloudsFresh`]'s
    /// size): cleared and never written.
    CloudsFresh,
}

impl DepthTarget {
    /// The target's resource it is (`None`: the shadow map, a texture of the
    /// configuration).
    #[must_use]
    pub const fn target_resource(self) -> Option<TargetResource> {
        match self {
            Self::ShadowMap => None,
            Self::Camera => Some(TargetResource::CameraDepth),
            Self::Particles => Some(TargetResource::ParticleDepth),
            Self::Mirror => Some(TargetResource::MirrorDepth),
            Self::Clouds => Some(TargetResource::CloudDepth),
            Self::CloudsFresh => Some(TargetResource::CloudFreshDepth),
        }
    }
}

impl ColourTarget {
    /// The target's resource it is (`None`: the frame's own target, cleared to the
    /// sky; an image is cleared to transparent).
    #[must_use]
    pub const fn target_resource(self) -> Option<TargetResource> {
        match self {
            Self::Frame => None,
            Self::Particles => Some(TargetResource::ParticleImage),
            Self::Mirror => Some(TargetResource::MirrorImage),
            Self::Clouds => Some(TargetResource::CloudImage),
            Self::CloudsB => Some(TargetResource::CloudImageB),
            Self::CloudsFresh => Some(TargetResource::CloudFresh),
        }
    }
}

/// Which image a render pass draws into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColourTarget {
    /// The frame's target (the window's image or the offscreen one).
    Frame,
    /// The particles' image, at [`precip_model::ParticleResolution`] of the frame
    /// (`crate::frame_resources::TargetResource::ParticleImage`): cleared to
    /// transparent, then laid over the frame.
    Particles,
    /// The water bodies' mirror image
    /// (`crate::frame_resources::TargetResource::MirrorImage`): cleared to
    /// transparent (the sky), drawn within the water's rectangle, then sampled by
    /// the water bodies.
    Mirror,
    /// The clouds' image (`crate::frame_resources::TargetResource::CloudImage`), at
    /// a quarter of the frame's side: marched through the cloud layer, then sampled
    /// by the sky.
    Clouds,
    /// The clouds' second image (`…::CloudImageB`): the images alternate by frame,
    /// each pass reading the other as the frame before's.
    CloudsB,
    /// The clouds' fresh image (`…::CloudFresh`): the one pixel of each 4 × 4
    /// block of the clouds' image the frame marches, read by the clouds' pass.
    CloudsFresh,
}

/// Which of the scene's meshes a draw draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshesOf {
    /// Every mesh.
    All,
    /// The water bodies (meshes tagged water) but the sea: their fragments mirror
    /// the scene.
    WaterBodies,
    /// The sea (meshes tagged `"water": "sea"`).
    Sea,
    /// Every mesh but the water bodies.
    AllButWaterBodies,
}

/// Which of the meshes' tiles a draw takes, by where they lie on the cover grid
/// (`precip_model::scene::gpu_scene::TileRegion`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneTiles {
    /// All of them.
    All,
    /// Those wholly on the grid's interior (`precip_model::host::grid_interior_m`),
    /// where a surface shows the grid's cover alone.
    OnTheGridInterior,
    /// The others.
    OffTheGridInterior,
}

/// What a draw draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrawOf {
    /// The scene's meshes `which` picks, from its vertex and index buffers; with
    /// `materials`, each mesh's material group bound before it.
    SceneMeshes {
        /// Bind each mesh's material group.
        materials: bool,
        /// Which meshes.
        which: MeshesOf,
        /// Which of their tiles.
        tiles: SceneTiles,
    },
    /// One triangle of 3 vertices covering the target.
    FullScreenTriangle,
    /// The terrain's clipmap: `precip_model::scene::terrain::ClipmapRows::vertices`
    /// vertices pulled by their index (`mirror_vertices` in the water's mirror),
    /// with the terrain's material group bound when `materials`.
    TerrainClipmap {
        /// Bind the terrain's material group.
        materials: bool,
        /// The mirror's levels (from `ClipmapRows::levels.w`), not the frame's.
        mirror: bool,
    },
    /// `drawIndirect` with the frame's [`FrameDraws`] at this byte offset.
    Indirect {
        /// Byte offset of the [`crate::recipe::DrawArgs`].
        offset: u64,
    },
}

/// Primitive topology.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Topology {
    /// Triangle list.
    TriangleList,
    /// Triangle strip.
    TriangleStrip,
}

/// How a draw writes the colour target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Blend {
    /// No colour target (depth only).
    None,
    /// Replaces the colour.
    Opaque,
    /// Straight alpha blending: `src·a + dst·(1 − a)` (alpha: `a + dst_a·(1 − a)`,
    /// so an image cleared to transparent holds premultiplied colour).
    Alpha,
    /// Premultiplied: `src + dst·(1 − a)`.
    Premultiplied,
}

/// One draw of a render pass: its entry points of [`crate::shaders::Program::Render`]
/// and its pipeline state. Depth is tested less-or-equal in every draw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Draw {
    /// Vertex and fragment entry points.
    pub entry_points: (&'static str, Option<&'static str>),
    /// What it draws.
    pub of: DrawOf,
    /// Reads the scene's vertex buffer (`SceneVertex`), else pulls from storage.
    pub scene_vertices: bool,
    /// Topology.
    pub topology: Topology,
    /// Writes depth.
    pub depth_write: bool,
    /// Depth bias `(constant, slope)`, against shadow acne.
    pub depth_bias: Option<(i32, f32)>,
    /// Colour.
    pub blend: Blend,
    /// When it is drawn (its pass running).
    pub when: PassWhen,
}

impl Draw {
    /// What names its pipeline: the fragment entry point, or the vertex one of a
    /// depth-only draw (two draws may share a vertex stage).
    #[must_use]
    pub const fn key(&self) -> &'static str {
        match self.entry_points.1 {
            Some(fragment) => fragment,
            None => self.entry_points.0,
        }
    }
}

/// A render pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderPassRecipe {
    /// Its depth buffer.
    pub depth: DepthTarget,
    /// How the depth starts.
    pub depth_load: AttachmentLoad,
    /// Whether the depth is kept after the pass.
    pub depth_stored: bool,
    /// The colour target and how it starts, or `None` (depth only).
    pub colour: Option<AttachmentLoad>,
    /// Which image the colour target is.
    pub colour_target: ColourTarget,
    /// The draws, in order.
    pub draws: &'static [Draw],
}

/// What a pass does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PassWork {
    /// Compute kernels in order, each after the last one's writes.
    Kernels(&'static [KernelPass]),
    /// A render pass.
    Render(RenderPassRecipe),
    /// The colour target and the camera's depth as the passes so far left them,
    /// copied into the target's [`crate::frame_resources::TargetResource::SceneCopy`]
    /// and [`crate::frame_resources::TargetResource::DepthCopy`], for the next
    /// frame's scene to read (its water's reflections); both stay ready for the next
    /// render pass.
    CopyTarget,
}

/// When a pass runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PassWhen {
    /// Every frame.
    Always,
    /// When [`precip_model::drawing::shadow_cache::ShadowCache`] says the map is to be redrawn.
    ShadowRedrawn,
    /// While standing water may show (some rain has fallen or the scene has water
    /// bodies) and the target can be copied.
    WaterShows,
    /// While the ground's puddles mirror the scene (`precip_model::Mirrors`, and the
    /// frame before's copies are there).
    GroundMirrors,
    /// While they do not.
    GroundMirrorsNot,
    /// While some particle is in the air to be drawn
    /// (`precip_model::host::HostState::particles_in_the_air`: at 0 mm/h none is).
    ParticlesInTheAir,
    /// While rain and snow are in the air and drawn at the frame's resolution.
    ParticlesFull,
    /// While they are in the air and drawn at a reduced one
    /// ([`precip_model::ParticleResolution`]).
    ParticlesReduced,
    /// While the water bodies' planar mirror is drawn
    /// ([`precip_model::drawing::water_mirror::frame_mirror`]).
    WaterMirrored,
    /// While it is not (the water bodies follow their rays over the frame before).
    WaterMirroredNot,
    /// While a cloud layer is set (`RenderSettings::cloud_layers`) and the frame
    /// writes the clouds' image A (frames alternate between A and B).
    CloudsA,
    /// While one is set and the frame marches one pixel per block (the frame
    /// before's image is there to take the rest from).
    CloudsFresh,
    /// While one is set (the clouds' shadow map).
    Clouds,
    /// While one is set and the frame writes image B.
    CloudsB,
    /// While none is.
    CloudsNot,
    /// While the scene has a sea (a mesh tagged `"water": "sea"`).
    Sea,
    /// While the sea has a shore ([`precip_model::drawing::shore::ShoreGrid`]).
    Shore,
    /// While the scene stands on a terrain (`precip_model::PreparedScene::on_terrain`).
    Terrain,
}

/// One pass of the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FramePass {
    /// Its name (timings, debug labels).
    pub name: &'static str,
    /// What it does.
    pub work: PassWork,
    /// When it runs.
    pub when: PassWhen,
}

const SHADOW_DRAW: Draw = Draw {
    entry_points: render_passes::SHADOW,
    of: DrawOf::SceneMeshes {
        materials: false,
        which: MeshesOf::All,
        tiles: SceneTiles::All,
    },
    scene_vertices: true,
    topology: Topology::TriangleList,
    depth_write: true,
    depth_bias: Some((2, 2.0)),
    blend: Blend::None,
    when: PassWhen::Always,
};

// The terrain's clipmap into the shadow map.
const TERRAIN_SHADOW_DRAW: Draw = Draw {
    entry_points: render_passes::TERRAIN_SHADOW,
    of: DrawOf::TerrainClipmap {
        materials: false,
        mirror: false,
    },
    scene_vertices: false,
    when: PassWhen::Terrain,
    ..SHADOW_DRAW
};

// The terrain's clipmap, its fragments the scene's (a pipeline of its own: its
// vertices come from the pyramid, not the scene's buffer).
const TERRAIN_DRAW: Draw = Draw {
    entry_points: render_passes::TERRAIN,
    of: DrawOf::TerrainClipmap {
        materials: true,
        mirror: false,
    },
    scene_vertices: false,
    when: PassWhen::Terrain,
    ..SCENE_DRAW
};

const SCENE_DRAW: Draw = Draw {
    entry_points: render_passes::SCENE,
    of: DrawOf::SceneMeshes {
        materials: true,
        which: MeshesOf::AllButWaterBodies,
        tiles: SceneTiles::All,
    },
    scene_vertices: true,
    topology: Topology::TriangleList,
    depth_write: true,
    depth_bias: None,
    blend: Blend::Opaque,
    when: PassWhen::GroundMirrorsNot,
};

// The scene pass's meshes (but the water bodies) on the cover grid's interior: a
// fragment shader without the far cover's reads (fs_scene_on_grid; lavapipe runs a
// branch's code in every fragment of a shader that has it, taken or not: 28 ms of
// the demo's 1280×720 scene pass), then the rest with them.
const SCENE_ON_GRID_DRAW: Draw = Draw {
    entry_points: render_passes::SCENE_ON_GRID,
    of: DrawOf::SceneMeshes {
        materials: true,
        which: MeshesOf::AllButWaterBodies,
        tiles: SceneTiles::OnTheGridInterior,
    },
    ..SCENE_DRAW
};

const SCENE_OFF_GRID_DRAW: Draw = Draw {
    of: DrawOf::SceneMeshes {
        materials: true,
        which: MeshesOf::AllButWaterBodies,
        tiles: SceneTiles::OffTheGridInterior,
    },
    ..SCENE_DRAW
};

// The same meshes when their puddles mirror the scene: the water bodies' pipeline.
const GROUND_MIRROR_DRAW: Draw = Draw {
    entry_points: render_passes::WATER_BODIES,
    when: PassWhen::GroundMirrors,
    ..SCENE_DRAW
};

// The water bodies, whose fragments also follow their mirrored rays
// (render_reflections.wgsl): a pipeline of their own, so the other meshes'
// fragments carry none of that code (lavapipe pays for a loop's code in every
// fragment of a shader that has one, run or not: +30 ms a 1280×720 frame).
const WATER_BODY_DRAW: Draw = Draw {
    entry_points: render_passes::WATER_BODIES,
    of: DrawOf::SceneMeshes {
        materials: true,
        which: MeshesOf::WaterBodies,
        tiles: SceneTiles::All,
    },
    when: PassWhen::WaterMirroredNot,
    ..SCENE_DRAW
};

// The sea: its still surface moved by the waves, its fragments shaded by their
// slopes and foam, following their mirrored rays (a pipeline of its own).
const SEA_DRAW: Draw = Draw {
    entry_points: render_passes::SEA,
    of: DrawOf::SceneMeshes {
        materials: true,
        which: MeshesOf::Sea,
        tiles: SceneTiles::All,
    },
    when: PassWhen::Sea,
    ..SCENE_DRAW
};

// The water bodies where the planar mirror is drawn: one sample of its image, no
// ray (a pipeline of its own, for the reason above).
const WATER_BODY_PLANAR_DRAW: Draw = Draw {
    entry_points: render_passes::WATER_BODIES_PLANAR,
    when: PassWhen::WaterMirrored,
    ..WATER_BODY_DRAW
};

// The scene but the water bodies, reflected about their level, into the mirror
// image (what lies below the level cut).
const MIRROR_DRAW: Draw = Draw {
    entry_points: render_passes::MIRROR,
    when: PassWhen::Always,
    ..SCENE_DRAW
};

// The terrain's clipmap reflected into the mirror image (the hills in the pond),
// from a coarser level than the frame's (ClipmapRows::mirror_vertices).
const TERRAIN_MIRROR_DRAW: Draw = Draw {
    entry_points: render_passes::TERRAIN_MIRROR,
    of: DrawOf::TerrainClipmap {
        materials: true,
        mirror: true,
    },
    scene_vertices: false,
    when: PassWhen::Terrain,
    ..MIRROR_DRAW
};

// The cloud layers at a quarter of the frame's side (render_clouds.wgsl), into
// their own image, which the sky then reads; A and B alternate by frame. The
// fresh pixels and the frame before's image at depth 0 (written), then the march
// at the far plane where that left a pixel (all of them without a history).
const CLOUDS_DRAW: Draw = Draw {
    entry_points: render_passes::CLOUDS,
    depth_write: true,
    when: PassWhen::CloudsFresh,
    ..SKY_DRAW
};

const CLOUDS_ALL_DRAW: Draw = Draw {
    entry_points: render_passes::CLOUDS_ALL,
    when: PassWhen::Always,
    ..SKY_DRAW
};

const CLOUDS_B_DRAW: Draw = Draw {
    entry_points: render_passes::CLOUDS_B,
    ..CLOUDS_DRAW
};

// The frame's one pixel per 4 × 4 block of the clouds' image marched into the
// fresh image, which the clouds' pass then reads.
const CLOUDS_FRESH_DRAW: Draw = Draw {
    entry_points: render_passes::CLOUDS_FRESH,
    ..CLOUDS_ALL_DRAW
};

// At the far plane (depth 1), less-or-equal: only where no mesh stands.
const SKY_DRAW: Draw = Draw {
    entry_points: render_passes::SKY,
    of: DrawOf::FullScreenTriangle,
    scene_vertices: false,
    topology: Topology::TriangleList,
    depth_write: false,
    depth_bias: None,
    blend: Blend::Opaque,
    when: PassWhen::CloudsNot,
};

// The same under a drawn cloud layer: a pipeline of its own that reads the clouds'
// image the frame marched (A or B).
const SKY_CLOUDS_DRAW: Draw = Draw {
    entry_points: render_passes::SKY_CLOUDS,
    when: PassWhen::CloudsA,
    ..SKY_DRAW
};

const SKY_CLOUDS_B_DRAW: Draw = Draw {
    entry_points: render_passes::SKY_CLOUDS_B,
    when: PassWhen::CloudsB,
    ..SKY_DRAW
};

/// A particles' indirect draw of `entry_points` with the [`FrameDraws`] at `offset`:
/// strips, blended, depth-tested but not written.
const fn particle_draw(entry_points: (&'static str, Option<&'static str>), offset: u64) -> Draw {
    Draw {
        entry_points,
        of: DrawOf::Indirect { offset },
        scene_vertices: false,
        topology: Topology::TriangleStrip,
        depth_write: false,
        depth_bias: None,
        blend: Blend::Alpha,
        when: PassWhen::Always,
    }
}

const PARTICLE_DRAWS: [Draw; 4] = [
    // At depth 0 it passes the less-equal test everywhere: no depth test.
    Draw {
        entry_points: render_passes::SPLAT_RESOLVE,
        of: DrawOf::FullScreenTriangle,
        scene_vertices: false,
        topology: Topology::TriangleList,
        depth_write: false,
        depth_bias: None,
        blend: Blend::Alpha,
        when: PassWhen::Always,
    },
    particle_draw(render_passes::SNOW, FrameDraws::SNOW_OFFSET),
    // The sprites beyond the kept quads (none unless more than their capacity).
    particle_draw(render_passes::SNOW_MADE, FrameDraws::SNOW_MADE_OFFSET),
    particle_draw(render_passes::RAIN, FrameDraws::RAIN_OFFSET),
];

// At reduced resolution: the sprites and streaks into the particles' image, each
// fragment testing the scene's depth itself (the image's depth is cleared and never
// written: at depth 0 … 1 less-or-equal passes).
const REDUCED_PARTICLE_DRAWS: [Draw; 3] = [
    Draw {
        entry_points: render_passes::SNOW_REDUCED,
        ..PARTICLE_DRAWS[1]
    },
    Draw {
        entry_points: render_passes::SNOW_MADE_REDUCED,
        ..PARTICLE_DRAWS[2]
    },
    Draw {
        entry_points: render_passes::RAIN_REDUCED,
        ..PARTICLE_DRAWS[3]
    },
];

// Then, at the frame's resolution, the splat resolved and the particles' image laid
// over it, over the frame: one full-screen triangle at depth 0 (on a CPU rasteriser
// each full-screen pass costs as much as a frame's worth of fragments).
const PARTICLE_COMPOSITE_DRAWS: [Draw; 1] = [Draw {
    entry_points: render_passes::PARTICLES_COMPOSITE,
    blend: Blend::Premultiplied,
    ..PARTICLE_DRAWS[0]
}];

// The particles' passes over the scene: its colour and depth loaded, the depth
// tested and not written.
const OVER_THE_FRAME: RenderPassRecipe = RenderPassRecipe {
    depth: DepthTarget::Camera,
    depth_load: AttachmentLoad::Load,
    depth_stored: false,
    colour: Some(AttachmentLoad::Load),
    colour_target: ColourTarget::Frame,
    draws: &PARTICLE_DRAWS,
};

const CLOUDS_PASS: RenderPassRecipe = RenderPassRecipe {
    depth: DepthTarget::Clouds,
    depth_load: AttachmentLoad::Clear,
    depth_stored: true,
    colour: Some(AttachmentLoad::Clear),
    colour_target: ColourTarget::Clouds,
    draws: &[CLOUDS_DRAW, CLOUDS_ALL_DRAW],
};

/// The frame, in order (see the module docs and [`crate::renderer`]).
pub const FRAME_PASSES: [FramePass; 17] = [
    FramePass {
        name: "cover_texture",
        work: PassWork::Kernels(&[COVER_TEXTURE_PASS, DROP_GROUND_PASS]),
        when: PassWhen::Always,
    },
    FramePass {
        name: "ocean",
        work: PassWork::Kernels(&OCEAN_PASSES),
        when: PassWhen::Sea,
    },
    FramePass {
        name: "shore",
        work: PassWork::Kernels(&SHORE_PASSES),
        when: PassWhen::Shore,
    },
    FramePass {
        name: "shadow",
        work: PassWork::Render(RenderPassRecipe {
            depth: DepthTarget::ShadowMap,
            depth_load: AttachmentLoad::Clear,
            depth_stored: true,
            colour: None,
            colour_target: ColourTarget::Frame,
            draws: &[SHADOW_DRAW, TERRAIN_SHADOW_DRAW],
        }),
        when: PassWhen::ShadowRedrawn,
    },
    FramePass {
        name: "water_mirror",
        work: PassWork::Render(RenderPassRecipe {
            depth: DepthTarget::Mirror,
            depth_load: AttachmentLoad::Clear,
            depth_stored: true,
            colour: Some(AttachmentLoad::Clear),
            colour_target: ColourTarget::Mirror,
            draws: &[MIRROR_DRAW, TERRAIN_MIRROR_DRAW],
        }),
        when: PassWhen::WaterMirrored,
    },
    FramePass {
        name: "cloud_shadow",
        work: PassWork::Kernels(&[CLOUD_SHADOW_PASS]),
        when: PassWhen::Clouds,
    },
    FramePass {
        name: "clouds_fresh",
        work: PassWork::Render(RenderPassRecipe {
            depth: DepthTarget::CloudsFresh,
            colour_target: ColourTarget::CloudsFresh,
            draws: &[CLOUDS_FRESH_DRAW],
            depth_stored: false,
            ..CLOUDS_PASS
        }),
        when: PassWhen::CloudsFresh,
    },
    FramePass {
        name: "clouds",
        work: PassWork::Render(CLOUDS_PASS),
        when: PassWhen::CloudsA,
    },
    FramePass {
        name: "clouds_b",
        work: PassWork::Render(RenderPassRecipe {
            colour_target: ColourTarget::CloudsB,
            draws: &[CLOUDS_B_DRAW, CLOUDS_ALL_DRAW],
            ..CLOUDS_PASS
        }),
        when: PassWhen::CloudsB,
    },
    FramePass {
        name: "scene",
        work: PassWork::Render(RenderPassRecipe {
            depth: DepthTarget::Camera,
            depth_load: AttachmentLoad::Clear,
            depth_stored: true,
            colour: Some(AttachmentLoad::Clear),
            colour_target: ColourTarget::Frame,
            draws: &[
                SCENE_ON_GRID_DRAW,
                SCENE_OFF_GRID_DRAW,
                GROUND_MIRROR_DRAW,
                TERRAIN_DRAW,
                WATER_BODY_DRAW,
                WATER_BODY_PLANAR_DRAW,
                SEA_DRAW,
                SKY_DRAW,
                SKY_CLOUDS_DRAW,
                SKY_CLOUDS_B_DRAW,
            ],
        }),
        when: PassWhen::Always,
    },
    FramePass {
        name: "scene_copy",
        work: PassWork::CopyTarget,
        when: PassWhen::WaterShows,
    },
    FramePass {
        name: "cull_particles",
        work: PassWork::Kernels(&CULL_PASSES),
        when: PassWhen::ParticlesInTheAir,
    },
    FramePass {
        name: "splat_particles",
        work: PassWork::Kernels(&[SPLAT_PASS]),
        when: PassWhen::ParticlesInTheAir,
    },
    FramePass {
        name: "snow_quads",
        work: PassWork::Kernels(&[SNOW_QUADS_PASS]),
        when: PassWhen::ParticlesInTheAir,
    },
    FramePass {
        name: "particles",
        work: PassWork::Render(OVER_THE_FRAME),
        when: PassWhen::ParticlesFull,
    },
    FramePass {
        name: "particles_reduced",
        work: PassWork::Render(RenderPassRecipe {
            depth: DepthTarget::Particles,
            depth_load: AttachmentLoad::Clear,
            depth_stored: false,
            colour: Some(AttachmentLoad::Clear),
            colour_target: ColourTarget::Particles,
            draws: &REDUCED_PARTICLE_DRAWS,
        }),
        when: PassWhen::ParticlesReduced,
    },
    FramePass {
        name: "particles_composite",
        work: PassWork::Render(RenderPassRecipe {
            draws: &PARTICLE_COMPOSITE_DRAWS,
            ..OVER_THE_FRAME
        }),
        when: PassWhen::ParticlesReduced,
    },
];

/// The names of the passes that run only while a cloud layer is drawn (a frame
/// without clouds reports none of them).
pub fn cloud_passes() -> impl Iterator<Item = &'static str> {
    FRAME_PASSES
        .iter()
        .filter(|p| {
            matches!(
                p.when,
                PassWhen::CloudsA | PassWhen::CloudsB | PassWhen::CloudsFresh | PassWhen::Clouds
            )
        })
        .map(|p| p.name)
}

/// The names of [`FRAME_PASSES`], in order: the passes a frame's timings report.
pub const TIMED_RENDER_PASSES: [&str; FRAME_PASSES.len()] = {
    let mut names = [""; FRAME_PASSES.len()];
    let mut i = 0;
    while i < FRAME_PASSES.len() {
        names[i] = FRAME_PASSES[i].name;
        i += 1;
    }
    names
};

/// Every draw of the frame, in frame order (each backend makes one pipeline for
/// each; the shadow's against the shadow pass, the others per colour format).
pub fn draws() -> impl Iterator<Item = (&'static FramePass, &'static Draw)> {
    FRAME_PASSES.iter().flat_map(|p| {
        let draws: &'static [Draw] = match &p.work {
            PassWork::Render(r) => r.draws,
            PassWork::Kernels(_) | PassWork::CopyTarget => &[],
        };
        draws.iter().map(move |d| (p, d))
    })
}

/// Every kernel of the frame, in frame order.
pub fn kernels() -> impl Iterator<Item = &'static KernelPass> {
    FRAME_PASSES.iter().flat_map(|p| match &p.work {
        PassWork::Kernels(k) => k.iter(),
        PassWork::Render(_) | PassWork::CopyTarget => [].iter(),
    })
}

/// What decides whether a pass runs this frame ([`PassWhen`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameConditions {
    /// The shadow map is to be drawn again
    /// (`precip_model::drawing::shadow_cache::ShadowCache`).
    pub shadow_redrawn: bool,
    /// Standing water may show and the target can be copied
    /// ([`PassWhen::WaterShows`]).
    pub water_shows: bool,
    /// The ground's puddles mirror the scene ([`PassWhen::GroundMirrors`]).
    pub ground_mirrors: bool,
    /// Some particle is in the air to be drawn ([`PassWhen::ParticlesInTheAir`]).
    pub particles_in_the_air: bool,
    /// Rain and snow are drawn at a reduced resolution
    /// ([`PassWhen::ParticlesReduced`]).
    pub particles_reduced: bool,
    /// The water bodies' planar mirror is drawn ([`PassWhen::WaterMirrored`]).
    pub water_mirrored: bool,
    /// A cloud layer is drawn ([`PassWhen::CloudsA`], [`PassWhen::CloudsB`]).
    pub clouds: bool,
    /// The frame marches the clouds into their image B (reading A), else into A
    /// (reading B).
    pub clouds_into_b: bool,
    /// The frame marches one pixel per block of the clouds' image and takes the
    /// rest from the frame before's ([`PassWhen::CloudsFresh`]).
    pub clouds_fresh: bool,
    /// The scene has a sea ([`PassWhen::Sea`]).
    pub sea: bool,
    /// The sea has a shore ([`PassWhen::Shore`]).
    pub shore: bool,
    /// The scene stands on a terrain ([`PassWhen::Terrain`]).
    pub terrain: bool,
}

impl PassWhen {
    /// Whether a pass with this condition runs in a frame of `conditions`.
    #[must_use]
    pub const fn holds(self, conditions: FrameConditions) -> bool {
        match self {
            Self::Always => true,
            Self::ShadowRedrawn => conditions.shadow_redrawn,
            Self::WaterShows => conditions.water_shows,
            Self::GroundMirrors => conditions.ground_mirrors,
            Self::GroundMirrorsNot => !conditions.ground_mirrors,
            Self::ParticlesInTheAir => conditions.particles_in_the_air,
            Self::ParticlesFull => conditions.particles_in_the_air && !conditions.particles_reduced,
            Self::ParticlesReduced => {
                conditions.particles_in_the_air && conditions.particles_reduced
            }
            Self::WaterMirrored => conditions.water_mirrored,
            Self::WaterMirroredNot => !conditions.water_mirrored,
            Self::CloudsA => conditions.clouds && !conditions.clouds_into_b,
            Self::CloudsFresh => conditions.clouds && conditions.clouds_fresh,
            Self::Clouds => conditions.clouds,
            Self::CloudsB => conditions.clouds && conditions.clouds_into_b,
            Self::CloudsNot => !conditions.clouds,
            Self::Sea => conditions.sea,
            Self::Shore => conditions.shore,
            Self::Terrain => conditions.terrain,
        }
    }
}

/// A pass of this frame: its place in [`FRAME_PASSES`] (its timestamps are
/// `2·index` and `2·index + 1`) and whether it runs.
#[derive(Debug, Clone, Copy)]
pub struct PlannedPass {
    /// Its index in [`FRAME_PASSES`].
    pub index: u32,
    /// The pass.
    pub pass: &'static FramePass,
    /// Whether it runs this frame (a skipped pass is not reported).
    pub runs: bool,
}

/// A kernel as this frame dispatches it.
#[derive(Debug, Clone, Copy)]
pub struct PlannedKernel {
    /// The kernel.
    pub kernel: &'static KernelPass,
    /// The groups it binds, at 0, 1, ….
    pub groups: &'static [GroupLayout],
    /// Workgroups `(x, y)`.
    pub workgroups: (u32, u32),
}

/// A draw of a render pass with the groups it binds.
#[derive(Debug, Clone, Copy)]
pub struct PlannedDraw {
    /// The draw.
    pub draw: &'static Draw,
    /// The groups its vertex entry point binds, at 0, 1, ….
    pub groups: &'static [GroupLayout],
}

/// The frame's passes in order, each with whether it runs under `conditions`: what
/// both backends walk when they record a frame.
pub fn frame_plan(conditions: FrameConditions) -> impl Iterator<Item = PlannedPass> {
    FRAME_PASSES
        .iter()
        .zip(0u32..)
        .map(move |(pass, index)| PlannedPass {
            index,
            pass,
            runs: pass.when.holds(conditions),
        })
}

impl PlannedPass {
    /// Its kernels with their groups and workgroups over `counts` (none for a render
    /// pass).
    pub fn kernels(&self, counts: DispatchCounts) -> impl Iterator<Item = PlannedKernel> {
        let list: &'static [KernelPass] = match &self.pass.work {
            PassWork::Kernels(list) => list,
            PassWork::Render(_) | PassWork::CopyTarget => &[],
        };
        list.iter().map(move |kernel| PlannedKernel {
            kernel,
            groups: groups_of(kernel.program, kernel.entry_point).unwrap_or(&[]),
            workgroups: dispatch_size(kernel.over.invocations(counts)),
        })
    }

    /// Its draws with their groups (none for a pass of kernels).
    pub fn draws(&self) -> impl Iterator<Item = PlannedDraw> {
        let list: &'static [Draw] = match &self.pass.work {
            PassWork::Render(recipe) => recipe.draws,
            PassWork::Kernels(_) | PassWork::CopyTarget => &[],
        };
        list.iter().map(|draw| PlannedDraw {
            draw,
            groups: groups_of(Program::Render, draw.entry_points.0).unwrap_or(&[]),
        })
    }
}

/// What the host decides for one frame, the same on every backend.
#[derive(Debug, Clone, Copy)]
pub struct FrameDecision {
    /// The frame's uniform block.
    pub params: RenderParams,
    /// Which conditional passes run.
    pub conditions: FrameConditions,
    /// The sky's colour (linear): the colour targets are cleared to it.
    pub sky_colour: Vec3,
    /// The rectangle of the frame the water bodies' mirror is drawn in, px
    /// `(x, y, width, height)`, when it is drawn.
    pub mirror_rect_px: Option<[u32; 4]>,
    /// The frame's size, px.
    pub target_px: (u32, u32),
}

/// The host's side of drawing one configuration: the box the sun's shadow map
/// encloses (the scene's bounds, computed once) and when the map is drawn again.
#[derive(Debug)]
pub struct FrameHost {
    shadow_bounds_m: (Vec3, Vec3),
    shadow_cache: ShadowCache,
    /// The scene has a water body (a mesh tagged water).
    water_bodies: bool,
    /// The scene has a sea.
    sea: bool,
    /// Its water bodies' level surfaces (the planar mirror's candidates).
    water_levels: Vec<WaterLevel>,
    /// The sea's shore, stepped by the frame's `shore` pass.
    shore: Option<ShoreFrames>,
}

impl FrameHost {
    /// For `setup`'s scene; the first frame draws the shadow map.
    #[must_use]
    pub fn new(setup: &Setup) -> Self {
        Self {
            shadow_bounds_m: setup.scene_bounds_m(),
            shadow_cache: ShadowCache::default(),
            water_bodies: setup
                .scene
                .as_ref()
                .is_some_and(|s| s.meshes.iter().any(precip_model::Mesh::is_water_body)),
            sea: setup
                .scene
                .as_ref()
                .is_some_and(|s| s.meshes.iter().any(precip_model::Mesh::is_sea)),
            water_levels: setup
                .scene
                .as_ref()
                .map_or_else(Vec::new, |s| water_levels(s)),
            shore: setup
                .scene
                .as_ref()
                .and_then(|s| ShoreGrid::of_scene(s))
                .and_then(|grid| {
                    let w = setup.weather.wind.mean_wind_mps;
                    ShoreFrames::new(grid, &setup.render.sea, [w.x, w.z]).ok()
                }),
        }
    }

    /// The sea's shore, where the scene has one.
    #[must_use]
    pub fn shore(&self) -> Option<&ShoreFrames> {
        self.shore.as_ref()
    }

    /// The sea's shore grid, where the scene has one.
    #[must_use]
    pub fn shore_grid(&self) -> Option<&ShoreGrid> {
        self.shore.as_ref().map(ShoreFrames::grid)
    }

    /// Whether the scene has water bodies at a level (the mirror's image is made).
    #[must_use]
    pub fn mirrors_water(&self) -> bool {
        !self.water_levels.is_empty()
    }

    /// The next frame of `sim` for `view`: its block (from the host state), whether
    /// the shadow map is drawn again and whether water may show (the renderer adds
    /// whether the target can be copied), the sky's colour.
    pub fn decide<G: Gpu>(&mut self, sim: &Simulation<G>, view: &View) -> FrameDecision {
        let host = sim.host();
        let setup = host.setup();
        let mut params = host.render_params(
            view,
            self.shadow_bounds_m,
            sim.particle_count(),
            sim.wave_frame(),
        );
        let mirror = frame_mirror(
            &self.water_levels,
            view.camera.position_m,
            params.view_proj,
            (view.width_px, view.height_px),
        );
        if let Some(m) = &mirror {
            params.mirror_view_proj = m.view_proj;
            params.mirror = glam::Vec4::new(m.level_m, 1.0, 0.0, 0.0);
        }
        let shadow_redrawn = self.shadow_cache.for_frame(
            setup,
            host.weather(),
            &mut params,
            host.time_s(),
            host.cover_window().moves(),
        );
        let wind = host.weather().wind.mean_wind_mps;
        let shore = self
            .shore
            .as_mut()
            .map(|s| s.next_frame(&setup.render.sea, [wind.x, wind.z], host.time_s()));
        if let Some(frame) = &shore {
            params = params.with_shore_rows(&frame.rows);
        }
        params = params
            .with_clipmap_rows(&host.clipmap_rows(view.camera.position_m))
            .with_land_cover_rows(&host.land_cover_rows())
            .with_far_cover_rows(&host.far_cover_rows());
        FrameDecision {
            params,
            conditions: FrameConditions {
                shadow_redrawn,
                water_shows: self.water_bodies || host.activity().water_may_stand,
                ground_mirrors: false,
                particles_in_the_air: !host.particles_in_the_air().is_empty(),
                particles_reduced: setup.render.particle_resolution != ParticleResolution::Full,
                water_mirrored: mirror.is_some(),
                clouds: !setup.render.cloud_layers.is_empty(),
                clouds_into_b: false,
                clouds_fresh: false,
                sea: self.sea,
                shore: shore.is_some(),
                terrain: host.terrain_pyramid().is_some(),
            },
            sky_colour: haze_colour(&setup.render, host.weather()),
            mirror_rect_px: mirror.map(|m| m.rect_px),
            target_px: (view.width_px, view.height_px),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pipeline_s_name_belongs_to_one_pair_of_entry_points() {
        // The backends find a draw's pipeline by its key: two draws that share one
        // must be the same shaders (the kept snow quads' draw and the draw beyond
        // them once shared `fs_snow`, and the second drew with the first's).
        let mut seen: Vec<(&str, (&str, Option<&str>))> = Vec::new();
        for (_, d) in draws() {
            match seen.iter().find(|(key, _)| *key == d.key()) {
                Some((_, entries)) => assert_eq!(*entries, d.entry_points, "{}", d.key()),
                None => seen.push((d.key(), d.entry_points)),
            }
        }
        assert!(seen.iter().any(|(key, _)| *key == "fs_snow_made"));
    }
    use crate::bind_groups::groups_of;
    use crate::shaders::Program;

    #[test]
    fn every_entry_point_exists_and_has_its_groups() {
        for k in kernels() {
            assert!(k.program.entry_points().contains(&k.entry_point), "{k:?}");
            assert!(groups_of(k.program, k.entry_point).is_some(), "{k:?}");
        }
        for (pass, d) in draws() {
            let (vs, fs) = d.entry_points;
            for e in std::iter::once(vs).chain(fs) {
                assert!(
                    Program::Render.entry_points().contains(&e),
                    "{}: {e}",
                    pass.name
                );
                assert!(groups_of(Program::Render, e).is_some(), "{e}");
            }
        }
    }

    #[test]
    fn colour_and_depth_state_fit_their_passes() {
        for (pass, d) in draws() {
            let PassWork::Render(r) = pass.work else {
                unreachable!("draws are in render passes")
            };
            // A depth-only pass draws no colour, and a colour pass always does.
            assert_eq!(r.colour.is_none(), d.blend == Blend::None, "{}", pass.name);
            // A pass that writes depth keeps it.
            assert!(!d.depth_write || r.depth_stored, "{}", pass.name);
            // Only the fragment-less draw has no fragment stage.
            assert_eq!(d.entry_points.1.is_none(), d.blend == Blend::None);
        }
    }

    #[test]
    fn the_plan_skips_the_shadow_and_the_copy_only_when_unneeded() {
        for (shadow_redrawn, water_shows, particles) in [
            (false, false, true),
            (true, false, true),
            (false, true, true),
            (false, false, false),
        ] {
            for (particles_reduced, water_mirrored, clouds, into_b) in [
                (false, false, false, false),
                (true, false, true, false),
                (false, true, false, true),
                (false, false, true, true),
            ] {
                let plan: Vec<_> = frame_plan(FrameConditions {
                    shadow_redrawn,
                    water_shows,
                    ground_mirrors: false,
                    particles_in_the_air: particles,
                    particles_reduced,
                    water_mirrored,
                    clouds,
                    clouds_into_b: into_b,
                    clouds_fresh: into_b,
                    sea: into_b,
                    shore: into_b && particles,
                    terrain: particles,
                })
                .collect();
                assert_eq!(plan.len(), FRAME_PASSES.len());
                for p in &plan {
                    let expected = match p.pass.name {
                        "shadow" => shadow_redrawn,
                        "scene_copy" => water_shows,
                        "cull_particles" | "splat_particles" | "snow_quads" => particles,
                        "particles" => particles && !particles_reduced,
                        "particles_reduced" | "particles_composite" => {
                            particles && particles_reduced
                        }
                        "water_mirror" => water_mirrored,
                        "clouds" => clouds && !into_b,
                        "clouds_b" | "clouds_fresh" => clouds && into_b,
                        "cloud_shadow" => clouds,
                        "ocean" => into_b,
                        "shore" => into_b && particles,
                        _ => true,
                    };
                    assert_eq!(p.runs, expected, "{}", p.pass.name);
                    assert_eq!(FRAME_PASSES[p.index as usize].name, p.pass.name);
                    for d in p.draws() {
                        assert!(!d.groups.is_empty(), "{}", p.pass.name);
                    }
                }
            }
        }
    }

    #[test]
    fn the_ground_is_drawn_once_by_the_pipeline_its_mirrors_need() {
        let scene = FRAME_PASSES
            .iter()
            .find(|p| p.name == "scene")
            .expect("a scene pass");
        let PassWork::Render(recipe) = scene.work else {
            unreachable!("the scene is a render pass")
        };
        for ground_mirrors in [false, true] {
            let conditions = FrameConditions {
                shadow_redrawn: false,
                water_shows: true,
                ground_mirrors,
                particles_in_the_air: true,
                particles_reduced: false,
                water_mirrored: false,
                clouds: false,
                clouds_into_b: false,
                clouds_fresh: false,
                sea: false,
                shore: false,
                terrain: false,
            };
            let ground: Vec<_> = recipe
                .draws
                .iter()
                .filter(|d| d.when.holds(conditions))
                .filter_map(|d| match d.of {
                    DrawOf::SceneMeshes {
                        materials: true,
                        which: MeshesOf::AllButWaterBodies,
                        tiles,
                    } => Some((d.key(), tiles)),
                    _ => None,
                })
                .collect();
            // Mirroring, all its tiles by the water bodies' pipeline; else those on
            // the grid's interior without the far cover's reads, the rest with them.
            let expected: &[(&str, SceneTiles)] = if ground_mirrors {
                &[(
                    render_passes::WATER_BODIES.1.unwrap_or_default(),
                    SceneTiles::All,
                )]
            } else {
                &[
                    (
                        render_passes::SCENE_ON_GRID.1.unwrap_or_default(),
                        SceneTiles::OnTheGridInterior,
                    ),
                    (
                        render_passes::SCENE.1.unwrap_or_default(),
                        SceneTiles::OffTheGridInterior,
                    ),
                ]
            };
            assert_eq!(ground, expected);
        }
    }

    #[test]
    fn a_clouds_pass_either_reuses_or_marches_every_pixel() {
        for into_b in [false, true] {
            for fresh in [false, true] {
                let conditions = FrameConditions {
                    shadow_redrawn: false,
                    water_shows: false,
                    ground_mirrors: false,
                    particles_in_the_air: false,
                    particles_reduced: false,
                    water_mirrored: false,
                    clouds: true,
                    clouds_into_b: into_b,
                    clouds_fresh: fresh,
                    sea: false,
                    shore: false,
                    terrain: true,
                };
                let ran: Vec<_> = frame_plan(conditions)
                    .filter(|p| p.runs && p.pass.name.starts_with("clouds"))
                    .collect();
                let names: Vec<_> = ran.iter().map(|p| p.pass.name).collect();
                let made = if into_b { "clouds_b" } else { "clouds" };
                if fresh {
                    assert_eq!(names, ["clouds_fresh", made]);
                } else {
                    assert_eq!(names, [made]);
                }
                let draws: Vec<_> = ran
                    .iter()
                    .filter(|p| p.pass.name == made)
                    .flat_map(|p| p.draws())
                    .filter(|d| d.draw.when.holds(conditions))
                    .map(|d| d.draw.entry_points.0)
                    .collect();
                let expected: &[&str] = match (fresh, into_b) {
                    (false, _) => &["vs_clouds_all"],
                    (true, false) => &["vs_clouds", "vs_clouds_all"],
                    (true, true) => &["vs_clouds_b", "vs_clouds_all"],
                };
                assert_eq!(draws, expected);
            }
        }
    }

    #[test]
    fn the_timed_names_are_the_passes_in_order() {
        assert_eq!(
            TIMED_RENDER_PASSES,
            [
                "cover_texture",
                "ocean",
                "shore",
                "shadow",
                "water_mirror",
                "cloud_shadow",
                "clouds_fresh",
                "clouds",
                "clouds_b",
                "scene",
                "scene_copy",
                "cull_particles",
                "splat_particles",
                "snow_quads",
                "particles",
                "particles_reduced",
                "particles_composite"
            ]
        );
    }
}
