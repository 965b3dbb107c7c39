//! Pure conversions of wgpu's errors into [`BackendError`].

use precip_model::BackendError;

/// This backend's name in errors and [`precip_model::BackendInfo`].
pub const NAME: &str = "wgpu";

/// A device-level failure, with what to do.
#[must_use]
pub fn map_device_error(what: &str, error: &dyn std::fmt::Display) -> BackendError {
    BackendError::Device {
        backend: NAME,
        message: format!("{what}: {error}"),
    }
}

/// An error captured by an error scope around `operation`.
#[must_use]
pub fn map_scope_error(operation: &str, error: &wgpu::Error) -> BackendError {
    let advice = match error {
        wgpu::Error::OutOfMemory { .. } => {
            return BackendError::OutOfMemory {
                backend: NAME,
                operation: operation.to_owned(),
            };
        }
        wgpu::Error::Validation { .. } => {
            "this is a bug in precip: please report it with this message"
        }
        _ => "the device reported an internal error",
    };
    BackendError::Device {
        backend: NAME,
        message: format!("{operation} failed: {error} ({advice})"),
    }
}

/// No adapter at all.
#[must_use]
pub fn no_adapter(detail: &dyn std::fmt::Display) -> BackendError {
    BackendError::NoDriver {
        backend: NAME,
        detail: format!("no GPU adapter found: {detail}"),
    }
}
