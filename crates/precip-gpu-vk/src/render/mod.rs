//! Drawing on Vulkan: the same frame as the wgpu backend's (`precip_gpu_wgpu::render`),
//! from the same WGSL and the same data: [`record_frame`] executes
//! `precip_gpu::frame::frame_plan` (`FRAME_PASSES`) as wgpu's
//! `encode_frame` does, binding each entry point's groups from
//! `precip_gpu::bind_groups::groups_of`.
//!
//! ## A frame, in one command buffer
//!
//! 1. a barrier: the step's compute writes (particles, cover) and a new splat-sums
//!    buffer's zero fill become visible to the shaders and kernels of the frame;
//! 2. each pass of the recipe between its two timestamps (`TOP_OF_PIPE` before,
//!    `BOTTOM_OF_PIPE` after; a shadow pass the cache skips writes both at once and
//!    is not reported): **cover_texture**, **shadow**, **scene**,
//!    **cull_particles**, **splat_particles**, **particles**. A kernel is followed
//!    by a barrier from its writes to every later kernel, draw and indirect read; a
//!    render pass maps to its pass object by its attachments (the shadow pass; the
//!    camera's clearing `scene` pass, leaving the depth read-only for the splat;
//!    the camera's loading `particles` pass), whose subpass dependencies order it;
//! 3. a barrier: the next frame's compute waits for this frame's shaders (it
//!    rewrites what they read; the resolve's zeroing lands first).
//!
//! Clip space is flipped with a negative viewport height, as wgpu-hal does, so the
//! WGSL runs unchanged and the images agree.
//!
//! ## Objects
//!
//! [`Renderer`] (once per device): set and pipeline layouts, samplers, the flake
//! texture, the shadow pass, the frame's kernels, and per colour format the camera
//! passes and draw pipelines. [`RenderState`] (per configuration): the
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
use glam::Vec3;
use precip_gpu::bind_groups::{self as bg, GroupLayout};
use precip_gpu::frame::{
    AttachmentLoad, DepthTarget, DrawOf, FrameConditions, FrameHost, PassWork, frame_plan,
};
use precip_gpu::frame_resources::{FrameBuffer, FrameTexture};
use precip_gpu::recipe::DispatchCounts;
use precip_gpu::shaders::Program;
use precip_model::BackendError;

