//! The two particle volumes (docs/architecture.md §2): the seeds' world emitter rectangle, and
//! a camera volume that particles wrap through.

use glam::{Mat4, Vec2, Vec3};

use crate::backend::error::BackendError;

/// The seeds' emitter: a `W × H` rectangle in its own frame (OCS: X and Y along the
/// sides, Z its normal) placed in the world by `model` (docs/model.md §1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldEmitter {
    /// OCS → world.
    pub model: Mat4,
    /// Side W along OCS X, m.
    pub width_m: f32,
    /// Side H along OCS Y, m.
    pub height_m: f32,
    /// Initial velocity v0, m/s.
    pub initial_velocity_mps: Vec3,
    /// Velocity spread k_v ≥ 0, m/s: `v = v0 + 2·k_v·(f − ½, f − ½, f − ½)`.
    pub velocity_spread_mps: f32,
    /// Rotation amplitude k_rot ∈ [0, π], rad.
    pub rotation_amplitude_rad: f32,
    /// Rotation speed k_vel ≥ 0, rad/s.
    pub rotation_speed_rad_per_s: f32,
    /// Life time t_max, s: a particle still falling then is re-born.
    pub life_time_s: f32,
}

impl WorldEmitter {
    /// A horizontal `width × depth` rectangle centred at `centre_m` whose normal points
    /// down (OCS X → world X, OCS Y → world Z, OCS Z → world −Y), flakes starting at a
    /// typical fall speed, and a life time long enough to fall `fall_height_m` at the
    /// slowest terminal speed.
    #[must_use]
    pub fn horizontal(centre_m: Vec3, width_m: f32, depth_m: f32, fall_height_m: f32) -> Self {
        Self {
            model: Mat4::from_translation(centre_m)
                * Mat4::from_rotation_x(std::f32::consts::FRAC_PI_2),
            width_m,
            height_m: depth_m,
            initial_velocity_mps: Vec3::new(0.0, -1.0, 0.0),
            velocity_spread_mps: 0.2,
            rotation_amplitude_rad: 0.6,
            rotation_speed_rad_per_s: 1.5,
            life_time_s: 2.0 * fall_height_m.max(1.0) / 0.5,
        }
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<(), BackendError> {
        let bad = |field: &'static str, problem: &str| BackendError::Setup {
            field,
            problem: problem.to_owned(),
        };
        if !self.model.is_finite() {
            return Err(bad(
                "world_emitter.model",
                "is not finite: give a finite OCS-to-world matrix",
            ));
        }
        for (field, v) in [
            ("world_emitter.width_m", self.width_m),
            ("world_emitter.height_m", self.height_m),
        ] {
            if !(v.is_finite() && v > 0.0 && v <= 1.0e6) {
                return Err(bad(field, "must be in (0, 1000000] m"));
            }
        }
        if !self.initial_velocity_mps.is_finite() || self.initial_velocity_mps.length() > 200.0 {
            return Err(bad(
                "world_emitter.initial_velocity_mps",
                "must be finite and at most 200 m/s",
            ));
        }
        if !(self.velocity_spread_mps.is_finite()
            && (0.0..=100.0).contains(&self.velocity_spread_mps))
        {
            return Err(bad(
                "world_emitter.velocity_spread_mps",
                "must be in [0, 100] m/s",
            ));
        }
        validate_rotation(
            "world_emitter",
            self.rotation_amplitude_rad,
            self.rotation_speed_rad_per_s,
        )?;
        if !(self.life_time_s.is_finite() && self.life_time_s > 0.0 && self.life_time_s <= 1.0e5) {
            return Err(bad("world_emitter.life_time_s", "must be in (0, 100000] s"));
        }
        if self.horizontal_area_m2() < 1.0e-6 * self.width_m * self.height_m {
            return Err(bad(
                "world_emitter.model",
                "places the rectangle vertically: precipitation needs a rectangle with a horizontal extent",
            ));
        }
        Ok(())
    }

    /// The world point at OCS `(u, v)` on the rectangle (`u, v ∈ [−½, ½]` × sides).
    #[must_use]
    pub fn point(&self, u_m: f32, v_m: f32) -> Vec3 {
        self.model.transform_point3(Vec3::new(u_m, v_m, 0.0))
    }

    /// The rectangle's area projected on the ground (XZ), m²: the area whose
    /// precipitation its particles carry.
    #[must_use]
    pub fn horizontal_area_m2(&self) -> f32 {
        let ax = self.model.transform_vector3(Vec3::X) * self.width_m;
        let ay = self.model.transform_vector3(Vec3::Y) * self.height_m;
        ax.cross(ay).y.abs()
    }

