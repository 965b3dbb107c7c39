//! Drawing on Vulkan: the same frame as the wgpu backend's (`precip_gpu_wgpu::render`),
//! from the same WGSL and the same recipe (`precip_model::gpu::{render_passes,
//! CULL_PASSES, render_bindings, cull_bindings, SceneVertex}`).
//!
//! ## A frame, in one command buffer
//!
//! 1. a barrier: the step's compute writes (particles, cover) and a new splat-sums
//!    buffer's zero fill become visible to the shaders and kernels of the frame;
//!    Then **cover_texture**: the cover texels into the two filtered images the
//!    surfaces sample (kept in `GENERAL`), and a barrier to the shaders;
//! 2. **shadow** — render pass with the shadow map, the displaced scene from the sun;
//! 3. **scene** — a render pass into the target (offscreen image or swapchain image)
//!    that clears it and draws every mesh, leaving the depth read-only;
//! 4. **cull_particles** — the three kernels, barriers between them;
//! 5. **splat_particles** — the splat kernel (reads the depth, adds to the sums),
//!    then a barrier to the indirect draws, vertex pulling and the resolve;
//! 6. **particles** — a second pass that loads the target, blends the splat sums
//!    (zeroing them) and draws snow and rain by `vkCmdDrawIndirect` (passes as
//!    wgpu's, so each has its timestamps);
//! 7. a barrier: the next frame's compute waits for this frame's shaders (it
//!    rewrites what they read; the resolve's zeroing lands first).
//!
//! Clip space is flipped with a negative viewport height, as wgpu-hal does, so the
//! WGSL runs unchanged and the images agree. Timestamps bracket each pass.
//!
//! ## Objects
//!
//! [`Renderer`] (once per device): set and pipeline layouts, samplers, the flake
//! texture, the shadow pass and pipeline, the cull kernels, and per colour format
//! the camera passes and draw pipelines. [`RenderState`] (per configuration): the
//! scene, [`frame::FrameResources`], the offscreen target.

pub mod frame;
pub mod layouts;
pub mod passes;
pub mod pipelines;
pub mod samplers;
pub mod scene;
pub mod stamps;
pub mod target;

use ash::vk;
use glam::{UVec3, Vec3};
use precip_model::BackendError;
use precip_model::drawing::{FLAKE_TEXTURE_PX, snowflake_opacity};
use precip_model::gpu::{DispatchOver, FrameDraws, dispatch_size};
use precip_model::shaders::Program;

use self::frame::FrameResources;
use self::layouts::RenderLayouts;
use self::passes::CameraPasses;
use self::pipelines::{CullPipelines, DrawPipelines, shadow_pipeline};
use self::samplers::Samplers;
use self::scene::SceneGpu;
use self::stamps::RenderStamps;
use self::target::OffscreenTarget;
use crate::commands::{compute_barrier, memory_barrier};
use crate::device::Device;
use crate::image::{Image, ImageSpec};
use crate::programs::module;
use crate::resources::upload_image;

/// The camera passes of one colour format and final layout.
#[derive(Debug)]
struct CameraPass {
    format: vk::Format,
    final_layout: vk::ImageLayout,
    passes: CameraPasses,
}

/// Layouts, passes and pipelines of one device.
#[derive(Debug)]
pub struct Renderer {
    /// Set and pipeline layouts.
    pub layouts: RenderLayouts,
    /// The samplers.
    pub samplers: Samplers,
    /// The flake's opacity (R8).
    pub flake: Image,
    /// The sun's depth pass.
    pub shadow_pass: vk::RenderPass,
    /// Its pipeline.
    pub shadow: vk::Pipeline,
    /// The cull kernels.
    pub cull: CullPipelines,
    /// Frame timestamps, when the queue has them.
    pub stamps: Option<RenderStamps>,
    render_module: vk::ShaderModule,
    cull_module: vk::ShaderModule,
    camera_passes: Vec<CameraPass>,
    draws: Vec<(vk::Format, DrawPipelines)>,
}

