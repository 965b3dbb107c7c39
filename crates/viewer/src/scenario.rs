//! The weather of an OpenSCENARIO 1.x file (`--scenario FILE.xosc`).
//!
//! The first `Environment` anywhere in the file (an `EnvironmentAction` of the
//! `Init`, a catalog's, …) gives the weather: its `Weather` element's `temperature`
//! (K, 1.1+), its `Precipitation` (`precipitationType` `dry`, `rain` or `snow`;
//! `precipitationIntensity` in mm/h (1.1+), or 1.0's `intensity` in `[0, 1]`, which is
//! read as a fraction of a heavy 10 mm/h), its `Wind` (`direction`: the heading the
//! wind blows toward, rad, counter-clockwise from the world's x axis; `speed`, m/s)
//! and its `Fog` (`visualRange`, m, becomes the clear air's extinction `3.912/V`; with
//! a `BoundingBox`, a fog layer of that visibility up to the box's top), and a cloud
//! layer from its `fractionalCloudCover` or `cloudState` ([`cloud_layer_of`]).
//! World axes: OpenSCENARIO's x is precip's x (east), its y is precip's −z (north).
//! Snow above −1 °C is wet snow. What is missing or out of range is an error that
//! names the element and attribute.

use std::path::{Path, PathBuf};

use glam::Vec3;
use precip_model::drawing::clouds::{CloudKind, CloudLayer};
use precip_model::drawing::fog_layer::FogLayer;
use precip_model::wind::WindField;
use precip_model::{PrecipitationKind, Weather};
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// A scenario whose weather cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{file}: {detail}")]
    Read {
        /// The file.
        file: PathBuf,
        /// Why.
        detail: String,
    },
    /// The XML is broken.
    #[error("{file}: not well-formed XML: {detail}")]
    Xml {
        /// The file.
        file: PathBuf,
        /// Where and why.
        detail: String,
    },
    /// No `Environment` with a `Weather`.
    #[error(
        "{file}: no Environment/Weather element: give the scenario an EnvironmentAction with a Weather"
    )]
    NoWeather {
        /// The file.
        file: PathBuf,
    },
    /// An attribute is missing, not a number, or out of range.
    #[error("{file}: {element}@{attribute} = {value:?}: {problem}")]
    Attribute {
        /// The file.
        file: PathBuf,
        /// The element.
        element: &'static str,
        /// The attribute.
        attribute: &'static str,
        /// What it says.
        value: String,
        /// What is wrong and what is allowed.
        problem: String,
    },
    /// The weather it describes is not physical (precip_model's validation).
    #[error("{file}: {0}", file = .1.display())]
    Weather(precip_model::WeatherError, PathBuf),
}

/// The weather a scenario sets, and the clear air's extinction from its fog.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScenarioWeather {
    /// The weather.
    pub weather: Weather,
    /// The fog's extinction, per m (`None` without a `Fog` element, or with a
    /// `BoundingBox`: then it is a layer).
    pub fog_extinction_per_m: Option<f32>,
    /// A `Fog` with a `BoundingBox`: a fog layer up to the box's top (its centre's
    /// `z` + half its `height`; OpenSCENARIO's `z` is up). The layer spreads
    /// horizontally without end.
    pub fog_layer: Option<FogLayer>,
    /// The cloud layer its `Weather`'s `fractionalCloudCover` (1.1+, oktas) or
    /// `cloudState` (1.0) implies ([`cloud_layer_of`]).
    pub cloud_layer: Option<CloudLayer>,
}

