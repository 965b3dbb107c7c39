//! [`HostWeather`]: the weather a host sets with global Weather Control packets.
//!
//! ## Severity to intensity
//!
//! CIGI 3.3 gives a layer's severity as 0 (least) to 5 (most severe) without units
//! and leaves its meaning to the IG. precip spreads the six steps over the
//! intensity classes of the AMS Glossary (rain: light below 2.5 mm/h, moderate to
//! 7.6, heavy above, violent above 50; snow, as water: light below 1 mm/h, heavy
//! above 2.5), roughly doubling a step, so 0 is the lightest that shows and 5 the
//! heaviest a simulator meets:
//!
//! | severity | 0 | 1 | 2 | 3 | 4 | 5 |
//! | --- | --- | --- | --- | --- | --- | --- |
//! | rain, mm/h | 0.5 | 1.5 | 4 | 10 | 25 | 60 |
//! | snow and sleet, mm/h of water | 0.2 | 0.5 | 1 | 2 | 4 | 8 |
//! | hail, mm/h of water | 1 | 2 | 5 | 10 | 20 | 40 |
//! | sand and dust: visibility, m | 5 000 | 2 000 | 1 000 | 500 | 200 | 50 |
//!
//! Sand and dust are given by what one sees through them (WMO: a dust haze above
//! 1 km, a sandstorm below, a severe one below 200 m), so a visibility range the
//! host sends wins over the severity; the settling rate is the one that holds that
//! visibility ([`precip_model::physics::grain`]). The layer's coverage (%) scales the rate
//! (showers over part of the area). Base elevation and thickness are kept
//! ([`HostWeather::layer_extent_m`]) but precipitation falls to the ground from
//! whatever layer sends it. The ground fog (layer 0) is a fog layer from the ground
//! up to its base elevation + thickness, of the visibility range the host sends (by
//! severity when it sends 0: 1 000, 500, 300, 200, 100, 50 m); disabling it clears
//! it. Cloud layers 1–3 (base elevation, thickness, coverage, cloud type: [`cloud_kind`],
//! transition band: the air thickening toward the layer within it, above and below)
//! are kept and every one that is on is drawn, lowest first; a layer reaching into
//! the one below it starts at that one's top (dropped where less than 10 m of it is
//! left). Hail (layer 7) falls as hail ([`precip_model::physics::hail`]: its stones
//! grow with the rate: pea-sized at severity 0, a median of 11 mm and one stone in
//! twenty past 29 mm at 5). The regional and
//! entity scopes are counted as ignored.

use glam::Vec3;
use precip_model::drawing::clouds::{CloudKind, CloudLayer, CloudLayers};
use precip_model::drawing::fog_layer::FogLayer;
use precip_model::physics::grain::{Grain, grain_settling_speed_mps};
use precip_model::wind::WindField;
use precip_model::{PrecipitationKind, Weather};

use crate::packet::WeatherControl;

/// Rain's rate by severity, mm/h (module docs).
pub const RAIN_MM_PER_H: [f32; 6] = [0.5, 1.5, 4.0, 10.0, 25.0, 60.0];
/// Snow's and sleet's water rate by severity, mm/h.
pub const SNOW_MM_PER_H: [f32; 6] = [0.2, 0.5, 1.0, 2.0, 4.0, 8.0];
/// Hail's water rate by severity, mm/h (a hailfall's ice as water: a few mm/h of
/// pea hail to the 40 mm/h of a severe storm's core).
pub const HAIL_MM_PER_H: [f32; 6] = [1.0, 2.0, 5.0, 10.0, 20.0, 40.0];
/// Sand's and dust's visibility by severity, m.
pub const GRAIN_VISIBILITY_M: [f32; 6] = [5_000.0, 2_000.0, 1_000.0, 500.0, 200.0, 50.0];
/// Ground fog's visibility by severity when the host sends none, m (WMO: fog is
/// below 1 km).
pub const FOG_VISIBILITY_M: [f32; 6] = [1_000.0, 500.0, 300.0, 200.0, 100.0, 50.0];
/// CIGI 3.3's layer ID of the ground fog.
pub const GROUND_FOG_LAYER: u8 = 0;
/// The thinnest cloud layer drawn, m ([`CloudLayer::validate`]'s least).
const MIN_CLOUD_THICKNESS_M: f32 = 10.0;

