//! Subdivision of a scene's triangles so the snow displacement has vertices to move.
//!
//! The vertex shader raises upward surfaces by the cover's depth at each vertex
//! (docs/model.md §4 goes beyond seed 003 here); a ground plane of two triangles would rise
//! as a whole. A triangle the displacement raises somewhere
//! ([`crate::scene::displacement::raised`] at any point of a lattice of up to
//! [`PROBE_SPLITS`]² pieces over it: eligible, facing up, top-most under the sky) is
//! split into `k²` smaller ones, `k = ⌈longest edge / max_edge⌉`, all attributes
//! interpolated; every other triangle (walls, ceilings, floors under a roof,
//! ineligible meshes) is kept whole, since its vertices never move. Two triangles
//! sharing an edge of the same length split it at the same points; where their `k`
//! differ (a long thin triangle beside a small one, or a raised one beside a kept
//! one) a T-junction remains and may open a hairline where the snow depths differ. A
//! triangle budget caps the result: the edge limit grows until the scene fits.
//!
//! Not done: detail by distance to the camera (the split is fixed at configuration;
//! a view-dependent level of detail needs chunks re-chosen per frame).

use glam::Vec2;

use crate::particles::ground::GroundMap;
use crate::scene::displacement::raised;
use crate::scene::{Mesh, Scene};

/// The lattice over a triangle on which [`raised`] is probed: `min(k, 8)` pieces an
/// edge (an exposed patch narrower than an eighth of the triangle may be missed and
/// stay flat).
pub const PROBE_SPLITS: u32 = 8;

/// The most pieces one triangle is split into along an edge.
pub const MAX_SPLITS_PER_EDGE: u32 = 64;

fn splits(mesh: &Mesh, t: &[u32], max_edge_m: f32) -> u32 {
    let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions_m[i as usize]);
    let longest = a.distance(b).max(b.distance(c)).max(c.distance(a));
    ((longest / max_edge_m).ceil() as u32).clamp(1, MAX_SPLITS_PER_EDGE)
}

/// Whether the displacement raises any point of triangle `t` (probed on a lattice of
/// `min(k, PROBE_SPLITS)` pieces an edge for the `k` of `max_edge_m`).
fn displaceable(mesh: &Mesh, t: &[u32], max_edge_m: f32, ground: &GroundMap) -> bool {
    let k = splits(mesh, t, max_edge_m);
    if k == 1 {
        return false;
    }
    let k = k.min(PROBE_SPLITS);
    let [ia, ib, ic] = [t[0], t[1], t[2]].map(|i| i as usize);
    (0..=k).any(|j| {
        (0..=(k - j)).any(|i| {
            let (wb, wc) = (i as f32 / k as f32, j as f32 / k as f32);
            let wa = 1.0 - wb - wc;
            let lerp3 = |v: &[glam::Vec3]| wa * v[ia] + wb * v[ib] + wc * v[ic];
            let e = &mesh.snow_eligibility;
            raised(
                ground,
                lerp3(&mesh.positions_m),
                lerp3(&mesh.normals),
                wa * e[ia] + wb * e[ib] + wc * e[ic],
            )
        })
    })
}

/// Per mesh, per triangle: whether it is split at all.
fn displaceable_triangles(scene: &Scene, max_edge_m: f32, ground: &GroundMap) -> Vec<Vec<bool>> {
    scene
        .meshes
        .iter()
        .map(|m| {
            // A water body holds no snow (its vertices carry no eligibility on the
            // GPU): nothing raises it.
            m.indices
                .chunks_exact(3)
                .map(|t| !m.is_water_body() && displaceable(m, t, max_edge_m, ground))
                .collect()
        })
        .collect()
}

