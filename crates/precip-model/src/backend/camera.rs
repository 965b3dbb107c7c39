//! The camera, a view (camera + target size), and a read-back image.

use glam::{Vec2, Vec3};

use crate::backend::error::BackendError;

/// A perspective camera, world units (m), Y up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position, m.
    pub position_m: Vec3,
    /// Viewing direction (need not be normalised; not zero).
    pub forward: Vec3,
    /// Up hint (not parallel to `forward`).
    pub up: Vec3,
    /// Vertical field of view, rad, in `(0, π)`.
    pub vertical_fov_rad: f32,
    /// Width / height.
    pub aspect: f32,
    /// Near plane, m.
    pub near_m: f32,
    /// Far plane, m.
    pub far_m: f32,
    /// Off-axis projection: the image's centre moved by this many half-widths (x,
    /// right) and half-heights (y, up) of the field of view, each in `[-4, 4]` (0:
    /// on axis). The channels of a tiled display rig share one image plane: each
    /// shows its window of it, and where windows overlap they draw the same rays.
    pub lens_shift: Vec2,
    /// Shutter, aperture and focus: how long a frame exposes (the streaks) and
    /// what is sharp (the near flakes' blur).
    pub lens: Lens,
}

/// A camera's exposure and thin lens (docs/model.md (5.4), (5.14), (5.16)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lens {
    /// Exposure (shutter) time, s, in `[0, 1]`: a particle is drawn over its motion
    /// during it (0: frozen).
    pub exposure_s: f32,
    /// f-number `N` (focal length over aperture diameter), `≥ 0.5`; infinite: a
    /// pinhole, everything sharp.
    pub f_number: f32,
    /// Distance in focus, m, in `[0.1, 10⁶]`.
    pub focus_distance_m: f32,
}

impl Default for Lens {
    /// 1/60 s at f/4, focused at 10 m: a video camera's everyday setting.
    fn default() -> Self {
        Self {
            exposure_s: 1.0 / 60.0,
            f_number: 4.0,
            focus_distance_m: 10.0,
        }
    }
}

/// Height of the sensor the lens images onto, m (full frame, 24 × 36 mm): with the
/// field of view it sets the focal length, and with the f-number the aperture.
pub const SENSOR_HEIGHT_M: f32 = 0.024;

impl Lens {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), BackendError> {
        if !(self.exposure_s.is_finite() && (0.0..=1.0).contains(&self.exposure_s)) {
            return Err(BackendError::InvalidCamera(
                "lens.exposure_s must be in [0, 1] s",
            ));
        }
        if self.f_number.is_nan() || self.f_number < 0.5 {
            return Err(BackendError::InvalidCamera(
                "lens.f_number must be at least 0.5 (infinite for a pinhole)",
            ));
        }
        if !(self.focus_distance_m.is_finite() && (0.1..=1.0e6).contains(&self.focus_distance_m)) {
            return Err(BackendError::InvalidCamera(
                "lens.focus_distance_m must be in [0.1, 1000000] m",
            ));
        }
        Ok(())
    }

    /// The aperture's diameter, m, for a vertical field of view `vertical_fov_rad`:
    /// focal length `f = (h_sensor/2)/tan(fov/2)` over the f-number (0 for a pinhole).
    #[must_use]
    pub fn aperture_m(&self, vertical_fov_rad: f32) -> f32 {
        let focal_m = 0.5 * SENSOR_HEIGHT_M / (0.5 * vertical_fov_rad).tan().max(1.0e-6);
        if self.f_number.is_finite() {
            focal_m / self.f_number
        } else {
            0.0
        }
    }
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position_m: Vec3::new(0.0, 2.0, 10.0),
            forward: Vec3::NEG_Z,
            up: Vec3::Y,
            vertical_fov_rad: 60f32.to_radians(),
            aspect: 16.0 / 9.0,
            near_m: 0.1,
            far_m: 2000.0,
            lens_shift: Vec2::ZERO,
            lens: Lens::default(),
        }
    }
}

