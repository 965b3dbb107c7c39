//! A fly camera: yaw/pitch from the mouse or arrow keys, movement along the view.

use glam::Vec3;
use precip_model::Camera;

/// Yaw and pitch over a position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlyCamera {
    /// Eye, m.
    pub position_m: Vec3,
    /// Rotation about +Y from −Z, rad.
    pub yaw_rad: f32,
    /// Elevation, rad, within ±89°.
    pub pitch_rad: f32,
    /// Speed, m/s.
    pub speed_mps: f32,
}

impl FlyCamera {
    /// Starts at `camera`'s position and direction.
    #[must_use]
    pub fn from_camera(camera: &Camera) -> Self {
        let f = camera.forward.normalize();
        Self {
            position_m: camera.position_m,
            yaw_rad: (-f.x).atan2(-f.z),
            pitch_rad: f.y.clamp(-1.0, 1.0).asin(),
            speed_mps: 6.0,
        }
    }

    /// The unit viewing direction.
    #[must_use]
    pub fn forward(&self) -> Vec3 {
        let (sy, cy) = self.yaw_rad.sin_cos();
        let (sp, cp) = self.pitch_rad.sin_cos();
        Vec3::new(-sy * cp, sp, -cy * cp)
    }

    /// Turns by `(d_yaw, d_pitch)` rad.
    pub fn turn(&mut self, d_yaw: f32, d_pitch: f32) {
        self.yaw_rad += d_yaw;
        let limit = 89f32.to_radians();
        self.pitch_rad = (self.pitch_rad + d_pitch).clamp(-limit, limit);
    }

    /// Moves for `dt_s` by `(right, up, forward)` in `[-1, 1]`.
    pub fn fly(&mut self, dt_s: f32, right: f32, up: f32, forward: f32) {
        let f = self.forward();
        let r = f.cross(Vec3::Y).normalize_or(Vec3::X);
        self.position_m += (r * right + Vec3::Y * up + f * forward) * self.speed_mps * dt_s;
    }

    /// The camera for drawing, with `template`'s lens.
    #[must_use]
    pub fn camera(&self, template: &Camera) -> Camera {
        Camera {
            position_m: self.position_m,
            forward: self.forward(),
            up: Vec3::Y,
            ..*template
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_a_camera_and_flies_forward() {
        let c = Camera {
            forward: Vec3::new(1.0, -0.5, -2.0),
            ..Camera::default()
        };
        let mut fly = FlyCamera::from_camera(&c);
        assert!((fly.forward() - c.forward.normalize()).length() < 1e-5);
        let before = fly.position_m;
        fly.fly(1.0, 0.0, 0.0, 1.0);
        assert!(((fly.position_m - before) - fly.forward() * 6.0).length() < 1e-4);
        fly.turn(0.0, 10.0);
        assert!(fly.pitch_rad <= 89f32.to_radians() + 1e-6);
        assert!(fly.camera(&c).validate().is_ok());
    }
}
