//! [`Hal`]: the device calls of [`precip_gpu::Gpu`] on Vulkan (wgpu twin:
//! `precip_gpu_wgpu::gpu`), and the submissions in flight. Nothing here knows what
//! the buffers hold, which kernels run or what a frame draws: the executor and
//! renderer of `precip-gpu` decide; a frame's commands become a command buffer in
//! [`crate::frame`].
//!
//! ## Submissions
//!
//! Work is submitted without waiting; at most [`FRAMES_IN_FLIGHT`] submissions are
//! pending when a step writes its ring of uniform blocks ([`Gpu::free_slot`]).
//! Objects replaced while work may still use them are retired and freed when that
//! work has finished ([`Retired`]); what the executor hands back is freed once
//! nothing is in flight.

use std::collections::{HashMap, VecDeque};

use ash::vk;
use glam::UVec3;
use gpu_allocator::MemoryLocation;
use precip_gpu::bind_groups::{BindingKind, GroupLayout};
use precip_gpu::frame::{Draw, RenderPassRecipe};
use precip_gpu::frame_resources::{Sampler, TexelFormat, TextureUsage};
use precip_gpu::gpu::{BindingResource, Dispatch, FrameWork, Gpu, PassKind, Target, TextureDesc};
use precip_gpu::resources::BufferUsage;
use precip_gpu::shaders::Program;
use precip_model::{BackendError, DeviceMemory};

use crate::bind_groups::{descriptor_type, set_layout};
use crate::buffer::Buffer;
use crate::commands::{InFlight, Semaphores, Workgroups, record_dispatch, submit, submit_synced};
use crate::descriptors::{self, buffer_info, image_info, write};
use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::frame::{PassBegin, RenderPassKey, framebuffer, record_frame, render_pass};
use crate::image::{DEPTH_FORMAT, Image, ImageSpec};
use crate::pipelines::draw_pipeline;
use crate::programs::{compute, module, pipeline_layout};
use crate::query::{FRAME_QUERY_COUNT, QUERY_COUNT, QueryPool};
use crate::retire::Retired;
use crate::transfer::{download, download_image, to_layout, upload_at, upload_image};
use crate::uploads::{self, Uploads};

pub use crate::transfer::FRAMES_IN_FLIGHT;

/// The offscreen image's format.
pub const OFFSCREEN_FORMAT: vk::Format = vk::Format::R8G8B8A8_SRGB;

/// A pipeline (compute or graphics) and its layout.
#[derive(Debug)]
pub struct Pipeline {
    /// The pipeline.
    pub pipeline: vk::Pipeline,
    /// Its layout.
    pub layout: vk::PipelineLayout,
}

/// A descriptor set and the pool it was allocated from.
#[derive(Debug)]
pub struct BindGroup {
    pool: vk::DescriptorPool,
    /// The set.
    pub set: vk::DescriptorSet,
}

/// A 2D image and the layout it rests in between passes (fixed by its usage).
#[derive(Debug)]
pub struct Texture {
    /// The image and its view.
    pub image: Image,
    /// Its layout between passes.
    pub layout: vk::ImageLayout,
    texel_bytes: u32,
}

/// A swapchain image to draw into, and the semaphores of its acquire and present.
#[derive(Debug, Clone, Copy)]
pub struct SwapchainImage {
    /// The image.
    pub image: vk::Image,
    /// Its view.
    pub view: vk::ImageView,
    /// It can be copied from (`TRANSFER_SRC`).
    pub copyable: bool,
    /// The swapchain's format.
    pub format: vk::Format,
    /// Signalled when the image is acquired (the frame waits on it).
    pub acquired: vk::Semaphore,
    /// Signalled when the frame is drawn (present waits on it).
    pub drawn: vk::Semaphore,
}

/// The device calls on Vulkan.
#[derive(Debug)]
pub struct Hal {
    /// Submitted steps and frames with their numbers, oldest first.
    in_flight: VecDeque<(u64, InFlight)>,
    /// Submissions so far.
    pub submitted: u64,
    /// Submissions known to be finished.
    completed: u64,
    /// Objects waiting for submissions to finish.
    pub retired: Retired,
    /// Writes of device-local buffers waiting for the next submission.
    uploads: Uploads,
    /// Timestamp queries, where the device has them.
    pub timestamps: Option<QueryPool>,
    /// Timed submissions so far (picks the queries' slot).
    timed: usize,
    /// A frame's timestamp queries, where the device has them.
    frame_stamps: Option<QueryPool>,
    modules: HashMap<Program, vk::ShaderModule>,
    render_passes: Vec<(RenderPassKey, vk::RenderPass)>,
    /// The device (dropped last).
    pub device: Device,
}

