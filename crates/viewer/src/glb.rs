//! A small glTF 2.0 binary (GLB) writer for triangle meshes: what the demo scene and
//! the test fixtures are written with. Each mesh becomes one node, one mesh with one
//! indexed triangle primitive (POSITION with min/max, NORMAL, optional TEXCOORD_0 and
//! `_SNOW_MASK`) and one material; `extras` can go on the material or the node.

use glam::Vec3;
use serde_json::{Value, json};

/// One mesh to write.
#[derive(Debug, Clone, Default)]
pub struct GlbMesh {
    /// Node and mesh name.
    pub name: String,
    /// Positions, m.
    pub positions: Vec<[f32; 3]>,
    /// Unit normals (one per position).
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates (one per position), or empty for none.
    pub uvs: Vec<[f32; 2]>,
    /// Triangle list.
    pub indices: Vec<u32>,
    /// Per-vertex `_SNOW_MASK`, or empty.
    pub snow_mask: Vec<f32>,
    /// Linear base colour factor.
    pub base_colour: [f32; 4],
    /// `extras` of the material.
    pub material_extras: Option<Value>,
    /// `extras` of the node.
    pub node_extras: Option<Value>,
}

/// A mesh over the grid of the given x and z positions (each increasing), its
/// heights by `height`, its normals from the height's slope, facing up.
#[must_use]
pub fn height_grid(
    name: &str,
    xs: &[f32],
    zs: &[f32],
    height: impl Fn(f32, f32) -> f32,
) -> GlbMesh {
    let mut m = GlbMesh {
        name: name.to_owned(),
        ..GlbMesh::default()
    };
    for &z in zs {
        for &x in xs {
            let e = 0.05;
            let normal = Vec3::new(
                height(x - e, z) - height(x + e, z),
                2.0 * e,
                height(x, z - e) - height(x, z + e),
            )
            .normalize();
            m.positions.push([x, height(x, z), z]);
            m.normals.push(normal.to_array());
        }
    }
    let row = xs.len() as u32;
    // (Fewer than two positions along an axis: no cell.)
    for j in 0..(zs.len() as u32).saturating_sub(1) {
        for i in 0..row.saturating_sub(1) {
            let a = j * row + i;
            // Counter-clockwise seen from above (+Y) for x and z increasing.
            m.indices
                .extend_from_slice(&[a, a + row, a + 1, a + 1, a + row, a + row + 1]);
        }
    }
    m
}

/// Layout of the growing binary chunk.
#[derive(Default)]
struct Binary {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Binary {
    /// Appends `data` as a buffer view plus an accessor; returns the accessor index.
    fn push(
        &mut self,
        data: &[u8],
        target: u32,
        count: usize,
        component: u32,
        kind: &str,
        bounds: Option<(Value, Value)>,
    ) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(data);
        self.views.push(json!({
            "buffer": 0, "byteOffset": offset, "byteLength": data.len(), "target": target
        }));
        let mut accessor = json!({
            "bufferView": self.views.len() - 1, "componentType": component,
            "count": count, "type": kind
        });
        if let Some((min, max)) = bounds {
            accessor["min"] = min;
            accessor["max"] = max;
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }
}

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// The meshes as a GLB file's bytes.
#[must_use]
pub fn write_glb(meshes: &[GlbMesh], generator: &str) -> Vec<u8> {
    let mut bin = Binary::default();
    let (mut json_meshes, mut materials, mut nodes) = (Vec::new(), Vec::new(), Vec::new());
    for (i, m) in meshes.iter().enumerate() {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &m.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let n = m.positions.len();
        let position = bin.push(
            bytemuck::cast_slice(&m.positions),
            ARRAY_BUFFER,
            n,
            FLOAT,
            "VEC3",
            Some((json!(lo), json!(hi))),
        );
        let normal = bin.push(
            bytemuck::cast_slice(&m.normals),
            ARRAY_BUFFER,
            n,
            FLOAT,
            "VEC3",
            None,
        );
        let mut attributes = json!({ "POSITION": position, "NORMAL": normal });
        if !m.uvs.is_empty() {
            let uv = bin.push(
                bytemuck::cast_slice(&m.uvs),
                ARRAY_BUFFER,
                n,
                FLOAT,
                "VEC2",
                None,
            );
            attributes["TEXCOORD_0"] = json!(uv);
        }
        if !m.snow_mask.is_empty() {
            let mask = bin.push(
                bytemuck::cast_slice(&m.snow_mask),
                ARRAY_BUFFER,
                n,
                FLOAT,
                "SCALAR",
                None,
            );
            attributes["_SNOW_MASK"] = json!(mask);
        }
        let indices = bin.push(
            bytemuck::cast_slice(&m.indices),
            ELEMENT_ARRAY_BUFFER,
            m.indices.len(),
            UNSIGNED_INT,
            "SCALAR",
            None,
        );
        let mut material = json!({
            "name": m.name,
            "pbrMetallicRoughness": {
                "baseColorFactor": m.base_colour, "metallicFactor": 0.0, "roughnessFactor": 1.0
            }
        });
        if let Some(e) = &m.material_extras {
            material["extras"] = e.clone();
        }
        materials.push(material);
        json_meshes.push(json!({
            "name": m.name,
            "primitives": [{ "attributes": attributes, "indices": indices, "material": i, "mode": 4 }]
        }));
        let mut node = json!({ "name": m.name, "mesh": i });
        if let Some(e) = &m.node_extras {
            node["extras"] = e.clone();
        }
        nodes.push(node);
    }
    while !bin.bytes.len().is_multiple_of(4) {
        bin.bytes.push(0);
    }
    let document = json!({
        "asset": { "version": "2.0", "generator": generator },
        "scene": 0,
        "scenes": [{ "name": "scene", "nodes": (0..meshes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": json_meshes,
        "materials": materials,
        "accessors": bin.accessors,
        "bufferViews": bin.views,
        "buffers": [{ "byteLength": bin.bytes.len() }],
    });
    let mut json_bytes = document.to_string().into_bytes();
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let total = 12 + 8 + json_bytes.len() + 8 + bin.bytes.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_bytes);
    out.extend_from_slice(&(bin.bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin.bytes);
    out
}
