//! The precip model: weather in physical units, snowflake and raindrop physics,
//! particles and their emitters, the [`Backend`] trait and the CPU reference backend.
//!
//! ## Map
//!
//! - Weather and derived quantities: [`weather`], [`visibility`].
//! - Physics (MODEL.md §2): [`snowflake`], [`raindrop`], [`snowfall`] (size spectra),
//!   [`drag`] (gravity + drag, the stable integrator), [`rotation`].
//! - Particles (MODEL.md §1): [`particle`] (the GPU layout), [`rng`] (counter-based
//!   random numbers), [`emitter`] (world emitter, camera volume), [`birth`],
//!   [`step`] (one particle's step), [`ground`] (what particles land on).
//! - Scenes: [`scene`] (the neutral triangle scene, validated, with slope eligibility),
//!   [`top_down`] (its ground map), [`tessellate`] (vertices for the snow's
//!   displacement), [`builtin`] (a house on a plane).
//! - Drawing (MODEL.md §5): [`drawing`] (sprite, tetrahedron, view cone, lighting, fog),
//!   [`render`] (settings and the per-frame block of the renderers).
//! - Sensors: [`optics`] (extinction, backscatter and MOR at 550/905/1550 nm),
//!   [`lidar`] (beams against the particles and the scene).
//! - Contract: [`backend`] (the trait), [`setup`], [`camera`], [`error`].
//! - [`cpu`] — the reference backend.
//! - GPU: [`shaders`] (the WGSL sources, joined per program), [`gpu`] (the frame
//!   recipe, bindings and uniform blocks both GPU backends follow).
//!
//! Every formula here has a WGSL twin of the same name in `shaders/`, so a reader
//! compares them function by function. The wind lives in
//! `precip-wind` and the snow cover in `precip-cover`.

pub mod backend;
pub mod bind_groups;
pub mod birth;
pub mod builtin;
pub mod camera;
pub mod cpu;
pub mod displacement;
pub mod drag;
pub mod drawing;
pub mod drifting_snow;
pub mod emitter;
pub mod error;
pub mod frame_recipe;
pub mod gpu;
pub mod gpu_scene;
pub mod grain;
pub mod ground;
pub mod lidar;
pub mod limits;
pub mod optics;
pub mod particle;
pub mod raindrop;
pub mod render;
pub mod rng;
pub mod rotation;
pub mod scene;
pub mod setup;
pub mod shaders;
pub mod shadow_cache;
pub mod shadow_fit;
pub mod snowfall;
pub mod snowflake;
pub mod splash;
pub mod step;
pub mod terrain_flow;
pub mod tessellate;
pub mod top_down;
pub mod visibility;
pub mod water_look;
pub mod water_waves;
pub mod weather;

pub use backend::{
    Backend, BackendInfo, DeviceMemory, DrawnCounts, MAX_STEP_S, PassTiming, TimingSource, Timings,
    substeps,
};
pub use camera::{Camera, Image, View};
pub use cpu::CpuBackend;
pub use emitter::{CameraVolume, WorldEmitter};
pub use error::{BackendError, WeatherError};
pub use ground::GroundMap;
pub use limits::DeviceLimits;
pub use particle::{Particle, ParticleKind, ParticleSource};
pub use render::RenderSettings;
pub use scene::{Material, Mesh, PreparedScene, Scene, SceneError, SceneReport, TextureRgba8};
pub use setup::{CameraVolumeSetup, CoverSetup, EmitterSetup, GrainLift, Setup};
pub use weather::{PrecipitationKind, Weather};

pub use precip_cover as cover;
pub use precip_wind as wind;
