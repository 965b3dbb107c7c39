//! Descriptor set layouts (from `precip_gpu::bind_groups`' tables, as the wgpu
//! backend's bind group layouts) and one pipeline layout per entry point of the
//! frame recipe, made of its groups (`precip_gpu::bind_groups::groups_of`): the
//! same set layouts in the same order, so sets bound for one stay valid for the next.
//!
//! `RenderParams` is dynamic read-only storage (not a uniform: see render_scene.wgsl):
//! one block per frame in flight, so the host writes frame n + 1's while frame n draws.

use ash::vk;
use precip_gpu::bind_groups::{self as bg, GroupLayout, groups_of};
use precip_gpu::frame;
use precip_gpu::shaders::Program;
use precip_model::BackendError;

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
    /// The pipeline layout of each kernel and draw (by its first entry point).
    pipeline_layouts: Vec<(&'static str, vk::PipelineLayout)>,
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
        let mut made = Self {
            frame: vk::DescriptorSetLayout::null(),
            light: vk::DescriptorSetLayout::null(),
            material: vk::DescriptorSetLayout::null(),
            cull: vk::DescriptorSetLayout::null(),
            splat: vk::DescriptorSetLayout::null(),
            splat_resolve: vk::DescriptorSetLayout::null(),
            cover_texture: vk::DescriptorSetLayout::null(),
            pipeline_layouts: Vec::new(),
        };
        match made.fill(device) {
            Ok(()) => Ok(made),
            Err(e) => {
                made.destroy(device);
                Err(e)
            }
        }
    }

    fn fill(&mut self, device: &Device) -> Result<(), BackendError> {
        self.frame = set_layout(device, &bg::RENDER_FRAME)?;
        self.light = set_layout(device, &bg::RENDER_LIGHT)?;
        self.material = set_layout(device, &bg::RENDER_MATERIAL)?;
        self.cull = set_layout(device, &bg::CULL)?;
        self.splat = set_layout(device, &bg::SPLAT)?;
        self.splat_resolve = set_layout(device, &bg::SPLAT_RESOLVE)?;
        self.cover_texture = set_layout(device, &bg::COVER_TEXTURE)?;
        let entries = frame::kernels()
            .map(|k| (k.program, k.entry_point))
            .chain(frame::draws().map(|(_, d)| (Program::Render, d.entry_points.0)));
        for (program, entry) in entries {
            let sets: Vec<vk::DescriptorSetLayout> = groups_of(program, entry)
                .unwrap_or(&[])
                .iter()
                .filter_map(|g| self.set_layout_of(g))
                .collect();
            let layout = pipeline_layout(device, entry, &sets)?;
            self.pipeline_layouts.push((entry, layout));
        }
        Ok(())
    }

    /// The set layout made from table `group`, if it is one of the frame's.
    #[must_use]
    pub fn set_layout_of(&self, group: &GroupLayout) -> Option<vk::DescriptorSetLayout> {
        bg::lookup(
            group,
            [
                (&bg::RENDER_FRAME, self.frame),
                (&bg::RENDER_LIGHT, self.light),
                (&bg::RENDER_MATERIAL, self.material),
                (&bg::CULL, self.cull),
                (&bg::SPLAT, self.splat),
                (&bg::SPLAT_RESOLVE, self.splat_resolve),
                (&bg::COVER_TEXTURE, self.cover_texture),
            ],
        )
    }

    /// The pipeline layout of the kernel or draw whose (vertex) entry point is
    /// `entry_point`.
    #[must_use]
    pub fn pipeline_layout(&self, entry_point: &str) -> Option<vk::PipelineLayout> {
        self.pipeline_layouts
            .iter()
            .find(|(e, _)| *e == entry_point)
            .map(|(_, l)| *l)
    }

    /// Destroys the layouts (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; each is destroyed once (by the renderer's
        // destroy); null handles are ignored by Vulkan.
        unsafe {
            for (_, layout) in self.pipeline_layouts {
                device.raw.destroy_pipeline_layout(layout, None);
            }
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
