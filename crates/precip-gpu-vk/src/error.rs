//! Pure conversions of Vulkan's errors into [`BackendError`], with what to do.

use ash::vk;
use precip_model::BackendError;

/// This backend's name in errors and `BackendInfo`.
pub const NAME: &str = "vk";

/// A failed Vulkan call `what`.
#[must_use]
pub fn map_vk(what: &str, result: vk::Result) -> BackendError {
    let advice = match result {
        vk::Result::ERROR_OUT_OF_HOST_MEMORY | vk::Result::ERROR_OUT_OF_DEVICE_MEMORY => {
            "out of memory: lower the particle budget or the grid sizes"
        }
        vk::Result::ERROR_DEVICE_LOST => "the device was lost (driver reset): create a new backend",
        vk::Result::ERROR_INCOMPATIBLE_DRIVER | vk::Result::ERROR_INITIALIZATION_FAILED => {
            "no usable Vulkan driver: install one, e.g. `apt-get install mesa-vulkan-drivers`"
        }
        vk::Result::ERROR_LAYER_NOT_PRESENT => {
            "a requested layer is missing: `apt-get install vulkan-validationlayers`"
        }
        vk::Result::ERROR_EXTENSION_NOT_PRESENT | vk::Result::ERROR_FEATURE_NOT_PRESENT => {
            "the device lacks a required extension or feature"
        }
        _ => "an unexpected Vulkan error",
    };
    BackendError::Device {
        backend: NAME,
        message: format!("{what}: {result} ({advice})"),
    }
}

/// A failure of the memory allocator.
#[must_use]
pub fn map_allocation(what: &str, error: &gpu_allocator::AllocationError) -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: format!("{what}: {error} (lower the particle budget or the grid sizes)"),
    }
}

/// The Vulkan loader is missing.
#[must_use]
pub fn no_driver(detail: &dyn std::fmt::Display) -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: format!(
            "no Vulkan loader or driver ({detail}): install one, e.g. `apt-get install mesa-vulkan-drivers` on Debian or Ubuntu"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_say_what_to_do() {
        let e = map_vk("allocating", vk::Result::ERROR_OUT_OF_DEVICE_MEMORY).to_string();
        assert!(e.contains("particle budget"), "{e}");
        let e = map_vk(
            "creating the instance",
            vk::Result::ERROR_INCOMPATIBLE_DRIVER,
        )
        .to_string();
        assert!(e.contains("mesa-vulkan-drivers"), "{e}");
        let e = map_vk("x", vk::Result::ERROR_DEVICE_LOST).to_string();
        assert!(e.contains("lost"), "{e}");
    }
}
