//! The sun's shadow map fitted to the view: its texels spread over the part of the
//! scene the camera can see, not over the whole scene.
//!
//! An orthographic shadow map's texel at light-space `(x, y)` holds the nearest
//! caster along that one sun ray, so the map's `x, y` range need only cover the
//! *receivers* in view, while its depth range must keep every *caster* (the whole
//! scene, as before). The receivers are the box of the view frustum, from the camera
//! to the distance where shadows still show, intersected with the scene's box. That
//! distance is the smaller of the far plane and the Koschmieder visibility in the
//! frame's fog (beyond it a shadow's contrast is under 2 %).
//!
//! The fit is made stable so the [`crate::drawing::shadow_cache`] can keep the map while the
//! camera moves a little: its side is rounded up to a power of two metres (with room
//! for the snap) and its centre snapped to a sixteenth of that side. A view that sees
//! most of the scene falls back to the whole-scene map ([`sun_view_projection`]).
//!
//! The map's texel count is `RenderSettings::shadow_map_px` either way: with the fit,
//! each texel covers (side / px)² instead of (scene diameter / px)².

use glam::camera::rh::proj::directx;
use glam::{Mat4, Vec3};

use crate::backend::camera::Camera;
use crate::drawing::render::{sun_view, sun_view_projection};
use crate::weather::visibility::koschmieder_visibility_m;

/// Parts of the fitted side the centre is snapped to.
pub const SNAP_PARTS: f32 = 16.0;

/// The eight corners of `camera`'s frustum between its near plane and `distance_m`,
/// for a target of `aspect`.
#[must_use]
pub fn frustum_corners(camera: &Camera, aspect: f32, distance_m: f32) -> [Vec3; 8] {
    let f = camera.forward.normalize();
    let r = f.cross(camera.up).normalize();
    let u = r.cross(f);
    let tan = (0.5 * camera.vertical_fov_rad).tan();
    let mut out = [Vec3::ZERO; 8];
    for (k, t) in [camera.near_m, distance_m.max(camera.near_m)]
        .into_iter()
        .enumerate()
    {
        let (h, w) = (t * tan, t * tan * aspect);
        for (c, (sx, sy)) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            out[4 * k + c] = camera.position_m + f * t + r * (sx * w) + u * (sy * h);
        }
    }
    out
}

/// How far shadows show: the far plane, or the visibility in fog of
/// `extinction_per_m` if nearer, m.
#[must_use]
pub fn shadow_distance_m(camera: &Camera, extinction_per_m: f32) -> f32 {
    let visibility = koschmieder_visibility_m(extinction_per_m);
    if visibility.is_finite() && visibility > 0.0 {
        camera.far_m.min(visibility)
    } else {
        camera.far_m
    }
}

