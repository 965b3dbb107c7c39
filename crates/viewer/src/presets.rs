//! Weather presets: TOML files (serde) naming the weather in physical units. Every
//! file of `presets/` at the repository root ships built in by its name
//! ([`BUILT_IN`], listed by `build.rs`).

use std::path::Path;

use glam::Vec3;
use precip_model::drawing::clouds::{CloudKind, CloudLayer, CloudLayers, MAX_CLOUD_LAYERS};
use precip_model::drawing::fog_layer::FogLayer;
use precip_model::physics::grain::Grain;
use precip_model::wind::WindField;
use precip_model::{PrecipitationKind, Weather};
use serde::{Deserialize, Serialize};

/// The weather of a preset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Preset {
    /// The kind's name ([`PrecipitationKind::name`]: "dry-snow", "rain", "hail", …;
    /// `PrecipitationKind::names` lists them).
    #[serde(with = "kind_name")]
    pub kind: PrecipitationKind,
    /// Precipitation rate as water, mm/h; sand and dust: the grains settling from
    /// the air, kg/(m²·h).
    pub intensity_mm_per_h: f32,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Mean wind speed, m/s.
    pub wind_speed_mps: f32,
    /// Where the wind blows from, degrees clockwise from north (−Z); 270 = from the west.
    pub wind_from_deg: f32,
    /// Gust factor μ.
    pub gust_factor: f32,
    /// Relative humidity near the ground, `[0, 1]` (how fast wet surfaces dry);
    /// optional, 0.9 when absent.
    #[serde(default = "default_relative_humidity")]
    pub relative_humidity: f32,
    /// Sand and dust: the grains' mean diameter, mm; optional (0.2 mm sand, 0.01 mm
    /// dust when absent).
    #[serde(default)]
    pub grain_diameter_mm: Option<f32>,
    /// Sand and dust: the grains' density, kg/m³; optional (quartz, 2650).
    #[serde(default)]
    pub grain_density_kg_m3: Option<f32>,
    /// A fog layer's top, m above the scene's origin (valley or ground fog);
    /// optional, with `fog_visibility_m`.
    #[serde(default)]
    pub fog_top_m: Option<f32>,
    /// The visibility inside the fog layer, m; optional (200 m when only the top is
    /// given).
    #[serde(default)]
    pub fog_visibility_m: Option<f32>,
    /// A cloud layer's type: "stratus", "nimbostratus", "cumulus" or
    /// "cumulonimbus"; optional (no clouds when absent and no cover is given).
    #[serde(default)]
    pub cloud_type: Option<CloudTypeName>,
    /// The share of the sky the cloud layer covers, `[0, 1]` (oktas / 8); optional
    /// (0.6 when only the type is given).
    #[serde(default)]
    pub cloud_cover: Option<f32>,
    /// The cloud layer's base, m; optional (the type's typical base).
    #[serde(default)]
    pub cloud_base_m: Option<f32>,
    /// The cloud layer's thickness, m; optional (the type's typical thickness).
    #[serde(default)]
    pub cloud_thickness_m: Option<f32>,
    /// The height of the band below and above the cloud layer over which the air
    /// thickens toward it, m (CIGI's transition band); optional (0: a sharp edge).
    #[serde(default)]
    pub cloud_transition_band_m: Option<f32>,
    /// The rate falling beyond the camera's 3 km, averaged over the land, mm/h of
    /// water, in shafts under the lowest cloud layer's clouds; optional (the
    /// weather's own). Showers around a dry place: `intensity = 0`,
    /// `rate_beyond_mm_per_h = 20`.
    #[serde(default)]
    pub rate_beyond_mm_per_h: Option<f32>,
    /// More cloud layers, above or below the first (up to three in all, none
    /// reaching into another): `more_clouds = [{ type = "stratus", cover = 0.9,
    /// base_m = 4000, thickness_m = 400 }]`, cover, base and thickness optional.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub more_clouds: Vec<MoreClouds>,
}

