//! [`Weather`]: what the user sets, in physical units, validated at the boundary.

mod kind;
pub mod sun;
pub mod visibility;

pub use kind::PrecipitationKind;

use precip_wind::WindField;

use crate::backend::error::WeatherError;
use crate::particles::kind::ParticleKind;
use crate::physics::grain::Grain;

/// Air temperature at and below which sleet is all snow, °C.
pub const SLEET_ALL_SNOW_C: f32 = -1.0;
/// Air temperature at and above which sleet is all rain, °C.
pub const SLEET_ALL_RAIN_C: f32 = 3.0;

/// Fraction of sleet's water that falls as (wet) snow: 1 at ≤ −1 °C, 0 at ≥ +3 °C,
/// linear between (the threshold-range rain/snow partition of hydrological models
/// such as HBV, centred at +1 °C). Host-side only: the GPU reads the result as
/// `SpeciesParams::snow_fraction` ([`crate::particles::kind`]).
#[must_use]
pub fn sleet_snow_fraction(air_temperature_c: f32) -> f32 {
    ((SLEET_ALL_RAIN_C - air_temperature_c) / (SLEET_ALL_RAIN_C - SLEET_ALL_SNOW_C)).clamp(0.0, 1.0)
}

/// The weather, in physical units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weather {
    /// What falls.
    pub kind: PrecipitationKind,
    /// Precipitation rate as liquid water, mm/h (snow: its water equivalent);
    /// allowed `[0, 300]`. Sand and dust: the grains settling from the air (carried
    /// in from up-wind), kg/(m²·h) — the same number (a mm of water is a kg/m²).
    pub intensity_mm_per_h: f32,
    /// Sand and dust only: the grains; `None`: the kind's own
    /// ([`PrecipitationKind::default_grain`]).
    pub grain: Option<Grain>,
    /// Air temperature, °C; allowed `[-60, 50]` and the kind's own range.
    pub air_temperature_c: f32,
    /// The wind.
    pub wind: WindField,
    /// Relative humidity of the air near the ground, `[0, 1]`: how fast wet surfaces
    /// dry (evaporation stops in saturated air).
    pub relative_humidity: f32,
}

impl Default for Weather {
    /// Moderate dry snow at −5 °C in calm air.
    fn default() -> Self {
        Self {
            kind: PrecipitationKind::DrySnow,
            intensity_mm_per_h: 1.0,
            air_temperature_c: -5.0,
            wind: WindField::calm(),
            relative_humidity: Self::DEFAULT_RELATIVE_HUMIDITY,
            grain: None,
        }
    }
}

impl Weather {
    /// Relative humidity when none is given: moist air, as under most precipitation.
    pub const DEFAULT_RELATIVE_HUMIDITY: f32 = 0.9;

    /// Highest accepted intensity, mm/h (above the heaviest recorded hourly rain).
    pub const MAX_INTENSITY_MM_PER_H: f32 = 300.0;

    /// Checks every field; the error names the field and its allowed range.
    pub fn validate(&self) -> Result<(), WeatherError> {
        let i = self.intensity_mm_per_h;
        if !(i.is_finite() && (0.0..=Self::MAX_INTENSITY_MM_PER_H).contains(&i)) {
            return Err(WeatherError::OutOfRange {
                field: "intensity_mm_per_h",
                value: f64::from(i),
                allowed: "[0, 300] mm/h of water",
            });
        }
        let t = self.air_temperature_c;
        if !(t.is_finite() && (-60.0..=50.0).contains(&t)) {
            return Err(WeatherError::OutOfRange {
                field: "air_temperature_c",
                value: f64::from(t),
                allowed: "[-60, 50] °C",
            });
        }
        let (lo, hi, allowed) = self.kind.temperature_range_c();
        if !(lo..=hi).contains(&t) {
            return Err(WeatherError::KindTemperature {
                kind: self.kind,
                air_temperature_c: t,
                allowed,
            });
        }
        let rh = self.relative_humidity;
        if !(rh.is_finite() && (0.0..=1.0).contains(&rh)) {
            return Err(WeatherError::OutOfRange {
                field: "relative_humidity",
                value: f64::from(rh),
                allowed: "[0, 1] (a fraction, not percent)",
            });
        }
        if let Some(grain) = self.grain {
            if self.kind.default_grain().is_none() {
                return Err(WeatherError::GrainWithoutGrains { kind: self.kind });
            }
            let d = grain.diameter_m;
            if !(d.is_finite() && (1.0e-6..=2.0e-3).contains(&d)) {
                return Err(WeatherError::OutOfRange {
                    field: "grain.diameter_m",
                    value: f64::from(d),
                    allowed: "[0.000001, 0.002] m (1 µm dust to 2 mm coarse sand)",
                });
            }
            let rho = grain.density_kg_m3;
            if !(rho.is_finite() && (500.0..=8000.0).contains(&rho)) {
                return Err(WeatherError::OutOfRange {
                    field: "grain.density_kg_m3",
                    value: f64::from(rho),
                    allowed: "[500, 8000] kg/m³ (quartz is 2650)",
                });
            }
        }
        self.wind.validate()?;
        Ok(())
    }

