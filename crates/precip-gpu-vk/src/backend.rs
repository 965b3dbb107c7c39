//! [`VkBackend`]: the [`Backend`] on raw Vulkan — configure, weather, camera, step,
//! render (see [`crate::render`]), read-back and timings, with the wgpu backend's
//! kernels and recipe.
//!
//! ## Submissions
//!
//! Steps and frames are submitted without waiting; at most [`FRAMES_IN_FLIGHT`] are
//! pending, and each has its own uniform blocks, so the host writes the next while
//! the GPU runs the last. Objects replaced while work may still use them (a target
//! of another size) are retired and freed when that work has finished
//! ([`crate::retire`]).

use precip_gpu::recipe::dispatch_size;
use precip_gpu::shaders::Program;
use precip_model::cover::CoverGrid;
use precip_model::host::HostState;
use precip_model::sensors::lidar::{BeamQuery, BeamReturn};
use precip_model::{
    Backend, BackendError, BackendInfo, Camera, DeviceMemory, DrawnCounts, Image, Particle, Setup,
    TimingSource, Timings, View, Weather,
};

use std::collections::VecDeque;

use ash::vk;

use crate::commands::{InFlight, compute_barrier, record_dispatch, submit};
use crate::device::Device;
use crate::error::NAME;
use crate::instance::Instance;
use crate::programs::Programs;
use crate::query::Timestamps;
use crate::render::{RenderState, Renderer};
use crate::resources::{COVER_TEXEL_BYTES, FRAMES_IN_FLIGHT, Resources, download, upload_image};
use crate::retire::Retired;

mod draw;
mod present;

pub use draw::SwapchainFrame;
pub use present::Presented;

const PARTICLE_BYTES: u64 = size_of::<Particle>() as u64;

/// A configured simulation: the host state every backend shares, and the device's.
#[derive(Debug)]
struct State {
    host: HostState,
    resources: Resources,
    /// Drawing's resources, made on the first render.
    render: Option<RenderState>,
}

impl State {
    fn destroy(self, device: &Device) {
        self.resources.destroy(device);
        if let Some(r) = self.render {
            r.destroy(device);
        }
    }
}

/// precip on Vulkan.
#[derive(Debug)]
pub struct VkBackend {
    state: Option<State>,
    /// Submitted steps and frames with their numbers, oldest first (at most
    /// `FRAMES_IN_FLIGHT`).
    in_flight: VecDeque<(u64, InFlight)>,
    /// Submissions so far.
    submitted: u64,
    /// Submissions known to be finished.
    completed: u64,
    /// Objects waiting for submissions to finish.
    retired: Retired,
    /// Drawing's layouts and pipelines, made on the first render.
    renderer: Option<Renderer>,
    /// The attached window.
    window: Option<crate::swapchain::WindowSurface>,
    /// Steps submitted since configure (picks the in-flight slot).
    steps_submitted: usize,
    timestamps: Option<Timestamps>,
    programs: Programs,
    device: Device,
}

impl VkBackend {
    /// Opens its own instance and device; `validation` enables the Khronos validation
    /// layer (its messages are kept: [`VkBackend::validation_messages`]).
    pub fn new(validation: bool) -> Result<Self, BackendError> {
        Self::on(Device::new(Instance::new(validation)?)?)
    }

