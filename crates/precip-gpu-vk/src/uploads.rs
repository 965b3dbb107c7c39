//! [`Uploads`]: writes of device-local buffers carried by the next submission, as
//! wgpu's `Queue::write_buffer` does them (wgpu twin: none, the queue is wgpu's).
//!
//! A frame that writes a device-local buffer (the far cover's rows every few steps,
//! the terrain's windows while the camera flies) copies the bytes into a
//! host-visible staging buffer at once and records the copy at the head of the next
//! submission, behind a barrier from everything submitted before and ahead of one
//! to everything after: the host never waits for the device to write a buffer, so
//! the frames in flight keep their overlap, and the staging buffers are reused —
//! a staging buffer takes writes until the next submission carries it (a new one
//! is opened when it is full), and is free again once that submission has
//! finished; a submission that fails gives its copies back for the next. One over [`KEPT_STAGING_BYTES`] (a
//! write of an unusual size) is freed instead of kept, so the memory held stays
//! that of the steady frames' writes.
//!
//! The caller of `write_buffer` has made sure no submitted work reads the bytes
//! (`precip_gpu::Gpu::write_buffer`); copies of one submission run in the order
//! written, so a later write of the same bytes wins.

use ash::vk;
use gpu_allocator::MemoryLocation;
use precip_model::BackendError;

use crate::buffer::Buffer;
use crate::commands::memory_barrier;
use crate::device::Device;

/// The smallest staging buffer made, bytes (the far cover's rows of a full-size
/// terrain and a few terrain windows fit).
const STAGING_BYTES_MIN: u64 = 2 << 20;

/// A free staging buffer larger than this is freed rather than kept.
pub const KEPT_STAGING_BYTES: u64 = 8 << 20;

/// Free staging buffers kept for later writes.
const KEPT_FREE_STAGINGS: usize = 2;

/// Where a staging buffer stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    /// Taking writes for the next submission.
    Open,
    /// Carried by the submission of this number.
    Carried(u64),
    /// Unused.
    Free,
}

#[derive(Debug)]
struct Staging {
    buffer: Buffer,
    capacity: u64,
    used: u64,
    stage: Stage,
}

/// A copy the next submission makes.
#[derive(Debug, Clone, Copy)]
pub struct Copy {
    from: vk::Buffer,
    to: vk::Buffer,
    region: vk::BufferCopy,
}

/// Staging buffers and the copies waiting for the next submission.
#[derive(Debug, Default)]
pub struct Uploads {
    stagings: Vec<Staging>,
    copies: Vec<Copy>,
}

impl Uploads {
    /// Copies `bytes` into staging memory and queues their copy to `target` at
    /// `offset` for the next submission.
    pub fn write(
        &mut self,
        device: &Device,
        target: vk::Buffer,
        offset: u64,
        bytes: &[u8],
    ) -> Result<(), BackendError> {
        if bytes.is_empty() {
            return Ok(());
        }
        let len = bytes.len() as u64;
        let index = self.staging_with_room(device, len)?;
        let staging = &mut self.stagings[index];
        let start = staging.used;
        staging.buffer.write(start as usize, bytes)?;
        // Copies start at multiples of 4 bytes (any offset is valid; aligned ones
        // copy faster).
        staging.used = (start + len).next_multiple_of(4);
        staging.stage = Stage::Open;
        self.copies.push(Copy {
            from: staging.buffer.raw,
            to: target,
            region: vk::BufferCopy {
                src_offset: start,
                dst_offset: offset,
                size: len,
            },
        });
        Ok(())
    }

    /// Whether copies wait for a submission.
    #[must_use]
    pub fn pending(&self) -> bool {
        !self.copies.is_empty()
    }

    /// The copies waiting, handed to the submission numbered `submission`, whose
    /// command buffer records them ([`record`]); the staging buffers they read
    /// are free once it has finished ([`Uploads::release`]).
    pub fn take(&mut self, submission: u64) -> Vec<Copy> {
        for s in &mut self.stagings {
            if s.stage == Stage::Open {
                s.stage = Stage::Carried(submission);
            }
        }
        std::mem::take(&mut self.copies)
    }

