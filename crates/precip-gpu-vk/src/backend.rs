//! [`VkBackend`]: the [`Backend`] on raw Vulkan — configure, weather, camera, step,
//! render (see [`crate::render`]), read-back and timings, with the wgpu backend's
//! kernels and recipe.
//!
//! ## Submissions
//!
//! Steps and frames are submitted without waiting ([`crate::gpu`]); configure,
//! weather changes, steps and beam queries are the executor's
//! (`precip_gpu::Simulation`), run over [`Hal`].

use precip_gpu::{Gpu, Kernels, Simulation};
use precip_model::cover::CoverGrid;
use precip_model::sensors::lidar::{BeamQuery, BeamReturn};
use precip_model::sensors::optics::Optics;
use precip_model::{
    Backend, BackendError, BackendInfo, Camera, DeviceMemory, DrawnCounts, Image, Particle, Setup,
    TimingSource, Timings, View, Weather,
};

use crate::device::Device;
use crate::error::NAME;
use crate::gpu::Hal;
use crate::instance::Instance;
use crate::render::{RenderState, Renderer};

mod draw;
mod present;

pub use draw::SwapchainFrame;
pub use present::Presented;

/// A configured simulation: the host state every backend shares, and the device's.
#[derive(Debug)]
struct State {
    sim: Simulation<Hal>,
    /// Drawing's resources, made on the first render.
    render: Option<RenderState>,
}

impl State {
    fn destroy(self, hal: &mut Hal) {
        self.sim.destroy(hal);
        if let Some(r) = self.render {
            r.destroy(&hal.device);
        }
    }
}

/// precip on Vulkan.
#[derive(Debug)]
pub struct VkBackend {
    state: Option<State>,
    /// Drawing's layouts and pipelines, made on the first render.
    renderer: Option<Renderer>,
    /// The attached window.
    window: Option<crate::swapchain::WindowSurface>,
    kernels: Option<Kernels<Hal>>,
    hal: Hal,
}

impl VkBackend {
    /// Opens its own instance and device; `validation` enables the Khronos validation
    /// layer (its messages are kept: [`VkBackend::validation_messages`]).
    pub fn new(validation: bool) -> Result<Self, BackendError> {
        Self::on(Device::new(Instance::new(validation)?)?)
    }

    /// Compiles the kernels on `device` and wraps it.
    fn on(device: Device) -> Result<Self, BackendError> {
        let mut hal = Hal::new(device)?;
        let kernels = match Kernels::new(&mut hal) {
            Ok(k) => k,
            Err(e) => {
                // SAFETY: nothing was submitted; runs once.
                unsafe { hal.destroy() };
                return Err(e);
            }
        };
        Ok(Self {
            state: None,
            renderer: None,
            window: None,
            kernels: Some(kernels),
            hal,
        })
    }

    /// Runs on a device the caller owns (an engine's renderer); see
    /// [`Device::external`] for what the caller must guarantee.
    ///
    /// # Safety
    /// As [`Device::external`].
    pub unsafe fn on_external_device(
        external: crate::device::ExternalDevice,
    ) -> Result<Self, BackendError> {
        // SAFETY: forwarded to the caller.
        let device = unsafe { Device::external(external) }?;
        Self::on(device)
    }

    /// The validation layer's warnings and errors so far, taken.
    #[must_use]
    pub fn validation_messages(&self) -> Vec<String> {
        self.hal.device.instance.take_messages()
    }

    /// The list the validation layer writes into; it outlives the backend, so leak
    /// reports at device destruction can be read after a drop.
    #[must_use]
    pub fn validation_log(&self) -> crate::Messages {
        self.hal.device.instance.messages.clone()
    }

    /// The device (its raw `ash::Device`, queue and allocator), for tests that misuse
    /// it on purpose.
    #[cfg(test)]
    #[must_use]
    pub(crate) fn device(&self) -> &Device {
        &self.hal.device
    }

    /// The device's name.
    #[must_use]
    pub fn device_name(&self) -> String {
        self.hal.device.name_of_device()
    }

    /// The most particles one configuration holds.
    #[must_use]
    pub fn max_particles(&self) -> u64 {
        self.hal.device.limits().max_particles()
    }

    /// Waits for every submission in flight.
    fn settle(&mut self) -> Result<(), BackendError> {
        self.hal.settle()
    }

    fn state(&self, operation: &'static str) -> Result<&State, BackendError> {
        self.state
            .as_ref()
            .ok_or(BackendError::NotConfigured { operation })
    }
}

/// The kernels are taken only by `drop`: a call after it is a bug.
fn kernels_gone() -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: "the kernels are gone (a bug in precip: please report it)".into(),
    }
}

impl Drop for VkBackend {
    fn drop(&mut self) {
        let _ = self.settle();
        let _ = self.hal.device.wait_idle();
        self.hal.retired.release_all(&self.hal.device);
        if let Some(window) = self.window.take() {
            window.destroy(&self.hal.device);
        }
        if let Some(state) = self.state.take() {
            state.destroy(&mut self.hal);
        }
        if let Some(r) = self.renderer.take() {
            r.destroy(&self.hal.device);
        }
        if let Some(k) = self.kernels.take() {
            k.destroy(&mut self.hal);
        }
        // SAFETY: every submission was waited for and the device is idle (above); the
        // backend is being dropped, so this runs once.
        unsafe { self.hal.destroy() };
    }
}

