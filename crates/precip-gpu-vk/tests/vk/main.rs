//! The Vulkan backend with the Khronos validation layer: any warning or error message
//! fails the test. Without Vulkan the tests print why and pass, unless
//! `PRECIP_REQUIRE_GPU=1`.

use glam::Vec3;
use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::wind::WindField;
use precip_model::{Backend, BackendError, CpuBackend, Particle, PrecipitationKind, Setup, View};
use proptest::prelude::*;

mod render;

/// A backend with validation, or `None` (after saying why) without Vulkan.
pub(crate) fn vk(test: &str) -> Option<VkBackend> {
    match VkBackend::new(true) {
        Ok(b) => Some(b),
        Err(e) => {
            assert!(
                std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
                "{test}: PRECIP_REQUIRE_GPU=1 but {e}"
            );
            eprintln!("SKIPPED {test}: {e}");
            None
        }
    }
}

/// Fails on anything in `log` (read after the backend is dropped, it holds the leak
/// reports of device destruction too).
pub(crate) fn assert_log_clean(log: &precip_gpu_vk::Messages, when: &str) {
    let messages = log.lock().map(|m| m.clone()).unwrap_or_default();
    assert!(
        messages.is_empty(),
        "validation layer, {when}:\n{}",
        messages.join("\n")
    );
}

pub(crate) fn assert_clean(vk: &VkBackend, when: &str) {
    let messages = vk.validation_messages();
    assert!(
        messages.is_empty(),
        "validation layer {when}:\n{}",
        messages.join("\n")
    );
}

fn scenario(seed: u32, kind: PrecipitationKind, wind_mps: f32, count: u32) -> Setup {
    let mut setup = Setup::over_flat_ground(60.0, 32, 20.0, count);
    setup.seed = seed;
    setup.weather.kind = kind;
    setup.weather.air_temperature_c = if kind == PrecipitationKind::Rain {
        8.0
    } else {
        -4.0
    };
    setup.weather.intensity_mm_per_h = 3.0;
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(wind_mps, 0.0, 0.3 * wind_mps),
        vertical_gust_mps: 0.3,
        ..WindField::calm()
    };
    setup.cover.time_scale = 500.0;
    setup
}

fn run(backend: &mut dyn Backend, setup: &Setup, steps: usize, dt: f32) -> Vec<Particle> {
    backend.configure(setup).expect("valid");
    for _ in 0..steps {
        backend.step(dt).expect("valid step");
    }
    backend.read_particles().expect("particles")
}

/// Largest distance in units in the last place between two floats.
fn ulps(a: f32, b: f32) -> u32 {
    let key = |x: f32| {
        let bits = x.to_bits() as i32;
        if bits < 0 { i32::MIN - bits } else { bits }
    };
    key(a).abs_diff(key(b))
}

#[test]
fn a_full_run_is_clean_under_the_validation_layer() {
    let Some(mut vk) = vk("a_full_run_is_clean_under_the_validation_layer") else {
        return;
    };
    let setup = scenario(3, PrecipitationKind::Sleet, 4.0, 5_000);
    let particles = run(&mut vk, &setup, 5, 0.12);
    assert_eq!(particles.len(), 5_000);
    assert!(particles.iter().all(|p| p.position_m.is_finite()));
    let mut weather = setup.weather;
    weather.wind.seed += 1;
    vk.set_weather(&weather).expect("re-bakes the wind");
    vk.step(0.05).expect("valid step");
    let cover = vk.read_cover().expect("cover");
    assert!(cover.totals().deposited_kg > 0.0, "something landed");
    let timings = vk.timings().expect("timings");
    assert!(timings.passes.is_empty() || timings.passes.iter().all(|p| p.milliseconds >= 0.0));
    assert!(matches!(
        vk.step(0.0),
        Err(BackendError::InvalidTimeStep { .. })
    ));
    vk.render(&View {
        camera: setup.camera,
        width_px: 8,
        height_px: 8,
    })
    .expect("renders");
    assert_eq!(vk.read_image().expect("an image").rgba8.len(), 8 * 8 * 4);
    assert_clean(&vk, "during a run");
}

#[test]
fn creating_and_dropping_leaks_nothing() {
    for round in 0..4 {
        let Some(mut vk) = vk("creating_and_dropping_leaks_nothing") else {
            return;
        };
        let log = vk.validation_log();
        let setup = scenario(round, PrecipitationKind::DrySnow, 1.0, 1_000 + 500 * round);
        run(&mut vk, &setup, 2, 0.05);
        // Re-configure: the old configuration's objects are freed.
        run(&mut vk, &setup, 1, 0.05);
        drop(vk);
        assert_log_clean(&log, &format!("round {round}"));
    }
}

#[test]
fn before_configure_calls_are_refused() {
    let Some(mut vk) = vk("before_configure_calls_are_refused") else {
        return;
    };
    assert!(matches!(
        vk.step(0.05),
        Err(BackendError::NotConfigured { .. })
    ));
    assert!(matches!(
        vk.read_particles(),
        Err(BackendError::NotConfigured { .. })
    ));
    let too_many = Setup::over_flat_ground(10.0, 8, 5.0, u32::MAX);
    assert!(matches!(
        vk.configure(&too_many),
        Err(BackendError::CapacityTooLarge { .. })
    ));
    assert_clean(&vk, "refusing bad calls");
}

