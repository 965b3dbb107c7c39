//! The water bodies' planar mirror (docs/model.md (5.13c)): the scene drawn once more,
//! reflected about the level of the water bodies nearest the camera, into an image
//! the water samples where it stands, so a pond shows the house beyond it, the hill
//! behind the camera and anything the frame does not, as a still water surface does.
//!
//! A level water surface at height `h` is a plane mirror: what it shows at a point
//! is what a camera reflected about `y = h` sees there. Drawing the scene through
//! `P·V·R` (`R: (x, y, z) → (x, 2h − y, z)`) puts each point's mirror image where the
//! real camera sees it on the water, so the water reads the mirror image at its own
//! pixel; what lies below the level (the basin, the ground under the water) is cut.
//! The light is reflected on the way: the mirror's fog and view direction are the
//! reflected camera's (the path camera → water → object is as long as the straight
//! line from the reflected camera).
//!
//! Only the water's rectangle on the frame is drawn ([`FrameMirror::rect_px`], the
//! water bodies' box projected, widened by the waves' reach); a frame whose water is
//! out of view draws no mirror. Water bodies at another level reflect the sky (the
//! screen-space reflections of (5.13b) serve the frames without a mirror).

use glam::{Mat4, Vec3, Vec4};

use crate::scene::Scene;

/// Water-body meshes within this of one height are one level surface, m.
pub const MIRROR_LEVEL_TOLERANCE_M: f32 = 0.05;

/// The most the waves move the point the water reads in the mirror image, as a
/// share of the target's height (WGSL `MIRROR_SLOPE_REACH`): the rectangle drawn is
/// widened by it.
pub const MIRROR_SLOPE_REACH: f32 = 0.02;

/// The mirror image's side against the frame's (half: a quarter of the fragments).
pub const MIRROR_DOWNSCALE: u32 = 2;

/// A level water surface: its height and the box of the water bodies at it, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaterLevel {
    /// The surface's height, m.
    pub level_m: f32,
    /// The box's least corner, m.
    pub lo_m: Vec3,
    /// Its greatest corner, m.
    pub hi_m: Vec3,
}

/// The scene's water bodies by level: each water-body mesh flat within
/// [`MIRROR_LEVEL_TOLERANCE_M`] is a level surface at its mean height; those at one
/// level (within the tolerance) share a box. A mesh that is not flat mirrors nothing
/// here.
#[must_use]
pub fn water_levels(scene: &Scene) -> Vec<WaterLevel> {
    let mut levels: Vec<WaterLevel> = Vec::new();
    for mesh in scene.meshes.iter().filter(|m| m.is_water_body()) {
        let Some(&first) = mesh.positions_m.first() else {
            continue;
        };
        let (lo, hi) = mesh
            .positions_m
            .iter()
            .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        if hi.y - lo.y > MIRROR_LEVEL_TOLERANCE_M {
            continue;
        }
        let level_m = 0.5 * (lo.y + hi.y);
        match levels
            .iter_mut()
            .find(|l| (l.level_m - level_m).abs() <= MIRROR_LEVEL_TOLERANCE_M)
        {
            Some(l) => {
                l.lo_m = l.lo_m.min(lo);
                l.hi_m = l.hi_m.max(hi);
            }
            None => levels.push(WaterLevel {
                level_m,
                lo_m: lo,
                hi_m: hi,
            }),
        }
    }
    levels
}

/// The reflection about the plane `y = level_m`: `(x, y, z) → (x, 2h − y, z)`.
#[must_use]
pub fn mirror_about_level(level_m: f32) -> Mat4 {
    Mat4::from_cols(
        Vec4::X,
        Vec4::NEG_Y,
        Vec4::Z,
        Vec4::new(0.0, 2.0 * level_m, 0.0, 1.0),
    )
}

/// The mirror a frame draws.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameMirror {
    /// The mirror's level, m.
    pub level_m: f32,
    /// World → clip through the mirror: the camera's `view_proj` × [`mirror_about_level`].
    pub view_proj: Mat4,
    /// The rectangle of the frame the water may cover, px `(x, y, width, height)`,
    /// y down, within the target.
    pub rect_px: [u32; 4],
}

/// The mirror of a frame seen through `view_proj` on a `size` target from
/// `camera_m`: the level below the camera nearest it (a mirror seen from below shows
/// nothing), if its water is in view.
#[must_use]
pub fn frame_mirror(
    levels: &[WaterLevel],
    camera_m: Vec3,
    view_proj: Mat4,
    size: (u32, u32),
) -> Option<FrameMirror> {
    let level = levels
        .iter()
        .filter(|l| l.level_m < camera_m.y)
        .min_by(|a, b| {
            let d = |l: &WaterLevel| camera_m.clamp(l.lo_m, l.hi_m).distance_squared(camera_m);
            d(a).total_cmp(&d(b))
        })?;
    let rect_px = water_rect_px(level, view_proj, size)?;
    Some(FrameMirror {
        level_m: level.level_m,
        view_proj: view_proj * mirror_about_level(level.level_m),
        rect_px,
    })
}

