//! The wgpu backend on its own: determinism, the mass link, bad input, timings,
//! and running on a device the caller owns.

use crate::common;

use precip_gpu_wgpu::{GpuDevice, WgpuBackend};
use precip_model::cover::CoverFeed;
use precip_model::{
    Backend, BackendError, CameraVolumeSetup, PrecipitationKind, Setup, TimingSource, Weather,
    WeatherError,
};

fn small() -> Setup {
    let mut setup = Setup::over_flat_ground(30.0, 16, 10.0, 3_000);
    setup.weather = Weather {
        kind: PrecipitationKind::Sleet,
        intensity_mm_per_h: 3.0,
        air_temperature_c: 1.0,
        ..Weather::default()
    };
    setup.cover.time_scale = 300.0;
    setup
}

#[test]
fn the_same_seed_twice_gives_bit_identical_buffers() {
    for (name, mut gpu) in common::gpu_backends("determinism") {
        common::run(&mut gpu, &small(), 30, 0.05);
        let (p1, c1) = (
            gpu.read_particles().expect("ok"),
            gpu.read_cover().expect("ok"),
        );
        common::run(&mut gpu, &small(), 30, 0.05);
        let (p2, c2) = (
            gpu.read_particles().expect("ok"),
            gpu.read_cover().expect("ok"),
        );
        assert_eq!(common::bytes(&p1), common::bytes(&p2), "{name}: particles");
        assert_eq!(
            bytemuck::cast_slice::<_, u8>(&c1.texels),
            bytemuck::cast_slice::<_, u8>(&c2.texels),
            "{name}: cover"
        );
        let mut other = small();
        other.seed += 1;
        common::run(&mut gpu, &other, 30, 0.05);
        assert_ne!(
            common::bytes(&p1),
            common::bytes(&gpu.read_particles().expect("ok")),
            "{name}: seeds"
        );
    }
}

#[test]
fn particles_deposit_the_intensity_on_the_gpu() {
    // As the CPU's mass link test: per m² per hour, the intensity within 5 %.
    let texels = 40u32;
    let border = 6u32;
    let mut setup = Setup::over_flat_ground(40.0, texels, 15.0, 12_000);
    setup.weather = Weather {
        intensity_mm_per_h: 2.0,
        ..Weather::default()
    };
    setup.seed = 17;
    let seconds = 240.0f32;
    for (name, mut gpu) in common::gpu_backends("mass link") {
        common::run(&mut gpu, &setup, (seconds / 0.25) as usize, 0.25);
        let cover = gpu.read_cover().expect("configured");
        let mut sum = 0.0f64;
        let mut n = 0usize;
        for (index, t) in cover.texels.iter().enumerate() {
            let (i, j) = (index as u32 % texels, index as u32 / texels);
            if (border..texels - border).contains(&i) && (border..texels - border).contains(&j) {
                assert_eq!(CoverFeed::from_raw(t.feed), CoverFeed::Particles);
                sum += f64::from(t.deposited_mm);
                n += 1;
            }
        }
        let rate = sum / n as f64 / (f64::from(seconds) / 3600.0);
        println!("{name}: deposited {rate:.4} mm/h for 2 mm/h");
        assert!((rate / 2.0 - 1.0).abs() < 0.05, "{name}: {rate} mm/h");
    }
}

#[test]
fn bad_input_never_reaches_the_gpu_and_changes_nothing() {
    for (name, mut gpu) in common::gpu_backends("bad input") {
        common::run(&mut gpu, &small(), 5, 0.05);
        let before = common::bytes(&gpu.read_particles().expect("ok"));

        let mut absurd = small();
        absurd.camera_volume = Some(CameraVolumeSetup {
            volume: Default::default(),
            particle_count: u32::MAX - 10_000,
        });
        match gpu.configure(&absurd) {
            Err(BackendError::CapacityTooLarge {
                requested,
                max,
                limit,
            }) => {
                assert!(
                    requested > max && limit.contains("storage binding"),
                    "{name}: {limit}"
                );
            }
            other => panic!("{name}: {other:?}"),
        }
        let mut zero = small();
        zero.world_emitter = None;
        assert!(
            matches!(gpu.configure(&zero), Err(BackendError::ZeroCapacity)),
            "{name}"
        );
        let bad_weather = Weather {
            intensity_mm_per_h: f32::NAN,
            ..small().weather
        };
        assert!(matches!(
            gpu.set_weather(&bad_weather),
            Err(BackendError::Weather(WeatherError::OutOfRange { .. }))
        ));
        for dt in [0.0, -1.0, f32::NAN, 2.0] {
            assert!(
                matches!(gpu.step(dt), Err(BackendError::InvalidTimeStep { .. })),
                "{name}: {dt}"
            );
        }
        assert_eq!(
            before,
            common::bytes(&gpu.read_particles().expect("ok")),
            "{name}: state changed"
        );
        // Drawing reads the particles and never changes them.
        gpu.render(&precip_model::View {
            camera: Default::default(),
            width_px: 8,
            height_px: 8,
        })
        .expect("renders");
        assert_eq!(
            before,
            common::bytes(&gpu.read_particles().expect("ok")),
            "{name}: render changed the particles"
        );
    }
}

