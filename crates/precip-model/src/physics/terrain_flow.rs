//! The wind near the ground follows it: air does not blow into a hill or a wall, it
//! rises over it and comes down behind it. WGSL twin: `terrain_following_wind` in
//! `shaders/ground.wgsl`.
//!
//! The wind volume ([`precip_wind`]) knows no terrain, so a flake drifting at 14 m/s
//! and settling at 1 m/s, a path 4° off the horizontal, would strike every windward
//! face it meets and leave a 70 m shadow behind a 5 m hill. The flow that replaces
//! it near the ground must do two things: let no air through the ground (the
//! no-penetration condition, Jackson & Hunt 1975, *Q. J. R. Meteorol. Soc.* 101,
//! 929–955) and **lose no air** (no divergence). Flakes settling at a constant speed
//! through a divergence-free flow that runs along the ground keep their number
//! density, so every square metre of ground receives the open field's snowfall — the
//! wind moves the snow afterwards (precip_cover's drift). A flow that lifts flakes
//! over an obstacle and does not bring them down again leaves a shadow behind it; one
//! that slows without the air sinking heaps them at its foot (both measured with
//! the flow this one replaced: docs/model.md (3.7)).
//!
//! The flow here is a channel flow in terrain-following (sigma) coordinates, in the
//! vertical plane of the wind's horizontal direction `ŝ`, between a lower boundary
//! `G(s)` and the flow's ceiling `T` ([`flow_ceiling_m`]: at least as deep above the
//! highest ground as the relief below it), with the stream function
//! `ψ = U·(T − B)·(y − G)/(T − G)` (`B` the ground where the air along `ŝ` comes
//! onto the map, read half a texel inside its up-wind edge: constant along the
//! wind, and over ground at that height the flow is the volume's, as off the map).
//! Its velocity
//!
//! - `u_s = ∂ψ/∂y = U·(T − B)/(T − G)`: faster over what stands high, as the air
//!   squeezed between ground and ceiling must be,
//! - `v = −∂ψ/∂s = u_s·G'·(T − y)/(T − G)`: rising with the boundary at it, fading
//!   to nothing at the ceiling,
//!
//! is divergence-free in every vertical plane along `ŝ` whatever `G` is (the
//! cross-wind component is 0), and `G` and `T` are streamlines. Above the ceiling the
//! wind is the volume's; below it the volume's vertical gusts fade to nothing at `G`
//! (`× (y − G)/(T − G)`).
//!
//! **The boundary `G` is the dividing streamline**, not the ground: the ground where
//! the flow follows it, but the flow separates before a steep obstacle and
//! reattaches behind it (Tabler 1991: about one obstacle height up-wind of a wall and
//! about 12 heights behind it). Along `ŝ` the ground `H` is read at the points of a
//! lattice fixed in the world, [`FLOW_LATTICE_M`] apart,
//! [`TERRAIN_FLOW_LOOKAHEAD_SAMPLES`] ahead and [`TERRAIN_FLOW_WAKE_SAMPLES`] behind
//! the particle, and
//!
//! `G = max(H₀, max_d H(d) − c·d, max_e H(−e) − m_e·e)`, `c =`
//! [`TERRAIN_FLOW_MAX_CLIMB`], `m_e = max(1/L, (H(−e) − H₀)/R)`
//!
//! (`H₀` the line between the lattice points either side; `L = ` precip_cover's
//! `WAKE_LENGTH_RATIO`, 12; `R =` [`TERRAIN_FLOW_WAKE_REACH_M`]: what stands taller
//! than `R/L` comes down within `R`). `G'` is the slope of the term that gives the
//! maximum: the ground's between the lattice points, `c`, or `−m_e` (plus
//! `e·H₀'/R` where `R` sets it: the ground under the particle moves on with it). A
//! lattice fixed in the world makes `G` a field of the position and `G'` its
//! derivative, so the flow keeps its air; samples that moved with the particle made
//! `G` flicker as they crossed a wall's texels, and flakes piled up where it rose.
//! What is thinner than the lattice's spacing may fall between its points: the
//! flow does not see it and blows against it (`crate::particles::step`'s wall rule
//! then applies).
//!
//! **Under the dividing streamline** (in the separation bubble before a wall or in
//! its lee) the air is still: flakes that settle into it come down where they
//! crossed `G`, as they do in the recirculation behind a real wall.
//!
//! Off the map the ground is level and the wind is the volume's. Above
//! [`flow_ceiling_m`] none of this changes the wind, so a particle there skips the
//! ground reads (most of the step's cost in a deep emitter). The reference's
//! numbers: docs/model.md (3.5)–(3.7); the footprint it gives behind a wall, a house,
//! a hill and up a slope: `tests/snowfall_footprint.rs`.

