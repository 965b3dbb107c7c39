//! The per-configuration resources of drawing: the frame's uniform blocks (one per
//! frame in flight), the cull lists and indirect draws, the shadow map with its
//! framebuffer, and the descriptor sets of the draws and the cull kernels.

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use precip_gpu::recipe::{
    DRAWN_LIST_BYTES_PER_PARTICLE, FrameDraws, GROUP_COUNT_BYTES, SPLAT_BYTES_PER_PIXEL,
    cull_bindings as cb, cull_groups, render_bindings as rb,
};
use precip_model::drawing::render::RenderParams;
use precip_model::{BackendError, Setup};

use super::Renderer;
use crate::buffer::Buffer;
use crate::descriptors::{self, buffer_info, image_info, sampler_info, write};
use crate::device::Device;
use crate::error::map_vk;
use crate::image::{DEPTH_FORMAT, Image, ImageSpec};

/// The cover textures' format (`precip_gpu::recipe::COVER_TEXTURE_FORMAT_NAME`).
pub const COVER_TEXTURE_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
use crate::gpu::Hal;
use crate::transfer::{FRAMES_IN_FLIGHT, to_general};
use precip_gpu::Simulation;
use precip_gpu::resources::SimBuffer;

/// What drawing adds to a configuration.
#[derive(Debug)]
pub struct FrameResources {
    /// `RenderParams`, one block per frame in flight at `params_stride`.
    pub params: Buffer,
    /// Bytes between the blocks.
    pub params_stride: u64,
    group_counts: Buffer,
    drawn: Buffer,
    /// Each particle's class this frame (`cull_count` writes it).
    drawn_kinds: Buffer,
    /// [`FrameDraws`]: the two indirect draws and the splat count.
    pub draws: Buffer,
    /// The sun's depth.
    pub shadow_map: Image,
    /// The cover's two filtered textures (`GENERAL`: written by `cover_texture`,
    /// sampled by the draws).
    cover_images: [Image; 3],
    /// Set 0 of the `cover_texture` kernel.
    pub cover_texture_set: vk::DescriptorSet,
    /// Cover texels (the kernel's dispatch).
    pub cover_texels: u32,
    /// Its framebuffer (the shadow pass).
    pub shadow_framebuffer: vk::Framebuffer,
    pool: vk::DescriptorPool,
    /// Set 0 of the draws.
    pub frame_set: vk::DescriptorSet,
    /// Set 1 of the draws.
    pub light_set: vk::DescriptorSet,
    /// Set 0 of the cull kernels.
    pub cull_set: vk::DescriptorSet,
    /// Set 2 of the splat kernel, one per frame in flight (written by
    /// [`FrameResources::write_splat_sets`] with the frame's target).
    pub splat_sets: [vk::DescriptorSet; FRAMES_IN_FLIGHT],
    /// Set 2 of the resolve draw, one per frame in flight.
    pub resolve_sets: [vk::DescriptorSet; FRAMES_IN_FLIGHT],
}

/// The splat's sums for one target size ([`SPLAT_BYTES_PER_PIXEL`] per pixel).
#[derive(Debug)]
pub struct SplatSums {
    /// The buffer.
    pub buffer: Buffer,
    /// The target's width, height, px.
    pub size: (u32, u32),
    /// Whether it was zeroed on the device (the first frame that uses it fills it;
    /// after that the resolve zeroes what it reads).
    pub zeroed: bool,
}