/// The rectangle of a `size` target that `level`'s water covers through
/// `view_proj`, widened by [`MIRROR_SLOPE_REACH`] (where the water reaches behind
/// the camera: the whole target below the horizon, [`horizon_top_px`]); `None` out
/// of view (wholly behind the camera, or projected off the target).
#[must_use]
pub fn water_rect_px(level: &WaterLevel, view_proj: Mat4, size: (u32, u32)) -> Option<[u32; 4]> {
    let (width, height) = (size.0 as f32, size.1 as f32);
    let (mut lo, mut hi) = (glam::Vec2::splat(f32::MAX), glam::Vec2::splat(f32::MIN));
    let mut behind = 0;
    for k in 0..4 {
        let corner = Vec3::new(
            if k & 1 == 0 {
                level.lo_m.x
            } else {
                level.hi_m.x
            },
            level.level_m,
            if k & 2 == 0 {
                level.lo_m.z
            } else {
                level.hi_m.z
            },
        );
        let clip = view_proj * corner.extend(1.0);
        if clip.w <= 1.0e-4 {
            behind += 1;
            continue;
        }
        let ndc = clip.truncate().truncate() / clip.w;
        let px = glam::Vec2::new((ndc.x + 1.0) * 0.5 * width, (1.0 - ndc.y) * 0.5 * height);
        lo = lo.min(px);
        hi = hi.max(px);
    }
    match behind {
        0 => {}
        4 => return None,
        _ => {
            let reach = MIRROR_SLOPE_REACH * height + 1.0;
            let top = (horizon_top_px(view_proj, size) - reach).clamp(0.0, height);
            let y0 = top.floor() as u32;
            return (y0 < size.1).then_some([0, y0, size.0, size.1 - y0]);
        }
    }
    let reach = MIRROR_SLOPE_REACH * height + 1.0;
    let lo = (lo - reach).max(glam::Vec2::ZERO);
    let hi = (hi + reach).min(glam::Vec2::new(width, height));
    if hi.x <= lo.x || hi.y <= lo.y {
        return None;
    }
    let (x0, y0) = (lo.x.floor() as u32, lo.y.floor() as u32);
    let (x1, y1) = (hi.x.ceil() as u32, hi.y.ceil() as u32);
    Some([x0, y0, x1.min(size.0) - x0, y1.min(size.1) - y0])
}

