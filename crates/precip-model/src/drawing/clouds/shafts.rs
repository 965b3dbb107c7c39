//! Rain and snow shafts (docs/model.md (6.16)): the weather a user sets is the
//! weather around the camera — within [`LOCAL_WEATHER_RADIUS_M`], where its
//! particles fall and its cover lies — and beyond it the same mean rate falls only
//! from the lowest layer's clouds, under the columns they stand over
//! ([`super::cloud_column`]), from their base to the ground: `rate/s` under a layer
//! whose columns stand over the share `s` of the land ([`shaft_share`]: about its
//! coverage `c`, less the columns' soft edges; [`shaft_extinction_per_m`]), none
//! between, so the mean over the layer's area is the rate set. Seen from under the
//! deck, the far air between the camera and the clouds is grey where a shaft hangs
//! and clear between them; the haze of sand and dust, which no cloud drops, stays
//! everywhere.
//!
//! WGSL twin: `precipitation_haze` (render_clouds.wgsl), with the map read by
//! the sampler instead of [`super::sample_coverage_map`].

use glam::{Vec2, Vec3};

use super::{CloudLayer, cloud_column, cloud_map_uv, sample_coverage_map};
use crate::Weather;

/// The distance from the camera within which the weather is the one set, m.
pub const LOCAL_WEATHER_RADIUS_M: f32 = 3_000.0;
/// Samples of the shafts along a path beyond [`LOCAL_WEATHER_RADIUS_M`].
pub const RAIN_SHAFT_SAMPLES: u32 = 8;
/// The share of the horizon's sky light a layer's base and the shafts under it
/// scatter (in their clouds' shade; docs/model.md (6.10), (6.16)): a look.
pub const CLOUD_BASE_SKY_SHARE: f32 = 0.4;

/// The least share of the land a shaft's rate is concentrated by (`rate/s`, at
/// most 20×).
pub const MIN_SHAFT_COVERAGE: f32 = 0.05;

/// The share of the land under the columns of a layer covering `coverage`: the
/// mean of `column(c − m)` over the coverage map (its texels' values counted once
/// in 256 bins), at least [`MIN_SHAFT_COVERAGE`] — a little less than `c`, the
/// columns' edges being soft.
#[must_use]
pub fn shaft_share(coverage: f32) -> f32 {
    static BINS: std::sync::OnceLock<[u32; 256]> = std::sync::OnceLock::new();
    let bins = BINS.get_or_init(|| {
        let mut bins = [0_u32; 256];
        for &m in &super::cloud_noise().coverage {
            bins[usize::from(m)] += 1;
        }
        bins
    });
    let total: u32 = bins.iter().sum();
    let under: f64 = bins
        .iter()
        .enumerate()
        .map(|(m, &count)| f64::from(count) * f64::from(cloud_column(coverage, m as f32 / 255.0)))
        .sum();
    ((under / f64::from(total.max(1))) as f32).max(MIN_SHAFT_COVERAGE)
}

/// The extinction per m of what falls under one of `lowest`'s clouds: `weather`'s
/// rain and snow at `rate/s` ([`shaft_share`]; capped at the largest rate a weather
/// may have), so the mean over the layer's area is the rate set; sand and dust do
/// not fall from clouds (0).
#[must_use]
pub fn shaft_extinction_per_m(weather: &Weather, lowest: &CloudLayer) -> f32 {
    let concentrated = Weather {
        intensity_mm_per_h: (weather.intensity_mm_per_h / shaft_share(lowest.coverage))
            .min(Weather::MAX_INTENSITY_MM_PER_H),
        ..*weather
    };
    (concentrated.extinction_per_m() - concentrated.grain_extinction_per_m()).max(0.0)
}

/// The extinctions of the air a sky ray crosses under the clouds, per m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HazeExtinctions {
    /// The clear air's and the grains', everywhere.
    pub rest_per_m: f32,
    /// The precipitation's around the camera (within [`LOCAL_WEATHER_RADIUS_M`]).
    pub local_per_m: f32,
    /// The precipitation's in a shaft beyond ([`shaft_extinction_per_m`]).
    pub shaft_per_m: f32,
}

