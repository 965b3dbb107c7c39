//! A camera flown along waypoints (`--flight FILE`, or `orbit`: once around the demo):
//! each line `t_s x_m y_m z_m heading_deg pitch_deg [roll_deg]` (commas or spaces,
//! `#` comments), times increasing; world axes as the scene's (x east, y up, z
//! south), the heading clockwise from north (−z), pitch up, roll right wing down —
//! the attitude CIGI hosts use ([`precip_cigi::host_view::view_axes`]). Between
//! waypoints the position and the angles are interpolated linearly (the heading the
//! short way round); before the first and after the last the camera holds.

use glam::Vec3;
use precip_model::Camera;

/// One waypoint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Waypoint {
    /// When, s from the start.
    pub t_s: f64,
    /// Where, m.
    pub position_m: Vec3,
    /// Heading, pitch, roll, degrees.
    pub attitude_deg: [f64; 3],
}

/// A flight: waypoints in time order.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    waypoints: Vec<Waypoint>,
}

/// The built-in `orbit`: once around the demo house in 24 s, 30 m out and 12 m up,
/// looking at it 15° down.
pub const ORBIT: &str = "# t_s x_m y_m z_m heading_deg pitch_deg roll_deg
0 0 12 30 0 -15 0
6 -30 12 0 90 -15 0
12 0 12 -30 180 -15 0
18 30 12 0 270 -15 0
24 0 12 30 360 -15 0
";