    /// Compiles the programs on `device` and wraps it.
    fn on(device: Device) -> Result<Self, BackendError> {
        let programs = Programs::new(&device)?;
        let timestamps = Timestamps::new(&device)?;
        Ok(Self {
            state: None,
            in_flight: VecDeque::new(),
            submitted: 0,
            completed: 0,
            retired: Retired::default(),
            renderer: None,
            window: None,
            steps_submitted: 0,
            timestamps,
            programs,
            device,
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
        self.device.instance.take_messages()
    }

    /// The list the validation layer writes into; it outlives the backend, so leak
    /// reports at device destruction can be read after a drop.
    #[must_use]
    pub fn validation_log(&self) -> crate::Messages {
        self.device.instance.messages.clone()
    }

    /// The device (its raw `ash::Device`, queue and allocator), for tests that misuse
    /// it on purpose.
    #[cfg(test)]
    #[must_use]
    pub(crate) fn device(&self) -> &Device {
        &self.device
    }

    /// The device's name.
    #[must_use]
    pub fn device_name(&self) -> String {
        self.device.name_of_device()
    }

    /// The most particles one configuration holds.
    #[must_use]
    pub fn max_particles(&self) -> u64 {
        self.device.limits().max_particles()
    }

    /// Waits for every submission in flight.
    fn settle(&mut self) -> Result<(), BackendError> {
        self.wait_until(0)
    }

    /// Waits for the oldest submissions until at most `pending` are in flight.
    fn wait_until(&mut self, pending: usize) -> Result<(), BackendError> {
        while self.in_flight.len() > pending {
            if let Some((number, f)) = self.in_flight.pop_front() {
                f.wait(&self.device)?;
                self.completed = number + 1;
            }
        }
        self.retired.release(&self.device, self.completed);
        Ok(())
    }

    /// Records a submission in flight.
    fn track(&mut self, f: InFlight) {
        self.in_flight.push_back((self.submitted, f));
        self.submitted += 1;
    }

    fn state(&self, operation: &'static str) -> Result<&State, BackendError> {
        self.state
            .as_ref()
            .ok_or(BackendError::NotConfigured { operation })
    }
}

impl Drop for VkBackend {
    fn drop(&mut self) {
        let _ = self.settle();
        let _ = self.device.wait_idle();
        self.retired.release_all(&self.device);
        if let Some(window) = self.window.take() {
            window.destroy(&self.device);
        }
        if let Some(state) = self.state.take() {
            state.destroy(&self.device);
        }
        if let Some(r) = self.renderer.take() {
            r.destroy(&self.device);
        }
        if let Some(t) = self.timestamps.take() {
            t.destroy(&self.device);
        }
        // SAFETY: every submission was waited for and the device is idle (above); the
        // backend is being dropped, so this runs once.
        unsafe { self.programs.destroy(&self.device) };
    }
}

impl Backend for VkBackend {
    fn info(&self) -> BackendInfo {
        BackendInfo {
            name: NAME,
            device: format!("{} (Vulkan)", self.device.name_of_device()),
            max_particles: self.max_particles(),
            renders: true,
        }
    }

    fn configure(&mut self, setup: &Setup) -> Result<(), BackendError> {
        self.device.limits().check_setup(setup)?;
        let host = HostState::configure(setup)?;
        let cover = setup.initial_cover()?;
        let (world, camera) = setup.particle_counts();
        let count = world + camera;
        self.settle()?;
        self.device.wait_idle()?;
        self.retired.release_all(&self.device);
        if let Some(old) = self.state.take() {
            old.destroy(&self.device);
        }
        if let Some(s) = self.renderer.as_mut().and_then(|r| r.stamps.as_mut()) {
            s.written = false;
        }
        let mut resources = Resources::new(
            &self.device,
            &self.programs,
            count,
            &setup.ground,
            &cover,
            &host.frames(),
            host.wind(),
        )?;
        resources
            .step_uniforms
            .write(0, bytemuck::bytes_of(&host.init_block()))?;
        let device = &self.device;
        let programs = &self.programs;
        let r = &resources;
        submit(device, |cb| {
            // SAFETY: `cb` is recording outside a render pass (inside `submit`); the
            // init pipeline was made with the step layout, whose set has one dynamic
            // binding.
            unsafe {
                record_dispatch(
                    device,
                    cb,
                    (programs.init, programs.step_layout),
                    r.step_set,
                    &[0],
                    dispatch_size(count),
                );
            }
        })?
        .wait(device)?;
        if let Some(t) = self.timestamps.as_mut() {
            t.written = 0;
        }
        self.steps_submitted = 0;
        self.state = Some(State {
            host,
            resources,
            render: None,
        });
        Ok(())
    }

    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError> {
        self.state("set_weather")?;
        self.settle()?;
        let device = &self.device;
        let Some(state) = self.state.as_mut() else {
            return Err(BackendError::NotConfigured {
                operation: "set_weather",
            });
        };
        let change = state.host.set_weather(weather)?;
        if change.wind_rebaked {
            upload_image(device, &state.resources.wind, state.host.wind().as_bytes())?;
        }
        state.resources.write_wind_params(&state.host.wind_params())
    }

    fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        self.state
            .as_mut()
            .ok_or(BackendError::NotConfigured {
                operation: "set_camera",
            })?
            .host
            .set_camera(camera)
    }

    fn step(&mut self, dt_s: f32) -> Result<(), BackendError> {
        let steps = self.state("step")?.host.substeps(dt_s)?;
        let count = steps.blocks.len() as u32;
        // This step's slot of uniform blocks and queries was last used FRAMES_IN_FLIGHT
        // steps ago: wait for that submission only.
        self.wait_until(FRAMES_IN_FLIGHT - 1)?;
        let slot = self.steps_submitted % FRAMES_IN_FLIGHT;
        let device = &self.device;
        let programs = &self.programs;
        let timestamps = self.timestamps.as_ref();
        let Some(state) = self.state.as_mut() else {
            return Err(BackendError::NotConfigured { operation: "step" });
        };
        let stride = state.resources.uniform_stride as usize;
        let base = state.resources.slot_base(slot) as usize;
        for (k, blocks) in steps.blocks.iter().enumerate() {
            state
                .resources
                .step_uniforms
                .write(base + k * stride, bytemuck::bytes_of(&blocks.step))?;
            state
                .resources
                .cover_uniforms
                .write(base + k * stride, bytemuck::bytes_of(&blocks.cover))?;
        }
        let r = &state.resources;
        let mut written = 0;
        let first_query = slot as u32 * crate::query::QUERY_COUNT;
        let slot_base = r.slot_base(slot);
        let in_flight = submit(device, |cb| {
            let stamp = |written: &mut u32| {
                if let Some(t) = timestamps {
                    // SAFETY: `cb` is recording; the query index is below QUERY_COUNT.
                    unsafe {
                        device.raw.cmd_write_timestamp(
                            cb,
                            vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                            t.pool,
                            first_query + *written,
                        )
                    };
                    *written += 1;
                }
            };
            if let Some(t) = timestamps {
                // SAFETY: `cb` is recording; resets the queries this step writes.
                unsafe {
                    device.raw.cmd_reset_query_pool(
                        cb,
                        t.pool,
                        first_query,
                        crate::query::QUERY_COUNT,
                    )
                };
            }
            stamp(&mut written);
            for k in 0..count {
                let offset = (slot_base + u64::from(k) * r.uniform_stride) as u32;
                for (kernel, pipeline) in &programs.substep {
                    let (layout, set) = match kernel.program {
                        Program::CoverUpdate => (programs.cover_layout, r.cover_set),
                        _ => (programs.step_layout, r.step_set),
                    };
                    let (x, y) = dispatch_size(kernel.over.invocations(r.dispatch_counts()));
                    // SAFETY: `cb` is recording; pipeline, layout and set match; the
                    // dynamic offset is aligned and within the uniform buffer.
                    unsafe {
                        device
                            .raw
                            .cmd_bind_pipeline(cb, vk::PipelineBindPoint::COMPUTE, *pipeline);
                        device.raw.cmd_bind_descriptor_sets(
                            cb,
                            vk::PipelineBindPoint::COMPUTE,
                            layout,
                            0,
                            &[set],
                            &[offset],
                        );
                        device.raw.cmd_dispatch(cb, x, y, 1);
                    }
                    // SAFETY: `cb` is recording, outside a render pass (inside `submit`).
                    unsafe { compute_barrier(device, cb) };
                    stamp(&mut written);
                }
            }
        })?;
        self.track(in_flight);
        self.steps_submitted += 1;
        if let Some(t) = self.timestamps.as_mut() {
            t.written = written;
            t.slot = slot;
        }
        if let Some(state) = self.state.as_mut() {
            state.host.advance(&steps);
        }
        Ok(())
    }

    fn render(&mut self, view: &View) -> Result<(), BackendError> {
        self.draw(view, None)
    }

    fn weather(&self) -> Result<Weather, BackendError> {
        Ok(*self.state("weather")?.host.weather())
    }

    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError> {
        let beams = query.validate()?;
        self.settle()?;
        let state = self.state("query_beams")?;
        let r = &state.resources;
        let params = query.params(&beams, r.particle_count, &state.host.setup().ground);
        let hits = crate::beams::query_beams(&self.device, &self.programs, r, &params, &beams)?;
        let air = state.host.unresolved_air();
        query.answer(NAME, &beams, &hits, state.host.weather(), &air)
    }

    fn read_particles(&mut self) -> Result<Vec<Particle>, BackendError> {
        self.settle()?;
        let r = &self.state("read_particles")?.resources;
        let bytes = download(
            &self.device,
            &r.particles,
            u64::from(r.particle_count) * PARTICLE_BYTES,
        )?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    fn read_cover(&mut self) -> Result<CoverGrid, BackendError> {
        self.settle()?;
        let state = self.state("read_cover")?;
        let r = &state.resources;
        let bytes = download(
            &self.device,
            &r.cover,
            u64::from(r.cover_texel_count) * COVER_TEXEL_BYTES,
        )?;
        Ok(CoverGrid {
            frame: state.host.setup().cover.frame,
            texels: bytemuck::pod_collect_to_vec(&bytes),
        })
    }

    fn read_image(&mut self) -> Result<Image, BackendError> {
        self.settle()?;
        let state = self.state("read_image")?;
        match state.render.as_ref() {
            Some(RenderState {
                offscreen: Some(target),
                rendered: true,
                ..
            }) => target.read(&self.device),
            _ => Err(BackendError::NothingRendered),
        }
    }

    fn timings(&mut self) -> Result<Timings, BackendError> {
        self.settle()?;
        let mut timings = match &self.timestamps {
            Some(t) => t.read(&self.device)?,
            None => Timings {
                source: TimingSource::Unavailable,
                passes: Vec::new(),
            },
        };
        if let Some(stamps) = self.renderer.as_ref().and_then(|r| r.stamps.as_ref()) {
            timings.passes.extend(stamps.read(&self.device)?);
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
        let report = self.device.allocator.lock().ok()?.generate_report();
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
