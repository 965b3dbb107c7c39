//! The [`Backend`] trait (docs/architecture.md §3): one contract, implemented by the CPU
//! reference and the GPU crates. The same inputs give the same outputs on every
//! backend, within the tolerances of docs/architecture.md §5.

pub mod camera;
pub mod error;
pub mod limits;
pub mod setup;

use precip_cover::CoverGrid;

use crate::backend::camera::{Camera, Image, View};
use crate::backend::error::BackendError;
use crate::backend::setup::Setup;
use crate::particles::particle::Particle;
use crate::sensors::lidar::{BeamQuery, BeamReturn};
use crate::sensors::optics::Optics;
use crate::weather::Weather;

/// The longest `dt` one `step` accepts, s (sub-stepped internally).
pub const MAX_STEP_S: f32 = 1.0;

/// The most sub-steps one `step` makes.
pub const MAX_SUBSTEPS: u32 = 20;

/// Checks `dt_s` and splits it into equal sub-steps of at most
/// [`crate::physics::drag::MAX_SUBSTEP_S`]: `(count, length)`. Every backend splits the same way.
pub fn substeps(dt_s: f32) -> Result<(u32, f32), BackendError> {
    if !(dt_s.is_finite() && dt_s > 0.0 && dt_s <= MAX_STEP_S) {
        return Err(BackendError::InvalidTimeStep {
            dt_s,
            max_s: MAX_STEP_S,
        });
    }
    let count = ((dt_s / crate::physics::drag::MAX_SUBSTEP_S).ceil() as u32).clamp(1, MAX_SUBSTEPS);
    Ok((count, dt_s / count as f32))
}

/// What a backend is and how much it holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BackendInfo {
    /// Short name: "cpu", "wgpu", "vk".
    pub name: &'static str,
    /// The device, in words.
    pub device: String,
    /// The most particles one configuration may hold.
    pub max_particles: u64,
    /// Whether `render` and `read_image` work.
    pub renders: bool,
}

/// Where timings come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimingSource {
    /// Host wall clock around each pass (the CPU backend).
    HostClock,
    /// GPU timestamp queries.
    GpuTimestamps,
    /// The device cannot time passes.
    Unavailable,
}

/// Time of one pass of the last frame.
#[derive(Debug, Clone, PartialEq)]
pub struct PassTiming {
    /// The pass: a kernel's entry point ("step_particles", "cover_update", …) or "wind_bake".
    pub pass: &'static str,
    /// Milliseconds.
    pub milliseconds: f64,
}

/// The device memory a GPU backend holds now: its live allocations (buffers, images,
/// their sub-allocations) as its allocator counts them. Soak tests bound its growth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DeviceMemory {
    /// Live allocations.
    pub allocations: u64,
    /// Bytes they use.
    pub allocated_bytes: u64,
    /// Bytes of the memory blocks reserved for them.
    pub reserved_bytes: u64,
}

/// Per-pass timings of the last `step`/`render`/`set_weather`.
#[derive(Debug, Clone, PartialEq)]
pub struct Timings {
    /// Where they come from.
    pub source: TimingSource,
    /// Passes in order.
    pub passes: Vec<PassTiming>,
}

/// What the last frame drew, after culling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DrawnCounts {
    /// Snow sprites rasterised.
    pub sprites: u32,
    /// Rain tetrahedra rasterised.
    pub streaks: u32,
    /// Sub-pixel particles splatted.
    pub splats: u32,
}

impl DrawnCounts {
    /// Every particle drawn, however.
    #[must_use]
    pub const fn total(&self) -> u64 {
        self.sprites as u64 + self.streaks as u64 + self.splats as u64
    }
}

