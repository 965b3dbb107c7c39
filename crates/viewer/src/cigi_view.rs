//! The camera a CIGI host flies ([`precip_cigi::CigiReceiver::take_eyepoint`]): its
//! eyepoint with the viewer's lens, and the command line's `--origin`.

use precip_cigi::{Eyepoint, GeodeticOrigin};
use precip_model::Camera;

/// `camera` moved to the host's eyepoint: its position, direction and roll (`up`),
/// and the field of view and off-axis shift the host defined (else `camera`'s).
#[must_use]
pub fn camera_at_eyepoint(eye: &Eyepoint, camera: &Camera) -> Camera {
    Camera {
        position_m: eye.position_m,
        forward: eye.forward,
        up: eye.up,
        vertical_fov_rad: eye.vertical_fov_rad.unwrap_or(camera.vertical_fov_rad),
        lens_shift: eye.lens_shift.unwrap_or(camera.lens_shift),
        ..*camera
    }
}

/// `LAT,LON[,ALT]` (degrees, degrees, metres above the WGS 84 ellipsoid): where
/// the scene's origin lies on the Earth.
pub fn parse_origin(text: &str) -> Result<GeodeticOrigin, String> {
    let numbers: Vec<f64> = text
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .map_err(|e| format!("`{t}` in `{text}`: {e}"))
        })
        .collect::<Result<_, _>>()?;
    let origin = match numbers.as_slice() {
        [lat, lon] => GeodeticOrigin {
            latitude_deg: *lat,
            longitude_deg: *lon,
            altitude_m: 0.0,
        },
        [lat, lon, alt] => GeodeticOrigin {
            latitude_deg: *lat,
            longitude_deg: *lon,
            altitude_m: *alt,
        },
        _ => {
            return Err(format!(
                "`{text}`: write LAT,LON or LAT,LON,ALT (degrees, degrees, m), e.g. 47.45,8.56,430"
            ));
        }
    };
    origin.validate().map_err(|e| format!("`{text}`: {e}"))?;
    Ok(origin)
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3};

    use super::*;

    #[test]
    fn the_origin_is_read_and_checked_and_the_eyepoint_keeps_the_lens() {
        let o = parse_origin("47.45, 8.56,430").expect("valid");
        assert_eq!(
            (o.latitude_deg, o.longitude_deg, o.altitude_m),
            (47.45, 8.56, 430.0)
        );
        assert!(parse_origin("47,8").expect("valid").altitude_m.abs() < 1e-12);
        for bad in ["47", "47,8,1,2", "north,8", "95,8", "47,8,1e9"] {
            assert!(parse_origin(bad).is_err(), "{bad}");
        }
        let eye = Eyepoint {
            position_m: Vec3::new(1.0, 300.0, -2.0),
            forward: Vec3::X,
            up: Vec3::new(0.0, 0.8, 0.6),
            vertical_fov_rad: None,
            lens_shift: Some(Vec2::new(0.2, 0.0)),
        };
        let camera = camera_at_eyepoint(&eye, &Camera::default());
        assert_eq!(camera.position_m, eye.position_m);
        assert_eq!(camera.up, eye.up);
        assert!((camera.vertical_fov_rad - Camera::default().vertical_fov_rad).abs() < 1e-9);
        assert_eq!(camera.lens_shift, Vec2::new(0.2, 0.0));
        assert_eq!(camera.lens, Camera::default().lens);
    }
}
