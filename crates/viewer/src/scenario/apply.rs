//! A scenario's timeline played on a backend: each change applied when the
//! simulated clock reaches it (its weather, fog layer, clouds, sun and haze).

use glam::Vec3;
use precip_model::{Backend, BackendError};

use super::{ScenarioWeather, TimedWeather};

/// The changes still to come and the light they keep.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioClock {
    changes: Vec<TimedWeather>,
    next: usize,
    to_sun: Vec3,
    clear_air_extinction_per_m: f32,
}

impl ScenarioClock {
    /// Plays `changes` (in time order) over a run that starts with the sun toward
    /// `to_sun`; an environment without a `Fog` has the clear air's
    /// `clear_air_extinction_per_m`, one without a `Sun` keeps the sun it had.
    #[must_use]
    pub fn new(changes: Vec<TimedWeather>, to_sun: Vec3, clear_air_extinction_per_m: f32) -> Self {
        Self {
            changes,
            next: 0,
            to_sun,
            clear_air_extinction_per_m,
        }
    }

    /// Applies every change due by `time_s` (simulated seconds since the start) to
    /// `backend`; returns a line for each, for the run's summary.
    pub fn advance(
        &mut self,
        time_s: f64,
        backend: &mut dyn Backend,
    ) -> Result<Vec<String>, BackendError> {
        let mut applied = Vec::new();
        while let Some(change) = self.changes.get(self.next) {
            if change.at_s > time_s {
                break;
            }
            self.to_sun = change.weather.to_sun.unwrap_or(self.to_sun);
            apply(
                backend,
                &change.weather,
                self.to_sun,
                self.clear_air_extinction_per_m,
            )?;
            applied.push(format!(
                "scenario: at {:.1} s ({} s due) {}: {}",
                time_s,
                change.at_s,
                change.event,
                describe(&change.weather)
            ));
            self.next += 1;
        }
        Ok(applied)
    }

    /// Changes not yet applied.
    #[must_use]
    pub fn pending(&self) -> usize {
        self.changes.len() - self.next
    }
}

/// Sets `w` on `backend`: weather, fog layer, clouds, sun, haze.
fn apply(
    backend: &mut dyn Backend,
    w: &ScenarioWeather,
    to_sun: Vec3,
    clear_air_extinction_per_m: f32,
) -> Result<(), BackendError> {
    backend.set_weather(&w.weather)?;
    backend.set_fog_layer(w.fog_layer)?;
    backend.set_cloud_layers(w.cloud_layer.into())?;
    backend.set_atmosphere(
        Some(to_sun),
        Some(w.fog_extinction_per_m.unwrap_or(clear_air_extinction_per_m)),
    )
}

/// One line for a scenario's weather.
#[must_use]
pub fn describe(w: &ScenarioWeather) -> String {
    let mut line = format!(
        "{:?} {:.2} mm/h at {:.1} °C, wind {:.1} m/s",
        w.weather.kind,
        w.weather.intensity_mm_per_h,
        w.weather.air_temperature_c,
        w.weather.wind.mean_wind_mps.length()
    );
    if let Some(fog) = w.fog_extinction_per_m {
        line += &format!(", fog visibility {:.0} m", 3.912 / fog);
    }
    if let Some(layer) = w.fog_layer {
        line += &format!(", fog layer to {:.0} m", layer.top_m);
    }
    if let Some(c) = w.cloud_layer {
        line += &format!(
            ", {:?} {:.0} % from {:.0} m",
            c.kind,
            c.coverage * 100.0,
            c.base_m
        );
    }
    if let Some(s) = w.to_sun {
        line += &format!(", sun {:.0}° up", s.y.clamp(-1.0, 1.0).asin().to_degrees());
    }
    if let Some(f) = w.friction_scale {
        line += &format!(", road friction ×{f:.2} (reported only)");
    }
    if let Some(t) = &w.time_of_day {
        line += &format!(", time of day {t}");
    }
    line
}
