//! [`PrecipitationKind`]: what the weather makes fall, one row per kind — its name in
//! presets and on command lines, the temperatures it falls at, its usual
//! temperature, how its water splits into snow and rain, its grains. The viewer's
//! `--kind`, presets, keys and help text read this table, so a new kind is a variant
//! and a row here, not an edit in each front end. What each falling particle then is
//! and does: [`crate::particles::kind`].

use crate::drawing::clouds::CloudKind;
use crate::particles::kind::ParticleKind;
use crate::physics::grain::Grain;
use crate::weather::sleet_snow_fraction;

/// The kind of precipitation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PrecipitationKind {
    /// Dry snow: `C = 0.170 kg/m²`, terminal speeds 0.5–1.5 m/s.
    DrySnow,
    /// Wet snow: `C = 0.724 kg/m²`, terminal speeds 1.0–2.0 m/s.
    WetSnow,
    /// Rain: Marshall–Palmer drops at their measured terminal speeds.
    Rain,
    /// Sleet: a mix of wet snow and rain whose snow fraction follows the air
    /// temperature ([`sleet_snow_fraction`]).
    Sleet,
    /// Blowing sand ([`crate::physics::grain`]): grains settling from the air and lifted by
    /// the wind from sand in the scene.
    Sand,
    /// Mineral dust ([`crate::physics::grain`]): a haze settling slowly, and dust thrown up
    /// from sand in the scene by a strong wind.
    Dust,
    /// Hail ([`crate::physics::hail`]): stones of 5–50 mm at their measured fall
    /// speeds, larger as the hailfall is heavier; they pile on the ground as ice and
    /// melt.
    Hail,
}

/// One kind's row.
struct Row {
    /// Its name in presets and on command lines (kebab-case).
    name: &'static str,
    /// Air temperatures it may fall at, °C (inclusive), and in words.
    allowed_c: (f32, f32, &'static str),
    /// Temperatures it usually falls at, °C: switching to it moves the air's
    /// temperature into this range.
    usual_c: (f32, f32),
    /// The temperature a weather of this kind starts at when none is given, °C.
    default_c: f32,
    /// Its grains when the weather names none.
    grain: Option<Grain>,
}

impl PrecipitationKind {
    /// Every kind, in the order the viewer's keys 1… select them.
    pub const ALL: [Self; 7] = [
        Self::DrySnow,
        Self::WetSnow,
        Self::Rain,
        Self::Sleet,
        Self::Sand,
        Self::Dust,
        Self::Hail,
    ];

    const fn row(self) -> Row {
        match self {
            Self::DrySnow => Row {
                name: "dry-snow",
                allowed_c: (-60.0, 2.0, "-60..=+2 °C for dry snow"),
                usual_c: (-60.0, -2.0),
                default_c: -5.0,
                grain: None,
            },
            Self::WetSnow => Row {
                name: "wet-snow",
                allowed_c: (-15.0, 6.0, "-15..=+6 °C for wet snow"),
                usual_c: (0.0, 0.0),
                default_c: 0.0,
                grain: None,
            },
            Self::Rain => Row {
                name: "rain",
                allowed_c: (
                    -10.0,
                    50.0,
                    "-10..=+50 °C for rain (freezing rain below 0 °C)",
                ),
                usual_c: (5.0, 50.0),
                default_c: 8.0,
                grain: None,
            },
            Self::Sleet => Row {
                name: "sleet",
                allowed_c: (-5.0, 6.0, "-5..=+6 °C for sleet"),
                usual_c: (1.0, 1.0),
                default_c: 1.0,
                grain: None,
            },
            Self::Sand => Row {
                name: "sand",
                allowed_c: (-60.0, 50.0, "-60..=+50 °C for sand and dust"),
                usual_c: (-60.0, 50.0),
                default_c: 30.0,
                grain: Some(Grain::SAND),
            },
            Self::Dust => Row {
                name: "dust",
                allowed_c: (-60.0, 50.0, "-60..=+50 °C for sand and dust"),
                usual_c: (-60.0, 50.0),
                default_c: 30.0,
                grain: Some(Grain::DUST),
            },
            Self::Hail => Row {
                name: "hail",
                // Hail reaches the ground from thunderstorms in warm air; it falls
                // too fast to melt on the way below 40 °C.
                allowed_c: (-10.0, 40.0, "-10..=+40 °C for hail"),
                usual_c: (5.0, 30.0),
                default_c: 15.0,
                grain: None,
            },
        }
    }

    /// Its name in presets and on command lines: `dry-snow`, `wet-snow`, `rain`,
    /// `sleet`, `sand`, `dust`, `hail`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        self.row().name
    }

    /// The kind of `name` ([`Self::name`]; `_` for `-` accepted), `None` for no kind.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        let name = name.trim().replace('_', "-");
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Every kind's name, comma-separated (for messages and help).
    #[must_use]
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// The air temperatures this kind may fall at, °C (inclusive), and in words.
    #[must_use]
    pub const fn temperature_range_c(self) -> (f32, f32, &'static str) {
        self.row().allowed_c
    }

