//! The cover grid follows a camera flying over a terrain (issue 29's cover at any
//! scale), alike on every backend: flown 400 m away and back over a small grid in
//! steady snow, the grid moves with the camera and comes back over its start, the
//! cover that left it is kept beyond it and lent back, nothing is created or lost
//! (the books of the grid and the cover beyond it close over the whole terrain),
//! and the CPU reference and the GPU backends hold the same cover.

use std::sync::Arc;

use glam::{IVec2, UVec2, Vec2, Vec3};
use precip_conformance::all_subjects;
use precip_model::backend::setup::CameraVolumeSetup;
use precip_model::cover::{CoverGrid, CoverTotals, GridFrame};
use precip_model::scene::builtin::house_on_plane;
use precip_model::scene::terrain::Terrain;
use precip_model::{Camera, CameraVolume, GroundMap, Setup, Weather};

/// Snow, mm of water an hour.
const RATE_MM_PER_H: f32 = 2.0;
/// Cover seconds per simulated second: an hour of cover a second.
const TIME_SCALE: f32 = 3_600.0;
const DT_S: f32 = 0.05;
/// Steps out, and as many back.
const STEPS_OUT: u32 = 20;
/// The camera's flight a step, m (400 m out).
const STEP_M: f32 = 20.0;

/// The house on a 2 km square of gently rolling land, a 64 m grid of 2 m cover
/// texels round it that follows the camera, snowing at −5 °C in calm air, the
/// cover fed by the weather's rate everywhere (no world emitter), a few
/// particles round the camera.
fn flight() -> Setup {
    let (n, spacing) = (201u32, 10.0f32);
    let half = 0.5 * (n - 1) as f32 * spacing;
    let heights = (0..n * n)
        .map(|k| {
            let (x, z) = (
                (k % n) as f32 * spacing - half,
                (k / n) as f32 * spacing - half,
            );
            -0.5 + 3.0 * (x / 170.0).sin() * (z / 230.0).cos()
        })
        .collect();
    let terrain = Terrain::new(UVec2::splat(n), spacing, Vec2::ZERO, heights).expect("a terrain");
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, 2_000).expect("valid");
    let scene = setup.scene.take().expect("a scene");
    let scene = Arc::unwrap_or_clone(scene).on_terrain(Arc::new(terrain));
    let ground = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(64));
    setup.ground = GroundMap::of_prepared(&scene, ground);
    setup.scene = Some(Arc::new(scene));
    setup.cover.frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(32));
    setup.cover.follows_camera = true;
    setup.cover.time_scale = TIME_SCALE;
    setup.world_emitter = None;
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume {
            half_extent_m: Vec3::splat(5.0),
            ..CameraVolume::default()
        },
        particle_count: 500,
    });
    setup.weather = Weather {
        intensity_mm_per_h: RATE_MM_PER_H,
        air_temperature_c: -5.0,
        ..Weather::default()
    };
    setup.camera = Camera {
        position_m: Vec3::new(0.0, 50.0, 0.0),
        forward: Vec3::new(1.0, -0.5, 0.0),
        ..Camera::default()
    };
    setup
}

/// What a backend holds after the flight.
struct Flown {
    name: String,
    cover: CoverGrid,
    far: CoverTotals,
    shift: IVec2,
    moves: u32,
    farthest_shift: IVec2,
}

fn fly(subject: &mut precip_conformance::Subject, setup: &Setup) -> Flown {
    let backend = &mut subject.backend;
    backend.configure(setup).expect("configures");
    let mut camera = setup.camera;
    let mut farthest_shift = IVec2::ZERO;
    for k in 0..2 * STEPS_OUT {
        camera.position_m.x += if k < STEPS_OUT { STEP_M } else { -STEP_M };
        backend.set_camera(&camera).expect("a camera");
        backend.step(DT_S).expect("steps");
        let window = backend.cover_window().expect("configured");
        if window.shift().x > farthest_shift.x {
            farthest_shift = window.shift();
        }
    }
    // Back where it began: a step more lets the grid follow the last move.
    backend.step(DT_S).expect("steps");
    let window = backend.cover_window().expect("configured");
    Flown {
        name: subject.name.clone(),
        cover: backend.read_cover().expect("the cover"),
        far: backend.far_cover_totals().expect("a terrain's far cover"),
        shift: window.shift(),
        moves: window.moves(),
        farthest_shift,
    }
}

