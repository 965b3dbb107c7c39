//! The eyepoint a CIGI host flies: where the view precip draws stands and looks.
//!
//! The host places entities with Entity Control — geodetic latitude, longitude and
//! altitude (WGS 84) and a heading, pitch and roll, or an offset from a parent
//! entity — and hangs views on them with View Control (an offset along the
//! entity's body axes and a turn from its attitude); View Definition gives a view's
//! field of view. precip draws one view (`view_id`, 0 by default): from the entity
//! its View Control names, or the ownship (entity 0) before any.
//!
//! The scene lies on a local tangent plane at [`GeodeticOrigin`] (the scene's
//! `y = 0` at its altitude): a geodetic point is taken to Earth-centred
//! coordinates and from there to east, north, up at the origin, exactly (no
//! flat-earth scaling), so at 10 km the ground falls 7.8 m below the plane as the
//! Earth curves. precip's world axes are east = +x, up = +y, north = −z. An
//! attitude is the aerospace sequence yaw, pitch, roll about the body's down,
//! right and forward axes in the north-east-down frame at the origin (the frames
//! at the entity and at the origin differ by the meridians' convergence: 0.07° at
//! 10 km at 45°, left out).
//!
//! Source: CIGI ICD 3.3 §4.1.2, §4.1.16, §4.1.21; WGS 84 (NIMA TR8350.2).

use std::collections::BTreeMap;

use glam::{DMat3, DVec3, Vec2, Vec3};

use crate::packet::{CelestialSphereControl, EntityControl, ViewControl, ViewDefinition};

/// WGS 84 semi-major axis, m.
pub const WGS84_A_M: f64 = 6_378_137.0;
/// WGS 84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// Where the scene's origin lies on the Earth: the point whose local tangent plane
/// the scene is drawn on (its `y = 0` at `altitude_m`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeodeticOrigin {
    /// Latitude, degrees.
    pub latitude_deg: f64,
    /// Longitude, degrees.
    pub longitude_deg: f64,
    /// Altitude above the ellipsoid, m.
    pub altitude_m: f64,
}

impl Default for GeodeticOrigin {
    /// 0° N 0° E at sea level (a host whose database has no origin: give one with
    /// the viewer's `--origin`).
    fn default() -> Self {
        Self {
            latitude_deg: 0.0,
            longitude_deg: 0.0,
            altitude_m: 0.0,
        }
    }
}

/// Earth-centred, Earth-fixed coordinates of a geodetic point, m.
#[must_use]
pub fn ecef_m(latitude_deg: f64, longitude_deg: f64, altitude_m: f64) -> DVec3 {
    let e2 = WGS84_F * (2.0 - WGS84_F);
    let (sin_lat, cos_lat) = latitude_deg.to_radians().sin_cos();
    let (sin_lon, cos_lon) = longitude_deg.to_radians().sin_cos();
    let n = WGS84_A_M / (1.0 - e2 * sin_lat * sin_lat).sqrt();
    DVec3::new(
        (n + altitude_m) * cos_lat * cos_lon,
        (n + altitude_m) * cos_lat * sin_lon,
        (n * (1.0 - e2) + altitude_m) * sin_lat,
    )
}

impl GeodeticOrigin {
    /// Checks the latitude (±90°), longitude (±180°) and altitude (±20 km).
    pub fn validate(&self) -> Result<(), String> {
        if !(self.latitude_deg.is_finite() && self.latitude_deg.abs() <= 90.0) {
            return Err(format!(
                "latitude {} must be within ±90°",
                self.latitude_deg
            ));
        }
        if !(self.longitude_deg.is_finite() && self.longitude_deg.abs() <= 180.0) {
            return Err(format!(
                "longitude {} must be within ±180°",
                self.longitude_deg
            ));
        }
        if !(self.altitude_m.is_finite() && self.altitude_m.abs() <= 20_000.0) {
            return Err(format!(
                "altitude {} m must be within ±20 000 m",
                self.altitude_m
            ));
        }
        Ok(())
    }

