//! Where the sun stands at a time and place (docs/model.md (6.17)): the NOAA
//! Global Monitoring Laboratory's "General Solar Position Calculations" (Spencer
//! 1971's Fourier series for the equation of time and the declination; about
//! 0.1° — plenty for the direction of a scene's light). What a scenario's
//! `TimeOfDay` (or a CIGI host's date and time) says about the light, at the
//! scene's geodetic origin.

use glam::Vec3;

/// A date and time in UTC.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UtcTime {
    /// Year, e.g. 2026.
    pub year: i32,
    /// Month, 1–12.
    pub month: u32,
    /// Day of the month, 1–31.
    pub day: u32,
    /// Hours since midnight, with minutes and seconds as fractions.
    pub hour: f64,
}

impl UtcTime {
    /// Reads ISO 8601 `YYYY-MM-DDTHH:MM:SS[.s][Z|±HH:MM]` (no offset: UTC), as
    /// OpenSCENARIO's `dateTime` is written.
    pub fn parse_iso8601(text: &str) -> Result<Self, String> {
        let bad = || format!("`{text}` is not a date and time as YYYY-MM-DDTHH:MM:SS[±HH:MM]");
        let t = text.trim();
        let (date, rest) = t.split_once(['T', ' ']).ok_or_else(bad)?;
        let mut d = date.split('-');
        let next = |it: &mut std::str::Split<'_, char>| -> Result<i64, String> {
            it.next().and_then(|v| v.parse().ok()).ok_or_else(bad)
        };
        let (year, month, day) = (next(&mut d)?, next(&mut d)?, next(&mut d)?);
        // The offset: Z, +HH:MM or -HH:MM after the time.
        let (time, offset_h) = if let Some(clock) = rest.strip_suffix('Z') {
            (clock, 0.0)
        } else if let Some(at) = rest.rfind(['+', '-']).filter(|&i| i >= 5) {
            let (clock, off) = rest.split_at(at);
            let sign = if off.starts_with('-') { -1.0 } else { 1.0 };
            let (h, m) = off[1..].split_once(':').unwrap_or((&off[1..], "0"));
            let h: f64 = h.parse().map_err(|_| bad())?;
            let m: f64 = m.parse().map_err(|_| bad())?;
            (clock, sign * (h + m / 60.0))
        } else {
            (rest, 0.0)
        };
        let mut c = time.split(':');
        let h: f64 = c.next().and_then(|v| v.parse().ok()).ok_or_else(bad)?;
        let m: f64 = c.next().and_then(|v| v.parse().ok()).ok_or_else(bad)?;
        let s: f64 = c.next().map_or(Ok(0.0), |v| v.parse().map_err(|_| bad()))?;
        let valid = (1..=12).contains(&month)
            && (1..=31).contains(&day)
            && (0.0..24.0).contains(&h)
            && (0.0..60.0).contains(&m)
            && (0.0..61.0).contains(&s);
        if !valid {
            return Err(bad());
        }
        // To UTC: a day either way is fine for the sun's direction.
        Ok(Self {
            year: year as i32,
            month: month as u32,
            day: day as u32,
            hour: h + m / 60.0 + s / 3600.0 - offset_h,
        })
    }

    /// The day of the year, 1 on 1 January.
    #[must_use]
    pub fn day_of_year(&self) -> u32 {
        const BEFORE: [u32; 12] = [0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334];
        let leap = (self.year % 4 == 0 && self.year % 100 != 0) || self.year % 400 == 0;
        let m = self.month.clamp(1, 12) as usize;
        BEFORE[m - 1]
            .saturating_add(self.day)
            .saturating_add(u32::from(leap && m > 2))
    }
}

/// The sun's elevation and azimuth (clockwise from north), rad, at `time` seen
/// from `latitude_deg`, `longitude_deg` (east positive).
#[must_use]
pub fn solar_elevation_azimuth_rad(
    time: &UtcTime,
    latitude_deg: f64,
    longitude_deg: f64,
) -> (f64, f64) {
    use std::f64::consts::PI;
    let gamma =
        2.0 * PI / 365.0 * (f64::from(time.day_of_year()) - 1.0 + (time.hour - 12.0) / 24.0);
    let (s1, c1) = gamma.sin_cos();
    let (s2, c2) = (2.0 * gamma).sin_cos();
    let (s3, c3) = (3.0 * gamma).sin_cos();
    // The equation of time, minutes, and the declination, rad (Spencer 1971).
    let equation_of_time =
        229.18 * (0.000075 + 0.001868 * c1 - 0.032077 * s1 - 0.014615 * c2 - 0.040849 * s2);
    let declination = 0.006918 - 0.399912 * c1 + 0.070257 * s1 - 0.006758 * c2 + 0.000907 * s2
        - 0.002697 * c3
        + 0.00148 * s3;
    // True solar time, minutes, and the hour angle.
    let solar_minutes =
        (time.hour * 60.0 + equation_of_time + 4.0 * longitude_deg).rem_euclid(1440.0);
    let hour_angle = (solar_minutes / 4.0 - 180.0).to_radians();
    let lat = latitude_deg.to_radians();
    let cos_zenith = (lat.sin() * declination.sin()
        + lat.cos() * declination.cos() * hour_angle.cos())
    .clamp(-1.0, 1.0);
    let zenith = cos_zenith.acos();
    // Azimuth clockwise from north: from the east and north parts of the sun's
    // direction.
    let east = -declination.cos() * hour_angle.sin();
    let north = lat.cos() * declination.sin() - lat.sin() * declination.cos() * hour_angle.cos();
    let azimuth = east.atan2(north).rem_euclid(2.0 * PI);
    (PI / 2.0 - zenith, azimuth)
}

