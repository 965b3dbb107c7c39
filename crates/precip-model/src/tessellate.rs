//! Subdivision of a scene's triangles so the snow displacement has vertices to move.
//!
//! The vertex shader raises upward surfaces by the cover's depth at each vertex
//! (MODEL.md §4 goes beyond seed 003 here); a ground plane of two triangles would rise
//! as a whole. Every triangle is split into `k²` smaller ones, `k = ⌈longest edge /
//! max_edge⌉`, all attributes interpolated. Two triangles sharing an edge of the same
//! length split it at the same points; where their `k` differ (a long thin triangle
//! beside a small one) a T-junction remains and may open a hairline where the snow
//! depths differ. A triangle budget caps the result: the edge limit grows until the
//! scene fits.

use glam::Vec2;

use crate::scene::{Mesh, Scene};

/// The most pieces one triangle is split into along an edge.
pub const MAX_SPLITS_PER_EDGE: u32 = 64;

fn splits(mesh: &Mesh, t: &[u32], max_edge_m: f32) -> u32 {
    let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions_m[i as usize]);
    let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
    ((longest / max_edge_m).ceil() as u32).clamp(1, MAX_SPLITS_PER_EDGE)
}

fn triangle_count(scene: &Scene, max_edge_m: f32) -> u64 {
    scene
        .meshes
        .iter()
        .flat_map(|m| m.indices.chunks_exact(3).map(move |t| (m, t)))
        .map(|(m, t)| u64::from(splits(m, t, max_edge_m)).pow(2))
        .sum()
}

fn tessellate_mesh(mesh: &Mesh, max_edge_m: f32) -> Mesh {
    let mut out = Mesh {
        name: mesh.name.clone(),
        material: mesh.material.clone(),
        ..Mesh::default()
    };
    for t in mesh.indices.chunks_exact(3) {
        let k = splits(mesh, t, max_edge_m);
        let [ia, ib, ic] = [t[0], t[1], t[2]].map(|i| i as usize);
        let base = out.positions_m.len() as u32;
        // Vertex (i, j) at barycentric ((k−i−j)/k, i/k, j/k), rows j = 0..=k.
        let mut row_start = Vec::with_capacity(k as usize + 1);
        for j in 0..=k {
            row_start.push(out.positions_m.len() as u32 - base);
            for i in 0..=(k - j) {
                let (wb, wc) = (i as f32 / k as f32, j as f32 / k as f32);
                let wa = 1.0 - wb - wc;
                let lerp3 = |v: &[glam::Vec3]| wa * v[ia] + wb * v[ib] + wc * v[ic];
                out.positions_m.push(lerp3(&mesh.positions_m));
                out.normals
                    .push(lerp3(&mesh.normals).normalize_or(glam::Vec3::Y));
                let uv = |v: &[Vec2]| wa * v[ia] + wb * v[ib] + wc * v[ic];
                out.uvs.push(uv(&mesh.uvs));
                let e = &mesh.snow_eligibility;
                out.snow_eligibility
                    .push(wa * e[ia] + wb * e[ib] + wc * e[ic]);
            }
        }
        let at = |i: u32, j: u32| base + row_start[j as usize] + i;
        for j in 0..k {
            for i in 0..(k - j) {
                out.indices
                    .extend_from_slice(&[at(i, j), at(i + 1, j), at(i, j + 1)]);
                if i + 1 < k - j {
                    out.indices
                        .extend_from_slice(&[at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
    }
    out
}

impl Scene {
    /// This prepared scene with triangles no longer than about `max_edge_m`, in at most
    /// `max_triangles` triangles (the edge limit grows until it fits); see the module
    /// docs. `max_edge_m` must be positive.
    #[must_use]
    pub fn tessellated(&self, max_edge_m: f32, max_triangles: u64) -> Self {
        let mut edge = if max_edge_m.is_finite() && max_edge_m > 0.0 {
            max_edge_m
        } else {
            1.0
        };
        while triangle_count(self, edge) > max_triangles.max(1) && edge < 1.0e9 {
            edge *= 1.5;
        }
        Self {
            meshes: self
                .meshes
                .iter()
                .map(|m| tessellate_mesh(m, edge))
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn plane(side_m: f32) -> Scene {
        let s = side_m / 2.0;
        Scene {
            meshes: vec![Mesh {
                name: "plane".into(),
                positions_m: vec![
                    Vec3::new(-s, 0.0, -s),
                    Vec3::new(-s, 0.0, s),
                    Vec3::new(s, 0.0, s),
                    Vec3::new(s, 0.0, -s),
                ],
                indices: vec![0, 1, 2, 0, 2, 3],
                ..Mesh::default()
            }],
        }
        .prepare()
        .expect("valid")
        .0
        .into_scene()
    }

    #[test]
    fn splits_keep_area_and_attributes() {
        let scene = plane(10.0);
        let fine = scene.tessellated(1.0, 1_000_000);
        let area = |s: &Scene| -> f32 {
            s.meshes
                .iter()
                .flat_map(|m| {
                    m.indices.chunks_exact(3).map(|t| {
                        let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions_m[i as usize]);
                        0.5 * (b - a).cross(c - a).length()
                    })
                })
                .sum()
        };
        assert!((area(&fine) - 100.0).abs() < 1e-2);
        // Diagonal ≈ 14.1 m → 15 splits → 225 triangles each.
        assert_eq!(fine.meshes[0].indices.len() / 3, 2 * 225);
        let m = &fine.meshes[0];
        assert!(m.normals.iter().all(|n| (*n - Vec3::Y).length() < 1e-6));
        assert!(m.snow_eligibility.iter().all(|e| (*e - 1.0).abs() < 1e-6));
        // Still a valid scene, no degenerate triangle.
        let (_, report) = fine.clone().prepare().expect("valid");
        assert_eq!(report.degenerate_triangles, 0);
        // Winding kept: every normal from the cross product points up.
        for t in m.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions_m[i as usize]);
            assert!((b - a).cross(c - a).y * (plane_winding()) > 0.0);
        }
    }

    fn plane_winding() -> f32 {
        // The plane's triangle (−s,−s) (−s,s) (s,s) has its cross product along +Y.
        let (a, b, c) = (
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        );
        (b - a).cross(c - a).y.signum()
    }

    #[test]
    fn the_budget_caps_the_triangles() {
        let scene = plane(1000.0);
        let capped = scene.tessellated(0.1, 5_000);
        assert!(capped.meshes[0].indices.len() / 3 <= 5_000);
        assert!(capped.meshes[0].indices.len() / 3 >= 2);
    }
}