impl Hal {
    /// The calls on `device`.
    pub fn new(device: Device) -> Result<Self, BackendError> {
        let step_queries = QUERY_COUNT * FRAMES_IN_FLIGHT as u32;
        let timestamps = QueryPool::new(&device, "precip timestamps", step_queries)?;
        let frame_stamps =
            match QueryPool::new(&device, "precip frame timestamps", FRAME_QUERY_COUNT) {
                Ok(f) => f,
                Err(e) => {
                    if let Some(t) = timestamps {
                        t.destroy(&device);
                    }
                    return Err(e);
                }
            };
        Ok(Self {
            in_flight: VecDeque::new(),
            submitted: 0,
            completed: 0,
            retired: Retired::default(),
            uploads: Uploads::default(),
            timestamps,
            timed: 0,
            frame_stamps,
            modules: HashMap::new(),
            render_passes: Vec::new(),
            device,
        })
    }

    /// Waits for the oldest submissions until at most `pending` are in flight, and
    /// frees what they held.
    pub fn wait_until(&mut self, pending: usize) -> Result<(), BackendError> {
        while self.in_flight.len() > pending {
            if let Some((number, f)) = self.in_flight.pop_front() {
                f.wait(&self.device)?;
                self.completed = number + 1;
            }
        }
        self.retired.release(&self.device, self.completed);
        self.uploads.release(&self.device, self.completed);
        Ok(())
    }

    /// Submits the writes waiting for a submission, if any, in one of their own.
    fn flush_uploads(&mut self) -> Result<(), BackendError> {
        if !self.uploads.pending() {
            return Ok(());
        }
        let number = self.submitted;
        let copies = self.uploads.take(number);
        let device = &self.device;
        // SAFETY: `cb` is recording outside a render pass (inside `submit`); the
        // copies' buffers live until the submission finishes (module docs of
        // `uploads`).
        match submit(device, |cb| unsafe { uploads::record(device, cb, &copies) }) {
            Ok(in_flight) => {
                self.track(in_flight);
                Ok(())
            }
            Err(e) => {
                self.uploads.restore(copies, number);
                Err(e)
            }
        }
    }

    /// Records a submission in flight.
    pub fn track(&mut self, f: InFlight) {
        self.in_flight.push_back((self.submitted, f));
        self.submitted += 1;
    }

    /// The render pass of `key`, made on first use.
    fn render_pass(&mut self, key: RenderPassKey) -> Result<vk::RenderPass, BackendError> {
        if let Some((_, pass)) = self.render_passes.iter().find(|(k, _)| *k == key) {
            return Ok(*pass);
        }
        let pass = render_pass(&self.device, &key)?;
        self.render_passes.push((key, pass));
        Ok(pass)
    }

    /// How each pass of `frame` begins (render passes that run), its framebuffers
    /// made for this frame; on an error, those made are destroyed.
    fn pass_begins(
        &mut self,
        frame: &FrameWork<'_, Self>,
        colour: (vk::ImageView, vk::Format, vk::ImageLayout),
    ) -> Result<Vec<Option<PassBegin>>, BackendError> {
        let mut begins = Vec::with_capacity(frame.passes.len());
        for pass in &frame.passes {
            let begin = match &pass.kind {
                PassKind::Render(a) if pass.runs => {
                    let recipe = a.recipe;
                    // A texture drawn into ends the pass ready to be sampled.
                    let (view, format, last) = match a.colour {
                        Some(t) => (t.image.view, t.image.format, t.layout),
                        None if a.colour_last => colour,
                        None => (
                            colour.0,
                            colour.1,
                            vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                        ),
                    };
                    let key = RenderPassKey {
                        colour: recipe.colour.map(|load| (format, load, last)),
                        depth_load: recipe.depth_load,
                        depth_stored: recipe.depth_stored,
                        depth_written: a.depth_written,
                    };
                    let made = self.render_pass(key).and_then(|pass| {
                        let views: &[vk::ImageView] = if key.colour.is_some() {
                            &[view, a.depth.image.view]
                        } else {
                            &[a.depth.image.view]
                        };
                        let size = a.depth.image.size();
                        framebuffer(&self.device, pass, views, size).map(|framebuffer| PassBegin {
                            pass,
                            framebuffer,
                            size,
                            colour: key.colour.is_some(),
                            clear_colour: a.clear_colour,
                            scissor: a.scissor,
                        })
                    });
                    match made {
                        Ok(b) => Some(b),
                        Err(e) => {
                            destroy_framebuffers(&self.device, &begins);
                            return Err(e);
                        }
                    }
                }
                _ => None,
            };
            begins.push(begin);
        }
        Ok(begins)
    }

