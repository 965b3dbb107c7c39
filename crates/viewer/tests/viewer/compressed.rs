//! Quantized and compressed glTF, made by a third-party tool (gltf-transform; the
//! commands are in tests/fixtures/compressed/make.mjs) from the built-in demo: each
//! loads to the demo's scene; a texture transform moves the UVs; a file that requires
//! an unknown extension is refused naming it; mutated compressed files never panic.

use std::path::PathBuf;

use glam::Vec2;
use precip_model::Scene;
use precip_viewer::demo::DEMO_GLB;
use precip_viewer::{LoadError, load_scene, load_scene_from_slice};
use proptest::prelude::*;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/compressed")
        .join(name)
}

fn area_m2(scene: &Scene, mesh: usize) -> f64 {
    let m = &scene.meshes[mesh];
    m.indices
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| m.positions_m[t[k] as usize]);
            f64::from((b - a).cross(c - a).length()) * 0.5
        })
        .sum()
}

#[test]
fn quantized_meshopt_and_draco_files_load_as_the_demo() {
    let demo = load_scene_from_slice(DEMO_GLB, "demo.glb")
        .expect("demo")
        .scene;
    for name in ["demo-quantized.glb", "demo-meshopt.glb", "demo-draco.glb"] {
        let loaded = load_scene(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let scene = loaded.scene;
        assert!(
            !loaded
                .report
                .skipped
                .iter()
                .any(|s| s.contains("extension")),
            "{name}: {:?}",
            loaded.report.skipped
        );
        assert_eq!(scene.meshes.len(), demo.meshes.len(), "{name}");
        let (lo, hi) = scene.bounds_m().expect("bounds");
        let (dlo, dhi) = demo.bounds_m().expect("bounds");
        assert!(
            (lo - dlo).abs().max_element() < 0.02 && (hi - dhi).abs().max_element() < 0.02,
            "{name}: bounds {lo}..{hi} against {dlo}..{dhi}"
        );
        for (i, (m, d)) in scene.meshes.iter().zip(&demo.meshes).enumerate() {
            assert_eq!(
                m.indices.len(),
                d.indices.len(),
                "{name} mesh {i}: triangles"
            );
            assert_eq!(m.surface, d.surface, "{name} mesh {i}: surface");
            let (a, b) = (area_m2(&scene, i), area_m2(&demo, i));
            assert!(
                (a - b).abs() <= 0.005 * b + 1e-4,
                "{name} mesh {i}: area {a} against {b}"
            );
            let mean =
                |e: &[f32]| e.iter().map(|&x| f64::from(x)).sum::<f64>() / e.len().max(1) as f64;
            let (e, de) = (mean(&m.snow_eligibility), mean(&d.snow_eligibility));
            assert!(
                (e - de).abs() < 0.02,
                "{name} mesh {i}: eligibility {e} against {de}"
            );
        }
    }
}

#[test]
fn a_texture_transform_moves_the_texture_coordinates() {
    let loaded = load_scene(&fixture("texture-transform.glb")).expect("loads");
    let mesh = &loaded.scene.meshes[0];
    assert!(
        mesh.material.base_colour_texture.is_some(),
        "{:?}",
        loaded.report.skipped
    );
    // offset (0.25, 0.5), rotation π/2, scale (2, 3): u' = 0.25 + 3v, v' = 0.5 − 2u.
    let wanted = [(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0)]
        .map(|(u, v): (f32, f32)| Vec2::new(0.25 + 3.0 * v, 0.5 - 2.0 * u));
    for (got, want) in mesh.uvs.iter().zip(wanted) {
        assert!((*got - want).length() < 1e-5, "{got} against {want}");
    }
}

#[test]
fn a_file_requiring_an_unknown_extension_is_refused_naming_it() {
    let e = load_scene(&fixture("requires-unknown.glb")).expect_err("refused");
    let text = e.to_string();
    assert!(
        text.contains("requires-unknown.glb") && text.contains("EXT_precip_unknown"),
        "{text}"
    );
}

fn caught_a_panic(e: &LoadError) -> bool {
    e.to_string().contains("the glTF reader failed")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_compressed_files_load_or_fail_cleanly(
        which in 0usize..3,
        flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6),
    ) {
        let name = ["demo-quantized.glb", "demo-meshopt.glb", "demo-draco.glb"][which];
        let mut bytes = std::fs::read(fixture(name)).expect("fixture");
        // Past the header, so most mutations reach the compressed data.
        for (at, value) in &flips {
            let i = 20 + at.index(bytes.len() - 20);
            bytes[i] = *value;
        }
        if let Err(e) = load_scene_from_slice(&bytes, "mutated") {
            prop_assert!(!caught_a_panic(&e), "a panic was caught: {e}");
            prop_assert!(e.to_string().contains("mutated"), "the error names the file: {e}");
        }
    }
}