    /// A geodetic point in the scene's world: east, up, −north on the tangent
    /// plane at the origin, m.
    #[must_use]
    pub fn world_m(&self, latitude_deg: f64, longitude_deg: f64, altitude_m: f64) -> DVec3 {
        let d = ecef_m(latitude_deg, longitude_deg, altitude_m)
            - ecef_m(self.latitude_deg, self.longitude_deg, self.altitude_m);
        let (sin_lat, cos_lat) = self.latitude_deg.to_radians().sin_cos();
        let (sin_lon, cos_lon) = self.longitude_deg.to_radians().sin_cos();
        let east = -sin_lon * d.x + cos_lon * d.y;
        let north = -sin_lat * cos_lon * d.x - sin_lat * sin_lon * d.y + cos_lat * d.z;
        let up = cos_lat * cos_lon * d.x + cos_lat * sin_lon * d.y + sin_lat * d.z;
        DVec3::new(east, up, -north)
    }
}

/// North-east-down → the world's east, up, −north.
fn world_of_ned(v: DVec3) -> DVec3 {
    DVec3::new(v.y, -v.z, -v.x)
}

/// The rotation of the body axes (x forward, y right, z down) into north-east-down
/// for a yaw, pitch and roll in degrees.
#[must_use]
pub fn attitude(yaw_deg: f64, pitch_deg: f64, roll_deg: f64) -> DMat3 {
    DMat3::from_rotation_z(yaw_deg.to_radians())
        * DMat3::from_rotation_y(pitch_deg.to_radians())
        * DMat3::from_rotation_x(roll_deg.to_radians())
}

/// The world's forward and up (unit) of a body turned by a heading (clockwise from
/// north), pitch (nose up) and roll (right wing down), degrees.
#[must_use]
pub fn view_axes(yaw_deg: f64, pitch_deg: f64, roll_deg: f64) -> (Vec3, Vec3) {
    let r = attitude(yaw_deg, pitch_deg, roll_deg);
    (
        world_of_ned(r * DVec3::X).normalize().as_vec3(),
        world_of_ned(-(r * DVec3::Z)).normalize().as_vec3(),
    )
}

/// Where the view precip draws stands and looks, in the scene's world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eyepoint {
    /// The eye, m.
    pub position_m: Vec3,
    /// The direction it looks (unit).
    pub forward: Vec3,
    /// The view's up (unit, square to `forward`).
    pub up: Vec3,
    /// The vertical field of view, rad, when the host defined one.
    pub vertical_fov_rad: Option<f32>,
    /// The lens shift of an off-axis view (NDC), when the host defined one: the
    /// horizontal part relative to the image's own width.
    pub lens_shift: Option<Vec2>,
}

/// An entity's pose in the world.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pose {
    position_m: DVec3,
    /// Body → north-east-down.
    rotation: DMat3,
}

/// The entities, views and field of view a host has set (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct HostView {
    origin: GeodeticOrigin,
    view_id: u16,
    entities: BTreeMap<u16, Pose>,
    view_control: Option<ViewControl>,
    field_of_view: Option<(f32, f32, f32, f32)>,
}

/// The most entities followed (a host with more is an exercise, not an
/// ownship: the rest are not placed).
pub const MAX_ENTITIES: usize = 1024;

impl HostView {
    /// Draws view `view_id` on the tangent plane at `origin`.
    #[must_use]
    pub fn new(origin: GeodeticOrigin, view_id: u16) -> Self {
        Self {
            origin,
            view_id,
            entities: BTreeMap::new(),
            view_control: None,
            field_of_view: None,
        }
    }

    /// Takes an Entity Control; false when it placed nothing (a destroyed or
    /// standby entity is forgotten; an attached one whose parent is unknown, or one
    /// past [`MAX_ENTITIES`], is not placed).
    pub fn apply_entity(&mut self, packet: &EntityControl) -> bool {
        if packet.entity_state != 1 {
            self.entities.remove(&packet.entity_id);
            return false;
        }
        let own = attitude(
            f64::from(packet.yaw_deg),
            f64::from(packet.pitch_deg),
            f64::from(packet.roll_deg),
        );
        let pose = if packet.attached {
            let Some(parent) = self.entities.get(&packet.parent_id).copied() else {
                return false;
            };
            let offset = DVec3::new(
                packet.latitude_deg_or_x_m,
                packet.longitude_deg_or_y_m,
                packet.altitude_m_or_z_m,
            );
            Pose {
                position_m: parent.position_m + world_of_ned(parent.rotation * offset),
                rotation: parent.rotation * own,
            }
        } else {
            Pose {
                position_m: self.origin.world_m(
                    packet.latitude_deg_or_x_m,
                    packet.longitude_deg_or_y_m,
                    packet.altitude_m_or_z_m,
                ),
                rotation: own,
            }
        };
        if self.entities.len() >= MAX_ENTITIES && !self.entities.contains_key(&packet.entity_id) {
            return false;
        }
        self.entities.insert(packet.entity_id, pose);
        true
    }