    /// The temperature a weather of this kind starts at when none is given, °C.
    #[must_use]
    pub const fn default_air_temperature_c(self) -> f32 {
        self.row().default_c
    }

    /// The air's temperature after switching to this kind from `air_temperature_c`:
    /// moved into the temperatures it usually falls at (snow below −2 °C, rain
    /// above 5 °C, wet snow at 0 °C, sleet at 1 °C), kept where already there.
    #[must_use]
    pub fn usual_air_temperature_c(self, air_temperature_c: f32) -> f32 {
        let (lo, hi) = self.row().usual_c;
        air_temperature_c.clamp(lo, hi)
    }

    /// The grains of this kind when the weather names none: 0.2 mm quartz sand,
    /// 10 µm quartz dust; `None` for water and ice.
    #[must_use]
    pub const fn default_grain(self) -> Option<Grain> {
        self.row().grain
    }

    /// The fraction of its rate that falls as particles of `particle` at
    /// `air_temperature_c` (the fractions of a kind sum to 1).
    #[must_use]
    pub fn share_of(self, particle: ParticleKind, air_temperature_c: f32) -> f32 {
        use ParticleKind as P;
        match (self, particle) {
            (Self::DrySnow, P::DrySnow)
            | (Self::WetSnow, P::WetSnow)
            | (Self::Rain, P::Rain)
            | (Self::Sand | Self::Dust, P::Grain)
            | (Self::Hail, P::Hail) => 1.0,
            (Self::Sleet, P::WetSnow) => sleet_snow_fraction(air_temperature_c),
            (Self::Sleet, P::Rain) => 1.0 - sleet_snow_fraction(air_temperature_c),
            _ => 0.0,
        }
    }

    /// Fraction of its water that falls as snow at `air_temperature_c`.
    #[must_use]
    pub fn snow_fraction(self, air_temperature_c: f32) -> f32 {
        ParticleKind::ALL
            .into_iter()
            .filter(|p| p.is_snow())
            .map(|p| self.share_of(p, air_temperature_c))
            .sum()
    }

    /// The cloud deck it falls from at `rate_mm_per_h` (WMO cloud atlas): drizzle
    /// (rain under 1 mm/h) from stratus, heavy rain (10 mm/h and more) and hail from
    /// cumulonimbus, other rain, snow and sleet from nimbostratus; with nothing
    /// falling, or sand and dust, cumulus.
    #[must_use]
    pub fn falls_from(self, rate_mm_per_h: f32) -> CloudKind {
        match self {
            _ if rate_mm_per_h <= 0.0 => CloudKind::Cumulus,
            Self::Sand | Self::Dust => CloudKind::Cumulus,
            Self::Rain if rate_mm_per_h < 1.0 => CloudKind::Stratus,
            Self::Rain if rate_mm_per_h >= 10.0 => CloudKind::Cumulonimbus,
            Self::Hail => CloudKind::Cumulonimbus,
            Self::Rain | Self::Sleet | Self::DrySnow | Self::WetSnow => CloudKind::Nimbostratus,
        }
    }

    /// Whether its snow, if any, is wet (sleet's snow is wet).
    #[must_use]
    pub const fn snow_is_wet(self) -> bool {
        !matches!(self, Self::DrySnow)
    }
}

impl std::fmt::Display for PrecipitationKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_found_by_its_name() {
        for kind in PrecipitationKind::ALL {
            assert_eq!(PrecipitationKind::from_name(kind.name()), Some(kind));
            assert!(PrecipitationKind::names().contains(kind.name()));
        }
        assert_eq!(
            PrecipitationKind::from_name("dry_snow"),
            Some(PrecipitationKind::DrySnow)
        );
        assert_eq!(PrecipitationKind::from_name("graupel"), None);
    }

    #[test]
    fn every_kind_s_temperatures_lie_in_what_it_allows() {
        for kind in PrecipitationKind::ALL {
            let (lo, hi, _) = kind.temperature_range_c();
            assert!(
                (lo..=hi).contains(&kind.default_air_temperature_c()),
                "{kind}"
            );
            for t in [-60.0, -10.0, 0.0, 3.0, 20.0, 50.0] {
                let usual = kind.usual_air_temperature_c(t);
                assert!((lo..=hi).contains(&usual), "{kind} from {t}: {usual}");
            }
            let f = kind.snow_fraction(kind.default_air_temperature_c());
            assert!((0.0..=1.0).contains(&f), "{kind}");
            for t in [-5.0, 0.0, 1.0, 2.0, 5.0] {
                let shares: f32 = ParticleKind::ALL
                    .into_iter()
                    .map(|p| kind.share_of(p, t))
                    .sum();
                assert!((shares - 1.0).abs() < 1e-6, "{kind} at {t} °C: {shares}");
            }
            // Grains fall alone.
            if kind.default_grain().is_some() {
                assert!(f.abs() < f32::EPSILON, "{kind}");
            }
        }
    }
}
