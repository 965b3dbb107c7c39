//! Bad input gives the typed error and leaves the backend as it was.

use crate::common;

use precip_model::wind::WindField;
use precip_model::{
    Backend, BackendError, Camera, CameraVolumeSetup, CpuBackend, Setup, View, Weather,
    WeatherError,
};

fn setup() -> Setup {
    Setup::over_flat_ground(20.0, 10, 8.0, 500)
}

/// Runs `f` (which must fail) on one backend and nothing on a twin, steps both, and
/// requires identical state: the failed call changed nothing.
fn unchanged_after(f: impl FnOnce(&mut CpuBackend) -> Result<(), BackendError>) -> BackendError {
    let mut tried = common::configured(&setup());
    let mut twin = common::configured(&setup());
    common::run(&mut tried, 3, 0.05);
    common::run(&mut twin, 3, 0.05);
    let err = f(&mut tried).expect_err("must be refused");
    common::run(&mut tried, 5, 0.05);
    common::run(&mut twin, 5, 0.05);
    assert_eq!(
        common::particle_bytes(&mut tried),
        common::particle_bytes(&mut twin),
        "{err}"
    );
    assert_eq!(
        common::cover_bytes(&mut tried),
        common::cover_bytes(&mut twin),
        "{err}"
    );
    err
}

#[test]
fn each_invalid_weather_field_is_refused_by_name() {
    let base = Weather {
        intensity_mm_per_h: 1.5,
        ..Weather::default()
    };
    let cases: Vec<(Weather, &str)> = vec![
        (
            Weather {
                intensity_mm_per_h: f32::NAN,
                ..base
            },
            "intensity_mm_per_h",
        ),
        (
            Weather {
                intensity_mm_per_h: -0.5,
                ..base
            },
            "intensity_mm_per_h",
        ),
        (
            Weather {
                intensity_mm_per_h: 5000.0,
                ..base
            },
            "intensity_mm_per_h",
        ),
        (
            Weather {
                air_temperature_c: f32::NEG_INFINITY,
                ..base
            },
            "air_temperature_c",
        ),
        (
            Weather {
                air_temperature_c: 120.0,
                ..base
            },
            "air_temperature_c",
        ),
    ];
    for (weather, field) in cases {
        let err = unchanged_after(|b| b.set_weather(&weather));
        match err {
            BackendError::Weather(WeatherError::OutOfRange { field: f, .. }) => {
                assert_eq!(f, field)
            }
            other => panic!("{field}: {other}"),
        }
    }
    let too_warm_for_snow = Weather {
        air_temperature_c: 20.0,
        ..base
    };
    let err = unchanged_after(|b| b.set_weather(&too_warm_for_snow));
    assert!(
        matches!(
            err,
            BackendError::Weather(WeatherError::KindTemperature { .. })
        ),
        "{err}"
    );
    let bad_wind = Weather {
        wind: WindField {
            octaves: 99,
            ..WindField::calm()
        },
        ..base
    };
    let err = unchanged_after(|b| b.set_weather(&bad_wind));
    assert!(
        matches!(err, BackendError::Weather(WeatherError::Wind(_))),
        "{err}"
    );
    assert!(err.to_string().contains("octaves"), "{err}");
}

#[test]
fn invalid_time_steps_are_refused() {
    for dt in [0.0, -0.01, f32::NAN, f32::INFINITY, 1.5] {
        let err = unchanged_after(|b| b.step(dt));
        assert!(
            matches!(err, BackendError::InvalidTimeStep { .. }),
            "{dt}: {err}"
        );
    }
}

#[test]
fn zero_and_absurd_capacities_are_refused_and_the_old_configuration_stays() {
    let mut zero = setup();
    zero.world_emitter = None;
    let err = unchanged_after(|b| b.configure(&zero));
    assert!(matches!(err, BackendError::ZeroCapacity), "{err}");

    let mut absurd = setup();
    absurd.camera_volume = Some(CameraVolumeSetup {
        volume: Default::default(),
        particle_count: u32::MAX,
    });
    let err = unchanged_after(|b| b.configure(&absurd));
    match err {
        BackendError::CapacityTooLarge { requested, max, .. } => assert!(requested > max),
        other => panic!("{other}"),
    }
}

#[test]
fn other_invalid_setups_name_their_field() {
    let mut bad_ground = setup();
    bad_ground.ground.height_m[3] = f32::NAN;
    let err = unchanged_after(|b| b.configure(&bad_ground));
    assert!(err.to_string().contains("ground.height_m"), "{err}");

    let mut bad_scale = setup();
    bad_scale.cover.time_scale = -1.0;
    let err = unchanged_after(|b| b.configure(&bad_scale));
    assert!(err.to_string().contains("cover.time_scale"), "{err}");

    let bad_camera = Camera {
        near_m: 0.0,
        ..Camera::default()
    };
    let err = unchanged_after(|b| b.set_camera(&bad_camera));
    assert!(matches!(err, BackendError::InvalidCamera(_)), "{err}");
}

#[test]
fn the_cpu_backend_does_not_render_and_says_so() {
    let mut backend = common::configured(&setup());
    let view = View {
        camera: Camera::default(),
        width_px: 64,
        height_px: 64,
    };
    assert!(matches!(
        backend.render(&view),
        Err(BackendError::NotSupported { backend: "cpu", .. })
    ));
    assert!(matches!(
        backend.read_image(),
        Err(BackendError::NotSupported { .. })
    ));
    let mut fresh = CpuBackend::new();
    assert!(matches!(
        fresh.step(0.01),
        Err(BackendError::NotConfigured { .. })
    ));
    assert!(!fresh.info().renders);
}
