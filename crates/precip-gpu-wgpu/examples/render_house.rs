//! Renders the built-in scene (a plane and a gabled house) under falling snow (or
//! rain) for N frames and writes them as PNGs, with GPU time per pass.
//!
//! `cargo run --release -p precip-gpu-wgpu --example render_house -- [frames] [KIND] [out_dir]`
//! (KIND: dry-snow, wet-snow, rain, sleet, sand or dust; `snow` is dry snow)
//!
//! The cover runs at 3 hours per simulated second, so the roof whitens within a few
//! frames while the walls and the ground under the eaves stay bare.

use std::error::Error;
use std::path::PathBuf;

use glam::Vec3;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::scene::builtin::house_on_plane;
use precip_model::wind::WindField;
use precip_model::{Backend, PrecipitationKind, Setup, View};

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let frames: u32 = args.next().map_or(Ok(8), |a| a.parse())?;
    let kind = match args.next().as_deref() {
        None | Some("snow") => PrecipitationKind::DrySnow,
        Some(name) => PrecipitationKind::from_name(name)
            .ok_or_else(|| format!("unknown kind {name}: {}", PrecipitationKind::names()))?,
    };
    let out = PathBuf::from(args.next().unwrap_or_else(|| "target/render_house".into()));
    std::fs::create_dir_all(&out)?;

    let (mut setup, report) = Setup::over_scene(house_on_plane(), 128, 8.0, 100_000)?;
    println!("scene: {report:?}");
    setup.weather.kind = kind;
    setup.weather.intensity_mm_per_h = 4.0;
    setup.weather.air_temperature_c = kind.default_air_temperature_c();
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(0.8, 0.0, 0.3),
        ..WindField::calm()
    };
    setup.cover.time_scale = 3.0 * 3600.0;
    let mut gpu = WgpuBackend::new()?;
    println!("{}", gpu.info().device);
    gpu.configure(&setup)?;
    let view = View {
        camera: setup.camera,
        width_px: 640,
        height_px: 360,
    };
    for frame in 0..frames {
        for _ in 0..5 {
            gpu.step(0.05)?;
        }
        gpu.render(&view)?;
        let image = gpu.read_image()?;
        let path = out.join(format!("frame_{frame:03}.png"));
        image::save_buffer(
            &path,
            &image.rgba8,
            image.width_px,
            image.height_px,
            image::ExtendedColorType::Rgba8,
        )?;
        let passes: Vec<String> = gpu
            .timings()?
            .passes
            .iter()
            .map(|p| format!("{} {:.2} ms", p.pass, p.milliseconds))
            .collect();
        println!("{} — {}", path.display(), passes.join(", "));
    }
    Ok(())
}
