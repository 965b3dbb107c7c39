//! The scene packed for a GPU backend: tessellated for the snow's displacement, every
//! mesh's vertices in one [`SceneVertex`] list, indices offset by each mesh's first
//! vertex, and each mesh's index range — the same bytes for the wgpu and Vulkan
//! backends, which only upload them — with the displacement's level of detail
//! ([`SceneLod`]): the split triangles grouped in square tiles of [`LOD_TILE_M`], each
//! tile's fine triangles and its coarse ones (the input triangles) side by side in
//! the index buffer, so a frame draws the fine ones only near the camera
//! ([`SceneLod::ranges`], within [`crate::scene::displacement::detail_distance_m`]).
//!
//! Where a fine tile meets a coarse one the shared edge has the fine side's extra
//! vertices raised by the snow and the coarse side's not: a hairline may open there
//! where the depth changes along the edge, at the detail distance (an edge spans 4 px
//! there) and beyond.

use std::collections::BTreeMap;
use std::ops::Range;

use glam::Vec3;

use crate::backend::error::BackendError;
use crate::drawing::render::RenderSettings;
use crate::host::SceneVertex;
use crate::particles::ground::GroundMap;
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
    /// What to draw of each mesh, by distance.
    pub lod: SceneLod,
}

/// Side of the square tiles the level of detail chooses by, m.
pub const LOD_TILE_M: f32 = 8.0;

/// A tile of a mesh's split triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct LodTile {
    /// Its vertices' box, m.
    pub bounds_m: (Vec3, Vec3),
    /// Its fine triangles' indices.
    pub fine: Range<u32>,
    /// Its coarse triangles' indices.
    pub coarse: Range<u32>,
}

/// One mesh's level of detail.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeshLod {
    /// The triangles never split (drawn always).
    pub always: Range<u32>,
    /// Their vertices' box, m (inverted when there are none).
    pub always_bounds_m: (Vec3, Vec3),
    /// The tiles of split triangles.
    pub tiles: Vec<LodTile>,
}

/// The scene's level of detail for the snow's displacement.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SceneLod {
    /// Per mesh, in mesh order.
    pub meshes: Vec<MeshLod>,
    /// The fine triangles' edge limit, m.
    pub edge_m: f32,
}

impl SceneLod {
    /// How far the fine triangles are drawn in `view`
    /// ([`crate::scene::displacement::detail_distance_m`] at its centre pixel's angle), m.
    #[must_use]
    pub fn detail_distance_m(&self, view: &crate::backend::camera::View) -> f32 {
        let pixel_angle =
            2.0 * (0.5 * view.camera.vertical_fov_rad).tan() / view.height_px.max(1) as f32;
        crate::scene::displacement::detail_distance_m(self.edge_m, pixel_angle)
    }

