//! A frame's commands into one Vulkan command buffer (wgpu twin:
//! `precip_gpu_wgpu::frame`): what `precip_gpu::renderer` recorded, plus what
//! Vulkan needs besides.
//!
//! - **Render passes** are made from a pass's attachments ([`RenderPassKey`]: the
//!   colour target's format, how each attachment loads and stores, whether depth
//!   is written, the colour's final layout) and kept; **framebuffers** are made for
//!   each frame and retired after it.
//! - **Layouts**: between passes every texture rests in one layout fixed by its
//!   usage — depth buffers `DEPTH_STENCIL_READ_ONLY_OPTIMAL` (sampled by the scene
//!   and the splat kernel), storage textures `GENERAL`, sampled ones
//!   `SHADER_READ_ONLY_OPTIMAL`; a render pass moves its attachments out of it and
//!   back. The colour target ends the frame's last colour pass ready to copy
//!   (offscreen) or to present (a swapchain image).
//! - **Barriers**: the step's writes before the frame; after each dispatch, its
//!   writes to every later kernel, draw and indirect read; each render pass's
//!   subpass dependencies order it after the last use of its attachments (the
//!   shadow map sampled by the last frame, the depth buffer shared by frames in
//!   flight) and make its results visible to what reads them next; after the frame,
//!   the next submission waits for what the frame's shaders read.
//!
//! Timestamps: two a pass (`TOP_OF_PIPE` at its start, `BOTTOM_OF_PIPE` at its
//! end); a pass that does not run writes both at once and is not reported. Clip
//! space is flipped with a negative viewport height, as wgpu-hal does, so the WGSL
//! runs unchanged and the images agree.

use ash::vk;
use precip_gpu::frame::AttachmentLoad;
use precip_gpu::gpu::{Command, FrameWork, PassKind};
use precip_model::BackendError;

use crate::commands::{image_barriers, memory_barrier};
use crate::device::Device;
use crate::error::map_vk;
use crate::gpu::Hal;
use crate::gpu::Texture;
use crate::image::DEPTH_FORMAT;
use crate::query::{FRAME_QUERY_COUNT, QueryPool};
use crate::transfer::image_barrier;

/// What a render pass object is made from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderPassKey {
    /// The colour target's format, how it loads and its layout after the pass.
    pub colour: Option<(vk::Format, AttachmentLoad, vk::ImageLayout)>,
    /// How the depth loads.
    pub depth_load: AttachmentLoad,
    /// Whether the depth is kept.
    pub depth_stored: bool,
    /// Whether a draw writes depth (else it is attached read-only).
    pub depth_written: bool,
}

const FRAGMENT_TESTS: vk::PipelineStageFlags = vk::PipelineStageFlags::from_raw(
    vk::PipelineStageFlags::EARLY_FRAGMENT_TESTS.as_raw()
        | vk::PipelineStageFlags::LATE_FRAGMENT_TESTS.as_raw(),
);

fn load_op(load: AttachmentLoad) -> vk::AttachmentLoadOp {
    match load {
        AttachmentLoad::Clear => vk::AttachmentLoadOp::CLEAR,
        AttachmentLoad::Load => vk::AttachmentLoadOp::LOAD,
    }
}

