//! The ground map rendered from a [`Scene`]: an orthographic view straight down
//! (docs/architecture.md §2, "the ground"), rasterised on the CPU.
//!
//! Each texel takes the top-most surface under its centre: every triangle whose XZ
//! projection holds the centre offers its interpolated height, the highest wins, and
//! its interpolated snow eligibility and its mesh's surface come with it. Walls (zero XZ area) never win; a
//! roof hides the floor and the ground beneath it, so particles land on the roof and
//! the cover under the eaves belongs to the roof. Texels no triangle covers take the
//! scene's lowest height with no eligibility.
//!
//! Why on the CPU: the map is built once per scene, is an exact point sample (the
//! same test a GPU rasteriser makes at pixel centres), and every backend — the CPU
//! reference included — then lands particles on the very same heights (docs/architecture.md §5).

use glam::{Vec2, Vec3};
use precip_cover::{GridFrame, Surface};
use rayon::prelude::*;

use crate::particles::ground::GroundMap;
use crate::scene::terrain::Terrain;
use crate::scene::{PreparedScene, Scene};

/// Barycentric weights of `p` in the XZ triangle `(a, b, c)`, or `None` outside it
/// (edges included, so abutting triangles leave no gap).
fn barycentric_xz(p: Vec2, a: Vec2, b: Vec2, c: Vec2) -> Option<Vec3> {
    let area = (b - a).perp_dot(c - a);
    if area.abs() < 1e-12 {
        return None;
    }
    let w_a = (b - p).perp_dot(c - p) / area;
    let w_b = (c - p).perp_dot(a - p) / area;
    let w_c = 1.0 - w_a - w_b;
    let tolerance = -1e-6;
    (w_a >= tolerance && w_b >= tolerance && w_c >= tolerance).then_some(Vec3::new(w_a, w_b, w_c))
}

/// Calls `f(texel, weights)` for each texel centre of `frame` inside the XZ
/// projection of the triangle `corners` (texels in row order, barycentric weights).
fn for_each_centre(frame: GridFrame, corners: [Vec3; 3], mut f: impl FnMut(usize, Vec3)) {
    let cell = frame.cell_m();
    let (nx, nz) = (i64::from(frame.texels.x), i64::from(frame.texels.y));
    let [a2, b2, c2] = corners.map(|v| Vec2::new(v.x, v.z));
    let lo = (a2.min(b2).min(c2) - frame.origin_m) / cell;
    let hi = (a2.max(b2).max(c2) - frame.origin_m) / cell;
    // Texel centres (i + ½) inside [lo, hi].
    let i0 = ((lo.x - 0.5).ceil() as i64).max(0);
    let i1 = ((hi.x - 0.5).floor() as i64).min(nx - 1);
    let j0 = ((lo.y - 0.5).ceil() as i64).max(0);
    let j1 = ((hi.y - 0.5).floor() as i64).min(nz - 1);
    for j in j0..=j1 {
        for i in i0..=i1 {
            let centre = frame.origin_m + (Vec2::new(i as f32, j as f32) + 0.5) * cell;
            if let Some(w) = barycentric_xz(centre, a2, b2, c2) {
                f((i + nx * j) as usize, w);
            }
        }
    }
}

/// The lowest downward-facing face of `meshes` over each texel centre of `frame`,
/// m (rows in order; `+∞` where none lies): the underside of a deck or a box,
/// the bottom of a wall. What stands on the ground has its underside at or below
/// the ground; what floats over it (a pier's deck) has it above.
#[must_use]
pub fn lowest_undersides<'a>(
    meshes: impl Iterator<Item = &'a crate::scene::Mesh>,
    frame: GridFrame,
) -> Vec<f32> {
    let mut lowest = vec![f32::INFINITY; frame.texel_count()];
    for mesh in meshes {
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| mesh.positions_m[i as usize]);
            if (b - a).cross(c - a).y >= 0.0 {
                continue;
            }
            for_each_centre(frame, [a, b, c], |k, w| {
                let h = w.x * a.y + w.y * b.y + w.z * c.y;
                lowest[k] = lowest[k].min(h);
            });
        }
    }
    lowest
}