use glam::{Vec2, Vec3};
use precip_cover::drift::WAKE_LENGTH_RATIO;

use crate::particles::ground::GroundMap;

/// Least depth of the flow's channel above the map's highest ground, m: of the
/// order of a scene's hills, walls and roofs ([`flow_ceiling_m`]).
pub const TERRAIN_FLOW_DEPTH_M: f32 = 10.0;

/// Spacing of the lattice along the wind at which the flow reads the ground, m:
/// three 0.5 m texels.
pub const FLOW_LATTICE_M: f32 = 1.5;
/// Lattice points ahead at which the flow reads the ground (to 12 m).
pub const TERRAIN_FLOW_LOOKAHEAD_SAMPLES: u32 = 8;
/// The steepest climb of the dividing streamline before an obstacle, rise over
/// run: it separates about one obstacle height up-wind (Tabler 1991).
pub const TERRAIN_FLOW_MAX_CLIMB: f32 = 1.0;

/// Within this distance behind an obstacle the dividing streamline comes down to
/// the ground, m (what is taller than `R/12` comes down faster than 1 in 12).
pub const TERRAIN_FLOW_WAKE_REACH_M: f32 = 18.0;
/// Lattice points behind at which the flow reads the ground (to
/// [`TERRAIN_FLOW_WAKE_REACH_M`]).
pub const TERRAIN_FLOW_WAKE_SAMPLES: u32 = 12;

/// The height above which the ground does not turn the wind, m
/// (`StepParams::flow_ceiling_m`): the map's highest ground plus
/// [`TERRAIN_FLOW_DEPTH_M`] or plus the map's relief (highest less lowest ground),
/// whichever is more. The channel's air runs `(T − B)/(T − G)` times the volume's
/// speed over the dividing streamline `G` (module docs), so a channel at least as
/// deep above the highest ground as the relief below it never more than doubles the
/// wind: over 300 m ridges a 10 m channel would blow thirty times as fast.
#[must_use]
pub fn flow_ceiling_m(ground: &GroundMap) -> f32 {
    let (lowest_m, highest_m) = ground
        .height_m
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &h| {
            (lo.min(h), hi.max(h))
        });
    highest_m + TERRAIN_FLOW_DEPTH_M.max(highest_m - lowest_m)
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
    let horizontal = Vec2::new(wind_mps.x, wind_mps.z);
    let speed = horizontal.length();
    if speed < 1.0e-3 {
        let fade = ((position_m.y - here_m) / (ceiling_m - here_m)).clamp(0.0, 1.0);
        return Vec3::new(wind_mps.x, wind_mps.y * fade, wind_mps.z);
    }
    let direction = horizontal / speed;
    let (top_m, slope) = dividing_streamline(direction, xz, here_m, ground);
    let base_m = inflow_ground_m(direction, xz, here_m, ground);
    // G and B ≤ the highest ground < T: both depths ≥ 10 m.
    let depth_m = ceiling_m - top_m;
    let along_mps = speed * (ceiling_m - base_m) / depth_m;
    if position_m.y >= top_m {
        let up = (position_m.y - top_m) / depth_m;
        let rise_mps = along_mps * slope * (1.0 - up) + wind_mps.y * up;
        Vec3::new(direction.x * along_mps, rise_mps, direction.y * along_mps)
    } else {
        Vec3::ZERO
    }
}

/// The ground where the air along the wind through `xz` comes onto the map, m
/// (`B` in the module docs): read half a texel inside the map's edge up-wind.
/// Constant along the wind, so the channel's flow keeps its air; over ground at
/// this height it is the volume's wind, as off the map.
fn inflow_ground_m(direction: Vec2, xz: Vec2, here_m: f32, ground: &GroundMap) -> f32 {
    let low = ground.frame.origin_m;
    let high = low + ground.frame.size_m;
    // Distance up-wind to the edge along each axis (infinite along a wind parallel
    // to it).
    let back = |at: f32, low: f32, high: f32, along: f32| {
        if along > 0.0 {
            (at - low) / along
        } else if along < 0.0 {
            (at - high) / along
        } else {
            f32::INFINITY
        }
    };
    let to_edge_m = back(xz.x, low.x, high.x, direction.x)
        .min(back(xz.y, low.y, high.y, direction.y))
        .max(0.0);
    let inside_m = 0.5 * ground.frame.cell_m().min_element();
    ground
        .height_at(xz - direction * (to_edge_m - inside_m).max(0.0))
        .unwrap_or(here_m)
}

