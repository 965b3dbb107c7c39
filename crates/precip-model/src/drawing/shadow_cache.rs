//! When the sun's depth map is drawn again (docs/architecture.md §2 step 4): the shadow pass
//! re-renders the displaced scene from the sun, which changes only when the sun's
//! projection changes (configuration: sun direction, scene bounds), the displacement
//! is switched, or the snow surface has moved by more than can show in the map: a
//! texel of the map ([`shadow_texel_m`]), and at least [`SHADOW_REFRESH_RISE_M`].
//!
//! The snow's movement is not read back from the GPU: it is bounded from the weather.
//! New snow raises a surface at most at the snowfall rate over the lightest new-snow
//! density, times [`LANDING_LUMP_FACTOR`] for the grain of particle landings and
//! drift; melt lowers it at most at the degree-day rate of the oldest (darkest) snow
//! over the same density. Settling is slower than both and is caught by the
//! [`SHADOW_MAX_AGE_COVER_S`] refresh. At the viewer's default time scale (0.05
//! days a second) and 2 mm/h of snow, the demo's map (2048 texels over about 80 m,
//! 4 cm each) is redrawn about every tenth of a second while it snows, every third
//! frame at 30 fps; in a real-time simulator it is redrawn every 15 minutes, the
//! settling refresh.
//!
//! A frame-rate budget may keep a stale map for `RenderSettings::shadow_refresh_frames`
//! frames: the frame then samples it with the projection it was drawn with
//! ([`ShadowCache::decide`]), so a camera that moves (and with it the map's fit)
//! redraws it every `n`th frame instead of every frame.

use glam::Mat4;
use precip_cover::{CoverParams, new_snow_density, snow_albedo};

use crate::backend::setup::Setup;
use crate::drawing::render::RenderParams;
use crate::weather::Weather;

/// How far the snow surface may move before the map is redrawn, at least, m (the
/// map's texel, [`shadow_texel_m`], where that is coarser).
pub const SHADOW_REFRESH_RISE_M: f32 = 0.01;

/// The side of a texel of a `map_px`² sun map drawn through the orthographic
/// `sun_view_proj`, m: the shorter of the two extents it maps onto the map, over
/// `map_px`. A surface that moves by less moves no shadow edge by more than about a
/// texel.
#[must_use]
pub fn shadow_texel_m(sun_view_proj: Mat4, map_px: u32) -> f32 {
    let row = |r: usize| sun_view_proj.row(r).truncate().length();
    let extent_m = 2.0 / row(0).max(row(1)).max(f32::MIN_POSITIVE);
    extent_m / map_px.max(1) as f32
}

/// Local landings exceed the mean rate by at most this factor (grain, drift).
pub const LANDING_LUMP_FACTOR: f32 = 4.0;

/// The map is redrawn at least this often in cover time, s (settling).
pub const SHADOW_MAX_AGE_COVER_S: f64 = 900.0;

/// Fastest the snow surface can move under `weather`, m per second of cover time.
#[must_use]
pub fn snow_surface_speed_bound_mps(weather: &Weather, cover: &CoverParams) -> f32 {
    let density = new_snow_density(weather.air_temperature_c).max(1.0);
    let mm_per_h_to_mps = 1.0e-3 / 3600.0;
    let rise = weather.channel_rate_mm_per_h(precip_cover::DepositBuffer::SNOW)
        * LANDING_LUMP_FACTOR
        * 1000.0
        / density;
    let excess = (weather.air_temperature_c - cover.melt_threshold_c).max(0.0);
    let melt_per_day = cover.melt_proportionality_mm_per_c_day
        * cover.solar_irradiance_factor.max(0.0)
        * (1.0 - snow_albedo(f32::MAX, cover.albedo_decay_per_day).min(1.0))
        * excess;
    let fall = melt_per_day / 24.0 * 1000.0 / density;
    (rise + fall) * mm_per_h_to_mps
}

/// What the last shadow map was drawn for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Drawn {
    sun_view_proj: Mat4,
    displacement: bool,
    cover_time_s: f64,
    /// Frames since it went stale (0: fresh).
    stale_frames: u32,
}

/// Decides, frame by frame, whether the shadow pass runs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ShadowCache {
    drawn: Option<Drawn>,
    /// The cover grid's moves when the map was last decided
    /// ([`crate::host::CoverWindow::moves`]).
    cover_moves: u32,
}