impl Backend for VkBackend {
    fn info(&self) -> BackendInfo {
        BackendInfo {
            name: NAME,
            device: format!("{} (Vulkan)", self.hal.device.name_of_device()),
            max_particles: self.max_particles(),
            renders: true,
        }
    }

    fn configure(&mut self, setup: &Setup) -> Result<(), BackendError> {
        let prepared = Simulation::prepare(&self.hal, setup)?;
        self.settle()?;
        self.hal.device.wait_idle()?;
        self.hal.retired.release_all(&self.hal.device);
        if let Some(old) = self.state.take() {
            old.destroy(&mut self.hal);
        }
        if let Some(s) = self.renderer.as_mut().and_then(|r| r.stamps.as_mut()) {
            s.written = false;
        }
        let kernels = self.kernels.as_ref().ok_or_else(kernels_gone)?;
        let sim = Simulation::configure(&mut self.hal, kernels, prepared)?;
        if let Some(t) = self.hal.timestamps.as_mut() {
            t.written = 0;
        }
        self.state = Some(State { sim, render: None });
        Ok(())
    }

    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_weather",
        })?;
        state.sim.set_weather(&mut self.hal, weather)
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
        let kernels = self.kernels.as_ref().ok_or_else(kernels_gone)?;
        let state = self
            .state
            .as_mut()
            .ok_or(BackendError::NotConfigured { operation: "step" })?;
        state.sim.step(&mut self.hal, kernels, dt_s)
    }

    fn render(&mut self, view: &View) -> Result<(), BackendError> {
        self.draw(view, None)
    }

    fn weather(&self) -> Result<Weather, BackendError> {
        Ok(*self.state("weather")?.sim.host().weather())
    }

    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "query_beams",
        })?;
        let kernels = self.kernels.as_ref().ok_or_else(kernels_gone)?;
        state.sim.query_beams(&mut self.hal, kernels, NAME, query)
    }

    /// The camera volume's cross-sections summed on the device (`optics_sums`):
    /// a few hundred bytes read back instead of every particle.
    fn optics(&mut self) -> Result<Optics, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "optics",
        })?;
        let kernels = self.kernels.as_ref().ok_or_else(kernels_gone)?;
        state.sim.optics(&mut self.hal, kernels)
    }

    fn read_particles(&mut self) -> Result<Vec<Particle>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_particles",
        })?;
        state.sim.read_particles(&mut self.hal)
    }

    fn read_cover(&mut self) -> Result<CoverGrid, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_cover",
        })?;
        state.sim.read_cover(&mut self.hal)
    }

    fn read_image(&mut self) -> Result<Image, BackendError> {
        self.settle()?;
        let state = self.state("read_image")?;
        match state.render.as_ref() {
            Some(RenderState {
                offscreen: Some(target),
                rendered: true,
                ..
            }) => target.read(&self.hal.device),
            _ => Err(BackendError::NothingRendered),
        }
    }

    fn timings(&mut self) -> Result<Timings, BackendError> {
        self.settle()?;
        let mut timings = Timings {
            source: if self.hal.timestamps.is_some() {
                TimingSource::GpuTimestamps
            } else {
                TimingSource::Unavailable
            },
            passes: Simulation::step_timings(&mut self.hal)?,
        };
        if let Some(stamps) = self.renderer.as_ref().and_then(|r| r.stamps.as_ref()) {
            timings.passes.extend(stamps.read(&self.hal.device)?);
            if !timings.passes.is_empty() {
                timings.source = TimingSource::GpuTimestamps;
            }
        }
        Ok(timings)
    }

    fn drawn(&mut self) -> Result<Option<DrawnCounts>, BackendError> {
        self.drawn_counts().map(Some)
    }

    fn device_memory(&self) -> Option<DeviceMemory> {
        let report = self.hal.device.allocator.lock().ok()?.generate_report();
        Some(DeviceMemory {
            allocations: report.allocations.len() as u64,
            allocated_bytes: report.total_allocated_bytes,
            reserved_bytes: report.total_capacity_bytes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::VkBackend;

    #[test]
    fn the_messenger_reports_a_misuse() {
        // A negative control: the validation-clean checks of the tests mean something
        // only if a real validation error reaches the log.
        let vk = match VkBackend::new(true) {
            Ok(vk) => vk,
            Err(e) => {
                assert!(
                    std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
                    "PRECIP_REQUIRE_GPU=1 but {e}"
                );
                eprintln!("SKIPPED the_messenger_reports_a_misuse: {e}");
                return;
            }
        };
        let device = &vk.device().raw;
        let info = ash::vk::BufferCreateInfo::default()
            .size(0)
            .usage(ash::vk::BufferUsageFlags::STORAGE_BUFFER);
        // SAFETY: deliberately invalid (size 0) to provoke the validation layer;
        // lavapipe still returns a handle or an error, and either is cleaned up here.
        let made = unsafe { device.create_buffer(&info, None) };
        if let Ok(buffer) = made {
            // SAFETY: the buffer is unused and destroyed once.
            unsafe { device.destroy_buffer(buffer, None) };
        }
        let messages = vk.validation_messages();
        assert!(
            messages.iter().any(|m| m.contains("size")),
            "the layer should report a zero-size buffer: {messages:?}"
        );
    }
}
