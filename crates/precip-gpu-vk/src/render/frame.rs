//! The per-configuration resources of drawing on Vulkan, made from the frame's
//! resources table (`precip_gpu::frame_resources`): its buffers (the frame's
//! uniform block, one per frame in flight), images and descriptor sets filled as the
//! table says, the shadow map's framebuffer, and per frame in flight the target's
//! sets (`TARGET_GROUPS`), written when the target changes. wgpu twin:
//! `precip_gpu_wgpu::render::frame`.

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use precip_gpu::Simulation;
use precip_gpu::bind_groups::{BindingKind, GroupLayout};
use precip_gpu::frame_resources::{
    FRAME_GROUPS, FrameBound, FrameBuffer, FrameBufferUsage, FrameGroupFill, FrameTexture, Sampler,
    TARGET_GROUPS, TargetResource, TexelFormat, TextureUsage, frame_buffers, frame_textures,
    splat_sums_bytes,
};
use precip_model::{BackendError, Setup};

use super::Renderer;
use crate::bind_groups::descriptor_type;
use crate::buffer::Buffer;
use crate::descriptors::{self, write};
use crate::device::Device;
use crate::error::map_vk;
use crate::gpu::Hal;
use crate::image::{DEPTH_FORMAT, Image, ImageSpec};
use crate::transfer::{FRAMES_IN_FLIGHT, to_general, upload_image};

/// The cover textures' format (`precip_gpu::recipe::COVER_TEXTURE_FORMAT_NAME`).
pub const COVER_TEXTURE_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;

/// What drawing adds to a configuration.
#[derive(Debug)]
pub struct FrameResources {
    buffers: Vec<(FrameBuffer, Buffer)>,
    images: Vec<(FrameTexture, Image, TextureUsage)>,
    /// Bytes between two frames' `RenderParams` blocks.
    pub params_stride: u64,
    /// The shadow map as the shadow pass's attachment.
    pub shadow_framebuffer: vk::Framebuffer,
    pool: vk::DescriptorPool,
    sets: Vec<(&'static str, vk::DescriptorSet)>,
    /// The splat kernel's set, one per frame in flight.
    pub splat_sets: [vk::DescriptorSet; FRAMES_IN_FLIGHT],
    /// The resolve draw's set, one per frame in flight.
    pub resolve_sets: [vk::DescriptorSet; FRAMES_IN_FLIGHT],
    /// Cover texels (the `cover_texture` kernel's dispatch).
    pub cover_texels: u32,
}

/// The splat's sums for one target size (`precip_gpu::frame_resources::splat_sums_bytes`).
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
        Ok(Self {
            buffer: Buffer::new(
                device,
                "splat sums",
                splat_sums_bytes(size),
                vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuOnly,
            )?,
            size,
            zeroed: false,
        })
    }
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

/// A resource the tables name that was not made (a bug in precip).
fn missing(what: &str) -> BackendError {
    BackendError::Device {
        backend: crate::error::NAME,
        message: format!("{what} of the frame is missing (a bug in precip: please report it)"),
    }
}

/// The Vulkan format of `format`.
fn texel_format(format: TexelFormat) -> vk::Format {
    match format {
        TexelFormat::Depth32Float => DEPTH_FORMAT,
        TexelFormat::Rgba16Float => COVER_TEXTURE_FORMAT,
        TexelFormat::R8Unorm => vk::Format::R8_UNORM,
    }
}

/// The layout an image of `usage` is in when a shader reads it.
fn read_layout(usage: TextureUsage) -> vk::ImageLayout {
    match usage {
        TextureUsage::StorageAndSampled => vk::ImageLayout::GENERAL,
        TextureUsage::DepthAttachment | TextureUsage::Sampled => {
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL
        }
    }
}

/// What a frame's resources hold while they are made, freed when a later step fails.
#[derive(Default)]
struct Made {
    buffers: Vec<(FrameBuffer, Buffer)>,
    images: Vec<(FrameTexture, Image, TextureUsage)>,
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
        self.images
            .into_iter()
            .for_each(|(_, i, _)| i.destroy(device));
        self.buffers
            .into_iter()
            .for_each(|(_, b)| b.destroy(device));
    }
}