impl GroundMap {
    /// The top-most surface of a prepared `scene` over `frame` (see the module docs).
    /// `scene` must have been through [`Scene::prepare`] (complete attributes).
    #[must_use]
    pub fn from_scene(scene: &Scene, frame: GridFrame) -> Self {
        let floor = scene.bounds_m().map_or(0.0, |(lo, _)| lo.y);
        Self::top_down(scene.meshes.iter(), frame, floor, None)
    }

    /// The top-most surface of a prepared scene, and of the terrain it stands on if
    /// any ([`PreparedScene::on_terrain`]), over `frame`.
    #[must_use]
    pub fn of_prepared(scene: &PreparedScene, frame: GridFrame) -> Self {
        match scene.terrain() {
            Some(terrain) => Self::from_scene_and_terrain(scene, terrain, frame),
            None => Self::from_scene(scene, frame),
        }
    }

    /// The top-most of a prepared `scene` and `terrain` over `frame`: where the
    /// terrain rises above every mesh (or no mesh lies) its height, its eligibility
    /// (from its slope; none on open water) and surface (from its land cover, else
    /// its slope) ([`Terrain::eligibility_at`], [`Terrain::surface_at`]);
    /// off the terrain and the meshes the scene's lowest height, as
    /// [`GroundMap::from_scene`].
    #[must_use]
    pub fn from_scene_and_terrain(scene: &Scene, terrain: &Terrain, frame: GridFrame) -> Self {
        let floor = scene.bounds_m().map_or(0.0, |(lo, _)| lo.y);
        let mut map = Self::top_down(scene.meshes.iter(), frame, f32::NEG_INFINITY, None);
        let cell = frame.cell_m();
        let nx = frame.texels.x as usize;
        // Each texel on its own, in parallel (a 1024² map is a million terrain
        // lookups: made at configure and again at each move of a grid that follows
        // the camera).
        map.height_m
            .par_iter_mut()
            .zip(map.eligibility.par_iter_mut())
            .zip(map.surface.par_iter_mut())
            .enumerate()
            .for_each(|(k, ((h, eligibility), surface))| {
                let centre =
                    frame.origin_m + (Vec2::new((k % nx) as f32, (k / nx) as f32) + 0.5) * cell;
                match terrain.height_at(centre) {
                    Some(t) if t > *h => {
                        let normal = terrain.normal_at(centre);
                        *h = t;
                        *eligibility = terrain.eligibility_at(centre, normal);
                        *surface = terrain.surface_at(centre, normal);
                    }
                    _ if !h.is_finite() => *h = floor,
                    _ => {}
                }
            });
        map
    }

