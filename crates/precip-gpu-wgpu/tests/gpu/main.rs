//! The wgpu backend on every adapter found: one test binary (its modules share
//! helpers). Without an adapter the tests print why and pass, unless
//! `PRECIP_REQUIRE_GPU=1`.

mod behaviour;
mod common;
mod drawing;
mod equivalence;
mod images;
mod ocean;
mod render;
mod rng;
