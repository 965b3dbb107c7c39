//! The air of a far cell (docs/model.md (4.18), (4.19)): the weather is set at the
//! site (the terrain under the cover grid's centre); a far cell at another height
//! breathes the same air moved by the standard atmosphere's lapse rate, with the
//! snow's share of what falls, the relative humidity and the sun on its slope that
//! follow. Host only: the GPU reads the cells' rows ([`crate::host::FarCover`]).

use glam::Vec3;
use precip_cover::saturation_vapour_pressure_hpa;

use crate::weather::sleet_snow_fraction;

/// The air's cooling with height, °C per metre: the ICAO standard atmosphere's
/// troposphere, 6.5 K/km (ISO 2533:1975).
pub const LAPSE_RATE_C_PER_M: f32 = 0.0065;

/// The share of an open level site's melt that the direct sun brings (the rest the
/// air's warmth, the sky's long waves), which a slope's aspect scales
/// ([`slope_irradiance_factor`]): a choice of the order of the absorbed short
/// waves' share of the melt energy over snow in a mid-latitude melt season
/// (Ohmura 2001, *J. Appl. Meteor.* 40).
pub const SUN_MELT_SHARE: f32 = 0.5;

/// The most a slope facing the sun multiplies the direct sun's part
/// ([`slope_irradiance_factor`]).
pub const MAX_SLOPE_SUN_RATIO: f32 = 3.0;

/// The solar irradiance factor `R_l` of a slope of unit normal `normal` under the
/// sun toward `to_sun` (model (4.6), (4.19)): the open level site's 1 with its sun's
/// part, [`SUN_MELT_SHARE`], scaled by the direct beam on the slope over that on
/// level ground, `max(n·s, 0)/s_y` (the sun at least 0.05 above the horizon, the
/// ratio at most [`MAX_SLOPE_SUN_RATIO`]): `R_l = 1 − p + p·ratio`. A north face
/// under a southern sun 30° up keeps half the melt, a 30° south face 1.37×.
#[must_use]
pub fn slope_irradiance_factor(normal: Vec3, to_sun: Vec3) -> f32 {
    let sun = to_sun.normalize_or(Vec3::Y);
    let ratio = (normal.dot(sun).max(0.0) / sun.y.max(0.05)).min(MAX_SLOPE_SUN_RATIO);
    1.0 - SUN_MELT_SHARE + SUN_MELT_SHARE * ratio
}

/// The relative humidity where the air is `local_c`, given `site_humidity` at
/// `site_c` (model (4.18)): the site's vapour pressure over the saturation
/// pressure there (Magnus, `saturation_vapour_pressure_hpa`), at most 1 — the
/// same air colder is nearer saturation (the pressure's fall with height left
/// out).
#[must_use]
pub fn local_relative_humidity(site_humidity: f32, site_c: f32, local_c: f32) -> f32 {
    (site_humidity * saturation_vapour_pressure_hpa(site_c)
        / saturation_vapour_pressure_hpa(local_c))
    .clamp(0.0, 1.0)
}

/// The share of snow in what falls where the air is `local_c`, given the share
/// `site_share` the weather has at `site_c` (model (4.18)): moved by the sleet
/// ramp's difference between the two temperatures, so it is the weather's own at
/// the site's height and a kind's snow stays snow wherever it is colder.
#[must_use]
pub fn local_snow_share(site_share: f32, site_c: f32, local_c: f32) -> f32 {
    (site_share + sleet_snow_fraction(local_c) - sleet_snow_fraction(site_c)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_snow_share_is_the_weathers_at_the_site_and_follows_the_ramp_away() {
        assert!((local_snow_share(0.7, 1.0, 1.0) - 0.7).abs() < 1e-6);
        assert!((local_snow_share(1.0, -10.0, -2.0) - 1.0).abs() < 1e-6);
        assert!(local_snow_share(0.0, 8.0, 4.0).abs() < 1e-6);
        // Wet snow at +1 °C: rain 1 000 m lower (+7.5 °C), snow 1 000 m higher.
        let at = sleet_snow_fraction(1.0);
        assert!(local_snow_share(at, 1.0, 7.5).abs() < 1e-6);
        assert!((local_snow_share(at, 1.0, -5.5) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn the_same_air_colder_is_nearer_saturation() {
        assert!((local_relative_humidity(0.6, 10.0, 10.0) - 0.6).abs() < 1e-6);
        // 1 km up (6.5 K colder): 0.6 at +10 °C is 0.94.
        let up = local_relative_humidity(0.6, 10.0, 3.5);
        assert!((up - 0.937).abs() < 0.005, "{up}");
        // 1 km down it is drier; saturation caps it.
        assert!(local_relative_humidity(0.6, 10.0, 16.5) < 0.41);
        assert!((local_relative_humidity(0.9, 10.0, -5.0) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_slope_facing_the_sun_takes_more_of_its_melt() {
        // Flat ground and the sun anywhere: the open site's melt.
        for sun in [Vec3::Y, Vec3::new(0.4, 0.8, 0.3), Vec3::new(0.0, 0.1, -1.0)] {
            assert!((slope_irradiance_factor(Vec3::Y, sun) - 1.0).abs() < 1e-6);
        }
        // 30° faces under a sun 30° up in the south (+z): the north face gets no
        // beam, the south face √3 times level ground's.
        let sun = Vec3::new(0.0, 0.5, 0.866_025_4);
        let (s30, c30) = (0.5, 0.866_025_4);
        let north = slope_irradiance_factor(Vec3::new(0.0, c30, -s30), sun);
        let south = slope_irradiance_factor(Vec3::new(0.0, c30, s30), sun);
        assert!((north - 0.5).abs() < 1e-4, "{north}");
        assert!(
            (south - (0.5 + 0.5 * 3.0_f32.sqrt())).abs() < 1e-4,
            "{south}"
        );
        // A low sun is capped: a face toward it at most 3× the beam.
        let low = slope_irradiance_factor(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.01, 1.0));
        assert!(
            (low - (0.5 + 0.5 * MAX_SLOPE_SUN_RATIO)).abs() < 1e-4,
            "{low}"
        );
    }
}