    /// Gives back the copies `take` handed to submission `submission` when it was
    /// not submitted (an error): they wait for the next one, before any written
    /// since, and their staging buffers take writes again.
    pub fn restore(&mut self, copies: Vec<Copy>, submission: u64) {
        for s in &mut self.stagings {
            if s.stage == Stage::Carried(submission) {
                s.stage = Stage::Open;
            }
        }
        let later = std::mem::replace(&mut self.copies, copies);
        self.copies.extend(later);
    }

    /// Frees the staging buffers of finished submissions (`completed` have
    /// finished): kept for the next writes, at most [`KEPT_FREE_STAGINGS`] of
    /// them and none over [`KEPT_STAGING_BYTES`].
    pub fn release(&mut self, device: &Device, completed: u64) {
        for s in &mut self.stagings {
            if let Stage::Carried(n) = s.stage
                && n < completed
            {
                s.stage = Stage::Free;
                s.used = 0;
            }
        }
        let mut kept = 0;
        let mut i = 0;
        while i < self.stagings.len() {
            let s = &self.stagings[i];
            let free = s.stage == Stage::Free;
            if free && kept < KEPT_FREE_STAGINGS && s.capacity <= KEPT_STAGING_BYTES {
                kept += 1;
                i += 1;
            } else if free {
                self.stagings.swap_remove(i).buffer.destroy(device);
            } else {
                i += 1;
            }
        }
    }

    /// Frees every staging buffer (the device is idle; waiting copies are dropped).
    pub fn destroy(&mut self, device: &Device) {
        self.copies.clear();
        for s in self.stagings.drain(..) {
            s.buffer.destroy(device);
        }
    }

    /// The staging buffer the next `len` bytes go into: the open one with room, a
    /// free one large enough, or a new one.
    fn staging_with_room(&mut self, device: &Device, len: u64) -> Result<usize, BackendError> {
        let fits = |s: &Staging| s.capacity - s.used >= len;
        if let Some(i) = self
            .stagings
            .iter()
            .position(|s| s.stage == Stage::Open && fits(s))
        {
            return Ok(i);
        }
        if let Some(i) = self
            .stagings
            .iter()
            .position(|s| s.stage == Stage::Free && fits(s))
        {
            return Ok(i);
        }
        let capacity = len.next_power_of_two().max(STAGING_BYTES_MIN);
        let buffer = Buffer::new(
            device,
            "staging",
            capacity,
            vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::CpuToGpu,
        )?;
        self.stagings.push(Staging {
            buffer,
            capacity,
            used: 0,
            stage: Stage::Free,
        });
        Ok(self.stagings.len() - 1)
    }
}

/// Records `copies` behind a barrier from every command submitted before (their
/// targets' earlier reads and writes) and ahead of one to every command after.
///
/// # Safety
/// `commands` is a command buffer of `device` recording outside a render pass; the
/// copies' buffers are live until the submission finishes (the staging buffers are
/// [`Uploads`]' own, released only after it; a target is destroyed only after
/// waiting for every submission).
pub unsafe fn record(device: &Device, commands: vk::CommandBuffer, copies: &[Copy]) {
    if copies.is_empty() {
        return;
    }
    let all = vk::PipelineStageFlags::ALL_COMMANDS;
    let any = vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE;
    let transfer = vk::PipelineStageFlags::TRANSFER;
    let write = vk::AccessFlags::TRANSFER_WRITE;
    // SAFETY: the caller's guarantees: recording outside a render pass, the buffers
    // live.
    unsafe {
        memory_barrier(device, commands, (all, any), (transfer, write));
        for c in copies {
            device
                .raw
                .cmd_copy_buffer(commands, c.from, c.to, std::slice::from_ref(&c.region));
        }
        memory_barrier(device, commands, (transfer, write), (all, any));
    }
}
