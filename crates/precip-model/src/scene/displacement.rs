//! Where the snow's displacement raises a surface (docs/model.md §4, beyond seed 003): the
//! vertex shader's rule, and from it which triangles need vertices to move.
//!
//! A vertex rises by the cover's depth × its eligibility × [`upward`] × [`exposed`]:
//! only eligible, sky-facing surfaces that are the top-most at their `(x, z)` (no
//! roof above) carry snow. [`Scene::tessellated`](crate::scene::Scene) splits only
//! the triangles where some point rises; walls, ceilings, sheltered floors and
//! ineligible meshes keep their triangles, so the triangle budget goes where the
//! displacement shows.
//!
//! WGSL twins: `upward`, `exposure` and `displaced` in `shaders/render_scene.wgsl`.

use glam::{Vec2, Vec3};

use crate::particles::ground::GroundMap;

/// How much a surface faces up for snow: none below `n.y = 0.2`, full from 0.6
/// (`smoothstep`).
#[must_use]
pub fn upward(normal: Vec3) -> f32 {
    let t = ((normal.y - 0.2) / 0.4).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// How far below the top-most surface a point still counts as on it, m: 5 cm plus
/// half a ground texel (the ground map's heights are texel samples). WGSL reads it as
/// `RenderParams.cover_look2.z`.
#[must_use]
pub fn exposure_tolerance_m(ground_cell_m: Vec2) -> f32 {
    0.05 + 0.5 * ground_cell_m.max_element().min(1.0e3)
}

/// Whether the point `world_m` on a surface of `normal` is the top-most surface
/// under the sky (off the ground map: yes). A sloped surface gets more tolerance, up
/// to four texels, as its height changes across a texel.
#[must_use]
pub fn exposed(ground: &GroundMap, world_m: Vec3, normal: Vec3, tolerance_m: f32) -> bool {
    let Some(top_m) = ground.height_at(Vec2::new(world_m.x, world_m.z)) else {
        return true;
    };
    let cell = ground.frame.cell_m();
    let slope = Vec2::new(normal.x, normal.z).length() / normal.y.abs().max(0.05);
    let tolerance = tolerance_m + cell.max_element() * slope.min(4.0);
    world_m.y >= top_m - tolerance
}

/// Whether the displacement raises a vertex at `position_m` of `normal` and
/// `eligibility` at all (for some snow depth).
#[must_use]
pub fn raised(ground: &GroundMap, position_m: Vec3, normal: Vec3, eligibility: f32) -> bool {
    let n = normal.normalize_or_zero();
    eligibility > 0.0
        && upward(n) > 0.0
        && exposed(
            ground,
            position_m,
            n,
            exposure_tolerance_m(ground.frame.cell_m()),
        )
}

/// The fewest pixels a tessellated edge spans where the fine triangles are drawn.
pub const DETAIL_MIN_PX: f32 = 4.0;

/// How far from the camera the displacement's fine triangles are drawn, m: where an
/// edge of `edge_m` spans [`DETAIL_MIN_PX`] pixels of `pixel_angle_rad` (beyond, the
/// snow's relief within a triangle is under a few pixels and the coarse triangles,
/// raised at their corners, show it).
#[must_use]
pub fn detail_distance_m(edge_m: f32, pixel_angle_rad: f32) -> f32 {
    edge_m / (DETAIL_MIN_PX * pixel_angle_rad.max(1.0e-6))
}

#[cfg(test)]
mod tests {
    use super::*;
    use precip_cover::GridFrame;

    fn ground_at(height_m: f32) -> GroundMap {
        GroundMap::flat(
            GridFrame::centred(Vec2::ZERO, Vec2::splat(20.0), glam::UVec2::splat(20)),
            height_m,
            1.0,
        )
    }

    #[test]
    fn only_eligible_upward_top_most_surfaces_rise() {
        let ground = ground_at(0.0);
        assert!(raised(&ground, Vec3::ZERO, Vec3::Y, 1.0));
        assert!(!raised(&ground, Vec3::ZERO, Vec3::Y, 0.0), "ineligible");
        assert!(!raised(&ground, Vec3::ZERO, Vec3::X, 1.0), "a wall");
        assert!(!raised(&ground, Vec3::ZERO, -Vec3::Y, 1.0), "a ceiling");
        let roofed = ground_at(3.0);
        assert!(!raised(&roofed, Vec3::ZERO, Vec3::Y, 1.0), "under a roof");
        assert!(
            raised(&roofed, Vec3::new(0.0, 3.0, 0.0), Vec3::Y, 1.0),
            "the roof"
        );
        assert!(
            raised(&roofed, Vec3::new(50.0, 0.0, 0.0), Vec3::Y, 1.0),
            "off the map"
        );
    }

    #[test]
    fn detail_reaches_where_an_edge_spans_four_pixels() {
        // 60° over 720 px: 1.6 mrad a pixel at the centre; a 0.5 m edge spans 4 px at 78 m.
        let pixel = 2.0 * (30f32.to_radians()).tan() / 720.0;
        assert!(
            (detail_distance_m(0.5, pixel) - 77.9).abs() < 0.5,
            "{}",
            detail_distance_m(0.5, pixel)
        );
    }

    #[test]
    fn upward_is_a_smoothstep_from_0_2_to_0_6() {
        assert!(upward(Vec3::new(0.0, 0.2, 0.0)).abs() < 1e-6);
        assert!((upward(Vec3::new(0.0, 0.4, 0.0)) - 0.5).abs() < 1e-6);
        assert!((upward(Vec3::Y) - 1.0).abs() < 1e-6);
    }
}