    /// Toward the sun at the date and time of a Celestial Sphere Control, seen from
    /// the origin (precip_model::weather::sun); `None` when the host does not ask
    /// for the ephemeris model or sends no valid date (MMDDYYYY).
    #[must_use]
    pub fn sun(&self, packet: &CelestialSphereControl) -> Option<Vec3> {
        if !(packet.ephemeris && packet.date_valid) || packet.hour > 23 || packet.minute > 59 {
            return None;
        }
        let time = precip_model::weather::sun::UtcTime {
            year: (packet.date % 10_000) as i32,
            month: packet.date / 1_000_000,
            day: (packet.date / 10_000) % 100,
            hour: f64::from(packet.hour) + f64::from(packet.minute) / 60.0,
        };
        if !((1..=12).contains(&time.month) && (1..=31).contains(&time.day)) {
            return None;
        }
        Some(precip_model::weather::sun::to_sun_at(
            &time,
            self.origin.latitude_deg,
            self.origin.longitude_deg,
        ))
    }

    /// Takes a View Control; false when it is for another view.
    pub fn apply_view_control(&mut self, packet: &ViewControl) -> bool {
        if packet.view_id != self.view_id {
            return false;
        }
        // Fields not enabled keep their last value.
        let mut next = *packet;
        if let Some(last) = self.view_control {
            for i in 0..6 {
                if !packet.enabled[i] {
                    next.offsets[i] = last.offsets[i];
                    next.enabled[i] = last.enabled[i];
                }
            }
        }
        self.view_control = Some(next);
        true
    }

    /// Takes a View Definition; false when it is for another view or its
    /// half-angles make no field of view (each within ±89°, top above bottom and
    /// right of left, by at least 1°).
    pub fn apply_view_definition(&mut self, packet: &ViewDefinition) -> bool {
        if packet.view_id != self.view_id {
            return false;
        }
        let (mut left, mut right, mut top, mut bottom) =
            self.field_of_view.unwrap_or((-30.0, 30.0, 20.0, -20.0));
        let v = packet.values;
        for (i, slot) in [&mut left, &mut right, &mut top, &mut bottom]
            .into_iter()
            .enumerate()
        {
            if packet.enabled[2 + i] {
                *slot = v[2 + i];
            }
        }
        let sane = [left, right, top, bottom].iter().all(|a| a.abs() <= 89.0)
            && right - left >= 1.0
            && top - bottom >= 1.0;
        if !sane {
            return false;
        }
        self.field_of_view = Some((left, right, top, bottom));
        true
    }

    /// The eyepoint: the view's entity's pose moved and turned by its View Control
    /// (the ownship's pose before any), with the View Definition's field of view;
    /// `None` before the host placed that entity.
    #[must_use]
    pub fn eyepoint(&self, aspect: f32) -> Option<Eyepoint> {
        let entity = self.view_control.map_or(0, |v| v.entity_id);
        let pose = self.entities.get(&entity)?;
        let (offset, turn) = self
            .view_control
            .map_or((DVec3::ZERO, DMat3::IDENTITY), |v| {
                let o = |i: usize| f64::from(if v.enabled[i] { v.offsets[i] } else { 0.0 });
                (DVec3::new(o(0), o(1), o(2)), attitude(o(5), o(4), o(3)))
            });
        let rotation = pose.rotation * turn;
        let position = pose.position_m + world_of_ned(pose.rotation * offset);
        let forward = world_of_ned(rotation * DVec3::X).normalize();
        let up = world_of_ned(-(rotation * DVec3::Z)).normalize();
        let (vertical_fov_rad, lens_shift) = match self.field_of_view {
            Some(fov) => {
                let (fov, shift) = fov_and_shift(fov, aspect);
                (Some(fov), Some(shift))
            }
            None => (None, None),
        };
        Some(Eyepoint {
            position_m: position.as_vec3(),
            forward: forward.as_vec3(),
            up: up.as_vec3(),
            vertical_fov_rad,
            lens_shift,
        })
    }
}

