//! What the benches and the report share: the step scenario (wind over flat ground,
//! a 128² cover grid), the frame scenario (the built-in house, 1280×720 unless asked
//! otherwise), the backends present on this machine, and the report's plot ([`plot`]).
//!
//! # Example
//!
//! The benches' step scenario, stepped on the CPU reference as `cargo bench -p
//! precip-benches --bench backends` steps it on every backend:
//!
//! ```
//! use precip_model::{Backend, CpuBackend};
//!
//! let setup = precip_benches::scenario(1_000);
//! let mut cpu = CpuBackend::new();
//! cpu.configure(&setup).expect("configures");
//! cpu.step(1.0 / 30.0).expect("steps");
//! assert_eq!(cpu.read_particles().expect("reads back").len(), 1_000);
//! ```

pub mod peer;
pub mod plot;
pub mod terrain;
pub mod traffic;

use glam::Vec3;
use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::scene::builtin::house_on_plane;
use precip_model::wind::WindField;
use precip_model::{Backend, CpuBackend, Setup, View};

/// Particle counts measured.
pub const COUNTS: [u32; 3] = [10_000, 100_000, 1_000_000];

/// Particle counts of the full frames: [`COUNTS`] and 10⁷ where the device holds it.
pub const FRAME_COUNTS: [u32; 4] = [10_000, 100_000, 1_000_000, 10_000_000];

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

/// The frame's size, px.
pub const FRAME_SIZE: (u32, u32) = (1280, 720);

/// The frame scenario at `count` particles: snow in a light wind over the built-in
/// house (a 128² ground map), seen from its default camera at `size_px` (width,
/// height; [`FRAME_SIZE`] unless asked otherwise).
#[must_use]
pub fn frame_scenario(count: u32, size_px: (u32, u32)) -> (Setup, View) {
    let (mut setup, _) =
        Setup::over_scene(house_on_plane(), 128, 6.0, count).expect("the built-in house is valid");
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(3.0, 0.0, 1.0),
        vertical_gust_mps: 0.3,
        ..WindField::calm()
    };
    let view = View {
        camera: setup.camera,
        width_px: size_px.0,
        height_px: size_px.1,
    };
    (setup, view)
}

/// One frame: a step, then the render; waits for the GPU (through the timings,
/// which it returns).
pub fn frame(backend: &mut dyn Backend, view: &View) -> precip_model::Timings {
    backend.step(DT_S).expect("valid step");
    backend.render(view).expect("renders");
    backend.timings().expect("waits for the GPU")
}

/// Seconds a backend runs frames (or steps) after it is configured before they
/// are measured, at least: a GPU's clock follows its load within a second or so,
/// and the first frames after a configure (seconds of host work, the GPU idle)
/// ran at a lower one (an H200: a frame's passes up to 4× their steady ms).
pub const WARM_UP_S: f64 = 1.5;

/// Seconds a measure takes at least (and at least its count of frames or steps).
pub const MEASURE_S: f64 = 0.5;

/// Runs `run` at least `count` times and for at least `seconds`; how many times
/// it ran.
pub fn repeat_for(count: u32, seconds: f64, mut run: impl FnMut()) -> u32 {
    let start = std::time::Instant::now();
    let mut done = 0;
    while done < count || start.elapsed().as_secs_f64() < seconds {
        run();
        done += 1;
    }
    done
}

/// `timings`' passes added to `passes` (by name, in the order first met) as
/// `1 / n` of a mean.
pub fn accumulate_passes(
    passes: &mut Vec<(&'static str, f64)>,
    timings: precip_model::Timings,
    n: f64,
) {
    for p in timings.passes {
        let ms = p.milliseconds / n;
        match passes.iter_mut().find(|(name, _)| *name == p.pass) {
            Some(k) => k.1 += ms,
            None => passes.push((p.pass, ms)),
        }
    }
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

/// Bytes a step moves per particle ([`precip_gpu::recipe::step_bytes_per_particle`]:
/// `step_particles` reads and writes the 64-byte particle; the birth kernel touches
/// only the few re-born).
#[must_use]
pub fn step_bytes_per_particle() -> u64 {
    precip_gpu::recipe::step_bytes_per_particle()
}

#[cfg(test)]
mod tests {
    #[test]
    fn repeat_for_runs_at_least_its_count_and_its_seconds() {
        let mut runs = 0;
        assert_eq!(super::repeat_for(3, 0.0, || runs += 1), 3);
        assert_eq!(runs, 3);
        let start = std::time::Instant::now();
        let done = super::repeat_for(1, 0.05, || {
            std::thread::sleep(std::time::Duration::from_millis(10))
        });
        assert!(done >= 5 && start.elapsed().as_secs_f64() >= 0.05, "{done}");
    }
}