fn triangle_count(scene: &Scene, split: &[Vec<bool>], max_edge_m: f32) -> u64 {
    scene
        .meshes
        .iter()
        .zip(split)
        .flat_map(|(m, s)| {
            m.indices
                .chunks_exact(3)
                .zip(s)
                .map(move |(t, s)| (m, t, *s))
        })
        .map(|(m, t, s)| {
            if s {
                u64::from(splits(m, t, max_edge_m)).pow(2)
            } else {
                1
            }
        })
        .sum()
}

/// One triangle of the input after tessellation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Piece {
    /// Its triangles' indices in the tessellated mesh's `indices`.
    pub fine: std::ops::Range<usize>,
    /// Its three corners (the input triangle, same winding) as indices of the
    /// tessellated mesh's vertices: the piece drawn coarse.
    pub coarse: [u32; 3],
    /// Whether it was split (else `fine` is `coarse`).
    pub split: bool,
}

/// A scene after [`Scene::tessellated`], with each input triangle's [`Piece`] per
/// mesh (the level of detail of `crate::scene::gpu_scene` chooses between a piece's fine
/// and coarse triangles).
#[derive(Debug, Clone)]
pub struct Tessellation {
    /// The tessellated scene (fine).
    pub scene: Scene,
    /// Per mesh, per input triangle.
    pub pieces: Vec<Vec<Piece>>,
    /// The edge limit the split used (grown from the one asked for until the budget
    /// held), m.
    pub edge_m: f32,
}

fn tessellate_mesh(mesh: &Mesh, split: &[bool], max_edge_m: f32) -> (Mesh, Vec<Piece>) {
    let mut pieces = Vec::with_capacity(split.len());
    let mut out = Mesh {
        name: mesh.name.clone(),
        material: mesh.material.clone(),
        surface: mesh.surface,
        sea: mesh.sea,
        ..Mesh::default()
    };
    for (t, &split) in mesh.indices.chunks_exact(3).zip(split) {
        let k = if split {
            splits(mesh, t, max_edge_m)
        } else {
            1
        };
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
        let first = out.indices.len();
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
        pieces.push(Piece {
            fine: first..out.indices.len(),
            coarse: [at(0, 0), at(k, 0), at(0, k)],
            split: k > 1,
        });
    }
    (out, pieces)
}

