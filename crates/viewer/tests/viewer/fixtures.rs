//! Fixture scenes written in code: a GLB, and its JSON/BIN parts to rewrite as
//! .gltf + .bin, data URIs, hierarchies and broken variants.

use precip_viewer::glb::{GlbMesh, write_glb};
use serde_json::{Value, json};

/// A 4 m square at height `y` facing up, four vertices, two triangles.
pub fn square(name: &str, y: f32) -> GlbMesh {
    GlbMesh {
        name: name.to_owned(),
        positions: vec![[0.0, y, 0.0], [0.0, y, 4.0], [4.0, y, 4.0], [4.0, y, 0.0]],
        normals: vec![[0.0, 1.0, 0.0]; 4],
        uvs: vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]],
        indices: vec![0, 1, 2, 0, 2, 3],
        base_colour: [0.5, 0.5, 0.5, 1.0],
        ..GlbMesh::default()
    }
}

/// A wall: a 4 m square standing in the XY plane.
pub fn wall(name: &str) -> GlbMesh {
    GlbMesh {
        name: name.to_owned(),
        positions: vec![
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [4.0, 4.0, 0.0],
            [0.0, 4.0, 0.0],
        ],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        uvs: vec![[0.0; 2]; 4],
        indices: vec![0, 1, 2, 0, 2, 3],
        base_colour: [0.7, 0.6, 0.5, 1.0],
        ..GlbMesh::default()
    }
}

/// Ground with a `_SNOW_MASK`, a wall and a square whose material says no snow.
pub fn masked_meshes() -> Vec<GlbMesh> {
    let mut ground = square("ground", 0.0);
    ground.snow_mask = vec![1.0, 0.5, 0.0, 1.0];
    let mut heated = square("heated", 1.0);
    heated.material_extras = Some(json!({ "snow": false }));
    let mut half = square("half", 2.0);
    half.node_extras = Some(json!({ "snow": 0.5 }));
    vec![ground, wall("wall"), heated, half]
}

/// A GLB's JSON and binary chunk.
pub fn split_glb(glb: &[u8]) -> (Value, Vec<u8>) {
    let json_len = u32::from_le_bytes(glb[12..16].try_into().expect("4 bytes")) as usize;
    let json: Value = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
    let bin_at = 20 + json_len;
    let bin_len = u32::from_le_bytes(glb[bin_at..bin_at + 4].try_into().expect("4 bytes")) as usize;
    (json, glb[bin_at + 8..bin_at + 8 + bin_len].to_vec())
}

/// Standard base64 (for data URIs).
pub fn base64(bytes: &[u8]) -> String {
    const TABLE: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(TABLE[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A self-contained .gltf (buffer as a data URI) of `meshes`.
pub fn data_uri_gltf(meshes: &[GlbMesh]) -> Vec<u8> {
    let (mut json, bin) = split_glb(&write_glb(meshes, "test"));
    json["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64(&bin)
    ));
    serde_json::to_vec(&json).expect("serialises")
}

/// A 2×2 PNG: red, green, blue, white.
pub fn png_2x2() -> Vec<u8> {
    let pixels = [
        255u8, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255,
    ];
    let mut out = Vec::new();
    image::write_buffer_with_format(
        &mut std::io::Cursor::new(&mut out),
        &pixels,
        2,
        2,
        image::ExtendedColorType::Rgba8,
        image::ImageFormat::Png,
    )
    .expect("encodes");
    out
}
