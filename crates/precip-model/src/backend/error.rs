//! Typed errors of the model and of every backend.

use precip_cover::CoverError;
use precip_wind::WindError;

use crate::weather::PrecipitationKind;

/// What was wrong with a [`crate::Weather`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WeatherError {
    /// A field was non-finite or out of its range.
    #[error("weather field `{field}` = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// The field.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// The air temperature does not allow this kind of precipitation.
    #[error(
        "{kind} at {air_temperature_c} °C is not physical: allowed {allowed}; pick another kind (sleet or rain near 0 °C)"
    )]
    KindTemperature {
        /// The kind asked for.
        kind: PrecipitationKind,
        /// The air temperature given.
        air_temperature_c: f32,
        /// The range of that kind, in words.
        allowed: &'static str,
    },
    /// Grains were given for a kind that has none.
    #[error(
        "weather `grain` is given for {kind}, which has no grains: give it for sand or dust only, or leave it out"
    )]
    GrainWithoutGrains {
        /// The kind asked for.
        kind: PrecipitationKind,
    },
    /// The wind field was invalid.
    #[error("weather wind: {0}")]
    Wind(WindError),
}

// The variants that name their cause in their message do not also give it as their
// `source`: an error chain printed whole (`anyhow`'s `{:#}`) would say it twice.
impl From<WindError> for WeatherError {
    fn from(e: WindError) -> Self {
        Self::Wind(e)
    }
}

impl From<WindError> for BackendError {
    fn from(e: WindError) -> Self {
        Self::Wind(e)
    }
}

impl From<CoverError> for BackendError {
    fn from(e: CoverError) -> Self {
        Self::Cover(e)
    }
}

impl From<crate::scene::SceneError> for BackendError {
    fn from(e: crate::scene::SceneError) -> Self {
        Self::Scene(e)
    }
}

/// Everything a [`crate::Backend`] can refuse or fail at.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BackendError {
    /// Invalid weather; nothing was changed.
    #[error(transparent)]
    Weather(#[from] WeatherError),
    /// Invalid wind volume size; nothing was changed.
    #[error("wind volume: {0}")]
    Wind(WindError),
    /// Invalid cover grid or parameters; nothing was changed.
    #[error("snow cover: {0}")]
    Cover(CoverError),
    /// Some part of the setup is invalid; nothing was changed.
    #[error("invalid setup: `{field}` {problem}")]
    Setup {
        /// The field of [`crate::Setup`].
        field: &'static str,
        /// What is wrong and what to do.
        problem: String,
    },
    /// The setup asks for no particles at all.
    #[error(
        "the setup asks for zero particles: give the world emitter or the camera volume a particle count above 0"
    )]
    ZeroCapacity,
    /// More particles than the backend or device can hold.
    #[error(
        "{requested} particles requested but at most {max} fit ({limit}): lower the particle budget"
    )]
    CapacityTooLarge {
        /// Particles asked for.
        requested: u64,
        /// The most this backend holds.
        max: u64,
        /// The limit that binds, named.
        limit: String,
    },
    /// A step length that is not a positive finite number of seconds up to the maximum.
    #[error("time step {dt_s} s is invalid: give a finite dt in (0, {max_s}] s")]
    InvalidTimeStep {
        /// The step given.
        dt_s: f32,
        /// The longest step accepted.
        max_s: f32,
    },
    /// A camera with non-finite or degenerate values.
    #[error("invalid camera: {0}")]
    InvalidCamera(&'static str),
    /// A render target or view that cannot be drawn.
    #[error("invalid view: {0}")]
    InvalidView(String),
    /// A LiDAR beam query that cannot be cast.
    #[error("invalid beam query: {0}")]
    InvalidBeams(String),
    /// The scene cannot be used.
    #[error("scene: {0}")]
    Scene(crate::scene::SceneError),
    /// Nothing has been rendered yet.
    #[error("read_image needs a rendered frame: call render(&view) first")]
    NothingRendered,
    /// The call needs `configure` first.
    #[error("{operation} needs a configured backend: call configure(&setup) first")]
    NotConfigured {
        /// The call made.
        operation: &'static str,
    },
    /// This backend cannot do that at all.
    #[error("the {backend} backend does not support {operation}: use a GPU backend for it")]
    NotSupported {
        /// The backend's name.
        backend: &'static str,
        /// What was asked.
        operation: &'static str,
    },
    /// The device or host ran out of memory; nothing was changed.
    #[error(
        "{backend}: out of memory while {operation}: lower the particle budget, the grid sizes or the image size"
    )]
    OutOfMemory {
        /// The backend's name.
        backend: &'static str,
        /// What was being done.
        operation: String,
    },
    /// The device was lost (a driver reset or a hang); the backend is unusable.
    #[error("{backend}: the device was lost while {operation}: create a new backend")]
    DeviceLost {
        /// The backend's name.
        backend: &'static str,
        /// What was being done.
        operation: String,
    },
    /// A layer, extension or feature the backend needs is missing.
    #[error("{backend}: {what} is missing: {advice}")]
    MissingCapability {
        /// The backend's name.
        backend: &'static str,
        /// What is missing, by name where known (e.g. `VK_KHR_swapchain`).
        what: String,
        /// What to do.
        advice: String,
    },
    /// No GPU driver or loader.
    #[error(
        "{backend}: no GPU driver ({detail}): install one, e.g. `apt-get install mesa-vulkan-drivers` on Debian or Ubuntu"
    )]
    NoDriver {
        /// The backend's name.
        backend: &'static str,
        /// What the system said.
        detail: String,
    },
    /// Another device-level failure reported by a GPU backend.
    #[error("{backend}: {message}")]
    Device {
        /// The backend's name.
        backend: &'static str,
        /// What happened and what to do.
        message: String,
    },
}
