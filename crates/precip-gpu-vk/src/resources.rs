//! The buffers, wind volume and descriptor sets of one configuration, and uploads.

use ash::vk;
use gpu_allocator::MemoryLocation;
use precip_gpu::recipe::{
    DispatchCounts, Frames, cover_bindings, pending_births_bytes, step_bindings,
};
use precip_model::backend::MAX_SUBSTEPS;
use precip_model::cover::GridFrame;
use precip_model::cover::{CoverGrid, CoverStepParams, CoverTexel, DepositBuffer};
use precip_model::particles::step::StepParams;
use precip_model::physics::water_waves::initial_waves;
use precip_model::wind::{WindParams, WindVolume};
use precip_model::{BackendError, GroundMap, Particle};

use crate::buffer::Buffer;
use crate::commands::{compute_barrier, submit};
use crate::descriptors::{self, buffer_info, image_info, write};
use crate::device::Device;
use crate::image::{COLOUR, Image};
use crate::programs::Programs;

/// Steps recorded ahead of the GPU: each has its own ring of uniform blocks and
/// queries, so the host writes step n + 1's while step n runs.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// Everything one configuration allocates.
#[derive(Debug)]
pub struct Resources {
    /// `array<Particle>`.
    pub particles: Buffer,
    /// How many.
    pub particle_count: u32,
    /// `array<CoverTexel>`.
    pub cover: Buffer,
    /// How many.
    pub cover_texel_count: u32,
    /// Two `u32` per cover texel.
    pub deposits: Buffer,
    /// The particles to re-birth this sub-step and the birth kernel's indirect
    /// dispatch (`precip_gpu::recipe::pending_births_bytes`).
    pub pending_births: Buffer,
    /// Ground heights.
    pub ground: Buffer,
    /// The water bodies' waves (`precip_model::physics::water_waves`).
    pub waves: Buffer,
    /// Their grid.
    pub wave_frame: GridFrame,
    /// `Frames`.
    pub frames: Buffer,
    wind_params: Buffer,
    /// The wind volume.
    pub wind: Image,
    /// One `StepParams` per sub-step at `uniform_stride`, [`FRAMES_IN_FLIGHT`] rings.
    pub step_uniforms: Buffer,
    /// One `CoverStepParams` per sub-step.
    pub cover_uniforms: Buffer,
    /// Bytes between sub-steps' blocks.
    pub uniform_stride: u64,
    pool: vk::DescriptorPool,
    /// Set 0 of the particle kernels.
    pub step_set: vk::DescriptorSet,
    /// Set 0 of the cover kernel.
    pub cover_set: vk::DescriptorSet,
}

const STORAGE: vk::BufferUsageFlags = vk::BufferUsageFlags::from_raw(
    vk::BufferUsageFlags::STORAGE_BUFFER.as_raw()
        | vk::BufferUsageFlags::TRANSFER_SRC.as_raw()
        | vk::BufferUsageFlags::TRANSFER_DST.as_raw(),
);

/// Copies `bytes` into `target` through a staging buffer (waits).
pub fn upload(device: &Device, target: &Buffer, bytes: &[u8]) -> Result<(), BackendError> {
    if bytes.is_empty() {
        return Ok(());
    }
    let mut staging = Buffer::new(
        device,
        "staging",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    staging.write(0, bytes)?;
    let result = submit(device, |cb| {
        let region = vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size: bytes.len() as u64,
        };
        // SAFETY: both buffers are live and large enough; `cb` is recording.
        unsafe {
            device
                .raw
                .cmd_copy_buffer(cb, staging.raw, target.raw, &[region])
        };
        // SAFETY: `cb` is recording, outside a render pass (inside `submit`).
        unsafe { compute_barrier(device, cb) };
    })
    .and_then(|f| f.wait(device));
    staging.destroy(device);
    result
}

/// Copies the first `size` bytes of `source` back (waits).
pub fn download(device: &Device, source: &Buffer, size: u64) -> Result<Vec<u8>, BackendError> {
    if size == 0 {
        return Ok(Vec::new());
    }
    let staging = Buffer::new(
        device,
        "read-back",
        size,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    let result = submit(device, |cb| {
        let region = vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size,
        };
        // SAFETY: both buffers are live and large enough; `cb` is recording.
        unsafe {
            device
                .raw
                .cmd_copy_buffer(cb, source.raw, staging.raw, &[region])
        };
    })
    .and_then(|f| f.wait(device))
    .and_then(|()| staging.read(size as usize));
    staging.destroy(device);
    result
}