/// The vertical field of view (rad) and the lens shift (NDC) of half-angles
/// `(left, right, top, bottom)` in degrees drawn into an image of `aspect`
/// (width / height): the vertical extent is the view's, the horizontal follows the
/// image's aspect, and each axis is shifted so the view's centre direction lands at
/// the image's centre.
#[must_use]
pub fn fov_and_shift((left, right, top, bottom): (f32, f32, f32, f32), aspect: f32) -> (f32, Vec2) {
    let t = |deg: f32| deg.to_radians().tan();
    let half_height = 0.5 * (t(top) - t(bottom));
    let half_width = aspect.max(1e-3) * half_height;
    let shift = Vec2::new(
        0.5 * (t(right) + t(left)) / half_width,
        0.5 * (t(top) + t(bottom)) / half_height,
    );
    (2.0 * half_height.atan(), shift)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ORIGIN: GeodeticOrigin = GeodeticOrigin {
        latitude_deg: 47.0,
        longitude_deg: 8.0,
        altitude_m: 400.0,
    };

    fn close(a: DVec3, b: DVec3, tolerance: f64) -> bool {
        (a - b).length() <= tolerance
    }

    #[test]
    fn the_tangent_plane_is_east_up_minus_north_and_curves_away() {
        assert!(close(ORIGIN.world_m(47.0, 8.0, 400.0), DVec3::ZERO, 1e-6));
        // Straight up is +y.
        assert!(close(
            ORIGIN.world_m(47.0, 8.0, 500.0),
            DVec3::Y * 100.0,
            1e-6
        ));
        // 0.01° north: the meridian's radius of curvature at 47°, M = a(1 − e²)/(1 −
        // e² sin²φ)^(3/2) = 6 371 131 m → 1 111.98 m, toward −z; the plane lies
        // d²/2R = 0.097 m above the ground there.
        let north = ORIGIN.world_m(47.01, 8.0, 400.0);
        assert!((north.z + 1_111.98).abs() < 0.5, "{north}");
        assert!(
            north.x.abs() < 1e-3 && (north.y + 0.097).abs() < 0.01,
            "{north}"
        );
        // 0.01° east: N cos φ = 6 389 188 · cos 47° → 760.5 m toward +x.
        let east = ORIGIN.world_m(47.0, 8.01, 400.0);
        assert!((east.x - 760.5).abs() < 0.5 && east.z.abs() < 0.1, "{east}");
        // 10 km away the ground falls 7.8 m below the plane.
        let far = ORIGIN.world_m(47.0 + 10_000.0 / 111_198.0, 8.0, 400.0);
        assert!((far.y + 7.85).abs() < 0.1, "{far}");
        // The distance is the chord's.
        let chord = (ecef_m(47.01, 8.01, 900.0) - ecef_m(47.0, 8.0, 400.0)).length();
        assert!((ORIGIN.world_m(47.01, 8.01, 900.0).length() - chord).abs() < 1e-6);
        assert!(
            GeodeticOrigin {
                latitude_deg: 91.0,
                ..ORIGIN
            }
            .validate()
            .is_err()
        );
        assert!(ORIGIN.validate().is_ok());
    }

    #[test]
    fn heading_pitch_and_roll_turn_the_view_as_a_pilot_expects() {
        let axes = |yaw: f64, pitch: f64, roll: f64| {
            let r = attitude(yaw, pitch, roll);
            (world_of_ned(r * DVec3::X), world_of_ned(-(r * DVec3::Z)))
        };
        // North is −z, east +x; up is +y.
        let (f, u) = axes(0.0, 0.0, 0.0);
        assert!(close(f, DVec3::NEG_Z, 1e-12) && close(u, DVec3::Y, 1e-12));
        let (f, _) = axes(90.0, 0.0, 0.0);
        assert!(close(f, DVec3::X, 1e-12));
        // Nose up 30°: forward rises.
        let (f, u) = axes(0.0, 30.0, 0.0);
        assert!(
            close(f, DVec3::new(0.0, 0.5, -0.75f64.sqrt()), 1e-12),
            "{f}"
        );
        assert!(u.z > 0.0, "the top leans back (south, +z): {u}");
        // Right wing down 30° flying north: the top leans east (right).
        let (_, u) = axes(0.0, 0.0, 30.0);
        assert!(close(u, DVec3::new(0.5, 0.75f64.sqrt(), 0.0), 1e-12), "{u}");
    }

    fn ownship(lat: f64, lon: f64, alt: f64, yaw: f32) -> EntityControl {
        EntityControl {
            entity_id: 0,
            entity_state: 1,
            attached: false,
            entity_type: 0,
            parent_id: 0,
            roll_deg: 0.0,
            pitch_deg: 0.0,
            yaw_deg: yaw,
            latitude_deg_or_x_m: lat,
            longitude_deg_or_y_m: lon,
            altitude_m_or_z_m: alt,
        }
    }

    #[test]
    fn the_view_rides_on_its_entity_with_its_offsets_and_field_of_view() {
        let mut host = HostView::new(ORIGIN, 0);
        assert_eq!(host.eyepoint(16.0 / 9.0), None, "nothing placed yet");
        assert!(host.apply_entity(&ownship(47.0, 8.0, 700.0, 90.0)));
        let eye = host.eyepoint(16.0 / 9.0).expect("placed");
        assert!((eye.position_m - Vec3::new(0.0, 300.0, 0.0)).length() < 1e-3);
        assert!((eye.forward - Vec3::X).length() < 1e-6);
        assert_eq!(eye.vertical_fov_rad, None);
        // A pilot's eye 3 m ahead and 1 m above the reference point, looking 90°
        // left (north), on view 0; View Control for view 1 is not ours.
        let mut control = ViewControl {
            view_id: 1,
            group_id: 0,
            enabled: [true; 6],
            entity_id: 0,
            offsets: [3.0, 0.0, -1.0, 0.0, 0.0, -90.0],
        };
        assert!(!host.apply_view_control(&control));
        control.view_id = 0;
        assert!(host.apply_view_control(&control));
        let eye = host.eyepoint(16.0 / 9.0).expect("placed");
        assert!(
            (eye.position_m - Vec3::new(3.0, 301.0, 0.0)).length() < 1e-3,
            "{eye:?}"
        );
        assert!((eye.forward - Vec3::NEG_Z).length() < 1e-6, "{eye:?}");
        // A wingman attached 10 m to the right of the ownship.
        let wingman = EntityControl {
            entity_id: 7,
            attached: true,
            latitude_deg_or_x_m: 0.0,
            longitude_deg_or_y_m: 10.0,
            altitude_m_or_z_m: 0.0,
            yaw_deg: 0.0,
            parent_id: 0,
            ..ownship(0.0, 0.0, 0.0, 0.0)
        };
        assert!(host.apply_entity(&wingman));
        // The ownship flies east: its right is south, +z.
        let unknown_parent = EntityControl {
            parent_id: 99,
            ..wingman
        };
        assert!(!host.apply_entity(&unknown_parent));
        // A 60° × 40° view pitched 10° down by its half-angles (top 10°, bottom
        // −30°): a vertical field of 40° and a shift up the image.
        let definition = ViewDefinition {
            view_id: 0,
            group_id: 0,
            enabled: [false, false, true, true, true, true],
            values: [0.0, 0.0, -30.0, 30.0, 10.0, -30.0],
        };
        assert!(host.apply_view_definition(&definition));
        let eye = host.eyepoint(1.5).expect("placed");
        let fov = eye.vertical_fov_rad.expect("defined");
        let tan_sum = 10f32.to_radians().tan() + 30f32.to_radians().tan();
        assert!((fov - 2.0 * (tan_sum / 2.0).atan()).abs() < 1e-6);
        let shift = eye.lens_shift.expect("defined");
        assert!(shift.x.abs() < 1e-6 && shift.y < -0.3, "{shift}");
        // A field of view that is none is refused; a destroyed ownship leaves no view.
        let flat = ViewDefinition {
            values: [0.0, 0.0, -30.0, 30.0, 10.0, 10.0],
            ..definition
        };
        assert!(!host.apply_view_definition(&flat));
        let destroyed = EntityControl {
            entity_state: 2,
            ..ownship(47.0, 8.0, 700.0, 90.0)
        };
        assert!(!host.apply_entity(&destroyed));
        assert_eq!(host.eyepoint(1.5), None);
    }

    #[test]
    fn an_off_axis_view_lands_its_centre_at_the_image_s_centre() {
        // A symmetric view: no shift, the vertical field as given.
        let (fov, shift) = fov_and_shift((-30.0, 30.0, 20.0, -20.0), 1.5);
        assert!((fov - 40f32.to_radians()).abs() < 1e-6 && shift.length() < 1e-6);
        // The right half of a wide rig: its centre direction's NDC under the
        // symmetric projection is the shift.
        let (fov, shift) = fov_and_shift((0.0, 60.0, 20.0, -20.0), 1.5);
        let half_width = 1.5 * (fov / 2.0).tan();
        let centre = 0.5 * 60f32.to_radians().tan();
        assert!((shift.x - centre / half_width).abs() < 1e-6, "{shift}");
    }
}
