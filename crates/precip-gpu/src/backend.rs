//! [`GpuBackend`]: precip's [`Backend`] over any [`Gpu`], written once. It holds
//! the device calls, the compute kernels ([`Kernels`]), the frame objects
//! ([`Drawing`], made on the first frame) and the configuration (a [`Simulation`]
//! and its [`FrameState`]). `precip-gpu-wgpu`'s `WgpuBackend` and
//! `precip-gpu-vk`'s `VkBackend` wrap one, adding only how a device is opened and
//! how a window's image is drawn into ([`GpuBackend::draw`] with a surface);
//! [`delegate_backend!`](crate::delegate_backend) gives each the trait.

use precip_model::cover::CoverGrid;
use precip_model::sensors::lidar::{BeamQuery, BeamReturn};
use precip_model::sensors::optics::Optics;
use precip_model::{
    Backend, BackendError, BackendInfo, Camera, DeviceMemory, DrawnCounts, Image, Particle, Setup,
    TimingSource, Timings, View, Weather,
};

use crate::executor::{Kernels, Simulation};
use crate::gpu::Gpu;
use crate::renderer::{Drawing, FrameState};

/// A configuration: the simulation and, from the first frame, drawing's resources.
#[derive(Debug)]
struct Configured<G: Gpu> {
    sim: Simulation<G>,
    frame: Option<FrameState<G>>,
}

/// The kernels, or a bug's error.
fn kernels_of<G: Gpu>(kernels: Option<&Kernels<G>>) -> Result<&Kernels<G>, BackendError> {
    kernels.ok_or_else(|| BackendError::Device {
        backend: "precip-gpu",
        message: "the kernels are gone (a bug in precip: please report it)".into(),
    })
}

/// The configuration, or the error of `operation` without one.
fn configured<'a, G: Gpu>(
    state: Option<&'a Configured<G>>,
    operation: &'static str,
) -> Result<&'a Configured<G>, BackendError> {
    state.ok_or(BackendError::NotConfigured { operation })
}

/// precip on the device `G` calls.
#[derive(Debug)]
pub struct GpuBackend<G: Gpu> {
    kernels: Option<Kernels<G>>,
    drawing: Option<Drawing<G>>,
    state: Option<Configured<G>>,
    /// Dropped last: everything above is handed back to it first.
    gpu: G,
}

impl<G: Gpu> GpuBackend<G> {
    /// The backend over `gpu`, its compute programs compiled.
    pub fn new(mut gpu: G) -> Result<Self, BackendError> {
        gpu.binding_limits().admit(&gpu.describe())?;
        let kernels = Kernels::new(&mut gpu)?;
        Ok(Self {
            kernels: Some(kernels),
            drawing: None,
            state: None,
            gpu,
        })
    }

    /// The device calls.
    #[must_use]
    pub fn gpu(&self) -> &G {
        &self.gpu
    }

    /// The device calls, to change.
    pub fn gpu_mut(&mut self) -> &mut G {
        &mut self.gpu
    }

    /// The most particles one configuration holds on this device.
    #[must_use]
    pub fn max_particles(&self) -> u64 {
        self.gpu.limits().max_particles()
    }

