//! Where falling snow lands behind what the wind blows over: the footprint of the
//! flow that follows the ground (precip_model::physics::terrain_flow).
//!
//! Flakes settling at 1 m/s are released evenly along the wind above the flow's
//! ceiling and carried by `terrain_following_wind` (inertia-free, the limit a 1 m/s
//! flake's 0.1 s response reaches) until they meet the ground map. Over open ground
//! every metre receives the same number; an obstacle may take some on its faces and
//! at its feet, but beyond the wake the open field's rate must come back.

use glam::{UVec2, Vec2, Vec3};
use precip_model::GroundMap;
use precip_model::cover::GridFrame;
use precip_model::physics::terrain_flow::{flow_ceiling_m, terrain_following_wind};

const SETTLING_MPS: f32 = 1.0;

/// A strip 300 m along the wind (+x), 8 m across, 0.5 m texels, with `height(x)`.
fn strip(height: impl Fn(f32) -> f32) -> GroundMap {
    let frame = GridFrame::centred(Vec2::ZERO, Vec2::new(300.0, 8.0), UVec2::new(600, 16));
    let mut g = GroundMap::flat(frame, 0.0, 1.0);
    for i in 0..frame.texel_count() {
        g.height_m[i] = height(frame.texel_centre(i).x);
    }
    g
}

/// Landed flakes per metre in 10 m bins from x = -150 m, relative to the open
/// field's rate, flakes released every `spacing_m` metres.
fn footprint(ground: &GroundMap, wind_mps: f32, dt: f32) -> Vec<f32> {
    let bin_m = 10.0;
    let ceiling = flow_ceiling_m(ground);
    let spacing_m = 0.1;
    let travel = wind_mps * ceiling / SETTLING_MPS;
    let bins = (300.0 / bin_m) as usize;
    let mut landed = vec![0u32; bins];
    let mut x0 = -150.0 - travel - 20.0;
    while x0 < 150.0 {
        let mut p = Vec3::new(x0, ceiling + 0.01, 0.0);
        let mut v = Vec3::new(wind_mps, -SETTLING_MPS, 0.0);
        for _ in 0..100_000 {
            // The wind at the step's predicted midpoint, or at the flake where that
            // is under the ground, as the particles' step reads it
            // (precip_model::particles::step).
            let mut probe = p + v * (0.5 * dt);
            if ground
                .height_at(Vec2::new(probe.x, probe.z))
                .is_some_and(|h| probe.y < h)
            {
                probe = p;
            }
            let w = terrain_following_wind(Vec3::new(wind_mps, 0.0, 0.0), probe, ground, ceiling);
            v = w - Vec3::new(0.0, SETTLING_MPS, 0.0);
            p += v * dt;
            let h = ground.height_at(Vec2::new(p.x, p.z)).unwrap_or(0.0);
            if p.y <= h {
                let b = ((p.x + 150.0) / bin_m).floor();
                if (0.0..bins as f32).contains(&b) {
                    landed[b as usize] += 1;
                }
                break;
            }
        }
        x0 += spacing_m;
    }
    let open = bin_m / spacing_m;
    landed.iter().map(|&n| n as f32 / open).collect()
}

fn show(name: &str, f: &[f32]) {
    let s: Vec<String> = f.iter().map(|r| format!("{r:.2}")).collect();
    println!("{name}, 10 m bins from -150 m: {}", s.join(" "));
}

/// Bin `i`'s x range, m.
fn bin_x(i: usize) -> (f32, f32) {
    let from = -150.0 + 10.0 * i as f32;
    (from, from + 10.0)
}

/// Every bin up-wind of `from_m` and down-wind of `to_m` within `tolerance` of the
/// open field's rate.
fn assert_open_field_outside(name: &str, f: &[f32], (from_m, to_m): (f32, f32), tolerance: f32) {
    show(name, f);
    for (i, &r) in f.iter().enumerate() {
        let (low, high) = bin_x(i);
        if high <= from_m || low >= to_m {
            assert!(
                (r - 1.0).abs() <= tolerance,
                "{name}: {r:.2} of the open field's snow lands in {low}..{high} m"
            );
        }
    }
}

/// The particles' steps: 1/50 s, and the longest a backend takes (1/20 s,
/// `precip_model::physics::drag::MAX_SUBSTEP_S`), which a slow frame gives.
const STEPS_S: [f32; 2] = [0.02, 0.05];

#[test]
fn over_open_ground_every_metre_gets_the_same_snow() {
    for dt in STEPS_S {
        let f = footprint(&strip(|_| 0.0), 14.0, dt);
        assert_open_field_outside("open", &f, (0.0, 0.0), 0.05);
        // Away from the map's edges (where the flow meets the volume's wind), to 1 %.
        let inside = &f[1..f.len() - 1];
        assert!(inside.iter().all(|r| (r - 1.0).abs() <= 0.01), "{f:?}");
    }
}

#[test]
fn behind_a_wall_the_open_fields_snowfall_comes_back_within_10_m() {
    // 5 m high, 1 m thick, across the wind.
    let wall = strip(|x| if (0.0..1.0).contains(&x) { 5.0 } else { 0.0 });
    for dt in STEPS_S {
        let f = footprint(&wall, 14.0, dt);
        assert_open_field_outside("wall", &f, (-10.0, 10.0), 0.1);
        // The 10 m holding the wall and its lee: no shadow.
        assert!(f[15] > 0.75, "{}", f[15]);
    }
}

#[test]
fn a_house_a_gabled_roof_and_a_hill_leave_no_shadow_down_wind() {
    let house = strip(|x| if (0.0..10.0).contains(&x) { 6.0 } else { 0.0 });
    // Eaves at 4 m, the ridge at 7 m, 10 m deep.
    let gable = strip(|x| {
        if (0.0..10.0).contains(&x) {
            4.0 + 3.0 * (1.0 - (x - 5.0).abs() / 5.0)
        } else {
            0.0
        }
    });
    // A hill 8 m high, 20 m wide (Gaussian).
    let hill = strip(|x| 8.0 * (-(x / 20.0) * (x / 20.0)).exp());
    for dt in STEPS_S {
        let f = footprint(&house, 14.0, dt);
        assert_open_field_outside("house", &f, (-10.0, 20.0), 0.1);
        assert!(f[14..17].iter().all(|&r| r > 0.7), "{f:?}");
        let f = footprint(&gable, 14.0, dt);
        assert_open_field_outside("gabled roof", &f, (0.0, 20.0), 0.1);
        assert!(f[15..17].iter().all(|&r| r > 0.7), "{f:?}");
        let f = footprint(&hill, 14.0, dt);
        assert_open_field_outside("hill", &f, (0.0, 0.0), 0.15);
    }
}

#[test]
fn a_slope_up_to_a_plateau_gets_the_open_fields_snow() {
    // A 1 in 5 slope from x = 0 up to a 10 m plateau.
    let ramp = strip(|x| (0.2 * x).clamp(0.0, 10.0));
    for dt in STEPS_S {
        let f = footprint(&ramp, 14.0, dt);
        assert_open_field_outside("ramp", &f, (0.0, 0.0), 0.08);
    }
}

#[test]
fn in_a_light_wind_too() {
    let house = strip(|x| if (0.0..10.0).contains(&x) { 6.0 } else { 0.0 });
    for dt in STEPS_S {
        let f = footprint(&house, 3.0, dt);
        assert_open_field_outside("house, 3 m/s", &f, (0.0, 0.0), 0.12);
    }
}