/// Another cloud layer of a preset (`more_clouds`) or of the command line
/// (`--more-clouds TYPE[:COVER[:BASE_M[:THICKNESS_M]]]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoreClouds {
    /// Its type.
    #[serde(rename = "type")]
    pub kind: CloudTypeName,
    /// The share of the sky it covers, `[0, 1]` (0.6 when absent).
    #[serde(default)]
    pub cover: Option<f32>,
    /// Its base, m (the type's typical base when absent).
    #[serde(default)]
    pub base_m: Option<f32>,
    /// Its thickness, m (the type's typical thickness when absent).
    #[serde(default)]
    pub thickness_m: Option<f32>,
}

impl MoreClouds {
    /// The layer.
    #[must_use]
    pub fn layer(&self) -> CloudLayer {
        let typical =
            CloudLayer::typical(self.kind.into(), self.cover.unwrap_or(DEFAULT_CLOUD_COVER));
        CloudLayer {
            base_m: self.base_m.unwrap_or(typical.base_m),
            thickness_m: self.thickness_m.unwrap_or(typical.thickness_m),
            ..typical
        }
    }
}

impl std::str::FromStr for MoreClouds {
    type Err = String;

    /// `TYPE[:COVER[:BASE_M[:THICKNESS_M]]]`, e.g. `stratus:0.9:4000:400`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let mut parts = s.split(':');
        let kind = parts.next().unwrap_or_default();
        let kind = <CloudTypeName as clap::ValueEnum>::from_str(kind, true).map_err(|_| {
            format!(
                "`{kind}` is not a cloud type: write stratus, nimbostratus, cumulus or cumulonimbus, then :COVER:BASE_M:THICKNESS_M if wanted"
            )
        })?;
        let mut number = |what: &str| -> Result<Option<f32>, String> {
            parts
                .next()
                .map(|t| {
                    t.trim()
                        .parse::<f32>()
                        .map_err(|e| format!("{what} `{t}` in `{s}`: {e}"))
                })
                .transpose()
        };
        let more = Self {
            kind,
            cover: number("the cover (0–1)")?,
            base_m: number("the base, m")?,
            thickness_m: number("the thickness, m")?,
        };
        if parts.next().is_some() {
            return Err(format!("`{s}` has more than TYPE:COVER:BASE_M:THICKNESS_M"));
        }
        Ok(more)
    }
}

/// A cloud type, as written in presets and on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum CloudTypeName {
    /// A thin, flat, grey sheet.
    Stratus,
    /// A thick, even deck of rain or snow.
    Nimbostratus,
    /// Heaps with flat bases (fair weather).
    Cumulus,
    /// Towering storm clouds.
    Cumulonimbus,
}

impl From<CloudTypeName> for CloudKind {
    fn from(k: CloudTypeName) -> Self {
        match k {
            CloudTypeName::Stratus => Self::Stratus,
            CloudTypeName::Nimbostratus => Self::Nimbostratus,
            CloudTypeName::Cumulus => Self::Cumulus,
            CloudTypeName::Cumulonimbus => Self::Cumulonimbus,
        }
    }
}

/// The cover of a cloud layer whose preset gives only its type.
pub const DEFAULT_CLOUD_COVER: f32 = 0.6;

/// The visibility in a fog layer whose preset gives only its top, m.
pub const DEFAULT_FOG_VISIBILITY_M: f32 = 200.0;

fn default_relative_humidity() -> f32 {
    Weather::DEFAULT_RELATIVE_HUMIDITY
}

/// A kind of precipitation as written in presets and on the command line: its name
/// ([`PrecipitationKind::name`]), read from the model's table of kinds, so a new kind
/// needs nothing here.
pub mod kind_name {
    use precip_model::PrecipitationKind;
    use serde::de::Error as _;
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the kind's name.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(kind: &PrecipitationKind, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(kind.name())
    }

    /// Reads a kind's name; the error lists the names.
    ///
    /// # Errors
    /// A name that is no kind's.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<PrecipitationKind, D::Error> {
        let name = String::deserialize(d)?;
        PrecipitationKind::from_name(&name).ok_or_else(|| {
            D::Error::custom(format!(
                "`{name}` is not a kind of precipitation: write one of {}",
                PrecipitationKind::names()
            ))
        })
    }

    /// The command line's parser: the kinds' names as its possible values.
    #[must_use]
    pub fn parser() -> impl clap::builder::TypedValueParser<Value = PrecipitationKind> {
        use clap::builder::TypedValueParser as _;
        clap::builder::PossibleValuesParser::new(
            PrecipitationKind::ALL.map(PrecipitationKind::name),
        )
        .try_map(|name: String| {
            PrecipitationKind::from_name(&name).ok_or(format!("no kind `{name}`"))
        })
    }
}

