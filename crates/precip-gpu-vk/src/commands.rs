//! Recording and submitting command buffers, each behind a fence; the pairs of
//! finished submissions are reused by the next ones, so steady frames allocate none.

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

/// A command buffer and an unsignalled fence: a finished submission's, or new ones
/// while fewer exist than have ever been in flight at once.
fn take_pair(device: &Device) -> Result<(vk::CommandBuffer, vk::Fence), BackendError> {
    if let Some(pair) = device.recycled.lock().ok().and_then(|mut free| free.pop()) {
        return Ok(pair);
    }
    let info = vk::CommandBufferAllocateInfo::default()
        .command_pool(device.command_pool)
        .level(vk::CommandBufferLevel::PRIMARY)
        .command_buffer_count(1);
    // SAFETY: the pool belongs to this device and is used from this thread only.
    let commands = unsafe { device.raw.allocate_command_buffers(&info) }
        .map_err(|e| map_vk("allocating a command buffer", e))?[0];
    // SAFETY: a valid device.
    match unsafe {
        device
            .raw
            .create_fence(&vk::FenceCreateInfo::default(), None)
    } {
        Ok(fence) => Ok((commands, fence)),
        Err(e) => {
            // SAFETY: the buffer was just allocated and never submitted.
            unsafe {
                device
                    .raw
                    .free_command_buffers(device.command_pool, &[commands])
            };
            Err(map_vk("creating a fence", e))
        }
    }
}

/// Returns a pair no pending work uses (its fence unsignalled) for the next
/// submission; the command buffer is reset on its next `begin`.
fn give_back(device: &Device, pair: (vk::CommandBuffer, vk::Fence)) {
    match device.recycled.lock() {
        Ok(mut free) => free.push(pair),
        // A poisoned list (a panic elsewhere): free the pair now instead.
        // SAFETY: no pending work uses the pair.
        Err(_) => unsafe {
            device.raw.destroy_fence(pair.1, None);
            device
                .raw
                .free_command_buffers(device.command_pool, &[pair.0]);
        },
    }
}

/// [`submit`], waiting on and signalling `semaphores`. Command buffers and fences are
/// reused: a finished submission's pair serves the next one, so a frame allocates
/// none. On any error the pair goes back unused; nothing leaks.
pub fn submit_synced(
    device: &Device,
    semaphores: Semaphores<'_>,
    record: impl FnOnce(vk::CommandBuffer),
) -> Result<InFlight, BackendError> {
    let (commands, fence) = take_pair(device)?;
    let begin =
        vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
    let recorded = (|| {
        // SAFETY: the buffer is not pending (its last submission was waited for); its
        // pool allows resetting single buffers, which `begin` does implicitly.
        unsafe { device.raw.begin_command_buffer(commands, &begin) }
            .map_err(|e| map_vk("beginning a command buffer", e))?;
        record(commands);
        // SAFETY: the buffer is recording.
        unsafe { device.raw.end_command_buffer(commands) }
            .map_err(|e| map_vk("ending a command buffer", e))?;
        let buffers = [commands];
        let (wait, stages): (Vec<_>, Vec<_>) = semaphores.wait.iter().copied().unzip();
        let submit = vk::SubmitInfo::default()
            .command_buffers(&buffers)
            .wait_semaphores(&wait)
            .wait_dst_stage_mask(&stages)
            .signal_semaphores(semaphores.signal);
        // SAFETY: the queue belongs to this device; the command buffer is executable;
        // the fence is unsignalled.
        unsafe { device.raw.queue_submit(device.queue, &[submit], fence) }
            .map_err(|e| map_vk("submitting work", e))
    })();
    match recorded {
        Ok(()) => Ok(InFlight { fence, commands }),
        Err(e) => {
            give_back(device, (commands, fence));
            Err(e)
        }
    }
}

impl InFlight {
    /// Waits for the work, then hands its command buffer and fence to the next
    /// submission.
    pub fn wait(self, device: &Device) -> Result<(), BackendError> {
        // SAFETY: the fence belongs to this device.
        let waited = unsafe { device.raw.wait_for_fences(&[self.fence], true, u64::MAX) }
            .map_err(|e| map_vk("waiting for the GPU", e));
        // SAFETY: after a successful wait the GPU no longer uses the pair; after a
        // failed one (a lost device) nothing will run again, so it is freed.
        unsafe {
            if waited.is_ok() && device.raw.reset_fences(&[self.fence]).is_ok() {
                give_back(device, (self.commands, self.fence));
            } else {
                device.raw.destroy_fence(self.fence, None);
                device
                    .raw
                    .free_command_buffers(device.command_pool, &[self.commands]);
            }
        }
        waited
    }
}

