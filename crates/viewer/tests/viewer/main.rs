//! The viewer: scene files (fixtures written here, the demo), bad files, headless runs,
//! windows under Xvfb.

mod bad_files;
mod cigi_host;
mod cli;
mod coast;
mod compressed;
mod fixtures;
mod graphs;
mod headless;
mod loading;
mod scenario_run;
mod swapchain;
mod xvfb;