impl Renderer {
    /// Compiles the render and cull programs and makes what every frame shares.
    pub fn new(device: &Device) -> Result<Self, BackendError> {
        let layouts = RenderLayouts::new(device)?;
        let samplers = Samplers::new(device)?;
        let flake = Image::new(
            device,
            &ImageSpec {
                name: "flake opacity",
                extent: UVec3::new(FLAKE_TEXTURE_PX, FLAKE_TEXTURE_PX, 1),
                format: vk::Format::R8_UNORM,
                usage: vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            },
        )?;
        upload_image(device, &flake, &snowflake_opacity(FLAKE_TEXTURE_PX))?;
        let render_module = module(device, Program::Render)?;
        let cull_module = module(device, Program::CullParticles)?;
        let shadow_pass = passes::shadow(device)?;
        let shadow = shadow_pipeline(device, render_module, &layouts, shadow_pass)?;
        let cull = CullPipelines::new(device, cull_module, render_module, &layouts)?;
        Ok(Self {
            stamps: RenderStamps::new(device)?,
            layouts,
            samplers,
            flake,
            shadow_pass,
            shadow,
            cull,
            render_module,
            cull_module,
            camera_passes: Vec::new(),
            draws: Vec::new(),
        })
    }

    /// The camera passes into `format` ending in `final_layout`, and the draws for
    /// that format; made on first use.
    pub fn prepare(
        &mut self,
        device: &Device,
        format: vk::Format,
        final_layout: vk::ImageLayout,
    ) -> Result<CameraPasses, BackendError> {
        let passes = match self
            .camera_passes
            .iter()
            .find(|c| c.format == format && c.final_layout == final_layout)
        {
            Some(c) => c.passes,
            None => {
                let passes = passes::camera(device, format, final_layout)?;
                self.camera_passes.push(CameraPass {
                    format,
                    final_layout,
                    passes,
                });
                passes
            }
        };
        if !self.draws.iter().any(|(f, _)| *f == format) {
            let draws =
                DrawPipelines::new(device, self.render_module, &self.layouts, passes.scene)?;
            self.draws.push((format, draws));
        }
        Ok(passes)
    }

    /// The draws for `format` ([`Renderer::prepare`] first).
    #[must_use]
    pub fn draws(&self, format: vk::Format) -> Option<&DrawPipelines> {
        self.draws
            .iter()
            .find(|(f, _)| *f == format)
            .map(|(_, d)| d)
    }

    /// Destroys everything (the device must be idle).
    pub fn destroy(self, device: &Device) {
        for (_, d) in self.draws {
            d.destroy(device);
        }
        self.cull.destroy(device);
        if let Some(s) = self.stamps {
            s.destroy(device);
        }
        // SAFETY: the device is idle; each object is destroyed once.
        unsafe {
            device.raw.destroy_pipeline(self.shadow, None);
            device.raw.destroy_render_pass(self.shadow_pass, None);
            for c in &self.camera_passes {
                device.raw.destroy_render_pass(c.passes.scene, None);
                device.raw.destroy_render_pass(c.passes.particles, None);
            }
            device.raw.destroy_shader_module(self.render_module, None);
            device.raw.destroy_shader_module(self.cull_module, None);
        }
        self.samplers.destroy(device);
        self.flake.destroy(device);
        self.layouts.destroy(device);
    }
}

/// What drawing holds for one configuration.
#[derive(Debug)]
pub struct RenderState {
    /// The uploaded scene, if the setup has one.
    pub scene: Option<SceneGpu>,
    /// Uniform blocks, cull lists, shadow map, descriptor sets.
    pub frame: FrameResources,
    /// The offscreen target of the last `render`.
    pub offscreen: Option<OffscreenTarget>,
    /// Whether `offscreen` holds a frame.
    pub rendered: bool,
    /// The box the shadow map encloses (the scene's bounds, computed once), m.
    pub shadow_bounds_m: (Vec3, Vec3),
    /// Frames drawn since configure (picks the uniform block).
    pub frames_drawn: u64,
    /// Whether a frame redraws the shadow map.
    pub shadow_cache: precip_model::shadow_cache::ShadowCache,
    /// The splat's sums, for the last frame's size.
    pub splat_sums: Option<frame::SplatSums>,
}

impl RenderState {
    /// Frees everything (no pending work may use it).
    pub fn destroy(self, device: &Device) {
        if let Some(s) = self.scene {
            s.destroy(device);
        }
        self.frame.destroy(device);
        if let Some(t) = self.offscreen {
            t.destroy(device);
        }
        if let Some(s) = self.splat_sums {
            s.buffer.destroy(device);
        }
    }
}

