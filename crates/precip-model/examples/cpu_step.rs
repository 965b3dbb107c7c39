//! Times the CPU reference: wind bake, and particle steps per second at a few counts.
//!
//! `cargo run --release -p precip-model --example cpu_step`

use std::time::Instant;

use glam::Vec3;
use precip_model::wind::{WindField, WindVolume, WindVolumeSpec};
use precip_model::{Backend, CpuBackend, Setup};

fn main() -> Result<(), precip_model::BackendError> {
    let field = WindField {
        mean_wind_mps: Vec3::new(5.0, 0.0, 2.0),
        vertical_gust_mps: 0.5,
        ..WindField::calm()
    };
    let spec = WindVolumeSpec::default();
    let start = Instant::now();
    let _volume = WindVolume::bake(&field, &spec)?;
    println!(
        "wind bake {}x{}x{}: {:.1} ms",
        spec.texels.x,
        spec.texels.y,
        spec.texels.z,
        start.elapsed().as_secs_f64() * 1e3
    );
    for count in [10_000u32, 100_000, 1_000_000] {
        let mut setup = Setup::over_flat_ground(200.0, 256, 40.0, count);
        setup.weather.wind = field;
        let mut backend = CpuBackend::new();
        backend.configure(&setup)?;
        backend.step(0.02)?; // warm up
        let steps = (20_000_000 / count).clamp(5, 200);
        let start = Instant::now();
        for _ in 0..steps {
            backend.step(0.02)?;
        }
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "{count:>9} particles: {:.2} ms/step, {:.1} M particle-steps/s ({})",
            seconds * 1e3 / f64::from(steps),
            f64::from(count) * f64::from(steps) / seconds / 1e6,
            backend.info().device
        );
    }
    Ok(())
}