/// The cloud layer of OpenSCENARIO's cloud attributes, the first that is given:
/// `fractionalCloudCover` `nOktas` covers `n/8` of the sky (`nineOktas`, sky
/// obscured: all of it) with nimbostratus where it rains or snows, else cumulus up
/// to six oktas and stratus above; `cloudState` `free` and `skyOff` are none,
/// `cloudy` half the sky of cumulus, `overcast` all of it of stratus (nimbostratus
/// where it rains or snows), `rainy` all of it of nimbostratus. Each type at its
/// typical base and thickness.
#[must_use]
pub fn cloud_layer_of(
    fractional_cloud_cover: Option<&str>,
    cloud_state: Option<&str>,
    precipitating: bool,
) -> Option<CloudLayer> {
    let layer = |kind, coverage| Some(CloudLayer::typical(kind, coverage));
    if let Some(oktas) = fractional_cloud_cover {
        let n = match oktas.trim() {
            "zeroOktas" => 0,
            "oneOktas" => 1,
            "twoOktas" => 2,
            "threeOktas" => 3,
            "fourOktas" => 4,
            "fiveOktas" => 5,
            "sixOktas" => 6,
            "sevenOktas" => 7,
            "eightOktas" | "nineOktas" => 8,
            _ => return None,
        };
        let kind = if precipitating && n > 0 {
            CloudKind::Nimbostratus
        } else if n <= 6 {
            CloudKind::Cumulus
        } else {
            CloudKind::Stratus
        };
        return (n > 0).then(|| CloudLayer::typical(kind, n as f32 / 8.0));
    }
    match cloud_state?.trim() {
        "cloudy" => layer(CloudKind::Cumulus, 0.5),
        "overcast" if precipitating => layer(CloudKind::Nimbostratus, 1.0),
        "overcast" => layer(CloudKind::Stratus, 1.0),
        "rainy" => layer(CloudKind::Nimbostratus, 1.0),
        _ => None,
    }
}

/// Kelvin at 0 °C.
const KELVIN_AT_ZERO_C: f32 = 273.15;
/// What OpenSCENARIO 1.0's `intensity` 1 means, mm/h (a heavy rain).
pub const FULL_INTENSITY_MM_PER_H: f32 = 10.0;

/// The attributes of the weather elements, as found.
#[derive(Debug, Default)]
struct Found {
    in_environment: bool,
    weather: bool,
    temperature_k: Option<String>,
    precipitation_type: Option<String>,
    precipitation_mm_per_h: Option<String>,
    intensity_fraction: Option<String>,
    wind_direction_rad: Option<String>,
    wind_speed_mps: Option<String>,
    fog_visual_range_m: Option<String>,
    in_fog: bool,
    cloud_state: Option<String>,
    fractional_cloud_cover: Option<String>,
    fog_centre_z_m: Option<String>,
    fog_height_m: Option<String>,
}

fn attribute(e: &BytesStart<'_>, name: &str) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == name.as_bytes())
        .and_then(|a| {
            a.normalized_value(quick_xml::XmlVersion::default())
                .ok()
                .map(|v| v.into_owned())
        })
}

impl Found {
    fn element(&mut self, e: &BytesStart<'_>) {
        match e.name().as_ref() {
            b"Environment" if !self.weather => self.in_environment = true,
            b"Weather" if self.in_environment && !self.weather => {
                self.weather = true;
                self.temperature_k = attribute(e, "temperature");
                self.cloud_state = attribute(e, "cloudState");
                self.fractional_cloud_cover = attribute(e, "fractionalCloudCover");
            }
            b"Precipitation" if self.weather => {
                self.precipitation_type = attribute(e, "precipitationType");
                self.precipitation_mm_per_h = attribute(e, "precipitationIntensity");
                self.intensity_fraction = attribute(e, "intensity");
            }
            b"Wind" if self.weather => {
                self.wind_direction_rad = attribute(e, "direction");
                self.wind_speed_mps = attribute(e, "speed");
            }
            b"Fog" if self.weather => {
                self.fog_visual_range_m = attribute(e, "visualRange");
                self.in_fog = true;
            }
            b"Center" if self.in_fog => self.fog_centre_z_m = attribute(e, "z"),
            b"Dimensions" if self.in_fog => self.fog_height_m = attribute(e, "height"),
            _ => {}
        }
    }
}

/// Reads the weather of the OpenSCENARIO file `file`.
pub fn load_scenario_weather(file: &Path) -> Result<ScenarioWeather, ScenarioError> {
    let text = std::fs::read_to_string(file).map_err(|e| ScenarioError::Read {
        file: file.to_path_buf(),
        detail: e.to_string(),
    })?;
    scenario_weather(&text, file)
}

