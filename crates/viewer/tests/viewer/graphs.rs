//! Node graphs and image references from the wild: cycles, shared children, deep
//! chains, images that are `{}`, textures and samplers pointing anywhere. Each loads
//! or fails with an error naming the file; none overflows the stack or panics.

use precip_viewer::glb::write_glb;
use precip_viewer::{LoadError, load_scene_from_slice};
use proptest::prelude::*;
use serde_json::{Value, json};

use crate::fixtures::{base64, png_2x2, split_glb, square};

/// A square mesh as a data-URI .gltf whose nodes, images, textures and samplers are
/// replaced by the given lists (mesh 0 is the square; material 0 uses texture 0 when
/// `textured`).
fn with_graph(
    nodes: Value,
    roots: Value,
    images: Value,
    textures: Value,
    samplers: Value,
) -> Vec<u8> {
    let (mut json, bin) = split_glb(&write_glb(&[square("a", 0.0)], "graphs"));
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64(&bin)
    ));
    json["nodes"] = nodes;
    json["scenes"] = json!([{ "nodes": roots }]);
    json["scene"] = json!(0);
    json["images"] = images;
    json["textures"] = textures;
    json["samplers"] = samplers;
    json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    if json["meshes"][0]["primitives"][0]["material"].is_null() {
        json["meshes"][0]["primitives"][0]["material"] = json!(0);
    }
    serde_json::to_vec(&json).expect("json")
}

fn png_image() -> Value {
    json!({ "uri": format!("data:image/png;base64,{}", base64(&png_2x2())) })
}

fn caught_a_panic(e: &LoadError) -> bool {
    e.to_string().contains("the glTF reader failed")
}

#[test]
fn nodes_whose_children_form_a_cycle_are_an_error_naming_them() {
    let file = with_graph(
        json!([{ "mesh": 0, "children": [1] }, { "children": [0] }]),
        json!([0]),
        json!([png_image()]),
        json!([{ "source": 0 }]),
        json!([]),
    );
    let e = load_scene_from_slice(&file, "cycle.gltf").expect_err("a cycle");
    let text = e.to_string();
    assert!(
        text.contains("cycle.gltf") && text.contains("0 → 1 → 0"),
        "{text}"
    );
    // A node that is its own child.
    let file = with_graph(
        json!([{ "mesh": 0, "children": [0] }]),
        json!([0]),
        json!([png_image()]),
        json!([{ "source": 0 }]),
        json!([]),
    );
    let text = load_scene_from_slice(&file, "self.gltf")
        .expect_err("a cycle")
        .to_string();
    assert!(text.contains("cycle"), "{text}");
}

#[test]
fn an_image_that_is_an_empty_object_leaves_its_mesh_untextured() {
    let file = with_graph(
        json!([{ "mesh": 0 }]),
        json!([0]),
        json!([{}]),
        json!([{ "source": 0 }]),
        json!([]),
    );
    let loaded = load_scene_from_slice(&file, "empty-image.gltf").expect("loads");
    assert!(
        loaded.scene.meshes[0]
            .material
            .base_colour_texture
            .is_none()
    );
    assert!(
        loaded
            .report
            .skipped
            .iter()
            .any(|s| s.contains("image 0 has neither a uri nor a bufferView")),
        "{:?}",
        loaded.report.skipped
    );
    // A bufferView without a mimeType (the reader would unwrap it too).
    let file = with_graph(
        json!([{ "mesh": 0 }]),
        json!([0]),
        json!([{ "bufferView": 0 }]),
        json!([{ "source": 0 }]),
        json!([]),
    );
    let loaded = load_scene_from_slice(&file, "no-mime.gltf").expect("loads");
    assert!(
        loaded
            .report
            .skipped
            .iter()
            .any(|s| s.contains("no mimeType"))
    );
}

#[test]
fn a_deep_chain_loads_and_its_transforms_compose() {
    let depth = 20_000;
    let nodes: Vec<Value> = (0..depth)
        .map(|i| {
            if i + 1 < depth {
                json!({ "translation": [0.0, 0.001, 0.0], "children": [i + 1] })
            } else {
                json!({ "mesh": 0, "translation": [0.0, 0.001, 0.0] })
            }
        })
        .collect();
    let file = with_graph(
        json!(nodes),
        json!([0]),
        json!([png_image()]),
        json!([{ "source": 0 }]),
        json!([]),
    );
    let loaded = load_scene_from_slice(&file, "chain.gltf").expect("loads");
    let y = loaded.scene.meshes[0].positions_m[0].y;
    assert!((y - 20.0).abs() < 0.05, "20 000 × 1 mm = 20 m, got {y}");
}

#[test]
fn shared_children_are_drawn_once_with_a_warning() {
    let file = with_graph(
        json!([{ "children": [2] }, { "children": [2] }, { "mesh": 0 }]),
        json!([0, 1, 0]),
        json!([png_image()]),
        json!([{ "source": 0 }]),
        json!([]),
    );
    let loaded = load_scene_from_slice(&file, "shared.gltf").expect("loads");
    assert_eq!(loaded.scene.meshes.len(), 1);
    assert!(
        loaded
            .report
            .skipped
            .iter()
            .any(|s| s.contains("reached a second time")),
        "{:?}",
        loaded.report.skipped
    );
}

fn any_image() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(json!({})),
        Just(png_image()),
        Just(json!({ "bufferView": 0 })),
        Just(json!({ "bufferView": 0, "mimeType": "image/png" })),
        Just(json!({ "uri": "missing.png" })),
        Just(json!({ "uri": "data:image/png;base64,AAAA" })),
        (0u32..6).prop_map(|v| json!({ "bufferView": v, "mimeType": "image/png" })),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 600, ..ProptestConfig::default() })]

    #[test]
    fn random_graphs_and_references_load_or_fail_cleanly(
        children in proptest::collection::vec(proptest::collection::vec(0u32..9, 0..4), 1..8),
        meshes in proptest::collection::vec(proptest::option::of(0u32..2), 1..8),
        roots in proptest::collection::vec(0u32..9, 0..5),
        images in proptest::collection::vec(any_image(), 0..3),
        texture_sources in proptest::collection::vec(proptest::option::of(0u32..4), 0..3),
        texture_samplers in proptest::collection::vec(proptest::option::of(0u32..3), 0..3),
        samplers in 0usize..3,
    ) {
        let nodes: Vec<Value> = children
            .iter()
            .zip(meshes.iter().chain(std::iter::repeat(&None)))
            .map(|(c, m)| {
                let mut node = json!({});
                if !c.is_empty() {
                    node["children"] = json!(c);
                }
                if let Some(m) = m {
                    node["mesh"] = json!(m);
                }
                node
            })
            .collect();
        let textures: Vec<Value> = texture_sources
            .iter()
            .zip(texture_samplers.iter().chain(std::iter::repeat(&None)))
            .map(|(s, p)| {
                let mut t = json!({});
                if let Some(s) = s { t["source"] = json!(s); }
                if let Some(p) = p { t["sampler"] = json!(p); }
                t
            })
            .collect();
        let samplers: Vec<Value> = (0..samplers).map(|_| json!({ "magFilter": 9729 })).collect();
        let file = with_graph(json!(nodes), json!(roots), json!(images), json!(textures), json!(samplers));
        if let Err(e) = load_scene_from_slice(&file, "random.gltf") {
            prop_assert!(!caught_a_panic(&e), "a panic was caught: {e}");
            prop_assert!(e.to_string().contains("random.gltf"), "the error names the file: {e}");
        }
    }
}
