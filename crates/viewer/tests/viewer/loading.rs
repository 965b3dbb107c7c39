//! Valid files load with the expected geometry and snow eligibility.

use glam::Vec3;
use precip_viewer::demo::{DEMO_GLB, PATIO, ROAD_X_M, demo_glb};
use precip_viewer::glb::write_glb;
use precip_viewer::{load_scene, load_scene_from_slice};
use serde_json::json;

use crate::fixtures::{base64, data_uri_gltf, masked_meshes, png_2x2, split_glb, square};

fn mesh<'a>(scene: &'a precip_model::Scene, name: &str) -> &'a precip_model::Mesh {
    scene
        .meshes
        .iter()
        .find(|m| m.name.starts_with(name))
        .unwrap_or_else(|| panic!("no mesh {name}"))
}

fn check_masked(scene: &precip_model::Scene) {
    assert_eq!(
        mesh(scene, "ground").snow_eligibility,
        vec![1.0, 0.5, 0.0, 1.0],
        "_SNOW_MASK"
    );
    assert!(
        mesh(scene, "wall")
            .snow_eligibility
            .iter()
            .all(|e| e.abs() < 1e-6),
        "slope"
    );
    assert!(
        mesh(scene, "heated")
            .snow_eligibility
            .iter()
            .all(|e| e.abs() < 1e-6),
        "material extras"
    );
    assert!(
        mesh(scene, "half")
            .snow_eligibility
            .iter()
            .all(|e| (e - 0.5).abs() < 1e-6),
        "node extras"
    );
}