/// Where a frame goes.
#[derive(Debug, Clone, Copy)]
pub struct FrameTarget {
    /// The camera passes (its format's, ending in the target's layout).
    pub passes: CameraPasses,
    /// Colour and depth of the target.
    pub framebuffer: vk::Framebuffer,
    /// Width, height, px.
    pub size: (u32, u32),
    /// The sky's colour (linear), the clear colour.
    pub sky: Vec3,
    /// This frame's splat and resolve sets (set 2 of each).
    pub splat_sets: (vk::DescriptorSet, vk::DescriptorSet),
    /// The splat sums to fill with zeros first (new sums), if any.
    pub zero_splat_sums: Option<vk::Buffer>,
    /// Draw the shadow map (else the last one stands: `ShadowCache`).
    pub draw_shadow: bool,
}

/// The viewport of `size`, y flipped (WGSL's clip space, as wgpu-hal).
fn viewport(device: &Device, cb: vk::CommandBuffer, (width, height): (u32, u32)) {
    let viewport = vk::Viewport {
        x: 0.0,
        y: height as f32,
        width: width as f32,
        height: -(height as f32),
        min_depth: 0.0,
        max_depth: 1.0,
    };
    let scissor = vk::Rect2D {
        offset: vk::Offset2D { x: 0, y: 0 },
        extent: vk::Extent2D { width, height },
    };
    // SAFETY: `cb` is recording; negative heights are core since Vulkan 1.1.
    unsafe {
        device.raw.cmd_set_viewport(cb, 0, &[viewport]);
        device.raw.cmd_set_scissor(cb, 0, &[scissor]);
    }
}

