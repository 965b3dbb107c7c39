//! What the benches and the report share: the scenario (wind over flat ground, a
//! 128² cover grid) and the backends present on this machine.

use glam::Vec3;
use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::wind::WindField;
use precip_model::{Backend, CpuBackend, Setup};

/// Particle counts measured.
pub const COUNTS: [u32; 3] = [10_000, 100_000, 1_000_000];

/// One step's length, s (one sub-step).
pub const DT_S: f32 = 0.02;

/// The benchmark scenario at `count` particles.
#[must_use]
pub fn scenario(count: u32) -> Setup {
    let mut setup = Setup::over_flat_ground(200.0, 128, 40.0, count);
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(5.0, 0.0, 2.0),
        vertical_gust_mps: 0.5,
        ..WindField::calm()
    };
    setup
}

/// Every backend this machine has, by name (a missing one is reported and left out).
#[must_use]
pub fn backends() -> Vec<(&'static str, Box<dyn Backend>)> {
    let mut out: Vec<(&'static str, Box<dyn Backend>)> = vec![("cpu", Box::new(CpuBackend::new()))];
    match WgpuBackend::new() {
        Ok(b) => out.push(("wgpu", Box::new(b))),
        Err(e) => eprintln!("wgpu left out: {e}"),
    }
    match VkBackend::new(false) {
        Ok(b) => out.push(("vk", Box::new(b))),
        Err(e) => eprintln!("vk left out: {e}"),
    }
    out
}

/// Bytes a step moves per particle: `step_particles` and `birth_particles` each read
/// and write the 80-byte particle.
pub const STEP_BYTES_PER_PARTICLE: u64 = 4 * 80;
