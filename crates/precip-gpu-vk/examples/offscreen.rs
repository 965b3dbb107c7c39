//! The library in a few lines: set the weather in physical units, pick a backend,
//! step and render frames offscreen, write the last one as a PNG.
//!
//! `cargo run --release -p precip-gpu-vk --example offscreen -- vk target/offscreen.png`
//! (or `wgpu`): the same frame from either backend.

use glam::Vec3;
use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::scene::builtin::house_on_plane;
use precip_model::wind::WindField;
use precip_model::{Backend, PrecipitationKind, Setup, View};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let backend_name = args.next().unwrap_or_else(|| "vk".into());
    let out = args.next().unwrap_or_else(|| "target/offscreen.png".into());

    // The scene (any `precip_model::Scene`; the viewer crate loads glTF into one), a
    // 128² ground map, emitters 6 m above it and 50 000 particles.
    let (mut setup, _report) = Setup::over_scene(house_on_plane(), 128, 6.0, 50_000)?;
    setup.weather.kind = PrecipitationKind::WetSnow;
    setup.weather.intensity_mm_per_h = 4.0;
    setup.weather.air_temperature_c = -0.5;
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(4.0, 0.0, 1.0),
        ..WindField::calm()
    };
    setup.cover.time_scale = 3_600.0; // an hour of cover per second

    let mut backend: Box<dyn Backend> = match backend_name.as_str() {
        "wgpu" => Box::new(WgpuBackend::new()?),
        _ => Box::new(VkBackend::new(false)?),
    };
    println!("{}", backend.info().device);
    backend.configure(&setup)?;
    let view = View {
        camera: setup.camera,
        width_px: 960,
        height_px: 540,
    };
    for _ in 0..30 {
        backend.step(1.0 / 30.0)?;
        backend.render(&view)?;
    }
    let image = backend.read_image()?;
    image::save_buffer(
        &out,
        &image.rgba8,
        image.width_px,
        image.height_px,
        image::ExtendedColorType::Rgba8,
    )?;
    for pass in backend.timings()?.passes {
        println!("{:>16}: {:.2} ms", pass.pass, pass.milliseconds);
    }
    println!("wrote {out}");
    Ok(())
}