/// The render pass of `key`.
pub fn render_pass(device: &Device, key: &RenderPassKey) -> Result<vk::RenderPass, BackendError> {
    use vk::ImageLayout as L;
    let depth_rest = L::DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    let attachment = |format, load: AttachmentLoad, store: bool, rest, last| {
        vk::AttachmentDescription::default()
            .format(format)
            .samples(vk::SampleCountFlags::TYPE_1)
            .load_op(load_op(load))
            .store_op(if store {
                vk::AttachmentStoreOp::STORE
            } else {
                vk::AttachmentStoreOp::DONT_CARE
            })
            .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
            .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
            .initial_layout(match load {
                AttachmentLoad::Clear => L::UNDEFINED,
                AttachmentLoad::Load => rest,
            })
            .final_layout(last)
    };
    let mut attachments = Vec::with_capacity(2);
    if let Some((format, load, last)) = key.colour {
        let rest = L::COLOR_ATTACHMENT_OPTIMAL;
        attachments.push(attachment(format, load, true, rest, last));
    }
    attachments.push(attachment(
        DEPTH_FORMAT,
        key.depth_load,
        key.depth_stored,
        depth_rest,
        depth_rest,
    ));
    let colour = [vk::AttachmentReference {
        attachment: 0,
        layout: L::COLOR_ATTACHMENT_OPTIMAL,
    }];
    let depth = vk::AttachmentReference {
        attachment: attachments.len() as u32 - 1,
        // A cleared depth is written by its clear, even where no draw writes it.
        layout: if key.depth_written || key.depth_load == AttachmentLoad::Clear {
            L::DEPTH_STENCIL_ATTACHMENT_OPTIMAL
        } else {
            depth_rest
        },
    };
    let colour: &[vk::AttachmentReference] = if key.colour.is_some() { &colour } else { &[] };
    let subpass = [vk::SubpassDescription::default()
        .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
        .color_attachments(colour)
        .depth_stencil_attachment(&depth)];
    let attachment_stages = vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT | FRAGMENT_TESTS;
    let attachment_writes =
        vk::AccessFlags::COLOR_ATTACHMENT_WRITE | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_WRITE;
    let attachment_access = attachment_writes
        | vk::AccessFlags::COLOR_ATTACHMENT_READ
        | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_READ;
    let elsewhere = vk::PipelineStageFlags::TRANSFER
        | vk::PipelineStageFlags::COMPUTE_SHADER
        | vk::PipelineStageFlags::FRAGMENT_SHADER;
    let dependencies = [
        // Before: the last writes of its attachments, and the copies, kernels and
        // fragments that read them (the last frame's image copy, splat, shadow test).
        vk::SubpassDependency::default()
            .src_subpass(vk::SUBPASS_EXTERNAL)
            .dst_subpass(0)
            .src_stage_mask(attachment_stages | elsewhere)
            .dst_stage_mask(attachment_stages)
            .src_access_mask(attachment_writes)
            .dst_access_mask(attachment_access),
        // After: to the attachments' next use, copies, kernels and fragments.
        vk::SubpassDependency::default()
            .src_subpass(0)
            .dst_subpass(vk::SUBPASS_EXTERNAL)
            .src_stage_mask(attachment_stages)
            .dst_stage_mask(attachment_stages | elsewhere)
            .src_access_mask(attachment_writes)
            .dst_access_mask(
                attachment_access | vk::AccessFlags::TRANSFER_READ | vk::AccessFlags::SHADER_READ,
            ),
    ];
    let info = vk::RenderPassCreateInfo::default()
        .attachments(&attachments)
        .subpasses(&subpass)
        .dependencies(&dependencies);
    // SAFETY: a valid device; the create info and what it points to outlive the call.
    let pass = unsafe { device.raw.create_render_pass(&info, None) }
        .map_err(|e| map_vk("creating a render pass", e))?;
    device.name(pass, "precip render pass");
    Ok(pass)
}

/// A framebuffer of `views` for `pass`, `size` px.
pub fn framebuffer(
    device: &Device,
    pass: vk::RenderPass,
    views: &[vk::ImageView],
    (width, height): (u32, u32),
) -> Result<vk::Framebuffer, BackendError> {
    let info = vk::FramebufferCreateInfo::default()
        .render_pass(pass)
        .attachments(views)
        .width(width)
        .height(height)
        .layers(1);
    // SAFETY: the views and the pass are live and compatible (formats match).
    unsafe { device.raw.create_framebuffer(&info, None) }
        .map_err(|e| map_vk("creating a framebuffer", e))
}

/// How a render pass of the frame begins.
#[derive(Debug, Clone, Copy)]
pub struct PassBegin {
    /// The pass object.
    pub pass: vk::RenderPass,
    /// This frame's framebuffer.
    pub framebuffer: vk::Framebuffer,
    /// The render area, px.
    pub size: (u32, u32),
    /// Whether it has a colour attachment.
    pub colour: bool,
    /// What its colour is cleared to.
    pub clear_colour: [f32; 4],
    /// Where it draws, px `(x, y, width, height)` (`None`: everywhere).
    pub scissor: Option<[u32; 4]>,
}