/// World → clip of the sun's shadow map for the scene box `(lo, hi)` seen by `camera`
/// on a target of `aspect`, shadows showing to `distance_m`; see the module docs.
#[must_use]
pub fn fitted_sun_view_projection(
    to_sun: Vec3,
    (lo, hi): (Vec3, Vec3),
    camera: &Camera,
    aspect: f32,
    distance_m: f32,
) -> Mat4 {
    let whole = sun_view_projection(to_sun, lo, hi);
    let corners = frustum_corners(camera, aspect, distance_m);
    let seen_lo = corners
        .iter()
        .copied()
        .fold(Vec3::INFINITY, Vec3::min)
        .max(lo);
    let seen_hi = corners
        .iter()
        .copied()
        .fold(Vec3::NEG_INFINITY, Vec3::max)
        .min(hi);
    if !(seen_lo.cmple(seen_hi).all()) {
        return whole;
    }
    // The same light view as the whole-scene map (depth range included), only the
    // x, y window narrowed.
    let (view, radius) = sun_view(to_sun, lo, hi);
    let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for k in 0..8 {
        let pick = |bit: usize, a: f32, b: f32| if k & bit == 0 { a } else { b };
        let corner = Vec3::new(
            pick(1, seen_lo.x, seen_hi.x),
            pick(2, seen_lo.y, seen_hi.y),
            pick(4, seen_lo.z, seen_hi.z),
        );
        let p = view.transform_point3(corner);
        min = min.min(p);
        max = max.max(p);
    }
    let side = (max.x - min.x).max(max.y - min.y).max(1.0e-3);
    // Room for the centre's snap (at most side'/32 each way): side' ≥ side · 16/15.
    let snapped_side = (side * SNAP_PARTS / (SNAP_PARTS - 1.0))
        .log2()
        .ceil()
        .exp2();
    if !snapped_side.is_finite() || snapped_side >= 2.0 * radius {
        return whole;
    }
    let step = snapped_side / SNAP_PARTS;
    let cx = (0.5 * (min.x + max.x) / step).round() * step;
    let cy = (0.5 * (min.y + max.y) / step).round() * step;
    let half = 0.5 * snapped_side;
    let proj = directx::orthographic(
        cx - half,
        cx + half,
        cy - half,
        cy + half,
        0.0,
        4.0 * radius,
    );
    proj * view
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field() -> (Vec3, Vec3) {
        (
            Vec3::new(-500.0, 0.0, -500.0),
            Vec3::new(500.0, 30.0, 500.0),
        )
    }

    fn camera() -> Camera {
        Camera {
            position_m: Vec3::new(0.0, 2.0, 10.0),
            far_m: 60.0,
            ..Camera::default()
        }
    }

    fn in_map(m: Mat4, p: Vec3) -> bool {
        let c = m.project_point3(p);
        c.x.abs() <= 1.0 && c.y.abs() <= 1.0 && (0.0..=1.0).contains(&c.z)
    }

    #[test]
    fn a_view_of_a_large_scene_gets_a_much_finer_map_that_holds_what_it_sees() {
        let to_sun = Vec3::new(0.4, 1.0, 0.3);
        let cam = camera();
        let fitted = fitted_sun_view_projection(to_sun, field(), &cam, 16.0 / 9.0, 60.0);
        let whole = sun_view_projection(to_sun, field().0, field().1);
        // Texel size ∝ 1 / x scale of the projection.
        let finer = fitted.x_axis.length() / whole.x_axis.length();
        assert!(finer > 4.0, "the fitted map is only {finer}× finer");
        // Every point of the frustum inside the scene box is in the map, and so is
        // every caster of the scene (depth range), e.g. a far corner's top.
        for p in frustum_corners(&cam, 16.0 / 9.0, 60.0) {
            let p = p.clamp(field().0, field().1);
            assert!(in_map(fitted, p), "{p} is outside the fitted map");
        }
        let c = fitted.project_point3(Vec3::new(500.0, 30.0, 500.0));
        assert!((0.0..=1.0).contains(&c.z), "a far caster's depth {c}");
    }

    #[test]
    fn small_camera_moves_keep_the_same_map() {
        let to_sun = Vec3::new(0.4, 1.0, 0.3);
        let mut cam = camera();
        let first = fitted_sun_view_projection(to_sun, field(), &cam, 16.0 / 9.0, 60.0);
        let mut same = 0;
        for _ in 0..100 {
            cam.position_m.x += 0.01;
            if fitted_sun_view_projection(to_sun, field(), &cam, 16.0 / 9.0, 60.0) == first {
                same += 1;
            }
        }
        assert!(
            same >= 90,
            "the map changed in {} of 100 1-cm moves",
            100 - same
        );
    }

    #[test]
    fn a_view_of_most_of_the_scene_uses_the_whole_scene_map() {
        let to_sun = Vec3::new(0.4, 1.0, 0.3);
        let small = (Vec3::new(-10.0, 0.0, -10.0), Vec3::new(10.0, 5.0, 10.0));
        let cam = camera();
        assert_eq!(
            fitted_sun_view_projection(to_sun, small, &cam, 16.0 / 9.0, 60.0),
            sun_view_projection(to_sun, small.0, small.1)
        );
    }

    #[test]
    fn fog_shortens_the_shadow_distance() {
        let cam = camera();
        assert!((shadow_distance_m(&cam, 0.0) - 60.0).abs() < 1e-3);
        // 3.912 / 0.39 ≈ 10 m of visibility.
        assert!((shadow_distance_m(&cam, 0.3912) - 10.0).abs() < 0.1);
    }
}
