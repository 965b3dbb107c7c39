//! The open sea's kernels (render_ocean.wgsl: the spectra at the frame's time, the
//! inverse FFT in workgroup memory, the atlases) give on every GPU backend the
//! surfaces of the CPU reference, `precip_sea::ocean::SeaState::cascade(c)
//! .surface_at(t, λ)`, for every cascade and both spectra (JONSWAP, Phillips), to
//! half precision; and the atlases' border
//! texels wrap, so a bilinear read tiles without a seam.

use glam::Vec3;
use precip_conformance::each_gpu_backend;
use precip_model::cover::Surface;
use precip_model::{Backend, Mesh, Scene, Setup, View, Weather};
use precip_sea::ocean::{OCEAN_CASCADES, OCEAN_N, SeaSpectrum};

/// A square of sea 120 m wide beside a strip of beach, in a 15 m/s wind.
fn coast(wind_mps: Vec3) -> Setup {
    let square = |name: &str, x0: f32, x1: f32, y: f32| Mesh {
        name: name.into(),
        positions_m: vec![
            Vec3::new(x0, y, -60.0),
            Vec3::new(x1, y, -60.0),
            Vec3::new(x1, y, 60.0),
            Vec3::new(x0, y, 60.0),
        ],
        indices: vec![0, 2, 1, 0, 3, 2],
        ..Mesh::default()
    };
    let sea = Mesh {
        surface: Some(Surface::Water),
        sea: true,
        ..square("sea", -60.0, 40.0, 0.0)
    };
    let beach = Mesh {
        surface: Some(Surface::Sand),
        ..square("beach", 40.0, 60.0, 0.5)
    };
    let (mut setup, _) = Setup::over_scene(
        Scene {
            meshes: vec![sea, beach],
        },
        64,
        20.0,
        1_000,
    )
    .expect("a valid scene");
    setup.weather = Weather {
        kind: precip_model::PrecipitationKind::Rain,
        intensity_mm_per_h: 1.0,
        air_temperature_c: 8.0,
        ..Weather::default()
    };
    setup.weather.wind.mean_wind_mps = wind_mps;
    setup
}

/// The atlases' texels against the reference at `time_s`: the largest error of
/// each field over a cascade, as a share of the field's RMS there.
fn compare(name: &str, setup: &Setup, atlases: &[Vec<[f32; 4]>; 2], time_s: f32) {
    let w = setup.weather.wind.mean_wind_mps;
    let state = setup.render.sea.state([w.x, w.z]);
    let side = OCEAN_N + 2;
    let width = OCEAN_CASCADES * side;
    assert_eq!(atlases[0].len(), width * side, "{name}");
    for c in 0..OCEAN_CASCADES {
        let reference = state
            .cascade(c)
            .expect("a cascade")
            .surface_at(time_s, state.choppiness);
        let lambda = state.choppiness;
        let fields: [(&str, usize, usize, Vec<f32>); 6] = [
            (
                "λ·Dx",
                0,
                0,
                reference
                    .displacement_x_m
                    .iter()
                    .map(|d| lambda * d)
                    .collect(),
            ),
            ("h", 0, 1, reference.height_m.clone()),
            (
                "λ·Dz",
                0,
                2,
                reference
                    .displacement_z_m
                    .iter()
                    .map(|d| lambda * d)
                    .collect(),
            ),
            ("∂h/∂x", 1, 0, reference.slope_x.clone()),
            ("∂h/∂z", 1, 1, reference.slope_z.clone()),
            (
                "J − 1",
                1,
                2,
                reference.jacobian.iter().map(|j| j - 1.0).collect(),
            ),
        ];
        for (field, atlas, channel, want) in fields {
            let rms = (want.iter().map(|v| v * v).sum::<f32>() / want.len() as f32).sqrt();
            assert!(rms > 0.0, "{name}: cascade {c} {field} is flat");
            let mut worst = 0.0f32;
            for z in 0..OCEAN_N {
                for x in 0..OCEAN_N {
                    let texel = &atlases[atlas][(z + 1) * width + c * side + x + 1];
                    let got = texel[channel] - if field == "J − 1" { 1.0 } else { 0.0 };
                    let w = want[z * OCEAN_N + x];
                    // Half precision: 2⁻¹⁰ of the value (J's of 1 + its excess).
                    let half = if field == "J − 1" {
                        (1.0 + w).abs()
                    } else {
                        w.abs()
                    } / 1024.0;
                    worst = worst.max(((got - w).abs() - half).max(0.0) / rms);
                }
            }
            println!("{name}: cascade {c} {field}: RMS {rms:.3e}, worst error {worst:.2e} of it");
            assert!(
                worst < 5.0e-3,
                "{name}: cascade {c} {field}: {worst} of the RMS {rms}"
            );
        }
        // The borders hold the far side's texels.
        for atlas in atlases {
            for z in 0..side {
                let row = z * width + c * side;
                let from = ((z + OCEAN_N - 1) % OCEAN_N + 1) * width + c * side;
                let bits = |t: [f32; 4]| t.map(f32::to_bits);
                assert_eq!(
                    bits(atlas[row]),
                    bits(atlas[from + OCEAN_N]),
                    "{name}: left border, row {z}"
                );
                assert_eq!(
                    bits(atlas[row + side - 1]),
                    bits(atlas[from + 1]),
                    "{name}: right border, row {z}"
                );
            }
        }
    }
}

fn check<B: Backend>(
    name: &str,
    backend: &mut B,
    read: impl Fn(&mut B) -> Option<[Vec<[f32; 4]>; 2]>,
) {
    for spectrum in [SeaSpectrum::Jonswap, SeaSpectrum::Phillips] {
        let mut setup = coast(Vec3::new(12.0, 0.0, 9.0));
        setup.render.sea.spectrum = spectrum;
        backend.configure(&setup).expect("configures");
        for _ in 0..5 {
            backend.step(0.1).expect("steps");
        }
        let mut camera = setup.camera;
        camera.position_m = Vec3::new(50.0, 4.0, 0.0);
        camera.forward = Vec3::new(-1.0, -0.1, 0.0);
        let view = View {
            camera,
            width_px: 64,
            height_px: 48,
        };
        backend.render(&view).expect("renders");
        let atlases = read(backend).expect("a frame wrote the sea");
        compare(&format!("{name}, {spectrum:?}"), &setup, &atlases, 0.5);
    }
}

#[test]
fn the_sea_s_kernels_give_the_reference_surfaces_on_every_gpu_backend() {
    each_gpu_backend(
        "the sea's kernels",
        |name, b| check(name, b, |b| b.read_sea_atlases().expect("reads")),
        |name, b| check(name, b, |b| b.read_sea_atlases().expect("reads")),
    );
}
