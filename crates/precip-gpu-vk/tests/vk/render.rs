//! The Vulkan renderer against the wgpu one: the same frames within 1/255 per channel
//! on at least 99.9 % of pixels over random scenes, weather and cameras; clean under
//! the validation layer through resizes, re-configures and drops (no leaks); typed
//! errors for bad views; timings per pass.

use glam::Vec3;
use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::scene::builtin::house_on_plane;
use precip_model::wind::WindField;
use precip_model::{Backend, BackendError, Camera, Image, PrecipitationKind, Setup, View};
use proptest::prelude::*;

use crate::{assert_clean, assert_log_clean, vk};

/// Pixels whose channels all agree within 1/255, as a fraction, and the largest
/// channel difference.
fn agreement(a: &Image, b: &Image) -> (f64, u8) {
    assert_eq!((a.width_px, a.height_px), (b.width_px, b.height_px));
    let mut close = 0usize;
    let mut worst = 0u8;
    for (p, q) in a.rgba8.chunks_exact(4).zip(b.rgba8.chunks_exact(4)) {
        let d = p
            .iter()
            .zip(q)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap_or(0);
        worst = worst.max(d);
        if d <= 1 {
            close += 1;
        }
    }
    (close as f64 / (a.rgba8.len() / 4) as f64, worst)
}

fn house(seed: u32, kind: PrecipitationKind, wind_mps: f32, count: u32) -> Setup {
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, count).expect("valid");
    setup.seed = seed;
    setup.weather.kind = kind;
    setup.weather.air_temperature_c = if kind == PrecipitationKind::Rain {
        6.0
    } else {
        -3.0
    };
    setup.weather.intensity_mm_per_h = 4.0;
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(wind_mps, 0.0, -0.4 * wind_mps),
        ..WindField::calm()
    };
    // A visible cover within a few steps.
    setup.cover.time_scale = 20_000.0;
    setup
}

fn frame(backend: &mut dyn Backend, setup: &Setup, steps: usize, view: &View) -> Image {
    backend.configure(setup).expect("valid");
    for _ in 0..steps {
        backend.step(0.08).expect("valid step");
    }
    backend.set_camera(&view.camera).expect("valid camera");
    // Twice: the second frame's water reflects the first's scene (its copies).
    backend.render(view).expect("renders");
    backend.render(view).expect("renders");
    backend.read_image().expect("an image")
}