/// Toward the sun in the scene's world (x east, y up, z south), unit; a sun under
/// the horizon lights from just above it (0.05 rad: precip has no night).
#[must_use]
pub fn to_sun_at(time: &UtcTime, latitude_deg: f64, longitude_deg: f64) -> Vec3 {
    let (elevation, azimuth) = solar_elevation_azimuth_rad(time, latitude_deg, longitude_deg);
    let e = elevation.max(0.05);
    Vec3::new(
        (azimuth.sin() * e.cos()) as f32,
        e.sin() as f32,
        (-azimuth.cos() * e.cos()) as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(text: &str) -> UtcTime {
        UtcTime::parse_iso8601(text).expect("valid")
    }

    #[test]
    fn iso_dates_with_offsets_read_as_utc() {
        let t = at("2026-06-21T14:30:00+02:00");
        assert_eq!((t.year, t.month, t.day), (2026, 6, 21));
        assert!((t.hour - 12.5).abs() < 1e-9);
        assert!((at("2026-06-21T12:30:00Z").hour - 12.5).abs() < 1e-9);
        assert!((at("2026-06-21T12:30:00").hour - 12.5).abs() < 1e-9);
        assert!((at("2026-06-21T06:00:00.5-05:30").hour - (6.0 + 0.5 / 3600.0 + 5.5)).abs() < 1e-9);
        assert_eq!(at("2024-03-01T00:00:00").day_of_year(), 61, "leap year");
        assert_eq!(at("2026-03-01T00:00:00").day_of_year(), 60);
        for bad in [
            "2026-13-01T00:00:00",
            "noon",
            "2026-06-21",
            "2026-06-21T25:00:00",
        ] {
            assert!(UtcTime::parse_iso8601(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_sun_stands_where_the_almanac_says() {
        // Solstice noon at 47° N, 8° E (local solar noon ≈ 11:30 UTC): elevation
        // 90 − 47 + 23.44 = 66.4°, due south.
        let (e, a) = solar_elevation_azimuth_rad(&at("2026-06-21T11:30:00Z"), 47.0, 8.0);
        assert!((e.to_degrees() - 66.4).abs() < 0.5, "{}", e.to_degrees());
        assert!((a.to_degrees() - 180.0).abs() < 3.0, "{}", a.to_degrees());
        // Winter solstice noon: 90 − 47 − 23.44 = 19.6°.
        let (e, _) = solar_elevation_azimuth_rad(&at("2026-12-21T11:30:00Z"), 47.0, 8.0);
        assert!((e.to_degrees() - 19.6).abs() < 0.5, "{}", e.to_degrees());
        // Equinox morning on the equator: rising due east.
        let (e, a) = solar_elevation_azimuth_rad(&at("2026-03-20T06:07:00Z"), 0.0, 0.0);
        assert!(
            e.to_degrees().abs() < 1.5 && (a.to_degrees() - 90.0).abs() < 2.0,
            "{e} {a}"
        );
        // Midnight in summer at 47° N: under the horizon, so the light comes from
        // just above it.
        let (e, _) = solar_elevation_azimuth_rad(&at("2026-06-21T23:30:00Z"), 47.0, 8.0);
        assert!(e < 0.0);
        let night = to_sun_at(&at("2026-06-21T23:30:00Z"), 47.0, 8.0);
        assert!((night.y - 0.05f32.sin()).abs() < 1e-6 && (night.length() - 1.0).abs() < 1e-5);
        // Afternoon: the sun in the west-south-west (west is −x, south +z).
        let pm = to_sun_at(&at("2026-06-21T15:30:00Z"), 47.0, 8.0);
        assert!(pm.x < 0.0 && pm.z > 0.0 && pm.y > 0.3, "{pm}");
    }
}
