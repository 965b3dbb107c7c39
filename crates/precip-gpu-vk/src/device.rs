//! The logical device: a physical device with a queue that computes (and draws), its
//! limits, the memory allocator, a command pool and a fence for one submission at a
//! time.

use std::mem::ManuallyDrop;
use std::sync::Mutex;

use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use precip_model::BackendError;

use crate::error::{NAME, map_allocation, map_vk};
use crate::instance::Instance;

/// A device, its queue and allocator.
pub struct Device {
    /// The instance it came from (dropped after the device).
    pub instance: ManuallyDrop<Instance>,
    /// The physical device.
    pub physical: vk::PhysicalDevice,
    /// Its properties (limits, name, timestamp period).
    pub properties: vk::PhysicalDeviceProperties,
    /// The device.
    pub raw: ash::Device,
    /// The queue.
    pub queue: vk::Queue,
    /// Its family.
    pub queue_family: u32,
    /// Whether the queue writes timestamps.
    pub timestamps: bool,
    /// Whether VK_KHR_swapchain is enabled (precip's own device, when the driver has
    /// it; an engine's device presents through the engine).
    pub swapchain: bool,
    /// Memory.
    pub allocator: ManuallyDrop<Mutex<Allocator>>,
    /// Command buffers come from here.
    pub command_pool: vk::CommandPool,
    /// Command buffers and unsignalled fences of finished submissions, for the next
    /// ones (`crate::commands`).
    pub recycled: Mutex<Vec<(vk::CommandBuffer, vk::Fence)>>,
    /// The largest single allocation (Vulkan 1.1's maxMemoryAllocationSize), bytes:
    /// the largest buffer precip makes.
    pub max_allocation_bytes: u64,
    /// Whether dropping this destroys the device (false for the caller's).
    owned: bool,
    /// Sets object names (when the instance has VK_EXT_debug_utils).
    names: Option<ash::ext::debug_utils::Device>,
}

/// A device the caller owns (an engine's), for [`crate::VkBackend::on_external_device`].
#[derive(Clone)]
pub struct ExternalDevice {
    /// The loader the instance came from.
    pub entry: ash::Entry,
    /// The caller's instance (Vulkan 1.1 or later).
    pub instance: ash::Instance,
    /// The physical device of `device`.
    pub physical: vk::PhysicalDevice,
    /// The caller's device.
    pub device: ash::Device,
    /// A queue family with compute and graphics that `device` was created with.
    pub queue_family: u32,
    /// Which queue of that family precip submits to.
    pub queue_index: u32,
}

impl std::fmt::Debug for ExternalDevice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ExternalDevice")
            .field("queue_family", &self.queue_family)
            .field("queue_index", &self.queue_index)
            .finish_non_exhaustive()
    }
}

impl std::fmt::Debug for Device {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Device")
            .field("name", &self.name_of_device())
            .finish_non_exhaustive()
    }
}

impl Device {
    /// Runs on the caller's device: precip makes its own allocator and command pool on
    /// it and destroys only those.
    ///
    /// # Safety
    /// `external` must hold live objects created from one another as its fields say,
    /// the queue must not be used by another thread while precip submits, and the
    /// device and instance must outlive the backend.
    pub unsafe fn external(external: ExternalDevice) -> Result<Self, BackendError> {
        let instance = Instance::external(external.entry, external.instance);
        // SAFETY: the caller guarantees `physical` belongs to this instance.
        let (properties, families) = unsafe {
            (
                instance
                    .raw
                    .get_physical_device_properties(external.physical),
                instance
                    .raw
                    .get_physical_device_queue_family_properties(external.physical),
            )
        };
        let family = families
            .get(external.queue_family as usize)
            .ok_or_else(|| BackendError::Device {
                backend: NAME,
                message: format!("queue family {} does not exist", external.queue_family),
            })?;
        if !family
            .queue_flags
            .contains(vk::QueueFlags::COMPUTE | vk::QueueFlags::GRAPHICS)
        {
            return Err(crate::error::missing(
                format!(
                    "COMPUTE and GRAPHICS on queue family {}",
                    external.queue_family
                ),
                "give precip a queue family that both computes and draws",
            ));
        }
        let timestamps = family.timestamp_valid_bits > 0
            && properties.limits.timestamp_compute_and_graphics == vk::TRUE;
        let raw = external.device;
        // SAFETY: the caller guarantees the device was created with this queue.
        let queue = unsafe { raw.get_device_queue(external.queue_family, external.queue_index) };
        Self::finish(
            instance,
            external.physical,
            properties,
            raw,
            queue,
            external.queue_family,
            timestamps,
            false,
            false,
        )
    }

