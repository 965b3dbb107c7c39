//! The CPU reference backend end to end: one test binary (its modules share helpers).

mod bad_input;
mod common;
mod determinism;
mod drifting;
mod mass_link;
mod resting;
mod scene;
mod splashes;
