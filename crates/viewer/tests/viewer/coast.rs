//! The coastal scene: its sea is tagged and left out of the land's bounds, and on
//! the GPU a gale's sea is drawn rougher and whiter than a calm day's, the same
//! frame on both GPU backends.

use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::{WgpuBackend, adapters};
use precip_model::{Backend, Camera, PrecipitationKind, View, Weather};
use precip_viewer::coast::{BEACH_VIEW, coast_glb};
use precip_viewer::load_scene_from_slice;
use precip_viewer::presets::wind_vector;
use precip_viewer::scene_setup::{SceneOptions, scene_setup};

fn setup(wind_mps: f32) -> precip_model::Setup {
    let scene = load_scene_from_slice(&coast_glb(), "coast.glb")
        .expect("loads")
        .scene;
    let mut weather = Weather {
        kind: PrecipitationKind::Rain,
        intensity_mm_per_h: 0.0,
        air_temperature_c: 12.0,
        ..Weather::default()
    };
    weather.wind.mean_wind_mps = wind_vector(wind_mps, 265.0);
    let options = SceneOptions {
        particle_budget: 2_000,
        seed: 5,
        texel_m: 1.0,
        grid_side_m: None,
        cover_days_per_second: 1.0,
        weather,
        camera: Some(Camera {
            position_m: BEACH_VIEW.0,
            forward: BEACH_VIEW.1 - BEACH_VIEW.0,
            ..Camera::default()
        }),
    };
    scene_setup(scene, &options).expect("valid")
}

/// The luminances of the sea's band of the frame (below the horizon, clear of the
/// breakwater and the pier, toward the shore).
fn sea_band(image: &precip_model::Image) -> Vec<f32> {
    let (w, h) = (image.width_px as usize, image.height_px as usize);
    let mut values = Vec::new();
    for y in (h * 58 / 100)..(h * 72 / 100) {
        for x in (w * 25 / 100)..(w * 70 / 100) {
            let p = &image.rgba8[4 * (y * w + x)..4 * (y * w + x) + 3];
            values.push((f32::from(p[0]) + f32::from(p[1]) + f32::from(p[2])) / 3.0);
        }
    }
    values
}

/// Their spread.
fn spread(values: &[f32]) -> f32 {
    let n = values.len() as f32;
    let mean = values.iter().sum::<f32>() / n;
    (values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / n).sqrt()
}

fn frame(backend: &mut dyn Backend, wind_mps: f32) -> precip_model::Image {
    let setup = setup(wind_mps);
    backend.configure(&setup).expect("configures");
    backend.step(0.05).expect("steps");
    backend
        .render(&View {
            camera: setup.camera,
            width_px: 320,
            height_px: 180,
        })
        .expect("renders");
    backend.read_image().expect("an image")
}

#[test]
fn the_coast_s_sea_is_tagged_and_lies_beyond_the_land_s_bounds() {
    let scene = load_scene_from_slice(&coast_glb(), "coast.glb")
        .expect("loads")
        .scene;
    let seas: Vec<_> = scene.meshes.iter().filter(|m| m.is_sea()).collect();
    assert_eq!(seas.len(), 1, "one sea");
    let (all, land) = (
        scene.bounds_m().expect("bounds"),
        scene.land_bounds_m().expect("land"),
    );
    assert!(all.0.x < -19_000.0 && land.0.x > -400.0, "{all:?} {land:?}");
    // The cover grid covers the land, at the texel asked for.
    let s = setup(5.0);
    assert!(s.cover.frame.size_m.x < 600.0, "{:?}", s.cover.frame);
}