    /// The index ranges to draw of mesh `mesh` seen from `camera_m`: its kept
    /// triangles, and each tile's fine triangles when the tile's box is within
    /// `detail_distance_m` of the camera, else its coarse ones; only the tiles
    /// `cull` may see (all without one).
    pub fn ranges(
        &self,
        mesh: usize,
        camera_m: Vec3,
        detail_distance_m: f32,
        cull: Option<TileCull>,
    ) -> impl Iterator<Item = Range<u32>> + '_ {
        self.ranges_with_distance(mesh, camera_m, detail_distance_m, (cull, None))
            .map(|(_, r)| r)
    }

    /// [`Self::ranges`] in `region` (all without one), each with how near
    /// `camera_m` its triangles' box comes, m.
    fn ranges_with_distance(
        &self,
        mesh: usize,
        camera_m: Vec3,
        detail_distance_m: f32,
        (cull, region): (Option<TileCull>, Option<TileRegion>),
    ) -> impl Iterator<Item = (f32, Range<u32>)> + '_ {
        let nearest_m = move |(lo, hi): (Vec3, Vec3)| camera_m.clamp(lo, hi).distance(camera_m);
        let in_region = move |bounds_m| region.is_none_or(|r| r.takes(bounds_m));
        let lod = self.meshes.get(mesh);
        lod.filter(|m| !m.always.is_empty() && in_region(m.always_bounds_m))
            .map(|m| (nearest_m(m.always_bounds_m), m.always.clone()))
            .into_iter()
            .chain(lod.into_iter().flat_map(move |m| {
                m.tiles
                    .iter()
                    .filter(move |t| {
                        cull.is_none_or(|c| c.may_see(t.bounds_m)) && in_region(t.bounds_m)
                    })
                    .map(move |t| {
                        let d = nearest_m(t.bounds_m);
                        if d <= detail_distance_m {
                            (d, t.fine.clone())
                        } else {
                            (d, t.coarse.clone())
                        }
                    })
            }))
            .filter(|(_, r)| !r.is_empty())
    }

    /// The ranges of every mesh of `meshes` ([`Self::ranges`]) in `region` (all
    /// without one), nearest to `camera_m` first (by their boxes; equal ones in
    /// mesh and index order).
    ///
    /// The scene's draws test depth less-or-equal: a fragment behind one already
    /// drawn is rejected before it is shaded, one drawn before what hides it is
    /// shaded for nothing. Front to back, a pixel's hidden surfaces are mostly
    /// rejected — on a CPU rasteriser, which shades every fragment that passes
    /// (lavapipe: the demo's scene pass 225 → 200 ms at 1280×720), and on a
    /// GPU's early depth test alike. The image is the same but where two surfaces
    /// meet at exactly the same depth (there the later draw wins, as before).
    #[must_use]
    pub fn front_to_back(
        &self,
        meshes: impl IntoIterator<Item = usize>,
        camera_m: Vec3,
        detail_distance_m: f32,
        within: (Option<TileCull>, Option<TileRegion>),
    ) -> Vec<DrawnRange> {
        let mut drawn: Vec<DrawnRange> = meshes
            .into_iter()
            .flat_map(|mesh| {
                self.ranges_with_distance(mesh, camera_m, detail_distance_m, within)
                    .map(move |(nearest_m, indices)| DrawnRange {
                        mesh,
                        indices,
                        nearest_m,
                    })
            })
            .collect();
        drawn.sort_by(|a, b| {
            a.nearest_m
                .total_cmp(&b.nearest_m)
                .then(a.mesh.cmp(&b.mesh))
                .then(a.indices.start.cmp(&b.indices.start))
        });
        drawn
    }
}

/// A rectangle of the ground (x and z, m) and the side of it a draw takes: the
/// tiles (and kept triangles) whose box lies wholly inside it, or the others. The
/// scene's tiles on the cover grid's interior
/// ([`crate::host::grid_interior_m`]) are drawn by a fragment shader that reads no
/// far cover, the rest by the one that does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TileRegion {
    /// The (x, z) corners, lower and upper, m.
    pub rect_m: (glam::Vec2, glam::Vec2),
    /// Take the boxes wholly inside (else the others).
    pub inside: bool,
}

impl TileRegion {
    /// Whether a draw in this region takes the box `(lo, hi)`.
    #[must_use]
    pub fn takes(&self, (lo, hi): (Vec3, Vec3)) -> bool {
        let (a, b) = self.rect_m;
        let within = lo.x >= a.x && lo.z >= a.y && hi.x <= b.x && hi.z <= b.y;
        within == self.inside
    }
}

/// A range of a mesh's indices to draw ([`SceneLod::front_to_back`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnRange {
    /// The mesh's index.
    pub mesh: usize,
    /// Its indices to draw.
    pub indices: Range<u32>,
    /// How near the camera their triangles' box comes, m.
    pub nearest_m: f32,
}

/// How high snow may raise a tile's vertices above its box for culling, m (the
/// displacement is the cover's depth, not known on the host: a deep drift).
pub const TILE_SNOW_MARGIN_M: f32 = 10.0;

/// Which tiles a pass may see: those whose box (raised by [`TILE_SNOW_MARGIN_M`])
/// reaches into the clip volume of `view_proj` within the rectangle `ndc`
/// (`x0, y0, x1, y1`, y up) and above `floor_m`. A tile outside is not drawn: its
/// vertices would be shaded and every triangle clipped (a CPU rasteriser pays for
/// each).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TileCull {
    /// World → clip of the pass.
    pub view_proj: glam::Mat4,
    /// The part of the target drawn, normalised device coordinates.
    pub ndc: [f32; 4],
    /// Nothing below this height is drawn, m.
    pub floor_m: f32,
}

impl TileCull {
    /// All of the target of `view_proj`.
    #[must_use]
    pub const fn whole(view_proj: glam::Mat4) -> Self {
        Self {
            view_proj,
            ndc: [-1.0, -1.0, 1.0, 1.0],
            floor_m: f32::NEG_INFINITY,
        }
    }

