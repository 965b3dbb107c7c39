//! Drawing a frame on [`VkBackend`]: into the offscreen target (`render`) or a
//! swapchain image (`crate::swapchain`), and the drawn counts.

use ash::vk;

use super::VkBackend;
use crate::commands::{Semaphores, submit_synced};
use crate::render::frame::{FrameResources, SplatSums};
use crate::render::passes::CameraPasses;
use crate::render::scene::SceneGpu;
use crate::render::target::{OFFSCREEN_FORMAT, OffscreenTarget};
use crate::render::{FrameTarget, RenderState, Renderer, record_frame};
use crate::transfer::{FRAMES_IN_FLIGHT, download};
use precip_gpu::frame::FrameHost;
use precip_gpu::frame_resources::FrameBuffer;
use precip_gpu::recipe::FrameDraws;
use precip_model::{BackendError, DrawnCounts, View};

/// A swapchain image to draw into: its framebuffer (made for the camera pass of
/// `format` ending in `PRESENT_SRC_KHR`) and the semaphores of acquire and present.
#[derive(Debug, Clone, Copy)]
pub struct SwapchainFrame {
    /// The swapchain's format.
    pub format: vk::Format,
    /// The image's framebuffer (colour, depth).
    pub framebuffer: vk::Framebuffer,
    /// The framebuffer's depth view.
    pub depth: vk::ImageView,
    /// Signalled when the image is acquired.
    pub acquired: vk::Semaphore,
    /// Signalled when the frame is drawn (present waits on it).
    pub drawn: vk::Semaphore,
}

impl VkBackend {
    /// Makes the renderer on first use, and the camera passes of `format` ending in
    /// `final_layout` with their draws; returns those passes.
    pub(crate) fn prepare_renderer(
        &mut self,
        format: vk::Format,
        final_layout: vk::ImageLayout,
    ) -> Result<CameraPasses, BackendError> {
        if self.renderer.is_none() {
            self.renderer = Some(Renderer::new(&self.hal.device)?);
        }
        let Some(renderer) = self.renderer.as_mut() else {
            return Err(BackendError::NotConfigured {
                operation: "render",
            });
        };
        renderer.prepare(&self.hal.device, format, final_layout)
    }

    /// What the last frame drew: reads the cull's counts back (`Backend::drawn`).
    pub(crate) fn drawn_counts(&mut self) -> Result<DrawnCounts, BackendError> {
        self.settle()?;
        let state = self.state("drawn")?;
        let Some(render) = &state.render else {
            return Ok(DrawnCounts::default());
        };
        let bytes = download(
            &self.hal.device,
            render.frame.buffer(FrameBuffer::Draws)?,
            FrameDraws::BYTES,
        )?;
        Ok(FrameDraws::counts(&bytes))
    }

