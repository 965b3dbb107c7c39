//! The sea and the shore (docs/model.md §13).
//!
//! [`ocean`]: the open sea — wind-wave spectra (Phillips scaled to Pierson &
//! Moskowitz's fully developed sea, JONSWAP over a fetch with a directional
//! spreading) and the surface synthesised from one by the inverse FFT (Tessendorf
//! 2001) on a tiling patch, with its choppy displacement and the Jacobian where it
//! folds.
//!
//! [`optics`]: the colour of water by wavelength — absorption and scattering of
//! pure water, dissolved organic matter and particles, deep water's reflectance,
//! spectra to linear sRGB.
//!
//! [`shore`]: the coastal zone by the nonlinear shallow-water equations over the
//! scene's bathymetry — waves entering from the open sea, running up beaches,
//! reflected by walls — solved by a well-balanced, positivity-preserving
//! finite-volume scheme (the hydrostatic reconstruction of Audusse et al. 2004 with
//! an HLL flux, MUSCL slopes and a two-stage Runge–Kutta step). This crate is the
//! CPU reference the GPU kernels are to be checked against; it holds no GPU code.

pub mod ocean;
pub mod optics;
pub mod shore;
pub mod wgsl;

pub use shore::{
    Bathymetry, COURANT, DRY_DEPTH_M, Edge, GRAVITY_MPS2, IncomingWaves, Shore, ShoreError,
    ShoreState, WaveComponent,
};