#[test]
fn a_gale_s_sea_is_rougher_and_whiter_than_a_calm_s_on_every_gpu_backend() {
    let found = adapters();
    let require = std::env::var("PRECIP_REQUIRE_GPU").as_deref() == Ok("1");
    if found.is_empty() {
        assert!(!require, "PRECIP_REQUIRE_GPU=1 but no wgpu adapter");
        eprintln!("SKIPPED the coast on wgpu: no adapter");
        return;
    }
    let mut wgpu = WgpuBackend::on_adapter(&found[0]).expect("a device");
    let calm = frame(&mut wgpu, 3.0);
    let gale = frame(&mut wgpu, 20.0);
    let (calm_band, gale_band) = (sea_band(&calm), sea_band(&gale));
    let (calm_spread, gale_spread) = (spread(&calm_band), spread(&gale_band));
    // Foam: brighter than all but 1 % of the calm sea.
    let mut sorted = calm_band.clone();
    sorted.sort_by(f32::total_cmp);
    let bright = sorted[sorted.len() * 99 / 100];
    let share_over = |v: &[f32]| v.iter().filter(|x| **x > bright).count() as f32 / v.len() as f32;
    let (calm_white, gale_white) = (share_over(&calm_band), share_over(&gale_band));
    println!(
        "the sea's band: calm spread {calm_spread:.1}, gale {gale_spread:.1}; over the calm's 99th percentile ({bright:.0}): calm {:.1} %, gale {:.1} %",
        100.0 * calm_white,
        100.0 * gale_white
    );
    assert!(
        gale_spread > 1.3 * calm_spread,
        "{calm_spread} {gale_spread}"
    );
    assert!(gale_white > 0.05, "{calm_white} {gale_white}");
    // The sea is drawn: its band is not the sky's colour.
    let sky = &calm.rgba8[0..3];
    let (w, h) = (calm.width_px as usize, calm.height_px as usize);
    let sea = &calm.rgba8[4 * (h * 58 / 100 * w + w / 2)..][..3];
    assert_ne!(sky, sea);
    match VkBackend::new(true) {
        Ok(mut vk) => {
            let log = vk.validation_log();
            let vk_gale = frame(&mut vk, 20.0);
            let differ = vk_gale
                .rgba8
                .iter()
                .zip(&gale.rgba8)
                .filter(|(a, b)| a.abs_diff(**b) > 1)
                .count();
            assert!(
                differ * 1000 < gale.rgba8.len(),
                "{differ} channels differ by more than 1/255"
            );
            let messages = log.lock().map(|m| m.clone()).unwrap_or_default();
            assert!(messages.is_empty(), "{}", messages.join("\n"));
        }
        Err(e) => {
            assert!(!require, "PRECIP_REQUIRE_GPU=1 but vk: {e}");
            eprintln!("SKIPPED the coast on vk: {e}");
        }
    }
}

#[test]
fn the_coast_s_shore_runs_from_the_shoals_up_the_beach_past_the_pier_s_posts_to_the_wall() {
    use precip_model::drawing::shore::{SHORE_DEPTH_M, ShoreEdge, ShoreGrid};
    use precip_viewer::coast::{BREAKWATER, PIER, land_height_m};
    let scene = load_scene_from_slice(&coast_glb(), "coast.glb")
        .expect("loads")
        .scene;
    let grid = ShoreGrid::of_scene(&scene).expect("a shore");
    let b = &grid.bathymetry;
    println!(
        "the coast's shore: {} × {} cells of {} m from {:?}, edges {:?}",
        b.nx, b.ny, b.cell_m, grid.origin_m, grid.edges
    );
    // The sea's waves come in from the west; the beach's top is a wall; along the
    // shore the water is open.
    assert_eq!(
        grid.edges,
        [
            ShoreEdge::Incoming,
            ShoreEdge::Wall,
            ShoreEdge::Open,
            ShoreEdge::Open
        ]
    );
    assert!(grid.still_level_m.abs() < 1e-3);
    let bed = |x: f32, z: f32| {
        let i = ((x - grid.origin_m.x) / b.cell_m) as usize;
        let j = ((z - grid.origin_m.y) / b.cell_m) as usize;
        b.bed_m[j * b.nx + i]
    };
    // The shoals to SHORE_DEPTH_M, the beach to its top.
    let west = grid.origin_m.x;
    let deepest = -land_height_m(west + 1.0, 0.0);
    assert!(
        (deepest - SHORE_DEPTH_M).abs() < 0.5,
        "{deepest} m deep at the western edge"
    );
    // The breakwater stands on the bed: its top is the shore's bed (a wall).
    let ((wx0, wx1), (wz0, wz1), top) = BREAKWATER;
    let wall = bed(0.5 * (wx0 + wx1), 0.5 * (wz0 + wz1));
    assert!(
        (wall - top).abs() < 0.01,
        "the breakwater's cell at {wall} m"
    );
    // The pier's deck floats: the water runs under it, over the beach's slope.
    let ((px0, px1), (pz0, pz1), _) = PIER;
    let (x, z) = (0.5 * (px0 + px1) - 3.0, 0.5 * (pz0 + pz1));
    let under = bed(x, z);
    assert!(
        (under - land_height_m(x, z)).abs() < 0.2,
        "under the pier's deck the bed is at {under} m"
    );
    // The gale's step and the spin-up's cost on the host.
    let gale = setup(20.0);
    let w = gale.weather.wind.mean_wind_mps;
    let waves = grid.incoming_waves(&gale.render.sea.state([w.x, w.z]));
    let (cap, dt) = grid.step_bounds(&waves);
    let start = std::time::Instant::now();
    let frames =
        precip_model::drawing::shore::ShoreFrames::new(grid.clone(), &gale.render.sea, [w.x, w.z])
            .expect("spins up");
    println!(
        "a gale: the step {:.1} ms, the speed cap {cap:.1} m/s, the spin-up {:.0} ms on the host",
        1e3 * dt,
        1e3 * start.elapsed().as_secs_f64()
    );
    assert!(
        frames
            .spun_up()
            .state()
            .depth_m
            .iter()
            .all(|h| h.is_finite())
    );
}
