//! The viewer: scene files (fixtures written here, the demo), bad files, headless runs,
//! windows under Xvfb.

mod bad_files;
mod cli;
mod compressed;
mod fixtures;
mod graphs;
mod headless;
mod loading;
mod swapchain;
mod xvfb;