/// CIGI 3.3's layer IDs of the cloud layers.
pub const CLOUD_LAYERS: std::ops::RangeInclusive<u8> = 1..=3;

/// The cloud kind precip draws for a CIGI 3.3 cloud type: cumulonimbus, cumulus
/// (and the heaped altocumulus, stratocumulus, cirrocumulus), stratus (and the
/// sheets: altostratus, cirrostratus, cirrus), nimbostratus (and none or other).
#[must_use]
pub const fn cloud_kind(cloud_type: u8) -> CloudKind {
    match cloud_type {
        6 => CloudKind::Cumulonimbus,
        1 | 3 | 7 | 9 => CloudKind::Cumulus,
        2 | 4 | 5 | 10 => CloudKind::Stratus,
        _ => CloudKind::Nimbostratus,
    }
}

/// The precipitation kind of a Weather Control layer; `None` for the layers precip
/// does not draw.
#[must_use]
pub const fn layer_kind(layer: u8) -> Option<PrecipitationKind> {
    match layer {
        4 => Some(PrecipitationKind::Rain),
        5 => Some(PrecipitationKind::DrySnow),
        6 => Some(PrecipitationKind::Sleet),
        7 => Some(PrecipitationKind::Hail),
        8 => Some(PrecipitationKind::Sand),
        9 => Some(PrecipitationKind::Dust),
        _ => None,
    }
}

/// The settling rate of `grain` that holds visibility `visibility_m`, kg/(m²·h):
/// `σ = 3.912/V`, `C = σ·ρ·d/3`, rate `= C·w·3600`.
#[must_use]
pub fn grain_rate_for_visibility(grain: &Grain, visibility_m: f32) -> f32 {
    let sigma = 3.912 / visibility_m.max(1.0);
    let concentration = sigma * grain.density_kg_m3 * grain.diameter_m / 3.0;
    concentration * grain_settling_speed_mps(grain.diameter_m, grain.density_kg_m3) * 3600.0
}

/// What a global Weather Control did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Applied {
    /// The weather changed to this.
    Changed(Weather),
    /// The ground fog changed to this layer (`None`: cleared).
    Fog(Option<FogLayer>),
    /// The cloud layers drawn changed to these (none: no cloud layer is on).
    Clouds(CloudLayers),
    /// The packet was for a layer, scope or kind precip does not draw.
    Ignored,
    /// The weather it asks for is not physical (precip_model's validation): kept
    /// the last one.
    Refused,
}

/// The weather the host has set, starting from a given one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HostWeather {
    weather: Weather,
    layer_extent_m: Option<(f32, f32)>,
    fog_layer: Option<FogLayer>,
    /// Cloud layers 1–3 as the host set them.
    cloud_layers: [Option<CloudLayer>; 3],
}

impl HostWeather {
    /// Starts from `weather`.
    #[must_use]
    pub fn new(weather: Weather) -> Self {
        Self {
            weather,
            layer_extent_m: None,
            fog_layer: None,
            cloud_layers: [None; 3],
        }
    }

    /// The weather in effect.
    #[must_use]
    pub fn weather(&self) -> Weather {
        self.weather
    }

    /// The last precipitation layer's base elevation and thickness, m.
    #[must_use]
    pub fn layer_extent_m(&self) -> Option<(f32, f32)> {
        self.layer_extent_m
    }

    /// The cloud layers drawn: every one that is on, lowest first, each starting
    /// no lower than the top of the one below it (a layer with less than 10 m
    /// left above that top is not drawn).
    #[must_use]
    pub fn cloud_layers(&self) -> CloudLayers {
        let mut on: Vec<CloudLayer> = self.cloud_layers.iter().flatten().copied().collect();
        on.sort_by(|a, b| a.base_m.total_cmp(&b.base_m));
        let mut drawn: Vec<CloudLayer> = Vec::with_capacity(on.len());
        for layer in on {
            let floor = drawn.last().map_or(f32::NEG_INFINITY, CloudLayer::top_m);
            let base_m = layer.base_m.max(floor);
            let thickness_m = layer.top_m() - base_m;
            if thickness_m >= MIN_CLOUD_THICKNESS_M {
                drawn.push(CloudLayer {
                    base_m,
                    thickness_m,
                    ..layer
                });
            }
        }
        // Each layer was validated on arrival; cut as above they stay valid.
        CloudLayers::new(&drawn).unwrap_or_default()
    }