impl ShadowCache {
    /// Whether this frame must draw the shadow map, for the sun's projection, the
    /// displacement switch, the cover's simulated time (s), the surface's speed
    /// bound ([`snow_surface_speed_bound_mps`]) and the rise that shows in the map
    /// (m), recording the draw when it says yes; a stale map kept for up to
    /// `refresh_frames − 1` frames (not when the displacement switch changed or none
    /// was drawn). Also the sun's projection the map in use was drawn with (the
    /// frame samples it with that).
    pub fn decide(
        &mut self,
        sun_view_proj: Mat4,
        displacement: bool,
        cover_time_s: f64,
        surface_speed_bound_mps: f32,
        visible_rise_m: f32,
        refresh_frames: u32,
    ) -> (bool, Mat4) {
        let fresh = self.drawn.is_some_and(|d| {
            let elapsed = (cover_time_s - d.cover_time_s).abs();
            let moved = if displacement {
                elapsed * f64::from(surface_speed_bound_mps.max(0.0))
            } else {
                0.0
            };
            d.sun_view_proj == sun_view_proj
                && d.displacement == displacement
                && moved < f64::from(visible_rise_m.max(SHADOW_REFRESH_RISE_M))
                && elapsed < SHADOW_MAX_AGE_COVER_S
        });
        if let Some(d) = self
            .drawn
            .as_mut()
            .filter(|d| d.displacement == displacement)
            && !fresh
            && d.stale_frames + 1 < refresh_frames
        {
            d.stale_frames += 1;
            return (false, d.sun_view_proj);
        }
        if !fresh {
            self.drawn = Some(Drawn {
                sun_view_proj,
                displacement,
                cover_time_s,
                stale_frames: 0,
            });
        }
        (!fresh, sun_view_proj)
    }

    /// [`ShadowCache::decide`] for a frame of `setup` under `weather` at simulated
    /// time `time_s` (the cover's time is that times its time scale), drawn with
    /// `params`, keeping a stale map for `setup.render.shadow_refresh_frames`;
    /// `params.sun_view_proj` becomes the projection of the map in use. A cover
    /// grid that moved since the last frame (`cover_moves`, the grid's count,
    /// [`crate::host::CoverWindow::moves`]) redraws the map at once: the texels
    /// that entered were lent the far cover's snow, those that left are drawn from
    /// it, so the displaced surface changed along the grid's edges.
    pub fn for_frame(
        &mut self,
        setup: &Setup,
        weather: &Weather,
        params: &mut RenderParams,
        time_s: f64,
        cover_moves: u32,
    ) -> bool {
        if cover_moves != self.cover_moves {
            self.cover_moves = cover_moves;
            self.invalidate();
        }
        let (draw, sun_view_proj) = self.decide(
            params.sun_view_proj,
            setup.render.snow_displacement,
            time_s * f64::from(setup.cover.time_scale),
            snow_surface_speed_bound_mps(weather, &setup.cover.params),
            shadow_texel_m(params.sun_view_proj, setup.render.shadow_map_px),
            setup.render.shadow_refresh_frames,
        );
        params.sun_view_proj = sun_view_proj;
        draw
    }

