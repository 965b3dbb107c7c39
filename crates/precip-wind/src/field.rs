//! [`WindField`]: the user's description of the wind, in physical units.

use glam::Vec3;

use crate::error::{WindError, check_range};

/// The wind: mean wind plus Perlin gusts (docs/model.md §3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindField {
    /// Mean wind V̄_w in m/s, world frame (Y up).
    pub mean_wind_mps: Vec3,
    /// Gust factor μ: the random part along the mean wind is `μ·V̄_w·sin α`.
    /// Seed 003 keeps it within 3–5 %; the default is 4 %; allowed `[0, 1]`.
    pub gust_factor: f32,
    /// Wavelength of the lowest noise octave, metres; allowed `[1, 10000]`.
    pub noise_scale_m: f32,
    /// Number of fractal octaves of the noise; allowed `1..=8`.
    pub octaves: u32,
    /// Amplitude of the vertical gust w, m/s; allowed `[0, 20]`.
    pub vertical_gust_mps: f32,
    /// Seed of the noise: the same seed bakes the same volume.
    pub seed: u32,
}

impl Default for WindField {
    fn default() -> Self {
        Self::calm()
    }
}

impl WindField {
    /// The default gust factor μ, inside the seed's 3–5 % range.
    pub const DEFAULT_GUST_FACTOR: f32 = 0.04;

    /// The mean wind vector of a speed and the meteorological direction it blows
    /// from (degrees clockwise from north = −Z; east = +X), m/s: the convention of
    /// presets and of CIGI hosts.
    #[must_use]
    pub fn mean_wind_from(speed_mps: f32, from_deg: f32) -> Vec3 {
        let from = from_deg.to_radians();
        -speed_mps * Vec3::new(from.sin(), 0.0, -from.cos())
    }

    /// Still air: no mean wind, and so no horizontal gust; a weak vertical gust.
    #[must_use]
    pub const fn calm() -> Self {
        Self {
            mean_wind_mps: Vec3::ZERO,
            gust_factor: Self::DEFAULT_GUST_FACTOR,
            noise_scale_m: 40.0,
            octaves: 3,
            vertical_gust_mps: 0.0,
            seed: 0,
        }
    }

    /// A horizontal wind of `speed_mps` blowing **toward** the compass direction
    /// `toward_deg` (0° = −Z "north", 90° = +X "east"), default gusts.
    #[must_use]
    pub fn horizontal(speed_mps: f32, toward_deg: f32) -> Self {
        let rad = toward_deg.to_radians();
        Self {
            mean_wind_mps: Vec3::new(rad.sin() * speed_mps, 0.0, -rad.cos() * speed_mps),
            vertical_gust_mps: 0.1 * speed_mps.abs(),
            ..Self::calm()
        }
    }

    /// Checks every field; the error names the field and its allowed range.
    pub fn validate(&self) -> Result<(), WindError> {
        for (field, value) in [
            ("mean_wind_mps.x", self.mean_wind_mps.x),
            ("mean_wind_mps.y", self.mean_wind_mps.y),
            ("mean_wind_mps.z", self.mean_wind_mps.z),
        ] {
            check_range(
                field,
                value,
                -100.0,
                100.0,
                "finite, [-100, 100] m/s per axis",
            )?;
        }
        check_range("gust_factor", self.gust_factor, 0.0, 1.0, "[0, 1]")?;
        check_range(
            "noise_scale_m",
            self.noise_scale_m,
            1.0,
            1.0e4,
            "[1, 10000] m",
        )?;
        if !(1..=8).contains(&self.octaves) {
            return Err(WindError::OutOfRange {
                field: "octaves",
                value: f64::from(self.octaves),
                allowed: "1..=8",
            });
        }
        check_range(
            "vertical_gust_mps",
            self.vertical_gust_mps,
            0.0,
            20.0,
            "[0, 20] m/s",
        )
    }

    /// True when baking `self` and `other` gives different volumes.
    #[must_use]
    pub fn needs_rebake(&self, other: &Self) -> bool {
        self.gust_factor.to_bits() != other.gust_factor.to_bits()
            || self.noise_scale_m.to_bits() != other.noise_scale_m.to_bits()
            || self.octaves != other.octaves
            || self.vertical_gust_mps.to_bits() != other.vertical_gust_mps.to_bits()
            || self.seed != other.seed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_gust_factor_is_in_the_seeds_range() {
        let mu = WindField::default().gust_factor;
        assert!((0.03..=0.05).contains(&mu));
    }

    #[test]
    fn horizontal_points_where_it_says() {
        let east = WindField::horizontal(10.0, 90.0).mean_wind_mps;
        assert!((east.x - 10.0).abs() < 1e-4 && east.z.abs() < 1e-4);
        let north = WindField::horizontal(5.0, 0.0).mean_wind_mps;
        assert!((north.z + 5.0).abs() < 1e-4);
    }

    #[test]
    fn each_bad_field_is_named() {
        let bad = [
            (
                "mean_wind_mps.x",
                WindField {
                    mean_wind_mps: Vec3::new(f32::NAN, 0.0, 0.0),
                    ..WindField::calm()
                },
            ),
            (
                "gust_factor",
                WindField {
                    gust_factor: -0.1,
                    ..WindField::calm()
                },
            ),
            (
                "noise_scale_m",
                WindField {
                    noise_scale_m: 0.0,
                    ..WindField::calm()
                },
            ),
            (
                "octaves",
                WindField {
                    octaves: 0,
                    ..WindField::calm()
                },
            ),
            (
                "vertical_gust_mps",
                WindField {
                    vertical_gust_mps: f32::INFINITY,
                    ..WindField::calm()
                },
            ),
        ];
        for (name, field) in bad {
            match field.validate() {
                Err(WindError::OutOfRange { field, .. }) => assert_eq!(field, name),
                other => panic!("{name}: expected an error, got {other:?}"),
            }
        }
        assert!(WindField::horizontal(12.0, 45.0).validate().is_ok());
    }
}