    /// The frame for `view`: into `swapchain` when given, else into the offscreen
    /// target (re-made, the old one retired, when the size changes).
    pub(crate) fn draw(
        &mut self,
        view: &View,
        swapchain: Option<SwapchainFrame>,
    ) -> Result<(), BackendError> {
        self.hal.device.limits().check_view(view)?;
        self.state("render")?;
        // This frame's uniform block was last used FRAMES_IN_FLIGHT submissions ago.
        self.hal.wait_until(FRAMES_IN_FLIGHT - 1)?;
        let (format, final_layout) = match swapchain {
            Some(s) => (s.format, vk::ImageLayout::PRESENT_SRC_KHR),
            None => (OFFSCREEN_FORMAT, vk::ImageLayout::TRANSFER_SRC_OPTIMAL),
        };
        let passes = self.prepare_renderer(format, final_layout)?;
        let device = &self.hal.device;
        let (Some(renderer), Some(state)) = (self.renderer.as_ref(), self.state.as_mut()) else {
            return Err(BackendError::NotConfigured {
                operation: "render",
            });
        };
        if state.render.is_none() {
            let setup = state.sim.host().setup();
            let settings = &setup.render;
            let scene = match &setup.scene {
                Some(scene) => Some(SceneGpu::upload(
                    device,
                    renderer,
                    scene,
                    settings,
                    &setup.ground,
                )?),
                None => None,
            };
            let frame = match FrameResources::new(device, renderer, &state.sim, setup) {
                Ok(f) => f,
                Err(e) => {
                    if let Some(s) = scene {
                        s.destroy(device);
                    }
                    return Err(e);
                }
            };
            state.render = Some(RenderState {
                scene,
                frame,
                offscreen: None,
                rendered: false,
                host: FrameHost::new(setup),
                frames_drawn: 0,
                splat_sums: None,
            });
        }
        let Some(render) = state.render.as_mut() else {
            return Err(BackendError::NotConfigured {
                operation: "render",
            });
        };
        let size = (view.width_px, view.height_px);
        if swapchain.is_none() && render.offscreen.as_ref().is_none_or(|t| t.size() != size) {
            let new = OffscreenTarget::new(device, passes.scene, size)?;
            if let Some(old) = render.offscreen.replace(new) {
                self.hal
                    .retired
                    .retire(self.hal.submitted, move |d| old.destroy(d));
            }
            render.rendered = false;
        }
        let (framebuffer, depth) = match (swapchain, render.offscreen.as_ref()) {
            (Some(s), _) => (s.framebuffer, s.depth),
            (None, Some(t)) => (t.framebuffer, t.depth.view),
            (None, None) => return Err(BackendError::NothingRendered),
        };
        if render.splat_sums.as_ref().is_none_or(|s| s.size != size) {
            let new = SplatSums::new(device, size)?;
            if let Some(old) = render.splat_sums.replace(new) {
                self.hal
                    .retired
                    .retire(self.hal.submitted, move |d| old.buffer.destroy(d));
            }
        }
        let Some(sums) = render.splat_sums.as_mut() else {
            return Err(BackendError::NothingRendered);
        };
        let zero_splat_sums = (!sums.zeroed).then_some(sums.buffer.raw);
        sums.zeroed = true;
        let decision = render.host.decide(&state.sim, view);
        let (params, draw_shadow) = (decision.params, decision.conditions.shadow_redrawn);
        let slot = render.frames_drawn % FRAMES_IN_FLIGHT as u64;
        let offset = slot * render.frame.params_stride;
        if let Some(sums) = &render.splat_sums {
            // SAFETY: the slot's last frame finished (waited for above); the depth
            // view is the live target's.
            unsafe {
                render.frame.write_splat_sets(
                    device,
                    renderer,
                    &state.sim,
                    slot as usize,
                    (depth, &sums.buffer),
                )?;
            }
        }
        render
            .frame
            .buffer_mut(FrameBuffer::RenderParams)?
            .write(offset as usize, bytemuck::bytes_of(&params))?;
        let target = FrameTarget {
            passes,
            framebuffer,
            size,
            sky: decision.sky_colour,
            splat_sets: (
                render.frame.splat_sets[slot as usize],
                render.frame.resolve_sets[slot as usize],
            ),
            zero_splat_sums,
            draw_shadow,
            detail: (
                view.camera.position_m,
                render
                    .scene
                    .as_ref()
                    .map_or(0.0, |s| s.lod.detail_distance_m(view)),
            ),
        };
        let particle_count = state.sim.particle_count();
        if renderer.draws_for_pass(passes.scene).is_none() {
            return Err(cannot_draw(format));
        }
        let render_ref = &*render;
        let waits =
            swapchain.map(|s| [(s.acquired, vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT)]);
        let signals = swapchain.map(|s| [s.drawn]);
        let semaphores = Semaphores {
            wait: waits.as_ref().map_or(&[], |w| w.as_slice()),
            signal: signals.as_ref().map_or(&[], |s| s.as_slice()),
        };
        let in_flight = submit_synced(device, semaphores, |cb| {
            // SAFETY: `cb` is recording (submit_synced); the renderer, the render
            // state and the framebuffer are live and retired only after this
            // submission finishes; the offset is this slot's aligned block.
            unsafe {
                record_frame(
                    device,
                    renderer,
                    render_ref,
                    cb,
                    target,
                    offset as u32,
                    particle_count,
                );
            }
        })?;
        render.frames_drawn += 1;
        if swapchain.is_none() {
            render.rendered = true;
        }
        self.hal.track(in_flight);
        if let Some(s) = self.renderer.as_mut().and_then(|r| r.stamps.as_mut()) {
            s.written = true;
            s.shadow_drawn = draw_shadow;
        }
        Ok(())
    }
}

/// A frame that cannot be recorded: no pipelines for the target's format (a bug in
/// precip, never an `Ok` with nothing drawn).
fn cannot_draw(format: vk::Format) -> BackendError {
    BackendError::Device {
        backend: crate::error::NAME,
        message: format!(
            "no draw pipelines were made for the target format {format:?} (a bug in precip: please report it)"
        ),
    }
}
