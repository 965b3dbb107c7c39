//! Buffers with their memory from gpu-allocator: device-local ones for the kernels,
//! host-visible ones for uniforms, uploads and read-back.

use ash::vk;
use gpu_allocator::MemoryLocation;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use precip_model::BackendError;

use crate::device::Device;
use crate::error::{NAME, map_allocation, map_vk};

/// A buffer and its memory; [`Buffer::destroy`] frees both.
#[derive(Debug)]
pub struct Buffer {
    /// The buffer.
    pub raw: vk::Buffer,
    allocation: Option<Allocation>,
}

impl Buffer {
    /// A buffer of `size` bytes (at least 16) in `location`.
    pub fn new(
        device: &Device,
        name: &str,
        size: u64,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> Result<Self, BackendError> {
        let size = size.max(16);
        let info = vk::BufferCreateInfo::default()
            .size(size)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: a valid device and create info.
        let raw = unsafe { device.raw.create_buffer(&info, None) }
            .map_err(|e| map_vk(&format!("creating buffer {name}"), e))?;
        // SAFETY: `raw` was just created on this device.
        let requirements = unsafe { device.raw.get_buffer_memory_requirements(raw) };
        let allocation =
            device
                .allocator
                .lock()
                .map_err(|_| poisoned())?
                .allocate(&AllocationCreateDesc {
                    name,
                    requirements,
                    location,
                    linear: true,
                    allocation_scheme: AllocationScheme::GpuAllocatorManaged,
                });
        let allocation = match allocation {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: the buffer is unused and destroyed once.
                unsafe { device.raw.destroy_buffer(raw, None) };
                return Err(map_allocation(&format!("memory for {name}"), &e));
            }
        };
        // SAFETY: the allocation fits the buffer's requirements and is bound once.
        unsafe {
            device
                .raw
                .bind_buffer_memory(raw, allocation.memory(), allocation.offset())
        }
        .map_err(|e| map_vk(&format!("binding memory of {name}"), e))?;
        device.name(raw, &format!("precip {name}"));
        Ok(Self {
            raw,
            allocation: Some(allocation),
        })
    }

    /// Writes `bytes` at `offset` into a host-visible buffer.
    pub fn write(&mut self, offset: usize, bytes: &[u8]) -> Result<(), BackendError> {
        let slice = self
            .allocation
            .as_mut()
            .and_then(Allocation::mapped_slice_mut)
            .ok_or_else(not_mapped)?;
        let end = offset + bytes.len();
        slice
            .get_mut(offset..end)
            .ok_or_else(not_mapped)?
            .copy_from_slice(bytes);
        Ok(())
    }

    /// The first `len` bytes of a host-visible buffer.
    /// Whether the host writes it directly (host-visible, mapped memory).
    #[must_use]
    pub fn is_mapped(&self) -> bool {
        self.allocation
            .as_ref()
            .and_then(Allocation::mapped_ptr)
            .is_some()
    }

    pub fn read(&self, len: usize) -> Result<Vec<u8>, BackendError> {
        self.allocation
            .as_ref()
            .and_then(Allocation::mapped_slice)
            .and_then(|s| s.get(..len))
            .map(<[u8]>::to_vec)
            .ok_or_else(not_mapped)
    }

    /// Frees the buffer and its memory (the device must be done with it).
    pub fn destroy(mut self, device: &Device) {
        if let (Some(allocation), Ok(mut allocator)) =
            (self.allocation.take(), device.allocator.lock())
        {
            let _ = allocator.free(allocation);
        }
        // SAFETY: the caller guarantees no pending work uses the buffer.
        unsafe { device.raw.destroy_buffer(self.raw, None) };
    }
}

fn not_mapped() -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: "a host-visible buffer is not mapped (a bug in precip: please report it)".into(),
    }
}

/// The allocator's lock was poisoned by a panic elsewhere.
#[must_use]
pub fn poisoned() -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: "the memory allocator's lock is poisoned (an earlier panic): create a new backend"
            .into(),
    }
}