#[test]
fn the_cover_grid_follows_the_camera_and_keeps_the_books_on_every_backend() {
    let setup = flight();
    let steps = 2 * STEPS_OUT + 1;
    let hours = f64::from(steps) * f64::from(DT_S * TIME_SCALE) / 3_600.0;
    let fallen_mm = f64::from(RATE_MM_PER_H) * hours;
    let mut flown = Vec::new();
    for mut subject in all_subjects("the_cover_grid_follows_the_camera_and_keeps_the_books") {
        let f = fly(&mut subject, &setup);
        subject.check_clean("moving the cover grid");
        let grid = f.cover.totals();
        let whole_deposited = grid.deposited_kg + f.far.deposited_kg;
        let whole_imbalance = grid.imbalance_kg() + f.far.imbalance_kg();
        let swe: Vec<f32> = f.cover.texels.iter().map(|t| t.swe_mm).collect();
        let least = swe.iter().copied().fold(f32::INFINITY, f32::min);
        let mean = swe.iter().map(|&s| f64::from(s)).sum::<f64>() / swe.len() as f64;
        println!(
            "{}: {} moves (farthest {:?} texels), back at {:?}; the grid's mean SWE {mean:.3} mm (least {least:.3}) of {fallen_mm:.3} mm fallen; the whole terrain: {whole_deposited:.0} kg landed, imbalance {whole_imbalance:.2e} kg",
            f.name, f.moves, f.farthest_shift, f.shift
        );
        assert!(
            f.moves >= 10,
            "{}: the grid moved {} times",
            f.name,
            f.moves
        );
        assert!(
            f.farthest_shift.x >= 160,
            "{}: the grid went only {:?} texels out with the camera",
            f.name,
            f.farthest_shift
        );
        // Back over its start, the camera within a quarter of the grid's side of
        // its centre (a tile at most away), its frame the configured one moved by
        // whole texels, bit for bit.
        assert!(
            f.shift.abs().max_element() <= precip_model::host::MOVE_STEP_TEXELS,
            "{}: the grid is not back ({:?})",
            f.name,
            f.shift
        );
        assert_eq!(
            f.cover.frame,
            setup.cover.frame.moved_by_texels(f.shift),
            "{}: the grid came back elsewhere",
            f.name
        );
        // Nothing created or lost over the whole terrain (its 4 km² hold ~10⁷ kg).
        assert!(
            whole_imbalance.abs() < 1.0e-5 * whole_deposited,
            "{}: the whole terrain's books are off by {whole_imbalance} kg of {whole_deposited}",
            f.name
        );
        // The snow that fell on the land the grid left and came back to is there:
        // every texel holds the steady fall (the far cells step every fourth step,
        // so a lent texel may lag them by up to three steps' snow).
        let lag = 3.0 / f64::from(steps);
        assert!(
            (mean - fallen_mm).abs() < (lag + 0.02) * fallen_mm,
            "{}: the grid holds {mean} mm of SWE where {fallen_mm} mm fell",
            f.name
        );
        assert!(
            f64::from(least) > (1.0 - lag - 0.05) * fallen_mm,
            "{}: a texel holds {least} mm of SWE where {fallen_mm} mm fell",
            f.name
        );
        flown.push(f);
    }
    // The backends agree texel by texel.
    let (reference, others) = flown.split_first().expect("the CPU reference");
    for other in others {
        let worst = reference
            .cover
            .texels
            .iter()
            .zip(&other.cover.texels)
            .map(|(a, b)| (a.swe_mm - b.swe_mm).abs())
            .fold(0.0f32, f32::max);
        println!(
            "{} against {}: SWE differs by {worst:.2e} mm at most",
            other.name, reference.name
        );
        assert_eq!(other.moves, reference.moves, "{}", other.name);
        assert!(
            f64::from(worst) < 1.0e-3 * fallen_mm,
            "{}: a texel's SWE differs from the CPU's by {worst} mm",
            other.name
        );
        assert!(
            (other.far.swe_kg - reference.far.swe_kg).abs() < 1.0e-5 * reference.far.swe_kg,
            "{}: the cover beyond the grid differs ({} kg against {})",
            other.name,
            other.far.swe_kg,
            reference.far.swe_kg
        );
    }
}
