//! Recording and submitting command buffers: one submission in flight at a time,
//! waited for (and its command buffer freed) before the next one or a read-back.

use ash::vk;
use precip_model::BackendError;

use crate::device::Device;
use crate::error::map_vk;

/// A submitted command buffer and the fence that says it is done.
#[derive(Debug)]
pub struct InFlight {
    fence: vk::Fence,
    commands: vk::CommandBuffer,
}

/// Semaphores a submission waits on (at a stage) and signals (a swapchain's).
#[derive(Debug, Clone, Copy, Default)]
pub struct Semaphores<'a> {
    /// Waited before the stage.
    pub wait: &'a [(vk::Semaphore, vk::PipelineStageFlags)],
    /// Signalled when the work is done.
    pub signal: &'a [vk::Semaphore],
}

/// Records with `record` and submits; returns what to wait for.
pub fn submit(
    device: &Device,
    record: impl FnOnce(vk::CommandBuffer),
) -> Result<InFlight, BackendError> {
    submit_synced(device, Semaphores::default(), record)
}

/// [`submit`], waiting on and signalling `semaphores`.
pub fn submit_synced(
    device: &Device,
    semaphores: Semaphores<'_>,
    record: impl FnOnce(vk::CommandBuffer),
) -> Result<InFlight, BackendError> {
    let info = vk::CommandBufferAllocateInfo::default()
        .command_pool(device.command_pool)
        .level(vk::CommandBufferLevel::PRIMARY)
        .command_buffer_count(1);
    // SAFETY: the pool belongs to this device and is used from this thread only.
    let commands = unsafe { device.raw.allocate_command_buffers(&info) }
        .map_err(|e| map_vk("allocating a command buffer", e))?[0];
    let begin =
        vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
    // SAFETY: a fresh primary command buffer.
    unsafe { device.raw.begin_command_buffer(commands, &begin) }
        .map_err(|e| map_vk("beginning a command buffer", e))?;
    record(commands);
    // SAFETY: the buffer is recording.
    unsafe { device.raw.end_command_buffer(commands) }
        .map_err(|e| map_vk("ending a command buffer", e))?;
    // SAFETY: a valid device.
    let fence = unsafe {
        device
            .raw
            .create_fence(&vk::FenceCreateInfo::default(), None)
    }
    .map_err(|e| map_vk("creating a fence", e))?;
    let buffers = [commands];
    let (wait, stages): (Vec<_>, Vec<_>) = semaphores.wait.iter().copied().unzip();
    let submit = vk::SubmitInfo::default()
        .command_buffers(&buffers)
        .wait_semaphores(&wait)
        .wait_dst_stage_mask(&stages)
        .signal_semaphores(semaphores.signal);
    // SAFETY: the queue belongs to this device; the command buffer is executable.
    unsafe { device.raw.queue_submit(device.queue, &[submit], fence) }
        .map_err(|e| map_vk("submitting work", e))?;
    Ok(InFlight { fence, commands })
}

impl InFlight {
    /// Waits for the work, then frees its fence and command buffer.
    pub fn wait(self, device: &Device) -> Result<(), BackendError> {
        // SAFETY: the fence and buffer belong to this device; after the wait the GPU no
        // longer uses them.
        unsafe {
            let waited = device.raw.wait_for_fences(&[self.fence], true, u64::MAX);
            device.raw.destroy_fence(self.fence, None);
            device
                .raw
                .free_command_buffers(device.command_pool, &[self.commands]);
            waited.map_err(|e| map_vk("waiting for the GPU", e))
        }
    }
}

/// A barrier making compute writes visible to the next compute and transfer reads.
pub fn compute_barrier(device: &Device, commands: vk::CommandBuffer) {
    let barrier = vk::MemoryBarrier::default()
        .src_access_mask(vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE)
        .dst_access_mask(
            vk::AccessFlags::SHADER_READ
                | vk::AccessFlags::SHADER_WRITE
                | vk::AccessFlags::TRANSFER_READ,
        );
    // SAFETY: `commands` is recording.
    unsafe {
        device.raw.cmd_pipeline_barrier(
            commands,
            vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER,
            vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER,
            vk::DependencyFlags::empty(),
            &[barrier],
            &[],
            &[],
        );
    }
}

/// A global memory barrier from `src` (stages, accesses) to `dst`.
pub fn memory_barrier(
    device: &Device,
    commands: vk::CommandBuffer,
    src: (vk::PipelineStageFlags, vk::AccessFlags),
    dst: (vk::PipelineStageFlags, vk::AccessFlags),
) {
    let barrier = vk::MemoryBarrier::default()
        .src_access_mask(src.1)
        .dst_access_mask(dst.1);
    // SAFETY: `commands` is recording, outside a render pass.
    unsafe {
        device.raw.cmd_pipeline_barrier(
            commands,
            src.0,
            dst.0,
            vk::DependencyFlags::empty(),
            &[barrier],
            &[],
            &[],
        );
    }
}
