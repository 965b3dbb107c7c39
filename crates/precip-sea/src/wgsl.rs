//! The WGSL twins of this crate's Rust, for the GPU programs that join them
//! (`precip-gpu`'s shader assembly reads them from here, beside their Rust twins).

/// `ocean.wgsl`: the open sea's dispersion, spectra, spreading, the amplitudes'
/// normal draws and the FFT's butterfly, twins of [`crate::ocean`].
pub const OCEAN: &str = include_str!("../shaders/ocean.wgsl");
