//! Headless end to end on the GPU: the demo under snow writes PNGs; snow lies on the
//! roof, not on the road or the heated patio.

use glam::Vec2;
use precip_gpu_wgpu::{WgpuBackend, adapters};
use precip_model::scene::builtin::HousePlan;
use precip_model::{Backend, View, Weather};
use precip_viewer::demo::{DEMO_GLB, PATIO, ROAD_X_M};
use precip_viewer::headless::run_headless;
use precip_viewer::load_scene_from_slice;
use precip_viewer::scene_setup::{SceneOptions, scene_setup};

#[test]
fn a_headless_run_over_the_demo_writes_frames_and_snow_settles_where_it_should() {
    let found = adapters();
    if found.is_empty() {
        assert!(
            std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
            "PRECIP_REQUIRE_GPU=1 but no wgpu adapter found (install mesa-vulkan-drivers)"
        );
        eprintln!("SKIPPED headless: no wgpu adapter found");
        return;
    }
    let scene = load_scene_from_slice(DEMO_GLB, "demo.glb")
        .expect("loads")
        .scene;
    let options = SceneOptions {
        particle_budget: 30_000,
        seed: 3,
        texel_m: 0.5,
        grid_side_m: None,
        cover_days_per_second: 1.0,
        weather: Weather {
            intensity_mm_per_h: 3.0,
            air_temperature_c: -6.0,
            ..Weather::default()
        },
        camera: None,
    };
    let setup = scene_setup(scene, &options).expect("valid");
    assert!(
        setup.world_emitter.is_some(),
        "the demo is small enough for a world emitter"
    );
    for adapter in &found {
        let mut gpu = WgpuBackend::on_adapter(adapter).expect("a device");
        gpu.configure(&setup).expect("valid");
        let view = View {
            camera: setup.camera,
            width_px: 160,
            height_px: 90,
        };
        let out = std::env::temp_dir().join(format!("precip-headless-{}", std::process::id()));
        let summary = run_headless(&mut gpu, &view, 16, 0.25, &out, false).expect("runs");
        assert_eq!(summary.files.len(), 16);
        assert!(summary.files.iter().all(|f| f.exists()));
        assert!(summary.mean_frame_ms > 0.0 && summary.p95_frame_ms >= summary.mean_frame_ms * 0.5);
        let cover = gpu.read_cover().expect("cover");
        let plan = HousePlan::default();
        let swe = |p: Vec2| {
            let i = cover.frame.texel_index(p).expect("on the grid");
            cover.texels[i].swe_mm
        };
        let mean =
            |points: &[Vec2]| points.iter().map(|p| swe(*p)).sum::<f32>() / points.len() as f32;
        let roof: Vec<Vec2> = (-3..=3)
            .flat_map(|i| (-2..=2).map(move |j| Vec2::new(i as f32, j as f32)))
            .collect();
        let road_x = 0.5 * (ROAD_X_M.0 + ROAD_X_M.1);
        let road: Vec<Vec2> = (-10..=10)
            .map(|j| Vec2::new(road_x, 2.0 * j as f32))
            .collect();
        let patio: Vec<Vec2> = [Vec2::ZERO, Vec2::X, Vec2::NEG_X, Vec2::Y, Vec2::NEG_Y]
            .iter()
            // Within its heated core: at its rim the mask fades, and snow sliding
            // off the snow around it stays there in that share.
            .map(|d| PATIO.0 + 0.5 * *d)
            .collect();
        let summary_text = format!(
            "roof {:.1} mm, road {:.2} mm, patio {:.2} mm (plan {}×{} m)",
            mean(&roof),
            mean(&road),
            mean(&patio),
            plan.width_m,
            plan.depth_m
        );
        assert!(mean(&roof) > 5.0, "{summary_text}");
        assert!(mean(&road) < 0.01, "{summary_text}");
        assert!(mean(&patio) < 0.01, "{summary_text}");
        let _ = std::fs::remove_dir_all(&out);
    }
}
