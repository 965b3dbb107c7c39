//! Render passes: the shadow pass (depth only) and the camera's pass (colour and
//! depth) per colour format and final layout — the offscreen target ends ready to
//! copy, a swapchain image ready to present. Pipelines are made against one pass of
//! their format; Vulkan's compatibility rules let them run in every pass of it.
//!
//! The subpass dependencies order each pass after the last frame's use of its
//! attachments (the shadow map is sampled by the previous frame's fragments; the
//! depth buffer is shared by frames in flight) and make the results visible to what
//! reads them next.

use ash::vk;
use precip_model::BackendError;

use crate::device::Device;
use crate::error::map_vk;
use crate::image::DEPTH_FORMAT;

const FRAGMENT_TESTS: vk::PipelineStageFlags = vk::PipelineStageFlags::from_raw(
    vk::PipelineStageFlags::EARLY_FRAGMENT_TESTS.as_raw()
        | vk::PipelineStageFlags::LATE_FRAGMENT_TESTS.as_raw(),
);

fn create(
    device: &Device,
    name: &str,
    attachments: &[vk::AttachmentDescription],
    colour: &[vk::AttachmentReference],
    depth: &vk::AttachmentReference,
    dependencies: &[vk::SubpassDependency],
) -> Result<vk::RenderPass, BackendError> {
    let subpass = [vk::SubpassDescription::default()
        .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
        .color_attachments(colour)
        .depth_stencil_attachment(depth)];
    let info = vk::RenderPassCreateInfo::default()
        .attachments(attachments)
        .subpasses(&subpass)
        .dependencies(dependencies);
    // SAFETY: a valid device; the create info outlives the call.
    let pass = unsafe { device.raw.create_render_pass(&info, None) }
        .map_err(|e| map_vk("creating a render pass", e))?;
    device.name(pass, name);
    Ok(pass)
}

/// The sun's depth: cleared, stored, left for sampling.
pub fn shadow(device: &Device) -> Result<vk::RenderPass, BackendError> {
    let attachment = [vk::AttachmentDescription::default()
        .format(DEPTH_FORMAT)
        .samples(vk::SampleCountFlags::TYPE_1)
        .load_op(vk::AttachmentLoadOp::CLEAR)
        .store_op(vk::AttachmentStoreOp::STORE)
        .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
        .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
        .initial_layout(vk::ImageLayout::UNDEFINED)
        .final_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)];
    let depth = vk::AttachmentReference {
        attachment: 0,
        layout: vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
    };
    let dependencies = [
        vk::SubpassDependency::default()
            .src_subpass(vk::SUBPASS_EXTERNAL)
            .dst_subpass(0)
            .src_stage_mask(vk::PipelineStageFlags::FRAGMENT_SHADER)
            .dst_stage_mask(FRAGMENT_TESTS)
            .src_access_mask(vk::AccessFlags::empty())
            .dst_access_mask(
                vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_READ
                    | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_WRITE,
            ),
        vk::SubpassDependency::default()
            .src_subpass(0)
            .dst_subpass(vk::SUBPASS_EXTERNAL)
            .src_stage_mask(vk::PipelineStageFlags::LATE_FRAGMENT_TESTS)
            .dst_stage_mask(vk::PipelineStageFlags::FRAGMENT_SHADER)
            .src_access_mask(vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_WRITE)
            .dst_access_mask(vk::AccessFlags::SHADER_READ),
    ];
    create(
        device,
        "precip shadow pass",
        &attachment,
        &[],
        &depth,
        &dependencies,
    )
}

/// The camera's two passes into one target: the scene's (clears) and the
/// particles' (loads), as the wgpu backend's, so each has its own timestamps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CameraPasses {
    /// Clears colour and depth; leaves them as attachments.
    pub scene: vk::RenderPass,
    /// Loads them; leaves the colour in the target's final layout.
    pub particles: vk::RenderPass,
}

/// The camera's passes into `format`, the colour ending in `final_layout`
/// (`TRANSFER_SRC_OPTIMAL` offscreen, `PRESENT_SRC_KHR` for a swapchain). One
/// framebuffer serves both (they are compatible).
pub fn camera(
    device: &Device,
    format: vk::Format,
    final_layout: vk::ImageLayout,
) -> Result<CameraPasses, BackendError> {
    let scene = camera_pass(device, format, None)?;
    match camera_pass(device, format, Some(final_layout)) {
        Ok(particles) => Ok(CameraPasses { scene, particles }),
        Err(e) => {
            // SAFETY: the pass is unused and destroyed once.
            unsafe { device.raw.destroy_render_pass(scene, None) };
            Err(e)
        }
    }
}