/// A precipitation backend.
///
/// Every method validates its input before it changes anything: an `Err` leaves the
/// backend as it was.
pub trait Backend {
    /// Name, device and limits.
    fn info(&self) -> BackendInfo;
    /// Allocates and initialises everything for `setup` (pre-warmed particles, bare
    /// cover, baked wind).
    fn configure(&mut self, setup: &Setup) -> Result<(), BackendError>;
    /// Changes the weather; re-bakes the wind volume only when its noise changed.
    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError>;
    /// Moves the camera (the camera volume follows it).
    fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError>;
    /// Advances the particles and the cover by `dt_s` seconds (sub-stepped so each
    /// sub-step is at most 0.05 s); `dt_s` in `(0, 1]`.
    fn step(&mut self, dt_s: f32) -> Result<(), BackendError>;
    /// Draws the scene, cover and precipitation for `view`.
    fn render(&mut self, view: &View) -> Result<(), BackendError>;
    /// Draws rain and snow at `resolution` of the frame's from the next frame on
    /// (`RenderSettings::particle_resolution` changed without re-configuring: what a
    /// frame-rate controller turns). A backend that does not draw ignores it.
    fn set_particle_resolution(
        &mut self,
        resolution: crate::ParticleResolution,
    ) -> Result<(), BackendError> {
        let _ = resolution;
        Ok(())
    }
    /// Keeps a stale shadow map for up to `frames` frames from the next frame on
    /// (`RenderSettings::shadow_refresh_frames` changed without re-configuring,
    /// `[1, 60]`: what a frame-rate controller turns). A backend that does not draw
    /// ignores it.
    fn set_shadow_refresh_frames(&mut self, frames: u32) -> Result<(), BackendError> {
        let _ = frames;
        Ok(())
    }
    /// Takes the direction toward the sun (any length but zero) and the clear air's
    /// extinction per m (`None`: the one in effect) from the next frame, beam query
    /// and optics on (what a scenario's `Sun` and `Fog` or a CIGI host's date and
    /// time change while running; validated as `RenderSettings::to_sun` and
    /// `RenderSettings::clear_air_extinction_per_m`).
    fn set_atmosphere(
        &mut self,
        to_sun: Option<glam::Vec3>,
        clear_air_extinction_per_m: Option<f32>,
    ) -> Result<(), BackendError>;
    /// Takes cloud layers (up to three; none: no clouds) from the next frame on
    /// (what a host's cloud layers set while running; validated as
    /// `RenderSettings::cloud_layers`).
    fn set_cloud_layers(
        &mut self,
        cloud_layers: crate::drawing::clouds::CloudLayers,
    ) -> Result<(), BackendError>;
    /// Takes a fog layer, or none, from the next frame, beam query and optics on
    /// (what a host's ground-fog layer sets while running; validated as
    /// `RenderSettings::fog_layer`).
    fn set_fog_layer(
        &mut self,
        fog_layer: Option<crate::drawing::fog_layer::FogLayer>,
    ) -> Result<(), BackendError>;
    /// The weather in effect (the setup's, or the last `set_weather`'s).
    fn weather(&self) -> Result<Weather, BackendError>;
    /// Casts LiDAR beams against the particles and the scene's ground map as they
    /// are now ([`crate::sensors::lidar`]): per beam, the first particle struck and the hard
    /// target behind with its two-way transmittance.
    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError>;
    /// Extinction and backscatter at 550, 905 and 1550 nm and the meteorological
    /// optical range, from the particles in the camera volume now
    /// ([`Optics::live`]). Reads the particles back: once a frame at most.
    fn optics(&mut self) -> Result<Optics, BackendError> {
        let weather = self.weather()?;
        Ok(Optics::live(&weather, &self.read_particles()?))
    }
    /// Copies the particles back (tests and tools, never the frame loop).
    fn read_particles(&mut self) -> Result<Vec<Particle>, BackendError>;
    /// Copies the cover back.
    fn read_cover(&mut self) -> Result<CoverGrid, BackendError>;
    /// Copies the last rendered image back.
    fn read_image(&mut self) -> Result<Image, BackendError>;
    /// Timings of the last calls, per pass.
    fn timings(&mut self) -> Result<Timings, BackendError>;
    /// What the last frame drew (a read back from the device: tests, tools, and the
    /// viewer's sampled statistics); `None` for a backend that does not draw, zeros
    /// before the first frame.
    fn drawn(&mut self) -> Result<Option<DrawnCounts>, BackendError> {
        Ok(None)
    }
    /// The device memory held now, where the backend's allocator reports it (`None`
    /// for the CPU reference, or a driver that does not say).
    fn device_memory(&self) -> Option<DeviceMemory> {
        None
    }
    /// The books of the cover beyond the grid over the terrain's land off it
    /// ([`crate::host::HostState::far_cover_totals`]; `None` without a terrain or
    /// before configure): with [`Backend::read_cover`]'s, the whole terrain's.
    fn far_cover_totals(&self) -> Option<precip_cover::CoverTotals> {
        None
    }
    /// The snow line beyond the grid, m ([`crate::host::FarCover::snow_line_m`];
    /// `None` without a terrain, before configure or where no cell holds snow).
    fn far_snow_line_m(&self) -> Option<f32> {
        None
    }
    /// Where the cover grid is as it follows the camera over a terrain: its
    /// offset from where it was configured and its moves
    /// ([`crate::host::CoverWindow`]; `None` before configure).
    fn cover_window(&self) -> Option<crate::host::CoverWindow> {
        None
    }
}