/// The viewport of `size`, y flipped (WGSL's clip space, as wgpu-hal), drawing
/// within `scissor` (`x, y, width, height`, inside `size`) or everywhere.
///
/// # Safety
/// `cb` is a command buffer of `device` in the recording state.
unsafe fn viewport(
    device: &Device,
    cb: vk::CommandBuffer,
    (width, height): (u32, u32),
    scissor: Option<[u32; 4]>,
) {
    let viewport = vk::Viewport {
        x: 0.0,
        y: height as f32,
        width: width as f32,
        height: -(height as f32),
        min_depth: 0.0,
        max_depth: 1.0,
    };
    let [x, y, w, h] = scissor.unwrap_or([0, 0, width, height]);
    let scissor = vk::Rect2D {
        offset: vk::Offset2D {
            x: x.min(width) as i32,
            y: y.min(height) as i32,
        },
        extent: vk::Extent2D {
            width: w.min(width - x.min(width)),
            height: h.min(height - y.min(height)),
        },
    };
    // SAFETY: the caller guarantees `cb` is recording; negative heights are core
    // since Vulkan 1.1.
    unsafe {
        device.raw.cmd_set_viewport(cb, 0, &[viewport]);
        device.raw.cmd_set_scissor(cb, 0, &[scissor]);
    }
}

/// Records `frame` into `cb` (see the module docs); `begins` holds, for each pass,
/// how it begins if it is a render pass that runs; `target` is the colour target's
/// image and `target_final` the layout the frame's last pass on it leaves it in
/// (a copy of it after that pass finds it there).
///
/// # Safety
/// - `cb` is a command buffer of `hal`'s device in the recording state, outside a
///   render pass.
/// - `target` is the image of the framebuffers' colour views, made with
///   `TRANSFER_SRC` if the frame has a pass that copies it.
/// - Every object `frame` and `begins` name is live, made on that device, and
///   stays so until the submission of `cb` has finished; each pipeline was made
///   for a pass compatible with the one it is used in, each group for the layout it
///   is bound at, with one offset per dynamic binding.
pub unsafe fn record_frame(
    hal: &Hal,
    cb: vk::CommandBuffer,
    frame: &FrameWork<'_, Hal>,
    target: (vk::Image, vk::ImageLayout),
    begins: &[Option<PassBegin>],
    stamps: Option<&QueryPool>,
) {
    use vk::AccessFlags as A;
    let (target, target_final) = target;
    // The target rests in the colour attachment layout between render passes,
    // and in its final one after the last.
    let mut target_layout = vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL;
    use vk::PipelineStageFlags as S;
    let device = &hal.device;
    let stamp = |i, stage| {
        if let Some(s) = stamps {
            // SAFETY: `cb` is recording (the caller's guarantee); `i` is below the
            // pool's count (two a pass), reset at the start of this recording.
            unsafe { s.stamp(device, cb, i, stage) };
        }
    };
    // SAFETY: `cb` is recording outside a render pass; every handle is live (the
    // caller's guarantees).
    unsafe {
        if let Some(s) = stamps {
            s.reset(device, cb, 0, FRAME_QUERY_COUNT);
        }
        // The step's compute writes (particles, cover) and any copy, to this frame.
        memory_barrier(
            device,
            cb,
            (
                S::COMPUTE_SHADER | S::TRANSFER,
                A::SHADER_WRITE | A::TRANSFER_WRITE,
            ),
            (
                S::VERTEX_SHADER | S::FRAGMENT_SHADER | S::COMPUTE_SHADER | S::DRAW_INDIRECT,
                A::SHADER_READ | A::SHADER_WRITE | A::INDIRECT_COMMAND_READ,
            ),
        );
    }
    for ((index, pass), begin) in (0u32..).zip(&frame.passes).zip(begins) {
        let (start, end) = (2 * index, 2 * index + 1);
        stamp(start, S::TOP_OF_PIPE);
        if let (true, PassKind::CopyTarget { colour, depth }) = (pass.runs, &pass.kind) {
            // SAFETY: outside a render pass; `target` is in `target_layout`, the
            // depth buffer in its resting layout, and the copies are live images
            // of their sizes and formats (the caller's and the renderer's
            // guarantees).
            unsafe { copy_target(device, cb, (target, target_layout), colour, *depth) };
        } else if pass.runs {
            if let PassKind::Render(a) = &pass.kind
                && a.colour_last
            {
                target_layout = target_final;
            }
            let (bind_point, begin) = match (&pass.kind, begin) {
                (PassKind::Render(_), Some(begin)) => {
                    let clears = [
                        vk::ClearValue {
                            color: vk::ClearColorValue {
                                float32: begin.clear_colour,
                            },
                        },
                        vk::ClearValue {
                            depth_stencil: vk::ClearDepthStencilValue {
                                depth: 1.0,
                                stencil: 0,
                            },
                        },
                    ];
                    let info = vk::RenderPassBeginInfo::default()
                        .render_pass(begin.pass)
                        .framebuffer(begin.framebuffer)
                        .render_area(vk::Rect2D {
                            offset: vk::Offset2D { x: 0, y: 0 },
                            extent: vk::Extent2D {
                                width: begin.size.0,
                                height: begin.size.1,
                            },
                        })
                        .clear_values(if begin.colour { &clears } else { &clears[1..] });
                    // SAFETY: outside a render pass; the framebuffer was made for
                    // this pass, of this size.
                    unsafe {
                        device
                            .raw
                            .cmd_begin_render_pass(cb, &info, vk::SubpassContents::INLINE);
                        viewport(device, cb, begin.size, begin.scissor);
                    }
                    (vk::PipelineBindPoint::GRAPHICS, Some(begin))
                }
                _ => (vk::PipelineBindPoint::COMPUTE, None),
            };
            let mut layout = vk::PipelineLayout::null();
            for command in &pass.commands {
                // SAFETY: see the block above; a group or draw follows its pipeline
                // (the renderer's order), whose layout it is bound with.
                unsafe { record(hal, cb, bind_point, &mut layout, command) };
            }
            if begin.is_some() {
                // SAFETY: ends the pass begun above.
                unsafe { device.raw.cmd_end_render_pass(cb) };
            }
        }
        stamp(end, S::BOTTOM_OF_PIPE);
    }
    // The next frame's step and splat rewrite what these shaders read, and the
    // resolve's zeroing writes must land before the next splat adds.
    // SAFETY: outside a render pass.
    unsafe {
        memory_barrier(
            device,
            cb,
            (
                S::DRAW_INDIRECT | S::VERTEX_SHADER | S::FRAGMENT_SHADER | S::COMPUTE_SHADER,
                A::SHADER_WRITE,
            ),
            (
                S::COMPUTE_SHADER | S::TRANSFER,
                A::SHADER_READ | A::SHADER_WRITE | A::TRANSFER_WRITE,
            ),
        );
    }
}

