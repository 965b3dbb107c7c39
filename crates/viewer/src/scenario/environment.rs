//! One OpenSCENARIO `Environment` as precip's weather: its `Weather` element's
//! `temperature` (K, 1.1+), its `Precipitation` (`precipitationType` `dry`, `rain` or
//! `snow`; `precipitationIntensity` in mm/h (1.1+), or 1.0's `intensity` in `[0, 1]`,
//! read as a fraction of a heavy 10 mm/h), its `Wind` (`direction`: the heading the
//! wind blows toward, rad, counter-clockwise from the world's x axis; `speed`, m/s),
//! its `Fog` (`visualRange`, m, becomes the clear air's extinction `3.912/V`; with a
//! `BoundingBox`, a fog layer of that visibility up to the box's top), a cloud layer
//! from its `fractionalCloudCover` or `cloudState` ([`cloud_layer_of`]), its `Sun`
//! (`azimuth` clockwise from north, `elevation`, rad: the light's direction), and,
//! reported only, `TimeOfDay` and `RoadCondition`'s `frictionScaleFactor`. World
//! axes: OpenSCENARIO's x is precip's x (east), its y is precip's −z (north). Snow
//! above −1 °C is wet snow. What is missing or out of range is an error that names
//! the element and attribute; every attribute may be a parameter (`$name`, `${…}`).

use std::path::Path;

use glam::Vec3;
use precip_model::drawing::clouds::{CloudKind, CloudLayer};
use precip_model::drawing::fog_layer::FogLayer;
use precip_model::wind::WindField;
use precip_model::{PrecipitationKind, Weather};
use roxmltree::Node;

use super::ScenarioError;
use super::parameters::Parameters;

/// The weather a scenario sets, and the clear air's extinction from its fog.
#[derive(Debug, Clone, PartialEq)]
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
    /// Toward the sun (unit), from its `Sun`'s azimuth and elevation.
    pub to_sun: Option<Vec3>,
    /// `TimeOfDay@dateTime`, as written: the sun's direction where no `Sun` gives
    /// it ([`super::Scenario::light_by_time_of_day`]).
    pub time_of_day: Option<String>,
    /// `RoadCondition@frictionScaleFactor` (reported: precip has no tyres).
    pub friction_scale: Option<f32>,
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

/// The attributes of the weather elements, as found (parameters resolved).
#[derive(Debug, Default)]
struct Found {
    temperature_k: Option<String>,
    precipitation_type: Option<String>,
    precipitation_mm_per_h: Option<String>,
    intensity_fraction: Option<String>,
    wind_direction_rad: Option<String>,
    wind_speed_mps: Option<String>,
    fog_visual_range_m: Option<String>,
    cloud_state: Option<String>,
    fractional_cloud_cover: Option<String>,
    fog_centre_z_m: Option<String>,
    fog_height_m: Option<String>,
    sun_azimuth_rad: Option<String>,
    sun_elevation_rad: Option<String>,
    time_of_day: Option<String>,
    friction_scale: Option<String>,
}

/// The child of `node` named `tag`.
fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.has_tag_name(tag))
}

/// The weather of the `Environment` element `environment`, its attributes'
/// parameters resolved in `parameters` (`file` names it in errors).
pub fn environment_weather(
    environment: Node<'_, '_>,
    parameters: &Parameters,
    file: &Path,
) -> Result<ScenarioWeather, ScenarioError> {
    let get = |node: Option<Node<'_, '_>>, element: &'static str, name: &'static str| {
        node.and_then(|n| n.attribute(name))
            .map(|raw| {
                parameters
                    .resolve(raw)
                    .map_err(|problem| ScenarioError::Attribute {
                        file: file.to_path_buf(),
                        element,
                        attribute: name,
                        value: raw.to_owned(),
                        problem,
                    })
            })
            .transpose()
    };
    let weather = child(environment, "Weather").ok_or_else(|| ScenarioError::NoWeather {
        file: file.to_path_buf(),
    })?;
    let precipitation = child(weather, "Precipitation");
    let wind = child(weather, "Wind");
    let fog = child(weather, "Fog");
    let sun = child(weather, "Sun");
    let bounding_box = fog.and_then(|f| child(f, "BoundingBox"));
    let found = Found {
        temperature_k: get(Some(weather), "Weather", "temperature")?,
        cloud_state: get(Some(weather), "Weather", "cloudState")?,
        fractional_cloud_cover: get(Some(weather), "Weather", "fractionalCloudCover")?,
        precipitation_type: get(precipitation, "Precipitation", "precipitationType")?,
        precipitation_mm_per_h: get(precipitation, "Precipitation", "precipitationIntensity")?,
        intensity_fraction: get(precipitation, "Precipitation", "intensity")?,
        wind_direction_rad: get(wind, "Wind", "direction")?,
        wind_speed_mps: get(wind, "Wind", "speed")?,
        fog_visual_range_m: get(fog, "Fog", "visualRange")?,
        fog_centre_z_m: get(
            bounding_box.and_then(|b| child(b, "Center")),
            "Fog/BoundingBox/Center",
            "z",
        )?,
        fog_height_m: get(
            bounding_box.and_then(|b| child(b, "Dimensions")),
            "Fog/BoundingBox/Dimensions",
            "height",
        )?,
        sun_azimuth_rad: get(sun, "Sun", "azimuth")?,
        sun_elevation_rad: get(sun, "Sun", "elevation")?,
        time_of_day: get(child(environment, "TimeOfDay"), "TimeOfDay", "dateTime")?,
        friction_scale: get(
            child(environment, "RoadCondition"),
            "RoadCondition",
            "frictionScaleFactor",
        )?,
    };
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
    let azimuth = number(
        file,
        "Sun",
        "azimuth",
        found.sun_azimuth_rad.as_ref(),
        (-7.0, 7.0),
        "[0, 2π] rad clockwise from north",
    )?;
    let elevation = number(
        file,
        "Sun",
        "elevation",
        found.sun_elevation_rad.as_ref(),
        (-1.571, 1.571),
        "[−π/2, π/2] rad",
    )?;
    let to_sun = azimuth.zip(elevation).map(|(a, e)| {
        // North is −z, east +x; a sun under the horizon lights from just above it
        // (precip has no night).
        let e = e.max(0.05);
        Vec3::new(a.sin() * e.cos(), e.sin(), -a.cos() * e.cos())
    });
    let friction_scale = number(
        file,
        "RoadCondition",
        "frictionScaleFactor",
        found.friction_scale.as_ref(),
        (0.0, 10.0),
        "[0, 10]",
    )?;
    Ok(ScenarioWeather {
        weather,
        fog_extinction_per_m,
        fog_layer,
        cloud_layer,
        to_sun,
        time_of_day: found.time_of_day.clone(),
        friction_scale,
    })
}
