//! Snow that accumulates and melts on a scene (docs/model.md §4, seed 003), and the
//! water on its surfaces: films, puddles, infiltration, evaporation and overland
//! flow ([`water`], [`Surface`]).
//!
//! ## Design
//!
//! The cover is a grid over a world rectangle in the XZ plane (Y up), aligned with the
//! scene's top-down ground map. Each [`CoverTexel`] holds the state of the snow pack
//! there — snow water equivalent (SWE), held liquid water, depth, age, wetness — plus
//! its eligibility (from the scene's masks and slope) and the seed's two threshold
//! masks. The layout is the GPU's: one `#[repr(C)]` struct per texel in a storage
//! buffer, twin of `CoverTexel` in `shaders/cover.wgsl`.
//!
//! Snow arrives two ways (docs/architecture.md §2), never both for one texel:
//! deposits from landed particles ([`DepositBuffer`], fixed-point, summed atomically,
//! so the sum is independent of order), or the weather's rate applied directly.
//! [`update_texel`] is the CPU form of the cover kernel: it adds the input, ages the
//! snow, applies degree-day melt `M = C_m·(T_air − T_m)·t` with
//! `C_m = k_m·k_v·R_l·(1 − A)`, refreezes held water when there is no heat, drains what
//! the pack cannot hold, and compacts the pack. Water is conserved exactly in the books:
//! `deposited = swe + liquid + runoff` per texel.
//!
//! [`shade_texel`] composes coverage `A_S`, melted fraction `M_S`, the threshold masks
//! (`A_M = T_M.g − A_S`, `M_M = T_M.r − M_S`) and wet darkening into the values a
//! surface shader needs.
//!
//! ## Example
//!
//! A day of 10 mm/day of snow at −5 °C on a 16 m square, fed by the weather's rate:
//!
//! ```
//! use glam::{UVec2, Vec2};
//! use precip_cover::{
//!     CoverAir, CoverFeed, CoverGrid, CoverParams, DepositBuffer, GridFrame,
//!     generate_threshold_masks,
//! };
//!
//! let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(16.0), UVec2::splat(8));
//! let n = frame.texel_count();
//! let masks = generate_threshold_masks(&frame, 1, 4.0);
//! let mut cover = CoverGrid::new(frame, &vec![1.0; n], &masks, &vec![CoverFeed::WeatherRate; n])?;
//! let air = CoverAir {
//!     snow_rate_mm_per_day: 10.0,
//!     air_temperature_c: -5.0,
//!     relative_humidity: 0.8,
//!     ..CoverAir::default()
//! };
//! let mut deposits = DepositBuffer::new(n);
//! for _ in 0..24 {
//!     cover.step(&mut deposits, air, 1.0 / 24.0, &CoverParams::default()); // days
//! }
//! let books = cover.totals();
//! assert!(books.mean_snow_depth_mm() > 10.0, "fresh snow is deeper than its water");
//! assert!(books.imbalance_kg().abs() < 1e-3, "the water's books close");
//! # Ok::<(), precip_cover::CoverError>(())
//! ```

pub mod blowing;
mod deposit;
pub mod drift;
mod error;
mod frame;
mod gpu;
mod grid;
mod masks;
mod melt;
mod params;
mod shading;
mod snowpack;
mod surface;
mod texel;
mod update;
pub mod water;
pub mod wgsl;

pub use deposit::{DEPOSIT_CHANNELS, DEPOSIT_UNITS_PER_MM, DepositBuffer, Landed, deposit_units};
pub use drift::SNOW_DRIFT_ITERATIONS;
pub use error::CoverError;
pub use frame::GridFrame;
pub use gpu::{CoverAir, CoverStepParams};
pub use grid::{CoverGrid, CoverTotals};
pub use masks::{ThresholdMasks, generate_threshold_masks};
pub use melt::{degree_day_melt_mm, melt_factor, snow_albedo, vegetation_transmission};
pub use params::CoverParams;
pub use shading::{
    COVER_WARP_WAVELENGTH_TEXELS, CoverShading, GRAINS_COVERING_KG_M2, NEW_SNOW_DENSITY_KG_M3,
    THRESHOLD_NOISE_AMPLITUDE, THRESHOLD_NOISE_WAVELENGTHS_M, accumulated_fraction, cover_warp_m,
    ground_albedo, melted_fraction, settled_grain_cover, shade_texel, shade_with_masks,
    snow_cover_fraction, sub_texel_threshold, value_noise,
};
pub use snowpack::{compacted_density, new_snow_density};
pub use surface::{Surface, SurfaceWater};
pub use texel::{CoverFeed, CoverTexel};
pub use update::{CoverInput, update_texel};
pub use water::{WATER_FLOW_ITERATIONS, evaporation_mm_per_day, saturation_vapour_pressure_hpa};