use self::frame::FrameResources;
use self::layouts::RenderLayouts;
use self::passes::CameraPasses;
use self::pipelines::{DrawPipelines, KernelPipelines};
use self::samplers::Samplers;
use self::scene::SceneGpu;
use self::stamps::RenderStamps;
use self::target::OffscreenTarget;
use crate::commands::memory_barrier;
use crate::device::Device;
use crate::programs::module;

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
    /// The sun's depth pass.
    pub shadow_pass: vk::RenderPass,
    /// The frame's kernels.
    pub kernels: KernelPipelines,
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
        let render_module = module(device, Program::Render)?;
        let cull_module = module(device, Program::CullParticles)?;
        let shadow_pass = passes::shadow(device)?;
        let kernels = KernelPipelines::new(
            device,
            |program| match program {
                Program::Render => Some(render_module),
                Program::CullParticles => Some(cull_module),
                _ => None,
            },
            &layouts,
        )?;
        Ok(Self {
            stamps: RenderStamps::new(device)?,
            layouts,
            samplers,
            shadow_pass,
            kernels,
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
            let draws = DrawPipelines::new(
                device,
                self.render_module,
                &self.layouts,
                passes.scene,
                self.shadow_pass,
            )?;
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
        self.kernels.destroy(device);
        if let Some(s) = self.stamps {
            s.destroy(device);
        }
        // SAFETY: the device is idle; each object is destroyed once.
        unsafe {
            device.raw.destroy_render_pass(self.shadow_pass, None);
            for c in &self.camera_passes {
                device.raw.destroy_render_pass(c.passes.scene, None);
                device.raw.destroy_render_pass(c.passes.particles, None);
            }
            device.raw.destroy_shader_module(self.render_module, None);
            device.raw.destroy_shader_module(self.cull_module, None);
        }
        self.samplers.destroy(device);
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
    /// The host's side: the shadow map's box and when it is drawn again.
    pub host: FrameHost,
    /// Frames drawn since configure (picks the uniform block).
    pub frames_drawn: u64,
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
    /// The camera's position and how far the displacement's fine triangles are
    /// drawn (`SceneLod`), m.
    pub detail: (Vec3, f32),
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

/// The descriptor set made for table `group` (a mesh's material set is bound by the
/// scene's draw, per mesh).
fn set_of(
    frame: &FrameResources,
    target: &FrameTarget,
    group: &GroupLayout,
) -> Option<vk::DescriptorSet> {
    frame.set(group).or_else(|| {
        bg::lookup(
            group,
            [
                (&bg::SPLAT, target.splat_sets.0),
                (&bg::SPLAT_RESOLVE, target.splat_sets.1),
            ],
        )
    })
}

/// Records one frame into `cb`: `precip_gpu::frame::frame_plan` in order (see the module docs),
/// each bracketed by its timestamps; `params_offset` is the frame's `RenderParams`
/// block.
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
    let (Ok(shadow_map), Ok(draws_buffer)) = (
        frame.image(FrameTexture::ShadowMap),
        frame.buffer(FrameBuffer::Draws),
    ) else {
        return;
    };
    let stamps = renderer.stamps.as_ref();
    let stamp = |i, stage| {
        if let Some(s) = stamps {
            // SAFETY: `cb` is recording (the caller's guarantee); `i` < QUERIES, reset
            // at the start of this frame's recording below.
            unsafe { s.stamp(device, cb, i, stage) };
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
    // The step's compute writes (particles, cover) and the fill, to this frame.
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
    let depth_clear = vk::ClearValue {
        depth_stencil: vk::ClearDepthStencilValue {
            depth: 1.0,
            stencil: 0,
        },
    };
    let sky = target.sky;
    let sky_clear = vk::ClearValue {
        color: vk::ClearColorValue {
            float32: [sky.x, sky.y, sky.z, 1.0],
        },
    };
    // Binds the sets of `groups`, each at its index, the frame's block at its dynamic
    // offset.
    let bind_sets = |bind_point, groups: &[GroupLayout], layout| {
        for (index, group) in groups.iter().enumerate() {
            let Some(set) = set_of(frame, &target, group) else {
                continue;
            };
            // Each dynamic binding is the frame's block.
            let block = [params_offset; 2];
            let offsets = &block[..group.dynamic_bindings().min(2)];
            // SAFETY: `cb` is recording; the set's layout is the layout's set `index`
            // (both from the same table); the offset is that of the frame's block
            // (aligned and in the buffer).
            unsafe {
                device.raw.cmd_bind_descriptor_sets(
                    cb,
                    bind_point,
                    layout,
                    index as u32,
                    &[set],
                    offsets,
                );
            }
        }
    };
    let counts = DispatchCounts {
        particles: particle_count,
        cover_texels: frame.cover_texels,
        wave_cells: 0,
    };
    let conditions = FrameConditions {
        shadow_redrawn: target.draw_shadow,
    };
    for planned in frame_plan(conditions) {
        let (start, end) = (2 * planned.index, 2 * planned.index + 1);
        if !planned.runs {
            // Written, so the pool's results are available; not reported.
            stamp(start, S::TOP_OF_PIPE);
            stamp(end, S::BOTTOM_OF_PIPE);
            continue;
        }
        stamp(start, S::TOP_OF_PIPE);
        match &planned.pass.work {
            PassWork::Kernels(_) => {
                for k in planned.kernels(counts) {
                    let entry = k.kernel.entry_point;
                    let (Some(pipeline), Some(layout)) = (
                        renderer.kernels.get(entry),
                        renderer.layouts.pipeline_layout(entry),
                    ) else {
                        continue;
                    };
                    bind_sets(vk::PipelineBindPoint::COMPUTE, k.groups, layout);
                    let (x, y) = k.workgroups;
                    // SAFETY: `cb` is recording outside a render pass; the
                    // pipeline's sets are bound. Then its writes, to every later
                    // kernel, draw and indirect read of the frame.
                    unsafe {
                        device
                            .raw
                            .cmd_bind_pipeline(cb, vk::PipelineBindPoint::COMPUTE, pipeline);
                        device.raw.cmd_dispatch(cb, x, y, 1);
                        memory_barrier(
                            device,
                            cb,
                            (S::COMPUTE_SHADER, A::SHADER_WRITE),
                            (
                                S::COMPUTE_SHADER
                                    | S::DRAW_INDIRECT
                                    | S::VERTEX_SHADER
                                    | S::FRAGMENT_SHADER,
                                A::SHADER_READ | A::SHADER_WRITE | A::INDIRECT_COMMAND_READ,
                            ),
                        );
                    }
                }
            }
            PassWork::Render(recipe) => {
                // The passes' attachments load and store as the recipe says
                // (`passes.rs` makes them so); each kind maps to its pass object.
                let (render_pass, framebuffer, size, clears): (_, _, _, &[vk::ClearValue]) =
                    match (recipe.depth, recipe.colour) {
                        (DepthTarget::ShadowMap, _) => (
                            renderer.shadow_pass,
                            frame.shadow_framebuffer,
                            shadow_map.size(),
                            &[depth_clear],
                        ),
                        (DepthTarget::Camera, Some(AttachmentLoad::Clear)) => (
                            target.passes.scene,
                            target.framebuffer,
                            target.size,
                            &[sky_clear, depth_clear],
                        ),
                        (DepthTarget::Camera, _) => (
                            target.passes.particles,
                            target.framebuffer,
                            target.size,
                            &[],
                        ),
                    };
                let info = vk::RenderPassBeginInfo::default()
                    .render_pass(render_pass)
                    .framebuffer(framebuffer)
                    .render_area(vk::Rect2D {
                        offset: vk::Offset2D { x: 0, y: 0 },
                        extent: vk::Extent2D {
                            width: size.0,
                            height: size.1,
                        },
                    })
                    .clear_values(clears);
                // SAFETY: `cb` is recording outside a render pass; the framebuffer
                // was made for a pass compatible with `render_pass`, of `size`.
                unsafe {
                    device
                        .raw
                        .cmd_begin_render_pass(cb, &info, vk::SubpassContents::INLINE)
                };
                viewport(device, cb, size);
                for d in planned.draws() {
                    let vs = d.draw.entry_points.0;
                    let (Some(pipeline), Some(layout)) =
                        (draws.get(vs), renderer.layouts.pipeline_layout(vs))
                    else {
                        continue;
                    };
                    // SAFETY: inside the pass; the pipeline was made for a
                    // compatible pass.
                    unsafe {
                        device
                            .raw
                            .cmd_bind_pipeline(cb, vk::PipelineBindPoint::GRAPHICS, pipeline)
                    };
                    bind_sets(vk::PipelineBindPoint::GRAPHICS, d.groups, layout);
                    match d.draw.of {
                        DrawOf::SceneMeshes { materials } => {
                            if let Some(scene) = &state.scene {
                                scene.draw(device, cb, layout, materials, target.detail);
                            }
                        }
                        // SAFETY: inside the pass with the pipeline and its sets bound.
                        DrawOf::FullScreenTriangle => unsafe {
                            device.raw.cmd_draw(cb, 3, 1, 0, 0)
                        },
                        // SAFETY: as above; the draws buffer holds the frame's
                        // `FrameDraws`, made visible to indirect reads by the cull's
                        // barrier.
                        DrawOf::Indirect { offset } => unsafe {
                            device
                                .raw
                                .cmd_draw_indirect(cb, draws_buffer.raw, offset, 1, 16)
                        },
                    }
                }
                // SAFETY: ends the pass begun above (its dependencies make the
                // attachments visible to what reads them next).
                unsafe { device.raw.cmd_end_render_pass(cb) };
            }
        }
        stamp(end, S::BOTTOM_OF_PIPE);
    }
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