/// The dividing streamline's height `G` over `xz` and its slope `G'` along the
/// horizontal `direction` (module docs), from the ground read at points of a
/// lattice fixed in the world along the wind (spacing [`FLOW_LATTICE_M`]), so that
/// `G` is a field of the position and `G'` its derivative; `here_m` is the ground at
/// `xz` (the fallback off the map).
fn dividing_streamline(direction: Vec2, xz: Vec2, here_m: f32, ground: &GroundMap) -> (f32, f32) {
    let s = xz.dot(direction);
    let passed = (s / FLOW_LATTICE_M).floor() * FLOW_LATTICE_M;
    // Distance past the lattice point just passed, [0, spacing).
    let past = s - passed;
    let at = |d: f32| ground.height_at(xz + direction * d).unwrap_or(here_m);
    let behind_m = at(-past);
    let ahead_m = at(FLOW_LATTICE_M - past);
    // The ground between the two lattice points either side, and its slope.
    let ground_slope = (ahead_m - behind_m) / FLOW_LATTICE_M;
    let ground_m = behind_m + past * ground_slope;
    let (mut top_m, mut slope) = (ground_m, ground_slope);
    for k in 1..=TERRAIN_FLOW_LOOKAHEAD_SAMPLES {
        let d = FLOW_LATTICE_M * k as f32 - past;
        let h = if k == 1 { ahead_m } else { at(d) };
        let g = h - TERRAIN_FLOW_MAX_CLIMB * d;
        if g > top_m {
            (top_m, slope) = (g, TERRAIN_FLOW_MAX_CLIMB);
        }
    }
    for k in 0..TERRAIN_FLOW_WAKE_SAMPLES {
        let e = FLOW_LATTICE_M * k as f32 + past;
        let h = if k == 0 { behind_m } else { at(-e) };
        let within_reach = (h - ground_m) / TERRAIN_FLOW_WAKE_REACH_M;
        let (descent, descent_slope) = if within_reach > 1.0 / WAKE_LENGTH_RATIO {
            // m = (H(−e) − G₀)/R: as the particle moves on, the ground under it
            // moves too.
            let moving = e * ground_slope / TERRAIN_FLOW_WAKE_REACH_M;
            (within_reach, within_reach - moving)
        } else {
            (1.0 / WAKE_LENGTH_RATIO, 1.0 / WAKE_LENGTH_RATIO)
        };
        let g = h - descent * e;
        if g > top_m {
            (top_m, slope) = (g, -descent_slope);
        }
    }
    (top_m, slope)
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
    fn above_the_ceiling_the_wind_is_the_volumes_and_below_it_no_air_crosses_it() {
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
            // Just under it the channel's rise has faded: the air crosses the
            // ceiling as the volume's does (only its gusts), so it keeps its snow.
            let under = Vec3::new(p.x, ceiling - 1.0e-3, p.z);
            let flow = terrain_following_wind(wind, under, &ground, ceiling);
            assert!((flow.y - wind.y).abs() < 1.0e-3, "{flow}");
        }
    }

    #[test]
    fn over_deep_terrain_the_channel_never_more_than_doubles_the_wind() {
        // A 300 m ridge rising from a valley floor at the map's up-wind edge.
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(400.0), UVec2::splat(200));
        let mut ground = GroundMap::flat(frame, 0.0, 1.0);
        for i in 0..frame.texel_count() {
            let x = frame.texel_centre(i).x;
            ground.height_m[i] = 300.0 * (-(x / 60.0) * (x / 60.0)).exp();
        }
        let ceiling = flow_ceiling_m(&ground);
        assert!(
            (ceiling - (ground.height_m.iter().fold(0.0f32, |a, &h| a.max(h)) * 2.0)).abs() < 1.0
        );
        let wind = Vec3::new(14.0, 0.0, 0.0);
        let mut fastest = 0.0f32;
        for x in (-190..190).step_by(5) {
            for y in (0..600).step_by(10) {
                let flow = terrain_following_wind(
                    wind,
                    Vec3::new(x as f32, y as f32, 0.0),
                    &ground,
                    ceiling,
                );
                fastest = fastest.max(flow.x);
            }
        }
        assert!(
            fastest > 14.0 * 1.5 && fastest <= 14.0 * 2.0 + 1e-3,
            "{fastest}"
        );
    }

    #[test]
    fn along_a_slope_the_wind_runs_along_it_and_aloft_it_is_untouched() {
        let ground = ramp(0.5);
        let ceiling = flow_ceiling_m(&ground);
        let wind = Vec3::new(14.0, 0.0, 0.0);
        // On the ground between two lattice points (x = 0 and 1.5 m, their texels'
        // centres 0.125 and 0.875 m high): the ground's height there is the line
        // between them, 0.5 m at x = 0.75 m.
        let on = terrain_following_wind(wind, Vec3::new(0.75, 0.5, 0.0), &ground, ceiling);
        assert!((on.y / on.x - 0.5).abs() < 1e-4, "{on}");
        // The air coming onto the map at its up-wind edge (x = -20 m, 9.9 m below)
        // is squeezed as the ground rises: u = U·(T − B)/(T − G).
        let base = 0.5 * -19.75;
        let along = 14.0 * (ceiling - base) / (ceiling - 0.5);
        assert!((on.x - along).abs() < 1e-3, "{on} vs {along}");
        // Half-way up the channel the rise is half the ground's.
        let half_m = 0.5 + 0.5 * (ceiling - 0.5);
        let half = terrain_following_wind(wind, Vec3::new(0.75, half_m, 0.0), &ground, ceiling);
        assert!((half.y / half.x - 0.25).abs() < 1e-4, "{half}");
        let aloft = terrain_following_wind(wind, Vec3::new(0.75, ceiling, 0.0), &ground, ceiling);
        assert_eq!(aloft, wind);
    }

    /// An 80 m square of 0.5 m texels, `height` where `x` is in `span`.
    fn block(span: std::ops::Range<f32>, height_m: f32) -> GroundMap {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(80.0), UVec2::splat(160));
        let mut ground = GroundMap::flat(frame, 0.0, 1.0);
        for i in 0..frame.texel_count() {
            if span.contains(&frame.texel_centre(i).x) {
                ground.height_m[i] = height_m;
            }
        }
        ground
    }

    #[test]
    fn the_flow_separates_before_a_wall_and_still_air_lies_under_it() {
        let ground = block(5.0..40.0, 4.0);
        let ceiling = flow_ceiling_m(&ground);
        let wind = Vec3::new(10.0, 0.0, 0.0);
        // The first lattice point on the wall is x = 6 m: the dividing streamline
        // rises at 45° from x = 2 m to it, G(3.5) = 1.5 m.
        let over = terrain_following_wind(wind, Vec3::new(3.5, 2.0, 0.0), &ground, ceiling);
        let along = 10.0 * ceiling / (ceiling - 1.5);
        let up = 0.5 / (ceiling - 1.5);
        assert!(
            (over - Vec3::new(along, along * (1.0 - up), 0.0)).length() < 1e-3,
            "{over}"
        );
        // Under it the air is still: flakes settle there.
        let under = terrain_following_wind(wind, Vec3::new(3.5, 1.0, 0.0), &ground, ceiling);
        assert_eq!(under, Vec3::ZERO);
        // Further up-wind, the ground: no climb.
        let before = terrain_following_wind(wind, Vec3::new(-2.0, 1.0, 0.0), &ground, ceiling);
        assert!((before - wind).length() < 1e-4, "{before}");
    }

    #[test]
    fn behind_a_wall_the_flow_comes_down_within_its_reach() {
        let ground = block(-20.0..-19.0, 4.3);
        let ceiling = flow_ceiling_m(&ground);
        let wind = Vec3::new(10.0, 0.0, 0.0);
        // 9.5 m behind the lattice point on the wall (x = -19.5 m), the dividing
        // streamline has come down 4.3·9.5/18 m: G = 2.03 m.
        let g = 4.3 - 4.3 / 18.0 * 9.5;
        let under = terrain_following_wind(wind, Vec3::new(-10.0, g - 0.1, 0.0), &ground, ceiling);
        assert_eq!(under, Vec3::ZERO);
        let over = terrain_following_wind(wind, Vec3::new(-10.0, g + 1.0, 0.0), &ground, ceiling);
        let along = 10.0 * ceiling / (ceiling - g);
        let up = 1.0 / (ceiling - g);
        let rise = -along * 4.3 / 18.0 * (1.0 - up);
        assert!(
            (over - Vec3::new(along, rise, 0.0)).length() < 1e-3,
            "{over} vs {along}, {rise}"
        );
        // Beyond the reach the ground again: the open wind.
        let beyond = terrain_following_wind(wind, Vec3::new(0.0, 1.0, 0.0), &ground, ceiling);
        assert!((beyond - wind).length() < 1e-4, "{beyond}");
    }

    proptest::proptest! {
        #[test]
        fn the_flow_is_finite_and_never_turns_against_the_wind(
            x in -45.0f32..45.0, y in -2.0f32..20.0, z in -45.0f32..45.0,
            angle in 0.0f32..std::f32::consts::TAU, speed in 0.0f32..30.0, gust in -2.0f32..2.0,
        ) {
            let ground = block(-10.0..-4.0, 7.0);
            let ceiling = flow_ceiling_m(&ground);
            let wind = Vec3::new(speed * angle.cos(), gust, speed * angle.sin());
            let flow = terrain_following_wind(wind, Vec3::new(x, y, z), &ground, ceiling);
            proptest::prop_assert!(flow.is_finite(), "{flow}");
            let along = Vec2::new(flow.x, flow.z).dot(Vec2::new(wind.x, wind.z));
            proptest::prop_assert!(along >= 0.0, "{flow} against {wind}");
        }
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