impl SplatSums {
    /// Sums for a `size` target (filled with zeros by the first frame).
    pub fn new(device: &Device, size: (u32, u32)) -> Result<Self, BackendError> {
        let bytes = u64::from(size.0) * u64::from(size.1) * SPLAT_BYTES_PER_PIXEL;
        Ok(Self {
            buffer: Buffer::new(
                device,
                "splat sums",
                bytes,
                STORAGE | vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuOnly,
            )?,
            size,
            zeroed: false,
        })
    }
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

/// A resource made above not found below: a bug.
fn missing(what: &str) -> BackendError {
    BackendError::Device {
        backend: crate::error::NAME,
        message: format!("a {what} of the frame is missing (a bug in precip: please report it)"),
    }
}

/// What [`FrameResources::new`] has made so far, freed when a later step fails.
#[derive(Default)]
struct Made {
    buffers: Vec<Buffer>,
    images: Vec<Image>,
    framebuffer: Option<vk::Framebuffer>,
    pool: Option<vk::DescriptorPool>,
}

impl Made {
    fn destroy(self, device: &Device) {
        // SAFETY: nothing uses these yet (construction failed); each is destroyed once.
        unsafe {
            if let Some(pool) = self.pool {
                device.raw.destroy_descriptor_pool(pool, None);
            }
            if let Some(framebuffer) = self.framebuffer {
                device.raw.destroy_framebuffer(framebuffer, None);
            }
        }
        self.images.into_iter().for_each(|i| i.destroy(device));
        self.buffers.into_iter().for_each(|b| b.destroy(device));
    }
}

impl FrameResources {
    /// Allocates drawing's resources beside the simulation's `sim`; on an error,
    /// frees what it made.
    pub fn new(
        device: &Device,
        renderer: &Renderer,
        sim: &Simulation<Hal>,
        setup: &Setup,
    ) -> Result<Self, BackendError> {
        let mut made = Made::default();
        let result = Self::make(device, renderer, sim, setup, &mut made);
        made.destroy(device);
        result
    }

