//! The wind near the ground follows it: air does not blow into a hill, it rises over
//! it. WGSL twin: `terrain_following_wind` in `shaders/ground.wgsl`.
//!
//! The wind volume ([`precip_wind`]) knows no terrain, so a flake drifting at 14 m/s
//! and settling at 1 m/s, a path 4° off the horizontal, would strike every windward
//! face it meets and leave a 70 m shadow behind a 5 m hill. Over real terrain the
//! flow's component into the surface vanishes at the surface (the no-penetration
//! condition) and the disturbance fades over a height of the order of the terrain's
//! own length scale (Jackson & Hunt 1975, *Q. J. R. Meteorol. Soc.* 101, 929–955,
//! for low hills). A flake then settles onto any slope at its terminal speed, the
//! flux `V_t·cos θ` per unit of surface: windward faces get no more than the rest
//! and lee faces are fed, as in the snowfall measured over hills (the wind moves
//! the snow afterwards: precip_cover's drift).
//!
//! Here, two parts:
//!
//! - **Along the ground**: `u' = u − w·(u·n)·n`, with `n` the ground map's normal
//!   from central differences over ±[`TERRAIN_FLOW_SPAN_M`] and
//!   `w = clamp(1 − a/D, 0, 1)` for a height `a` above the ground,
//!   `D =` [`TERRAIN_FLOW_DEPTH_M`]. Lee faces pull the flow down along them.
//! - **Over what is ahead**: the flow rises before an obstacle, not at it (it
//!   separates about one obstacle height up-wind of a wall, Tabler 1991). Along the
//!   wind's horizontal direction the ground is read [`TERRAIN_FLOW_LOOKAHEAD_SAMPLES`]
//!   times up to [`TERRAIN_FLOW_LOOKAHEAD_M`] ahead; where it stands above the
//!   particle the flow climbs at the steepest such angle,
//!   `u'_y = max(u'_y, |u'_h|·min(max_d (H(d) − y)/d, `[`TERRAIN_FLOW_MAX_CLIMB`]`))`
//!   (on an even slope both parts agree: the flow runs along it). A flake
//!   close under a wall's top still strikes the wall (and is deposited at its foot);
//!   the rest clear the roof.
//! - **In the wake** behind it the flow is slowed as the drift's wind is
//!   (precip_cover::drift: Winstral's shelter `S_x`, the steepest sight line up-wind
//!   to ground above the particle by more than the relief, read
//!   [`TERRAIN_FLOW_WAKE_SAMPLES`] times up to [`TERRAIN_FLOW_WAKE_REACH_M`];
//!   `u'_h ×= 1/(1 + (L·S_x)²)`, `L = 12`): flakes settle in the lee of walls and
//!   houses instead of sailing on, as in the recirculation behind a real one.
//!
//! Off the map the ground is level. Above [`flow_ceiling_m`] (the map's highest
//! ground plus [`TERRAIN_FLOW_DEPTH_M`]) none of the three parts changes the wind, so
//! a particle there skips the ground reads (most of the step's cost in a deep
//! emitter): the result is the same bits.

use glam::{Vec2, Vec3};
use precip_cover::drift::{SHELTER_RELIEF_M, WAKE_LENGTH_RATIO};

use crate::particles::ground::GroundMap;

/// Half span of the ground's slope used for the flow, m: wider than a ground texel
/// so that a wall is a steep slope, not a step between two texels.
pub const TERRAIN_FLOW_SPAN_M: f32 = 2.0;
/// Height over which the flow's deflection fades, m: of the order of a scene's
/// hills, walls and roofs.
pub const TERRAIN_FLOW_DEPTH_M: f32 = 10.0;

/// How far ahead the flow reads the ground, m.
pub const TERRAIN_FLOW_LOOKAHEAD_M: f32 = 12.0;
/// Samples over [`TERRAIN_FLOW_LOOKAHEAD_M`].
pub const TERRAIN_FLOW_LOOKAHEAD_SAMPLES: u32 = 8;
/// The steepest climb of the flow before an obstacle, rise over run.
pub const TERRAIN_FLOW_MAX_CLIMB: f32 = 1.0;

/// How far up-wind the flow looks for what shelters it, m.
pub const TERRAIN_FLOW_WAKE_REACH_M: f32 = 36.0;
/// Samples over [`TERRAIN_FLOW_WAKE_REACH_M`].
pub const TERRAIN_FLOW_WAKE_SAMPLES: u32 = 12;

/// The height above which the ground does not turn the wind, m: the map's highest
/// ground plus [`TERRAIN_FLOW_DEPTH_M`] (`StepParams::flow_ceiling_m`).
#[must_use]
pub fn flow_ceiling_m(ground: &GroundMap) -> f32 {
    ground
        .height_m
        .iter()
        .copied()
        .fold(f32::NEG_INFINITY, f32::max)
        + TERRAIN_FLOW_DEPTH_M
}

