//! Drawing on wgpu: the scene with its snow cover, then the precipitation, built on
//! the GPU from the particle buffer (MODEL.md §5, DESIGN.md §2 step 4).
//!
//! ## A frame
//!
//! 0. **cover_texture** — the cover texels into two filtered textures
//!    (`precip_model::gpu::COVER_TEXTURE_PASS`) that the surfaces sample.
//! 1. **shadow** — the scene's displaced geometry from the sun into a depth map.
//! 2. **scene** — every mesh, displaced by the snow depth and shaded with the cover
//!    (coverage by the threshold masks, wet darkening, exposure to the sky from the
//!    ground map, slope and eligibility), Blinn–Phong with the shadow map, fog.
//! 3. **cull_particles** — three compute kernels (`precip_model::gpu::CULL_PASSES`)
//!    test each particle against the view cone, compact the drawn ones into a snow
//!    list and a rain list in buffer order, and write two indirect draws' instance
//!    counts. Culled particles cost no vertex or raster work; with culling off the
//!    same lists hold every particle, so the images match. Sub-pixel particles are in
//!    neither list.
//! 4. **splat_particles** — one kernel (`precip_model::gpu::SPLAT_PASS`) adds each
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
use self::pipelines::{CullPipelines, DrawPipelines};
use self::scene::SceneGpu;
use self::stamps::RenderStamps;
use self::target::{ColourTarget, DepthBuffer};
use precip_model::gpu::dispatch_size;
use precip_model::gpu::{DispatchOver, FrameDraws};
use precip_model::shadow_cache::ShadowCache;

/// Layouts and pipelines of one device.
#[derive(Debug)]
pub struct Renderer {
    /// Bind group layouts.
    pub layouts: RenderLayouts,
    /// The cull kernels.
    pub cull: CullPipelines,
    draws: HashMap<wgpu::TextureFormat, DrawPipelines>,
}

impl Renderer {
    /// Makes the layouts and the cull kernels.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Self {
        let layouts = RenderLayouts::new(device);
        let cull = CullPipelines::new(device, &layouts);
        Self {
            layouts,
            cull,
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
    /// The box the shadow map encloses (the scene's bounds, computed once), m.
    pub shadow_bounds_m: (Vec3, Vec3),
    /// Whether a frame redraws the shadow map.
    pub shadow_cache: ShadowCache,
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

/// Records one frame (see the module docs) into `encoder`.
pub fn encode_frame(
    encoder: &mut wgpu::CommandEncoder,
    draws: &DrawPipelines,
    cull: &CullPipelines,
    state: &RenderState,
    target: FrameTarget<'_>,
    stamps: Option<&RenderStamps>,
    particle_count: u32,
) {
    let frame = &state.frame;
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("precip cover_texture"),
            timestamp_writes: compute_stamps(stamps, 0),
        });
        pass.set_pipeline(&cull.cover_texture);
        pass.set_bind_group(0, &frame.cover_texture_group, &[]);
        let (x, y) = dispatch_size(frame.cover_texels);
        pass.dispatch_workgroups(x, y, 1);
    }
    if target.draw_shadow {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("precip shadow"),
            color_attachments: &[],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &frame.shadow_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: render_stamps(stamps, 1),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(scene) = &state.scene {
            pass.set_pipeline(&draws.shadow);
            pass.set_bind_group(0, &frame.frame_group, &[0]);
            scene.draw(&mut pass, false);
        }
    }
    let sky = target.sky;
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("precip scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target.colour,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: f64::from(sky.x),
                        g: f64::from(sky.y),
                        b: f64::from(sky.z),
                        a: 1.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &target.depth.view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: render_stamps(stamps, 2),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(scene) = &state.scene {
            pass.set_pipeline(&draws.scene);
            pass.set_bind_group(0, &frame.frame_group, &[0]);
            pass.set_bind_group(1, &frame.light_group, &[]);
            scene.draw(&mut pass, true);
        }
    }
    let particle_groups = dispatch_size(particle_count);
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("precip cull_particles"),
            timestamp_writes: compute_stamps(stamps, 3),
        });
        pass.set_bind_group(0, &frame.cull_group, &[0]);
        for (kernel, pipeline) in &cull.kernels {
            pass.set_pipeline(pipeline);
            let (x, y) = match kernel.over {
                DispatchOver::OneWorkgroup => (1, 1),
                _ => particle_groups,
            };
            pass.dispatch_workgroups(x, y, 1);
        }
    }
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("precip splat_particles"),
            timestamp_writes: compute_stamps(stamps, 4),
        });
        pass.set_pipeline(&cull.splat);
        pass.set_bind_group(0, &frame.frame_group, &[0]);
        pass.set_bind_group(1, &frame.light_group, &[]);
        pass.set_bind_group(2, &target.depth.splat_group, &[]);
        pass.dispatch_workgroups(particle_groups.0, particle_groups.1, 1);
    }
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("precip particles"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target.colour,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &target.depth.view,
            depth_ops: Some(wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Discard,
            }),
            stencil_ops: None,
        }),
        timestamp_writes: render_stamps(stamps, 5),
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_bind_group(0, &frame.frame_group, &[0]);
    pass.set_bind_group(1, &frame.light_group, &[]);
    pass.set_pipeline(&draws.splat_resolve);
    pass.set_bind_group(2, &target.depth.resolve_group, &[]);
    pass.draw(0..3, 0..1);
    pass.set_pipeline(&draws.snow);
    pass.draw_indirect(&frame.draws, FrameDraws::SNOW_OFFSET);
    pass.set_pipeline(&draws.rain);
    pass.draw_indirect(&frame.draws, FrameDraws::RAIN_OFFSET);
}
