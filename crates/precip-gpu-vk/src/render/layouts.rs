//! Descriptor set layouts (from `precip_model::bind_groups`' tables, as the wgpu
//! backend's bind group layouts) and pipeline layouts of the render, cull, splat and
//! cover-texture kernels.
//!
//! `RenderParams` is dynamic read-only storage (not a uniform: see render_scene.wgsl):
//! one block per frame in flight, so the host writes frame n + 1's while frame n draws.

use ash::vk;
use precip_model::BackendError;
use precip_model::bind_groups as bg;

use crate::bind_groups::set_layout;
use crate::device::Device;
use crate::error::map_vk;

/// The layouts, made once per device.
#[derive(Debug)]
pub struct RenderLayouts {
    /// Set 0 of the draws: the frame.
    pub frame: vk::DescriptorSetLayout,
    /// Set 1: shadow map and flake opacity.
    pub light: vk::DescriptorSetLayout,
    /// Set 2: a mesh's material.
    pub material: vk::DescriptorSetLayout,
    /// Set 0 of the cull kernels.
    pub cull: vk::DescriptorSetLayout,
    /// Set 2 of the splat kernel: the camera's depth and the splat sums.
    pub splat: vk::DescriptorSetLayout,
    /// Set 2 of the splat's resolve draw: the splat sums.
    pub splat_resolve: vk::DescriptorSetLayout,
    /// Set 0 of the `cover_texture` kernel: the texels and the two storage images.
    pub cover_texture: vk::DescriptorSetLayout,
    /// Every draw's pipeline layout (sets 0–2; the shadow and particle draws use a
    /// prefix of them).
    pub draw_layout: vk::PipelineLayout,
    /// The cull kernels' pipeline layout.
    pub cull_layout: vk::PipelineLayout,
    /// The splat kernel's (sets 0, 1 and the splat set).
    pub splat_layout: vk::PipelineLayout,
    /// The resolve draw's (sets 0, 1 and the resolve set).
    pub resolve_layout: vk::PipelineLayout,
    /// The `cover_texture` kernel's.
    pub cover_texture_layout: vk::PipelineLayout,
}

fn pipeline_layout(
    device: &Device,
    name: &str,
    sets: &[vk::DescriptorSetLayout],
) -> Result<vk::PipelineLayout, BackendError> {
    let info = vk::PipelineLayoutCreateInfo::default().set_layouts(sets);
    // SAFETY: a valid device; the set layouts are live.
    let layout = unsafe { device.raw.create_pipeline_layout(&info, None) }
        .map_err(|e| map_vk("creating a pipeline layout", e))?;
    device.name(layout, name);
    Ok(layout)
}

impl RenderLayouts {
    /// Creates the layouts.
    pub fn new(device: &Device) -> Result<Self, BackendError> {
        let frame = set_layout(device, &bg::RENDER_FRAME)?;
        let light = set_layout(device, &bg::RENDER_LIGHT)?;
        let material = set_layout(device, &bg::RENDER_MATERIAL)?;
        let cull = set_layout(device, &bg::CULL)?;
        let splat = set_layout(device, &bg::SPLAT)?;
        let splat_resolve = set_layout(device, &bg::SPLAT_RESOLVE)?;
        let cover_texture = set_layout(device, &bg::COVER_TEXTURE)?;
        Ok(Self {
            cover_texture_layout: pipeline_layout(
                device,
                "precip cover texture",
                &[cover_texture],
            )?,
            draw_layout: pipeline_layout(device, "precip draws", &[frame, light, material])?,
            cull_layout: pipeline_layout(device, "precip cull", &[cull])?,
            splat_layout: pipeline_layout(device, "precip splat", &[frame, light, splat])?,
            resolve_layout: pipeline_layout(
                device,
                "precip splat resolve",
                &[frame, light, splat_resolve],
            )?,
            frame,
            light,
            material,
            cull,
            splat,
            splat_resolve,
            cover_texture,
        })
    }

    /// Destroys the layouts (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; each is destroyed once (by the renderer's
        // destroy).
        unsafe {
            device.raw.destroy_pipeline_layout(self.draw_layout, None);
            device.raw.destroy_pipeline_layout(self.cull_layout, None);
            device.raw.destroy_pipeline_layout(self.splat_layout, None);
            device
                .raw
                .destroy_pipeline_layout(self.resolve_layout, None);
            device
                .raw
                .destroy_pipeline_layout(self.cover_texture_layout, None);
            for set in [
                self.frame,
                self.light,
                self.material,
                self.cull,
                self.splat,
                self.splat_resolve,
                self.cover_texture,
            ] {
                device.raw.destroy_descriptor_set_layout(set, None);
            }
        }
    }
}
