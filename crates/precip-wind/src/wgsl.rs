//! The WGSL twin of this crate's sampler, for the GPU programs that join it
//! (`precip-gpu`'s shader assembly reads it from here, beside its Rust twin).

/// `wind.wgsl`: the wind volume's sampler, twin of [`crate::WindVolume::sample`]
/// and [`crate::wind_velocity`].
pub const WIND: &str = include_str!("../shaders/wind.wgsl");
