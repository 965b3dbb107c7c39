//! The precip model: weather in physical units, the physics of snowflakes,
//! raindrops and grains, the particles and their emitters, scenes, drawing
//! formulas, sensors, the host state every backend shares, the [`Backend`] trait
//! and the CPU reference backend.
//!
//! ## Map
//!
//! Each topic is a folder; every formula is written once in Rust here and once in
//! WGSL beside it (`shaders/`, listed in [`wgsl`]), with the same names, so a reader
//! compares them function by function. `docs/model.md` gives each equation, its
//! source and the numbers it is tested against; `docs/architecture.md` the crates
//! and how a frame runs.
//!
//! - [`weather`]: what the user sets ([`Weather`], validated), the table of what
//!   falls ([`PrecipitationKind`]: one row a kind) and what follows from it
//!   (visibility, particle budgets).
//! - [`physics`]: snowflakes, raindrops, size spectra, drag, rotation, sand and dust,
//!   splashes, waves on water bodies, the wind near the ground, drifting snow.
//! - [`particles`]: the particle's GPU layout, the table of what each is and does
//!   ([`ParticleKind`]: every per-kind decision, WGSL twin `kind.wgsl`),
//!   counter-based random numbers, the emitters, birth, one particle's step, the
//!   ground map they land on.
//! - [`scene`]: the neutral triangle scene, its top-down ground map, tessellation
//!   and displacement, the built-in demo, the scene packed for the GPU.
//! - [`drawing`]: sprite, tetrahedron, lighting and fog; render settings and the
//!   frame's block; the sun's shadow map; how water looks.
//! - [`sensors`]: optics (extinction, backscatter, MOR) and LiDAR beams.
//! - [`backend`]: the [`Backend`] contract, [`Setup`], [`Camera`], errors, device
//!   limits.
//! - [`host`]: [`host::HostState`], the host side every backend shares (weather,
//!   wind volume, clock, sub-steps, every uniform block, computed once).
//! - [`cpu`]: the reference backend.
//! - [`wgsl`]: the WGSL twins, for `precip-gpu`'s programs.
//! - [`cover`] and [`wind`]: the snow cover (`precip-cover`) and the wind field
//!   (`precip-wind`), re-exported.
//!
//! The GPU's plan (programs, bindings, recipes) is in the `precip-gpu` crate.
//!
//! ## Example
//!
//! Snow at 2 mm/h and −3 °C over a flat 20 m square, on the CPU reference (a GPU
//! backend — `precip_gpu_wgpu::WgpuBackend`, `precip_gpu_vk::VkBackend` — takes
//! the same calls and draws frames too):
//!
//! ```
//! use precip_model::{Backend, CpuBackend, PrecipitationKind, Setup, Weather};
//!
//! let mut setup = Setup::over_flat_ground(20.0, 16, 10.0, 2_000);
//! setup.weather = Weather {
//!     kind: PrecipitationKind::DrySnow,
//!     intensity_mm_per_h: 2.0,
//!     air_temperature_c: -3.0,
//!     ..Weather::default()
//! };
//! let mut backend = CpuBackend::new();
//! backend.configure(&setup)?;
//! for _ in 0..40 {
//!     backend.step(0.05)?; // s
//! }
//! let flakes = backend.read_particles()?;
//! assert_eq!(flakes.len(), 2_000);
//! let cover = backend.read_cover()?;
//! assert!(cover.totals().mean_snow_depth_mm() >= 0.0);
//! // Bad input is refused, naming the field and what is allowed.
//! let hot = Weather { air_temperature_c: 30.0, ..setup.weather };
//! assert!(backend.set_weather(&hot).is_err());
//! # Ok::<(), precip_model::BackendError>(())
//! ```

pub mod backend;
pub mod cpu;
pub mod drawing;
pub mod host;
pub mod particles;
pub mod physics;
pub mod scene;
pub mod sensors;
pub mod weather;
pub mod wgsl;

pub use backend::camera::{Camera, Image, Lens, View};
pub use backend::error::{BackendError, WeatherError};
pub use backend::limits::DeviceLimits;
pub use backend::setup::{CameraVolumeSetup, CoverSetup, EmitterSetup, GrainLift, Setup};
pub use backend::{
    Backend, BackendInfo, DeviceMemory, DrawnCounts, MAX_STEP_S, PassTiming, TimingSource, Timings,
    substeps,
};
pub use cpu::CpuBackend;
pub use drawing::frame_rate_control::{FrameLevel, FrameRateControl};
pub use drawing::render::{Mirrors, ParticleResolution, Quality, RenderSettings};
pub use particles::emitter::{CameraVolume, WorldEmitter};
pub use particles::ground::GroundMap;
pub use particles::particle::{Particle, ParticleKind, ParticleSource};
pub use scene::{Material, Mesh, PreparedScene, Scene, SceneError, SceneReport, TextureRgba8};
pub use weather::{PrecipitationKind, Weather};

pub use precip_cover as cover;
pub use precip_wind as wind;