/// Observed on lavapipe: vk and wgpu particles are bit-identical (0 ULP) — both run
/// naga's SPIR-V of the same WGSL on the same driver. The bound allows a few ULP for
/// drivers that fuse differently.
const MAX_ULPS_VK_WGPU: u32 = 8;

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]

    #[test]
    fn vk_agrees_with_wgpu_within_a_few_ulp_and_with_the_cpu_reference(
        seed in 0u32..1000,
        kind in prop_oneof![Just(PrecipitationKind::DrySnow), Just(PrecipitationKind::Rain), Just(PrecipitationKind::Sleet)],
        wind in 0.0f32..8.0,
        count in 500u32..4000,
        dt in 0.01f32..0.2,
    ) {
        let Some(mut vk) = vk("vk_agrees_with_wgpu") else {
            return Ok(());
        };
        let setup = scenario(seed, kind, wind, count);
        let from_vk = run(&mut vk, &setup, 6, dt);
        let from_cpu = run(&mut CpuBackend::new(), &setup, 6, dt);
        let mut flipped = 0u32;
        // A landing decided one sub-step apart: same generation, age a sub-step off.
        let (_, substep_s) = precip_model::substeps(dt).expect("a valid dt");
        for (a, b) in from_cpu.iter().zip(&from_vk) {
            if a.generation != b.generation || (a.age_s - b.age_s).abs() > 0.5 * substep_s {
                flipped += 1;
                continue;
            }
            prop_assert!((a.position_m - b.position_m).abs().max_element() < 5e-4, "{a:?} vs {b:?}");
            prop_assert!((a.velocity_mps - b.velocity_mps).abs().max_element() < 1e-4, "{a:?} vs {b:?}");
        }
        prop_assert!(f64::from(flipped) <= 1e-3 * f64::from(count), "{flipped} flipped decisions");
        if let Ok(mut wgpu) = WgpuBackend::new() {
            let from_wgpu = run(&mut wgpu, &setup, 6, dt);
            let mut worst = 0;
            for (a, b) in from_wgpu.iter().zip(&from_vk) {
                prop_assert_eq!(a.generation, b.generation);
                for (x, y) in a.position_m.to_array().into_iter().zip(b.position_m.to_array())
                    .chain(a.velocity_mps.to_array().into_iter().zip(b.velocity_mps.to_array()))
                    .chain([(a.water_kg, b.water_kg), (a.age_s, b.age_s)])
                {
                    worst = worst.max(ulps(x, y));
                }
            }
            eprintln!("vk vs wgpu: worst {worst} ULP; vk vs CPU: {flipped} flipped of {count}");
            prop_assert!(worst <= MAX_ULPS_VK_WGPU, "vk vs wgpu: {worst} ULP");
            let (cv, cw) = (vk.read_cover().expect("cover"), wgpu.read_cover().expect("cover"));
            let (tv, tw) = (cv.totals(), cw.totals());
            prop_assert!((tv.deposited_kg - tw.deposited_kg).abs() <= 1e-6 * tv.deposited_kg.max(1.0), "{tv:?} vs {tw:?}");
            prop_assert!(tv.imbalance_kg().abs() <= 1e-3 * tv.deposited_kg.max(1.0), "water not conserved: {tv:?}");
        }
        assert_clean(&vk, "in the equivalence run");
    }
}

#[test]
#[expect(
    unsafe_code,
    reason = "the test plays an engine that owns its Vulkan device"
)]
fn runs_on_a_device_the_caller_owns_and_leaves_it_alive() {
    use ash::vk;
    use precip_gpu_vk::ExternalDevice;
    use precip_gpu_vk::Instance;
    let instance = match Instance::new(true) {
        Ok(i) => i,
        Err(e) => {
            assert!(
                std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
                "{e}"
            );
            eprintln!("SKIPPED runs_on_a_device_the_caller_owns: {e}");
            return;
        }
    };
    // The engine's device: the first physical device, a compute+graphics family.
    // SAFETY: plain queries and creation on a live instance; everything is destroyed
    // below in reverse order.
    let (physical, family, device) = unsafe {
        let physical = instance.raw.enumerate_physical_devices().expect("devices")[0];
        let family = instance
            .raw
            .get_physical_device_queue_family_properties(physical)
            .iter()
            .position(|f| {
                f.queue_flags
                    .contains(vk::QueueFlags::COMPUTE | vk::QueueFlags::GRAPHICS)
            })
            .expect("a family") as u32;
        let priorities = [1.0];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(family)
            .queue_priorities(&priorities)];
        let info = vk::DeviceCreateInfo::default().queue_create_infos(&queues);
        let device = instance
            .raw
            .create_device(physical, &info, None)
            .expect("a device");
        (physical, family, device)
    };
    let external = ExternalDevice {
        entry: instance.entry.clone(),
        instance: instance.raw.clone(),
        physical,
        device: device.clone(),
        queue_family: family,
        queue_index: 0,
    };
    {
        // SAFETY: the objects are live and outlive the backend (dropped in this block).
        let mut backend =
            unsafe { VkBackend::on_external_device(external) }.expect("adopts the device");
        let particles = run(
            &mut backend,
            &scenario(5, PrecipitationKind::DrySnow, 2.0, 2_000),
            3,
            0.05,
        );
        assert_eq!(particles.len(), 2_000);
        // It draws on the engine's device too.
        backend
            .render(&View {
                camera: precip_model::Camera::default(),
                width_px: 48,
                height_px: 32,
            })
            .expect("renders on the engine's device");
        assert_eq!(
            backend.read_image().expect("an image").rgba8.len(),
            48 * 32 * 4
        );
    }
    // The device is still the engine's: it can still be used, then destroyed by it.
    // SAFETY: the backend is gone and freed only its own objects.
    unsafe {
        device.device_wait_idle().expect("the device is alive");
        device.destroy_device(None);
    }
    let messages = instance.take_messages();
    assert!(
        messages.is_empty(),
        "validation layer:\n{}",
        messages.join("\n")
    );
}