/// One descriptor's info, kept alive while the writes that point at it are made.
enum Info {
    Buffer([vk::DescriptorBufferInfo; 1]),
    Image([vk::DescriptorImageInfo; 1]),
}

/// What the groups' entries resolve against.
struct Bindable<'a> {
    buffers: &'a [(FrameBuffer, Buffer)],
    images: &'a [(FrameTexture, Image, TextureUsage)],
    sim: &'a Simulation<Hal>,
    renderer: &'a Renderer,
    /// The target's depth view and splat sums, for the target's groups.
    target: Option<(vk::ImageView, &'a Buffer)>,
}

impl Bindable<'_> {
    /// The info of `bound` for a binding of `kind`.
    fn info(&self, kind: BindingKind, bound: FrameBound) -> Result<Info, BackendError> {
        let range = kind.block_bytes().unwrap_or(vk::WHOLE_SIZE);
        let buffer = |b: &Buffer| {
            Info::Buffer([vk::DescriptorBufferInfo {
                buffer: b.raw,
                offset: 0,
                range,
            }])
        };
        let image = |view, layout| {
            Info::Image([vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: view,
                image_layout: layout,
            }])
        };
        let of = |texture| {
            self.images
                .iter()
                .find(|(t, ..)| *t == texture)
                .ok_or_else(|| missing("a texture"))
        };
        Ok(match bound {
            FrameBound::Sim(b) => buffer(self.sim.buffer(b)),
            FrameBound::Buffer(b) => buffer(
                self.buffers
                    .iter()
                    .find(|(k, _)| *k == b)
                    .map(|(_, b)| b)
                    .ok_or_else(|| missing("a buffer"))?,
            ),
            FrameBound::Texture(t) => {
                let (_, i, usage) = of(t)?;
                image(i.view, read_layout(*usage))
            }
            FrameBound::StorageTexture(t) => image(of(t)?.1.view, vk::ImageLayout::GENERAL),
            FrameBound::Sampler(s) => Info::Image([vk::DescriptorImageInfo {
                sampler: match s {
                    Sampler::LinearClamp => self.renderer.samplers.flake,
                    Sampler::ShadowComparison => self.renderer.samplers.shadow,
                },
                image_view: vk::ImageView::null(),
                image_layout: vk::ImageLayout::UNDEFINED,
            }]),
            FrameBound::Target(TargetResource::CameraDepth) => image(
                self.target.ok_or_else(|| missing("the depth buffer"))?.0,
                vk::ImageLayout::DEPTH_STENCIL_READ_ONLY_OPTIMAL,
            ),
            FrameBound::Target(TargetResource::SplatSums) => {
                buffer(self.target.ok_or_else(|| missing("the splat sums"))?.1)
            }
        })
    }

    /// Writes `set` as `fill` says.
    ///
    /// # Safety
    /// `set` was allocated with `fill`'s layout and no pending work uses it.
    unsafe fn write(
        &self,
        device: &Device,
        set: vk::DescriptorSet,
        fill: &FrameGroupFill,
    ) -> Result<(), BackendError> {
        let mut infos = Vec::with_capacity(fill.bound.len());
        for &(binding, bound) in fill.bound {
            let kind = fill
                .layout
                .kind_of(binding)
                .ok_or_else(|| missing(fill.layout.name))?;
            infos.push((binding, kind, self.info(kind, bound)?));
        }
        let writes: Vec<vk::WriteDescriptorSet<'_>> = infos
            .iter()
            .map(|(binding, kind, info)| {
                let w = write(set, *binding, descriptor_type(*kind));
                match info {
                    Info::Buffer(b) => w.buffer_info(b),
                    Info::Image(i) => w.image_info(i),
                }
            })
            .collect();
        // SAFETY: every write names a live buffer, view or sampler of its binding's
        // type (checked against the table); the set is unused (the caller's guarantee).
        unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
        Ok(())
    }
}