    /// Whether the box `(lo, hi)` may show: false only when all its corners lie
    /// outside one plane of the clip volume (conservative: a box near a corner of
    /// the volume may be kept), or it lies below the floor.
    #[must_use]
    pub fn may_see(&self, (lo, hi): (Vec3, Vec3)) -> bool {
        let hi = hi + Vec3::Y * TILE_SNOW_MARGIN_M;
        if hi.y < self.floor_m {
            return false;
        }
        let [x0, y0, x1, y1] = self.ndc;
        let corners = (0..8).map(|k| {
            let p = Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            self.view_proj * p.extend(1.0)
        });
        // Each plane as a · (x, y, z, w) ≥ 0 inside.
        let planes = [
            glam::Vec4::new(1.0, 0.0, 0.0, -x0),
            glam::Vec4::new(-1.0, 0.0, 0.0, x1),
            glam::Vec4::new(0.0, 1.0, 0.0, -y0),
            glam::Vec4::new(0.0, -1.0, 0.0, y1),
            glam::Vec4::new(0.0, 0.0, 1.0, 0.0),
            glam::Vec4::new(0.0, 0.0, -1.0, 1.0),
        ];
        let clips: Vec<glam::Vec4> = corners.collect();
        !planes
            .iter()
            .any(|plane| clips.iter().all(|c| plane.dot(*c) < 0.0))
    }
}

/// Index position as `u32`.
fn at(len: usize) -> Result<u32, BackendError> {
    u32::try_from(len).map_err(|_| too_big("indices"))
}

fn too_big(what: &str) -> BackendError {
    BackendError::Setup {
        field: "scene",
        problem: format!(
            "its {what} exceed what 32-bit indices address: raise render.tessellation_edge_m or lower render.max_scene_triangles"
        ),
    }
}

/// The eligibility a water body's vertices carry: no snow lies on it, and the
/// scene's fragment shader draws it as open water (`fs_scene`).
pub const WATER_BODY_ELIGIBILITY: f32 = -1.0;

impl PackedScene {
    /// Tessellates `scene` (prepared: complete attributes) where the snow over
    /// `ground` raises it, as `settings` say, and packs it.
    pub fn new(
        scene: &Scene,
        settings: &RenderSettings,
        ground: &GroundMap,
    ) -> Result<Self, BackendError> {
        let tessellation = scene.tessellated(
            settings.tessellation_edge_m,
            settings.max_scene_triangles,
            ground,
        );
        let scene = tessellation.scene;
        let mut lod = SceneLod {
            meshes: Vec::with_capacity(scene.meshes.len()),
            edge_m: tessellation.edge_m,
        };
        let mut vertices: Vec<SceneVertex> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let mut ranges = Vec::with_capacity(scene.meshes.len());
        for (mesh, pieces) in scene.meshes.iter().zip(&tessellation.pieces) {
            let base = u32::try_from(vertices.len()).map_err(|_| too_big("vertices"))?;
            let water_body = mesh.is_water_body();
            for (i, p) in mesh.positions_m.iter().enumerate() {
                vertices.push(SceneVertex {
                    position_m: p.to_array(),
                    normal: mesh.normals[i].to_array(),
                    uv: mesh.uvs[i].to_array(),
                    eligibility: if water_body {
                        WATER_BODY_ELIGIBILITY
                    } else {
                        mesh.snow_eligibility[i]
                    },
                });
            }
            let start = at(indices.len())?;
            // Kept triangles first, then each tile's fine and coarse triangles.
            for piece in pieces.iter().filter(|p| !p.split) {
                indices.extend(piece.coarse.iter().map(|i| i + base));
            }
            let always = start..at(indices.len())?;
            let mut always_bounds_m = (Vec3::INFINITY, Vec3::NEG_INFINITY);
            for &i in &indices[always.start as usize..always.end as usize] {
                let p = mesh.positions_m[(i - base) as usize];
                always_bounds_m = (always_bounds_m.0.min(p), always_bounds_m.1.max(p));
            }
            let mut by_tile: BTreeMap<(i64, i64), Vec<&crate::scene::tessellate::Piece>> =
                BTreeMap::new();
            for piece in pieces.iter().filter(|p| p.split) {
                let [a, b, c] = piece.coarse.map(|i| mesh.positions_m[i as usize]);
                let centre = (a + b + c) / 3.0;
                let key = (
                    (centre.x / LOD_TILE_M).floor() as i64,
                    (centre.z / LOD_TILE_M).floor() as i64,
                );
                by_tile.entry(key).or_default().push(piece);
            }
            let mut tiles = Vec::with_capacity(by_tile.len());
            for tile in by_tile.values() {
                let fine_start = at(indices.len())?;
                let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
                for piece in tile {
                    for &i in &mesh.indices[piece.fine.clone()] {
                        indices.push(i + base);
                        lo = lo.min(mesh.positions_m[i as usize]);
                        hi = hi.max(mesh.positions_m[i as usize]);
                    }
                }
                let coarse_start = at(indices.len())?;
                for piece in tile {
                    indices.extend(piece.coarse.iter().map(|i| i + base));
                }
                tiles.push(LodTile {
                    bounds_m: (lo, hi),
                    fine: fine_start..coarse_start,
                    coarse: coarse_start..at(indices.len())?,
                });
            }
            let end = at(indices.len())?;
            ranges.push(start..end);
            lod.meshes.push(MeshLod {
                always,
                always_bounds_m,
                tiles,
            });
        }
        Ok(Self {
            scene,
            vertices,
            indices,
            ranges,
            lod,
        })
    }