/// Reads the weather of OpenSCENARIO text (`file` names it in errors).
pub fn scenario_weather(text: &str, file: &Path) -> Result<ScenarioWeather, ScenarioError> {
    let mut reader = Reader::from_str(text);
    let mut found = Found::default();
    loop {
        match reader.read_event() {
            Ok(Event::Start(e)) => found.element(&e),
            Ok(Event::Empty(e)) => {
                found.element(&e);
                // An empty <Fog/> holds no bounding box.
                found.in_fog &= e.name().as_ref() != b"Fog";
            }
            Ok(Event::End(e)) if e.name().as_ref() == b"Fog" => found.in_fog = false,
            Ok(Event::End(e)) if e.name().as_ref() == b"Environment" && found.weather => break,
            Ok(Event::End(e)) if e.name().as_ref() == b"Environment" => {
                found.in_environment = false;
            }
            Ok(Event::Eof) => break,
            Ok(_) => {}
            Err(e) => {
                return Err(ScenarioError::Xml {
                    file: file.to_path_buf(),
                    detail: format!("at byte {}: {e}", reader.error_position()),
                });
            }
        }
    }
    if !found.weather {
        return Err(ScenarioError::NoWeather {
            file: file.to_path_buf(),
        });
    }
    to_weather(&found, file)
}

fn number(
    file: &Path,
    element: &'static str,
    attribute: &'static str,
    value: Option<&String>,
    range: (f32, f32),
    words: &str,
) -> Result<Option<f32>, ScenarioError> {
    let Some(value) = value else {
        return Ok(None);
    };
    let bad = |problem: String| ScenarioError::Attribute {
        file: file.to_path_buf(),
        element,
        attribute,
        value: value.clone(),
        problem,
    };
    let v: f32 = value
        .trim()
        .parse()
        .map_err(|_| bad(format!("not a number; give {words}")))?;
    if !(v.is_finite() && (range.0..=range.1).contains(&v)) {
        return Err(bad(format!("out of range: allowed {words}")));
    }
    Ok(Some(v))
}

