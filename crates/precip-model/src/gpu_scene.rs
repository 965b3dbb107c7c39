//! The scene packed for a GPU backend: tessellated for the snow's displacement, every
//! mesh's vertices in one [`SceneVertex`] list, indices offset by each mesh's first
//! vertex, and each mesh's index range — the same bytes for the wgpu and Vulkan
//! backends, which only upload them.

use std::ops::Range;

use crate::error::BackendError;
use crate::gpu::SceneVertex;
use crate::ground::GroundMap;
use crate::render::RenderSettings;
use crate::scene::Scene;

/// A scene ready to upload.
#[derive(Debug, Clone)]
pub struct PackedScene {
    /// The tessellated scene (its meshes' materials go with `ranges`).
    pub scene: Scene,
    /// Every mesh's vertices.
    pub vertices: Vec<SceneVertex>,
    /// `u32` indices into `vertices`.
    pub indices: Vec<u32>,
    /// Each mesh's range of `indices`, in mesh order.
    pub ranges: Vec<Range<u32>>,
}

fn too_big(what: &str) -> BackendError {
    BackendError::Setup {
        field: "scene",
        problem: format!(
            "its {what} exceed what 32-bit indices address: raise render.tessellation_edge_m or lower render.max_scene_triangles"
        ),
    }
}

impl PackedScene {
    /// Tessellates `scene` (prepared: complete attributes) where the snow over
    /// `ground` raises it, as `settings` say, and packs it.
    pub fn new(
        scene: &Scene,
        settings: &RenderSettings,
        ground: &GroundMap,
    ) -> Result<Self, BackendError> {
        let scene = scene.tessellated(
            settings.tessellation_edge_m,
            settings.max_scene_triangles,
            ground,
        );
        let mut vertices: Vec<SceneVertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut ranges = Vec::with_capacity(scene.meshes.len());
        for mesh in &scene.meshes {
            let base = u32::try_from(vertices.len()).map_err(|_| too_big("vertices"))?;
            for (i, p) in mesh.positions_m.iter().enumerate() {
                vertices.push(SceneVertex {
                    position_m: p.to_array(),
                    normal: mesh.normals[i].to_array(),
                    uv: mesh.uvs[i].to_array(),
                    eligibility: mesh.snow_eligibility[i],
                });
            }
            let start = u32::try_from(indices.len()).map_err(|_| too_big("indices"))?;
            indices.extend(mesh.indices.iter().map(|i| i + base));
            let end = u32::try_from(indices.len()).map_err(|_| too_big("indices"))?;
            ranges.push(start..end);
        }
        Ok(Self {
            scene,
            vertices,
            indices,
            ranges,
        })
    }

    /// Triangles drawn.
    #[must_use]
    pub fn triangles(&self) -> u64 {
        self.indices.len() as u64 / 3
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin::house_on_plane;

    #[test]
    fn every_mesh_indexes_its_own_vertices() {
        let scene = house_on_plane().prepare().expect("valid").0;
        let ground = crate::setup::Setup::over_flat_ground(60.0, 64, 10.0, 1).ground;
        let packed = PackedScene::new(&scene, &RenderSettings::default(), &ground).expect("packs");
        assert_eq!(packed.ranges.len(), packed.scene.meshes.len());
        let mut first = 0u32;
        for (mesh, range) in packed.scene.meshes.iter().zip(&packed.ranges) {
            let count = mesh.positions_m.len() as u32;
            for &i in &packed.indices[range.start as usize..range.end as usize] {
                assert!((first..first + count).contains(&i), "{i} outside its mesh");
            }
            first += count;
        }
        assert_eq!(first as usize, packed.vertices.len());
        assert!(packed.triangles() > 0);
    }
}
