//! The open sea (docs/model.md (13.5)–(13.7)): wind-wave spectra (Phillips as
//! Tessendorf 2001 uses it, JONSWAP with a fetch and a directional spreading), and
//! the surface synthesised from one by the inverse FFT on a tiling patch, with its
//! choppy displacement and the Jacobian where it folds (foam). The CPU reference of
//! the GPU's FFT kernel (radix-2 Stockham, one stage a dispatch).

pub mod cascades;
pub mod fft;
pub mod spectrum;
pub mod synthesis;

pub use cascades::{
    CASCADE_SIZES_M, OCEAN_CASCADES, OCEAN_N, SHORTEST_WAVE_M, SeaSpectrum, SeaState,
    cascade_band_per_m, cascade_seed,
};
pub use spectrum::{
    PHILLIPS_AMPLITUDE, SPREADING_EXPONENT, SpectrumKind, WindSea, deep_group_speed_mps,
    directional_spreading, dispersion_rad_per_s, frequency_spectrum_rad, fully_developed_fetch_m,
    jonswap_peak_rad_per_s, jonswap_rad, whitecap_cover,
};
pub use synthesis::{OceanCascade, OceanSurface};