    /// Forgets the map (its contents are lost or stale).
    pub fn invalidate(&mut self) {
        self.drawn = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_map_is_redrawn_only_when_the_sun_the_switch_or_the_snow_moved() {
        let sun = Mat4::from_scale(glam::Vec3::splat(0.1));
        let mut cache = ShadowCache::default();
        let speed = 1.0e-5; // 1 cm in 1 000 s
        assert!(cache.decide(sun, true, 0.0, speed, 0.0, 1).0, "first frame");
        assert!(
            !cache.decide(sun, true, 10.0, speed, 0.0, 1).0,
            "nothing changed"
        );
        assert!(
            !cache.decide(sun, true, 899.0, speed, 0.0, 1).0,
            "9 mm at most"
        );
        assert!(cache.decide(sun, true, 1_001.0, speed, 0.0, 1).0, "1 cm");
        assert!(!cache.decide(sun, true, 1_002.0, speed, 0.0, 1).0);
        assert!(
            cache.decide(sun * 2.0, true, 1_002.0, speed, 0.0, 1).0,
            "the sun"
        );
        assert!(
            cache.decide(sun * 2.0, false, 1_002.0, speed, 0.0, 1).0,
            "the switch"
        );
        // Without displacement the snow does not move the map; age still does.
        assert!(!cache.decide(sun * 2.0, false, 1_800.0, 1.0, 0.0, 1).0);
        assert!(
            cache
                .decide(
                    sun * 2.0,
                    false,
                    1_002.0 + SHADOW_MAX_AGE_COVER_S,
                    1.0,
                    0.0,
                    1
                )
                .0
        );
        cache.invalidate();
        assert!(cache.decide(sun * 2.0, false, 1_902.0, 1.0, 0.0, 1).0);
    }

    #[test]
    fn a_rise_under_a_texel_of_the_map_does_not_redraw_it() {
        // 80 m across 2048 texels: 3.9 cm a texel.
        // Looking straight down: x over 80 m, z over 80 m, heights over 200 m.
        let sun = Mat4::from_cols(
            glam::Vec4::new(1.0 / 40.0, 0.0, 0.0, 0.0),
            glam::Vec4::new(0.0, 0.0, 1.0 / 200.0, 0.0),
            glam::Vec4::new(0.0, 1.0 / 40.0, 0.0, 0.0),
            glam::Vec4::new(0.0, -0.5, 0.0, 1.0),
        );
        let texel = shadow_texel_m(sun, 2048);
        assert!((texel - 80.0 / 2048.0).abs() < 1e-5, "{texel} m");
        let mut cache = ShadowCache::default();
        let speed = 1.0e-3; // 1 mm a second
        assert!(cache.decide(sun, true, 0.0, speed, texel, 1).0);
        assert!(!cache.decide(sun, true, 30.0, speed, texel, 1).0, "3 cm");
        assert!(cache.decide(sun, true, 40.0, speed, texel, 1).0, "4 cm");
        // A finer map shows the 1 cm floor.
        let fine = shadow_texel_m(sun, 8192);
        assert!(!cache.decide(sun, true, 49.0, speed, fine, 1).0);
        assert!(cache.decide(sun, true, 51.0, speed, fine, 1).0, "1.1 cm");
    }

    #[test]
    fn snowfall_and_melt_bound_the_surface_speed() {
        let cover = CoverParams::default();
        let cold = Weather {
            intensity_mm_per_h: 2.0,
            air_temperature_c: -5.0,
            ..Weather::default()
        };
        // 2 mm/h at ~100 kg/m³: 2 cm/h of snow, ×4: 8 cm/h.
        let v = snow_surface_speed_bound_mps(&cold, &cover) * 3600.0;
        assert!((0.06..0.1).contains(&v), "{v} m/h");
        let dry = Weather {
            intensity_mm_per_h: 0.0,
            ..cold
        };
        assert!(snow_surface_speed_bound_mps(&dry, &cover).abs() < f32::EPSILON);
        let thaw = Weather {
            intensity_mm_per_h: 0.0,
            air_temperature_c: 8.0,
            ..cold
        };
        assert!(snow_surface_speed_bound_mps(&thaw, &cover) > 0.0);
    }

    /// A move of the cover grid redraws the map on the next frame, however many
    /// frames a stale map may be kept; frames after it keep it again.
    #[test]
    fn a_move_of_the_cover_grid_redraws_the_map_at_once() {
        let mut setup = Setup::over_flat_ground(16.0, 16, 10.0, 100);
        setup.render.shadow_refresh_frames = 8;
        let weather = Weather::default();
        let params = RenderParams {
            sun_view_proj: Mat4::from_scale(glam::Vec3::splat(0.1)),
            ..bytemuck::Zeroable::zeroed()
        };
        let mut cache = ShadowCache::default();
        let frame = |cache: &mut ShadowCache, moves: u32, t: f64| {
            let mut p = params;
            cache.for_frame(&setup, &weather, &mut p, t, moves)
        };
        assert!(frame(&mut cache, 0, 0.0), "the first frame");
        assert!(!frame(&mut cache, 0, 0.01), "nothing changed");
        assert!(frame(&mut cache, 1, 0.02), "the grid moved");
        assert!(!frame(&mut cache, 1, 0.03), "it stays");
        assert!(frame(&mut cache, 3, 0.04), "it moved twice more");
    }

    #[test]
    fn a_stale_map_is_kept_for_the_refresh_frames_and_sampled_as_drawn() {
        let sun = Mat4::from_scale(glam::Vec3::splat(0.1));
        let moved = sun * 2.0;
        let mut cache = ShadowCache::default();
        assert_eq!(
            cache.decide(sun, true, 0.0, 0.0, 0.0, 4),
            (true, sun),
            "first frame"
        );
        // The camera moves every frame: kept three frames, sampled as drawn.
        for k in 1..4 {
            let view = sun * (1.0 + k as f32);
            assert_eq!(
                cache.decide(view, true, 0.0, 0.0, 0.0, 4),
                (false, sun),
                "frame {k}"
            );
        }
        assert_eq!(
            cache.decide(moved, true, 0.0, 0.0, 0.0, 4),
            (true, moved),
            "the fourth"
        );
        assert_eq!(
            cache.decide(moved, true, 0.0, 0.0, 0.0, 4),
            (false, moved),
            "fresh"
        );
        // The displacement switch is never waited for.
        assert_eq!(cache.decide(moved, false, 0.0, 0.0, 0.0, 4), (true, moved));
        // One refresh frame: redrawn at once.
        assert_eq!(cache.decide(sun, false, 0.0, 0.0, 0.0, 1), (true, sun));
    }
}
