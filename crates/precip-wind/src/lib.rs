//! The wind that carries precip's snowflakes and raindrops (docs/model.md §3, seed 003).
//!
//! ## Design
//!
//! The wind at a point is the mean wind plus a random part,
//! `V_w = V̄_w + μ·V̄_w·sin α + (0, w, 0)`: `μ` is the gust factor, `α ∈ [0, π]` a
//! phase that is continuous in space and time, and `w` a vertical gust. Both `sin α`
//! and `w` come from Perlin noise ([`noise`] crate), evaluated **once per weather
//! change** on the CPU and stored in a periodic 3D grid, the [`WindVolume`], whose
//! texels are exactly what the GPU uploads as an `Rgba32Float` 3D texture. No noise is
//! evaluated per particle.
//!
//! The particle kernels read the volume with `textureLoad` and manual trilinear
//! interpolation with periodic wrap; [`WindVolume::sample`] is the same arithmetic in
//! Rust, written to be read side by side with its WGSL twin. The pattern is animated
//! as frozen turbulence: the sampling point moves with the mean wind.
//!
//! ## Periodicity
//!
//! Plain Perlin noise does not tile, so a wrapped volume would have a seam. The bake
//! blends the noise with its copies shifted by one period along each axis, with
//! trilinear weights in the position's fraction of the period, normalised by the root
//! of the summed squared weights so that the blend keeps the noise's contrast. The
//! result is a continuous periodic function, and so is the sampler.

mod bake;
mod error;
mod field;
mod sampler;
mod volume;
pub mod wgsl;

pub use error::WindError;
pub use field::WindField;
pub use sampler::WindSample;
pub use sampler::wind_velocity;
pub use volume::{WindParams, WindTexel, WindVolume, WindVolumeSpec};