/// Copies the colour target `target.0` (in layout `target.1`:
/// `COLOR_ATTACHMENT_OPTIMAL` as a render pass that is not the frame's last left
/// it, or the final layout the last left it in) into `colour`, and the depth
/// buffer `depth.0` (resting in `DEPTH_STENCIL_READ_ONLY_OPTIMAL`) into `depth.1`;
/// the copies' old contents are dropped. Leaves the target and the depth buffer
/// as they were, and the copies in their resting layouts for the fragment shaders
/// after.
///
/// # Safety
/// `cb` is recording outside a render pass; all four images are live, each copy of
/// its source's size and format, the sources made with `TRANSFER_SRC` and the
/// copies with `TRANSFER_DST`.
unsafe fn copy_target(
    device: &Device,
    cb: vk::CommandBuffer,
    target: (vk::Image, vk::ImageLayout),
    colour: &Texture,
    depth: (&Texture, &Texture),
) {
    let (target, target_layout) = target;
    use vk::AccessFlags as A;
    use vk::ImageLayout as L;
    use vk::PipelineStageFlags as S;
    let barrier = image_barrier;
    let colour_range = crate::image::COLOUR;
    let depth_range = depth.0.image.range();
    let rest = depth.0.layout;
    let before = [
        barrier(
            target,
            colour_range,
            (target_layout, A::COLOR_ATTACHMENT_WRITE),
            (L::TRANSFER_SRC_OPTIMAL, A::TRANSFER_READ),
        ),
        barrier(
            depth.0.image.raw,
            depth_range,
            (rest, A::DEPTH_STENCIL_ATTACHMENT_WRITE),
            (L::TRANSFER_SRC_OPTIMAL, A::TRANSFER_READ),
        ),
        barrier(
            colour.image.raw,
            colour_range,
            (L::UNDEFINED, A::empty()),
            (L::TRANSFER_DST_OPTIMAL, A::TRANSFER_WRITE),
        ),
        barrier(
            depth.1.image.raw,
            depth_range,
            (L::UNDEFINED, A::empty()),
            (L::TRANSFER_DST_OPTIMAL, A::TRANSFER_WRITE),
        ),
    ];
    let after = [
        barrier(
            target,
            colour_range,
            (L::TRANSFER_SRC_OPTIMAL, A::empty()),
            (
                target_layout,
                A::COLOR_ATTACHMENT_READ | A::COLOR_ATTACHMENT_WRITE,
            ),
        ),
        barrier(
            depth.0.image.raw,
            depth_range,
            (L::TRANSFER_SRC_OPTIMAL, A::empty()),
            (rest, A::DEPTH_STENCIL_ATTACHMENT_READ | A::SHADER_READ),
        ),
        barrier(
            colour.image.raw,
            colour_range,
            (L::TRANSFER_DST_OPTIMAL, A::TRANSFER_WRITE),
            (colour.layout, A::SHADER_READ),
        ),
        barrier(
            depth.1.image.raw,
            depth_range,
            (L::TRANSFER_DST_OPTIMAL, A::TRANSFER_WRITE),
            (depth.1.layout, A::SHADER_READ),
        ),
    ];
    let region = |aspect_mask| {
        let layers = vk::ImageSubresourceLayers {
            aspect_mask,
            mip_level: 0,
            base_array_layer: 0,
            layer_count: 1,
        };
        vk::ImageCopy {
            src_subresource: layers,
            src_offset: vk::Offset3D::default(),
            dst_subresource: layers,
            dst_offset: vk::Offset3D::default(),
            extent: vk::Extent3D {
                width: colour.image.extent.x,
                height: colour.image.extent.y,
                depth: 1,
            },
        }
    };
    let fragment_tests = S::EARLY_FRAGMENT_TESTS | S::LATE_FRAGMENT_TESTS;
    // SAFETY: the caller's guarantees; the last frame's reads of the copies
    // (fragment shaders) are ordered before their overwrite by the first barrier's
    // stages, and the copies' writes before the next frame's reads by the second.
    unsafe {
        let drawing = S::COLOR_ATTACHMENT_OUTPUT | fragment_tests | S::FRAGMENT_SHADER;
        image_barriers(device, cb, (drawing, S::TRANSFER), &before);
        device.raw.cmd_copy_image(
            cb,
            target,
            L::TRANSFER_SRC_OPTIMAL,
            colour.image.raw,
            L::TRANSFER_DST_OPTIMAL,
            &[region(vk::ImageAspectFlags::COLOR)],
        );
        device.raw.cmd_copy_image(
            cb,
            depth.0.image.raw,
            L::TRANSFER_SRC_OPTIMAL,
            depth.1.image.raw,
            L::TRANSFER_DST_OPTIMAL,
            &[region(vk::ImageAspectFlags::DEPTH)],
        );
        image_barriers(
            device,
            cb,
            (S::TRANSFER, drawing | S::COMPUTE_SHADER),
            &after,
        );
    }
}

