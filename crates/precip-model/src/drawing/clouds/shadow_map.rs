//! The clouds' shadow map (docs/model.md (6.12)): the share of the sun's light that
//! reaches the ground through every layer, over a square of land around the camera,
//! written each frame by a kernel and read by every lit fragment where it lies, so
//! the clouds' shadows lie on the scene and the land beyond it and sail over them
//! with the wind. Its texels stay put on the ground as the camera moves (the square
//! is placed on whole texels: no swimming); toward its edges it fades into the
//! frame's one share at the camera, which stands in beyond
//! ([`cloud_shadow_map_weight`]: no straight edge across the land).
//!
//! WGSL twins: `cloud_shadow_map_point_m`, `cloud_shadow_map_weight` (drawing.wgsl),
//! the kernel `cloud_shadow_map` and `cloud_sun_share` (render_clouds.wgsl).

use glam::{UVec2, Vec2, Vec3};

use super::{CloudLayers, cloud_noise};

/// Texels of the clouds' shadow map along each side.
pub const CLOUD_SHADOW_MAP_PX: u32 = 128;
/// The land it spans along each side, m (125 m a texel: a cumulus spans several).
pub const CLOUD_SHADOW_MAP_SPAN_M: f32 = 16_000.0;
/// The share of the map's side over which it fades into the frame's share at
/// each edge.
pub const CLOUD_SHADOW_MAP_FADE: f32 = 0.15;

/// The side of a texel, m.
const TEXEL_M: f32 = CLOUD_SHADOW_MAP_SPAN_M / CLOUD_SHADOW_MAP_PX as f32;

/// The map's corner (least x, z) for a camera over `camera_xz_m`: centred on it,
/// on whole texels of the world's lattice. WGSL reads it from
/// `RenderParams::cloud_shadow_map`.
#[must_use]
pub fn cloud_shadow_map_origin_m(camera_xz_m: Vec2) -> Vec2 {
    (camera_xz_m / TEXEL_M - Vec2::splat(CLOUD_SHADOW_MAP_PX as f32 / 2.0)).floor() * TEXEL_M
}

/// The ground point texel `texel` of a map at `origin_m` stands for (its centre), m.
/// WGSL twin: `cloud_shadow_map_point_m`.
#[must_use]
pub fn cloud_shadow_map_point_m(origin_m: Vec2, texel: UVec2) -> Vec2 {
    origin_m + (texel.as_vec2() + Vec2::splat(0.5)) * TEXEL_M
}

/// How much of the map a point at `uv` on it (0 … 1 across, outside beyond) takes
/// against the frame's one share: 1 within, falling to 0 over the outer
/// [`CLOUD_SHADOW_MAP_FADE`] of each side, 0 beyond. WGSL twin:
/// `cloud_shadow_map_weight`.
#[must_use]
pub fn cloud_shadow_map_weight(uv: Vec2) -> f32 {
    let inside = uv.min(Vec2::ONE - uv).min_element();
    (inside / CLOUD_SHADOW_MAP_FADE).clamp(0.0, 1.0)
}

/// The map's texels for `layers` drifted by `drift_m`, the sun along the unit
/// `to_sun`, the land at `ground_y_m`, row by row: each the share of the sun's light
/// that reaches its point through every layer
/// ([`CloudLayers::sun_transmittance`]). What the kernel writes.
#[must_use]
pub fn cloud_shadow_map(
    layers: &CloudLayers,
    drift_m: Vec2,
    to_sun: Vec3,
    origin_m: Vec2,
    ground_y_m: f32,
) -> Vec<f32> {
    let n = CLOUD_SHADOW_MAP_PX;
    (0..n * n)
        .map(|i| {
            let xz = cloud_shadow_map_point_m(origin_m, UVec2::new(i % n, i / n));
            layers.sun_transmittance(
                cloud_noise(),
                drift_m,
                Vec3::new(xz.x, ground_y_m, xz.y),
                to_sun,
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::{CloudKind, CloudLayer};
    use super::*;

    #[test]
    fn the_map_is_centred_on_the_camera_on_whole_texels() {
        for camera in [
            Vec2::ZERO,
            Vec2::new(1234.5, -987.25),
            Vec2::new(-40_000.0, 7.0),
        ] {
            let origin = cloud_shadow_map_origin_m(camera);
            // On the world's lattice of texels.
            let cells = origin / TEXEL_M;
            assert!(
                (cells - cells.round()).abs().max_element() < 1e-3,
                "{origin}"
            );
            // The camera within a texel of the centre.
            let centre = origin + Vec2::splat(CLOUD_SHADOW_MAP_SPAN_M / 2.0);
            assert!(
                (centre - camera).abs().max_element() <= TEXEL_M,
                "{camera} {centre}"
            );
        }
        // Moving less than a texel keeps it; the texel centres are the lattice's.
        let a = cloud_shadow_map_origin_m(Vec2::new(10.0, 10.0));
        let b = cloud_shadow_map_origin_m(Vec2::new(11.0, 10.5));
        assert_eq!(a, b);
        let p = cloud_shadow_map_point_m(a, UVec2::new(3, 5));
        assert!((p - (a + Vec2::new(3.5, 5.5) * TEXEL_M)).length() < 1e-3);
    }

    #[test]
    fn the_map_fades_into_the_frame_s_share_at_its_edges() {
        assert!((cloud_shadow_map_weight(Vec2::splat(0.5)) - 1.0).abs() < 1e-6);
        assert!((cloud_shadow_map_weight(Vec2::new(0.5, 0.2)) - 1.0).abs() < 1e-6);
        let half = cloud_shadow_map_weight(Vec2::new(0.5, 1.0 - CLOUD_SHADOW_MAP_FADE / 2.0));
        assert!((half - 0.5).abs() < 1e-4, "{half}");
        assert!(cloud_shadow_map_weight(Vec2::new(-0.1, 0.5)).abs() < 1e-6);
        assert!(cloud_shadow_map_weight(Vec2::new(0.5, 1.3)).abs() < 1e-6);
    }

    #[test]
    fn a_half_covered_sky_shades_about_half_the_land() {
        let layers = CloudLayers::one(CloudLayer::typical(CloudKind::Cumulus, 0.5));
        let to_sun = Vec3::new(0.3, 0.9, 0.2).normalize();
        let origin = cloud_shadow_map_origin_m(Vec2::ZERO);
        let map = cloud_shadow_map(&layers, Vec2::ZERO, to_sun, origin, 0.0);
        assert_eq!(
            map.len(),
            (CLOUD_SHADOW_MAP_PX * CLOUD_SHADOW_MAP_PX) as usize
        );
        assert!(map.iter().all(|s| (0.0..=1.0).contains(s)));
        let shaded = map.iter().filter(|&&s| s < 0.5).count() as f32 / map.len() as f32;
        assert!((0.3..0.7).contains(&shaded), "{shaded}");
        // No layer: all sun.
        let clear = cloud_shadow_map(&CloudLayers::NONE, Vec2::ZERO, to_sun, origin, 0.0);
        assert!(clear.iter().all(|&s| (s - 1.0).abs() < 1e-6));
    }
}
