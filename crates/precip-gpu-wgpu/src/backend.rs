//! [`WgpuBackend`]: the [`Backend`] over wgpu: configure, weather, step, render (see
//! [`crate::render`]), read-back and timings.

use precip_gpu::frame::FrameHost;
use precip_gpu::frame_resources::{FrameBuffer, FrameTexture};
use precip_gpu::recipe::FrameDraws;
use precip_gpu::{Kernels, Simulation};
use precip_model::cover::CoverGrid;
use precip_model::sensors::lidar::{BeamQuery, BeamReturn};
use precip_model::sensors::optics::Optics;
use precip_model::{
    Backend, BackendError, BackendInfo, Camera, DeviceMemory, DrawnCounts, Image, Particle, Setup,
    TimingSource, Timings, View, Weather,
};

use crate::device::GpuDevice;
use crate::error::NAME;
use crate::gpu::{Hal, scoped};
use crate::render::frame::FrameResources;
use crate::render::scene::SceneGpu;
use crate::render::stamps::RenderStamps;
use crate::render::target::{ColourTarget, DepthBuffer, OFFSCREEN_FORMAT, read_texture};
use crate::render::{FrameTarget, RenderState, Renderer, encode_frame};
use crate::transfer::read_buffer;

/// A configured simulation: the host state every backend shares, and the device's.
#[derive(Debug)]
struct State {
    sim: Simulation<Hal>,
    /// Drawing's resources, made on the first render.
    render: Option<RenderState>,
}

/// precip on wgpu.
#[derive(Debug)]
pub struct WgpuBackend {
    gpu: GpuDevice,
    hal: Hal,
    kernels: Kernels<Hal>,
    render_stamps: Option<RenderStamps>,
    renderer: Option<Renderer>,
    state: Option<State>,
}

impl WgpuBackend {
    /// Opens a device on the default adapter.
    pub fn new() -> Result<Self, BackendError> {
        Self::with_device(GpuDevice::new_headless()?)
    }

    /// Opens a device on `adapter`.
    pub fn on_adapter(adapter: &wgpu::Adapter) -> Result<Self, BackendError> {
        Self::with_device(GpuDevice::open(adapter)?)
    }

    /// Runs on a device the caller owns (its compute programs are compiled here).
    pub fn with_device(gpu: GpuDevice) -> Result<Self, BackendError> {
        let mut hal = Hal::new(gpu.clone());
        let kernels = Kernels::new(&mut hal)?;
        let render_stamps = RenderStamps::new(&gpu);
        Ok(Self {
            gpu,
            hal,
            kernels,
            render_stamps,
            renderer: None,
            state: None,
        })
    }

    /// The device.
    #[must_use]
    pub fn device(&self) -> &GpuDevice {
        &self.gpu
    }

    /// The most particles one configuration holds on this device.
    #[must_use]
    pub fn max_particles(&self) -> u64 {
        self.gpu.limits().max_particles()
    }

    fn state_mut(&mut self, operation: &'static str) -> Result<&mut State, BackendError> {
        self.state
            .as_mut()
            .ok_or(BackendError::NotConfigured { operation })
    }
}

impl WgpuBackend {
    /// Draws a frame for `view` into the caller's `target` (a window surface's texture
    /// view, of `view`'s size, made with `RENDER_ATTACHMENT`); the caller presents it.
    /// `read_image` still reads the last offscreen `render`.
    pub fn render_to(
        &mut self,
        view: &View,
        target: &wgpu::TextureView,
    ) -> Result<(), BackendError> {
        let texture = target.texture();
        let size = texture.size();
        if (size.width, size.height) != (view.width_px, view.height_px) {
            return Err(BackendError::InvalidView(format!(
                "the target is {}×{} px but the view asks for {}×{}: give the view the target's size",
                size.width, size.height, view.width_px, view.height_px
            )));
        }
        if !texture
            .usage()
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        {
            return Err(BackendError::InvalidView(
                "the target texture lacks RENDER_ATTACHMENT usage".into(),
            ));
        }
        self.draw(view, Some((target, texture.format())))
    }