/// A barrier making compute writes visible to the next compute and transfer reads.
///
/// # Safety
/// `commands` is a command buffer of `device` in the recording state, outside a
/// render pass.
pub unsafe fn compute_barrier(device: &Device, commands: vk::CommandBuffer) {
    let (stages, a) = (
        vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER,
        vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
    );
    let written = vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE;
    // The next dispatch may read its workgroups from what this one wrote.
    let read = (
        stages | vk::PipelineStageFlags::DRAW_INDIRECT,
        a | vk::AccessFlags::TRANSFER_READ | vk::AccessFlags::INDIRECT_COMMAND_READ,
    );
    // SAFETY: the caller's guarantees, passed on.
    unsafe {
        memory_barrier(device, commands, (stages, written), read);
    }
}

/// The stages that read images in shaders.
pub const SHADER_STAGES: vk::PipelineStageFlags = vk::PipelineStageFlags::from_raw(
    vk::PipelineStageFlags::COMPUTE_SHADER.as_raw()
        | vk::PipelineStageFlags::VERTEX_SHADER.as_raw()
        | vk::PipelineStageFlags::FRAGMENT_SHADER.as_raw(),
);

/// Image barriers from the stages `src` to `dst`.
///
/// # Safety
/// `commands` is a command buffer of `device` in the recording state, outside a
/// render pass; the images the barriers name are live.
pub unsafe fn image_barriers(
    device: &Device,
    commands: vk::CommandBuffer,
    (src, dst): (vk::PipelineStageFlags, vk::PipelineStageFlags),
    barriers: &[vk::ImageMemoryBarrier<'_>],
) {
    let none = vk::DependencyFlags::empty();
    // SAFETY: the caller's guarantees.
    unsafe {
        device
            .raw
            .cmd_pipeline_barrier(commands, src, dst, none, &[], &[], barriers);
    }
}

/// A global memory barrier from `src` (stages, accesses) to `dst`.
///
/// # Safety
/// `commands` is a command buffer of `device` in the recording state, outside a
/// render pass.
pub unsafe fn memory_barrier(
    device: &Device,
    commands: vk::CommandBuffer,
    src: (vk::PipelineStageFlags, vk::AccessFlags),
    dst: (vk::PipelineStageFlags, vk::AccessFlags),
) {
    let barrier = vk::MemoryBarrier::default()
        .src_access_mask(src.1)
        .dst_access_mask(dst.1);
    // SAFETY: the caller guarantees `commands` is recording outside a render pass.
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

/// A dispatch's workgroups.
#[derive(Debug, Clone, Copy)]
pub enum Workgroups {
    /// `(x, y)`, `z` 1.
    Count((u32, u32)),
    /// Read from a buffer (made with `INDIRECT_BUFFER` usage) at a byte offset:
    /// `(x, y, z)`, written by an earlier dispatch.
    Indirect(vk::Buffer, u64),
}

/// Records one compute dispatch: binds `pipeline` and `set` (with its dynamic
/// `offsets`) on `layout`, dispatches `groups`, and a [`compute_barrier`].
///
/// # Safety
/// - `commands` is a command buffer of `device` in the recording state, outside a
///   render pass.
/// - `pipeline`, `layout` and `set` are live, made for each other, and `offsets`
///   has one entry per dynamic binding of the set.
/// - An indirect buffer is live, has `INDIRECT_BUFFER` usage and 12 bytes from the
///   offset, which is a multiple of 4.
pub unsafe fn record_dispatch(
    device: &Device,
    commands: vk::CommandBuffer,
    (pipeline, layout): (vk::Pipeline, vk::PipelineLayout),
    set: vk::DescriptorSet,
    offsets: &[u32],
    groups: Workgroups,
) {
    // SAFETY: the caller guarantees the command buffer is recording outside a render
    // pass and the pipeline, layout, set and offsets match.
    unsafe {
        device
            .raw
            .cmd_bind_pipeline(commands, vk::PipelineBindPoint::COMPUTE, pipeline);
        device.raw.cmd_bind_descriptor_sets(
            commands,
            vk::PipelineBindPoint::COMPUTE,
            layout,
            0,
            &[set],
            offsets,
        );
        match groups {
            Workgroups::Count((x, y)) => device.raw.cmd_dispatch(commands, x, y, 1),
            Workgroups::Indirect(buffer, offset) => {
                device.raw.cmd_dispatch_indirect(commands, buffer, offset);
            }
        }
        compute_barrier(device, commands);
    }
}