    /// Triangles in the index buffer (fine and coarse).
    #[must_use]
    pub fn triangles(&self) -> u64 {
        self.indices.len() as u64 / 3
    }

    /// Triangles drawn from `camera_m` with `detail_distance_m`.
    #[must_use]
    pub fn triangles_drawn(&self, camera_m: Vec3, detail_distance_m: f32) -> u64 {
        (0..self.lod.meshes.len())
            .flat_map(|m| self.lod.ranges(m, camera_m, detail_distance_m, None))
            .map(|r| u64::from(r.end - r.start) / 3)
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::house_on_plane;

    #[test]
    fn every_mesh_indexes_its_own_vertices() {
        let scene = house_on_plane().prepare().expect("valid").0;
        let ground = crate::backend::setup::Setup::over_flat_ground(60.0, 64, 10.0, 1).ground;
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

    /// The house on its plane, prepared and packed over a ground map of its
    /// extent; its bounds.
    fn house_packed() -> (crate::scene::PreparedScene, PackedScene, (Vec3, Vec3)) {
        let scene = house_on_plane().prepare().expect("valid").0;
        let (lo, hi) = scene.bounds_m().expect("not empty");
        let ground = GroundMap::from_scene(
            &scene,
            precip_cover::GridFrame::centred(
                glam::Vec2::new(0.5 * (lo.x + hi.x), 0.5 * (lo.z + hi.z)),
                glam::Vec2::new(hi.x - lo.x, hi.z - lo.z),
                glam::UVec2::splat(128),
            ),
        );
        let packed = PackedScene::new(&scene, &RenderSettings::default(), &ground).expect("packs");
        (scene, packed, (lo, hi))
    }

    #[test]
    fn near_tiles_draw_fine_far_tiles_coarse_and_every_triangle_once() {
        let (scene, packed, (lo, hi)) = house_packed();
        let fine: u64 = packed
            .scene
            .meshes
            .iter()
            .map(|m| m.indices.len() as u64 / 3)
            .sum();
        let coarse: u64 = scene
            .meshes
            .iter()
            .map(|m| m.indices.len() as u64 / 3)
            .sum();
        let centre = 0.5 * (lo + hi);
        // Everything near: the fine scene; everything far: the input scene.
        assert_eq!(packed.triangles_drawn(centre, 1.0e6), fine);
        assert_eq!(
            packed.triangles_drawn(centre + Vec3::Y * 1.0e5, 10.0),
            coarse
        );
        // Between: some tiles fine, the rest coarse.
        let corner = Vec3::new(lo.x, 1.7, lo.z);
        let mixed = packed.triangles_drawn(corner, 12.0);
        assert!(
            coarse < mixed && mixed < fine,
            "{coarse} < {mixed} < {fine}"
        );
        // Each mesh's ranges lie in its own range.
        for (m, range) in packed.ranges.iter().enumerate() {
            for r in packed.lod.ranges(m, corner, 12.0, None) {
                assert!(range.start <= r.start && r.end <= range.end);
            }
        }
    }

    #[test]
    fn front_to_back_draws_every_range_once_nearest_first() {
        let (_, packed, (lo, hi)) = house_packed();
        let meshes = packed.lod.meshes.len();
        for camera in [Vec3::new(lo.x, 1.7, lo.z), Vec3::new(hi.x, 30.0, 0.0)] {
            let drawn = packed
                .lod
                .front_to_back(0..meshes, camera, 12.0, (None, None));
            // The same ranges as mesh by mesh, each once.
            let mut by_mesh: Vec<(usize, u32, u32)> = (0..meshes)
                .flat_map(|m| {
                    packed
                        .lod
                        .ranges(m, camera, 12.0, None)
                        .map(move |r| (m, r.start, r.end))
                })
                .collect();
            let mut sorted: Vec<(usize, u32, u32)> = drawn
                .iter()
                .map(|d| (d.mesh, d.indices.start, d.indices.end))
                .collect();
            by_mesh.sort_unstable();
            sorted.sort_unstable();
            assert_eq!(sorted, by_mesh);
            assert!(drawn.len() > meshes, "the ground's tiles among them");
            // Nearest first, each distance its range's vertices' nearest or less.
            for pair in drawn.windows(2) {
                assert!(pair[0].nearest_m <= pair[1].nearest_m);
            }
            for d in &drawn {
                let nearest = packed.indices[d.indices.start as usize..d.indices.end as usize]
                    .iter()
                    .map(|&i| Vec3::from(packed.vertices[i as usize].position_m).distance(camera))
                    .fold(f32::INFINITY, f32::min);
                assert!(
                    d.nearest_m <= nearest + 1.0e-3,
                    "{} > {nearest}",
                    d.nearest_m
                );
            }
        }
        // A subset of the meshes draws only theirs.
        let one = packed
            .lod
            .front_to_back([0], Vec3::ZERO, 12.0, (None, None));
        assert!(one.iter().all(|d| d.mesh == 0));
        // A region's inside and outside split the ranges between them.
        let all = packed
            .lod
            .front_to_back(0..meshes, Vec3::ZERO, 12.0, (None, None));
        let rect_m = (
            glam::Vec2::new(lo.x + 8.0, lo.z + 8.0),
            glam::Vec2::new(hi.x - 8.0, hi.z - 8.0),
        );
        let [inside, outside] = [true, false].map(|inside| {
            let region = TileRegion { rect_m, inside };
            packed
                .lod
                .front_to_back(0..meshes, Vec3::ZERO, 12.0, (None, Some(region)))
        });
        assert!(!inside.is_empty() && !outside.is_empty());
        assert_eq!(inside.len() + outside.len(), all.len());
        for d in &inside {
            for &i in &packed.indices[d.indices.start as usize..d.indices.end as usize] {
                let p = Vec3::from(packed.vertices[i as usize].position_m);
                assert!(
                    p.x >= rect_m.0.x
                        && p.z >= rect_m.0.y
                        && p.x <= rect_m.1.x
                        && p.z <= rect_m.1.y
                );
            }
        }
    }

    #[test]
    fn tiles_out_of_a_pass_s_view_are_culled() {
        use crate::backend::camera::Camera;
        let camera = Camera {
            position_m: Vec3::new(0.0, 2.0, 0.0),
            forward: Vec3::NEG_Z,
            ..Camera::default()
        };
        let view_proj = crate::drawing::render::view_projection(&camera, 1.5);
        let cull = TileCull::whole(view_proj);
        let tile = |x: f32, z: f32| (Vec3::new(x, 0.0, z), Vec3::new(x + 8.0, 0.5, z + 8.0));
        assert!(cull.may_see(tile(-4.0, -20.0)), "ahead");
        assert!(cull.may_see(tile(-4.0, -4.0)), "around the camera");
        assert!(!cull.may_see(tile(-4.0, 10.0)), "behind");
        assert!(!cull.may_see(tile(200.0, -20.0)), "far to the right");
        assert!(!cull.may_see(tile(-4.0, -2.0e4)), "beyond the far plane");
        // Snow may raise a tile just below the view into it; far below, not.
        assert!(cull.may_see((Vec3::new(-4.0, -12.0, -30.0), Vec3::new(4.0, -11.0, -22.0))));
        assert!(!cull.may_see((
            Vec3::new(-4.0, -200.0, -20.0),
            Vec3::new(4.0, -150.0, -12.0)
        )));
        // A part of the target: the left half sees only what is left.
        let left = TileCull {
            ndc: [-1.0, -1.0, 0.0, 1.0],
            ..cull
        };
        assert!(left.may_see(tile(-12.0, -20.0)));
        assert!(!left.may_see(tile(6.0, -20.0)));
        // The floor: a tile wholly below it is cut.
        let floored = TileCull {
            floor_m: 20.0,
            ..cull
        };
        assert!(!floored.may_see(tile(-4.0, -20.0)));
    }
}