    /// The grains in the air: sand or dust weather's, `None` for water and ice.
    #[must_use]
    pub fn grains(&self) -> Option<Grain> {
        self.kind.default_grain().map(|g| self.grain.unwrap_or(g))
    }

    /// Sand or dust settling from the air, kg/(m²·h); 0 for water and ice.
    #[must_use]
    pub fn grain_rate_kg_per_m2_h(&self) -> f32 {
        if self.grains().is_some() {
            self.intensity_mm_per_h
        } else {
            0.0
        }
    }

    /// Fraction of the water that falls as snow.
    #[must_use]
    pub fn snow_fraction(&self) -> f32 {
        self.kind.snow_fraction(self.air_temperature_c)
    }

    /// Whether the snow part is wet snow (sleet's snow is wet).
    #[must_use]
    pub fn snow_is_wet(&self) -> bool {
        self.kind.snow_is_wet()
    }

    /// What lands in the cover's deposit channel `channel` (`DepositBuffer::SNOW`,
    /// `RAIN`, `GRAINS`), mm/h of water: the rates of the particle kinds that land
    /// there ([`ParticleKind::deposit_channel`]; hail lands as snow). The cover's
    /// rate-fed texels, its activity and its shadow's bounds take this, not a kind.
    #[must_use]
    pub fn channel_rate_mm_per_h(&self, channel: usize) -> f32 {
        ParticleKind::ALL
            .into_iter()
            .filter(|k| k.deposit_channel() == channel)
            .map(|k| k.rate_in(self))
            .sum()
    }

    /// Snow's water rate, mm/h.
    #[must_use]
    pub fn snow_rate_mm_per_h(&self) -> f32 {
        self.intensity_mm_per_h * self.snow_fraction()
    }

    /// Rain's water rate, mm/h.
    #[must_use]
    pub fn rain_rate_mm_per_h(&self) -> f32 {
        ParticleKind::Rain.rate_in(self)
    }