    /// The top-most surface of `meshes` (prepared) over `frame`, `floor` m where
    /// none lies; with `under`, the top-most upward face at or under that height
    /// (the bed under a level: a deck or a wall's top above it is none).
    #[must_use]
    pub fn top_down<'a>(
        meshes: impl Iterator<Item = &'a crate::scene::Mesh>,
        frame: GridFrame,
        floor: f32,
        under: Option<f32>,
    ) -> Self {
        let n = frame.texel_count();
        let mut height_m = vec![f32::NEG_INFINITY; n];
        let mut eligibility = vec![0.0; n];
        let mut surface = vec![Surface::default(); n];
        for mesh in meshes {
            for t in mesh.indices.chunks_exact(3) {
                let [ia, ib, ic] = [t[0], t[1], t[2]].map(|i| i as usize);
                let [a, b, c] = [ia, ib, ic].map(|i| mesh.positions_m[i]);
                if under.is_some() && (b - a).cross(c - a).y <= 0.0 {
                    continue;
                }
                let ceiling = under.unwrap_or(f32::INFINITY);
                let elig =
                    [ia, ib, ic].map(|i| mesh.snow_eligibility.get(i).copied().unwrap_or(0.0));
                for_each_centre(frame, [a, b, c], |k, w| {
                    let h = w.x * a.y + w.y * b.y + w.z * c.y;
                    if h > height_m[k] && h <= ceiling {
                        height_m[k] = h;
                        eligibility[k] =
                            (w.x * elig[0] + w.y * elig[1] + w.z * elig[2]).clamp(0.0, 1.0);
                        surface[k] = mesh
                            .surface
                            .unwrap_or_else(|| Surface::from_eligibility(eligibility[k]));
                    }
                });
            }
        }
        for (h, s) in height_m.iter_mut().zip(&mut surface) {
            if !h.is_finite() {
                *h = floor;
                *s = Surface::Soil;
            }
        }
        Self {
            frame,
            height_m,
            eligibility,
            surface,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::UVec2;

    use super::*;
    use crate::scene::builtin::house_on_plane;
    use crate::scene::terrain::Terrain;

    #[test]
    fn on_a_terrain_the_ground_is_the_top_most_of_the_meshes_and_the_terrain() {
        let (scene, _) = house_on_plane()
            .prepare()
            .expect("the built-in scene is valid");
        let (lo, hi) = scene.bounds_m().expect("it has vertices");
        // A terrain rising along x from 2 m under the plane at x = 0 by 1 in 4, over
        // twice the scene's width.
        let n = 41;
        let side = 2.0 * (hi.x - lo.x);
        let spacing = side / (n - 1) as f32;
        let mut h = Vec::new();
        for _ in 0..n {
            for i in 0..n {
                let x = i as f32 * spacing - 0.5 * side;
                h.push(lo.y - 2.0 + 0.25 * x);
            }
        }
        let terrain = Terrain::new(UVec2::splat(n), spacing, Vec2::ZERO, h).expect("valid");
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(side), UVec2::splat(64));
        // The meshes alone, −∞ where none lies.
        let meshes = GroundMap::top_down(scene.meshes.iter(), frame, f32::NEG_INFINITY, None);
        let both = GroundMap::from_scene_and_terrain(&scene, &terrain, frame);
        let (mut terrain_wins, mut mesh_wins, mut off_meshes) = (0, 0, 0);
        for k in 0..frame.texel_count() {
            let t = terrain
                .height_at(frame.texel_centre(k))
                .expect("on the terrain");
            let m = meshes.height_m[k];
            let expected = if m.is_finite() { m.max(t) } else { t };
            assert!(
                (both.height_m[k] - expected).abs() < 1e-4,
                "texel {k}: {} against {expected}",
                both.height_m[k]
            );
            if t > m {
                assert_eq!(
                    both.surface[k],
                    Terrain::surface_for(terrain.normal_at(frame.texel_centre(k)))
                );
                if m.is_finite() {
                    terrain_wins += 1;
                } else {
                    off_meshes += 1;
                }
            } else {
                mesh_wins += 1;
            }
        }
        // The terrain rises through the plane on one side and the plane stands over
        // it on the other; off the plane the terrain alone (not the scene's floor).
        assert!(terrain_wins > 0 && mesh_wins > 0 && off_meshes > 0);
        assert!(hi.y > lo.y);
    }

    #[test]
    fn a_roof_hides_the_ground_and_walls_never_win() {
        let (scene, _) = house_on_plane().prepare().expect("valid");
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(40.0), UVec2::splat(80));
        let map = GroundMap::from_scene(&scene, frame);
        map.validate().expect("a valid map");
        let plan = crate::scene::builtin::HousePlan::default();
        // Open ground: height 0, eligible.
        let open = Vec2::new(15.0, 15.0);
        assert!(map.height_at(open).expect("on the map").abs() < 1e-4);
        assert!(map.eligibility_at(open) > 0.99);
        // Under the ridge: the roof's top.
        let ridge = map.height_at(Vec2::new(0.0, 0.1)).expect("on the map");
        assert!((ridge - plan.ridge_height_m()).abs() < 0.2, "ridge {ridge}");
        // Under the eaves (outside the walls, inside the overhang): the roof, not the ground.
        let eave = Vec2::new(0.0, plan.depth_m / 2.0 + plan.overhang_m * 0.5);
        let h = map.height_at(eave).expect("on the map");
        assert!(h > plan.wall_height_m - 0.5, "eave texel at {h} m");
        assert!(map.eligibility_at(eave) > 0.5, "a 30° roof holds snow");
    }

    #[test]
    fn uncovered_texels_take_the_floor_with_no_eligibility() {
        let (scene, _) = house_on_plane().prepare().expect("valid");
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(400.0), UVec2::splat(40));
        let map = GroundMap::from_scene(&scene, frame);
        let far = Vec2::new(190.0, 190.0);
        assert!(map.eligibility_at(far).abs() < f32::MIN_POSITIVE);
        assert!(map.height_at(far).expect("on the map").is_finite());
    }
}