/// The highest row of a `size` target (y down, px) a level plane below the camera
/// reaches through `view_proj`: its horizon, where the horizontal directions ahead
/// project (sampled every degree round the compass); 0 where the horizon lies above
/// the target or no horizontal direction lies ahead (a camera looking straight
/// down).
#[must_use]
pub fn horizon_top_px(view_proj: Mat4, size: (u32, u32)) -> f32 {
    let (width, height) = (size.0 as f32, size.1 as f32);
    let mut top: Option<f32> = None;
    for degree in 0..360 {
        let a = (degree as f32).to_radians();
        let clip = view_proj * Vec4::new(a.cos(), 0.0, a.sin(), 0.0);
        if clip.w <= 1.0e-4 {
            continue;
        }
        let x = (clip.x / clip.w + 1.0) * 0.5 * width;
        let y = (1.0 - clip.y / clip.w) * 0.5 * height;
        // Beside the target the line goes on: what counts is over its width.
        if (-0.5 * width..=1.5 * width).contains(&x) {
            top = Some(top.map_or(y, |t| t.min(y)));
        }
    }
    top.map_or(0.0, |t| t.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::camera::Camera;
    use crate::drawing::render::view_projection;
    use crate::scene::{Material, Mesh};

    fn pond(level_m: f32, centre_x_m: f32) -> Mesh {
        let c = Vec3::new(centre_x_m, level_m, 0.0);
        Mesh {
            name: "pond".into(),
            positions_m: vec![
                c + Vec3::new(-2.0, 0.0, -2.0),
                c + Vec3::new(2.0, 0.0, -2.0),
                c + Vec3::new(2.0, 0.0, 2.0),
                c + Vec3::new(-2.0, 0.01, 2.0),
            ],
            normals: Vec::new(),
            uvs: Vec::new(),
            indices: vec![0, 2, 1, 0, 3, 2],
            snow_eligibility: Vec::new(),
            surface: Some(precip_cover::Surface::Water),
            sea: false,
            material: Material::default(),
        }
    }

    #[test]
    fn a_sea_round_the_camera_is_mirrored_below_its_horizon_only() {
        let level = WaterLevel {
            level_m: 0.0,
            lo_m: Vec3::new(-20_000.0, 0.0, -20_000.0),
            hi_m: Vec3::new(20_000.0, 0.0, 20_000.0),
        };
        let size = (1280, 720);
        let at = |forward: Vec3| {
            let camera = Camera {
                position_m: Vec3::new(0.0, 3.0, 0.0),
                forward,
                ..Camera::default()
            };
            water_rect_px(&level, view_projection(&camera, 1280.0 / 720.0), size).expect("in view")
        };
        // Level: the horizon mid-frame (the slope's reach above it).
        let level_view = at(Vec3::X);
        assert!((340..=360).contains(&level_view[1]), "{level_view:?}");
        assert_eq!(level_view[1] + level_view[3], 720);
        // Looking down a little: the horizon higher; straight down: all of it.
        let down = at(Vec3::new(1.0, -0.3, 0.0));
        assert!(down[1] < level_view[1], "{down:?}");
        assert_eq!(at(Vec3::new(0.0, -1.0, 0.001)), [0, 0, 1280, 720]);
    }

    #[test]
    fn the_sea_mirrors_the_scene_at_its_level_as_a_pond_does() {
        // Its still level: the waves tilt the ray the image is read along
        // (render_ocean.wgsl).
        let sea = Mesh {
            sea: true,
            ..pond(0.0, 0.0)
        };
        let scene = Scene {
            meshes: vec![sea, pond(2.0, 10.0)],
        };
        let levels = water_levels(&scene);
        assert_eq!(levels.len(), 2, "{levels:?}");
        assert!(levels.iter().any(|l| l.level_m.abs() < 0.01), "{levels:?}");
    }

    #[test]
    fn the_mirror_reflects_about_the_level() {
        let m = mirror_about_level(1.5);
        assert!(
            (m.transform_point3(Vec3::new(2.0, 4.0, -3.0)) - Vec3::new(2.0, -1.0, -3.0)).length()
                < 1e-6
        );
        assert!(
            (m.transform_point3(Vec3::new(7.0, 1.5, 9.0)) - Vec3::new(7.0, 1.5, 9.0)).length()
                < 1e-6
        );
        assert!((m * m - Mat4::IDENTITY).abs_diff_eq(Mat4::ZERO, 1e-6));
    }

    #[test]
    fn ponds_at_one_level_share_a_box_and_the_nearest_level_below_the_camera_mirrors() {
        let scene = Scene {
            meshes: vec![pond(0.0, -10.0), pond(0.02, 10.0), pond(3.0, 0.0)],
        };
        let levels = water_levels(&scene);
        assert_eq!(levels.len(), 2, "{levels:?}");
        assert!((levels[0].lo_m.x + 12.0).abs() < 1e-6 && (levels[0].hi_m.x - 12.0).abs() < 1e-6);
        let camera = Camera {
            position_m: Vec3::new(0.0, 2.0, 20.0),
            forward: Vec3::new(0.0, -0.3, -1.0),
            ..Camera::default()
        };
        let view_proj = view_projection(&camera, 16.0 / 9.0);
        // The pond at 3 m is above the camera: the ground-level ponds mirror.
        let m = frame_mirror(&levels, camera.position_m, view_proj, (640, 360)).expect("in view");
        assert!(m.level_m.abs() < 0.02, "{m:?}");
        let [x, y, w, h] = m.rect_px;
        assert!(x + w <= 640 && y + h <= 360 && w > 100 && h > 10, "{m:?}");
        // The rectangle holds the projection of each pond's centre.
        for centre in [Vec3::new(-10.0, 0.0, 0.0), Vec3::new(10.0, 0.0, 0.0)] {
            let clip = view_proj * centre.extend(1.0);
            let px = (
                (clip.x / clip.w + 1.0) * 320.0,
                (1.0 - clip.y / clip.w) * 180.0,
            );
            assert!(px.0 >= x as f32 && px.0 <= (x + w) as f32, "{px:?} {m:?}");
            assert!(px.1 >= y as f32 && px.1 <= (y + h) as f32, "{px:?} {m:?}");
        }
        // A point's mirror image projects where the water under it would show it.
        let above = Vec3::new(10.0, 2.5, 0.0);
        let image = m.view_proj * above.extend(1.0);
        let direct = view_proj * Vec3::new(10.0, -2.5 + 2.0 * m.level_m, 0.0).extend(1.0);
        assert!((image / image.w - direct / direct.w).length() < 1e-5);
        // Looking away from the water: no mirror.
        let away = Camera {
            forward: Vec3::new(0.0, 0.3, 1.0),
            ..camera
        };
        let view_proj = view_projection(&away, 16.0 / 9.0);
        assert_eq!(
            frame_mirror(&levels, away.position_m, view_proj, (640, 360)),
            None
        );
        // Under every level: none.
        assert_eq!(
            frame_mirror(&levels, Vec3::new(0.0, -1.0, 20.0), view_proj, (640, 360)),
            None
        );
    }
}
