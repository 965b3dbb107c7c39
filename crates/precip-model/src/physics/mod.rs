//! The physics of what falls and what it does on landing, each formula once in
//! Rust here and once in WGSL (`shaders/physics.wgsl`, `splash.wgsl`,
//! `water_waves.wgsl`, `ground.wgsl`), side by side; `docs/model.md` gives every
//! equation with its source and the numbers it is tested against.
//!
//! - [`snowflake`] and [`raindrop`]: size, density, mass and terminal speed
//!   (`docs/model.md` §2); [`snowfall`]: the flakes' size spectrum.
//! - [`drag`]: gravity and drag toward the wind, the stable integrator;
//!   [`rotation`]: the flakes' oscillation.
//! - [`grain`]: sand and dust (fall speeds, the wind's threshold, saltation);
//!   [`hail`]: hailstones' fall speeds and size spectrum.
//! - [`splash`]: secondary droplets; [`water_waves`]: rain rings on water bodies.
//! - [`terrain_flow`]: the wind near the ground; [`drifting_snow`]: blowing snow
//!   made visible.

pub mod drag;
pub mod drifting_snow;
pub mod grain;
pub mod hail;
pub mod raindrop;
pub mod rotation;
pub mod snowfall;
pub mod snowflake;
pub mod splash;
pub mod terrain_flow;
pub mod water_waves;
