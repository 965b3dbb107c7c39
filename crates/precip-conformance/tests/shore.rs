//! The shore's kernels (render_shore.wgsl: the shallow-water equations over the
//! shore's grid, two Heun steps a frame) give on every GPU backend the water of
//! the CPU reference, `precip_sea::Shore` over the same bathymetry with the same
//! edges, incoming waves, speed cap and steps
//! (`precip_model::drawing::shore::ShoreGrid::reference`); a calm sea over the same
//! beach stays at rest to round-off (well-balanced), and the sea's waves do come in.

use glam::Vec3;
use precip_conformance::each_gpu_backend;
use precip_model::cover::Surface;
use precip_model::drawing::shore::{ShoreEdge, ShoreFrames, ShoreGrid, ShoreGridState};
use precip_model::{Backend, Mesh, Scene, Setup, View, Weather};

/// Frames drawn and the simulated time between two, s (under two of the shore's
/// stable steps, so its clock keeps up with the frames').
const FRAMES: u32 = 60;
const FRAME_S: f32 = 0.04;

/// A mesh over the grid `xs × zs` at heights `y(x)`, faces up.
fn height_grid(name: &str, xs: &[f32], zs: &[f32], y: impl Fn(f32) -> f32) -> Mesh {
    let mut positions_m = Vec::new();
    for &z in zs {
        for &x in xs {
            positions_m.push(Vec3::new(x, y(x), z));
        }
    }
    let w = xs.len() as u32;
    let mut indices = Vec::new();
    for j in 0..zs.len() as u32 - 1 {
        for i in 0..w - 1 {
            let (p00, p10, p01, p11) = (
                j * w + i,
                j * w + i + 1,
                (j + 1) * w + i,
                (j + 1) * w + i + 1,
            );
            indices.extend_from_slice(&[p00, p11, p10, p00, p01, p11]);
        }
    }
    Mesh {
        name: name.into(),
        positions_m,
        indices,
        ..Mesh::default()
    }
}

/// A beach sloping 1 : 14 from 5 m under the sea's level to 3 m over it, the sea
/// over it and out to the west, a `wind_mps` wind blowing onshore (+x).
fn beach(wind_mps: f32) -> Setup {
    let zs: Vec<f32> = (0..=8).map(|j| -40.0 + 10.0 * j as f32).collect();
    let beach_xs: Vec<f32> = (0..=28).map(|i| -80.0 + 4.0 * i as f32).collect();
    let sand = Mesh {
        surface: Some(Surface::Sand),
        ..height_grid("beach", &beach_xs, &zs, |x| -5.0 + (x + 80.0) / 14.0)
    };
    let sea_xs: Vec<f32> = (0..=20).map(|i| -160.0 + 10.0 * i as f32).collect();
    let sea = Mesh {
        surface: Some(Surface::Water),
        sea: true,
        ..height_grid("sea", &sea_xs, &zs, |_| 0.0)
    };
    let (mut setup, _) = Setup::over_scene(
        Scene {
            meshes: vec![sea, sand],
        },
        64,
        20.0,
        1_000,
    )
    .expect("a valid scene");
    setup.weather = Weather {
        kind: precip_model::PrecipitationKind::Rain,
        intensity_mm_per_h: 0.5,
        air_temperature_c: 10.0,
        ..Weather::default()
    };
    setup.weather.wind.mean_wind_mps = Vec3::new(wind_mps, 0.0, 0.0);
    setup
}