    /// Mean horizontal wind speed near the ground, m/s (evaporation).
    #[must_use]
    pub fn ground_wind_speed_mps(&self) -> f32 {
        let w = self.wind.mean_wind_mps;
        (w.x * w.x + w.z * w.z).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kinds' tables lose nothing: a weather's whole rate lands in the cover's
    /// channels, for every kind (hail in the snow's).
    #[test]
    fn every_kind_s_rate_lands_in_the_cover_s_channels() {
        for kind in PrecipitationKind::ALL {
            let w = Weather {
                kind,
                intensity_mm_per_h: 4.0,
                air_temperature_c: kind.default_air_temperature_c(),
                ..Weather::default()
            };
            let landed: f32 = (0..precip_cover::DEPOSIT_CHANNELS)
                .map(|c| w.channel_rate_mm_per_h(c))
                .sum();
            assert!((landed - 4.0).abs() < 1e-5, "{kind}: {landed} mm/h");
        }
    }

    #[test]
    fn sleet_turns_from_snow_to_rain_around_zero() {
        assert!((sleet_snow_fraction(-3.0) - 1.0).abs() < 1e-6);
        assert!((sleet_snow_fraction(1.0) - 0.5).abs() < 1e-6);
        assert!(sleet_snow_fraction(4.0).abs() < 1e-6);
        let w = Weather {
            kind: PrecipitationKind::Sleet,
            air_temperature_c: 2.0,
            intensity_mm_per_h: 4.0,
            ..Weather::default()
        };
        assert!(
            (w.snow_rate_mm_per_h() - 1.0).abs() < 1e-5
                && (w.rain_rate_mm_per_h() - 3.0).abs() < 1e-5
        );
    }

    #[test]
    fn sand_and_dust_carry_grains_and_no_water() {
        let sand = Weather {
            kind: PrecipitationKind::Sand,
            intensity_mm_per_h: 2.0,
            air_temperature_c: 35.0,
            ..Weather::default()
        };
        assert!(sand.validate().is_ok());
        assert_eq!(sand.grains(), Some(Grain::SAND));
        assert!((sand.grain_rate_kg_per_m2_h() - 2.0).abs() < 1e-6);
        assert!(sand.snow_rate_mm_per_h().abs() < 1e-6 && sand.rain_rate_mm_per_h().abs() < 1e-6);
        let dust = Weather {
            kind: PrecipitationKind::Dust,
            ..sand
        };
        assert_eq!(dust.grains(), Some(Grain::DUST));
        let snow_with_grains = Weather {
            grain: Some(Grain::SAND),
            ..Weather::default()
        };
        assert!(matches!(
            snow_with_grains.validate(),
            Err(WeatherError::GrainWithoutGrains { .. })
        ));
        assert_eq!(Weather::default().grains(), None);
    }

    #[test]
    fn each_invalid_field_is_named() {
        let base = Weather::default();
        let cases = [
            (
                Weather {
                    intensity_mm_per_h: f32::NAN,
                    ..base
                },
                "intensity_mm_per_h",
            ),
            (
                Weather {
                    intensity_mm_per_h: -1.0,
                    ..base
                },
                "intensity_mm_per_h",
            ),
            (
                Weather {
                    intensity_mm_per_h: 1000.0,
                    ..base
                },
                "intensity_mm_per_h",
            ),
            (
                Weather {
                    air_temperature_c: f32::INFINITY,
                    ..base
                },
                "air_temperature_c",
            ),
            (
                Weather {
                    air_temperature_c: -80.0,
                    ..base
                },
                "air_temperature_c",
            ),
            (
                Weather {
                    relative_humidity: 70.0,
                    ..base
                },
                "relative_humidity",
            ),
            (
                Weather {
                    kind: PrecipitationKind::Dust,
                    grain: Some(Grain {
                        diameter_m: 0.01,
                        ..Grain::DUST
                    }),
                    ..base
                },
                "grain.diameter_m",
            ),
            (
                Weather {
                    kind: PrecipitationKind::Sand,
                    grain: Some(Grain {
                        density_kg_m3: f32::NAN,
                        ..Grain::SAND
                    }),
                    ..base
                },
                "grain.density_kg_m3",
            ),
        ];
        for (w, name) in cases {
            match w.validate() {
                Err(WeatherError::OutOfRange { field, .. }) => assert_eq!(field, name),
                other => panic!("{name}: {other:?}"),
            }
        }
        let warm_snow = Weather {
            air_temperature_c: 15.0,
            ..base
        };
        assert!(matches!(
            warm_snow.validate(),
            Err(WeatherError::KindTemperature { .. })
        ));
        let bad_wind = Weather {
            wind: WindField {
                gust_factor: 7.0,
                ..WindField::calm()
            },
            ..base
        };
        assert!(matches!(bad_wind.validate(), Err(WeatherError::Wind(_))));
        assert!(base.validate().is_ok());
        let message = Weather {
            intensity_mm_per_h: -1.0,
            ..base
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(
            message.contains("intensity_mm_per_h") && message.contains("[0, 300]"),
            "{message}"
        );
    }
}