impl FrameResources {
    /// Allocates drawing's resources beside the simulation's `sim`, from the table;
    /// on an error, frees what it made.
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

    fn make(
        device: &Device,
        renderer: &Renderer,
        sim: &Simulation<Hal>,
        setup: &Setup,
        made: &mut Made,
    ) -> Result<Self, BackendError> {
        let count = sim.particle_count();
        let limits = &device.properties.limits;
        // The block is bound as a uniform and as storage: both alignments (powers of two).
        let align = limits
            .min_storage_buffer_offset_alignment
            .max(limits.min_uniform_buffer_offset_alignment)
            .max(16);
        let mut params_stride = 0;
        for spec in frame_buffers(count) {
            use vk::BufferUsageFlags as U;
            let (bytes, usage, location) = match spec.usage {
                FrameBufferUsage::Params => {
                    params_stride = spec.bytes.div_ceil(align) * align;
                    (
                        params_stride * FRAMES_IN_FLIGHT as u64,
                        U::STORAGE_BUFFER | U::UNIFORM_BUFFER,
                        MemoryLocation::CpuToGpu,
                    )
                }
                FrameBufferUsage::Storage => {
                    (spec.bytes, U::STORAGE_BUFFER, MemoryLocation::GpuOnly)
                }
                FrameBufferUsage::Indirect => (
                    spec.bytes,
                    U::STORAGE_BUFFER | U::INDIRECT_BUFFER | U::TRANSFER_SRC,
                    MemoryLocation::GpuOnly,
                ),
            };
            let name = spec.label.trim_start_matches("precip ");
            made.buffers.push((
                spec.buffer,
                Buffer::new(device, name, bytes, usage, location)?,
            ));
        }
        for spec in frame_textures(setup) {
            use vk::ImageUsageFlags as U;
            let usage = match spec.usage {
                TextureUsage::DepthAttachment => U::DEPTH_STENCIL_ATTACHMENT | U::SAMPLED,
                TextureUsage::StorageAndSampled => U::STORAGE | U::SAMPLED,
                TextureUsage::Sampled => U::SAMPLED | U::TRANSFER_DST,
            };
            let image = Image::new(
                device,
                &ImageSpec {
                    name: spec.label.trim_start_matches("precip "),
                    extent: UVec3::new(spec.size[0], spec.size[1], 1),
                    format: texel_format(spec.format),
                    usage,
                },
            )?;
            made.images.push((spec.texture, image, spec.usage));
            if let (Some(texels), Some((_, image, _))) = (&spec.contents, made.images.last()) {
                upload_image(device, image, texels)?;
            }
        }
        let general: Vec<&Image> = made
            .images
            .iter()
            .filter(|(.., usage)| *usage == TextureUsage::StorageAndSampled)
            .map(|(_, i, _)| i)
            .collect();
        to_general(device, &general)?;
        let (shadow_view, shadow_size) = made
            .images
            .iter()
            .find(|(t, ..)| *t == FrameTexture::ShadowMap)
            .map(|(_, i, _)| (i.view, i.size()))
            .ok_or_else(|| missing("the shadow map"))?;
        let shadow_framebuffer =
            framebuffer(device, renderer.shadow_pass, &[shadow_view], shadow_size)?;
        made.framebuffer = Some(shadow_framebuffer);
        device.name(shadow_framebuffer, "precip shadow framebuffer");

        // One pool for the configuration's sets and the target's, per frame in flight.
        let fills: Vec<&FrameGroupFill> = FRAME_GROUPS
            .iter()
            .chain((0..FRAMES_IN_FLIGHT).flat_map(|_| TARGET_GROUPS.iter()))
            .collect();
        let mut sizes: Vec<(vk::DescriptorType, u32)> = Vec::new();
        for fill in &fills {
            for b in fill.layout.bindings {
                let ty = descriptor_type(b.kind);
                match sizes.iter_mut().find(|(t, _)| *t == ty) {
                    Some((_, n)) => *n += 1,
                    None => sizes.push((ty, 1)),
                }
            }
        }
        let pool = descriptors::pool(device, "frame", &sizes, fills.len() as u32)?;
        made.pool = Some(pool);
        let layouts = fills
            .iter()
            .map(|fill| {
                renderer
                    .layouts
                    .set_layout_of(fill.layout)
                    .ok_or_else(|| missing(fill.layout.name))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let all = descriptors::allocate(device, pool, &layouts)?;
        let bindable = Bindable {
            buffers: &made.buffers,
            images: &made.images,
            sim,
            renderer,
            target: None,
        };
        let mut sets = Vec::with_capacity(FRAME_GROUPS.len());
        for (fill, set) in FRAME_GROUPS.iter().zip(&all) {
            // SAFETY: the set was just allocated with the fill's layout.
            unsafe { bindable.write(device, *set, fill)? };
            sets.push((fill.layout.name, *set));
        }
        let target_sets = &all[FRAME_GROUPS.len()..];
        let per_slot = |k: usize| -> [vk::DescriptorSet; FRAMES_IN_FLIGHT] {
            std::array::from_fn(|slot| {
                target_sets
                    .get(slot * TARGET_GROUPS.len() + k)
                    .copied()
                    .unwrap_or_default()
            })
        };
        let (splat_sets, resolve_sets) = (per_slot(0), per_slot(1));
        let texels = setup.cover.frame.texels;
        made.framebuffer = None;
        made.pool = None;
        Ok(Self {
            buffers: std::mem::take(&mut made.buffers),
            images: std::mem::take(&mut made.images),
            params_stride,
            shadow_framebuffer,
            pool,
            sets,
            splat_sets,
            resolve_sets,
            cover_texels: texels.x * texels.y,
        })
    }

    /// Points `slot`'s splat and resolve sets at the target's depth view and `sums`.
    ///
    /// # Safety
    /// No pending work uses the slot's sets; the view and buffer are live.
    pub unsafe fn write_splat_sets(
        &self,
        device: &Device,
        renderer: &Renderer,
        sim: &Simulation<Hal>,
        slot: usize,
        (depth, sums): (vk::ImageView, &Buffer),
    ) -> Result<(), BackendError> {
        let bindable = Bindable {
            buffers: &self.buffers,
            images: &self.images,
            sim,
            renderer,
            target: Some((depth, sums)),
        };
        for (fill, set) in TARGET_GROUPS
            .iter()
            .zip([self.splat_sets[slot], self.resolve_sets[slot]])
        {
            // SAFETY: the set was allocated with the fill's layout; the caller
            // guarantees no pending work uses it.
            unsafe { bindable.write(device, set, fill)? };
        }
        Ok(())
    }

    /// A buffer of the frame.
    pub fn buffer(&self, buffer: FrameBuffer) -> Result<&Buffer, BackendError> {
        self.buffers
            .iter()
            .find(|(b, _)| *b == buffer)
            .map(|(_, b)| b)
            .ok_or_else(|| missing("a buffer"))
    }

    /// A buffer of the frame, to write.
    pub fn buffer_mut(&mut self, buffer: FrameBuffer) -> Result<&mut Buffer, BackendError> {
        self.buffers
            .iter_mut()
            .find(|(b, _)| *b == buffer)
            .map(|(_, b)| b)
            .ok_or_else(|| missing("a buffer"))
    }

    /// An image of the frame.
    pub fn image(&self, texture: FrameTexture) -> Result<&Image, BackendError> {
        self.images
            .iter()
            .find(|(t, ..)| *t == texture)
            .map(|(_, i, _)| i)
            .ok_or_else(|| missing("a texture"))
    }

    /// The set made for `table`, if it is one of the configuration's.
    #[must_use]
    pub fn set(&self, table: &GroupLayout) -> Option<vk::DescriptorSet> {
        self.sets
            .iter()
            .find(|(name, _)| *name == table.name)
            .map(|(_, s)| *s)
    }

    /// Frees everything (no pending work may use it).
    pub fn destroy(self, device: &Device) {
        Made {
            buffers: self.buffers,
            images: self.images,
            framebuffer: Some(self.shadow_framebuffer),
            pool: Some(self.pool),
        }
        .destroy(device);
    }
}