/// Draws the frames on `backend` and steps the reference alongside; the worst
/// difference of the surface, m, and of the discharges, m²/s, and how far the
/// surface rose anywhere, m.
fn run<B: Backend>(
    name: &str,
    backend: &mut B,
    setup: &Setup,
    read: impl Fn(&mut B) -> Option<ShoreGridState>,
) -> (f32, f32, f32) {
    let scene = setup.scene.as_ref().expect("a scene");
    let grid = ShoreGrid::of_scene(scene).expect("the beach has a shore");
    assert_eq!(
        grid.edges,
        [
            ShoreEdge::Incoming,
            ShoreEdge::Wall,
            ShoreEdge::Open,
            ShoreEdge::Open
        ],
        "{name}"
    );
    let w = setup.weather.wind.mean_wind_mps;
    let waves = grid.incoming_waves(&setup.render.sea.state([w.x, w.z]));
    let (cap, _) = grid.step_bounds(&waves);
    // The host's side of the shore, as the renderer runs it: its water spun up by
    // the reference.
    let mut frames =
        ShoreFrames::new(grid.clone(), &setup.render.sea, [w.x, w.z]).expect("spins up");
    let mut reference = frames.spun_up().clone();
    backend.configure(setup).expect("configures");
    let mut camera = setup.camera;
    camera.position_m = Vec3::new(40.0, 6.0, 0.0);
    camera.forward = Vec3::new(-1.0, -0.15, 0.0);
    let view = View {
        camera,
        width_px: 64,
        height_px: 48,
    };
    for frame in 1..=FRAMES {
        backend.step(FRAME_S).expect("steps");
        let shore = frames.next_frame(
            &setup.render.sea,
            [w.x, w.z],
            f64::from(frame) * f64::from(FRAME_S),
        );
        assert_eq!(shore.speed_cap_mps.to_bits(), cap.to_bits());
        assert!(
            (shore.steps.start_s - reference.time_s()).abs() < 1e-6,
            "{name}: the shore's clock keeps up"
        );
        for _ in 0..shore.count {
            if shore.steps.dt_s > 0.0 {
                reference.step(shore.steps.dt_s).expect("a stable step");
            }
        }
        backend.render(&view).expect("renders");
    }
    let got = read(backend).expect("a frame stepped the shore");
    assert_eq!(got.grid, grid, "{name}: the same grid");
    let want = reference.state();
    let b = &grid.bathymetry;
    let (mut surface, mut discharge, mut rise) = (0.0f32, 0.0f32, 0.0f32);
    for k in 0..grid.cells() {
        let (h, hw) = (got.state.depth_m[k], want.depth_m[k]);
        assert!(h.is_finite() && h >= 0.0, "{name}: cell {k} depth {h}");
        surface = surface.max((h - hw).abs());
        discharge = discharge
            .max((got.state.discharge_x_m2ps[k] - want.discharge_x_m2ps[k]).abs())
            .max((got.state.discharge_y_m2ps[k] - want.discharge_y_m2ps[k]).abs());
        if h > 0.0 {
            rise = rise.max((h + b.bed_m[k] - grid.still_level_m).abs());
        }
    }
    println!(
        "{name}: {} × {} cells of {} m, {FRAMES} frames: surface within {surface:.2e} m, discharge within {discharge:.2e} m²/s of the reference; the surface moved up to {rise:.3} m",
        b.nx, b.ny, b.cell_m
    );
    (surface, discharge, rise)
}

fn check<B: Backend>(name: &str, backend: &mut B, read: impl Fn(&mut B) -> Option<ShoreGridState>) {
    // A gale's waves come in and run up the beach: the same water as the CPU's.
    let (surface, discharge, rise) = run(name, backend, &beach(16.0), &read);
    assert!(rise > 0.05, "{name}: the waves came in ({rise} m)");
    assert!(surface < 2e-3, "{name}: surface off by {surface} m");
    assert!(
        discharge < 5e-3,
        "{name}: discharge off by {discharge} m²/s"
    );
    // A calm sea over the slope stays flat: exactly on lavapipe; an NVIDIA H100,
    // which fuses multiplies and adds, leaves discharges of 1.0e-5 m²/s where the
    // bed's source and the faces' pressures no longer cancel to the bit (a
    // current of 2 µm/s over 5 m of water), the surface still exact.
    let (surface, discharge, rise) = run(name, backend, &beach(0.0), &read);
    assert!(rise < 1e-5, "{name}: a calm sea moved {rise} m");
    assert!(
        surface < 1e-5 && discharge < 1e-4,
        "{name}: surface {surface} m, discharge {discharge} m²/s"
    );
}

#[test]
fn the_shore_s_kernels_step_the_reference_s_water_on_every_gpu_backend() {
    each_gpu_backend(
        "the shore's kernels",
        |name, b| check(name, b, |b| b.read_shore().expect("reads")),
        |name, b| check(name, b, |b| b.read_shore().expect("reads")),
    );
}
