//! Drawing on wgpu: the scene with its snow cover, then the precipitation, built on
//! the GPU from the particle buffer (docs/model.md §5, docs/architecture.md §2 step 4).
//!
//! ## A frame
//!
//! [`encode_frame`] walks `precip_gpu::frame::frame_plan` (`FRAME_PASSES`)
//! (`precip_gpu::frame`): each pass a compute pass or a render pass with its
//! two timestamps, each kernel and draw with the pipeline made from its recipe entry
//! and the groups of its entry point (`precip_gpu::bind_groups::groups_of`).
//! Vulkan twin: `precip_gpu_vk::render::record_frame`.
//!
//! 0. **cover_texture** — the cover texels into two filtered textures
//!    (`precip_gpu::recipe::COVER_TEXTURE_PASS`) that the surfaces sample.
//! 1. **shadow** — the scene's displaced geometry from the sun into a depth map.
//! 2. **scene** — every mesh, displaced by the snow depth and shaded with the cover
//!    (coverage by the threshold masks, wet darkening, exposure to the sky from the
//!    ground map, slope and eligibility), Blinn–Phong with the shadow map, fog.
//! 3. **cull_particles** — three compute kernels (`precip_gpu::recipe::CULL_PASSES`)
//!    test each particle against the view cone, compact the drawn ones into a snow
//!    list and a rain list in buffer order, and write two indirect draws' instance
//!    counts. Culled particles cost no vertex or raster work; with culling off the
//!    same lists hold every particle, so the images match. Sub-pixel particles are in
//!    neither list.
//! 4. **splat_particles** — one kernel (`precip_gpu::recipe::SPLAT_PASS`) adds each
//!    sub-pixel particle's light to the splat sums at its pixel, tested against the
//!    scene's depth (render_splat.wgsl).
//! 5. **particles** — the splat sums blended over the scene (and zeroed), then snow
//!    sprites (4-vertex strips) and rain tetrahedra (12-vertex lists) by indirect
//!    draws, pulled from the particle buffer in the vertex shader, blended over the
//!    scene with its depth.
//!
//! Nothing per particle crosses to the CPU. Pipelines are made per colour format on
//! first use (the offscreen `Rgba8UnormSrgb` target, or a window surface's format
//! through [`crate::WgpuBackend::render_to`]).

pub mod frame;
pub mod layouts;
pub mod pipelines;
pub mod scene;
pub mod stamps;
pub mod target;

use std::collections::HashMap;

use glam::Vec3;

use self::frame::FrameResources;
use self::layouts::RenderLayouts;
use self::pipelines::{DrawPipelines, KernelPipelines};
use self::scene::SceneGpu;
use self::stamps::RenderStamps;
use self::target::{ColourTarget, DepthBuffer};
use precip_gpu::bind_groups::GroupLayout;
use precip_gpu::frame::{
    AttachmentLoad, DepthTarget, DrawOf, FrameConditions, FrameHost, PassWork, frame_plan,
};
use precip_gpu::frame_resources::{FrameBuffer, FrameTexture};
use precip_gpu::recipe::DispatchCounts;

/// Layouts and pipelines of one device.
#[derive(Debug)]
pub struct Renderer {
    /// Bind group layouts.
    pub layouts: RenderLayouts,
    /// The frame's kernels.
    pub kernels: KernelPipelines,
    draws: HashMap<wgpu::TextureFormat, DrawPipelines>,
}

impl Renderer {
    /// Makes the layouts and the cull kernels.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Self {
        let layouts = RenderLayouts::new(device);
        let kernels = KernelPipelines::new(device, &layouts);
        Self {
            layouts,
            kernels,
            draws: HashMap::new(),
        }
    }

    /// Makes the draws for `format` if they are not made yet.
    pub fn prepare_format(&mut self, device: &wgpu::Device, format: wgpu::TextureFormat) {
        if !self.draws.contains_key(&format) {
            let pipelines = DrawPipelines::new(device, &self.layouts, format);
            self.draws.insert(format, pipelines);
        }
    }

    /// The draws for `format` ([`Renderer::prepare_format`] first).
    #[must_use]
    pub fn draws(&self, format: wgpu::TextureFormat) -> Option<&DrawPipelines> {
        self.draws.get(&format)
    }
}

/// What drawing holds for one configuration.
#[derive(Debug)]
pub struct RenderState {
    /// The uploaded scene, if the setup has one.
    pub scene: Option<SceneGpu>,
    /// Uniforms, cull lists, shadow map, bind groups.
    pub frame: FrameResources,
    /// The offscreen target of the last `render`.
    pub offscreen: Option<ColourTarget>,
    /// The depth buffer of the last frame's size.
    pub depth: Option<DepthBuffer>,
    /// Whether `offscreen` holds a frame.
    pub rendered: bool,
    /// The host's side: the shadow map's box and when it is drawn again.
    pub host: FrameHost,
}

/// Where a frame goes.
#[derive(Debug, Clone, Copy)]
pub struct FrameTarget<'a> {
    /// The colour view.
    pub colour: &'a wgpu::TextureView,
    /// A depth buffer of the same size, with its splat sums.
    pub depth: &'a DepthBuffer,
    /// The sky's colour (linear), the clear colour.
    pub sky: Vec3,
    /// Draw the shadow map (else the last one stands: `ShadowCache`).
    pub draw_shadow: bool,
    /// The camera's position and how far the displacement's fine triangles are
    /// drawn (`SceneLod`), m.
    pub detail: (Vec3, f32),
}