    /// Makes everything, each object kept in `made` until the last step moves them
    /// into the result (so `made` ends empty on success).
    fn make(
        device: &Device,
        renderer: &Renderer,
        sim: &Simulation<Hal>,
        setup: &Setup,
        made: &mut Made,
    ) -> Result<Self, BackendError> {
        let shadow_map_px = setup.render.shadow_map_px;
        let count = sim.particle_count();
        let groups = cull_groups(count);
        let limits = &device.properties.limits;
        // The block is bound as a uniform and as storage: both alignments (powers of two).
        let align = limits
            .min_storage_buffer_offset_alignment
            .max(limits.min_uniform_buffer_offset_alignment)
            .max(16);
        let params_stride = (size_of::<RenderParams>() as u64).div_ceil(align) * align;
        // params, group counts, drawn, drawn kinds, draws.
        let buffers = [
            (
                "render params",
                params_stride * FRAMES_IN_FLIGHT as u64,
                vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            ),
            (
                "cull groups",
                u64::from(groups) * GROUP_COUNT_BYTES,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "drawn",
                u64::from(count) * DRAWN_LIST_BYTES_PER_PARTICLE,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "drawn kinds",
                u64::from(count) * 4,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "draws",
                FrameDraws::BYTES,
                STORAGE
                    | vk::BufferUsageFlags::INDIRECT_BUFFER
                    | vk::BufferUsageFlags::TRANSFER_SRC,
                MemoryLocation::GpuOnly,
            ),
        ];
        for (name, size, usage, location) in buffers {
            made.buffers
                .push(Buffer::new(device, name, size, usage, location)?);
        }
        made.images.push(Image::new(
            device,
            &ImageSpec {
                name: "shadow map",
                extent: UVec3::new(shadow_map_px, shadow_map_px, 1),
                format: DEPTH_FORMAT,
                usage: vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED,
            },
        )?);
        let shadow_view = made.images[0].view;
        let shadow_size = made.images[0].size();
        let shadow_framebuffer =
            framebuffer(device, renderer.shadow_pass, &[shadow_view], shadow_size)?;
        made.framebuffer = Some(shadow_framebuffer);
        device.name(shadow_framebuffer, "precip shadow framebuffer");
        let texels = setup.cover.frame.texels;
        for name in ["cover a", "cover b", "cover c"] {
            made.images.push(Image::new(
                device,
                &ImageSpec {
                    name,
                    extent: UVec3::new(texels.x, texels.y, 1),
                    format: COVER_TEXTURE_FORMAT,
                    usage: vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::SAMPLED,
                },
            )?);
        }
        to_general(device, &[&made.images[1], &made.images[2], &made.images[3]])?;

        use vk::DescriptorType as T;
        let pool = descriptors::pool(
            device,
            "frame",
            &[
                (T::UNIFORM_BUFFER_DYNAMIC, 1),
                (T::STORAGE_BUFFER_DYNAMIC, 2),
                (T::STORAGE_BUFFER, 11 + 2 * FRAMES_IN_FLIGHT as u32),
                (T::SAMPLED_IMAGE, 5 + FRAMES_IN_FLIGHT as u32),
                (T::SAMPLER, 3),
                (T::STORAGE_IMAGE, 3),
            ],
            4 + 2 * FRAMES_IN_FLIGHT as u32,
        )?;
        made.pool = Some(pool);
        let mut layouts = vec![
            renderer.layouts.frame,
            renderer.layouts.light,
            renderer.layouts.cull,
            renderer.layouts.cover_texture,
        ];
        layouts.extend([renderer.layouts.splat; FRAMES_IN_FLIGHT]);
        layouts.extend([renderer.layouts.splat_resolve; FRAMES_IN_FLIGHT]);
        let sets = descriptors::allocate(device, pool, &layouts)?;
        let (frame_set, light_set, cull_set, cover_texture_set) =
            (sets[0], sets[1], sets[2], sets[3]);
        let splat_sets: [vk::DescriptorSet; FRAMES_IN_FLIGHT] =
            std::array::from_fn(|i| sets[4 + i]);
        let resolve_sets: [vk::DescriptorSet; FRAMES_IN_FLIGHT] =
            std::array::from_fn(|i| sets[4 + FRAMES_IN_FLIGHT + i]);
        let general = |view| {
            [vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: view,
                image_layout: vk::ImageLayout::GENERAL,
            }]
        };
        let (cover_a, cover_b, cover_c) = (
            general(made.images[1].view),
            general(made.images[2].view),
            general(made.images[3].view),
        );
        let cover_sampler = sampler_info(renderer.samplers.flake);
        let whole = |b: &Buffer| buffer_info(b, vk::WHOLE_SIZE);
        let [params, group_counts, drawn, drawn_kinds, draws] =
            [0, 1, 2, 3, 4].map(|i| &made.buffers[i]);
        let params_info = buffer_info(params, size_of::<RenderParams>() as u64);
        let (cover, ground, particles) = (
            whole(sim.buffer(SimBuffer::Cover)),
            whole(sim.buffer(SimBuffer::Ground)),
            whole(sim.buffer(SimBuffer::Particles)),
        );
        let waves = whole(sim.buffer(SimBuffer::Waves));
        let (drawn_info, groups_info, draws_info, kinds_info) = (
            whole(drawn),
            whole(group_counts),
            whole(draws),
            whole(drawn_kinds),
        );
        let (shadow_image, flake_image) =
            (image_info(shadow_view), image_info(renderer.flake.view));
        let (shadow_sampler, flake_sampler) = (
            sampler_info(renderer.samplers.shadow),
            sampler_info(renderer.samplers.flake),
        );
        let writes = [
            write(frame_set, rb::PARAMS, T::UNIFORM_BUFFER_DYNAMIC).buffer_info(&params_info),
            write(frame_set, rb::PARAMS_SWITCHES, T::STORAGE_BUFFER_DYNAMIC)
                .buffer_info(&params_info),
            write(frame_set, rb::COVER_A, T::SAMPLED_IMAGE).image_info(&cover_a),
            write(frame_set, rb::COVER_B, T::SAMPLED_IMAGE).image_info(&cover_b),
            write(frame_set, rb::COVER_C, T::SAMPLED_IMAGE).image_info(&cover_c),
            write(frame_set, rb::COVER_SAMPLER, T::SAMPLER).image_info(&cover_sampler),
            write(cover_texture_set, rb::COVER, T::STORAGE_BUFFER).buffer_info(&cover),
            write(cover_texture_set, rb::COVER_A_OUT, T::STORAGE_IMAGE).image_info(&cover_a),
            write(cover_texture_set, rb::COVER_B_OUT, T::STORAGE_IMAGE).image_info(&cover_b),
            write(cover_texture_set, rb::COVER_C_OUT, T::STORAGE_IMAGE).image_info(&cover_c),
            write(frame_set, rb::GROUND_HEIGHT, T::STORAGE_BUFFER).buffer_info(&ground),
            write(frame_set, rb::WAVES, T::STORAGE_BUFFER).buffer_info(&waves),
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
            write(cull_set, cb::DRAWN_KINDS, T::STORAGE_BUFFER).buffer_info(&kinds_info),
        ];
        // SAFETY: every write names a live buffer, view or sampler of the binding's
        // type and usage.
        unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
        let mut buffers = std::mem::take(&mut made.buffers).into_iter();
        let mut images = std::mem::take(&mut made.images).into_iter();
        made.framebuffer = None;
        made.pool = None;
        let (Some(params), Some(group_counts), Some(drawn), Some(drawn_kinds), Some(draws)) = (
            buffers.next(),
            buffers.next(),
            buffers.next(),
            buffers.next(),
            buffers.next(),
        ) else {
            return Err(missing("buffer"));
        };
        let (Some(shadow_map), Some(cover_a), Some(cover_b), Some(cover_c)) =
            (images.next(), images.next(), images.next(), images.next())
        else {
            return Err(missing("image"));
        };
        Ok(Self {
            params,
            params_stride,
            group_counts,
            drawn,
            drawn_kinds,
            draws,
            shadow_map,
            shadow_framebuffer,
            cover_images: [cover_a, cover_b, cover_c],
            cover_texture_set,
            cover_texels: texels.x * texels.y,
            pool,
            frame_set,
            light_set,
            cull_set,
            splat_sets,
            resolve_sets,
        })
    }

