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
//! CPU reference the GPU kernels are checked against (their WGSL twins are in
//! [`wgsl`]; the kernels that join them run in `precip-gpu`).
//!
//! ## Example
//!
//! A lake at rest over a bed that rises out of it stays at rest, and keeps its
//! water (the scheme is well-balanced and conservative):
//!
//! ```
//! use precip_sea::{Bathymetry, Edge, Shore, ShoreState};
//!
//! // 40 cells of 1 m, 1 m deep at the west end, dry land from 20 m on.
//! let bed = Bathymetry::from_fn(40, 3, 1.0, |x, _| -1.0 + x / 20.0);
//! let rest = ShoreState::at_rest(&bed, 0.0);
//! let walls = [Edge::Wall, Edge::Wall, Edge::Wall, Edge::Wall];
//! let mut lake = Shore::new(bed, walls, rest)?;
//! let water_m3 = lake.volume_m3();
//! lake.advance(10.0)?; // s
//! assert!((lake.volume_m3() - water_m3).abs() < 1e-6 * water_m3);
//! assert!(lake.state().discharge_x_m2ps.iter().all(|q| q.abs() < 1e-5));
//! # Ok::<(), precip_sea::ShoreError>(())
//! ```

pub mod ocean;
pub mod optics;
pub mod shore;
pub mod wgsl;

pub use shore::{
    Bathymetry, COURANT, DRY_DEPTH_M, Edge, GRAVITY_MPS2, IncomingWaves, Shore, ShoreError,
    ShoreState, WaveComponent,
};
