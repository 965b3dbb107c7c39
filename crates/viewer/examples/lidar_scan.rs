//! A LiDAR in the snow: steps the built-in demo under a weather, renders a frame, and
//! casts a spinning 32-channel LiDAR from the camera against the particles and the
//! scene; writes `frame.png` and `scan.ply` (the strongest echo of each beam, with a
//! flag for echoes from flakes or drops) side by side.
//!
//! `cargo run --release -p precip-viewer --example lidar_scan -- [OUT_DIR] [PRESET] [FRAMES]`
//! (defaults: `lidar-scan`, `blizzard`, 30), on the wgpu backend.

use anyhow::Context as _;
use precip_model::View;
use precip_model::sensors::lidar::{BeamQuery, EchoOrigin};
use precip_model::sensors::optics::Band;
use precip_viewer::backends::{BackendName, open_headless};
use precip_viewer::demo::DEMO_GLB;
use precip_viewer::lidar_scan::{SpinningLidar, point_cloud, write_ply};
use precip_viewer::presets::Preset;
use precip_viewer::scene_setup::{SceneOptions, scene_setup};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| "lidar-scan".into()));
    let preset = args.next().unwrap_or_else(|| "blizzard".into());
    let frames: u32 = args
        .next()
        .map_or(Ok(30), |f| f.parse())
        .context("FRAMES")?;
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;

    let weather = Preset::load(&preset)?.weather()?;
    let loaded = precip_viewer::load_scene_from_slice(DEMO_GLB, "built-in demo.glb")?;
    let setup = scene_setup(
        loaded.scene,
        &SceneOptions {
            particle_budget: 150_000,
            seed: 1,
            texel_m: 0.5,
            grid_side_m: None,
            cover_days_per_second: 0.05,
            weather,
            camera: None,
        },
    )?;
    let (mut backend, _) = open_headless(BackendName::Wgpu)?;
    backend.configure(&setup)?;
    for _ in 0..frames {
        backend.step(1.0 / 30.0)?;
    }
    let view = View {
        camera: setup.camera,
        width_px: 960,
        height_px: 540,
    };
    backend.render(&view)?;
    let image = backend.read_image()?;
    image::save_buffer(
        out.join("frame.png"),
        &image.rgba8,
        image.width_px,
        image.height_px,
        image::ExtendedColorType::Rgba8,
    )?;

    let lidar = SpinningLidar::automotive(setup.camera.position_m);
    let query = BeamQuery {
        beams: lidar.beams(),
        band: Band::NearInfrared,
        aperture_radius_m: precip_viewer::lidar_scan::APERTURE_RADIUS_M,
        extinction_per_m: Some(backend.optics()?.band(Band::NearInfrared).extinction_per_m),
        sample_unresolved: true,
    };
    let started = std::time::Instant::now();
    let returns = backend.query_beams(&query)?;
    let took = started.elapsed();
    let wind = backend.weather()?.wind.mean_wind_mps;
    let points = point_cloud(
        &query.beams,
        &returns,
        query.band,
        lidar.detection_threshold(),
        wind.x.hypot(wind.z),
    );
    write_ply(&out.join("scan.ply"), &points)?;
    let from_particles = points.iter().filter(|p| p.from_particle).count();
    let drawn = returns
        .iter()
        .filter(|r| r.particle.is_some_and(|p| p.origin == EchoOrigin::Spectrum))
        .count();
    let near: Vec<f32> = points
        .iter()
        .filter(|p| p.from_particle)
        .map(|p| (p.position_m - lidar.origin_m).length())
        .collect();
    let furthest = near.iter().copied().fold(0.0f32, f32::max);
    println!(
        "{} beams in {:.0} ms: {} points detected, {from_particles} of them echoes from {preset} particles (the furthest at {furthest:.1} m; {drawn} beams struck a particle drawn from the spectrum); wrote {} and {}",
        query.beams.len(),
        took.as_secs_f64() * 1e3,
        points.len(),
        out.join("frame.png").display(),
        out.join("scan.ply").display()
    );
    Ok(())
}