/// The scene's pass (`load_into: None`: clears) or the particles' (loads, ends in
/// the given layout).
fn camera_pass(
    device: &Device,
    format: vk::Format,
    load_into: Option<vk::ImageLayout>,
) -> Result<vk::RenderPass, BackendError> {
    use vk::ImageLayout as L;
    // The scene's pass leaves the depth read-only: the splat kernel samples it between
    // the passes, and the particles' pass tests against it without writing.
    let (load, initial, colour_final, depth_initial, depth_layout, depth_store) = match load_into {
        None => (
            vk::AttachmentLoadOp::CLEAR,
            L::UNDEFINED,
            L::COLOR_ATTACHMENT_OPTIMAL,
            L::UNDEFINED,
            L::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
            vk::AttachmentStoreOp::STORE,
        ),
        Some(final_layout) => (
            vk::AttachmentLoadOp::LOAD,
            L::COLOR_ATTACHMENT_OPTIMAL,
            final_layout,
            L::DEPTH_STENCIL_READ_ONLY_OPTIMAL,
            L::DEPTH_STENCIL_READ_ONLY_OPTIMAL,
            vk::AttachmentStoreOp::DONT_CARE,
        ),
    };
    let attachments = [
        vk::AttachmentDescription::default()
            .format(format)
            .samples(vk::SampleCountFlags::TYPE_1)
            .load_op(load)
            .store_op(vk::AttachmentStoreOp::STORE)
            .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
            .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
            .initial_layout(initial)
            .final_layout(colour_final),
        vk::AttachmentDescription::default()
            .format(DEPTH_FORMAT)
            .samples(vk::SampleCountFlags::TYPE_1)
            .load_op(load)
            .store_op(depth_store)
            .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
            .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
            .initial_layout(depth_initial)
            .final_layout(L::DEPTH_STENCIL_READ_ONLY_OPTIMAL),
    ];
    let colour = [vk::AttachmentReference {
        attachment: 0,
        layout: L::COLOR_ATTACHMENT_OPTIMAL,
    }];
    let depth = vk::AttachmentReference {
        attachment: 1,
        layout: depth_layout,
    };
    let attachment_stages = vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT | FRAGMENT_TESTS;
    let attachment_writes =
        vk::AccessFlags::COLOR_ATTACHMENT_WRITE | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_WRITE;
    let dependencies = [
        // Before: the last frame's attachments, copies and splat (it read the depth).
        vk::SubpassDependency::default()
            .src_subpass(vk::SUBPASS_EXTERNAL)
            .dst_subpass(0)
            .src_stage_mask(
                attachment_stages
                    | vk::PipelineStageFlags::TRANSFER
                    | vk::PipelineStageFlags::COMPUTE_SHADER,
            )
            .dst_stage_mask(attachment_stages)
            .src_access_mask(attachment_writes)
            .dst_access_mask(
                attachment_writes
                    | vk::AccessFlags::COLOR_ATTACHMENT_READ
                    | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_READ,
            ),
        vk::SubpassDependency::default()
            .src_subpass(0)
            .dst_subpass(vk::SUBPASS_EXTERNAL)
            .src_stage_mask(attachment_stages)
            .dst_stage_mask(
                attachment_stages
                    | vk::PipelineStageFlags::TRANSFER
                    | vk::PipelineStageFlags::COMPUTE_SHADER,
            )
            .src_access_mask(attachment_writes)
            .dst_access_mask(
                attachment_writes
                    | vk::AccessFlags::COLOR_ATTACHMENT_READ
                    | vk::AccessFlags::DEPTH_STENCIL_ATTACHMENT_READ
                    | vk::AccessFlags::TRANSFER_READ
                    | vk::AccessFlags::SHADER_READ,
            ),
    ];
    create(
        device,
        if load_into.is_some() {
            "precip particles pass"
        } else {
            "precip scene pass"
        },
        &attachments,
        &colour,
        &depth,
        &dependencies,
    )
}
