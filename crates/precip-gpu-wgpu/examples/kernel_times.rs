//! Prints GPU time per kernel of one step at 10⁴, 10⁵ and 10⁶ particles (timestamp
//! queries), the report behind the README's performance notes.
//!
//! `cargo run --release -p precip-gpu-wgpu --example kernel_times`

use glam::Vec3;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::wind::WindField;
use precip_model::{Backend, BackendError, Setup};

fn main() -> Result<(), BackendError> {
    let mut gpu = WgpuBackend::new()?;
    println!("{}", gpu.info().device);
    for count in [10_000u32, 100_000, 1_000_000] {
        let mut setup = Setup::over_flat_ground(200.0, 128, 40.0, count);
        setup.weather.wind = WindField {
            mean_wind_mps: Vec3::new(5.0, 0.0, 2.0),
            vertical_gust_mps: 0.5,
            ..WindField::calm()
        };
        gpu.configure(&setup)?;
        let mut sums = Vec::new();
        let steps = 10;
        for _ in 0..steps {
            gpu.step(0.02)?;
            for (i, pass) in gpu.timings()?.passes.iter().enumerate() {
                if sums.len() <= i {
                    sums.push((pass.pass, 0.0));
                }
                sums[i].1 += pass.milliseconds / f64::from(steps);
            }
        }
        let line: Vec<String> = sums
            .iter()
            .map(|(name, ms)| format!("{name} {ms:.2} ms"))
            .collect();
        println!("{count:>9} particles: {}", line.join(", "));
    }
    Ok(())
}