fn wgpu() -> Option<WgpuBackend> {
    match WgpuBackend::new() {
        Ok(b) => Some(b),
        Err(e) => {
            eprintln!("no wgpu adapter to compare with: {e}");
            None
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    #[test]
    fn vk_and_wgpu_draw_the_same_frames(
        seed in 0u32..10_000,
        rain in any::<bool>(),
        wind_mps in 0.0f32..9.0,
        steps in 1usize..4,
        count in 2_000u32..12_000,
        (x, y, z) in (-14.0f32..14.0, 1.5f32..9.0, 8.0f32..16.0),
        yaw in -0.5f32..0.5,
        culling in any::<bool>(),
        resolution in 0usize..3,
        snow_quads in any::<bool>(),
    ) {
        let (Some(mut vk), Some(mut wgpu)) = (vk("vk_and_wgpu_draw_the_same_frames"), wgpu()) else {
            return Ok(());
        };
        let kind = if rain { PrecipitationKind::Rain } else { PrecipitationKind::WetSnow };
        let mut setup = house(seed, kind, wind_mps, count);
        setup.render.view_cone_culling = culling;
        setup.render.particle_resolution = [
            precip_model::ParticleResolution::Full,
            precip_model::ParticleResolution::Half,
            precip_model::ParticleResolution::Quarter,
        ][resolution];
        let position = Vec3::new(x, y, z);
        let camera = Camera {
            position_m: position,
            forward: (Vec3::new(yaw * 10.0, 1.5, 0.0) - position).normalize(),
            ..Camera::default()
        };
        setup.camera = camera;
        let view = View { camera, width_px: 160, height_px: 96 };
        // wgpu keeps the snow quads; vk keeps them or has each corner make its own.
        let b = frame(&mut wgpu, &setup, steps, &view);
        setup.render.snow_quads = snow_quads;
        let a = frame(&mut vk, &setup, steps, &view);
        let (close, worst) = agreement(&a, &b);
        let distinct = a.rgba8.chunks_exact(4).collect::<std::collections::HashSet<_>>().len();
        eprintln!("vk vs wgpu: {:.5} within 1/255, worst {worst}/255, {distinct} distinct colours, drawn {:?}", close, vk.drawn().ok());
        prop_assert!(close >= 0.999, "{:.4} % of pixels within 1/255 (worst {worst}/255)", close * 100.0);
        prop_assert_eq!(vk.drawn().expect("counts"), wgpu.drawn().expect("counts"));
        assert_clean(&vk, "while drawing");
    }
}

/// A pond before the house, seen low across it: both backends mirror the house in
/// it alike (through the planar mirror, drawn within the water's rectangle).
#[test]
fn vk_and_wgpu_mirror_the_house_in_a_pond_alike() {
    let (Some(mut vk), Some(mut wgpu)) =
        (vk("vk_and_wgpu_mirror_the_house_in_a_pond_alike"), wgpu())
    else {
        return;
    };
    let (mut setup, _) = Setup::over_scene(
        precip_model::scene::builtin::house_with_pond(),
        64,
        6.0,
        2_000,
    )
    .expect("valid");
    setup.weather.intensity_mm_per_h = 0.5;
    // Through a fog layer over the pond, which the mirror reflects with the camera,
    // under cumulus (the clouds' pass and image).
    setup.render.fog_layer = Some(precip_model::drawing::fog_layer::FogLayer::new(2.5, 60.0));
    setup.render.cloud_layers = precip_model::drawing::clouds::CloudLayers::one(
        precip_model::drawing::clouds::CloudLayer::typical(
            precip_model::drawing::clouds::CloudKind::Cumulus,
            0.5,
        ),
    );
    let position = Vec3::new(0.0, 0.8, 18.0);
    let camera = Camera {
        position_m: position,
        forward: (Vec3::new(0.0, 1.0, 0.0) - position).normalize(),
        ..Camera::default()
    };
    setup.camera = camera;
    let view = View {
        camera,
        width_px: 160,
        height_px: 96,
    };
    let a = frame(&mut vk, &setup, 2, &view);
    let b = frame(&mut wgpu, &setup, 2, &view);
    let (close, worst) = agreement(&a, &b);
    assert!(
        close >= 0.999,
        "{:.4} % of pixels within 1/255 (worst {worst}/255)",
        close * 100.0
    );
    assert_clean(&vk, "while mirroring");
}

#[test]
fn vk_and_wgpu_reuse_the_clouds_alike_with_no_rain_falling() {
    let (Some(mut vk), Some(mut wgpu)) = (
        vk("vk_and_wgpu_reuse_the_clouds_alike_with_no_rain_falling"),
        wgpu(),
    ) else {
        return;
    };
    // No rain: the scene is the last pass on the target, and the pond's copy of
    // it comes after (the target is copied in its final layout). Turning under
    // cumulus: the clouds' fresh pixels, the frame before's image and the march
    // of what it did not see.
    let (mut setup, _) = Setup::over_scene(
        precip_model::scene::builtin::house_with_pond(),
        64,
        6.0,
        500,
    )
    .expect("valid");
    setup.weather.intensity_mm_per_h = 0.0;
    setup.render.cloud_layers = precip_model::drawing::clouds::CloudLayers::one(
        precip_model::drawing::clouds::CloudLayer::typical(
            precip_model::drawing::clouds::CloudKind::Cumulus,
            0.5,
        ),
    );
    let view_at = |k: usize| {
        let yaw = (3.0 * k as f32).to_radians();
        View {
            camera: Camera {
                position_m: Vec3::new(0.0, 1.5, 18.0),
                forward: Vec3::new(yaw.sin(), 0.35, -yaw.cos()).normalize(),
                ..Camera::default()
            },
            width_px: 160,
            height_px: 96,
        }
    };
    let mut images = Vec::new();
    for backend in [&mut vk as &mut dyn Backend, &mut wgpu] {
        backend.configure(&setup).expect("valid");
        backend.step(0.08).expect("valid step");
        for k in 0..6 {
            backend
                .set_camera(&view_at(k).camera)
                .expect("valid camera");
            backend.render(&view_at(k)).expect("renders");
        }
        images.push(backend.read_image().expect("an image"));
    }
    let (close, worst) = agreement(&images[0], &images[1]);
    assert!(
        close >= 0.999,
        "{:.4} % of pixels within 1/255 (worst {worst}/255)",
        close * 100.0
    );
    assert_clean(&vk, "reusing the clouds with no rain");
}

#[test]
fn resizing_reconfiguring_and_dropping_leave_nothing_behind() {
    for round in 0..2u32 {
        let Some(mut vk) = vk("resizing_reconfiguring_and_dropping_leave_nothing_behind") else {
            return;
        };
        let log = vk.validation_log();
        let setup = house(round, PrecipitationKind::DrySnow, 2.0, 3_000);
        vk.configure(&setup).expect("valid");
        // Several sizes back to back: the old targets are retired while frames are
        // still in flight, then freed.
        for (i, (w, h)) in [(64, 48), (97, 33), (64, 48), (200, 120), (1, 1)]
            .into_iter()
            .enumerate()
        {
            vk.step(0.05).expect("valid step");
            vk.render(&View {
                camera: setup.camera,
                width_px: w,
                height_px: h,
            })
            .expect("renders");
            if i % 2 == 1 {
                let image = vk.read_image().expect("an image");
                assert_eq!((image.width_px, image.height_px), (w, h));
            }
        }
        // Re-configure with the render state alive, then render again.
        vk.configure(&setup).expect("valid");
        vk.render(&View {
            camera: setup.camera,
            width_px: 32,
            height_px: 32,
        })
        .expect("renders");
        drop(vk);
        assert_log_clean(&log, &format!("round {round}"));
    }
}

#[test]
fn bad_views_are_typed_errors_and_nothing_is_read_before_a_frame() {
    let Some(mut vk) = vk("bad_views_are_typed_errors") else {
        return;
    };
    let setup = house(1, PrecipitationKind::DrySnow, 0.0, 500);
    let camera = setup.camera;
    let view = |width_px, height_px| View {
        camera,
        width_px,
        height_px,
    };
    assert!(matches!(
        vk.render(&view(8, 8)),
        Err(BackendError::NotConfigured { .. })
    ));
    vk.configure(&setup).expect("valid");
    assert!(matches!(
        vk.read_image(),
        Err(BackendError::NothingRendered)
    ));
    for (w, h) in [(0, 8), (8, 0), (100_000, 8), (u32::MAX, u32::MAX)] {
        assert!(
            matches!(vk.render(&view(w, h)), Err(BackendError::InvalidView(_))),
            "{w}×{h}"
        );
    }
    let mut nan = view(8, 8);
    nan.camera.position_m.x = f32::NAN;
    assert!(vk.render(&nan).is_err());
    assert!(vk.info().renders);
    assert_clean(&vk, "refusing bad views");
}

#[test]
fn timings_name_every_pass_of_a_frame() {
    let Some(mut vk) = vk("timings_name_every_pass_of_a_frame") else {
        return;
    };
    let mut setup = house(2, PrecipitationKind::DrySnow, 1.0, 2_000);
    for resolution in [
        precip_model::ParticleResolution::Full,
        precip_model::ParticleResolution::Quarter,
    ] {
        setup.render.particle_resolution = resolution;
        vk.configure(&setup).expect("valid");
        vk.step(0.05).expect("valid step");
        vk.render(&View {
            camera: setup.camera,
            width_px: 64,
            height_px: 48,
        })
        .expect("renders");
        let timings = vk.timings().expect("timings");
        if timings.source == precip_model::TimingSource::Unavailable {
            eprintln!("no timestamps on this device");
            return;
        }
        // The particles are drawn one way or the other; the house has no water and
        // no sea, the sky no clouds.
        let cloudless: Vec<&str> = precip_gpu::recipe::cloud_passes().collect();
        let not_run: &[&str] = if resolution == precip_model::ParticleResolution::Full {
            &[
                "particles_reduced",
                "particles_composite",
                "water_mirror",
                "ocean",
                "shore",
            ]
        } else {
            &["particles", "water_mirror", "ocean", "shore"]
        };
        for pass in ["step_particles"]
            .into_iter()
            .chain(precip_gpu::recipe::TIMED_RENDER_PASSES)
        {
            let t = timings.passes.iter().find(|p| p.pass == pass);
            assert_eq!(
                t.is_none(),
                not_run.contains(&pass) || cloudless.contains(&pass),
                "{pass}: {timings:?}"
            );
            assert!(t.is_none_or(|t| t.milliseconds.is_finite() && t.milliseconds >= 0.0));
        }
    }
    let _: fn(bool) -> Result<VkBackend, BackendError> = VkBackend::new;
}

#[test]
fn the_image_comparison_sees_a_small_change() {
    // A negative control for the equivalence property: one particle count apart, the
    // same backend's frames must fail the 99.9 % bound.
    let Some(mut vk) = vk("the_image_comparison_sees_a_small_change") else {
        return;
    };
    let setup = house(5, PrecipitationKind::WetSnow, 3.0, 6_000);
    let view = View {
        camera: setup.camera,
        width_px: 160,
        height_px: 96,
    };
    let a = frame(&mut vk, &setup, 2, &view);
    let mut other = setup.clone();
    other.seed += 1;
    let b = frame(&mut vk, &other, 2, &view);
    let (close, worst) = agreement(&a, &b);
    assert!(
        close < 0.999 && worst > 1,
        "another seed should show: {close} within 1/255, worst {worst}"
    );
    assert_clean(&vk, "drawing twice");
}
