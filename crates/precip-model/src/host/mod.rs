//! The host side every backend shares: [`HostState`] (setup, weather, wind volume,
//! camera, clock, and the uniform blocks computed from them, once), the blocks that
//! cross to the GPU besides those of their own modules ([`Frames`],
//! [`SceneVertex`]), and the dispatch arithmetic ([`dispatch_size`]).
//!
//! The CPU reference runs its sub-steps with the blocks a [`HostState`] gives; the
//! GPU backends upload the same blocks. Each derived number has one place: the mean
//! wind, for instance, reaches the particles' block, the cover's block and the wind
//! sampler's block from the one [`crate::Weather`] the host state holds.

mod activity;
pub mod cover_window;
mod dispatch;
mod far_air;
mod far_cover;
mod far_water;
mod layout;
mod state;

pub use activity::Activity;
pub use cover_window::{CoverWindow, MOVE_AT_SIDE_SHARE, MOVE_STEP_TEXELS};
pub use dispatch::{MAX_WORKGROUPS_PER_DIMENSION, WORKGROUP_SIZE, cull_groups, dispatch_size};
pub use far_air::{
    LAPSE_RATE_C_PER_M, MAX_SLOPE_SUN_RATIO, SUN_MELT_SHARE, local_relative_humidity,
    local_snow_share, slope_irradiance_factor,
};
pub use far_cover::{
    FAR_CELLS_MAX, FAR_COVER_SURFACES, FAR_MASK, FAR_PIECE_DAYS, FAR_ROW_FLOATS, FAR_STEP_EVERY,
    FarCover, FarCoverRows, GRID_BLEND_SHARE, SNOW_LINE_BAND_M, SNOW_LINE_DEPTH_MM, far_cover_slot,
    grid_blend, grid_interior_m,
};
pub use far_water::{SHAFT_SAMPLES_PER_SIDE, Shafts, WaterBeyond};
pub use layout::{Frames, SceneVertex};
pub use state::{HostState, SubStepBlocks, SubSteps, WeatherChange};