    /// The cover's three filtered textures as the last frame wrote them (tests and
    /// tools): per texel `[depth mm, SWE mm, peak SWE mm, wetness, accumulation mask,
    /// melt mask, age days, puddle ratio, sand and dust kg/m², the surface's roughness
    /// length under snow m, 0, 0]`, rows of the
    /// cover grid in order; `None` before a frame.
    pub fn read_cover_textures(&mut self) -> Result<Option<Vec<[f32; 12]>>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_cover_textures",
        })?;
        let Some(render) = &state.render else {
            return Ok(None);
        };
        let halves = |t| -> Result<Vec<f32>, BackendError> {
            let image = read_texture(&self.gpu, t)?;
            Ok(image
                .rgba8
                .chunks_exact(2)
                .map(|h| f16_to_f32(u16::from_le_bytes([h[0], h[1]])))
                .collect())
        };
        let [a, b, c] = [
            FrameTexture::CoverA,
            FrameTexture::CoverB,
            FrameTexture::CoverC,
        ]
        .map(|t| render.frame.texture(t));
        let (a, b, c) = (halves(a?)?, halves(b?)?, halves(c?)?);
        Ok(Some(
            a.chunks_exact(4)
                .zip(b.chunks_exact(4))
                .zip(c.chunks_exact(4))
                .map(|((a, b), c)| {
                    [
                        a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3], c[0], c[1], c[2], c[3],
                    ]
                })
                .collect(),
        ))
    }

    /// The frame: into `external` when given, else into the offscreen target.
    fn draw(
        &mut self,
        view: &View,
        external: Option<(&wgpu::TextureView, wgpu::TextureFormat)>,
    ) -> Result<(), BackendError> {
        self.gpu.limits().check_view(view)?;
        let gpu = self.gpu.clone();
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "render",
        })?;
        let format = external.map_or(OFFSCREEN_FORMAT, |(_, f)| f);
        let renderer = self
            .renderer
            .get_or_insert_with(|| Renderer::new(&gpu.device));
        scoped(&gpu, "preparing to render", || {
            renderer.prepare_format(&gpu.device, format);
        })?;
        if state.render.is_none() {
            let setup = state.sim.host().setup();
            let settings = &setup.render;
            let scene = match &setup.scene {
                Some(scene) => Some(scoped(&gpu, "uploading the scene", || {
                    SceneGpu::upload(&gpu, &renderer.layouts, scene, settings, &setup.ground)
                })??),
                None => None,
            };
            let frame = scoped(&gpu, "preparing to render", || {
                FrameResources::new(&gpu, &renderer.layouts, &state.sim, setup)
            })??;
            state.render = Some(RenderState {
                scene,
                frame,
                offscreen: None,
                depth: None,
                rendered: false,
                host: FrameHost::new(setup),
            });
        }
        let Some(render) = state.render.as_mut() else {
            return Err(BackendError::NotConfigured {
                operation: "render",
            });
        };
        let size = (view.width_px, view.height_px);
        if external.is_none() && render.offscreen.as_ref().is_none_or(|t| t.size != size) {
            render.offscreen = Some(ColourTarget::new(&gpu, size.0, size.1));
        }
        if render.depth.as_ref().is_none_or(|d| d.size != size) {
            let depth = scoped(&gpu, "preparing the target", || {
                DepthBuffer::new(&gpu, &renderer.layouts, size, &render.frame, &state.sim)
            })??;
            render.depth = Some(depth);
        }
        let decision = render.host.decide(&state.sim, view);
        let (params, draw_shadow) = (decision.params, decision.conditions.shadow_redrawn);
        if let Some(s) = self.render_stamps.as_mut() {
            s.shadow_drawn = draw_shadow;
        }
        let stamps = self.render_stamps.as_ref();
        let render_ref = &*render;
        let detail = (
            view.camera.position_m,
            render_ref
                .scene
                .as_ref()
                .map_or(0.0, |s| s.lod.detail_distance_m(view)),
        );
        let colour = match (external, render_ref.offscreen.as_ref()) {
            (Some((view, _)), _) => view,
            (None, Some(target)) => &target.view,
            (None, None) => return Err(cannot_draw("the offscreen target is missing")),
        };
        let (Some(draws), Some(depth)) = (renderer.draws(format), render_ref.depth.as_ref()) else {
            return Err(cannot_draw(&format!(
                "no draw pipelines or depth buffer for the target format {format:?}"
            )));
        };
        let params_buffer = render_ref.frame.buffer(FrameBuffer::RenderParams)?;
        scoped(&gpu, "render", || {
            gpu.queue
                .write_buffer(params_buffer, 0, bytemuck::bytes_of(&params));
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("precip frame"),
                });
            encode_frame(
                &mut encoder,
                draws,
                &renderer.kernels,
                render_ref,
                FrameTarget {
                    colour,
                    depth,
                    sky: decision.sky_colour,
                    draw_shadow,
                    detail,
                },
                stamps,
                state.sim.particle_count(),
            );
            if let Some(s) = stamps {
                s.resolve(&mut encoder);
            }
            gpu.queue.submit([encoder.finish()]);
        })?;
        if let Some(s) = self.render_stamps.as_mut() {
            s.written = true;
        }
        if external.is_none() {
            render.rendered = true;
        }
        let _ = gpu.device.poll(wgpu::PollType::Poll);
        Ok(())
    }
}

impl Backend for WgpuBackend {
    fn info(&self) -> BackendInfo {
        BackendInfo {
            name: NAME,
            device: self.gpu.describe(),
            max_particles: self.max_particles(),
            renders: true,
        }
    }

    fn configure(&mut self, setup: &Setup) -> Result<(), BackendError> {
        let prepared = Simulation::prepare(&self.hal, setup)?;
        if let Some(old) = self.state.take() {
            old.sim.destroy(&mut self.hal);
        }
        let sim = Simulation::configure(&mut self.hal, &self.kernels, prepared)?;
        self.gpu.wait()?;
        if let Some(t) = self.hal.timestamps.as_mut() {
            t.written = 0;
        }
        self.state = Some(State { sim, render: None });
        if let Some(s) = self.render_stamps.as_mut() {
            s.written = false;
        }
        Ok(())
    }

    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError> {
        let state = self.state.as_mut().ok_or(BackendError::NotConfigured {
            operation: "set_weather",
        })?;
        state.sim.set_weather(&mut self.hal, weather)
    }

    fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        self.state_mut("set_camera")?.sim.set_camera(camera)
    }

    fn step(&mut self, dt_s: f32) -> Result<(), BackendError> {
        let state = self
            .state
            .as_mut()
            .ok_or(BackendError::NotConfigured { operation: "step" })?;
        state.sim.step(&mut self.hal, &self.kernels, dt_s)
    }

    fn render(&mut self, view: &View) -> Result<(), BackendError> {
        self.draw(view, None)
    }

    fn weather(&self) -> Result<Weather, BackendError> {
        self.state
            .as_ref()
            .map(|s| *s.sim.host().weather())
            .ok_or(BackendError::NotConfigured {
                operation: "weather",
            })
    }

    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "query_beams",
        })?;
        state
            .sim
            .query_beams(&mut self.hal, &self.kernels, NAME, query)
    }

    /// The camera volume's cross-sections summed on the device (`optics_sums`):
    /// a few hundred bytes read back instead of every particle.
    fn optics(&mut self) -> Result<Optics, BackendError> {
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "optics",
        })?;
        state.sim.optics(&mut self.hal, &self.kernels)
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
        let state = self.state.as_ref().ok_or(BackendError::NotConfigured {
            operation: "read_image",
        })?;
        match state.render.as_ref() {
            Some(RenderState {
                offscreen: Some(target),
                rendered: true,
                ..
            }) => target.read(&self.gpu),
            _ => Err(BackendError::NothingRendered),
        }
    }

    fn timings(&mut self) -> Result<Timings, BackendError> {
        let mut timings = Timings {
            source: if self.hal.timestamps.is_some() {
                TimingSource::GpuTimestamps
            } else {
                TimingSource::Unavailable
            },
            passes: Simulation::step_timings(&mut self.hal)?,
        };
        if let Some(stamps) = &self.render_stamps {
            timings.passes.extend(stamps.read(&self.gpu)?);
            if !timings.passes.is_empty() {
                timings.source = TimingSource::GpuTimestamps;
            }
        }
        Ok(timings)
    }

    fn drawn(&mut self) -> Result<Option<DrawnCounts>, BackendError> {
        let state = self
            .state
            .as_ref()
            .ok_or(BackendError::NotConfigured { operation: "drawn" })?;
        let Some(render) = &state.render else {
            return Ok(Some(DrawnCounts::default()));
        };
        let bytes = read_buffer(
            &self.gpu,
            render.frame.buffer(FrameBuffer::Draws)?,
            FrameDraws::BYTES,
        )?;
        Ok(Some(FrameDraws::counts(&bytes)))
    }

    /// Precip's allocations and wgpu's fixed ones; not wgpu's indirect-call
    /// validation pool, whose 1 MiB buffers wgpu adds while more frames are in flight
    /// than it has buffers for and keeps for reuse (bounded by the frames in flight,
    /// freed with the device): its size follows the host's timing, not our frames.
    fn device_memory(&self) -> Option<DeviceMemory> {
        self.gpu.device.generate_allocator_report().map(|r| {
            let (allocations, allocated_bytes) = r
                .allocations
                .iter()
                .filter(|a| !a.name.starts_with(WGPU_INDIRECT_VALIDATION_POOL))
                .fold((0, 0), |(n, bytes), a| (n + 1, bytes + a.size));
            DeviceMemory {
                allocations,
                allocated_bytes,
                reserved_bytes: r.total_reserved_bytes,
            }
        })
    }
}

/// How wgpu names the buffers of its indirect-call validation pool.
const WGPU_INDIRECT_VALIDATION_POOL: &str = "(wgpu internal) Indirect";

/// A frame that cannot be drawn (a bug in precip): a typed error, never an `Ok` with
/// nothing drawn.
fn cannot_draw(why: &str) -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: format!("cannot draw the frame: {why} (a bug in precip: please report it)"),
    }
}

/// An IEEE half (binary16) as `f32`.
fn f16_to_f32(bits: u16) -> f32 {
    let sign = if bits & 0x8000 == 0 { 1.0 } else { -1.0 };
    let exponent = i32::from((bits >> 10) & 0x1f);
    let mantissa = f32::from(bits & 0x3ff);
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        31 if mantissa == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

#[cfg(test)]
mod tests {
    use super::f16_to_f32;

    #[test]
    fn halves_decode() {
        assert!((f16_to_f32(0x3c00) - 1.0).abs() < f32::EPSILON);
        assert!((f16_to_f32(0xc000) + 2.0).abs() < f32::EPSILON);
        assert!((f16_to_f32(0x7bff) - 65504.0).abs() < f32::EPSILON);
        assert!((f16_to_f32(0x0001) - 2f32.powi(-24)).abs() < f32::EPSILON);
        assert!(f16_to_f32(0x7c00).is_infinite() && f16_to_f32(0x7e00).is_nan());
    }
}
