//! A camera flown fast keeps its volume full, alike on every backend (issue 29's
//! fast cameras): the camera volume's particles wrap through its box's sides as the
//! box follows the camera (docs/model.md (1.8)), so at 70 m/s 300 m above the ground
//! none is left behind in a wake and none is re-born in a burst ahead.

use glam::Vec3;
use precip_conformance::all_subjects;
use precip_model::backend::setup::CameraVolumeSetup;
use precip_model::{CameraVolume, ParticleSource, Setup, Weather};

const HALF_M: Vec3 = Vec3::new(8.0, 6.0, 8.0);

fn flight() -> Setup {
    let mut s = Setup::over_flat_ground(200.0, 32, 15.0, 1_000);
    s.seed = 9;
    s.weather = Weather {
        intensity_mm_per_h: 2.0,
        air_temperature_c: -5.0,
        ..Weather::default()
    };
    s.camera.position_m = Vec3::new(-50.0, 300.0, 0.0);
    s.camera.forward = Vec3::X;
    s.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume {
            half_extent_m: HALF_M,
            ..CameraVolume::default()
        },
        particle_count: 4_000,
    });
    s
}

/// Over `steps` of 0.05 s with the camera moving `speed_mps` along +x: the least
/// share of the camera volume's particles inside the box around the camera, and the
/// re-births a step (a particle's generation moving on).
fn fly(subject: &mut precip_conformance::Subject, speed_mps: f32, steps: u32) -> (f32, f32) {
    let setup = flight();
    let backend = &mut subject.backend;
    backend.configure(&setup).expect("valid");
    let mut camera = setup.camera;
    let mut before = backend.read_particles().expect("particles");
    let (mut least, mut reborn) = (1.0f32, 0.0f32);
    for _ in 0..steps {
        camera.position_m.x += speed_mps * 0.05;
        backend.set_camera(&camera).expect("valid camera");
        backend.step(0.05).expect("steps");
        let now = backend.read_particles().expect("particles");
        let ours: Vec<_> = now
            .iter()
            .zip(&before)
            .filter(|(p, _)| p.source() == ParticleSource::CameraVolume)
            .collect();
        let inside = ours
            .iter()
            .filter(|(p, _)| {
                let d = (p.position_m - camera.position_m).abs();
                d.cmple(HALF_M + Vec3::splat(0.5)).all()
            })
            .count();
        least = least.min(inside as f32 / ours.len() as f32);
        reborn += ours
            .iter()
            .filter(|(p, b)| p.generation != b.generation)
            .count() as f32;
        before = now;
    }
    (least, reborn / steps as f32)
}

#[test]
fn a_camera_flown_at_70_m_per_s_keeps_its_volume_full_on_every_backend() {
    for mut subject in all_subjects("a_camera_flown_at_70_m_per_s") {
        let (still_inside, still_reborn) = fly(&mut subject, 0.0, 30);
        let (fast_inside, fast_reborn) = fly(&mut subject, 70.0, 30);
        println!(
            "{}: inside the box {still_inside:.4} still, {fast_inside:.4} at 70 m/s; re-born a step {still_reborn:.1} still, {fast_reborn:.1} at 70 m/s",
            subject.name
        );
        assert!(
            still_inside > 0.99 && fast_inside > 0.99,
            "{}: a wake",
            subject.name
        );
        assert!(
            fast_reborn <= 1.5 * still_reborn + 5.0,
            "{}: a burst of newborns ({fast_reborn} against {still_reborn})",
            subject.name
        );
        subject.check_clean("flying fast");
    }
}