/// The wind `wind_mps` at `position_m` turned to follow the ground (module docs);
/// `ceiling_m` is [`flow_ceiling_m`] of `ground`.
#[must_use]
pub fn terrain_following_wind(
    wind_mps: Vec3,
    position_m: Vec3,
    ground: &GroundMap,
    ceiling_m: f32,
) -> Vec3 {
    if position_m.y >= ceiling_m {
        return wind_mps;
    }
    let xz = Vec2::new(position_m.x, position_m.z);
    let Some(here_m) = ground.height_at(xz) else {
        return wind_mps;
    };
    let weight = (1.0 - (position_m.y - here_m) / TERRAIN_FLOW_DEPTH_M).clamp(0.0, 1.0);
    let along_ground = if weight > 0.0 {
        let s = TERRAIN_FLOW_SPAN_M;
        let at = |dx: f32, dz: f32| ground.height_at(xz + Vec2::new(dx, dz)).unwrap_or(here_m);
        let normal = Vec3::new(
            (at(-s, 0.0) - at(s, 0.0)) / (2.0 * s),
            1.0,
            (at(0.0, -s) - at(0.0, s)) / (2.0 * s),
        )
        .normalize();
        wind_mps - normal * (weight * wind_mps.dot(normal))
    } else {
        wind_mps
    };
    let horizontal = Vec2::new(along_ground.x, along_ground.z);
    let speed = horizontal.length();
    if speed < 1.0e-3 {
        return along_ground;
    }
    let direction = horizontal / speed;
    let wake = WAKE_LENGTH_RATIO * shelter_up_wind(direction, position_m, ground);
    let slowed = 1.0 / (1.0 + wake * wake);
    let climb = climb_over_what_is_ahead(direction, position_m, ground);
    let rise_mps = if climb > 0.0 {
        along_ground.y.max(speed * slowed * climb)
    } else {
        along_ground.y
    };
    Vec3::new(along_ground.x * slowed, rise_mps, along_ground.z * slowed)
}

/// The steepest sight line from `xz` along the horizontal `direction` to ground
/// standing above `level_m`: `max_d (H(xz + d·direction) − level)/d` over `samples`
/// points up to `reach_m`, 0 when none stands above it.
fn steepest_sight_line(
    ground: &GroundMap,
    xz: Vec2,
    direction: Vec2,
    level_m: f32,
    (reach_m, samples): (f32, u32),
) -> f32 {
    let spacing = reach_m / samples as f32;
    let mut steepest = 0.0f32;
    for k in 1..=samples {
        let d = spacing * k as f32;
        if let Some(h) = ground.height_at(xz + direction * d) {
            steepest = steepest.max((h - level_m) / d);
        }
    }
    steepest
}

/// The slope (rise over run) the flow climbs to clear the ground ahead of
/// `position_m` along the horizontal `direction` (module docs).
fn climb_over_what_is_ahead(direction: Vec2, position_m: Vec3, ground: &GroundMap) -> f32 {
    let xz = Vec2::new(position_m.x, position_m.z);
    let reach = (TERRAIN_FLOW_LOOKAHEAD_M, TERRAIN_FLOW_LOOKAHEAD_SAMPLES);
    steepest_sight_line(ground, xz, direction, position_m.y, reach).min(TERRAIN_FLOW_MAX_CLIMB)
}

/// Winstral's `S_x` for a particle: the steepest sight line up-wind (against the
/// horizontal `direction`) to ground standing above `position_m` by more than the
/// relief that counts (module docs).
fn shelter_up_wind(direction: Vec2, position_m: Vec3, ground: &GroundMap) -> f32 {
    let xz = Vec2::new(position_m.x, position_m.z);
    let reach = (TERRAIN_FLOW_WAKE_REACH_M, TERRAIN_FLOW_WAKE_SAMPLES);
    steepest_sight_line(
        ground,
        xz,
        -direction,
        position_m.y + SHELTER_RELIEF_M,
        reach,
    )
}

#[cfg(test)]
mod tests {
    use glam::UVec2;
    use precip_cover::GridFrame;

    use super::*;

