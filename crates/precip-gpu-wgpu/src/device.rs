//! Adapters and devices: open one headless, or adopt the caller's.

use precip_model::BackendError;

use crate::error::{map_device_error, no_adapter};

/// A device with its queue and what precip needs to know about it.
#[derive(Debug, Clone)]
pub struct GpuDevice {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter it came from.
    pub info: wgpu::AdapterInfo,
}

/// A headless instance, honouring `WGPU_BACKEND` and friends, with
/// [`instance_flags`].
#[must_use]
pub fn instance() -> wgpu::Instance {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    descriptor.flags = instance_flags();
    wgpu::Instance::new(descriptor)
}

/// The instance flags precip asks for: wgpu's defaults and environment, without
/// the validation of indirect calls unless `WGPU_VALIDATION_INDIRECT_CALL` asks for
/// it. That validation copies every indirect draw's arguments through a pool of its
/// own, and the pool grew by 8 KiB a frame over 1 500 frames of the viewer (RSS,
/// lavapipe, wgpu 30; 0.0 without it, as on the Vulkan backend). precip's indirect
/// draws pull their vertices from storage buffers, bounds-checked by the shaders, and
/// their counts are written by its own culling kernels. An application that opens
/// its own instance for a window passes these flags too.
#[must_use]
pub fn instance_flags() -> wgpu::InstanceFlags {
    let mut flags = wgpu::InstanceFlags::from_env_or_default();
    if std::env::var_os("WGPU_VALIDATION_INDIRECT_CALL").is_none() {
        flags.remove(wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL);
    }
    flags
}

/// Every adapter this machine offers (for tests that run on each).
#[must_use]
pub fn adapters() -> Vec<wgpu::Adapter> {
    pollster::block_on(instance().enumerate_adapters(wgpu::Backends::all()))
}

/// The features precip uses when the adapter has them: timestamps per kernel.
#[must_use]
pub fn wanted_features(adapter_features: wgpu::Features) -> wgpu::Features {
    let timestamps =
        wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES;
    adapter_features & timestamps
}

impl GpuDevice {
    /// Opens a device on the default adapter.
    pub fn new_headless() -> Result<Self, BackendError> {
        let adapter =
            pollster::block_on(instance().request_adapter(&wgpu::RequestAdapterOptions::default()))
                .map_err(|e| no_adapter(&e))?;
        Self::open(&adapter)
    }

    /// Opens a device on `adapter`, asking for all its limits (so particle buffers can
    /// be as large as it allows) and for timestamp queries where it has them.
    pub fn open(adapter: &wgpu::Adapter) -> Result<Self, BackendError> {
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("precip"),
            required_features: wanted_features(adapter.features()),
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
            .map_err(|e| map_device_error("opening the device", &e))?;
        Ok(Self {
            device,
            queue,
            info: adapter.get_info(),
        })
    }

    /// Adopts a device the caller owns (an engine's renderer). precip uses timestamp
    /// queries only if the device was opened with them.
    #[must_use]
    pub fn from_existing(
        device: wgpu::Device,
        queue: wgpu::Queue,
        info: wgpu::AdapterInfo,
    ) -> Self {
        Self {
            device,
            queue,
            info,
        }
    }

    /// Whether per-kernel timestamps are available.
    #[must_use]
    pub fn has_timestamps(&self) -> bool {
        self.device.features().contains(
            wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES,
        )
    }

    /// The device in words.
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {:?}, {})",
            self.info.name, self.info.device_type, self.info.backend, self.info.driver
        )
    }

    /// The device's limits in the terms every backend checks.
    #[must_use]
    pub fn limits(&self) -> precip_model::DeviceLimits {
        let limits = self.device.limits();
        precip_model::DeviceLimits {
            device: self.info.name.clone(),
            max_storage_binding_bytes: self.max_storage_binding_bytes(),
            max_buffer_bytes: limits.max_buffer_size,
            max_texture_side_px: limits.max_texture_dimension_2d,
        }
    }

    /// The largest storage buffer one binding may hold, bytes.
    #[must_use]
    pub fn max_storage_binding_bytes(&self) -> u64 {
        let limits = self.device.limits();
        limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size)
    }

    /// Waits until all submitted work is done.
    pub fn wait(&self) -> Result<(), BackendError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| map_device_error("waiting for the device", &e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precip_instances_leave_out_wgpus_indirect_call_validation() {
        if std::env::var_os("WGPU_VALIDATION_INDIRECT_CALL").is_some() {
            eprintln!("skipped: WGPU_VALIDATION_INDIRECT_CALL is set and decides");
            return;
        }
        let flags = instance_flags();
        assert!(!flags.contains(wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL));
        // Everything else as wgpu's defaults and environment have it.
        let mut defaults = wgpu::InstanceFlags::from_env_or_default();
        defaults.remove(wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL);
        assert_eq!(flags, defaults);
    }
}