/// A barrier moving all of colour `image` from layout `old` (after accesses `src`)
/// to `new` (before accesses `dst`).
fn layout_barrier(
    image: &Image,
    (old, src): (vk::ImageLayout, vk::AccessFlags),
    (new, dst): (vk::ImageLayout, vk::AccessFlags),
) -> vk::ImageMemoryBarrier<'static> {
    vk::ImageMemoryBarrier::default()
        .old_layout(old)
        .new_layout(new)
        .src_access_mask(src)
        .dst_access_mask(dst)
        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .image(image.raw)
        .subresource_range(COLOUR)
}

/// Fills a sampled image's texels (`bytes` tightly packed) and leaves it in
/// `SHADER_READ_ONLY_OPTIMAL` for every shader stage (waits).
pub fn upload_image(device: &Device, image: &Image, bytes: &[u8]) -> Result<(), BackendError> {
    let mut staging = Buffer::new(
        device,
        "image staging",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    staging.write(0, bytes)?;
    let e = image.extent;
    let result = submit(device, |cb| {
        let barrier = |old, new, src, dst| layout_barrier(image, (old, src), (new, dst));
        let to_transfer = barrier(
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            vk::AccessFlags::empty(),
            vk::AccessFlags::TRANSFER_WRITE,
        );
        let to_shader = barrier(
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            vk::AccessFlags::TRANSFER_WRITE,
            vk::AccessFlags::SHADER_READ,
        );
        let region = vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers {
                aspect_mask: vk::ImageAspectFlags::COLOR,
                mip_level: 0,
                base_array_layer: 0,
                layer_count: 1,
            })
            .image_extent(vk::Extent3D {
                width: e.x,
                height: e.y,
                depth: e.z,
            });
        // SAFETY: `cb` is recording; the image and staging buffer are live; the
        // barriers move the whole image through the layouts the copy and the shaders
        // need (the earlier contents are discarded: UNDEFINED), after any earlier
        // work that read it.
        unsafe {
            device.raw.cmd_pipeline_barrier(
                cb,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::TRANSFER,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[to_transfer],
            );
            device.raw.cmd_copy_buffer_to_image(
                cb,
                staging.raw,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
            );
            device.raw.cmd_pipeline_barrier(
                cb,
                vk::PipelineStageFlags::TRANSFER,
                vk::PipelineStageFlags::COMPUTE_SHADER
                    | vk::PipelineStageFlags::VERTEX_SHADER
                    | vk::PipelineStageFlags::FRAGMENT_SHADER,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[to_shader],
            );
        }
    })
    .and_then(|f| f.wait(device));
    staging.destroy(device);
    result
}

/// Moves `images` (colour, just made) to `GENERAL`, where shaders both write them as
/// storage images and sample them; waits.
pub fn to_general(device: &Device, images: &[&Image]) -> Result<(), BackendError> {
    let barriers: Vec<vk::ImageMemoryBarrier<'_>> = images
        .iter()
        .map(|image| {
            layout_barrier(
                image,
                (vk::ImageLayout::UNDEFINED, vk::AccessFlags::empty()),
                (
                    vk::ImageLayout::GENERAL,
                    vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
                ),
            )
        })
        .collect();
    submit(device, |cb| {
        // SAFETY: `cb` is recording; the images are live and unused (just made).
        unsafe {
            device.raw.cmd_pipeline_barrier(
                cb,
                vk::PipelineStageFlags::TOP_OF_PIPE,
                vk::PipelineStageFlags::COMPUTE_SHADER
                    | vk::PipelineStageFlags::VERTEX_SHADER
                    | vk::PipelineStageFlags::FRAGMENT_SHADER,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &barriers,
            );
        }
    })
    .and_then(|f| f.wait(device))
}