/// Records one frame (see the module docs) into `cb`; `params_offset` is the
/// frame's `RenderParams` block.
///
/// # Safety
/// - `cb` is a command buffer of `device` in the recording state, outside a render
///   pass.
/// - `renderer`, `state` and `target`'s framebuffer are live objects of `device`, and
///   stay so until the submission of `cb` has finished.
/// - `params_offset` is aligned and leaves a whole `RenderParams` in the buffer.
pub unsafe fn record_frame(
    device: &Device,
    renderer: &Renderer,
    state: &RenderState,
    cb: vk::CommandBuffer,
    target: FrameTarget,
    params_offset: u32,
    particle_count: u32,
) {
    use vk::AccessFlags as A;
    use vk::PipelineStageFlags as S;
    let Some(draws) = renderer.draws_for_pass(target.passes.scene) else {
        return;
    };
    let frame = &state.frame;
    let layout = renderer.layouts.draw_layout;
    let stamps = renderer.stamps.as_ref();
    let stamp = |i| {
        if let Some(s) = stamps {
            // SAFETY: `cb` is recording (the caller's guarantee); `i` < QUERIES, reset
            // at the start of this frame's recording below.
            unsafe { s.stamp(device, cb, i) };
        }
    };
    if let Some(s) = stamps {
        // SAFETY: `cb` is recording, outside a render pass (the caller's guarantee).
        unsafe { s.reset(device, cb) };
    }
    if let Some(sums) = target.zero_splat_sums {
        // SAFETY: `cb` is recording outside a render pass; the buffer is live and was
        // made with TRANSFER_DST; the barrier below orders the fill before the splat.
        unsafe { device.raw.cmd_fill_buffer(cb, sums, 0, vk::WHOLE_SIZE, 0) };
    }
    // SAFETY: `cb` is recording, outside a render pass (the caller's guarantee).
    unsafe {
        memory_barrier(
            device,
            cb,
            (
                S::COMPUTE_SHADER | S::TRANSFER,
                A::SHADER_WRITE | A::TRANSFER_WRITE,
            ),
            (
                S::VERTEX_SHADER | S::FRAGMENT_SHADER | S::COMPUTE_SHADER,
                A::SHADER_READ | A::SHADER_WRITE,
            ),
        );
    }
    stamp(0);
    let shadow_px = frame.shadow_map.size();
    let depth_clear = vk::ClearValue {
        depth_stencil: vk::ClearDepthStencilValue {
            depth: 1.0,
            stencil: 0,
        },
    };
    let begin = |pass, framebuffer, size: (u32, u32), clears: &[vk::ClearValue]| {
        let info = vk::RenderPassBeginInfo::default()
            .render_pass(pass)
            .framebuffer(framebuffer)
            .render_area(vk::Rect2D {
                offset: vk::Offset2D { x: 0, y: 0 },
                extent: vk::Extent2D {
                    width: size.0,
                    height: size.1,
                },
            })
            .clear_values(clears);
        // SAFETY: `cb` is recording outside a render pass; the framebuffer was made
        // for a pass compatible with `pass`, of `size`.
        unsafe {
            device
                .raw
                .cmd_begin_render_pass(cb, &info, vk::SubpassContents::INLINE)
        };
        viewport(device, cb, size);
    };
    // The frame's and the cull's set 0 take the frame's dynamic offset (`dynamic`).
    let dynamic = [params_offset];
    let bind_sets =
        |bind_point, pipeline_layout, first: u32, sets: &[vk::DescriptorSet], offsets: &[u32]| {
            // SAFETY: `cb` is recording; the sets match the layout from `first`; the
            // offsets are those of their dynamic descriptors (the frame's block: aligned
            // and in the buffer).
            unsafe {
                device.raw.cmd_bind_descriptor_sets(
                    cb,
                    bind_point,
                    pipeline_layout,
                    first,
                    sets,
                    offsets,
                );
            }
        };
    let dispatch = |pipeline, (x, y): (u32, u32)| {
        // SAFETY: `cb` is recording outside a render pass; the pipeline's sets are
        // bound.
        unsafe {
            device
                .raw
                .cmd_bind_pipeline(cb, vk::PipelineBindPoint::COMPUTE, pipeline);
            device.raw.cmd_dispatch(cb, x, y, 1);
        }
    };
    bind_sets(
        vk::PipelineBindPoint::COMPUTE,
        renderer.layouts.cover_texture_layout,
        0,
        &[frame.cover_texture_set],
        &[],
    );
    dispatch(
        renderer.cull.cover_texture,
        dispatch_size(frame.cover_texels),
    );
    // SAFETY: `cb` is recording, outside a render pass (the caller's guarantee).
    unsafe {
        memory_barrier(
            device,
            cb,
            (S::COMPUTE_SHADER, A::SHADER_WRITE),
            (
                S::VERTEX_SHADER | S::FRAGMENT_SHADER | S::COMPUTE_SHADER,
                A::SHADER_READ,
            ),
        );
    }
    stamp(1);
    if target.draw_shadow {
        begin(
            renderer.shadow_pass,
            frame.shadow_framebuffer,
            shadow_px,
            &[depth_clear],
        );
        if let Some(scene) = &state.scene {
            // SAFETY: inside the shadow pass; the shadow pipeline was made for it.
            unsafe {
                device
                    .raw
                    .cmd_bind_pipeline(cb, vk::PipelineBindPoint::GRAPHICS, renderer.shadow)
            };
            bind_sets(
                vk::PipelineBindPoint::GRAPHICS,
                layout,
                0,
                &[frame.frame_set],
                &dynamic,
            );
            scene.draw(device, cb, layout, false);
        }
        // SAFETY: ends the pass begun above.
        unsafe { device.raw.cmd_end_render_pass(cb) };
    }
    stamp(2);
    let sky = target.sky;
    let clears = [
        vk::ClearValue {
            color: vk::ClearColorValue {
                float32: [sky.x, sky.y, sky.z, 1.0],
            },
        },
        depth_clear,
    ];
    begin(
        target.passes.scene,
        target.framebuffer,
        target.size,
        &clears,
    );
    if let Some(scene) = &state.scene {
        // SAFETY: inside the camera pass; the scene pipeline was made for a
        // compatible pass.
        unsafe {
            device
                .raw
                .cmd_bind_pipeline(cb, vk::PipelineBindPoint::GRAPHICS, draws.scene)
        };
        bind_sets(
            vk::PipelineBindPoint::GRAPHICS,
            layout,
            0,
            &[frame.frame_set, frame.light_set],
            &dynamic,
        );
        scene.draw(device, cb, layout, true);
    }
    // SAFETY: ends the scene pass (its dependency makes the depth visible to the
    // splat kernel, read-only).
    unsafe { device.raw.cmd_end_render_pass(cb) };
    stamp(3);
    let particle_groups = dispatch_size(particle_count);
    bind_sets(
        vk::PipelineBindPoint::COMPUTE,
        renderer.layouts.cull_layout,
        0,
        &[frame.cull_set],
        &dynamic,
    );
    for (kernel, pipeline) in &renderer.cull.kernels {
        let groups = match kernel.over {
            DispatchOver::OneWorkgroup => (1, 1),
            _ => particle_groups,
        };
        dispatch(*pipeline, groups);
        // SAFETY: `cb` is recording, outside a render pass (between the dispatches).
        unsafe { compute_barrier(device, cb) };
    }
    stamp(4);
    bind_sets(
        vk::PipelineBindPoint::COMPUTE,
        renderer.layouts.splat_layout,
        0,
        &[frame.frame_set, frame.light_set, target.splat_sets.0],
        &dynamic,
    );
    dispatch(renderer.cull.splat, particle_groups);
    // SAFETY: `cb` is recording, outside a render pass (the caller's guarantee).
    unsafe {
        memory_barrier(
            device,
            cb,
            (S::COMPUTE_SHADER, A::SHADER_WRITE),
            (
                S::DRAW_INDIRECT | S::VERTEX_SHADER | S::FRAGMENT_SHADER,
                A::INDIRECT_COMMAND_READ | A::SHADER_READ | A::SHADER_WRITE,
            ),
        );
    }
    stamp(5);
    begin(
        target.passes.particles,
        target.framebuffer,
        target.size,
        &[],
    );
    bind_sets(
        vk::PipelineBindPoint::GRAPHICS,
        layout,
        0,
        &[frame.frame_set, frame.light_set],
        &dynamic,
    );
    // SAFETY: inside the camera pass; the resolve pipeline was made for a compatible
    // pass; its layout shares sets 0 and 1 with the draws' (compatible), set 2 is
    // bound here.
    unsafe {
        device
            .raw
            .cmd_bind_pipeline(cb, vk::PipelineBindPoint::GRAPHICS, draws.splat_resolve);
    }
    bind_sets(
        vk::PipelineBindPoint::GRAPHICS,
        renderer.layouts.resolve_layout,
        2,
        &[target.splat_sets.1],
        &[],
    );
    // SAFETY: inside the camera pass; the particle pipelines were made for a
    // compatible pass; the draws buffer holds two 16-byte `DrawArgs`, made visible to
    // indirect reads by the barrier above.
    unsafe {
        device.raw.cmd_draw(cb, 3, 1, 0, 0);
        device
            .raw
            .cmd_bind_pipeline(cb, vk::PipelineBindPoint::GRAPHICS, draws.snow);
        device
            .raw
            .cmd_draw_indirect(cb, frame.draws.raw, FrameDraws::SNOW_OFFSET, 1, 16);
        device
            .raw
            .cmd_bind_pipeline(cb, vk::PipelineBindPoint::GRAPHICS, draws.rain);
        device
            .raw
            .cmd_draw_indirect(cb, frame.draws.raw, FrameDraws::RAIN_OFFSET, 1, 16);
        device.raw.cmd_end_render_pass(cb);
    }
    stamp(6);
    // The next frame's step and splat rewrite what these shaders read, and the
    // resolve's zeroing writes must land before the next splat adds.
    // SAFETY: `cb` is recording, outside a render pass (the caller's guarantee).
    unsafe {
        memory_barrier(
            device,
            cb,
            (
                S::DRAW_INDIRECT | S::VERTEX_SHADER | S::FRAGMENT_SHADER,
                A::SHADER_WRITE,
            ),
            (
                S::COMPUTE_SHADER | S::TRANSFER,
                A::SHADER_READ | A::SHADER_WRITE | A::TRANSFER_WRITE,
            ),
        );
    }
}

impl Renderer {
    /// The draws whose format `pass` renders to.
    pub(crate) fn draws_for_pass(&self, pass: vk::RenderPass) -> Option<&DrawPipelines> {
        let format = self
            .camera_passes
            .iter()
            .find(|c| c.passes.scene == pass)?
            .format;
        self.draws(format)
    }
}