impl Scene {
    /// This prepared scene with the triangles the snow raises over `ground` split to
    /// edges no longer than about `max_edge_m`, in at most `max_triangles` triangles
    /// (the edge limit grows until it fits; the triangles kept whole count once); see
    /// the module docs. `max_edge_m` must be positive.
    #[must_use]
    pub fn tessellated(
        &self,
        max_edge_m: f32,
        max_triangles: u64,
        ground: &GroundMap,
    ) -> Tessellation {
        let mut edge = if max_edge_m.is_finite() && max_edge_m > 0.0 {
            max_edge_m
        } else {
            1.0
        };
        let split = displaceable_triangles(self, edge, ground);
        while triangle_count(self, &split, edge) > max_triangles.max(1) && edge < 1.0e9 {
            edge *= 1.5;
        }
        let (meshes, pieces) = self
            .meshes
            .iter()
            .zip(&split)
            .map(|(m, s)| tessellate_mesh(m, s, edge))
            .unzip();
        Tessellation {
            scene: Self { meshes },
            pieces,
            edge_m: edge,
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

    fn open_ground() -> GroundMap {
        GroundMap::flat(
            precip_cover::GridFrame::centred(
                Vec2::ZERO,
                Vec2::splat(2000.0),
                glam::UVec2::splat(64),
            ),
            0.0,
            1.0,
        )
    }

    #[test]
    fn splits_keep_area_and_attributes() {
        let scene = plane(10.0);
        let fine = scene.tessellated(1.0, 1_000_000, &open_ground()).scene;
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

    #[test]
    fn water_bodies_are_kept_whole_and_the_sea_stays_the_sea() {
        // A 10 m pond and a 10 m sea: nothing raises them, so neither is split, and
        // the tags go through.
        let mut scene = plane(10.0);
        scene.meshes[0].surface = Some(precip_cover::Surface::Water);
        let sea = Mesh {
            sea: true,
            ..scene.meshes[0].clone()
        };
        scene.meshes.push(sea);
        let out = scene.tessellated(1.0, 1_000_000, &open_ground()).scene;
        assert!(out.meshes.iter().all(|m| m.indices.len() == 6));
        assert!(!out.meshes[0].is_sea() && out.meshes[1].is_sea());
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
        let capped = scene.tessellated(0.1, 5_000, &open_ground()).scene;
        assert!(capped.meshes[0].indices.len() / 3 <= 5_000);
        assert!(capped.meshes[0].indices.len() / 3 >= 2);
    }

    #[test]
    fn only_what_the_snow_raises_is_split() {
        let flat = plane(10.0);
        let open = flat.tessellated(1.0, 1_000_000, &open_ground()).scene;
        assert_eq!(open.meshes[0].indices.len() / 3, 2 * 225);
        // The same plane 3 m under a roof (the ground map's top is the roof).
        let roofed = GroundMap::flat(
            precip_cover::GridFrame::centred(Vec2::ZERO, Vec2::splat(20.0), glam::UVec2::splat(20)),
            3.0,
            1.0,
        );
        let sheltered = flat.tessellated(1.0, 1_000_000, &roofed).scene;
        assert_eq!(sheltered.meshes[0].indices.len() / 3, 2, "kept whole");
        // Ineligible: kept whole.
        let mut bare = flat.clone();
        bare.meshes[0].snow_eligibility.fill(0.0);
        assert_eq!(
            bare.tessellated(1.0, 1_000_000, &open_ground())
                .scene
                .meshes[0]
                .indices
                .len()
                / 3,
            2
        );
        // Standing up as a wall: kept whole.
        let mut wall = flat.clone();
        let mesh = &mut wall.meshes[0];
        for (p, n) in mesh.positions_m.iter_mut().zip(&mut mesh.normals) {
            *p = Vec3::new(p.x, p.z, 0.0);
            *n = Vec3::Z;
        }
        assert_eq!(
            wall.tessellated(1.0, 1_000_000, &open_ground())
                .scene
                .meshes[0]
                .indices
                .len()
                / 3,
            2
        );
    }

    #[test]
    fn the_built_in_house_splits_its_roof_and_ground_but_not_its_walls() {
        let scene = crate::scene::builtin::house_on_plane()
            .prepare()
            .expect("valid")
            .0
            .into_scene();
        let (lo, hi) = scene.bounds_m().expect("not empty");
        let centre = 0.5 * (Vec2::new(lo.x, lo.z) + Vec2::new(hi.x, hi.z));
        let size = Vec2::new(hi.x - lo.x, hi.z - lo.z);
        let ground = GroundMap::from_scene(
            &scene,
            precip_cover::GridFrame::centred(centre, size, glam::UVec2::splat(128)),
        );
        let split = scene.tessellated(0.5, u64::MAX, &ground).scene;
        let triangles = |s: &Scene, name: &str| {
            s.meshes
                .iter()
                .find(|m| m.name == name)
                .map_or(0, |m| m.indices.len() / 3)
        };
        assert_eq!(triangles(&split, "walls"), triangles(&scene, "walls"));
        assert!(triangles(&split, "roof") > 4 * triangles(&scene, "roof"));
        assert!(triangles(&split, "ground") > 4 * triangles(&scene, "ground"));
        // Everything split, as before the rule: more triangles for nothing.
        let everything: u64 = scene
            .meshes
            .iter()
            .flat_map(|m| m.indices.chunks_exact(3).map(move |t| (m, t)))
            .map(|(m, t)| u64::from(splits(m, t, 0.5)).pow(2))
            .sum();
        let total: usize = split.meshes.iter().map(|m| m.indices.len() / 3).sum();
        println!(
            "house at 0.5 m: {total} triangles split where the snow rises, {everything} split everywhere"
        );
        assert!((total as u64) < everything);
    }
}