impl Resources {
    /// Allocates, uploads and binds everything but the particles (the init kernel
    /// fills them). On any failure everything made so far is freed.
    pub fn new(
        device: &Device,
        programs: &Programs,
        particle_count: u32,
        ground: &GroundMap,
        cover: &CoverGrid,
        frames: &Frames,
        wind: &WindVolume,
    ) -> Result<Self, BackendError> {
        let align = device
            .properties
            .limits
            .min_uniform_buffer_offset_alignment
            .max(16);
        let block = size_of::<StepParams>().max(size_of::<CoverStepParams>()) as u64;
        let uniform_stride = block.div_ceil(align) * align;
        let blocks = u64::from(MAX_SUBSTEPS) * FRAMES_IN_FLIGHT as u64;
        let cover_bytes: &[u8] = bytemuck::cast_slice(&cover.texels);
        let ground_words = ground.gpu_words();
        let ground_bytes: &[u8] = bytemuck::cast_slice(&ground_words);
        let waves: Vec<i32> = initial_waves(&frames.waves, ground);
        let wave_bytes: &[u8] = bytemuck::cast_slice(&waves);
        let uniform_usage = vk::BufferUsageFlags::UNIFORM_BUFFER;
        let specs = [
            (
                "particles",
                u64::from(particle_count) * size_of::<Particle>() as u64,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "cover",
                cover_bytes.len() as u64,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "deposits",
                DepositBuffer::bytes_for(cover.texels.len()) as u64,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "pending births",
                pending_births_bytes(particle_count),
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::GpuOnly,
            ),
            (
                "ground",
                ground_bytes.len() as u64,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "waves",
                wave_bytes.len() as u64,
                STORAGE,
                MemoryLocation::GpuOnly,
            ),
            (
                "frames",
                size_of::<Frames>() as u64,
                uniform_usage,
                MemoryLocation::CpuToGpu,
            ),
            (
                "wind params",
                size_of::<WindParams>() as u64,
                uniform_usage,
                MemoryLocation::CpuToGpu,
            ),
            (
                "step uniforms",
                uniform_stride * blocks,
                uniform_usage,
                MemoryLocation::CpuToGpu,
            ),
            (
                "cover uniforms",
                uniform_stride * blocks,
                uniform_usage,
                MemoryLocation::CpuToGpu,
            ),
        ];
        let mut made: Vec<Buffer> = Vec::with_capacity(specs.len());
        let free = |made: Vec<Buffer>| made.into_iter().for_each(|b| b.destroy(device));
        for (name, size, usage, location) in specs {
            match Buffer::new(device, name, size, usage, location) {
                Ok(b) => made.push(b),
                Err(e) => {
                    free(made);
                    return Err(e);
                }
            }
        }
        let volume = match Image::volume(device, wind.spec.texels) {
            Ok(v) => v,
            Err(e) => {
                free(made);
                return Err(e);
            }
        };
        use vk::DescriptorType as T;
        let pool = match descriptors::pool(
            device,
            "simulation",
            &[
                (T::UNIFORM_BUFFER_DYNAMIC, 2),
                (T::UNIFORM_BUFFER, 2),
                (T::SAMPLED_IMAGE, 1),
                (T::STORAGE_BUFFER, 8),
            ],
            2,
        ) {
            Ok(p) => p,
            Err(e) => {
                free(made);
                volume.destroy(device);
                return Err(e);
            }
        };
        let [
            particles,
            cover_buffer,
            deposits,
            pending_births,
            ground_buffer,
            waves_buffer,
            frames_buffer,
            wind_params,
            step_uniforms,
            cover_uniforms,
        ] = match <[Buffer; 10]>::try_from(made) {
            Ok(all) => all,
            Err(made) => {
                free(made);
                volume.destroy(device);
                // SAFETY: the pool was just made and holds no set in use.
                unsafe { device.raw.destroy_descriptor_pool(pool, None) };
                return Err(BackendError::Device {
                    backend: crate::error::NAME,
                    message: "a buffer of the configuration is missing (a bug in precip: please report it)".into(),
                });
            }
        };
        let mut resources = Self {
            particles,
            particle_count,
            cover: cover_buffer,
            cover_texel_count: cover.texels.len() as u32,
            deposits,
            pending_births,
            ground: ground_buffer,
            waves: waves_buffer,
            wave_frame: frames.waves,
            frames: frames_buffer,
            wind_params,
            wind: volume,
            step_uniforms,
            cover_uniforms,
            uniform_stride,
            pool,
            step_set: vk::DescriptorSet::null(),
            cover_set: vk::DescriptorSet::null(),
        };
        match resources.fill(
            device,
            programs,
            [cover_bytes, ground_bytes, wave_bytes],
            frames,
            wind,
        ) {
            Ok(()) => Ok(resources),
            Err(e) => {
                resources.destroy(device);
                Err(e)
            }
        }
    }