    /// Draws a frame for `view` into `surface` (a window's image of `view`'s size;
    /// the caller presents it), or into the offscreen image that
    /// [`Backend::read_image`] reads when `None`.
    pub fn draw(&mut self, view: &View, surface: Option<&G::Surface>) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "render",
        })?;
        if self.drawing.is_none() {
            self.drawing = Some(Drawing::new(&mut self.gpu)?);
        }
        let Some(drawing) = self.drawing.as_mut() else {
            return Err(BackendError::NotConfigured {
                operation: "render",
            });
        };
        if state.frame.is_none() {
            state.frame = Some(FrameState::new(&mut self.gpu, drawing, &state.sim)?);
        }
        match state.frame.as_mut() {
            Some(frame) => frame.draw(&mut self.gpu, drawing, &mut state.sim, view, surface),
            None => Err(BackendError::NotConfigured {
                operation: "render",
            }),
        }
    }

    /// The cover's three filtered textures as the last frame wrote them (tests and
    /// tools; see [`FrameState::cover_textures`]); `None` before a frame.
    pub fn read_cover_textures(&mut self) -> Result<Option<Vec<[f32; 12]>>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_cover_textures",
        })?;
        match &state.frame {
            Some(frame) => frame.cover_textures(&mut self.gpu),
            None => Ok(None),
        }
    }

    /// The sea's atlases as the last frame wrote them (tests and tools; see
    /// [`FrameState::sea_atlases`]); `None` before a frame.
    pub fn read_sea_atlases(&mut self) -> Result<Option<[Vec<[f32; 4]>; 2]>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_sea_atlases",
        })?;
        match &state.frame {
            Some(frame) => frame.sea_atlases(&mut self.gpu),
            None => Ok(None),
        }
    }

    /// The shore's grid and water as the last frame left them (tests and tools; see
    /// [`FrameState::shore_state`]); `None` before a frame or without a shore.
    pub fn read_shore(
        &mut self,
    ) -> Result<Option<precip_model::drawing::shore::ShoreGridState>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_shore",
        })?;
        match &state.frame {
            Some(frame) => frame.shore_state(&mut self.gpu),
            None => Ok(None),
        }
    }

    /// The albedo of the ground the last frame's drops refracted and of the land
    /// beyond the scene (tests and tools; see [`FrameState::drop_ground_albedo`]);
    /// `None` before a frame.
    pub fn read_drop_ground_albedo(&mut self) -> Result<Option<[f32; 2]>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_drop_ground_albedo",
        })?;
        match &state.frame {
            Some(frame) => frame.drop_ground_albedo(&mut self.gpu),
            None => Ok(None),
        }
    }

    fn release_state(&mut self) {
        if let Some(old) = self.state.take() {
            if let Some(frame) = old.frame {
                frame.destroy(&mut self.gpu);
            }
            old.sim.destroy(&mut self.gpu);
        }
    }
}

impl<G: Gpu> Drop for GpuBackend<G> {
    fn drop(&mut self) {
        let _ = self.gpu.settle();
        self.release_state();
        if let Some(d) = self.drawing.take() {
            d.destroy(&mut self.gpu);
        }
        if let Some(k) = self.kernels.take() {
            k.destroy(&mut self.gpu);
        }
    }
}

impl<G: Gpu> Backend for GpuBackend<G> {
    fn info(&self) -> BackendInfo {
        BackendInfo {
            name: self.gpu.name(),
            device: self.gpu.describe(),
            max_particles: self.max_particles(),
            renders: true,
        }
    }

