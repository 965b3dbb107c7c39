//! Broken files give a clear error, never a panic.

use precip_viewer::glb::write_glb;
use precip_viewer::{LoadError, load_scene, load_scene_from_slice};
use proptest::prelude::*;
use serde_json::json;

use crate::fixtures::{base64, masked_meshes, split_glb, square};

fn gltf_with(json: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut json = json.clone();
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64(bin)
    ));
    serde_json::to_vec(&json).expect("json")
}

fn message(result: Result<precip_viewer::LoadedScene, LoadError>) -> String {
    match result {
        Ok(_) => panic!("a broken file loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn each_kind_of_broken_file_names_its_problem() {
    let glb = write_glb(&[square("a", 0.0)], "test");
    let truncated = message(load_scene_from_slice(&glb[..glb.len() / 2], "cut.glb"));
    assert!(truncated.contains("cut.glb"), "{truncated}");
    let mut magic = glb.clone();
    magic[..4].copy_from_slice(b"gLTX");
    assert!(message(load_scene_from_slice(&magic, "magic.glb")).contains("magic.glb"));
    assert!(message(load_scene_from_slice(b"{ \"asset\": ", "json.gltf")).contains("json.gltf"));
    let missing = message(load_scene(std::path::Path::new("/nonexistent/scene.gltf")));
    assert!(missing.contains("scene.gltf"), "{missing}");

    let (json, bin) = split_glb(&glb);
    // A .gltf whose .bin is missing.
    let dir = std::env::temp_dir().join(format!("precip-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut external = json.clone();
    external["buffers"][0]["uri"] = json!("gone.bin");
    std::fs::write(
        dir.join("x.gltf"),
        serde_json::to_vec(&external).expect("json"),
    )
    .expect("write");
    assert!(message(load_scene(&dir.join("x.gltf"))).contains("x.gltf"));
    let _ = std::fs::remove_dir_all(&dir);

    // An accessor past its buffer view.
    let mut long = json.clone();
    long["accessors"][0]["count"] = json!(1000);
    let text = message(load_scene_from_slice(&gltf_with(&long, &bin), "long.gltf"));
    assert!(
        text.contains("long.gltf") && text.contains("accessor"),
        "{text}"
    );

    // A POSITION naming an accessor that does not exist (gltf-json's validation
    // would index it unchecked; found by the mutation proptest).
    let mut missing_accessor = json.clone();
    missing_accessor["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99);
    let text = message(load_scene_from_slice(
        &gltf_with(&missing_accessor, &bin),
        "accessor.gltf",
    ));
    assert!(text.contains("accessor 99"), "{text}");

    // An index beyond the vertices (indices are the last view: 6 × u32).
    let mut bad_index = bin.clone();
    let at = bad_index.len() - 4;
    bad_index[at..].copy_from_slice(&77u32.to_le_bytes());
    let text = message(load_scene_from_slice(
        &gltf_with(&json, &bad_index),
        "index.gltf",
    ));
    assert!(text.contains("index 77"), "{text}");

    // A NaN position (the first float of the first view).
    let mut nan = bin.clone();
    nan[..4].copy_from_slice(&f32::NAN.to_le_bytes());
    let text = message(load_scene_from_slice(&gltf_with(&json, &nan), "nan.gltf"));
    assert!(text.contains("non-finite"), "{text}");

    // No triangles at all.
    let mut points = json.clone();
    points["meshes"][0]["primitives"][0]["mode"] = json!(0);
    let text = message(load_scene_from_slice(
        &gltf_with(&points, &bin),
        "points.gltf",
    ));
    assert!(text.contains("no triangles"), "{text}");

    // Bad extras.
    let mut extras = json;
    extras["nodes"][0]["extras"] = json!({ "snow": "lots" });
    let text = message(load_scene_from_slice(
        &gltf_with(&extras, &bin),
        "extras.gltf",
    ));
    assert!(text.contains("extras.snow"), "{text}");
}

/// The marker of a panic caught inside the loader: must never be seen.
fn caught_a_panic(e: &LoadError) -> bool {
    e.to_string().contains("the glTF reader failed")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn mutated_files_load_or_fail_cleanly(
        flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
        cut in proptest::option::of(any::<prop::sample::Index>()),
        as_gltf in any::<bool>(),
    ) {
        let glb = write_glb(&masked_meshes(), "test");
        let mut bytes = if as_gltf {
            let (json, bin) = split_glb(&glb);
            gltf_with(&json, &bin)
        } else {
            glb
        };
        for (at, value) in &flips {
            let i = at.index(bytes.len());
            bytes[i] = *value;
        }
        if let Some(c) = cut {
            bytes.truncate(c.index(bytes.len()));
        }
        if let Err(e) = load_scene_from_slice(&bytes, "mutated") {
            prop_assert!(!caught_a_panic(&e), "a panic was caught: {e}");
            prop_assert!(e.to_string().contains("mutated"), "the error names the file: {e}");
        }
    }
}