/// Records one command.
///
/// # Safety
/// As [`record_frame`]'s; `layout` is the last pipeline's layout.
unsafe fn record(
    hal: &Hal,
    cb: vk::CommandBuffer,
    bind_point: vk::PipelineBindPoint,
    layout: &mut vk::PipelineLayout,
    command: &Command<'_, Hal>,
) {
    use vk::AccessFlags as A;
    use vk::PipelineStageFlags as S;
    let device = &hal.device;
    // SAFETY: the caller's guarantees.
    unsafe {
        match command {
            Command::Kernel(p) | Command::Pipeline(p) => {
                device.raw.cmd_bind_pipeline(cb, bind_point, p.pipeline);
                *layout = p.layout;
            }
            Command::Group {
                index,
                group,
                offsets,
            } => device.raw.cmd_bind_descriptor_sets(
                cb,
                bind_point,
                *layout,
                *index,
                &[group.set],
                offsets,
            ),
            Command::Dispatch(x, y) => {
                device.raw.cmd_dispatch(cb, *x, *y, 1);
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
            Command::Meshes { vertices, indices } => {
                device
                    .raw
                    .cmd_bind_vertex_buffers(cb, 0, &[vertices.raw], &[0]);
                device
                    .raw
                    .cmd_bind_index_buffer(cb, indices.raw, 0, vk::IndexType::UINT32);
            }
            Command::Draw(n) => device.raw.cmd_draw(cb, *n, 1, 0, 0),
            Command::DrawIndexed(range) => device.raw.cmd_draw_indexed(
                cb,
                range.end.saturating_sub(range.start),
                1,
                range.start,
                0,
                0,
            ),
            Command::DrawIndirect(buffer, offset) => {
                device.raw.cmd_draw_indirect(cb, buffer.raw, *offset, 1, 16);
            }
        }
    }
}