    fn configure(&mut self, setup: &Setup) -> Result<(), BackendError> {
        // Checked before anything of the last configuration is let go.
        let prepared = Simulation::prepare(&self.gpu, setup)?;
        self.gpu.settle()?;
        self.release_state();
        self.gpu.forget_times();
        let kernels = kernels_of(self.kernels.as_ref())?;
        let sim = Simulation::configure(&mut self.gpu, kernels, prepared)?;
        self.state = Some(Configured { sim, frame: None });
        Ok(())
    }

    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_weather",
        })?;
        state.sim.set_weather(&mut self.gpu, weather)
    }

    fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        self.state
            .as_mut()
            .ok_or(BackendError::NotConfigured {
                operation: "set_camera",
            })?
            .sim
            .set_camera(camera)
    }

    fn step(&mut self, dt_s: f32) -> Result<(), BackendError> {
        let kernels = kernels_of(self.kernels.as_ref())?;
        let state = self
            .state
            .as_mut()
            .ok_or(BackendError::NotConfigured { operation: "step" })?;
        state.sim.step(&mut self.gpu, kernels, dt_s)
    }

    fn render(&mut self, view: &View) -> Result<(), BackendError> {
        self.draw(view, None)
    }

    fn set_particle_resolution(
        &mut self,
        resolution: precip_model::ParticleResolution,
    ) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_particle_resolution",
        })?;
        state.sim.set_particle_resolution(resolution);
        if let Some(frame) = state.frame.as_mut() {
            frame.set_particle_resolution(resolution);
        }
        Ok(())
    }

    fn set_shadow_refresh_frames(&mut self, frames: u32) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_shadow_refresh_frames",
        })?;
        state.sim.set_shadow_refresh_frames(frames)
    }

    fn set_atmosphere(
        &mut self,
        to_sun: Option<glam::Vec3>,
        clear_air_extinction_per_m: Option<f32>,
    ) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_atmosphere",
        })?;
        state.sim.set_atmosphere(to_sun, clear_air_extinction_per_m)
    }

    fn set_cloud_layers(
        &mut self,
        cloud_layers: precip_model::drawing::clouds::CloudLayers,
    ) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_cloud_layers",
        })?;
        state.sim.set_cloud_layers(cloud_layers)
    }

    fn set_fog_layer(
        &mut self,
        fog_layer: Option<precip_model::drawing::fog_layer::FogLayer>,
    ) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_fog_layer",
        })?;
        state.sim.set_fog_layer(fog_layer)
    }

    fn weather(&self) -> Result<Weather, BackendError> {
        Ok(*configured(self.state.as_ref(), "weather")?
            .sim
            .host()
            .weather())
    }

    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError> {
        let state = configured(self.state.as_ref(), "query_beams")?;
        let name = self.gpu.name();
        state.sim.query_beams(
            &mut self.gpu,
            kernels_of(self.kernels.as_ref())?,
            name,
            query,
        )
    }

    /// The camera volume's cross-sections summed on the device (`optics_sums`):
    /// a few hundred bytes read back instead of every particle.
    fn optics(&mut self) -> Result<Optics, BackendError> {
        let state = configured(self.state.as_ref(), "optics")?;
        state
            .sim
            .optics(&mut self.gpu, kernels_of(self.kernels.as_ref())?)
    }

    fn read_particles(&mut self) -> Result<Vec<Particle>, BackendError> {
        let state = configured(self.state.as_ref(), "read_particles")?;
        state.sim.read_particles(&mut self.gpu)
    }

    fn read_cover(&mut self) -> Result<CoverGrid, BackendError> {
        let state = configured(self.state.as_ref(), "read_cover")?;
        state.sim.read_cover(&mut self.gpu)
    }

    fn read_image(&mut self) -> Result<Image, BackendError> {
        let state = configured(self.state.as_ref(), "read_image")?;
        match &state.frame {
            Some(frame) => frame.read_image(&mut self.gpu),
            None => Err(BackendError::NothingRendered),
        }
    }

    fn timings(&mut self) -> Result<Timings, BackendError> {
        let mut passes = match &self.state {
            Some(state) => state.sim.step_timings(&mut self.gpu)?,
            None => Vec::new(),
        };
        if let Some(frame) = self.state.as_ref().and_then(|s| s.frame.as_ref()) {
            passes.extend(frame.timings(&mut self.gpu)?);
        }
        Ok(Timings {
            source: if passes.is_empty() && !self.gpu.has_timestamps() {
                TimingSource::Unavailable
            } else {
                TimingSource::GpuTimestamps
            },
            passes,
        })
    }

    fn drawn(&mut self) -> Result<Option<DrawnCounts>, BackendError> {
        let state = configured(self.state.as_ref(), "drawn")?;
        match &state.frame {
            Some(frame) => frame.drawn(&mut self.gpu).map(Some),
            None => Ok(Some(DrawnCounts::default())),
        }
    }

    fn device_memory(&self) -> Option<DeviceMemory> {
        self.gpu.device_memory()
    }

    fn far_cover_totals(&self) -> Option<precip_model::cover::CoverTotals> {
        self.state.as_ref()?.sim.host().far_cover_totals()
    }

    fn far_snow_line_m(&self) -> Option<f32> {
        self.state.as_ref()?.sim.host().far_snow_line_m()
    }

    fn cover_window(&self) -> Option<precip_model::host::CoverWindow> {
        Some(self.state.as_ref()?.sim.host().cover_window().clone())
    }
}