    /// A 40 m square of 0.5 m texels rising at `slope` along +x.
    fn ramp(slope: f32) -> GroundMap {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(40.0), UVec2::splat(80));
        let mut g = GroundMap::flat(frame, 0.0, 1.0);
        for i in 0..frame.texel_count() {
            g.height_m[i] = slope * frame.texel_centre(i).x;
        }
        g
    }

    #[test]
    fn above_the_ceiling_the_skipped_reads_would_change_nothing() {
        let ground = ramp(0.2);
        let ceiling = flow_ceiling_m(&ground);
        assert!((ceiling - (0.2 * 19.75 + TERRAIN_FLOW_DEPTH_M)).abs() < 1e-4);
        let wind = Vec3::new(9.0, -0.5, 3.0);
        for p in [
            Vec3::new(-15.0, ceiling, 2.0),
            Vec3::new(0.0, ceiling + 0.01, -7.0),
            Vec3::new(18.0, ceiling + 30.0, 0.0),
        ] {
            assert_eq!(terrain_following_wind(wind, p, &ground, ceiling), wind);
            // The full computation, no ceiling: the same bits.
            assert_eq!(
                terrain_following_wind(wind, p, &ground, f32::INFINITY),
                wind
            );
        }
    }

    #[test]
    fn at_the_surface_the_wind_runs_along_it_and_aloft_it_is_untouched() {
        let ground = ramp(0.5);
        let wind = Vec3::new(14.0, 0.0, 0.0);
        let normal = Vec3::new(-0.5, 1.0, 0.0).normalize();
        // On the surface of the texel (centre x = 0.25 m, 0.125 m up).
        let at_surface = terrain_following_wind(
            wind,
            Vec3::new(0.25, 0.125, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert!(at_surface.dot(normal).abs() < 1e-3, "{at_surface}");
        assert!(
            at_surface.y > 5.0,
            "rises over the windward face: {at_surface}"
        );
        let aloft = terrain_following_wind(
            wind,
            Vec3::new(0.25, 20.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert_eq!(aloft, wind);
        let half = terrain_following_wind(
            wind,
            Vec3::new(0.25, 0.125 + 5.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert!(
            half.dot(normal) < -1.0 && half.dot(normal) > 0.9 * wind.dot(normal),
            "{half}"
        );
    }

    #[test]
    fn the_flow_climbs_before_a_wall_and_not_over_open_ground() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(40.0), UVec2::splat(80));
        let mut ground = GroundMap::flat(frame, 0.0, 1.0);
        for i in 0..frame.texel_count() {
            if frame.texel_centre(i).x > 5.0 {
                ground.height_m[i] = 4.0;
            }
        }
        let wind = Vec3::new(10.0, 0.0, 0.0);
        // 7 m before a 4 m wall, 1 m up: the steepest sight line to the wall's top
        // rises 3 m over 7.5 m (the first sample on top).
        let far = terrain_following_wind(
            wind,
            Vec3::new(-2.0, 1.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert!((far - Vec3::new(10.0, 4.0, 0.0)).length() < 1e-4, "{far}");
        // Close under the top the climb is capped at 45°: the flake strikes the wall.
        let close = terrain_following_wind(
            wind,
            Vec3::new(4.6, 1.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert!(
            (close.y - close.x).abs() < 1e-4 && close.x < 10.0,
            "{close}"
        );
        // Above the wall's top, or blowing away from it: nothing to climb.
        let over = terrain_following_wind(
            wind,
            Vec3::new(-2.0, 15.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert_eq!(over, wind);
        let away = terrain_following_wind(
            -wind,
            Vec3::new(-2.0, 1.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert!(away.y.abs() < 1e-6, "{away}");
    }

    #[test]
    fn behind_a_wall_the_flow_is_slowed_as_the_drift_is() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(80.0), UVec2::splat(160));
        let mut ground = GroundMap::flat(frame, 0.0, 1.0);
        for i in 0..frame.texel_count() {
            let x = frame.texel_centre(i).x;
            if (-20.0..-19.0).contains(&x) {
                ground.height_m[i] = 4.3;
            }
        }
        let wind = Vec3::new(10.0, 0.0, 0.0);
        // Behind the wall, 1 m up: the 5th sample up-wind (15 m) is on it,
        // S_x = (4.3 − 1 − 0.3)/15.
        let behind = terrain_following_wind(
            wind,
            Vec3::new(-4.75, 1.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        let sx = 3.0 / 15.0;
        let expected = 10.0 / (1.0 + (12.0 * sx) * (12.0 * sx));
        assert!((behind.x - expected).abs() < 1e-3, "{behind} vs {expected}");
        // Above the wall's top: the open wind.
        let above = terrain_following_wind(
            wind,
            Vec3::new(-4.75, 12.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert_eq!(above, wind);
    }

    #[test]
    fn over_level_ground_and_off_the_map_nothing_changes() {
        let ground = ramp(0.0);
        let wind = Vec3::new(3.0, -1.0, 2.0);
        let level = terrain_following_wind(
            wind,
            Vec3::new(0.0, 20.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert_eq!(level, wind);
        // The vertical part is the flake's business (its settling), not the wind's.
        let low = terrain_following_wind(
            wind,
            Vec3::new(0.0, 0.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert!((low - Vec3::new(3.0, 0.0, 2.0)).length() < 1e-5, "{low}");
        let off = terrain_following_wind(
            wind,
            Vec3::new(100.0, 0.0, 0.0),
            &ground,
            flow_ceiling_m(&ground),
        );
        assert_eq!(off, wind);
    }
}