/// What the air between `camera` and `t_end` m along the unit `dir` does to what
/// lies behind it: `(light, transmittance)`, the light it scatters toward the
/// camera as a share of the horizon's sky light `A`, and the share of what lies
/// behind that passes. Piecewise along the ray: within [`LOCAL_WEATHER_RADIUS_M`]
/// the clear air and the precipitation set (scattering `A`); beyond, under
/// `lowest`'s base, the clear air (`A`) and the shafts under its clouds (its map
/// read at `offset_m`, [`cloud_column`]), which hang in their clouds' shade and
/// scatter [`CLOUD_BASE_SKY_SHARE`]`·A`, by the midpoints of [`RAIN_SHAFT_SAMPLES`]
/// steps up to where the ray rises through the base; each step's light
/// `T·(1 − e^(−σΔ))·S/σ` behind the transmittance `T` in front of it, so a shaft
/// 10 km off stands out of the haze beyond it. From at or above the base, or
/// within the radius, the air is uniform: `(1 − e^(−σt), e^(−σt))`, σ the clear
/// air's and the precipitation's. WGSL twin: `precipitation_haze`
/// (render_clouds.wgsl), the map read by the sampler.
#[must_use]
pub fn precipitation_haze(
    map: &[u8],
    lowest: &CloudLayer,
    offset_m: Vec2,
    camera: Vec3,
    dir: Vec3,
    t_end: f32,
    air: HazeExtinctions,
) -> (f32, f32) {
    let r = LOCAL_WEATHER_RADIUS_M;
    let near = air.rest_per_m + air.local_per_m;
    if t_end <= r || camera.y >= lowest.base_m {
        let t = (-near * t_end.max(0.0)).exp();
        return (1.0 - t, t);
    }
    let mut transmittance = (-near * r).exp();
    let mut light = 1.0 - transmittance;
    // Where the ray rises through the base (never, going level or down).
    let t_base = if dir.y > 0.0 {
        ((lowest.base_m - camera.y) / dir.y).clamp(r, t_end)
    } else {
        t_end
    };
    let n = RAIN_SHAFT_SAMPLES;
    let dt = (t_base - r) / n as f32;
    for k in 0..n {
        let p = camera + dir * (r + (k as f32 + 0.5) * dt);
        let column = cloud_map_uv(p, offset_m);
        let shaft =
            air.shaft_per_m * cloud_column(lowest.coverage, sample_coverage_map(map, column));
        let sigma = air.rest_per_m + shaft;
        let step = (-sigma * dt).exp();
        if sigma > 0.0 {
            light += transmittance * (1.0 - step) * (air.rest_per_m + CLOUD_BASE_SKY_SHARE * shaft)
                / sigma;
        }
        transmittance *= step;
    }
    // Past the base's height (a level ray's far end): the clear air.
    let step = (-air.rest_per_m * (t_end - t_base)).exp();
    light += transmittance * (1.0 - step);
    (light, transmittance * step)
}

#[cfg(test)]
mod tests {
    use super::super::{CloudKind, cloud_noise};
    use super::*;

    #[test]
    fn near_the_camera_it_falls_everywhere_beyond_only_under_the_clouds() {
        let map = &cloud_noise().coverage;
        let camera = Vec3::new(0.0, 2.0, 0.0);
        let level = Vec3::X;
        let layer = |coverage| CloudLayer::typical(CloudKind::Cumulonimbus, coverage);
        // Within the radius, the whole path.
        // The path in falling precipitation, from the transmittance of a thin one.
        let thin = HazeExtinctions {
            rest_per_m: 0.0,
            local_per_m: 1e-6,
            shaft_per_m: 1e-6,
        };
        let path = |l: &CloudLayer, offset, camera, dir, t| {
            let (_, transmittance) = precipitation_haze(map, l, offset, camera, dir, t, thin);
            -f64::from(transmittance).ln() as f32 / 1e-6
        };
        let near = path(&layer(0.3), Vec2::ZERO, camera, level, 2_500.0);
        assert!((near - 2_500.0).abs() < 1.0, "{near}");
        // Beyond it, a full deck rains everywhere (but for its columns' soft edges,
        // 2 % of the map), none rains nowhere.
        let far = 20_000.0;
        let full = path(&layer(1.0), Vec2::ZERO, camera, level, far);
        assert!((full - far).abs() < 0.04 * far, "{full}");
        let none = path(&layer(0.0), Vec2::ZERO, camera, level, far);
        assert!((none - LOCAL_WEATHER_RADIUS_M).abs() < 1.0, "{none}");
        // Half a deck: over many directions about half the far path.
        let mut share = 0.0;
        let n = 200;
        for i in 0..n {
            let a = i as f32 * 0.0314;
            let dir = Vec3::new(a.cos(), 0.0, a.sin());
            let offset = Vec2::new(i as f32 * 977.0, 0.0);
            let p = path(&layer(0.5), offset, camera, dir, far);
            share += (p - LOCAL_WEATHER_RADIUS_M) / (far - LOCAL_WEATHER_RADIUS_M);
        }
        share /= n as f32;
        assert!((share - 0.5).abs() < 0.1, "{share}");
        // Rising through the base 800 m up at 3°, the shafts end where it enters
        // the cloud (15.3 km): nothing beyond counts.
        let up = Vec3::new(3f32.to_radians().cos(), 3f32.to_radians().sin(), 0.0);
        let through = path(&layer(1.0), Vec2::ZERO, camera, up, 40_000.0);
        let to_base = 798.0 / 3f32.to_radians().sin();
        assert!((through - to_base).abs() < 0.04 * to_base, "{through}");
        // From above the base: as before, the whole path.
        let above = Vec3::new(0.0, 900.0, 0.0);
        let all = path(&layer(0.0), Vec2::ZERO, above, level, far);
        assert!((all - far).abs() < 0.01 * far, "{all}");
    }

