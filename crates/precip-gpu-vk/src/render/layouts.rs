//! Descriptor set layouts and pipeline layouts of the render and cull programs
//! (bindings: `precip_model::gpu::{render_bindings, cull_bindings}`), the Vulkan
//! twins of the wgpu backend's bind group layouts.
//!
//! `RenderParams` is dynamic read-only storage (not a uniform: see render_scene.wgsl):
//! one block per frame in flight, so the host writes frame n + 1's while frame n draws.

use ash::vk;
use precip_model::BackendError;
use precip_model::gpu::{cull_bindings as cb, render_bindings as rb};

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

fn binding(
    b: u32,
    ty: vk::DescriptorType,
    stages: vk::ShaderStageFlags,
) -> vk::DescriptorSetLayoutBinding<'static> {
    vk::DescriptorSetLayoutBinding::default()
        .binding(b)
        .descriptor_type(ty)
        .descriptor_count(1)
        .stage_flags(stages)
}

fn set_layout(
    device: &Device,
    name: &str,
    bindings: &[vk::DescriptorSetLayoutBinding<'_>],
) -> Result<vk::DescriptorSetLayout, BackendError> {
    let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(bindings);
    // SAFETY: a valid device and create info.
    let layout = unsafe { device.raw.create_descriptor_set_layout(&info, None) }
        .map_err(|e| map_vk("creating a descriptor set layout", e))?;
    device.name(layout, name);
    Ok(layout)
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
        use vk::DescriptorType as T;
        let compute = vk::ShaderStageFlags::COMPUTE;
        // Sets 0 and 1 serve the draws and the splat kernel.
        let draw = vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT | compute;
        let material_stages = vk::ShaderStageFlags::VERTEX | vk::ShaderStageFlags::FRAGMENT;
        let frame = set_layout(
            device,
            "precip render frame",
            &[
                binding(rb::PARAMS, T::STORAGE_BUFFER_DYNAMIC, draw),
                binding(rb::GROUND_HEIGHT, T::STORAGE_BUFFER, draw),
                binding(rb::PARTICLES, T::STORAGE_BUFFER, draw),
                binding(rb::DRAWN, T::STORAGE_BUFFER, draw),
                binding(rb::COVER_A, T::SAMPLED_IMAGE, draw),
                binding(rb::COVER_B, T::SAMPLED_IMAGE, draw),
                binding(rb::COVER_SAMPLER, T::SAMPLER, draw),
            ],
        )?;
        let light = set_layout(
            device,
            "precip render light",
            &[
                binding(rb::SHADOW_MAP, T::SAMPLED_IMAGE, draw),
                binding(rb::SHADOW_SAMPLER, T::SAMPLER, draw),
                binding(rb::FLAKE_OPACITY, T::SAMPLED_IMAGE, draw),
                binding(rb::FLAKE_SAMPLER, T::SAMPLER, draw),
            ],
        )?;
        let material = set_layout(
            device,
            "precip render material",
            &[
                binding(rb::MATERIAL, T::UNIFORM_BUFFER, material_stages),
                binding(rb::BASE_COLOUR_TEXTURE, T::SAMPLED_IMAGE, material_stages),
                binding(rb::MATERIAL_SAMPLER, T::SAMPLER, material_stages),
            ],
        )?;
        let cull = set_layout(
            device,
            "precip cull",
            &[
                binding(cb::PARAMS, T::STORAGE_BUFFER_DYNAMIC, compute),
                binding(cb::PARTICLES, T::STORAGE_BUFFER, compute),
                binding(cb::GROUP_COUNTS, T::STORAGE_BUFFER, compute),
                binding(cb::DRAWN, T::STORAGE_BUFFER, compute),
                binding(cb::DRAWS, T::STORAGE_BUFFER, compute),
            ],
        )?;
        let splat = set_layout(
            device,
            "precip splat",
            &[
                binding(rb::SPLAT_SCENE_DEPTH, T::SAMPLED_IMAGE, compute),
                binding(rb::SPLAT_SUMS, T::STORAGE_BUFFER, compute),
            ],
        )?;
        let splat_resolve = set_layout(
            device,
            "precip splat resolve",
            &[binding(
                rb::RESOLVED_SUMS,
                T::STORAGE_BUFFER,
                vk::ShaderStageFlags::FRAGMENT,
            )],
        )?;
        let cover_texture = set_layout(
            device,
            "precip cover texture",
            &[
                binding(rb::COVER, T::STORAGE_BUFFER, compute),
                binding(rb::COVER_A_OUT, T::STORAGE_IMAGE, compute),
                binding(rb::COVER_B_OUT, T::STORAGE_IMAGE, compute),
            ],
        )?;
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
