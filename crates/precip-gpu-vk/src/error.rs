//! Pure conversions of Vulkan's errors into [`BackendError`], with what to do.

use ash::vk;
use precip_model::BackendError;

/// This backend's name in errors and `BackendInfo`.
pub const NAME: &str = "vk";

/// A failed Vulkan call `what`, as the typed error its result means.
#[must_use]
pub fn map_vk(what: &str, result: vk::Result) -> BackendError {
    use vk::Result as R;
    let operation = what.to_owned();
    match result {
        R::ERROR_OUT_OF_HOST_MEMORY
        | R::ERROR_OUT_OF_DEVICE_MEMORY
        | R::ERROR_OUT_OF_POOL_MEMORY
        | R::ERROR_FRAGMENTED_POOL
        | R::ERROR_FRAGMENTATION => BackendError::OutOfMemory {
            backend: NAME,
            operation,
        },
        R::ERROR_DEVICE_LOST | R::ERROR_SURFACE_LOST_KHR => BackendError::DeviceLost {
            backend: NAME,
            operation,
        },
        R::ERROR_INCOMPATIBLE_DRIVER | R::ERROR_INITIALIZATION_FAILED => BackendError::NoDriver {
            backend: NAME,
            detail: format!("{what}: {result}"),
        },
        R::ERROR_LAYER_NOT_PRESENT => missing(
            format!("a layer {what} needs"),
            "install the Khronos validation layer: `apt-get install vulkan-validationlayers`",
        ),
        R::ERROR_EXTENSION_NOT_PRESENT => missing(
            format!("an extension {what} needs"),
            "update the Vulkan driver",
        ),
        R::ERROR_FEATURE_NOT_PRESENT => missing(
            format!("a feature {what} needs"),
            "update the Vulkan driver",
        ),
        R::ERROR_FORMAT_NOT_SUPPORTED => missing(
            format!("an image format {what} needs"),
            "use another device",
        ),
        _ => BackendError::Device {
            backend: NAME,
            message: format!("{what}: {result} (an unexpected Vulkan error)"),
        },
    }
}

/// A missing layer, extension, feature or format, named.
#[must_use]
pub fn missing(what: String, advice: &str) -> BackendError {
    BackendError::MissingCapability {
        backend: NAME,
        what,
        advice: advice.to_owned(),
    }
}

/// A failure of the memory allocator.
#[must_use]
pub fn map_allocation(what: &str, error: &gpu_allocator::AllocationError) -> BackendError {
    match error {
        gpu_allocator::AllocationError::OutOfMemory => BackendError::OutOfMemory {
            backend: NAME,
            operation: what.to_owned(),
        },
        _ => BackendError::Device {
            backend: NAME,
            message: format!("{what}: {error}"),
        },
    }
}

/// The Vulkan loader is missing.
#[must_use]
pub fn no_driver(detail: &dyn std::fmt::Display) -> BackendError {
    BackendError::NoDriver {
        backend: NAME,
        detail: format!("no Vulkan loader: {detail}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_become_typed_errors_that_say_what_to_do() {
        let e = map_vk("allocating", vk::Result::ERROR_OUT_OF_DEVICE_MEMORY);
        assert!(matches!(e, BackendError::OutOfMemory { .. }), "{e:?}");
        assert!(e.to_string().contains("particle budget"), "{e}");
        let e = map_vk(
            "creating the instance",
            vk::Result::ERROR_INCOMPATIBLE_DRIVER,
        );
        assert!(matches!(e, BackendError::NoDriver { .. }), "{e:?}");
        assert!(e.to_string().contains("mesa-vulkan-drivers"), "{e}");
        let e = map_vk("drawing", vk::Result::ERROR_DEVICE_LOST);
        assert!(matches!(e, BackendError::DeviceLost { .. }), "{e:?}");
        assert!(e.to_string().contains("new backend"), "{e}");
        let e = map_vk("enabling validation", vk::Result::ERROR_LAYER_NOT_PRESENT);
        assert!(e.to_string().contains("vulkan-validationlayers"), "{e}");
        assert!(matches!(
            map_vk("x", vk::Result::ERROR_EXTENSION_NOT_PRESENT),
            BackendError::MissingCapability { .. }
        ));
        assert!(matches!(
            map_vk("x", vk::Result::ERROR_UNKNOWN),
            BackendError::Device { .. }
        ));
        assert!(matches!(
            map_allocation("x", &gpu_allocator::AllocationError::OutOfMemory),
            BackendError::OutOfMemory { .. }
        ));
    }
}
