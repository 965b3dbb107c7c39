//! Bind group layouts of the render, cull, splat and cover-texture kernels, made from
//! `precip_gpu::bind_groups`' tables.

use precip_gpu::bind_groups as bg;

use crate::bind_groups::bind_group_layout;

/// The layouts, made once per device.
#[derive(Debug)]
pub struct RenderLayouts {
    /// Group 0 of the render program: the frame.
    pub frame: wgpu::BindGroupLayout,
    /// Group 1: shadow map and flake opacity.
    pub light: wgpu::BindGroupLayout,
    /// Group 2: a mesh's material.
    pub material: wgpu::BindGroupLayout,
    /// Group 0 of the cull kernels.
    pub cull: wgpu::BindGroupLayout,
    /// Group 2 of the splat kernel: the camera's depth and the splat sums.
    pub splat: wgpu::BindGroupLayout,
    /// Group 2 of the splat's resolve draw: the splat sums.
    pub splat_resolve: wgpu::BindGroupLayout,
    /// Group 0 of the `cover_texture` kernel: the texels and the two storage views.
    pub cover_texture: wgpu::BindGroupLayout,
}

impl RenderLayouts {
    /// Creates the layouts.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Self {
        let layout = |g| bind_group_layout(device, g);
        Self {
            frame: layout(&bg::RENDER_FRAME),
            light: layout(&bg::RENDER_LIGHT),
            material: layout(&bg::RENDER_MATERIAL),
            cull: layout(&bg::CULL),
            splat: layout(&bg::SPLAT),
            splat_resolve: layout(&bg::SPLAT_RESOLVE),
            cover_texture: layout(&bg::COVER_TEXTURE),
        }
    }

    /// The layout made from table `group`, if it is one of the frame's.
    #[must_use]
    pub fn of(&self, group: &bg::GroupLayout) -> Option<&wgpu::BindGroupLayout> {
        bg::lookup(
            group,
            [
                (&bg::RENDER_FRAME, &self.frame),
                (&bg::RENDER_LIGHT, &self.light),
                (&bg::RENDER_MATERIAL, &self.material),
                (&bg::CULL, &self.cull),
                (&bg::SPLAT, &self.splat),
                (&bg::SPLAT_RESOLVE, &self.splat_resolve),
                (&bg::COVER_TEXTURE, &self.cover_texture),
            ],
        )
    }
}