impl Flight {
    /// Reads a flight from `text` (`name` says where in errors).
    pub fn parse(text: &str, name: &str) -> Result<Self, String> {
        let mut waypoints: Vec<Waypoint> = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or_default().trim();
            if line.is_empty() {
                continue;
            }
            let at = || format!("{name}:{}", n + 1);
            let numbers: Vec<f64> = line
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|t| !t.is_empty())
                .map(|t| {
                    t.parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| format!("{}: `{t}` is not a finite number", at()))
                })
                .collect::<Result<_, _>>()?;
            let (t_s, x, y, z, heading, pitch, roll) = match numbers.as_slice() {
                [t, x, y, z, h, p] => (*t, *x, *y, *z, *h, *p, 0.0),
                [t, x, y, z, h, p, r] => (*t, *x, *y, *z, *h, *p, *r),
                _ => {
                    return Err(format!(
                        "{}: {} numbers; a waypoint is `t_s x_m y_m z_m heading_deg pitch_deg [roll_deg]`",
                        at(),
                        numbers.len()
                    ));
                }
            };
            if let Some(last) = waypoints.last()
                && t_s <= last.t_s
            {
                return Err(format!(
                    "{}: t = {t_s} s is not after the waypoint before ({} s): times must increase",
                    at(),
                    last.t_s
                ));
            }
            if pitch.abs() > 90.0 || [x, y, z].iter().any(|v| v.abs() > 1.0e6) {
                return Err(format!(
                    "{}: pitch within ±90° and positions within ±1 000 km, please",
                    at()
                ));
            }
            waypoints.push(Waypoint {
                t_s,
                position_m: Vec3::new(x as f32, y as f32, z as f32),
                attitude_deg: [heading, pitch, roll],
            });
        }
        if waypoints.is_empty() {
            return Err(format!(
                "{name}: no waypoint (`t_s x_m y_m z_m heading_deg pitch_deg [roll_deg]` per line)"
            ));
        }
        Ok(Self { waypoints })
    }

    /// `orbit` or `valley` (built in: [`crate::terrain_file::valley_flight`], over
    /// `--terrain generated`) or the flight in the file `name`.
    pub fn load(name: &str) -> Result<Self, String> {
        if name == "orbit" {
            return Self::parse(ORBIT, "orbit");
        }
        if name == "valley" {
            return Self::parse(&crate::terrain_file::valley_flight(), "valley");
        }
        let text = std::fs::read_to_string(name).map_err(|e| format!("--flight {name}: {e}"))?;
        Self::parse(&text, name)
    }

    /// How long it flies, s.
    #[must_use]
    pub fn duration_s(&self) -> f64 {
        let first = self.waypoints.first().map_or(0.0, |w| w.t_s);
        self.waypoints.last().map_or(0.0, |w| w.t_s) - first
    }

    /// `template` (its lens) where the flight is at `t_s`.
    #[must_use]
    pub fn camera_at(&self, t_s: f64, template: &Camera) -> Camera {
        let next = self.waypoints.partition_point(|w| w.t_s <= t_s);
        let (a, b, f) = match (next.checked_sub(1), self.waypoints.get(next)) {
            (Some(i), Some(b)) => {
                let a = &self.waypoints[i];
                (a, b, (t_s - a.t_s) / (b.t_s - a.t_s))
            }
            (Some(i), None) => (&self.waypoints[i], &self.waypoints[i], 0.0),
            (None, _) => (&self.waypoints[0], &self.waypoints[0], 0.0),
        };
        let mut attitude = [0.0; 3];
        for (k, angle) in attitude.iter_mut().enumerate() {
            // The short way round.
            let delta = (b.attitude_deg[k] - a.attitude_deg[k] + 180.0).rem_euclid(360.0) - 180.0;
            *angle = a.attitude_deg[k] + f * delta;
        }
        let (forward, up) =
            precip_cigi::host_view::view_axes(attitude[0], attitude[1], attitude[2]);
        Camera {
            position_m: a.position_m.lerp(b.position_m, f as f32),
            forward,
            up,
            ..*template
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_orbit_circles_the_house_looking_at_it() {
        let orbit = Flight::load("orbit").expect("built in");
        assert!((orbit.duration_s() - 24.0).abs() < 1e-9);
        let template = Camera::default();
        for k in 0..=48 {
            let t = f64::from(k) * 0.5;
            let c = orbit.camera_at(t, &template);
            // On the waypoints' square-ish path 12 m up, looking toward the house.
            assert!((c.position_m.y - 12.0).abs() < 1e-4);
            let to_house = (Vec3::new(0.0, 12.0, 0.0) - c.position_m).normalize();
            let level = Vec3::new(c.forward.x, 0.0, c.forward.z).normalize();
            assert!(level.dot(to_house) > 0.7, "t {t}: {level} vs {to_house}");
            assert!((c.forward.y + 15f32.to_radians().sin()).abs() < 1e-4);
        }
        // At a waypoint exactly: 6 s is west of the house heading east.
        let c = orbit.camera_at(6.0, &template);
        assert!((c.position_m - Vec3::new(-30.0, 12.0, 0.0)).length() < 1e-4);
        assert!(c.forward.x > 0.9);
        // Before and after: held.
        assert_eq!(
            orbit.camera_at(-1.0, &template),
            orbit.camera_at(0.0, &template)
        );
        assert_eq!(
            orbit.camera_at(99.0, &template),
            orbit.camera_at(24.0, &template)
        );
    }

    #[test]
    fn bad_flights_say_which_line() {
        let e = Flight::parse("0 0 1 0 0 0\n0 1 1 0 0 0\n", "f.txt").expect_err("same time");
        assert!(e.contains("f.txt:2") && e.contains("increase"), "{e}");
        let e = Flight::parse("# only\n\n", "f.txt").expect_err("empty");
        assert!(e.contains("no waypoint"), "{e}");
        let e = Flight::parse("0, 0, 1, 0, nan, 0", "f.txt").expect_err("nan");
        assert!(e.contains("f.txt:1") && e.contains("nan"), "{e}");
        let e = Flight::parse("0 0 1 0 0", "f.txt").expect_err("five");
        assert!(e.contains("5 numbers"), "{e}");
        assert!(Flight::parse("0 0 1 0 0 95", "f.txt").is_err());
        let ok = Flight::parse("0,0,1,0,350,0\n10,100,1,0,10,0,5", "f.txt").expect("valid");
        // Heading 350° → 10° the short way: 0° half way.
        let c = ok.camera_at(5.0, &Camera::default());
        assert!((c.forward - Vec3::NEG_Z).length() < 1e-3, "{c:?}");
        assert!((c.position_m.x - 50.0).abs() < 1e-4);
    }
}