#[test]
fn glb_gltf_with_bin_and_data_uri_load_alike() {
    let glb = write_glb(&masked_meshes(), "test");
    let from_glb = load_scene_from_slice(&glb, "masked.glb").expect("loads");
    check_masked(&from_glb.scene);
    assert_eq!(from_glb.report.snow_mask_attribute, 1);
    assert_eq!(from_glb.report.snow_extras, 2);
    // Where each primitive's eligibility came from (`precip inspect` prints it).
    let from = |name: &str| {
        from_glb
            .report
            .tags
            .iter()
            .find(|t| t.primitive.starts_with(name))
            .unwrap_or_else(|| panic!("{name}: no tags in {:?}", from_glb.report.tags))
            .eligibility
            .clone()
    };
    assert_eq!(from("ground"), precip_viewer::TagSource::Attribute);
    assert_eq!(from("wall"), precip_viewer::TagSource::Untagged);
    assert!(
        matches!(from("heated"), precip_viewer::TagSource::Extras(ref on) if on.starts_with("material")),
        "{:?}",
        from("heated")
    );
    assert!(
        matches!(from("half"), precip_viewer::TagSource::Extras(ref on) if on.starts_with("node")),
        "{:?}",
        from("half")
    );

    let from_uri =
        load_scene_from_slice(&data_uri_gltf(&masked_meshes()), "masked.gltf").expect("loads");
    check_masked(&from_uri.scene);

    let dir = std::env::temp_dir().join(format!("precip-fixture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (mut json, bin) = split_glb(&glb);
    json["buffers"][0]["uri"] = json!("masked.bin");
    std::fs::write(dir.join("masked.bin"), &bin).expect("write");
    std::fs::write(
        dir.join("masked.gltf"),
        serde_json::to_vec(&json).expect("json"),
    )
    .expect("write");
    std::fs::write(dir.join("masked.glb"), &glb).expect("write");
    check_masked(
        &load_scene(&dir.join("masked.gltf"))
            .expect("gltf + bin")
            .scene,
    );
    check_masked(&load_scene(&dir.join("masked.glb")).expect("glb file").scene);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn non_indexed_primitives_hierarchies_and_textures() {
    let (mut json, bin) = split_glb(&write_glb(&[square("plain", 0.0)], "test"));
    // Non-indexed: the same 4 vertices would not make triangles, so point the primitive
    // at 3 of them without indices.
    let primitive = &mut json["meshes"][0]["primitives"][0];
    primitive.as_object_mut().expect("object").remove("indices");
    json["accessors"][0]["count"] = json!(3);
    json["accessors"][0]["max"] = json!([4.0, 0.0, 4.0]);
    for a in 1..=2 {
        json["accessors"][a]["count"] = json!(3);
    }
    // A parent node moves by (10, 0, 0) and doubles the size; the mesh's own node has
    // a snow extras the child inherits through no mesh of its own.
    json["nodes"] = json!([
        { "name": "plain", "mesh": 0 },
        { "name": "parent", "children": [0], "translation": [10.0, 0.0, 0.0], "scale": [2.0, 2.0, 2.0], "extras": { "snow": 0.25 } }
    ]);
    json["scenes"][0]["nodes"] = json!([1]);
    // A base-colour texture as a data URI.
    json["images"] = json!([{ "uri": format!("data:image/png;base64,{}", base64(&png_2x2())) }]);
    json["textures"] = json!([{ "source": 0 }]);
    json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64(&bin)
    ));
    let loaded = load_scene_from_slice(&serde_json::to_vec(&json).expect("json"), "tree.gltf")
        .expect("loads");
    let m = &loaded.scene.meshes[0];
    assert_eq!(m.indices.len(), 3);
    assert_eq!(
        m.positions_m[1],
        Vec3::new(10.0, 0.0, 8.0),
        "translated and scaled"
    );
    assert!(
        m.snow_eligibility.iter().all(|e| (e - 0.25).abs() < 1e-6),
        "inherited extras"
    );
    // Inherited from the parent node, which says so.
    assert_eq!(
        loaded.report.tags[0].eligibility,
        precip_viewer::TagSource::Extras("node 1 \"parent\"".into())
    );
    let t = m.material.base_colour_texture.as_ref().expect("a texture");
    assert_eq!((t.width_px, t.height_px), (2, 2));
    assert_eq!(&t.rgba8[..4], &[255, 0, 0, 255]);
}

#[test]
fn points_and_lines_are_skipped_with_a_warning() {
    let (mut json, bin) = split_glb(&write_glb(&[square("a", 0.0), square("b", 1.0)], "test"));
    json["meshes"][1]["primitives"][0]["mode"] = json!(0);
    json["extensionsUsed"] = json!(["KHR_materials_emissive_strength"]);
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64(&bin)
    ));
    let loaded = load_scene_from_slice(&serde_json::to_vec(&json).expect("json"), "mixed.gltf")
        .expect("loads");
    assert_eq!(loaded.scene.meshes.len(), 1);
    assert!(
        loaded.report.skipped.iter().any(|s| s.contains("Points")),
        "{:?}",
        loaded.report.skipped
    );
    assert!(
        loaded
            .report
            .skipped
            .iter()
            .any(|s| s.contains("KHR_materials"))
    );
}

#[test]
fn the_demo_is_what_the_code_writes_and_shows_every_convention() {
    assert!(
        demo_glb() == DEMO_GLB,
        "assets/demo.glb is stale: run `cargo run -- demo`"
    );
    let loaded = load_scene_from_slice(DEMO_GLB, "demo.glb").expect("loads");
    assert!(
        loaded.report.skipped.is_empty(),
        "{:?}",
        loaded.report.skipped
    );
    let scene = &loaded.scene;
    assert!(
        mesh(scene, "road")
            .snow_eligibility
            .iter()
            .all(|e| *e <= 0.0),
        "node extras"
    );
    assert!(
        mesh(scene, "house walls")
            .snow_eligibility
            .iter()
            .all(|e| *e <= 0.0),
        "material extras"
    );
    assert!(
        mesh(scene, "house roof")
            .snow_eligibility
            .iter()
            .all(|e| *e > 0.99),
        "slope"
    );
    let terrain = mesh(scene, "terrain");
    for (p, e) in terrain.positions_m.iter().zip(&terrain.snow_eligibility) {
        let in_patio = glam::Vec2::new(p.x, p.z).distance(PATIO.0) < PATIO.1;
        assert_eq!(*e <= 0.0, in_patio, "_SNOW_MASK at {p}");
    }
    assert!(ROAD_X_M.0 < ROAD_X_M.1);
}
