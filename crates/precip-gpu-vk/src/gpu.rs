//! [`Hal`]: the device calls of [`precip_gpu::Gpu`] on Vulkan (wgpu twin:
//! `precip_gpu_wgpu::gpu`), and the submissions in flight they share with the
//! frame. Nothing here knows what the buffers hold or which kernels run: the
//! executor of `precip-gpu` decides.
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
use precip_gpu::gpu::{BindingResource, Dispatch, Gpu};
use precip_gpu::resources::BufferUsage;
use precip_gpu::shaders::Program;
use precip_model::BackendError;

use crate::bind_groups::{descriptor_type, set_layout};
use crate::buffer::Buffer;
use crate::commands::{InFlight, record_dispatch, submit};
use crate::descriptors::{self, buffer_info, image_info, write};
use crate::device::Device;
use crate::error::NAME;
use crate::image::Image;
use crate::programs::{compute, module, pipeline_layout};
use crate::query::{QUERY_COUNT, Timestamps};
use crate::retire::Retired;
use crate::transfer::{download, upload_at, upload_image};

pub use crate::transfer::FRAMES_IN_FLIGHT;

/// A compute pipeline and its layout.
#[derive(Debug)]
pub struct Kernel {
    pipeline: vk::Pipeline,
    layout: vk::PipelineLayout,
}

/// A descriptor set and the pool it was allocated from.
#[derive(Debug)]
pub struct BindGroup {
    pool: vk::DescriptorPool,
    set: vk::DescriptorSet,
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
    /// Timestamp queries, where the device has them.
    pub timestamps: Option<Timestamps>,
    /// Timed submissions so far (picks the queries' slot).
    timed: usize,
    modules: HashMap<Program, vk::ShaderModule>,
    /// The device.
    pub device: Device,
}

impl Hal {
    /// The calls on `device`.
    pub fn new(device: Device) -> Result<Self, BackendError> {
        Ok(Self {
            in_flight: VecDeque::new(),
            submitted: 0,
            completed: 0,
            retired: Retired::default(),
            timestamps: Timestamps::new(&device)?,
            timed: 0,
            modules: HashMap::new(),
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
        Ok(())
    }

    /// Records a submission in flight.
    pub fn track(&mut self, f: InFlight) {
        self.in_flight.push_back((self.submitted, f));
        self.submitted += 1;
    }

    /// Frees everything the calls made for themselves (shader modules, queries).
    ///
    /// # Safety
    /// Nothing is in flight and the device is idle; runs once.
    pub unsafe fn destroy(&mut self) {
        if let Some(t) = self.timestamps.take() {
            t.destroy(&self.device);
        }
        for (_, m) in self.modules.drain() {
            // SAFETY: the caller guarantees the device is idle; each module once.
            unsafe { self.device.raw.destroy_shader_module(m, None) };
        }
    }

    fn module(&mut self, program: Program) -> Result<vk::ShaderModule, BackendError> {
        if let Some(m) = self.modules.get(&program) {
            return Ok(*m);
        }
        let m = module(&self.device, program)?;
        self.modules.insert(program, m);
        Ok(m)
    }

    /// Waits for everything in flight, so an object may be freed (best effort: a
    /// lost device frees anyway, nothing will run again).
    fn idle_for_destroy(&mut self) {
        let _ = self.wait_until(0);
    }
}

impl Gpu for Hal {
    type Buffer = Buffer;
    type Volume = Image;
    type GroupLayout = vk::DescriptorSetLayout;
    type BindGroup = BindGroup;
    type Kernel = Kernel;

    fn limits(&self) -> precip_model::DeviceLimits {
        self.device.limits()
    }

    fn uniform_alignment(&self) -> u64 {
        self.device
            .properties
            .limits
            .min_uniform_buffer_offset_alignment
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
        };
        let label = label.trim_start_matches("precip ");
        let mut buffer = Buffer::new(&self.device, label, bytes, flags, location)?;
        if let Some(contents) = contents {
            let written = self.write_buffer(&mut buffer, 0, contents);
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
            upload_at(&self.device, buffer, offset, bytes)
        }
    }

    fn read_buffer(&mut self, buffer: &Buffer, bytes: u64) -> Result<Vec<u8>, BackendError> {
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
        layout: &vk::DescriptorSetLayout,
    ) -> Result<Kernel, BackendError> {
        let module = self.module(program)?;
        let pipeline_layout = pipeline_layout(&self.device, *layout)?;
        match compute(&self.device, pipeline_layout, module, entry_point) {
            Ok(pipeline) => Ok(Kernel {
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
            match (resource, kind) {
                (BindingResource::Buffer(b), Some(k @ BindingKind::Uniform { min_bytes, .. })) => {
                    buffers.push((*binding, k, buffer_info(b, min_bytes)));
                }
                (BindingResource::Buffer(b), Some(k @ BindingKind::Storage { .. })) => {
                    buffers.push((*binding, k, buffer_info(b, vk::WHOLE_SIZE)));
                }
                (BindingResource::Volume(v), Some(k @ BindingKind::Texture { .. })) => {
                    images.push((*binding, k, image_info(v.view)));
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
        let in_flight = submit(device, |cb| {
            let stamp = |written: &mut u32| {
                if let Some(t) = timestamps
                    && *written < QUERY_COUNT
                {
                    // SAFETY: `cb` is recording; the query index is within the slot.
                    unsafe {
                        device.raw.cmd_write_timestamp(
                            cb,
                            vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                            t.pool,
                            first_query + *written,
                        );
                    }
                    *written += 1;
                }
            };
            if let Some(t) = timestamps {
                // SAFETY: `cb` is recording; resets the queries this submission writes.
                unsafe {
                    device
                        .raw
                        .cmd_reset_query_pool(cb, t.pool, first_query, QUERY_COUNT);
                }
            }
            stamp(&mut written);
            for d in dispatches {
                let offsets: &[u32] = match &d.offset {
                    Some(o) => std::slice::from_ref(o),
                    None => &[],
                };
                // SAFETY: `cb` is recording outside a render pass (inside `submit`);
                // the pipeline was made with the layout of the set's table, and the
                // offsets match its dynamic bindings (the executor's recipe).
                unsafe {
                    record_dispatch(
                        device,
                        cb,
                        (d.kernel.pipeline, d.kernel.layout),
                        d.group.set,
                        offsets,
                        d.workgroups,
                    );
                }
                stamp(&mut written);
            }
        })?;
        self.track(in_flight);
        if timed && let Some(t) = self.timestamps.as_mut() {
            t.written = written;
            t.slot = slot;
            self.timed += 1;
        }
        Ok(())
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

    fn destroy_bind_group(&mut self, group: BindGroup) {
        self.idle_for_destroy();
        // SAFETY: nothing in flight uses the set (waited above); the pool is freed once.
        unsafe { self.device.raw.destroy_descriptor_pool(group.pool, None) };
    }

    fn destroy_kernel(&mut self, kernel: Kernel) {
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