#[test]
fn timings_come_from_gpu_timestamps_where_the_adapter_has_them() {
    for (name, mut gpu) in common::gpu_backends("timings") {
        common::run(&mut gpu, &small(), 3, 0.1);
        let timings = gpu.timings().expect("ok");
        println!("{name}: {timings:?}");
        if gpu.device().has_timestamps() {
            assert_eq!(timings.source, TimingSource::GpuTimestamps);
            // One entry a kernel the step dispatched (an idle feature's are not).
            let activity = precip_model::host::Activity::default().after(&small().weather);
            let mut dispatched: Vec<&str> = precip_gpu::recipe::SUBSTEP_PASSES
                .iter()
                .filter(|p| p.when.holds(activity))
                .map(|p| p.entry_point)
                .collect();
            dispatched.sort_unstable();
            dispatched.dedup();
            assert_eq!(timings.passes.len(), dispatched.len(), "one entry a kernel");
            assert!(
                timings
                    .passes
                    .iter()
                    .all(|p| p.milliseconds > 0.0 && p.milliseconds < 10_000.0),
                "{name}"
            );
        } else {
            assert_eq!(timings.source, TimingSource::Unavailable);
        }
    }
}

#[test]
fn runs_on_a_device_the_caller_owns() {
    for (name, owned) in common::gpu_backends("caller's device") {
        let device = owned.device();
        let shared = GpuDevice::from_existing(
            device.device.clone(),
            device.queue.clone(),
            device.info.clone(),
        );
        let mut backend =
            WgpuBackend::with_device(shared).expect("the shared device compiles the kernels");
        common::run(&mut backend, &small(), 4, 0.05);
        assert_eq!(backend.read_particles().expect("ok").len(), 3_000, "{name}");
        assert!(backend.info().device.contains(&device.info.name));
    }
}

/// Every adapter, for a test that opens its own devices; none (a skip, or a
/// failure under PRECIP_REQUIRE_GPU=1, with its reason) where there is none.
fn adapters_for(test: &str) -> Vec<wgpu::Adapter> {
    let found = precip_gpu_wgpu::adapters();
    if found.is_empty() {
        assert!(common::gpu_backends(test).is_empty());
    }
    found
}

/// A device opened on `adapter` with `limits` (and its timestamps), as an
/// engine opens its own.
fn an_engine_s_device(adapter: &wgpu::Adapter, limits: wgpu::Limits) -> GpuDevice {
    let info = adapter.get_info();
    let descriptor = wgpu::DeviceDescriptor {
        label: Some("an engine's device"),
        required_features: adapter.features()
            & (wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES),
        required_limits: limits,
        ..Default::default()
    };
    let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
        .unwrap_or_else(|e| panic!("{}: an engine's device: {e}", info.name));
    GpuDevice::from_existing(device, queue, info)
}

/// An engine may hand precip a device opened with WebGPU's default limits (8
/// storage buffers a shader stage, 4 bind groups…), not the adapter's larger ones
/// precip asks for on its own: every kernel and every draw pipeline (made at the
/// first frame, whatever the scene) fits them, and a frame is drawn.
#[test]
fn runs_on_a_device_opened_with_webgpu_s_default_limits() {
    for adapter in &adapters_for("WebGPU's default limits") {
        let info = adapter.get_info();
        let shared = an_engine_s_device(adapter, wgpu::Limits::default());
        let mut backend = WgpuBackend::with_device(shared).unwrap_or_else(|e| {
            panic!("{}: the kernels within the default limits: {e}", info.name)
        });
        common::run(&mut backend, &small(), 2, 0.05);
        let view = precip_model::View {
            camera: precip_model::Camera::default(),
            width_px: 64,
            height_px: 48,
        };
        backend
            .render(&view)
            .unwrap_or_else(|e| panic!("{}: a frame within the default limits: {e}", info.name));
        let image = backend.read_image().expect("the frame reads back");
        assert_eq!((image.width_px, image.height_px), (64, 48), "{}", info.name);
    }
}

/// A device the caller opened with fewer storage buffers a stage than precip's
/// passes bind is refused with a typed error that names the limit, not a panic
/// inside wgpu.
#[test]
fn a_device_below_the_needed_limits_is_refused_with_a_typed_error() {
    for adapter in &adapters_for("too small limits") {
        let info = adapter.get_info();
        let shared = an_engine_s_device(
            adapter,
            wgpu::Limits {
                max_storage_buffers_per_shader_stage: 7,
                ..wgpu::Limits::default()
            },
        );
        let view = precip_model::View {
            camera: precip_model::Camera::default(),
            width_px: 64,
            height_px: 48,
        };
        let error = WgpuBackend::with_device(shared)
            .and_then(|mut backend| {
                backend.configure(&small())?;
                backend.step(0.05)?;
                backend.render(&view)
            })
            .expect_err("a device one storage buffer short is refused");
        let message = error.to_string();
        assert!(
            message.contains("max_storage_buffers_per_shader_stage is 7"),
            "{}: {message}",
            info.name
        );
    }
}
