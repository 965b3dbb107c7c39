//! Resting particles (precip_model::particles::step, "Resting particles"): at 0 mm/h
//! nothing moves and nothing lands; when the weather comes back after the camera
//! flew on, the camera volume's particles wake inside its box, and the water
//! reaches the cover at the weather's rate again.

use crate::common;

use glam::Vec3;
use precip_model::backend::setup::CameraVolumeSetup;
use precip_model::{Backend, Camera, CameraVolume, Particle, PrecipitationKind, Setup, Weather};

fn setup() -> Setup {
    let mut setup = Setup::over_flat_ground(40.0, 20, 15.0, 4_000);
    setup.weather = Weather {
        kind: PrecipitationKind::Rain,
        intensity_mm_per_h: 0.0,
        air_temperature_c: 10.0,
        ..Weather::default()
    };
    if let Some(e) = setup.world_emitter.as_mut() {
        e.particle_count = 2_000;
    }
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume {
            half_extent_m: Vec3::new(8.0, 6.0, 8.0),
            ..CameraVolume::default()
        },
        particle_count: 2_000,
    });
    setup
}

#[test]
fn at_zero_mm_per_hour_nothing_moves_and_rain_wakes_the_camera_volume_in_its_box() {
    let setup = setup();
    let mut backend = common::configured(&setup);
    let before = common::particle_bytes(&mut backend);
    common::run(&mut backend, 20, 0.05);
    assert_eq!(
        common::particle_bytes(&mut backend),
        before,
        "nothing moves at 0 mm/h"
    );

    // The camera flies 300 m away and climbs 200 m while nothing falls.
    let far = Vec3::new(300.0, 201.7, -40.0);
    backend
        .set_camera(&Camera {
            position_m: far,
            ..setup.camera
        })
        .expect("valid camera");
    common::run(&mut backend, 10, 0.05);
    assert_eq!(
        common::particle_bytes(&mut backend),
        before,
        "still nothing moves"
    );

    // Rain: the camera volume's particles wake and wrap into the box around the
    // camera within a step.
    backend
        .set_weather(&Weather {
            intensity_mm_per_h: 4.0,
            ..setup.weather
        })
        .expect("valid weather");
    common::run(&mut backend, 1, 0.05);
    let particles: Vec<Particle> = backend.read_particles().expect("configured");
    assert_eq!(
        in_the_box(&particles[2_000..], far),
        2_000,
        "woken below: in the box"
    );
    assert!(
        particles[..2_000]
            .iter()
            .zip(bytemuck::cast_slice::<u8, Particle>(&before))
            .all(|(a, b)| a != b),
        "every sky particle moved"
    );

    // Dry again; the camera comes down 200 m, so the resting particles hang far
    // above it; rain wakes them into the box again (they wrap by whole heights).
    let dry = setup.weather;
    backend.set_weather(&dry).expect("valid weather");
    backend.set_camera(&setup.camera).expect("valid camera");
    common::run(&mut backend, 3, 0.05);
    backend
        .set_weather(&Weather {
            intensity_mm_per_h: 4.0,
            ..dry
        })
        .expect("valid weather");
    common::run(&mut backend, 1, 0.05);
    let particles: Vec<Particle> = backend.read_particles().expect("configured");
    assert_eq!(
        in_the_box(&particles[2_000..], setup.camera.position_m),
        2_000,
        "woken above: in the box"
    );
}

/// How many of `particles` lie in the 16 × 12 × 16 m box centred at `centre_m`.
fn in_the_box(particles: &[Particle], centre_m: Vec3) -> usize {
    particles
        .iter()
        .filter(|p| {
            ((p.position_m - centre_m).abs() - Vec3::new(8.0, 6.0, 8.0)).max_element() <= 0.01
        })
        .count()
}