    /// Whether the vertical line through world `(x, z)` crosses the rectangle.
    #[must_use]
    pub fn footprint_contains(&self, xz_m: Vec2) -> bool {
        let origin = self.model.transform_point3(Vec3::ZERO);
        let ax = self.model.transform_vector3(Vec3::X);
        let ay = self.model.transform_vector3(Vec3::Y);
        // Solve origin.xz + u·ax.xz + v·ay.xz = (x, z).
        let det = ax.x * ay.z - ax.z * ay.x;
        if det.abs() < f32::EPSILON {
            return false;
        }
        let d = xz_m - Vec2::new(origin.x, origin.z);
        let u = (d.x * ay.z - d.y * ay.x) / det;
        let v = (ax.x * d.y - ax.z * d.x) / det;
        u.abs() <= 0.5 * self.width_m && v.abs() <= 0.5 * self.height_m
    }
}

/// A box around the camera that particles wrap through, so precipitation never ends
/// however far the camera flies. Particles leaving a side re-enter at the opposite
/// side; one that falls out of the bottom or reaches the ground is re-born at the top.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraVolume {
    /// Half the box's size, m.
    pub half_extent_m: Vec3,
    /// Rotation amplitude k_rot ∈ [0, π], rad.
    pub rotation_amplitude_rad: f32,
    /// Rotation speed k_vel ≥ 0, rad/s.
    pub rotation_speed_rad_per_s: f32,
}

impl Default for CameraVolume {
    /// A 60 × 40 × 60 m box.
    fn default() -> Self {
        Self {
            half_extent_m: Vec3::new(30.0, 20.0, 30.0),
            rotation_amplitude_rad: 0.6,
            rotation_speed_rad_per_s: 1.5,
        }
    }
}

impl CameraVolume {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), BackendError> {
        let h = self.half_extent_m;
        if !(h.is_finite() && h.min_element() >= 0.5 && h.max_element() <= 1.0e4) {
            return Err(BackendError::Setup {
                field: "camera_volume.half_extent_m",
                problem: "must be finite, each in [0.5, 10000] m".to_owned(),
            });
        }
        validate_rotation(
            "camera_volume",
            self.rotation_amplitude_rad,
            self.rotation_speed_rad_per_s,
        )
    }

    /// The box's volume, m³.
    #[must_use]
    pub fn volume_m3(&self) -> f32 {
        8.0 * self.half_extent_m.x * self.half_extent_m.y * self.half_extent_m.z
    }
}

fn validate_rotation(volume: &'static str, amplitude: f32, speed: f32) -> Result<(), BackendError> {
    if !(amplitude.is_finite() && (0.0..=std::f32::consts::PI).contains(&amplitude)) {
        return Err(BackendError::Setup {
            field: volume,
            problem: format!("rotation_amplitude_rad = {amplitude} must be in [0, π]"),
        });
    }
    if !(speed.is_finite() && (0.0..=100.0).contains(&speed)) {
        return Err(BackendError::Setup {
            field: volume,
            problem: format!("rotation_speed_rad_per_s = {speed} must be in [0, 100] rad/s"),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horizontal_emitter_faces_down_and_covers_its_footprint() {
        let e = WorldEmitter::horizontal(Vec3::new(5.0, 30.0, -5.0), 20.0, 10.0, 30.0);
        assert!(e.validate().is_ok());
        assert!((e.horizontal_area_m2() - 200.0).abs() < 1e-3);
        let n = e.model.transform_vector3(Vec3::Z);
        assert!((n - Vec3::NEG_Y).length() < 1e-6);
        assert!((e.point(0.0, 0.0) - Vec3::new(5.0, 30.0, -5.0)).length() < 1e-5);
        assert!(e.footprint_contains(Vec2::new(14.9, -0.1)));
        assert!(!e.footprint_contains(Vec2::new(15.1, -5.0)));
        assert!(!e.footprint_contains(Vec2::new(5.0, 0.1)));
    }

    #[test]
    fn a_vertical_emitter_is_refused() {
        let e = WorldEmitter {
            model: Mat4::IDENTITY,
            ..WorldEmitter::horizontal(Vec3::ZERO, 5.0, 5.0, 10.0)
        };
        assert!(matches!(
            e.validate(),
            Err(BackendError::Setup {
                field: "world_emitter.model",
                ..
            })
        ));
    }
}