    /// Uploads the initial data and writes the descriptor sets.
    fn fill(
        &mut self,
        device: &Device,
        programs: &Programs,
        [cover_bytes, ground_bytes, wave_bytes]: [&[u8]; 3],
        frames: &Frames,
        wind: &WindVolume,
    ) -> Result<(), BackendError> {
        upload(device, &self.cover, cover_bytes)?;
        upload(device, &self.waves, wave_bytes)?;
        upload(
            device,
            &self.deposits,
            &vec![0u8; DepositBuffer::bytes_for(cover_bytes.len() / size_of::<CoverTexel>())],
        )?;
        upload(device, &self.ground, ground_bytes)?;
        self.frames.write(0, bytemuck::bytes_of(frames))?;
        self.wind_params
            .write(0, bytemuck::bytes_of(&wind.gpu_params()))?;
        upload_image(device, &self.wind, wind.as_bytes())?;
        let sets = descriptors::allocate(
            device,
            self.pool,
            &[programs.step_set_layout, programs.cover_set_layout],
        )?;
        let (step_set, cover_set) = (sets[0], sets[1]);
        use vk::DescriptorType as T;
        let info = buffer_info;
        let whole = vk::WHOLE_SIZE;
        let step_params = info(&self.step_uniforms, size_of::<StepParams>() as u64);
        let frames_info = info(&self.frames, size_of::<Frames>() as u64);
        let wind_info = info(&self.wind_params, size_of::<WindParams>() as u64);
        let ground_info = info(&self.ground, whole);
        let particles_info = info(&self.particles, whole);
        let deposits_info = info(&self.deposits, whole);
        let births_info = info(&self.pending_births, whole);
        let waves_info = info(&self.waves, whole);
        let cover_params = info(&self.cover_uniforms, size_of::<CoverStepParams>() as u64);
        let cover_info = info(&self.cover, whole);
        let image = image_info(self.wind.view);
        let writes = [
            write(
                step_set,
                step_bindings::STEP_PARAMS,
                T::UNIFORM_BUFFER_DYNAMIC,
            )
            .buffer_info(&step_params),
            write(step_set, step_bindings::FRAMES, T::UNIFORM_BUFFER).buffer_info(&frames_info),
            write(step_set, step_bindings::WIND, T::UNIFORM_BUFFER).buffer_info(&wind_info),
            write(step_set, step_bindings::WIND_VOLUME, T::SAMPLED_IMAGE).image_info(&image),
            write(step_set, step_bindings::GROUND_HEIGHT, T::STORAGE_BUFFER)
                .buffer_info(&ground_info),
            write(step_set, step_bindings::PARTICLES, T::STORAGE_BUFFER)
                .buffer_info(&particles_info),
            write(step_set, step_bindings::DEPOSITS, T::STORAGE_BUFFER).buffer_info(&deposits_info),
            write(step_set, step_bindings::PENDING_BIRTHS, T::STORAGE_BUFFER)
                .buffer_info(&births_info),
            write(step_set, step_bindings::WAVES, T::STORAGE_BUFFER).buffer_info(&waves_info),
            write(step_set, step_bindings::COVER, T::STORAGE_BUFFER).buffer_info(&cover_info),
            write(
                cover_set,
                cover_bindings::COVER_PARAMS,
                T::UNIFORM_BUFFER_DYNAMIC,
            )
            .buffer_info(&cover_params),
            write(cover_set, cover_bindings::COVER, T::STORAGE_BUFFER).buffer_info(&cover_info),
            write(cover_set, cover_bindings::DEPOSITS, T::STORAGE_BUFFER)
                .buffer_info(&deposits_info),
        ];
        // SAFETY: every write names a live buffer or view of the right type and usage.
        unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
        self.step_set = step_set;
        self.cover_set = cover_set;
        Ok(())
    }

    /// What the sub-step's dispatches run over.
    #[must_use]
    pub fn dispatch_counts(&self) -> DispatchCounts {
        DispatchCounts::of(
            self.particle_count,
            self.cover_texel_count,
            &self.wave_frame,
        )
    }

    /// Byte offset of in-flight slot `slot`'s ring of uniform blocks.
    #[must_use]
    pub fn slot_base(&self, slot: usize) -> u64 {
        slot as u64 * self.uniform_stride * u64::from(MAX_SUBSTEPS)
    }

    /// Writes the wind's uniform block.
    pub fn write_wind_params(&mut self, params: &WindParams) -> Result<(), BackendError> {
        self.wind_params.write(0, bytemuck::bytes_of(params))
    }

    /// Frees everything (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; the pool (and its sets) is destroyed once.
        unsafe { device.raw.destroy_descriptor_pool(self.pool, None) };
        for b in [
            self.particles,
            self.cover,
            self.deposits,
            self.pending_births,
            self.ground,
            self.waves,
            self.frames,
            self.wind_params,
            self.step_uniforms,
            self.cover_uniforms,
        ] {
            b.destroy(device);
        }
        self.wind.destroy(device);
    }
}

/// Bytes of one cover texel.
pub const COVER_TEXEL_BYTES: u64 = size_of::<CoverTexel>() as u64;