/// Writes of timed pass `pass` (its index in `TIMED_RENDER_PASSES`): queries `2·pass`
/// before, `2·pass + 1` after.
fn pass_writes(stamps: Option<&RenderStamps>, pass: u32) -> Option<(&wgpu::QuerySet, u32)> {
    stamps.map(|s| (&s.set, 2 * pass))
}

fn render_stamps(
    stamps: Option<&RenderStamps>,
    pass: u32,
) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
    pass_writes(stamps, pass).map(|(query_set, i)| wgpu::RenderPassTimestampWrites {
        query_set,
        beginning_of_pass_write_index: Some(i),
        end_of_pass_write_index: Some(i + 1),
    })
}

fn compute_stamps(
    stamps: Option<&RenderStamps>,
    pass: u32,
) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
    pass_writes(stamps, pass).map(|(query_set, i)| wgpu::ComputePassTimestampWrites {
        query_set,
        beginning_of_pass_write_index: Some(i),
        end_of_pass_write_index: Some(i + 1),
    })
}

/// The bind group made for table `group` (a mesh's material group is bound by the
/// scene's draw, per mesh).
fn bind_group_of<'a>(
    frame: &'a FrameResources,
    depth: &'a DepthBuffer,
    group: &GroupLayout,
) -> Option<&'a wgpu::BindGroup> {
    frame.group(group).or_else(|| depth.group(group))
}

/// The dynamic offsets of `group`: the frame's block, at 0, for each dynamic binding
/// (each is the frame's `RenderParams`).
fn dynamic_offsets(group: &GroupLayout) -> &'static [u32] {
    &[0, 0][..group.dynamic_bindings().min(2)]
}

/// Binds each of `groups` that the frame holds at its index.
macro_rules! bind_groups {
    ($pass:expr, $frame:expr, $depth:expr, $groups:expr) => {
        for (index, group) in $groups.iter().enumerate() {
            if let Some(bind_group) = bind_group_of($frame, $depth, group) {
                $pass.set_bind_group(index as u32, bind_group, dynamic_offsets(group));
            }
        }
    };
}

fn load_op<V>(load: AttachmentLoad, clear: V) -> wgpu::LoadOp<V> {
    match load {
        AttachmentLoad::Clear => wgpu::LoadOp::Clear(clear),
        AttachmentLoad::Load => wgpu::LoadOp::Load,
    }
}

/// Records one frame into `encoder`: `precip_gpu::frame::frame_plan` in order (see the module
/// docs), each bracketed by its timestamps.
pub fn encode_frame(
    encoder: &mut wgpu::CommandEncoder,
    draws: &DrawPipelines,
    kernels: &KernelPipelines,
    state: &RenderState,
    target: FrameTarget<'_>,
    stamps: Option<&RenderStamps>,
    particle_count: u32,
) {
    let frame = &state.frame;
    let depth = target.depth;
    let (Ok(shadow_view), Ok(draws_buffer)) = (
        frame.view(FrameTexture::ShadowMap),
        frame.buffer(FrameBuffer::Draws),
    ) else {
        return;
    };
    let counts = DispatchCounts {
        particles: particle_count,
        cover_texels: frame.cover_texels,
        wave_cells: 0,
    };
    let conditions = FrameConditions {
        shadow_redrawn: target.draw_shadow,
    };
    for planned in frame_plan(conditions).filter(|p| p.runs) {
        let (pass, index) = (planned.pass, planned.index);
        match &pass.work {
            PassWork::Kernels(_) => {
                let mut compute = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(pass.name),
                    timestamp_writes: compute_stamps(stamps, index),
                });
                for k in planned.kernels(counts) {
                    let Some(pipeline) = kernels.get(k.kernel.entry_point) else {
                        continue;
                    };
                    compute.set_pipeline(pipeline);
                    bind_groups!(compute, frame, depth, k.groups);
                    compute.dispatch_workgroups(k.workgroups.0, k.workgroups.1, 1);
                }
            }
            PassWork::Render(recipe) => {
                let sky = target.sky;
                let sky = wgpu::Color {
                    r: f64::from(sky.x),
                    g: f64::from(sky.y),
                    b: f64::from(sky.z),
                    a: 1.0,
                };
                let colour = recipe.colour.map(|load| {
                    Some(wgpu::RenderPassColorAttachment {
                        view: target.colour,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: load_op(load, sky),
                            store: wgpu::StoreOp::Store,
                        },
                    })
                });
                let depth_view = match recipe.depth {
                    DepthTarget::ShadowMap => shadow_view,
                    DepthTarget::Camera => &depth.view,
                };
                let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(pass.name),
                    color_attachments: match &colour {
                        Some(c) => std::slice::from_ref(c),
                        None => &[],
                    },
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: depth_view,
                        depth_ops: Some(wgpu::Operations {
                            load: load_op(recipe.depth_load, 1.0),
                            store: if recipe.depth_stored {
                                wgpu::StoreOp::Store
                            } else {
                                wgpu::StoreOp::Discard
                            },
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: render_stamps(stamps, index),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                for d in planned.draws() {
                    let Some(pipeline) = draws.get(d.draw.entry_points.0) else {
                        continue;
                    };
                    render.set_pipeline(pipeline);
                    bind_groups!(render, frame, depth, d.groups);
                    match d.draw.of {
                        DrawOf::SceneMeshes { materials } => {
                            if let Some(scene) = &state.scene {
                                let (camera_m, distance_m) = target.detail;
                                scene.draw(&mut render, materials, camera_m, distance_m);
                            }
                        }
                        DrawOf::FullScreenTriangle => render.draw(0..3, 0..1),
                        DrawOf::Indirect { offset } => render.draw_indirect(draws_buffer, offset),
                    }
                }
            }
        }
    }
}