    #[expect(
        clippy::too_many_arguments,
        reason = "the parts of a device, assembled once"
    )]
    fn finish(
        instance: Instance,
        physical: vk::PhysicalDevice,
        properties: vk::PhysicalDeviceProperties,
        raw: ash::Device,
        queue: vk::Queue,
        queue_family: u32,
        timestamps: bool,
        swapchain: bool,
        owned: bool,
    ) -> Result<Self, BackendError> {
        // On failure the device is destroyed here when it is precip's own (before the
        // instance, which drops on return), so partial construction leaks nothing.
        let abandon = |raw: &ash::Device| {
            if owned {
                // SAFETY: nothing was created on the device yet but what was dropped.
                unsafe { raw.destroy_device(None) };
            }
        };
        let allocator = match Allocator::new(&AllocatorCreateDesc {
            instance: instance.raw.clone(),
            device: raw.clone(),
            physical_device: physical,
            debug_settings: gpu_allocator::AllocatorDebugSettings::default(),
            buffer_device_address: false,
            allocation_sizes: gpu_allocator::AllocationSizes::default(),
        }) {
            Ok(a) => a,
            Err(e) => {
                abandon(&raw);
                return Err(map_allocation("creating the allocator", &e));
            }
        };
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        // SAFETY: a valid device and create info.
        let command_pool = match unsafe { raw.create_command_pool(&pool_info, None) } {
            Ok(pool) => pool,
            Err(e) => {
                drop(allocator);
                abandon(&raw);
                return Err(map_vk("creating a command pool", e));
            }
        };
        let names = instance
            .has_debug_utils()
            .then(|| ash::ext::debug_utils::Device::new(&instance.raw, &raw));
        let mut maintenance3 = vk::PhysicalDeviceMaintenance3Properties::default();
        let mut properties2 = vk::PhysicalDeviceProperties2::default().push_next(&mut maintenance3);
        // SAFETY: `physical` belongs to this instance, which is Vulkan 1.1 or later (the
        // negative viewport precip draws with needs 1.1 too); the chain outlives the call.
        unsafe {
            instance
                .raw
                .get_physical_device_properties2(physical, &mut properties2)
        };
        let max_allocation_bytes = maintenance3.max_memory_allocation_size;
        let device = Self {
            instance: ManuallyDrop::new(instance),
            physical,
            properties,
            raw,
            queue,
            queue_family,
            timestamps,
            swapchain,
            allocator: ManuallyDrop::new(Mutex::new(allocator)),
            command_pool,
            recycled: Mutex::new(Vec::new()),
            max_allocation_bytes,
            owned,
            names,
        };
        device.name(device.command_pool, "precip commands");
        Ok(device)
    }

    /// Opens the first device with a compute-and-graphics queue (discrete GPUs first).
    pub fn new(instance: Instance) -> Result<Self, BackendError> {
        // SAFETY: enumeration on a live instance.
        let physicals = unsafe { instance.raw.enumerate_physical_devices() }
            .map_err(|e| map_vk("listing devices", e))?;
        let mut best: Option<(vk::PhysicalDevice, u32, u32)> = None;
        for physical in physicals {
            // SAFETY: `physical` comes from this instance.
            let (properties, families) = unsafe {
                (
                    instance.raw.get_physical_device_properties(physical),
                    instance
                        .raw
                        .get_physical_device_queue_family_properties(physical),
                )
            };
            let Some(family) = families.iter().position(|f| {
                f.queue_flags
                    .contains(vk::QueueFlags::COMPUTE | vk::QueueFlags::GRAPHICS)
            }) else {
                continue;
            };
            let rank = match properties.device_type {
                vk::PhysicalDeviceType::DISCRETE_GPU => 3,
                vk::PhysicalDeviceType::INTEGRATED_GPU => 2,
                vk::PhysicalDeviceType::VIRTUAL_GPU => 1,
                _ => 0,
            };
            if best.is_none_or(|(_, _, r)| rank > r) {
                best = Some((physical, family as u32, rank));
            }
        }
        let Some((physical, queue_family, _)) = best else {
            return Err(BackendError::NoDriver {
                backend: NAME,
                detail: "no Vulkan device with a compute and graphics queue".into(),
            });
        };
        // SAFETY: `physical` comes from this instance.
        let (properties, families) = unsafe {
            (
                instance.raw.get_physical_device_properties(physical),
                instance
                    .raw
                    .get_physical_device_queue_family_properties(physical),
            )
        };
        let timestamps = families[queue_family as usize].timestamp_valid_bits > 0
            && properties.limits.timestamp_compute_and_graphics == vk::TRUE;
        let priorities = [1.0];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(queue_family)
            .queue_priorities(&priorities)];
        // Swapchains only where windows can be presented to (VK_KHR_surface).
        // SAFETY: enumeration on a physical device of this instance.
        let swapchain = instance.surface
            && unsafe { instance.raw.enumerate_device_extension_properties(physical) }.is_ok_and(
                |all| {
                    all.iter().any(|e| {
                        e.extension_name_as_c_str()
                            .is_ok_and(|n| n == ash::khr::swapchain::NAME)
                    })
                },
            );
        let extensions = [ash::khr::swapchain::NAME.as_ptr()];
        let mut info = vk::DeviceCreateInfo::default().queue_create_infos(&queues);
        if swapchain {
            info = info.enabled_extension_names(&extensions);
        }
        // SAFETY: the create info outlives the call; `physical` is from this instance.
        let raw = unsafe { instance.raw.create_device(physical, &info, None) }
            .map_err(|e| map_vk("creating the device", e))?;
        // SAFETY: the queue family and index were requested above.
        let queue = unsafe { raw.get_device_queue(queue_family, 0) };
        Self::finish(
            instance,
            physical,
            properties,
            raw,
            queue,
            queue_family,
            timestamps,
            swapchain,
            true,
        )
    }

    /// Names a Vulkan object for debuggers and validation messages (a no-op without
    /// VK_EXT_debug_utils).
    pub fn name<H: vk::Handle>(&self, handle: H, name: &str) {
        let (Some(names), Ok(name)) = (&self.names, std::ffi::CString::new(name)) else {
            return;
        };
        let info = vk::DebugUtilsObjectNameInfoEXT::default()
            .object_handle(handle)
            .object_name(&name);
        // SAFETY: `handle` is a live object of this device; the name outlives the call.
        let _ = unsafe { names.set_debug_utils_object_name(&info) };
    }

    /// The device's name.
    #[must_use]
    pub fn name_of_device(&self) -> String {
        self.properties
            .device_name_as_c_str()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    }

    /// The device's limits in the terms every backend checks.
    #[must_use]
    pub fn limits(&self) -> precip_model::DeviceLimits {
        precip_model::DeviceLimits {
            device: self.name_of_device(),
            max_storage_binding_bytes: self.max_storage_range(),
            max_buffer_bytes: self.max_allocation_bytes,
            max_texture_side_px: self.properties.limits.max_image_dimension2_d,
        }
    }

    /// The largest storage buffer range, bytes.
    #[must_use]
    pub fn max_storage_range(&self) -> u64 {
        u64::from(self.properties.limits.max_storage_buffer_range)
    }

    /// Waits until the device is idle.
    pub fn wait_idle(&self) -> Result<(), BackendError> {
        // SAFETY: a live device; no other thread submits to it.
        unsafe { self.raw.device_wait_idle() }.map_err(|e| map_vk("waiting for the device", e))
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: waits for all work, then destroys what this struct created, children
        // before parents: pool, allocator (its memory), and the device and instance
        // only when they are precip's own.
        unsafe {
            let _ = self.raw.device_wait_idle();
            if let Ok(free) = self.recycled.get_mut() {
                for (_, fence) in free.drain(..) {
                    self.raw.destroy_fence(fence, None);
                }
            }
            self.raw.destroy_command_pool(self.command_pool, None);
            ManuallyDrop::drop(&mut self.allocator);
            if self.owned {
                self.raw.destroy_device(None);
            }
            ManuallyDrop::drop(&mut self.instance);
        }
    }
}
