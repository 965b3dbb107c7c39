//! precip's viewer as a library: glTF scenes with snow masks ([`gltf_scene`]), the
//! built-in demo ([`demo`], written with [`glb`]), weather presets ([`presets`]),
//! the scene's simulation set-up ([`scene_setup`]), a fly camera ([`fly_camera`]),
//! headless frames ([`headless`]) and the interactive window ([`window`]), on either
//! GPU backend ([`backends`]); weather from OpenSCENARIO files ([`scenario`]), a
//! spinning LiDAR's scans as PLY point clouds ([`lidar_scan`]) and the optics table
//! of `precip optics` ([`optics_report`]). The `precip` binary is its command line.
//!
//! # Example
//!
//! A tagged glTF scene (docs/examples/yard.gltf: a lawn, a road that holds no snow, a
//! pond) under a shipped preset, stepped on the CPU reference:
//!
//! ```
//! use precip_model::{Backend, CpuBackend, Setup};
//! use precip_viewer::load_scene;
//! use precip_viewer::presets::Preset;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let loaded = load_scene(std::path::Path::new("../../docs/examples/yard.gltf"))?;
//! assert_eq!(loaded.report.tags.len(), 3); // a line per primitive: what was read, from where
//! let (mut setup, _) = Setup::over_scene(loaded.scene.into_scene(), 64, 6.0, 2_000)?;
//! setup.weather = Preset::load("blizzard")?.weather()?;
//! let mut cpu = CpuBackend::new();
//! cpu.configure(&setup)?;
//! for _ in 0..10 {
//!     cpu.step(0.05)?;
//! }
//! assert!(!cpu.read_particles()?.is_empty());
//! # Ok(())
//! # }
//! ```

pub mod backends;
pub mod cigi_view;
pub mod coast;
pub mod demo;
pub mod eligibility;
pub mod error;
pub mod flight;
pub mod fly_camera;
pub mod frame_stats;
pub mod geotiff_place;
pub mod glb;
pub mod gltf_data;
pub mod gltf_scene;
pub mod headless;
pub mod heap;
pub mod land_cover_file;
pub mod lidar_scan;
pub mod meshopt_views;
pub mod node_graph;
pub mod optics_report;
pub mod png_writer;
pub mod presets;
pub mod scenario;
pub mod scene_setup;
pub mod snow_summary;
pub mod terrain_file;
pub mod water_summary;
pub mod window;

pub use backends::BackendName;
pub use error::LoadError;
pub use gltf_scene::{
    LoadReport, LoadedScene, PrimitiveTags, TagSource, load_scene, load_scene_from_slice,
};