impl Camera {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), BackendError> {
        if !(self.position_m.is_finite() && self.position_m.abs().max_element() <= 1.0e7) {
            return Err(BackendError::InvalidCamera(
                "position_m must be finite and within ±10000 km",
            ));
        }
        if !self.forward.is_finite() || self.forward.length_squared() < 1e-12 {
            return Err(BackendError::InvalidCamera(
                "forward must be a finite, non-zero direction",
            ));
        }
        if !self.up.is_finite() || self.forward.normalize().cross(self.up).length_squared() < 1e-12
        {
            return Err(BackendError::InvalidCamera(
                "up must be finite and not parallel to forward",
            ));
        }
        if !(self.vertical_fov_rad.is_finite()
            && self.vertical_fov_rad > 0.0
            && self.vertical_fov_rad < std::f32::consts::PI)
        {
            return Err(BackendError::InvalidCamera(
                "vertical_fov_rad must be in (0, π)",
            ));
        }
        if !(self.aspect.is_finite() && self.aspect > 1e-3 && self.aspect < 1e3) {
            return Err(BackendError::InvalidCamera(
                "aspect must be in (0.001, 1000)",
            ));
        }
        if !(self.near_m.is_finite()
            && self.far_m.is_finite()
            && self.near_m > 0.0
            && self.far_m > self.near_m)
        {
            return Err(BackendError::InvalidCamera(
                "near_m and far_m must be finite with 0 < near < far",
            ));
        }
        if !(self.lens_shift.is_finite() && self.lens_shift.abs().max_element() <= 4.0) {
            return Err(BackendError::InvalidCamera(
                "lens_shift must be finite, each within ±4 half-widths",
            ));
        }
        self.lens.validate()
    }

    /// The on-axis frustum enclosing this one on a target of `aspect`: its vertical
    /// field of view and aspect (the same as this camera's without a lens shift).
    /// Culling and the shadow map's fit use it, so the channels of a rig shifted
    /// symmetrically cull and shadow alike.
    #[must_use]
    pub fn enclosing_frustum(&self, aspect: f32) -> (f32, f32) {
        let tan_v = (0.5 * self.vertical_fov_rad).tan() * (1.0 + self.lens_shift.y.abs());
        let tan_h = (0.5 * self.vertical_fov_rad).tan() * aspect * (1.0 + self.lens_shift.x.abs());
        (2.0 * tan_v.atan(), tan_h / tan_v)
    }
}

/// What to render: a camera and a target size in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// Target width, px.
    pub width_px: u32,
    /// Target height, px.
    pub height_px: u32,
}

/// An RGBA8 (sRGB) image read back from a backend.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width, px.
    pub width_px: u32,
    /// Height, px.
    pub height_px: u32,
    /// Rows top to bottom, 4 bytes a pixel.
    pub rgba8: Vec<u8>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shifted_lens_is_enclosed_by_a_wider_frustum() {
        let camera = Camera {
            vertical_fov_rad: 90f32.to_radians(),
            lens_shift: Vec2::new(0.5, -1.0),
            ..Camera::default()
        };
        let (fov, aspect) = camera.enclosing_frustum(2.0);
        // tan: vertical 1 → 2, horizontal 2 → 3.
        assert!(((0.5 * fov).tan() - 2.0).abs() < 1e-5);
        assert!((aspect - 1.5).abs() < 1e-5);
        let on_axis = Camera::default();
        let (fov, aspect) = on_axis.enclosing_frustum(1.5);
        assert!((fov - on_axis.vertical_fov_rad).abs() < 1e-6 && (aspect - 1.5).abs() < 1e-6);
    }

    #[test]
    fn bad_cameras_are_refused() {
        let good = Camera::default();
        assert!(good.validate().is_ok());
        for bad in [
            Camera {
                position_m: Vec3::NAN,
                ..good
            },
            Camera {
                forward: Vec3::ZERO,
                ..good
            },
            Camera {
                up: Vec3::NEG_Z,
                ..good
            },
            Camera {
                vertical_fov_rad: 0.0,
                ..good
            },
            Camera {
                aspect: f32::NAN,
                ..good
            },
            Camera {
                near_m: 10.0,
                far_m: 1.0,
                ..good
            },
            Camera {
                lens_shift: Vec2::new(0.0, 5.0),
                ..good
            },
            Camera {
                lens_shift: Vec2::NAN,
                ..good
            },
        ] {
            assert!(
                matches!(bad.validate(), Err(BackendError::InvalidCamera(_))),
                "{bad:?}"
            );
        }
    }
}
