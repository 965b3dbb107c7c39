//! The per-configuration resources of drawing: the frame's uniform blocks (one per
//! frame in flight), the cull lists and indirect draws, the shadow map with its
//! framebuffer, and the descriptor sets of the draws and the cull kernels.

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use precip_model::BackendError;
use precip_model::gpu::{cull_bindings as cb, cull_groups, render_bindings as rb};
use precip_model::render::RenderParams;

use super::Renderer;
use crate::buffer::Buffer;
use crate::descriptors::{self, buffer_info, image_info, sampler_info, write};
use crate::device::Device;
use crate::error::map_vk;
use crate::image::{DEPTH_FORMAT, Image, ImageSpec};
use crate::resources::{FRAMES_IN_FLIGHT, Resources};

/// Bytes of the two indirect draws (snow, rain).
pub const DRAWS_BYTES: u64 = 32;

/// What drawing adds to a configuration.
#[derive(Debug)]
pub struct FrameResources {
    /// `RenderParams`, one block per frame in flight at `params_stride`.
    pub params: Buffer,
    /// Bytes between the blocks.
    pub params_stride: u64,
    group_counts: Buffer,
    drawn: Buffer,
    /// The two `DrawArgs` (snow, rain).
    pub draws: Buffer,
    /// The sun's depth.
    pub shadow_map: Image,
    /// Its framebuffer (the shadow pass).
    pub shadow_framebuffer: vk::Framebuffer,
    pool: vk::DescriptorPool,
    /// Set 0 of the draws.
    pub frame_set: vk::DescriptorSet,
    /// Set 1 of the draws.
    pub light_set: vk::DescriptorSet,
    /// Set 0 of the cull kernels.
    pub cull_set: vk::DescriptorSet,
}

const STORAGE: vk::BufferUsageFlags = vk::BufferUsageFlags::STORAGE_BUFFER;

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

impl FrameResources {
    /// Allocates drawing's resources beside the simulation's `sim`.
    pub fn new(
        device: &Device,
        renderer: &Renderer,
        sim: &Resources,
        shadow_map_px: u32,
    ) -> Result<Self, BackendError> {
        let count = sim.particle_count;
        let groups = cull_groups(count);
        let limits = &device.properties.limits;
        let align = limits.min_storage_buffer_offset_alignment.max(16);
        let params_stride = (size_of::<RenderParams>() as u64).div_ceil(align) * align;
        let params = Buffer::new(
            device,
            "render params",
            params_stride * FRAMES_IN_FLIGHT as u64,
            vk::BufferUsageFlags::STORAGE_BUFFER,
            MemoryLocation::CpuToGpu,
        )?;
        let gpu_only = |name, size, usage| {
            Buffer::new(device, name, size, STORAGE | usage, MemoryLocation::GpuOnly)
        };
        let group_counts = gpu_only(
            "cull groups",
            u64::from(groups) * 8,
            vk::BufferUsageFlags::empty(),
        )?;
        let drawn = gpu_only("drawn", u64::from(count) * 8, vk::BufferUsageFlags::empty())?;
        let draws = gpu_only(
            "draws",
            DRAWS_BYTES,
            vk::BufferUsageFlags::INDIRECT_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC,
        )?;
        let shadow_map = Image::new(
            device,
            &ImageSpec {
                name: "shadow map",
                extent: UVec3::new(shadow_map_px, shadow_map_px, 1),
                format: DEPTH_FORMAT,
                usage: vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED,
            },
        )?;
        let shadow_framebuffer = framebuffer(
            device,
            renderer.shadow_pass,
            &[shadow_map.view],
            shadow_map.size(),
        )?;
        device.name(shadow_framebuffer, "precip shadow framebuffer");

        use vk::DescriptorType as T;
        let pool = descriptors::pool(
            device,
            "frame",
            &[
                (T::STORAGE_BUFFER_DYNAMIC, 2),
                (T::STORAGE_BUFFER, 8),
                (T::SAMPLED_IMAGE, 2),
                (T::SAMPLER, 2),
            ],
            3,
        )?;
        let sets = descriptors::allocate(
            device,
            pool,
            &[
                renderer.layouts.frame,
                renderer.layouts.light,
                renderer.layouts.cull,
            ],
        )?;
        let (frame_set, light_set, cull_set) = (sets[0], sets[1], sets[2]);
        let whole = |b: &Buffer| buffer_info(b, vk::WHOLE_SIZE);
        let params_info = buffer_info(&params, size_of::<RenderParams>() as u64);
        let (cover, ground, particles) =
            (whole(&sim.cover), whole(&sim.ground), whole(&sim.particles));
        let (drawn_info, groups_info, draws_info) =
            (whole(&drawn), whole(&group_counts), whole(&draws));
        let (shadow_image, flake_image) =
            (image_info(shadow_map.view), image_info(renderer.flake.view));
        let (shadow_sampler, flake_sampler) = (
            sampler_info(renderer.samplers.shadow),
            sampler_info(renderer.samplers.flake),
        );
        let writes = [
            write(frame_set, rb::PARAMS, T::STORAGE_BUFFER_DYNAMIC).buffer_info(&params_info),
            write(frame_set, rb::COVER, T::STORAGE_BUFFER).buffer_info(&cover),
            write(frame_set, rb::GROUND_HEIGHT, T::STORAGE_BUFFER).buffer_info(&ground),
            write(frame_set, rb::PARTICLES, T::STORAGE_BUFFER).buffer_info(&particles),
            write(frame_set, rb::DRAWN, T::STORAGE_BUFFER).buffer_info(&drawn_info),
            write(light_set, rb::SHADOW_MAP, T::SAMPLED_IMAGE).image_info(&shadow_image),
            write(light_set, rb::SHADOW_SAMPLER, T::SAMPLER).image_info(&shadow_sampler),
            write(light_set, rb::FLAKE_OPACITY, T::SAMPLED_IMAGE).image_info(&flake_image),
            write(light_set, rb::FLAKE_SAMPLER, T::SAMPLER).image_info(&flake_sampler),
            write(cull_set, cb::PARAMS, T::STORAGE_BUFFER_DYNAMIC).buffer_info(&params_info),
            write(cull_set, cb::PARTICLES, T::STORAGE_BUFFER).buffer_info(&particles),
            write(cull_set, cb::GROUP_COUNTS, T::STORAGE_BUFFER).buffer_info(&groups_info),
            write(cull_set, cb::DRAWN, T::STORAGE_BUFFER).buffer_info(&drawn_info),
            write(cull_set, cb::DRAWS, T::STORAGE_BUFFER).buffer_info(&draws_info),
        ];
        // SAFETY: every write names a live buffer, view or sampler of the binding's
        // type and usage.
        unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
        Ok(Self {
            params,
            params_stride,
            group_counts,
            drawn,
            draws,
            shadow_map,
            shadow_framebuffer,
            pool,
            frame_set,
            light_set,
            cull_set,
        })
    }

    /// Frees everything (no pending work may use it).
    pub fn destroy(self, device: &Device) {
        // SAFETY: no pending work uses these; each is destroyed once.
        unsafe {
            device.raw.destroy_descriptor_pool(self.pool, None);
            device
                .raw
                .destroy_framebuffer(self.shadow_framebuffer, None);
        }
        self.shadow_map.destroy(device);
        for b in [self.params, self.group_counts, self.drawn, self.draws] {
            b.destroy(device);
        }
    }
}
