//! Where land classes meet on the drawn terrain (docs/model.md (5.17)).
//!
//! A land-cover raster (WorldCover's 10 m pixels, or coarser on the GPU) looked up
//! at the nearest pixel draws every border between two classes along the pixels'
//! edges: seen from a helicopter, a forest's edge or a glacier's is a staircase of
//! 10 m steps, which the terrain's warped lookup (the cover's smooth noise) only
//! bends into a sawtooth. Here the class at a point is the one that holds the most
//! of the bilinear weight of the four pixels round it: where two classes meet it
//! is the one whose share of the bilinear blend of their indicators passes one
//! half, so the border runs along the contour of that blend — straight across a
//! straight raster edge, along the diagonal of a staircase, a rounded corner at a
//! corner — and never along a pixel's edge but where the raster's edge is one. Each
//! point still gets exactly one class (the far cover's texel of its surface and
//! its snow share are a class's, not a blend of two).
//!
//! WGSL twin: `land_class_pick` in `shaders/drawing.wgsl` (read by `land_class_at`
//! in precip-gpu's render_terrain.wgsl).

use glam::Vec2;

/// The class drawn at fraction `f` (`[0, 1]²`) of the way between the centres of
/// four raster pixels whose classes are `corners` (x0z0, x1z0, x0z1, x1z1): the
/// class with the largest sum of the bilinear weights of the pixels that hold it,
/// the first corner's on a tie.
#[must_use]
pub fn land_class_pick(corners: [u32; 4], f: Vec2) -> u32 {
    let w = [
        (1.0 - f.x) * (1.0 - f.y),
        f.x * (1.0 - f.y),
        (1.0 - f.x) * f.y,
        f.x * f.y,
    ];
    let mut best = 0;
    let mut best_weight = -1.0;
    for k in 0..4 {
        let mut weight = 0.0;
        for j in 0..4 {
            if corners[j] == corners[k] {
                weight += w[j];
            }
        }
        if weight > best_weight {
            best = k;
            best_weight = weight;
        }
    }
    corners[best]
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn at_a_pixel_s_centre_its_own_class_is_drawn() {
        assert_eq!(land_class_pick([3, 5, 5, 5], Vec2::ZERO), 3);
        assert_eq!(land_class_pick([3, 5, 7, 9], Vec2::new(1.0, 0.0)), 5);
        assert_eq!(land_class_pick([3, 5, 7, 9], Vec2::new(0.0, 1.0)), 7);
        assert_eq!(land_class_pick([3, 5, 7, 9], Vec2::ONE), 9);
    }

    #[test]
    fn a_straight_raster_edge_stays_a_straight_border_halfway() {
        // Forest west, ice east: the border is at x = ½ at every z.
        for z in [0.0, 0.3, 0.7, 1.0] {
            assert_eq!(land_class_pick([1, 2, 1, 2], Vec2::new(0.49, z)), 1);
            assert_eq!(land_class_pick([1, 2, 1, 2], Vec2::new(0.51, z)), 2);
        }
    }

    /// A staircase in the raster (one class below the diagonal of its pixels)
    /// is drawn as a smooth border: at the corner pixel's cell the border is the
    /// contour where the lone corner's weight is one half, a curve, not the
    /// pixels' right angle.
    #[test]
    fn a_staircase_s_corner_is_rounded_off() {
        // Corner x1z1 is class 2, the rest class 1: class 2 where fx·fz > ½.
        let corners = [1, 1, 1, 2];
        assert_eq!(land_class_pick(corners, Vec2::new(0.9, 0.9)), 2);
        assert_eq!(land_class_pick(corners, Vec2::new(0.75, 0.6)), 1, "0.45");
        assert_eq!(land_class_pick(corners, Vec2::new(0.75, 0.7)), 2, "0.525");
        // Along the border, the class changes once going across it.
        let across: Vec<u32> = (0..=20)
            .map(|k| land_class_pick(corners, Vec2::splat(k as f32 / 20.0)))
            .collect();
        let changes = across.windows(2).filter(|w| w[0] != w[1]).count();
        assert_eq!(changes, 1, "{across:?}");
    }

    /// On a tie the first corner's class is drawn: half way across columns of
    /// two classes, and at the middle of four pixels split two by two or of four
    /// classes.
    #[test]
    fn a_tie_goes_to_the_first_corner() {
        assert_eq!(land_class_pick([2, 0, 2, 0], Vec2::new(0.5, 0.3)), 2);
        assert_eq!(land_class_pick([0, 2, 0, 2], Vec2::new(0.5, 0.3)), 0);
        assert_eq!(land_class_pick([4, 7, 7, 4], Vec2::splat(0.5)), 4);
        assert_eq!(land_class_pick([3, 1, 2, 0], Vec2::splat(0.5)), 3);
    }

    proptest! {
        /// The class drawn is one of the four, holds at least a quarter of the
        /// weight, and no other class holds more.
        #[test]
        fn the_class_drawn_holds_the_most_weight(
            corners in proptest::array::uniform4(0u32..4),
            fx in 0.0f32..=1.0,
            fz in 0.0f32..=1.0,
        ) {
            let f = Vec2::new(fx, fz);
            let w = [(1.0 - fx) * (1.0 - fz), fx * (1.0 - fz), (1.0 - fx) * fz, fx * fz];
            let weight_of = |c: u32| -> f32 {
                corners.iter().zip(w).filter(|(k, _)| **k == c).map(|(_, w)| w).sum()
            };
            let drawn = land_class_pick(corners, f);
            prop_assert!(corners.contains(&drawn));
            prop_assert!(weight_of(drawn) >= 0.25 - 1e-6);
            for c in corners {
                prop_assert!(weight_of(c) <= weight_of(drawn) + 1e-6);
            }
        }
    }
}
