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
//!
//! ## Example
//!
//! A 6 m/s wind toward the east, baked once, sampled where a flake is:
//!
//! ```
//! use glam::Vec3;
//! use precip_wind::{WindField, WindVolume, WindVolumeSpec, wind_velocity};
//!
//! let field = WindField::horizontal(6.0, 90.0); // m/s, toward 90° (east, +x)
//! let spec = WindVolumeSpec {
//!     texels: glam::UVec3::new(16, 8, 16),
//!     extent_m: Vec3::new(64.0, 32.0, 64.0),
//! };
//! let volume = WindVolume::bake(&field, &spec)?;
//! let gust = volume.sample(Vec3::new(3.0, 2.0, -7.0), 1.5); // m, s
//! let v = wind_velocity(field.mean_wind_mps, field.gust_factor, gust);
//! assert!(v.x > 5.0 && v.x < 7.0, "{v}");
//! // A field out of range is refused, naming the field and the range.
//! let storm = WindField::horizontal(500.0, 90.0);
//! assert!(storm.validate().unwrap_err().to_string().contains("[-100, 100]"));
//! # Ok::<(), precip_wind::WindError>(())
//! ```

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