    /// The ground fog in effect.
    #[must_use]
    pub fn fog_layer(&self) -> Option<FogLayer> {
        self.fog_layer
    }

    /// Applies one Weather Control packet (module docs).
    pub fn apply(&mut self, packet: &WeatherControl) -> Applied {
        if packet.layer == GROUND_FOG_LAYER && packet.scope == 0 {
            return self.apply_fog(packet);
        }
        if CLOUD_LAYERS.contains(&packet.layer) && packet.scope == 0 {
            return self.apply_clouds(packet);
        }
        let Some(kind) = layer_kind(packet.layer) else {
            return Applied::Ignored;
        };
        if packet.scope != 0 {
            return Applied::Ignored;
        }
        let severity = usize::from(packet.severity.min(5));
        let coverage = (packet.coverage_percent / 100.0).clamp(0.0, 1.0);
        let mut next = self.weather;
        if !packet.enabled {
            if next.kind != kind {
                return Applied::Ignored;
            }
            next.intensity_mm_per_h = 0.0;
        } else {
            next.kind = kind;
            next.grain = None;
            let rate = match kind.default_grain() {
                Some(grain) => {
                    let visibility = if packet.visibility_m > 0.0 {
                        packet.visibility_m
                    } else {
                        GRAIN_VISIBILITY_M[severity]
                    };
                    grain_rate_for_visibility(&grain, visibility)
                }
                None if kind == PrecipitationKind::Rain => RAIN_MM_PER_H[severity],
                None if kind == PrecipitationKind::Hail => HAIL_MM_PER_H[severity],
                None => SNOW_MM_PER_H[severity],
            };
            next.intensity_mm_per_h = rate * coverage;
            next.air_temperature_c = packet.air_temperature_c;
            if kind == PrecipitationKind::DrySnow && packet.air_temperature_c > -1.0 {
                // Snow near and above freezing is wet.
                next.kind = PrecipitationKind::WetSnow;
            }
        }
        next.relative_humidity = (f32::from(packet.humidity_percent) / 100.0).clamp(0.0, 1.0);
        let horizontal =
            WindField::mean_wind_from(packet.horizontal_wind_mps.max(0.0), packet.wind_from_deg);
        next.wind = WindField {
            mean_wind_mps: horizontal + Vec3::Y * packet.vertical_wind_mps,
            ..next.wind
        };
        if next.validate().is_err() {
            return Applied::Refused;
        }
        self.weather = next;
        self.layer_extent_m = Some((packet.base_elevation_m, packet.thickness_m));
        Applied::Changed(next)
    }

    /// A cloud layer's packet (layers 1–3).
    fn apply_clouds(&mut self, packet: &WeatherControl) -> Applied {
        let layer = packet.enabled.then(|| CloudLayer {
            base_m: packet.base_elevation_m,
            thickness_m: packet.thickness_m,
            coverage: (packet.coverage_percent / 100.0).clamp(0.0, 1.0),
            kind: cloud_kind(packet.cloud_type),
            transition_band_m: packet.transition_band_m,
        });
        if layer.as_ref().is_some_and(|l| l.validate().is_err()) {
            return Applied::Refused;
        }
        let slot = usize::from(packet.layer - 1);
        if let Some(s) = self.cloud_layers.get_mut(slot) {
            *s = layer;
        }
        Applied::Clouds(self.cloud_layers())
    }

    /// The ground fog layer of a packet for layer 0.
    fn apply_fog(&mut self, packet: &WeatherControl) -> Applied {
        let fog = packet.enabled.then(|| {
            let visibility = if packet.visibility_m > 0.0 {
                packet.visibility_m
            } else {
                FOG_VISIBILITY_M[usize::from(packet.severity.min(5))]
            };
            FogLayer::new(
                packet.base_elevation_m + packet.thickness_m.max(0.0),
                visibility,
            )
        });
        if fog.as_ref().is_some_and(|f| f.validate().is_err()) {
            return Applied::Refused;
        }
        self.fog_layer = fog;
        Applied::Fog(fog)
    }
}