    /// Points frame slot `slot`'s splat and resolve sets at `depth` (the target's
    /// depth view, read-only) and `sums`.
    ///
    /// # Safety
    /// No pending work uses the slot's sets (its last frame has finished); `depth`
    /// is a live depth view of `device`.
    pub unsafe fn write_splat_sets(
        &self,
        device: &Device,
        slot: usize,
        depth: vk::ImageView,
        sums: &Buffer,
    ) {
        use vk::DescriptorType as T;
        let depth_info = [vk::DescriptorImageInfo {
            sampler: vk::Sampler::null(),
            image_view: depth,
            image_layout: vk::ImageLayout::DEPTH_STENCIL_READ_ONLY_OPTIMAL,
        }];
        let sums_info = buffer_info(sums, vk::WHOLE_SIZE);
        let draws_info = buffer_info(&self.draws, vk::WHOLE_SIZE);
        let writes = [
            write(
                self.splat_sets[slot],
                rb::SPLAT_SCENE_DEPTH,
                T::SAMPLED_IMAGE,
            )
            .image_info(&depth_info),
            write(self.splat_sets[slot], rb::SPLAT_SUMS, T::STORAGE_BUFFER).buffer_info(&sums_info),
            write(self.splat_sets[slot], rb::SPLAT_DRAWS, T::STORAGE_BUFFER)
                .buffer_info(&draws_info),
            write(
                self.resolve_sets[slot],
                rb::RESOLVED_SUMS,
                T::STORAGE_BUFFER,
            )
            .buffer_info(&sums_info),
        ];
        // SAFETY: the view and buffer are live, of the bindings' types and usages;
        // the sets are not in use by pending work (the caller's guarantee).
        unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
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
        for image in self.cover_images {
            image.destroy(device);
        }
        for b in [
            self.params,
            self.group_counts,
            self.drawn,
            self.drawn_kinds,
            self.draws,
        ] {
            b.destroy(device);
        }
    }
}