/// Implements [`Backend`] for a newtype over a [`GpuBackend`] (its field `0`), by
/// handing every call to it, and `Deref`/`DerefMut` to it: how `WgpuBackend` and
/// `VkBackend` get the trait without writing it twice.
#[macro_export]
macro_rules! delegate_backend {
    ($backend:ty, $gpu:ty) => {
        impl ::std::ops::Deref for $backend {
            type Target = $crate::GpuBackend<$gpu>;
            fn deref(&self) -> &Self::Target {
                &self.0
            }
        }
        impl ::std::ops::DerefMut for $backend {
            fn deref_mut(&mut self) -> &mut Self::Target {
                &mut self.0
            }
        }
        impl ::precip_model::Backend for $backend {
            fn info(&self) -> ::precip_model::BackendInfo {
                self.0.info()
            }
            fn configure(
                &mut self,
                setup: &::precip_model::Setup,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.configure(setup)
            }
            fn set_weather(
                &mut self,
                weather: &::precip_model::Weather,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_weather(weather)
            }
            fn set_camera(
                &mut self,
                camera: &::precip_model::Camera,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_camera(camera)
            }
            fn step(&mut self, dt_s: f32) -> Result<(), ::precip_model::BackendError> {
                self.0.step(dt_s)
            }
            fn render(
                &mut self,
                view: &::precip_model::View,
            ) -> Result<(), ::precip_model::BackendError> {
                ::precip_model::Backend::render(&mut self.0, view)
            }
            fn set_particle_resolution(
                &mut self,
                resolution: ::precip_model::ParticleResolution,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_particle_resolution(resolution)
            }
            fn set_shadow_refresh_frames(
                &mut self,
                frames: u32,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_shadow_refresh_frames(frames)
            }
            fn set_fog_layer(
                &mut self,
                fog_layer: Option<::precip_model::drawing::fog_layer::FogLayer>,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_fog_layer(fog_layer)
            }
            fn set_atmosphere(
                &mut self,
                to_sun: Option<::glam::Vec3>,
                clear_air_extinction_per_m: Option<f32>,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_atmosphere(to_sun, clear_air_extinction_per_m)
            }
            fn set_cloud_layers(
                &mut self,
                cloud_layers: ::precip_model::drawing::clouds::CloudLayers,
            ) -> Result<(), ::precip_model::BackendError> {
                self.0.set_cloud_layers(cloud_layers)
            }
            fn weather(&self) -> Result<::precip_model::Weather, ::precip_model::BackendError> {
                self.0.weather()
            }
            fn query_beams(
                &mut self,
                query: &::precip_model::sensors::lidar::BeamQuery,
            ) -> Result<
                Vec<::precip_model::sensors::lidar::BeamReturn>,
                ::precip_model::BackendError,
            > {
                self.0.query_beams(query)
            }
            fn optics(
                &mut self,
            ) -> Result<::precip_model::sensors::optics::Optics, ::precip_model::BackendError>
            {
                self.0.optics()
            }
            fn read_particles(
                &mut self,
            ) -> Result<Vec<::precip_model::Particle>, ::precip_model::BackendError> {
                self.0.read_particles()
            }
            fn read_cover(
                &mut self,
            ) -> Result<::precip_model::cover::CoverGrid, ::precip_model::BackendError> {
                self.0.read_cover()
            }
            fn read_image(&mut self) -> Result<::precip_model::Image, ::precip_model::BackendError> {
                self.0.read_image()
            }
            fn timings(&mut self) -> Result<::precip_model::Timings, ::precip_model::BackendError> {
                self.0.timings()
            }
            fn drawn(
                &mut self,
            ) -> Result<Option<::precip_model::DrawnCounts>, ::precip_model::BackendError> {
                self.0.drawn()
            }
            fn device_memory(&self) -> Option<::precip_model::DeviceMemory> {
                self.0.device_memory()
            }
            fn far_cover_totals(&self) -> Option<::precip_model::cover::CoverTotals> {
                self.0.far_cover_totals()
            }
            fn far_snow_line_m(&self) -> Option<f32> {
                self.0.far_snow_line_m()
            }
            fn cover_window(&self) -> Option<::precip_model::host::CoverWindow> {
                self.0.cover_window()
            }
        }
    };
}