include!(concat!(env!("OUT_DIR"), "/built_in_presets.rs"));

/// A preset that cannot be used.
#[derive(Debug, thiserror::Error)]
#[error("preset {name}: {problem}")]
pub struct PresetError {
    /// The file or name.
    pub name: String,
    /// What is wrong.
    pub problem: String,
}

/// The wind vector of a speed and a meteorological direction (from, clockwise from
/// north = −Z; east = +X).
#[must_use]
pub fn wind_vector(speed_mps: f32, from_deg: f32) -> Vec3 {
    WindField::mean_wind_from(speed_mps, from_deg)
}

impl Preset {
    /// Parses TOML text.
    pub fn parse(text: &str, name: &str) -> Result<Self, PresetError> {
        toml::from_str(text).map_err(|e| PresetError {
            name: name.to_owned(),
            problem: e.to_string(),
        })
    }

    /// A shipped preset by name, or a TOML file by path.
    pub fn load(name_or_path: &str) -> Result<Self, PresetError> {
        if let Some((_, text)) = BUILT_IN.iter().find(|(n, _)| *n == name_or_path) {
            return Self::parse(text, name_or_path);
        }
        let text = std::fs::read_to_string(Path::new(name_or_path)).map_err(|e| PresetError {
            name: name_or_path.to_owned(),
            problem: format!(
                "{e} (built-in presets: {})",
                BUILT_IN.map(|(n, _)| n).join(", ")
            ),
        })?;
        Self::parse(&text, name_or_path)
    }

    /// The grains the preset names (`None`: the kind's own, or none given).
    fn grain(&self) -> Option<Grain> {
        if self.grain_diameter_mm.is_none() && self.grain_density_kg_m3.is_none() {
            return None;
        }
        let default = self.kind.default_grain().unwrap_or(Grain::SAND);
        Some(Grain {
            diameter_m: self
                .grain_diameter_mm
                .map_or(default.diameter_m, |d| d * 1.0e-3),
            density_kg_m3: self.grain_density_kg_m3.unwrap_or(default.density_kg_m3),
        })
    }

    /// The fog layer, validated: `None` without a top (a visibility alone is an
    /// error: say where the fog ends).
    pub fn fog_layer(&self) -> Result<Option<FogLayer>, PresetError> {
        let problem = |problem: String| PresetError {
            name: "fog layer (--fog-* or the preset's fog_*)".to_owned(),
            problem,
        };
        match (self.fog_top_m, self.fog_visibility_m) {
            (None, None) => Ok(None),
            (None, Some(v)) => Err(problem(format!(
                "fog_visibility_m = {v} needs fog_top_m (the fog's top, m); a fog without a top is the clear air's haze"
            ))),
            (Some(top), v) => {
                let fog = FogLayer::new(top, v.unwrap_or(DEFAULT_FOG_VISIBILITY_M));
                fog.validate().map_err(|e| problem(e.to_string()))?;
                Ok(Some(fog))
            }
        }
    }

    /// The cloud layer, validated: `None` without a type, cover, base or thickness;
    /// without a type, the deck the weather falls from
    /// ([`CloudLayer::implied_by`]).
    pub fn cloud_layer(&self) -> Result<Option<CloudLayer>, PresetError> {
        if self.cloud_type.is_none()
            && self.cloud_cover.is_none()
            && self.cloud_base_m.is_none()
            && self.cloud_thickness_m.is_none()
        {
            return Ok(None);
        }
        let coverage = self.cloud_cover.unwrap_or(DEFAULT_CLOUD_COVER);
        let typical = match (self.cloud_type, self.weather()) {
            (Some(kind), _) => CloudLayer::typical(kind.into(), coverage),
            (None, Ok(weather)) => CloudLayer::implied_by(&weather, coverage),
            (None, Err(_)) => CloudLayer::typical(CloudKind::Nimbostratus, coverage),
        };
        let layer = CloudLayer {
            base_m: self.cloud_base_m.unwrap_or(typical.base_m),
            thickness_m: self.cloud_thickness_m.unwrap_or(typical.thickness_m),
            transition_band_m: self.cloud_transition_band_m.unwrap_or(0.0),
            ..typical
        };
        layer.validate().map_err(|e| PresetError {
            name: "cloud layer (--cloud-* or the preset's cloud_*)".to_owned(),
            problem: e.to_string(),
        })?;
        Ok(Some(layer))
    }

