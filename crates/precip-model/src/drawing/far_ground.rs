//! The ground beyond the scene (docs/model.md (6.18)): a camera above the scene's
//! ground looking down past its edge sees land, not the sky. Where no mesh stands
//! and the ray points below the horizon, it meets a level plane at the height of
//! the scene's ground at its edges ([`far_ground_level_m`]); the land there looks
//! like the scene's ground — its albedo the cover's mean over the whole grid
//! ([`far_ground_albedo`], what has fallen there fell beyond too; bare ground to
//! fresh snow, [`far_ground_colour`]) — lit
//! as the scene's level ground is (ambient plus the sun's diffuse light through the
//! clouds' share) and seen through the air as the scene is. From 4.5 km over
//! cumulus the tops stand white over a darker land, and a valley fog lies over
//! fields, where before both lay over a white void.
//!
//! WGSL twins: `far_ground_lattice_m`, `far_ground_distance_m`, `far_ground_colour`
//! (drawing.wgsl); the `drop_ground` kernel writes the albedo each frame
//! (cover_texture.wgsl), the sky's draws use them (render_scene.wgsl).

use glam::{Vec2, Vec3};
use precip_cover::{CoverGrid, CoverParams, GridFrame, ground_albedo};

use super::{BARE_GROUND_ALBEDO, DROP_GROUND_SAMPLES_PER_SIDE};
use crate::GroundMap;

/// The colour (linear) of bare land far off, albedo about [`BARE_GROUND_ALBEDO`]:
/// grass and fields. WGSL twin: `FAR_GROUND_BARE_COLOUR`.
pub const FAR_GROUND_BARE_COLOUR: Vec3 = Vec3::new(0.2, 0.28, 0.12);
/// The colour of snow per unit of its brightness, `min(1, 1.2·albedo)` as the
/// scene's snow is shaded (a faint blue: fresh snow 0.8, old snow 0.4). WGSL twin:
/// `FAR_GROUND_SNOW_TINT`.
pub const FAR_GROUND_SNOW_TINT: Vec3 = Vec3::new(1.0, 1.0, 1.03);
/// The least albedo of snow lying on the land (old snow: the cover's albedo decays
/// from 0.8 to 0.4); above it the land is all snow.
const OLD_SNOW_ALBEDO: f32 = 0.4;
/// Border texels of the ground map [`far_ground_level_m`] reads, at most.
const LEVEL_SAMPLES: usize = 64;

/// The height of the land beyond the scene, m: the median of the ground map's
/// heights along its edges (up to 64 texels spread evenly around them; a wall
/// standing on an edge does not raise it).
#[must_use]
pub fn far_ground_level_m(ground: &GroundMap) -> f32 {
    let (w, h) = (
        ground.frame.texels.x as usize,
        ground.frame.texels.y as usize,
    );
    if w == 0 || h == 0 || ground.height_m.len() < w * h {
        return 0.0;
    }
    // The edge walked round: top row, right column, bottom row, left column.
    let perimeter = if w == 1 || h == 1 {
        w * h
    } else {
        2 * (w + h) - 4
    };
    let at = |i: usize| -> usize {
        if h == 1 || w == 1 {
            return i;
        }
        if i < w {
            i
        } else if i < w + h - 1 {
            (i - w + 1) * w + (w - 1)
        } else if i < 2 * w + h - 2 {
            (h - 1) * w + (w - 1 - (i - (w + h - 1)))
        } else {
            (h - 1 - (i - (2 * w + h - 2))) * w
        }
    };
    let n = perimeter.min(LEVEL_SAMPLES);
    let mut heights: Vec<f32> = (0..n)
        .filter_map(|k| ground.height_m.get(at(k * perimeter / n)).copied())
        .filter(|y| y.is_finite())
        .collect();
    if heights.is_empty() {
        return 0.0;
    }
    let mid = heights.len() / 2;
    let (_, median, _) = heights.select_nth_unstable_by(mid, f32::total_cmp);
    *median
}

/// Point `k` of the [`DROP_GROUND_SAMPLES_PER_SIDE`]² lattice spread over the grid
/// `frame` (cell centres, row by row), m. WGSL twin: `far_ground_lattice_m`.
#[must_use]
pub fn far_ground_lattice_m(frame: &GridFrame, k: u32) -> Vec2 {
    let n = DROP_GROUND_SAMPLES_PER_SIDE;
    let cell = Vec2::new((k % n) as f32, (k / n) as f32) + Vec2::splat(0.5);
    frame.origin_m + frame.size_m * cell / n as f32
}

/// The albedo of the land beyond the scene: the cover's ground albedo averaged over
/// the [`far_ground_lattice_m`] lattice on its grid (what has fallen on the scene
/// fell beyond it too). The `drop_ground` kernel's second number.
#[must_use]
pub fn far_ground_albedo(cover: &CoverGrid, params: &CoverParams) -> f32 {
    let n = DROP_GROUND_SAMPLES_PER_SIDE * DROP_GROUND_SAMPLES_PER_SIDE;
    let sum: f32 = (0..n)
        .map(|k| {
            cover
                .frame
                .texel_index(far_ground_lattice_m(&cover.frame, k))
                .and_then(|i| cover.texels.get(i))
                .map_or(BARE_GROUND_ALBEDO, |t| {
                    ground_albedo(t, params, BARE_GROUND_ALBEDO)
                })
        })
        .sum();
    sum / n as f32
}

