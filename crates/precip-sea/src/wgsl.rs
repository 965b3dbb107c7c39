//! The WGSL twins of this crate's Rust, for the GPU programs that join them
//! (`precip-gpu`'s shader assembly reads them from here, beside their Rust twins).

/// `ocean.wgsl`: the open sea's dispersion, spectra, spreading, the amplitudes'
/// normal draws and the FFT's butterfly, twins of [`crate::ocean`].
pub const OCEAN: &str = include_str!("../shaders/ocean.wgsl");

/// `shore.wgsl`: the coastal zone's scheme — faces, fluxes, the bed's source, the
/// incoming waves' edge, the speed cap — twins of [`crate::shore`].
pub const SHORE: &str = include_str!("../shaders/shore.wgsl");
