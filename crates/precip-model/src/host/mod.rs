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
mod dispatch;
mod layout;
mod state;

pub use activity::Activity;
pub use dispatch::{MAX_WORKGROUPS_PER_DIMENSION, WORKGROUP_SIZE, cull_groups, dispatch_size};
pub use layout::{Frames, SceneVertex};
pub use state::{
    FAR_COVER_SURFACES, HostState, SubStepBlocks, SubSteps, WeatherChange, far_cover_slot,
};