/// How far along a ray from a camera at height `camera_y_m`, its direction's
/// vertical component `dir_y` (of a unit direction), it meets the land at
/// `level_m`, m; `None` looking level or up, or from below the land.
/// WGSL twin: `far_ground_distance_m` (negative for none).
#[must_use]
pub fn far_ground_distance_m(camera_y_m: f32, dir_y: f32, level_m: f32) -> Option<f32> {
    (dir_y < -1e-4 && camera_y_m > level_m).then(|| (level_m - camera_y_m) / dir_y)
}

/// The far land's colour (linear, before the air): bare land to snow as the
/// ground's albedo `albedo` goes from [`BARE_GROUND_ALBEDO`] to 0.4 (old snow), the
/// snow as bright as the scene's snow of that albedo (`min(1, 1.2·albedo)`), lit as level
/// ground is by the scene's lighting — `lighting` its ambient and diffuse
/// intensities (`k_A·I_A`, `k_D·I_D`) — with the sun `sun_y` (the sine of its
/// elevation) up and `sun_share` of its light through the clouds.
/// WGSL twin: `far_ground_colour`.
#[must_use]
pub fn far_ground_colour(albedo: f32, lighting: Vec2, sun_y: f32, sun_share: f32) -> Vec3 {
    let snow =
        ((albedo - BARE_GROUND_ALBEDO) / (OLD_SNOW_ALBEDO - BARE_GROUND_ALBEDO)).clamp(0.0, 1.0);
    let white = (1.2 * albedo.max(OLD_SNOW_ALBEDO)).min(1.0);
    let base = FAR_GROUND_BARE_COLOUR.lerp(FAR_GROUND_SNOW_TINT * white, snow);
    base * (lighting.x + lighting.y * sun_y.max(0.0) * sun_share.clamp(0.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_land_lies_at_the_median_of_the_ground_s_edges() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::new(20.0, 10.0), glam::UVec2::new(20, 10));
        let mut ground = GroundMap::flat(frame, 3.0, 1.0);
        assert!((far_ground_level_m(&ground) - 3.0).abs() < 1e-6);
        // A wall along part of an edge and a hill inside leave it.
        for x in 0..5 {
            ground.height_m[x] = 12.0;
        }
        ground.height_m[5 * 20 + 10] = 40.0;
        assert!((far_ground_level_m(&ground) - 3.0).abs() < 1e-6);
        // A tilted plain: its edges' middle.
        for (i, y) in ground.height_m.iter_mut().enumerate() {
            *y = (i % 20) as f32;
        }
        let level = far_ground_level_m(&ground);
        assert!((5.0..=14.0).contains(&level), "{level}");
    }

    #[test]
    fn rays_below_the_horizon_meet_the_land() {
        // From 100 m looking 30° down: 200 m along the ray.
        let t = far_ground_distance_m(102.0, -0.5, 2.0).expect("meets it");
        assert!((t - 200.0).abs() < 1e-3);
        assert!(far_ground_distance_m(102.0, 0.1, 2.0).is_none());
        assert!(far_ground_distance_m(102.0, 0.0, 2.0).is_none());
        assert!(far_ground_distance_m(1.0, -0.5, 2.0).is_none());
    }

    #[test]
    fn the_land_is_fields_or_snow_lit_as_level_ground() {
        let lighting = Vec2::new(0.45, 0.65);
        let bare = far_ground_colour(BARE_GROUND_ALBEDO, lighting, 0.5, 1.0);
        assert!(
            (bare - FAR_GROUND_BARE_COLOUR * (0.45 + 0.65 * 0.5))
                .abs()
                .max_element()
                < 1e-6
        );
        let snow = far_ground_colour(0.8, lighting, 0.5, 1.0);
        assert!(
            (snow - FAR_GROUND_SNOW_TINT * 0.96 * (0.45 + 0.65 * 0.5))
                .abs()
                .max_element()
                < 1e-6
        );
        // Old snow is still snow, greyer.
        let old = far_ground_colour(0.4, lighting, 0.5, 1.0);
        assert!(
            (old - FAR_GROUND_SNOW_TINT * 0.48 * (0.45 + 0.65 * 0.5))
                .abs()
                .max_element()
                < 1e-5
        );
        // Under a full deck, the ambient light alone.
        let shaded = far_ground_colour(BARE_GROUND_ALBEDO, lighting, 0.5, 0.0);
        assert!((shaded - FAR_GROUND_BARE_COLOUR * 0.45).abs().max_element() < 1e-6);
        // Half snowed over: between.
        let half = far_ground_colour(0.3, lighting, 0.5, 1.0);
        assert!(half.y > bare.y && half.y < snow.y);
    }
}
