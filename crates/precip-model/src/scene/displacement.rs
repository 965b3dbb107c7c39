//! Where the snow's displacement raises a surface (docs/model.md §4, beyond seed 003): the
//! vertex shader's rule, and from it which triangles need vertices to move.
//!
//! A vertex rises by the cover's depth × its eligibility × [`upward`] × [`exposure`]:
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

/// How much the point `world_m` on a surface of `normal` is the top-most surface
/// under the sky, `[0, 1]` (off the ground map: 1): 1 within a tolerance of the
/// ground map's height there (interpolated between texels), fading to 0 over one
/// more tolerance below, so snow ends under an eave along a soft line that follows
/// no texel. A sloped surface gets more tolerance, up to four texels, as its height
/// changes across a texel. WGSL twin: `exposure` (render_scene.wgsl).
#[must_use]
pub fn exposure(ground: &GroundMap, world_m: Vec3, normal: Vec3, tolerance_m: f32) -> f32 {
    let Some(top_m) = ground.height_between_texels_at(Vec2::new(world_m.x, world_m.z)) else {
        return 1.0;
    };
    let cell = ground.frame.cell_m();
    let slope = Vec2::new(normal.x, normal.z).length() / normal.y.abs().max(0.05);
    let tolerance = tolerance_m + cell.max_element() * slope.min(4.0);
    let t = ((world_m.y - (top_m - 2.0 * tolerance)) / tolerance).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Whether [`exposure`] is above 0: the surface carries some snow.
#[must_use]
pub fn exposed(ground: &GroundMap, world_m: Vec3, normal: Vec3, tolerance_m: f32) -> bool {
    exposure(ground, world_m, normal, tolerance_m) > 0.0
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
    fn snow_ends_under_an_eave_along_a_soft_line_that_follows_no_texel() {
        // A 1 m grid, a roof 3 m up over x < 0, open ground beyond.
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(16.0), glam::UVec2::splat(16));
        let mut ground = GroundMap::flat(frame, 0.0, 1.0);
        for (i, h) in ground.height_m.iter_mut().enumerate() {
            if frame.texel_centre(i).x < 0.0 {
                *h = 3.0;
            }
        }
        let tolerance = exposure_tolerance_m(frame.cell_m());
        let at = |x: f32| exposure(&ground, Vec3::new(x, 0.0, 0.3), Vec3::Y, tolerance);
        assert!(at(-3.0).abs() < 1e-6, "under the roof");
        assert!((at(3.0) - 1.0).abs() < 1e-6, "in the open");
        // Across the eave in 1 cm steps: no jump (the old test stepped at the texel).
        let mut last = at(-3.0);
        for k in 1..=600 {
            let e = at(-3.0 + 0.01 * k as f32);
            assert!((e - last).abs() < 0.1, "{e} after {last} at step {k}");
            last = e;
        }
        // The roof itself is exposed right to its edge.
        assert!(exposure(&ground, Vec3::new(-0.2, 3.0, 0.3), Vec3::Y, tolerance) > 0.99);
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