fn to_weather(found: &Found, file: &Path) -> Result<ScenarioWeather, ScenarioError> {
    let temperature_c = number(
        file,
        "Weather",
        "temperature",
        found.temperature_k.as_ref(),
        (170.0, 340.0),
        "[170, 340] K",
    )?
    .map(|k| k - KELVIN_AT_ZERO_C);
    let kind_name = found.precipitation_type.as_deref().unwrap_or("dry");
    let mm_per_h = number(
        file,
        "Precipitation",
        "precipitationIntensity",
        found.precipitation_mm_per_h.as_ref(),
        (0.0, Weather::MAX_INTENSITY_MM_PER_H),
        "[0, 300] mm/h",
    )?;
    let fraction = number(
        file,
        "Precipitation",
        "intensity",
        found.intensity_fraction.as_ref(),
        (0.0, 1.0),
        "[0, 1] (OpenSCENARIO 1.0)",
    )?;
    let rate = mm_per_h.or(fraction.map(|f| f * FULL_INTENSITY_MM_PER_H));
    let (kind, default_c) = match kind_name {
        "rain" => (PrecipitationKind::Rain, 10.0),
        "snow" => (PrecipitationKind::DrySnow, -5.0),
        "dry" => (PrecipitationKind::Rain, 15.0),
        other => {
            return Err(ScenarioError::Attribute {
                file: file.to_path_buf(),
                element: "Precipitation",
                attribute: "precipitationType",
                value: other.to_owned(),
                problem: "not a precipitation type: use dry, rain or snow".into(),
            });
        }
    };
    let air_temperature_c = temperature_c.unwrap_or(default_c);
    let kind = if kind == PrecipitationKind::DrySnow && air_temperature_c > -1.0 {
        PrecipitationKind::WetSnow
    } else {
        kind
    };
    let intensity_mm_per_h = if kind_name == "dry" {
        0.0
    } else {
        rate.ok_or_else(|| ScenarioError::Attribute {
            file: file.to_path_buf(),
            element: "Precipitation",
            attribute: "precipitationIntensity",
            value: String::new(),
            problem: "missing: give the rate in mm/h (or 1.0's intensity in [0, 1])".into(),
        })?
    };
    let direction = number(
        file,
        "Wind",
        "direction",
        found.wind_direction_rad.as_ref(),
        (-7.0, 7.0),
        "[0, 2π] rad",
    )?
    .unwrap_or(0.0);
    let speed = number(
        file,
        "Wind",
        "speed",
        found.wind_speed_mps.as_ref(),
        (0.0, 100.0),
        "[0, 100] m/s",
    )?
    .unwrap_or(0.0);
    let fog_extinction_per_m = number(
        file,
        "Fog",
        "visualRange",
        found.fog_visual_range_m.as_ref(),
        (1.0, 1.0e7),
        "[1, 10 000 000] m",
    )?
    .map(|v| 3.912 / v);
    let centre_z = number(
        file,
        "Fog/BoundingBox/Center",
        "z",
        found.fog_centre_z_m.as_ref(),
        (-20_000.0, 20_000.0),
        "a height within ±20 000 m",
    )?;
    let height = number(
        file,
        "Fog/BoundingBox/Dimensions",
        "height",
        found.fog_height_m.as_ref(),
        (0.0, 20_000.0),
        "[0, 20 000] m",
    )?;
    let (fog_extinction_per_m, fog_layer) = match (fog_extinction_per_m, centre_z, height) {
        (Some(b), Some(z), Some(h)) => (None, Some(FogLayer::new(z + 0.5 * h, 3.912 / b))),
        (b, _, _) => (b, None),
    };
    if let Some(layer) = &fog_layer {
        layer.validate().map_err(|e| ScenarioError::Attribute {
            file: file.to_path_buf(),
            element: "Fog",
            attribute: "visualRange",
            value: found.fog_visual_range_m.clone().unwrap_or_default(),
            problem: e.to_string(),
        })?;
    }
    let weather = Weather {
        kind,
        intensity_mm_per_h,
        air_temperature_c,
        wind: WindField {
            mean_wind_mps: Vec3::new(direction.cos(), 0.0, -direction.sin()) * speed,
            ..WindField::calm()
        },
        ..Weather::default()
    };
    weather
        .validate()
        .map_err(|e| ScenarioError::Weather(e, file.to_path_buf()))?;
    let cloud_layer = cloud_layer_of(
        found.fractional_cloud_cover.as_deref(),
        found.cloud_state.as_deref(),
        weather.intensity_mm_per_h > 0.0,
    );
    Ok(ScenarioWeather {
        weather,
        fog_extinction_per_m,
        fog_layer,
        cloud_layer,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xosc(environment: &str) -> String {
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-11-25T00:00:00" description="t" author="t"/>
  <Storyboard>
    <Init><Actions><GlobalAction><EnvironmentAction>
      {environment}
    </EnvironmentAction></GlobalAction></Actions></Init>
  </Storyboard>
</OpenSCENARIO>"#
        )
    }

    fn read(environment: &str) -> Result<ScenarioWeather, ScenarioError> {
        scenario_weather(&xosc(environment), Path::new("t.xosc"))
    }

    #[test]
    fn cloud_cover_in_oktas_or_as_a_state_is_a_cloud_layer() {
        let w = read(
            r#"<Environment name="c"><Weather temperature="290" fractionalCloudCover="threeOktas">
                 <Precipitation precipitationType="dry"/></Weather></Environment>"#,
        )
        .expect("valid");
        assert_eq!(
            w.cloud_layer,
            Some(CloudLayer::typical(CloudKind::Cumulus, 0.375))
        );
        let rainy = read(
            r#"<Environment name="r"><Weather cloudState="rainy">
                 <Precipitation precipitationType="rain" intensity="0.5"/></Weather></Environment>"#,
        )
        .expect("valid");
        assert_eq!(
            rainy.cloud_layer,
            Some(CloudLayer::typical(CloudKind::Nimbostratus, 1.0))
        );
        assert_eq!(cloud_layer_of(None, Some("free"), false), None);
        assert_eq!(cloud_layer_of(Some("zeroOktas"), Some("rainy"), true), None);
        assert_eq!(
            cloud_layer_of(Some("eightOktas"), None, true),
            Some(CloudLayer::typical(CloudKind::Nimbostratus, 1.0))
        );
        assert_eq!(
            cloud_layer_of(None, Some("overcast"), false),
            Some(CloudLayer::typical(CloudKind::Stratus, 1.0))
        );
    }

    #[test]
    fn a_fog_with_a_bounding_box_is_a_layer_up_to_its_top() {
        let w = read(
            r#"<Environment name="valley"><Weather temperature="278.15">
                 <Fog visualRange="150">
                   <BoundingBox>
                     <Center x="0" y="0" z="10"/>
                     <Dimensions width="2000" length="2000" height="30"/>
                   </BoundingBox>
                 </Fog>
                 <Precipitation precipitationType="dry"/>
               </Weather></Environment>"#,
        )
        .expect("valid");
        assert_eq!(w.fog_layer, Some(FogLayer::new(25.0, 150.0)));
        assert_eq!(
            w.fog_extinction_per_m, None,
            "the layer, not a uniform haze"
        );
        let bad = read(
            r#"<Environment name="v"><Weather><Fog visualRange="150"><BoundingBox>
                 <Center x="0" y="0" z="high"/><Dimensions width="1" length="1" height="30"/>
               </BoundingBox></Fog><Precipitation precipitationType="dry"/></Weather></Environment>"#,
        )
        .expect_err("z is not a number");
        assert!(bad.to_string().contains("Center"), "{bad}");
    }

    #[test]
    fn rain_snow_wind_and_fog_of_openscenario_one_one() {
        let w = read(
            r#"<Environment name="wet">
                 <TimeOfDay animation="false" dateTime="2026-11-25T12:00:00"/>
                 <Weather temperature="283.15" fractionalCloudCover="eightOktas">
                   <Sun azimuth="0" elevation="1" illuminance="1000"/>
                   <Fog visualRange="800"/>
                   <Precipitation precipitationType="rain" precipitationIntensity="7.5"/>
                   <Wind direction="1.5707963" speed="6"/>
                 </Weather>
                 <RoadCondition frictionScaleFactor="0.7"/>
               </Environment>"#,
        )
        .expect("valid");
        assert_eq!(w.weather.kind, PrecipitationKind::Rain);
        assert!((w.weather.intensity_mm_per_h - 7.5).abs() < 1e-6);
        assert!((w.weather.air_temperature_c - 10.0).abs() < 1e-3);
        // Toward +y (north) is precip's −z.
        let m = w.weather.wind.mean_wind_mps;
        assert!(m.x.abs() < 1e-4 && (m.z + 6.0).abs() < 1e-4, "{m}");
        assert!((w.fog_extinction_per_m.expect("fog") - 3.912 / 800.0).abs() < 1e-7);

        let snow = read(
            r#"<Environment name="s"><Weather temperature="263.15">
                 <Precipitation precipitationType="snow" precipitationIntensity="2"/>
               </Weather></Environment>"#,
        )
        .expect("valid");
        assert_eq!(snow.weather.kind, PrecipitationKind::DrySnow);
        let wet = read(
            r#"<Environment name="s"><Weather temperature="273.65">
                 <Precipitation precipitationType="snow" intensity="0.5"/>
               </Weather></Environment>"#,
        )
        .expect("1.0's intensity");
        assert_eq!(wet.weather.kind, PrecipitationKind::WetSnow);
        assert!((wet.weather.intensity_mm_per_h - 5.0).abs() < 1e-6);
        let dry = read(
            r#"<Environment name="d"><Weather><Precipitation precipitationType="dry"/></Weather></Environment>"#,
        )
        .expect("dry");
        assert!(dry.weather.intensity_mm_per_h.abs() < f32::MIN_POSITIVE);
    }

    #[test]
    fn missing_and_out_of_range_values_are_named() {
        let err = |env: &str| read(env).expect_err("refused").to_string();
        assert!(err("").contains("no Environment/Weather"));
        assert!(
            err(r#"<Environment name="x"><Weather><Precipitation precipitationType="hail" precipitationIntensity="1"/></Weather></Environment>"#)
                .contains("precipitationType")
        );
        assert!(
            err(r#"<Environment name="x"><Weather temperature="20"><Precipitation precipitationType="rain" precipitationIntensity="1"/></Weather></Environment>"#)
                .contains("temperature")
        );
        assert!(
            err(r#"<Environment name="x"><Weather><Precipitation precipitationType="rain" precipitationIntensity="-3"/></Weather></Environment>"#)
                .contains("precipitationIntensity")
        );
        assert!(
            err(r#"<Environment name="x"><Weather><Precipitation precipitationType="rain"/></Weather></Environment>"#)
                .contains("missing")
        );
        assert!(
            err(r#"<Environment name="x"><Weather><Fog visualRange="fog"/><Precipitation precipitationType="dry"/></Weather></Environment>"#)
                .contains("visualRange")
        );
        assert!(
            err(r#"<Environment name="x"><Weather temperature="303.15"><Precipitation precipitationType="snow" precipitationIntensity="1"/></Weather></Environment>"#)
                .contains("°C")
        );
        let broken = scenario_weather("<OpenSCENARIO><Environment>", Path::new("b.xosc"));
        assert!(broken.is_err());
    }
}
