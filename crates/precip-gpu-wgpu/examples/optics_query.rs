//! Times `Backend::optics()` — the camera volume's cross-sections summed on the
//! device (`optics_sums`) — against reading every particle back and summing on the
//! host (`Optics::live`, what it did before), at 10⁴ to 10⁶ camera-volume particles,
//! and prints both answers' 550 nm extinction.
//!
//! `cargo run --release -p precip-gpu-wgpu --example optics_query`

use std::time::Instant;

use glam::Vec3;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::backend::setup::CameraVolumeSetup;
use precip_model::sensors::optics::{Band, Optics};
use precip_model::{Backend, BackendError, CameraVolume, PrecipitationKind, Setup, Weather};

fn main() -> Result<(), BackendError> {
    let mut gpu = WgpuBackend::new()?;
    println!("{}", gpu.info().device);
    for count in [10_000u32, 100_000, 1_000_000] {
        let mut setup = Setup::over_flat_ground(40.0, 64, 15.0, 1_000);
        setup.weather = Weather {
            kind: PrecipitationKind::Rain,
            intensity_mm_per_h: 10.0,
            air_temperature_c: 12.0,
            ..Weather::default()
        };
        setup.camera.position_m = Vec3::new(0.0, 1.7, 0.0);
        setup.camera_volume = Some(CameraVolumeSetup {
            volume: CameraVolume {
                half_extent_m: Vec3::splat(10.0),
                ..CameraVolume::default()
            },
            particle_count: count,
        });
        gpu.configure(&setup)?;
        gpu.step(0.05)?;
        // Warm both paths once, then time the best of five.
        let mut device = (f64::INFINITY, None);
        let mut host = (f64::INFINITY, None);
        for _ in 0..5 {
            let start = Instant::now();
            let o = gpu.optics()?;
            device = (device.0.min(start.elapsed().as_secs_f64() * 1e3), Some(o));
            let start = Instant::now();
            let o = Optics::live(&gpu.weather()?, &gpu.read_particles()?);
            host = (host.0.min(start.elapsed().as_secs_f64() * 1e3), Some(o));
        }
        let extinction =
            |o: Option<Optics>| o.map_or(0.0, |o| o.band(Band::Visible).extinction_per_m);
        println!(
            "{count:>9} camera-volume particles: on the device {:.2} ms (σ550 {:.4e}/m), read back and summed on the host {:.2} ms (σ550 {:.4e}/m)",
            device.0,
            extinction(device.1),
            host.0,
            extinction(host.1),
        );
    }
    Ok(())
}