    fn module(&mut self, program: Program) -> Result<vk::ShaderModule, BackendError> {
        if let Some(m) = self.modules.get(&program) {
            return Ok(*m);
        }
        let m = module(&self.device, program)?;
        self.modules.insert(program, m);
        Ok(m)
    }

    /// Waits for everything in flight, the writes waiting included, so an object
    /// may be freed (best effort: a lost device frees anyway, nothing will run
    /// again).
    fn idle_for_destroy(&mut self) {
        let _ = self.flush_uploads();
        let _ = self.wait_until(0);
    }
}

impl Gpu for Hal {
    type Buffer = Buffer;
    type Volume = Image;
    type GroupLayout = vk::DescriptorSetLayout;
    type BindGroup = BindGroup;
    type Kernel = Pipeline;
    type Texture = Texture;
    type Sampler = vk::Sampler;
    type DrawPipeline = Pipeline;
    type Surface = SwapchainImage;
    type ColourFormat = vk::Format;

    fn name(&self) -> &'static str {
        NAME
    }

    fn describe(&self) -> String {
        format!("{} (Vulkan)", self.device.name_of_device())
    }

    fn device_memory(&self) -> Option<DeviceMemory> {
        let report = self.device.allocator.lock().ok()?.generate_report();
        Some(DeviceMemory {
            allocations: report.allocations.len() as u64,
            allocated_bytes: report.total_allocated_bytes,
            reserved_bytes: report.total_capacity_bytes,
        })
    }

    fn limits(&self) -> precip_model::DeviceLimits {
        self.device.limits()
    }

    fn binding_limits(&self) -> precip_gpu::binding_limits::BindingLimits {
        let limits = &self.device.properties.limits;
        precip_gpu::binding_limits::BindingLimits {
            bind_groups: limits.max_bound_descriptor_sets,
            storage_buffers_per_stage: limits.max_per_stage_descriptor_storage_buffers,
            uniform_buffers_per_stage: limits.max_per_stage_descriptor_uniform_buffers,
            sampled_textures_per_stage: limits.max_per_stage_descriptor_sampled_images,
            samplers_per_stage: limits.max_per_stage_descriptor_samplers,
            storage_textures_per_stage: limits.max_per_stage_descriptor_storage_images,
            dynamic_uniform_buffers: limits.max_descriptor_set_uniform_buffers_dynamic,
            dynamic_storage_buffers: limits.max_descriptor_set_storage_buffers_dynamic,
        }
    }

    fn uniform_alignment(&self) -> u64 {
        let limits = &self.device.properties.limits;
        limits
            .min_uniform_buffer_offset_alignment
            .max(limits.min_storage_buffer_offset_alignment)
    }

    fn slots(&self) -> u32 {
        FRAMES_IN_FLIGHT as u32
    }

    fn create_buffer(
        &mut self,
        label: &'static str,
        bytes: u64,
        usage: BufferUsage,
        contents: Option<&[u8]>,
    ) -> Result<Buffer, BackendError> {
        use vk::BufferUsageFlags as U;
        let (flags, location) = match usage {
            BufferUsage::Storage => (
                U::STORAGE_BUFFER | U::TRANSFER_SRC | U::TRANSFER_DST,
                MemoryLocation::GpuOnly,
            ),
            BufferUsage::Uniform => (U::UNIFORM_BUFFER, MemoryLocation::CpuToGpu),
            BufferUsage::FrameBlocks => (
                U::UNIFORM_BUFFER | U::STORAGE_BUFFER,
                MemoryLocation::CpuToGpu,
            ),
            BufferUsage::Indirect => (
                U::STORAGE_BUFFER | U::INDIRECT_BUFFER | U::TRANSFER_SRC | U::TRANSFER_DST,
                MemoryLocation::GpuOnly,
            ),
            BufferUsage::Vertices => (U::VERTEX_BUFFER | U::TRANSFER_DST, MemoryLocation::GpuOnly),
            BufferUsage::Indices => (U::INDEX_BUFFER | U::TRANSFER_DST, MemoryLocation::GpuOnly),
        };
        let label = label.trim_start_matches("precip ");
        let mut buffer = Buffer::new(&self.device, label, bytes, flags, location)?;
        if let Some(contents) = contents {
            // A new buffer's contents are written at once (waits), not staged: a
            // configuration's buffers would otherwise all sit in staging memory
            // together until its first submission.
            let written = if buffer.is_mapped() {
                buffer.write(0, contents)
            } else {
                upload_at(&self.device, &buffer, 0, contents)
            };
            if let Err(e) = written {
                buffer.destroy(&self.device);
                return Err(e);
            }
        }
        Ok(buffer)
    }

    fn write_buffer(
        &mut self,
        buffer: &mut Buffer,
        offset: u64,
        bytes: &[u8],
    ) -> Result<(), BackendError> {
        if buffer.is_mapped() {
            buffer.write(offset as usize, bytes)
        } else {
            self.uploads.write(&self.device, buffer.raw, offset, bytes)
        }
    }

    fn read_buffer(&mut self, buffer: &Buffer, bytes: u64) -> Result<Vec<u8>, BackendError> {
        self.flush_uploads()?;
        self.wait_until(0)?;
        download(&self.device, buffer, bytes)
    }

    fn create_volume(
        &mut self,
        _label: &'static str,
        [x, y, z]: [u32; 3],
        texels: &[u8],
    ) -> Result<Image, BackendError> {
        let image = Image::volume(&self.device, UVec3::new(x, y, z))?;
        match upload_image(&self.device, &image, texels) {
            Ok(()) => Ok(image),
            Err(e) => {
                image.destroy(&self.device);
                Err(e)
            }
        }
    }

    fn write_volume(&mut self, volume: &Image, texels: &[u8]) -> Result<(), BackendError> {
        self.wait_until(0)?;
        upload_image(&self.device, volume, texels)
    }

    fn group_layout(
        &mut self,
        table: &GroupLayout,
    ) -> Result<vk::DescriptorSetLayout, BackendError> {
        set_layout(&self.device, table)
    }

    fn kernel(
        &mut self,
        program: Program,
        entry_point: &'static str,
        layouts: &[&vk::DescriptorSetLayout],
    ) -> Result<Pipeline, BackendError> {
        let module = self.module(program)?;
        let sets: Vec<vk::DescriptorSetLayout> = layouts.iter().map(|l| **l).collect();
        let pipeline_layout = pipeline_layout(&self.device, &sets)?;
        match compute(&self.device, pipeline_layout, module, entry_point) {
            Ok(pipeline) => Ok(Pipeline {
                pipeline,
                layout: pipeline_layout,
            }),
            Err(e) => {
                // SAFETY: the layout was just made and nothing uses it.
                unsafe {
                    self.device
                        .raw
                        .destroy_pipeline_layout(pipeline_layout, None);
                }
                Err(e)
            }
        }
    }

    fn create_texture(&mut self, desc: &TextureDesc<'_>) -> Result<Texture, BackendError> {
        use vk::ImageLayout as L;
        use vk::ImageUsageFlags as U;
        let (usage, layout) = match desc.usage {
            TextureUsage::DepthAttachment => (
                U::DEPTH_STENCIL_ATTACHMENT | U::SAMPLED | U::TRANSFER_SRC,
                L::DEPTH_STENCIL_READ_ONLY_OPTIMAL,
            ),
            TextureUsage::StorageAndSampled => {
                (U::STORAGE | U::SAMPLED | U::TRANSFER_SRC, L::GENERAL)
            }
            TextureUsage::Sampled => (U::SAMPLED | U::TRANSFER_DST, L::SHADER_READ_ONLY_OPTIMAL),
            TextureUsage::ColourTarget => (
                U::COLOR_ATTACHMENT | U::TRANSFER_SRC,
                L::TRANSFER_SRC_OPTIMAL,
            ),
            TextureUsage::CopyOfTarget => {
                (U::SAMPLED | U::TRANSFER_DST, L::SHADER_READ_ONLY_OPTIMAL)
            }
            TextureUsage::DrawnThenSampled => (
                U::COLOR_ATTACHMENT | U::SAMPLED,
                L::SHADER_READ_ONLY_OPTIMAL,
            ),
        };
        let image = Image::new(
            &self.device,
            &ImageSpec {
                name: desc.label.trim_start_matches("precip "),
                extent: UVec3::new(desc.size.0, desc.size.1, 1),
                format: texel_format(desc.format),
                usage,
            },
        )?;
        let filled = match (desc.contents, desc.usage) {
            (Some(texels), _) => upload_image(&self.device, &image, texels),
            (None, TextureUsage::Sampled | TextureUsage::ColourTarget) => Ok(()),
            (None, _) => to_layout(&self.device, &[&image], layout),
        };
        match filled {
            Ok(()) => Ok(Texture {
                image,
                layout,
                texel_bytes: desc.format.texel_bytes(),
            }),
            Err(e) => {
                image.destroy(&self.device);
                Err(e)
            }
        }
    }

    fn read_texture(&mut self, texture: &Texture) -> Result<Vec<u8>, BackendError> {
        self.wait_until(0)?;
        download_image(
            &self.device,
            &texture.image,
            texture.layout,
            texture.texel_bytes,
        )
    }

    fn create_sampler(&mut self, sampler: Sampler) -> Result<vk::Sampler, BackendError> {
        use vk::SamplerAddressMode as A;
        let (address, compare) = match sampler {
            Sampler::LinearClamp => (A::CLAMP_TO_EDGE, None),
            Sampler::ShadowComparison => (A::CLAMP_TO_EDGE, Some(vk::CompareOp::LESS_OR_EQUAL)),
            Sampler::LinearRepeat => (A::REPEAT, None),
        };
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(address)
            .address_mode_v(address)
            .address_mode_w(address)
            .compare_enable(compare.is_some())
            .compare_op(compare.unwrap_or(vk::CompareOp::NEVER))
            .min_lod(0.0)
            .max_lod(32.0);
        // SAFETY: a valid device and create info.
        unsafe { self.device.raw.create_sampler(&info, None) }
            .map_err(|e| map_vk("creating a sampler", e))
    }

    fn draw_pipeline(
        &mut self,
        draw: &Draw,
        pass: &RenderPassRecipe,
        layouts: &[&vk::DescriptorSetLayout],
        colour: Option<vk::Format>,
    ) -> Result<Pipeline, BackendError> {
        // Any pass of the same attachment formats is compatible with the pipeline.
        let render_pass = self.render_pass(RenderPassKey {
            colour: colour
                .zip(pass.colour)
                .map(|(format, load)| (format, load, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)),
            depth_load: pass.depth_load,
            depth_stored: pass.depth_stored,
            depth_written: pass.draws.iter().any(|d| d.depth_write),
        })?;
        let module = self.module(Program::Render)?;
        let sets: Vec<vk::DescriptorSetLayout> = layouts.iter().map(|l| **l).collect();
        let layout = pipeline_layout(&self.device, &sets)?;
        match draw_pipeline(&self.device, module, layout, render_pass, draw) {
            Ok(pipeline) => Ok(Pipeline { pipeline, layout }),
            Err(e) => {
                // SAFETY: the layout was just made and nothing uses it.
                unsafe { self.device.raw.destroy_pipeline_layout(layout, None) };
                Err(e)
            }
        }
    }

    fn colour_format(&self, target: Target<'_, Self>) -> vk::Format {
        match target {
            Target::Texture(t) => t.image.format,
            Target::Surface(s) => s.format,
        }
    }

    fn rasterises_on_cpu(&self) -> bool {
        self.device.properties.device_type == vk::PhysicalDeviceType::CPU
    }

    fn copy_format(&self, target: Target<'_, Self>) -> Option<TexelFormat> {
        let (format, copyable) = match target {
            // The offscreen image rests ready to be copied.
            Target::Texture(t) => (
                t.image.format,
                t.layout == vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            ),
            Target::Surface(s) => (s.format, s.copyable),
        };
        match format {
            _ if !copyable => None,
            vk::Format::R8G8B8A8_SRGB => Some(TexelFormat::Rgba8UnormSrgb),
            vk::Format::B8G8R8A8_SRGB => Some(TexelFormat::Bgra8UnormSrgb),
            _ => None,
        }
    }

    fn texture_size(&self, texture: &Texture) -> (u32, u32) {
        texture.image.size()
    }

    fn bind_group(
        &mut self,
        layout: &vk::DescriptorSetLayout,
        table: &GroupLayout,
        entries: &[(u32, BindingResource<'_, Self>)],
    ) -> Result<BindGroup, BackendError> {
        let mut sizes: Vec<(vk::DescriptorType, u32)> = Vec::new();
        for b in table.bindings {
            let ty = descriptor_type(b.kind);
            match sizes.iter_mut().find(|(t, _)| *t == ty) {
                Some((_, n)) => *n += 1,
                None => sizes.push((ty, 1)),
            }
        }
        let pool = descriptors::pool(&self.device, table.name, &sizes, 1)?;
        let group = match descriptors::allocate(&self.device, pool, &[*layout]) {
            Ok(sets) => BindGroup { pool, set: sets[0] },
            Err(e) => {
                // SAFETY: the pool was just made and holds no set in use.
                unsafe { self.device.raw.destroy_descriptor_pool(pool, None) };
                return Err(e);
            }
        };
        let mut buffers = Vec::new();
        let mut images = Vec::new();
        for (binding, resource) in entries {
            let kind = table.kind_of(*binding);
            let read_only = vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL;
            match (resource, kind) {
                (
                    BindingResource::Buffer(b),
                    Some(k @ (BindingKind::Uniform { .. } | BindingKind::Storage { .. })),
                ) => {
                    let range = k.block_bytes().unwrap_or(vk::WHOLE_SIZE);
                    buffers.push((*binding, k, buffer_info(b, range)));
                }
                (BindingResource::Volume(v), Some(k @ BindingKind::Texture { .. })) => {
                    images.push((*binding, k, image_info(v.view, read_only)));
                }
                (BindingResource::Texture(t), Some(k @ BindingKind::Texture { .. })) => {
                    images.push((*binding, k, image_info(t.image.view, t.layout)));
                }
                (
                    BindingResource::StorageTexture(t),
                    Some(k @ BindingKind::StorageTextureRgba16Float),
                ) => {
                    let general = vk::ImageLayout::GENERAL;
                    images.push((*binding, k, image_info(t.image.view, general)));
                }
                (BindingResource::Sampler(sampler), Some(k @ BindingKind::Sampler { .. })) => {
                    images.push((*binding, k, descriptors::sampler_info(**sampler)));
                }
                _ => {
                    // SAFETY: the pool's set is not used yet.
                    unsafe { self.device.raw.destroy_descriptor_pool(pool, None) };
                    return Err(BackendError::Device {
                        backend: NAME,
                        message: format!(
                            "{} binding {binding}: the resource does not fit its kind {kind:?} (a bug in precip: please report it)",
                            table.name
                        ),
                    });
                }
            }
        }
        let writes: Vec<vk::WriteDescriptorSet<'_>> = buffers
            .iter()
            .map(|(binding, kind, info)| {
                write(group.set, *binding, descriptor_type(*kind)).buffer_info(info)
            })
            .chain(images.iter().map(|(binding, kind, info)| {
                write(group.set, *binding, descriptor_type(*kind)).image_info(info)
            }))
            .collect();
        // SAFETY: every write names a live buffer or view of the binding's type and
        // usage (checked against the table above).
        unsafe { self.device.raw.update_descriptor_sets(&writes, &[]) };
        Ok(group)
    }

    fn free_slot(&mut self, _slot: u32) -> Result<(), BackendError> {
        // Submissions finish in order: with at most FRAMES_IN_FLIGHT − 1 pending,
        // the last one that used this slot's ring (FRAMES_IN_FLIGHT steps ago) is done.
        self.wait_until(FRAMES_IN_FLIGHT - 1)
    }

    fn settle(&mut self) -> Result<(), BackendError> {
        self.flush_uploads()?;
        self.wait_until(0)
    }

    fn dispatch(
        &mut self,
        dispatches: &[Dispatch<'_, Self>],
        timed: bool,
    ) -> Result<(), BackendError> {
        let device = &self.device;
        let timestamps = self.timestamps.as_ref().filter(|_| timed);
        let slot = self.timed % FRAMES_IN_FLIGHT;
        let first_query = slot as u32 * QUERY_COUNT;
        let mut written = 0;
        let number = self.submitted;
        let copies = self.uploads.take(number);
        let submitted = submit(device, |cb| {
            // SAFETY: `cb` is recording outside a render pass (inside `submit`);
            // the copies' buffers live until the submission finishes (module docs
            // of `uploads`).
            unsafe { uploads::record(device, cb, &copies) };
            let stamp = |written: &mut u32| {
                if let Some(t) = timestamps
                    && *written < QUERY_COUNT
                {
                    let (stage, index) = (
                        vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                        first_query + *written,
                    );
                    // SAFETY: `cb` is recording; the query is within the slot, reset
                    // below before the first.
                    unsafe { t.stamp(device, cb, index, stage) };
                    *written += 1;
                }
            };
            if let Some(t) = timestamps {
                // SAFETY: `cb` is recording outside a render pass; the slot's queries.
                unsafe { t.reset(device, cb, first_query, QUERY_COUNT) };
            }
            stamp(&mut written);
            for d in dispatches {
                let offsets: &[u32] = match &d.offset {
                    Some(o) => std::slice::from_ref(o),
                    None => &[],
                };
                // SAFETY: `cb` is recording outside a render pass (inside `submit`);
                // the pipeline was made with the layout of the set's table, and the
                // offsets match its dynamic bindings (the executor's recipe); an
                // indirect dispatch's buffer is a live `BufferUsage::Indirect` one
                // (INDIRECT_BUFFER usage) and the recipe's offsets are multiples of 16
                // with the 12 bytes within it.
                unsafe {
                    record_dispatch(
                        device,
                        cb,
                        (d.kernel.pipeline, d.kernel.layout),
                        d.group.set,
                        offsets,
                        match d.indirect {
                            Some((buffer, offset)) => Workgroups::Indirect(buffer.raw, offset),
                            None => Workgroups::Count(d.workgroups),
                        },
                    );
                }
                stamp(&mut written);
            }
        });
        let in_flight = match submitted {
            Ok(f) => f,
            Err(e) => {
                self.uploads.restore(copies, number);
                return Err(e);
            }
        };
        self.track(in_flight);
        if timed && let Some(t) = self.timestamps.as_mut() {
            t.written = (first_query, written);
            self.timed += 1;
        }
        Ok(())
    }

    fn submit_frame(
        &mut self,
        frame: &FrameWork<'_, Self>,
        target: Target<'_, Self>,
    ) -> Result<(), BackendError> {
        let (colour, image, semaphores) = match target {
            Target::Texture(t) => ((t.image.view, t.image.format, t.layout), t.image.raw, None),
            Target::Surface(s) => (
                (s.view, s.format, vk::ImageLayout::PRESENT_SRC_KHR),
                s.image,
                Some(s),
            ),
        };
        let begins = self.pass_begins(frame, colour)?;
        let waits =
            semaphores.map(|s| [(s.acquired, vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT)]);
        let signals = semaphores.map(|s| [s.drawn]);
        let semaphores = Semaphores {
            wait: waits.as_ref().map_or(&[], |w| w.as_slice()),
            signal: signals.as_ref().map_or(&[], |s| s.as_slice()),
        };
        let number = self.submitted;
        let copies = self.uploads.take(number);
        let stamps = self.frame_stamps.as_ref();
        let hal = &*self;
        let submitted = submit_synced(&self.device, semaphores, |cb| {
            // SAFETY: `cb` is recording outside a render pass; the copies' buffers
            // live until the submission finishes (module docs of `uploads`).
            unsafe { uploads::record(&hal.device, cb, &copies) };
            // SAFETY: `cb` is recording outside a render pass (`submit_synced`); the
            // frame's objects are the executor's, live until it destroys them (which
            // waits for this submission); the framebuffers are retired after it.
            unsafe { record_frame(hal, cb, frame, (image, colour.2), &begins, stamps) };
        });
        let in_flight = match submitted {
            Ok(f) => f,
            Err(e) => {
                destroy_framebuffers(&self.device, &begins);
                self.uploads.restore(copies, number);
                return Err(e);
            }
        };
        self.track(in_flight);
        self.retired
            .retire(self.submitted, move |d| destroy_framebuffers(d, &begins));
        if let Some(s) = self.frame_stamps.as_mut() {
            s.written = (0, FRAME_QUERY_COUNT);
        }
        Ok(())
    }

    fn frame_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError> {
        self.wait_until(0)?;
        match &self.frame_stamps {
            Some(s) if s.written.1 > 0 => s.pairs_ms(&self.device).map(Some),
            _ => Ok(None),
        }
    }

    fn forget_times(&mut self) {
        for pool in [&mut self.timestamps, &mut self.frame_stamps]
            .into_iter()
            .flatten()
        {
            pool.written = (0, 0);
        }
    }

    fn has_timestamps(&self) -> bool {
        self.timestamps.is_some() || self.frame_stamps.is_some()
    }

    fn kernel_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError> {
        self.wait_until(0)?;
        match &self.timestamps {
            Some(t) => t.elapsed_ms(&self.device).map(Some),
            None => Ok(None),
        }
    }

    fn destroy_buffer(&mut self, buffer: Buffer) {
        self.idle_for_destroy();
        buffer.destroy(&self.device);
    }

    fn destroy_volume(&mut self, volume: Image) {
        self.idle_for_destroy();
        volume.destroy(&self.device);
    }

    fn destroy_texture(&mut self, texture: Texture) {
        self.idle_for_destroy();
        texture.image.destroy(&self.device);
    }

    fn destroy_sampler(&mut self, sampler: vk::Sampler) {
        self.idle_for_destroy();
        // SAFETY: nothing in flight uses the sampler (waited above); destroyed once.
        unsafe { self.device.raw.destroy_sampler(sampler, None) };
    }

    fn destroy_draw_pipeline(&mut self, pipeline: Pipeline) {
        self.destroy_kernel(pipeline);
    }

    fn destroy_bind_group(&mut self, group: BindGroup) {
        self.idle_for_destroy();
        // SAFETY: nothing in flight uses the set (waited above); the pool is freed once.
        unsafe { self.device.raw.destroy_descriptor_pool(group.pool, None) };
    }

    fn destroy_kernel(&mut self, kernel: Pipeline) {
        self.idle_for_destroy();
        // SAFETY: nothing in flight uses the pipeline (waited above); each once.
        unsafe {
            self.device.raw.destroy_pipeline(kernel.pipeline, None);
            self.device.raw.destroy_pipeline_layout(kernel.layout, None);
        }
    }

    fn destroy_group_layout(&mut self, layout: vk::DescriptorSetLayout) {
        self.idle_for_destroy();
        // SAFETY: no pipeline or set made with it is used any more (waited above).
        unsafe { self.device.raw.destroy_descriptor_set_layout(layout, None) };
    }
}

impl Drop for Hal {
    /// Waits for the device, frees what is retired and what the calls made for
    /// themselves (shader modules, render passes, queries); the device goes last.
    fn drop(&mut self) {
        let _ = self.wait_until(0);
        let _ = self.device.wait_idle();
        self.retired.release_all(&self.device);
        self.uploads.destroy(&self.device);
        if let Some(t) = self.timestamps.take() {
            t.destroy(&self.device);
        }
        if let Some(s) = self.frame_stamps.take() {
            s.destroy(&self.device);
        }
        // SAFETY: the device is idle (waited above); each object is destroyed once.
        unsafe {
            for (_, m) in self.modules.drain() {
                self.device.raw.destroy_shader_module(m, None);
            }
            for (_, p) in self.render_passes.drain(..) {
                self.device.raw.destroy_render_pass(p, None);
            }
        }
    }
}

/// Destroys the framebuffers of `begins` (no pending work may use them).
fn destroy_framebuffers(device: &Device, begins: &[Option<PassBegin>]) {
    for b in begins.iter().flatten() {
        // SAFETY: the caller guarantees nothing pending uses it; each once.
        unsafe { device.raw.destroy_framebuffer(b.framebuffer, None) };
    }
}

/// The Vulkan format of `format`.
fn texel_format(format: TexelFormat) -> vk::Format {
    match format {
        TexelFormat::Depth32Float => DEPTH_FORMAT,
        TexelFormat::Rgba16Float => vk::Format::R16G16B16A16_SFLOAT,
        TexelFormat::R8Unorm => vk::Format::R8_UNORM,
        TexelFormat::Rgba8Unorm => vk::Format::R8G8B8A8_UNORM,
        TexelFormat::Rgba8UnormSrgb => OFFSCREEN_FORMAT,
        TexelFormat::Bgra8UnormSrgb => vk::Format::B8G8R8A8_SRGB,
    }
}