    /// Every cloud layer: the first ([`Preset::cloud_layer`]) and `more_clouds`,
    /// validated together (at most three, none reaching into another).
    pub fn cloud_layers(&self) -> Result<CloudLayers, PresetError> {
        let problem = |problem: String| PresetError {
            name: "cloud layers (--cloud-*, --more-clouds or the preset's cloud_*, more_clouds)"
                .to_owned(),
            problem,
        };
        let mut layers: Vec<CloudLayer> = self.cloud_layer()?.into_iter().collect();
        layers.extend(self.more_clouds.iter().map(MoreClouds::layer));
        if layers.len() > MAX_CLOUD_LAYERS {
            return Err(problem(format!(
                "{} layers given: at most {MAX_CLOUD_LAYERS} are drawn at once",
                layers.len()
            )));
        }
        CloudLayers::new(&layers).map_err(|e| problem(e.to_string()))
    }

    /// The weather, validated.
    pub fn weather(&self) -> Result<Weather, precip_model::WeatherError> {
        let weather = Weather {
            kind: self.kind,
            intensity_mm_per_h: self.intensity_mm_per_h,
            air_temperature_c: self.air_temperature_c,
            wind: WindField {
                mean_wind_mps: wind_vector(self.wind_speed_mps, self.wind_from_deg),
                gust_factor: self.gust_factor,
                ..WindField::calm()
            },
            relative_humidity: self.relative_humidity,
            grain: self.grain(),
        };
        weather.validate()?;
        Ok(weather)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A shipped preset's text.
    fn built_in(name: &str) -> &'static str {
        BUILT_IN
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, text)| *text)
            .unwrap_or_else(|| panic!("no preset {name}"))
    }

    #[test]
    fn every_shipped_preset_gives_a_valid_weather() {
        for (name, text) in BUILT_IN {
            let preset = Preset::parse(text, name).expect("parses");
            preset.weather().unwrap_or_else(|e| panic!("{name}: {e}"));
            preset.fog_layer().unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        preset_layers_are_checked();
        let valley = Preset::load("valley-fog").expect("shipped");
        assert_eq!(
            valley.fog_layer().expect("valid"),
            Some(FogLayer::new(12.0, 150.0))
        );
    }

    fn preset_layers_are_checked() {
        for (name, text) in BUILT_IN {
            let preset = Preset::parse(text, name).expect("parses");
            preset
                .cloud_layers()
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        let sky = Preset::load("layered-sky").expect("shipped");
        let layers = sky.cloud_layers().expect("valid");
        let kinds: Vec<CloudKind> = layers.iter().map(|l| l.kind).collect();
        assert_eq!(kinds, [CloudKind::Cumulus, CloudKind::Stratus]);
        // More clouds from the command line: a third layer, then one too many, then
        // one reaching into another.
        let mut p = sky.clone();
        p.more_clouds
            .push("nimbostratus:1:300:200".parse().expect("a layer"));
        let three = p.cloud_layers().expect("three");
        assert_eq!(three.lowest().map(|l| l.base_m), Some(300.0));
        p.more_clouds.push("stratus".parse().expect("a layer"));
        let e = p.cloud_layers().expect_err("four");
        assert!(e.to_string().contains("at most 3"), "{e}");
        let mut p = sky.clone();
        p.more_clouds
            .push("stratus:0.5:1500".parse().expect("a layer"));
        let e = p.cloud_layers().expect_err("inside the cumulus");
        assert!(e.to_string().contains("raise its base"), "{e}");
        for bad in ["cirrus", "stratus:lots", "stratus:0.5:1:2:3"] {
            assert!(bad.parse::<MoreClouds>().is_err(), "{bad}");
        }
        let storm = Preset::load("thunderstorm").expect("shipped");
        let layer = storm.cloud_layer().expect("valid").expect("a layer");
        assert_eq!(layer.kind, CloudKind::Cumulonimbus);
        assert!((layer.coverage - 0.85).abs() < 1e-6);
        let mut p = Preset::load("drizzle").expect("shipped");
        assert_eq!(p.cloud_layer().expect("none"), None);
        p.cloud_cover = Some(0.5);
        let deck = p.cloud_layer().expect("valid").expect("a deck");
        assert_eq!(
            deck.kind,
            CloudKind::Stratus,
            "a cover alone is the deck drizzle falls from"
        );
        p.cloud_cover = Some(1.5);
        let e = p.cloud_layer().expect_err("over 1");
        assert!(e.to_string().contains("coverage"), "{e}");
    }

    #[test]
    fn a_fog_needs_its_top_and_a_visibility_it_can_have() {
        let mut p = Preset::load("drizzle").expect("shipped");
        assert_eq!(p.fog_layer().expect("no fog"), None);
        p.fog_visibility_m = Some(100.0);
        let e = p.fog_layer().expect_err("no top");
        assert!(e.to_string().contains("fog_top_m"), "{e}");
        p.fog_top_m = Some(20.0);
        p.fog_visibility_m = Some(-5.0);
        let e = p.fog_layer().expect_err("negative visibility");
        assert!(e.to_string().contains("visibility"), "{e}");
        p.fog_visibility_m = None;
        assert_eq!(
            p.fog_layer().expect("the default visibility"),
            Some(FogLayer::new(20.0, DEFAULT_FOG_VISIBILITY_M))
        );
    }

    #[test]
    fn sand_and_dust_presets_carry_their_grains_and_see_as_far_as_they_say() {
        let sand = Preset::load("sandstorm").and_then(|p| {
            p.weather().map_err(|e| PresetError {
                name: "sandstorm".into(),
                problem: e.to_string(),
            })
        });
        let sand = sand.expect("sandstorm");
        let grain = sand.grains().expect("sand has grains");
        assert!(
            (grain.diameter_m - Grain::SAND.diameter_m).abs() < 1e-9,
            "{grain:?}"
        );
        let v = sand.visibility_m();
        assert!((250.0..450.0).contains(&v), "sandstorm sees {v} m");
        let dust = Preset::load("dust-haze")
            .expect("dust-haze")
            .weather()
            .expect("valid");
        assert_eq!(dust.grains(), Some(Grain::DUST));
        let v = dust.visibility_m();
        assert!((1_500.0..2_500.0).contains(&v), "dust haze sees {v} m");
        let text = format!(
            "{}
grain_diameter_mm = 9.0
",
            built_in("sleet")
        );
        assert!(
            Preset::parse(&text, "x")
                .expect("parses")
                .weather()
                .is_err(),
            "a 9 mm grain is refused"
        );
    }

    #[test]
    fn wind_from_the_west_blows_east() {
        let v = wind_vector(5.0, 270.0);
        assert!((v - Vec3::new(5.0, 0.0, 0.0)).length() < 1e-4, "{v}");
        let v = wind_vector(2.0, 0.0);
        assert!(
            (v - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-4,
            "from the north blows south (+Z)"
        );
    }

    #[test]
    fn unknown_fields_and_bad_values_are_refused() {
        assert!(Preset::parse("kind = \"graupel\"", "x").is_err());
        assert!(Preset::load("no-such-preset").is_err());
        let text =
            built_in("light-snow").replace("intensity_mm_per_h = 0.5", "intensity_mm_per_h = -3.0");
        assert!(
            Preset::parse(&text, "x")
                .expect("parses")
                .weather()
                .is_err()
        );
        let text = format!("{}\ncolour = 1\n", built_in("light-snow"));
        assert!(Preset::parse(&text, "x").is_err());
    }
}