    #[test]
    fn from_a_dry_place_a_shaft_stands_out_of_the_haze_behind_it() {
        let map = &cloud_noise().coverage;
        let camera = Vec3::new(0.0, 30.0, 0.0);
        let level = Vec3::X;
        let far = 30_000.0;
        // Clear air of 30 km visibility, nothing falling here, a shaft's
        // extinction of heavy rain (a kilometre's visibility) under a full deck.
        let air = HazeExtinctions {
            rest_per_m: 3.912 / 30_000.0,
            local_per_m: 0.0,
            shaft_per_m: 3.912 / 1_000.0,
        };
        let deck = CloudLayer::typical(CloudKind::Cumulonimbus, 1.0);
        let clear = CloudLayer::typical(CloudKind::Cumulonimbus, 0.0);
        let (light_clear, t_clear) =
            precipitation_haze(map, &clear, Vec2::ZERO, camera, level, far, air);
        // Clear air alone: Beer–Lambert, its light the rest.
        let beer = (-air.rest_per_m * far).exp();
        assert!((t_clear - beer).abs() < 1e-5 && (light_clear - (1.0 - beer)).abs() < 1e-5);
        // Under the deck the shafts beyond 3 km hide the far air and, in the
        // clouds' shade, send 0.4 of its light: the horizon is darker (against
        // 1 for the clear air with nothing behind it).
        let (light, t) = precipitation_haze(map, &deck, Vec2::ZERO, camera, level, far, air);
        assert!(t < 1e-6, "{t}");
        let near_air = 1.0 - (-air.rest_per_m * LOCAL_WEATHER_RADIUS_M).exp();
        let expected = near_air + (1.0 - near_air) * CLOUD_BASE_SKY_SHARE;
        assert!(
            (light - expected).abs() < 0.02,
            "{light} against {expected}"
        );
        // Never more light than the air's, whatever falls.
        for shaft_per_m in [0.0, 1e-4, 1e-3, 1e-2] {
            let (light, t) = precipitation_haze(
                map,
                &deck,
                Vec2::ZERO,
                camera,
                level,
                far,
                HazeExtinctions { shaft_per_m, ..air },
            );
            assert!(
                light + t <= 1.0 + 1e-5 && light >= 0.0 && t >= 0.0,
                "{shaft_per_m}"
            );
        }
    }

    #[test]
    fn a_shaft_rains_the_mean_rate_over_its_cloud_s_share_of_the_sky() {
        let weather = Weather {
            kind: crate::PrecipitationKind::Rain,
            intensity_mm_per_h: 2.0,
            ..Weather::default()
        };
        let cell = CloudLayer::typical(CloudKind::Cumulonimbus, 0.4);
        // 0.4 of the sky covered: the columns stand over a little less of the land.
        let share = shaft_share(0.4);
        eprintln!("the columns of a 0.4 layer stand over {share:.3} of the land");
        assert!((0.34..0.4).contains(&share), "{share}");
        let under = Weather {
            intensity_mm_per_h: 2.0 / share,
            ..weather
        };
        assert!((shaft_extinction_per_m(&weather, &cell) - under.extinction_per_m()).abs() < 1e-9);
        assert!((shaft_share(0.0) - MIN_SHAFT_COVERAGE).abs() < 1e-9);
        // A full deck stands over all but the map's clearest texels' soft edges and
        // rains about the rate itself; sand falls from no cloud.
        let deck = CloudLayer {
            coverage: 1.0,
            ..cell
        };
        let whole = shaft_share(1.0);
        assert!((0.97..=1.0).contains(&whole), "{whole}");
        let under_deck = Weather {
            intensity_mm_per_h: 2.0 / whole,
            ..weather
        };
        assert!(
            (shaft_extinction_per_m(&weather, &deck) - under_deck.extinction_per_m()).abs() < 1e-9
        );
        let sand = Weather {
            kind: crate::PrecipitationKind::Sand,
            ..weather
        };
        assert!(shaft_extinction_per_m(&sand, &cell) < 1e-12);
    }
}
