//! The shore's scheme against the benchmarks the shallow-water literature uses
//! (docs/model.md (13.4)): a lake at rest, mass, a dam break over a dry bed
//! (Ritter 1892), a long wave at a wall, a solitary wave's run-up on a plane beach
//! (Synolakis 1987).

use precip_sea::{
    Bathymetry, DRY_DEPTH_M, Edge, GRAVITY_MPS2 as G, IncomingWaves, Shore, ShoreError, ShoreState,
    WaveComponent,
};
use proptest::prelude::*;

const WALLS: [Edge; 4] = [Edge::Wall, Edge::Wall, Edge::Wall, Edge::Wall];

/// A bed of bumps over a 1 m deep basin, some rising above the water as islands.
fn bumpy(nx: usize, ny: usize) -> Bathymetry {
    Bathymetry::from_fn(nx, ny, 1.0, |x, y| {
        -1.0 + 0.8 * (-((x - 12.0).powi(2) + (y - 10.0).powi(2)) / 20.0).exp()
            + 1.5 * (-((x - 28.0).powi(2) + (y - 18.0).powi(2)) / 10.0).exp()
            + 0.2 * (0.4 * x).sin() * (0.3 * y).cos()
    })
}

#[test]
fn a_lake_at_rest_stays_at_rest_over_an_uneven_bed_with_an_island() {
    let bed = bumpy(40, 30);
    let state = ShoreState::at_rest(&bed, 0.0);
    let dry_before: Vec<bool> = state.depth_m.iter().map(|&h| h == 0.0).collect();
    assert!(dry_before.iter().any(|&d| d), "the island stands dry");
    let mut shore = Shore::new(bed, WALLS, state).expect("valid");
    let steps = shore.advance(60.0).expect("advances");
    let s = shore.state();
    let fastest = s
        .discharge_x_m2ps
        .iter()
        .chain(&s.discharge_y_m2ps)
        .fold(0.0f32, |m, q| m.max(q.abs()));
    let mut highest = 0.0f32;
    for j in 0..30 {
        for i in 0..40 {
            let k = j * 40 + i;
            if dry_before[k] {
                assert!(s.depth_m[k] <= DRY_DEPTH_M, "({i}, {j}) got wet");
            } else {
                highest = highest.max(shore.surface_m(i, j).abs());
            }
        }
    }
    println!("{steps} steps: largest discharge {fastest:e} m²/s, surface off by {highest:e} m");
    assert!(fastest < 1.0e-5 && highest < 1.0e-5, "{fastest} {highest}");
}

#[test]
fn the_water_s_volume_is_kept_as_it_sloshes_over_islands() {
    let bed = bumpy(50, 40);
    let mut state = ShoreState::at_rest(&bed, 0.0);
    // A hump of water 0.3 m high: it spreads, climbs the islands, reflects.
    for j in 0..40 {
        for i in 0..50 {
            let k = j * 50 + i;
            let r2 = ((i as f32 - 35.0).powi(2) + (j as f32 - 8.0).powi(2)) / 9.0;
            if state.depth_m[k] > 0.0 {
                state.depth_m[k] += 0.3 * (-r2).exp();
            }
        }
    }
    let mut shore = Shore::new(bed, WALLS, state).expect("valid");
    let before = shore.volume_m3();
    let steps = shore.advance(40.0).expect("advances");
    let after = shore.volume_m3();
    let moved = shore
        .state()
        .discharge_x_m2ps
        .iter()
        .fold(0.0f32, |m, q| m.max(q.abs()));
    println!("{steps} steps: {before} m³ → {after} m³, still moving at {moved} m²/s");
    assert!(moved > 1.0e-3, "the water moves");
    assert!(
        ((after - before) / before).abs() < 1.0e-6,
        "{before} → {after}"
    );
}

/// A channel one cell wide along x.
fn channel(nx: usize, cell_m: f32, bed: impl Fn(f32) -> f32) -> Bathymetry {
    Bathymetry::from_fn(nx, 1, cell_m, |x, _| bed(x))
}

#[test]
fn a_dam_break_over_a_dry_bed_follows_ritter() {
    // 1 m of water behind a dam at 50 m, dry beyond, on a flat bed: after 4 s the
    // depth is Ritter's, h = (2c₀ − ξ)²/(9g) for −c₀ ≤ ξ = (x − 50)/t ≤ 2c₀.
    let (nx, dx, h0, t) = (1_000, 0.1f32, 1.0f32, 4.0f32);
    let bed = channel(nx, dx, |_| 0.0);
    let mut state = ShoreState::at_rest(&bed, 0.0);
    for i in 0..nx / 2 {
        state.depth_m[i] = h0;
    }
    let mut shore = Shore::new(bed, WALLS, state).expect("valid");
    shore.advance(f64::from(t)).expect("advances");
    let c0 = (G * h0).sqrt();
    let ritter = |x: f32| {
        let xi = (x - 50.0) / t;
        if xi < -c0 {
            h0
        } else if xi <= 2.0 * c0 {
            (2.0 * c0 - xi).powi(2) / (9.0 * G)
        } else {
            0.0
        }
    };
    let (mut error, mut total) = (0.0f32, 0.0f32);
    for i in 0..nx {
        let x = (i as f32 + 0.5) * dx;
        let exact = ritter(x);
        // The moving part: from the rarefaction's head to the front.
        if (20.0..90.0).contains(&x) {
            error += (shore.state().depth_m[i] - exact).abs() * dx;
            total += exact * dx;
        }
    }
    let front = (0..nx)
        .rev()
        .find(|&i| shore.state().depth_m[i] > 1.0e-3)
        .map_or(0.0, |i| (i as f32 + 0.5) * dx);
    println!(
        "L1 error {:.4} of the moving water; front at {front:.1} m (Ritter: {:.1} m)",
        error / total,
        50.0 + 2.0 * c0 * t
    );
    assert!(error / total < 0.03, "{}", error / total);
    assert!(
        front > 50.0 + 1.6 * c0 * t && front <= 50.0 + 2.05 * c0 * t,
        "{front}"
    );
}

#[test]
fn a_long_wave_doubles_its_height_against_a_wall() {
    // A right-going long wave 5 mm high on 1 m of water (u = η·√(g/d)) meets the
    // wall at 500 m: there the surface rises to twice its height.
    let (nx, dx, a) = (2_000, 0.25f32, 0.005f32);
    let bed = channel(nx, dx, |_| -1.0);
    let mut state = ShoreState::at_rest(&bed, 0.0);
    for i in 0..nx {
        let x = (i as f32 + 0.5) * dx;
        let eta = a * (-((x - 300.0) / 10.0).powi(2)).exp();
        state.depth_m[i] = 1.0 + eta;
        state.discharge_x_m2ps[i] = (1.0 + eta) * eta * G.sqrt();
    }
    let mut shore = Shore::new(bed, WALLS, state).expect("valid");
    let mut highest = 0.0f32;
    let mut before_wall = 0.0f32;
    while shore.time_s() < 90.0 {
        let dt = shore.stable_dt_s();
        shore.step(dt).expect("steps");
        highest = highest.max(shore.surface_m(nx - 1, 0));
        if shore.time_s() < 40.0 {
            before_wall = before_wall.max(shore.surface_m(nx - 400, 0));
        }
    }
    println!("the wave {before_wall:.5} m high 100 m out; {highest:.5} m at the wall");
    assert!((before_wall / a - 1.0).abs() < 0.03, "{before_wall}");
    assert!((highest / (2.0 * a) - 1.0).abs() < 0.05, "{highest}");
}

/// The run-up of Synolakis's solitary wave (below) over a bed of Manning
/// roughness `manning_n`, m.
fn solitary_run_up(manning_n: f32) -> f32 {
    // Synolakis 1987 (J. Fluid Mech. 185): a solitary wave H/d = 0.0185 on depth d
    // over a 1:19.85 beach runs up R/d = 2.831·√(cot β)·(H/d)^(5/4) = 0.0860 (his
    // run-up law for waves that do not break, which his laboratory runs bear out).
    // The shoreline: where the water is 1 mm deep (THIN·d, 5 % of H); the front is a
    // thin film, so the run-up read depends on it (0.1 mm reads 7 % higher).
    const THIN: f32 = 1.0e-3;
    let (d, ratio, cot) = (1.0f32, 0.0185f32, 19.85f32);
    let (dx, land) = (0.05f32, 5.0f32);
    let nx = (90.0 / dx) as usize;
    let bed = Bathymetry::from_fn(nx, 1, dx, |x, _| (-(x - land) / cot).max(-d));
    let h = ratio * d;
    let gamma = (0.75 * ratio).sqrt();
    let half = (20f32.sqrt()).acosh() / gamma * d;
    let centre = land + cot * d + half;
    let mut state = ShoreState::at_rest(&bed, 0.0);
    for i in 0..nx {
        let x = (i as f32 + 0.5) * dx;
        let eta = h / ((gamma * (x - centre) / d).cosh()).powi(2);
        if state.depth_m[i] > 0.0 {
            state.depth_m[i] += eta;
            state.discharge_x_m2ps[i] = -state.depth_m[i] * eta * (G / d).sqrt();
        }
    }
    let edges = [Edge::Wall, Edge::Open, Edge::Wall, Edge::Wall];
    let mut shore = Shore::new(bed.clone(), edges, state)
        .and_then(|s| s.with_bed_friction(manning_n))
        .expect("valid");
    let mut run_up = f32::MIN;
    while shore.time_s() < 30.0 {
        let dt = shore.stable_dt_s();
        shore.step(dt).expect("steps");
        // The highest ground the water reaches.
        for i in 0..(land / dx) as usize + 40 {
            if shore.state().depth_m[i] > THIN * d {
                run_up = run_up.max(bed.bed_m[i]);
                break;
            }
        }
    }
    run_up
}

#[test]
fn a_solitary_wave_runs_up_a_plane_beach_as_synolakis_found() {
    let (d, ratio, cot) = (1.0f32, 0.0185f32, 19.85f32);
    let run_up = solitary_run_up(0.0);
    let law = 2.831 * cot.sqrt() * ratio.powf(1.25) * d;
    println!(
        "run-up {run_up:.4} m against Synolakis's {law:.4} m ({:+.1} %)",
        100.0 * (run_up / law - 1.0)
    );
    assert!((run_up / law - 1.0).abs() < 0.1, "{run_up} against {law}");
}

#[test]
fn a_rough_bed_holds_the_run_up_back_and_bad_roughness_is_refused() {
    // The laboratory's glass beach (Manning's n about 0.01) against a sand beach
    // (0.025): the film running up slows the more the rougher the bed.
    let (smooth, glass, sand) = (
        solitary_run_up(0.0),
        solitary_run_up(0.01),
        solitary_run_up(0.025),
    );
    println!("run-up {smooth:.4} m frictionless, {glass:.4} m at n = 0.01, {sand:.4} m at 0.025");
    assert!(sand < glass && glass < smooth, "{smooth} {glass} {sand}");
    assert!(
        sand > 0.5 * smooth,
        "friction holds it back, it does not stop it"
    );
    let bed = bumpy(8, 8);
    let rest = ShoreState::at_rest(&bed, 0.0);
    let shore = Shore::new(bed, WALLS, rest).expect("valid");
    for bad in [-0.01, 0.5, f32::NAN] {
        assert!(matches!(
            shore.clone().with_bed_friction(bad),
            Err(ShoreError::Friction(_))
        ));
    }
    // A lake at rest stays at rest over a rough bed too.
    let mut rough = shore.with_bed_friction(0.03).expect("valid");
    rough.advance(10.0).expect("steps");
    let moved = rough
        .state()
        .discharge_x_m2ps
        .iter()
        .chain(&rough.state().discharge_y_m2ps)
        .fold(0.0f32, |m, q| m.max(q.abs()));
    assert!(moved < 1e-5, "{moved}");
}

#[test]
fn waves_come_in_from_the_open_sea_and_bad_input_is_refused() {
    // A 2 s swell 2 cm high enters at the east edge of 1 m of water, crosses the
    // 100 m at √(g·d) and reaches the west wall (40 s), 2 cm high on its way.
    let bed = Bathymetry::from_fn(400, 1, 0.25, |_, _| -1.0);
    let waves = IncomingWaves {
        still_level_m: 0.0,
        components: vec![WaveComponent {
            along_edge_per_m: 0.0,
            amplitude_m: 0.02,
            period_s: 2.0,
            phase_rad: 0.0,
        }],
    };
    let edges = [
        Edge::Wall,
        Edge::Incoming(waves.clone()),
        Edge::Wall,
        Edge::Wall,
    ];
    let state = ShoreState::at_rest(&bed, 0.0);
    let mut shore = Shore::new(bed.clone(), edges.clone(), state.clone()).expect("valid");
    let mut east = 0.0f32;
    while shore.time_s() < 20.0 {
        let dt = shore.stable_dt_s();
        shore.step(dt).expect("steps");
        east = east.max(shore.surface_m(380, 0));
    }
    shore.advance(20.0).expect("advances");
    let west: f32 = (0..20)
        .map(|i| shore.surface_m(i, 0).abs())
        .fold(0.0, f32::max);
    println!("the swell: {east:.4} m high near its edge, {west:.4} m at the far wall");
    assert!(
        (east / 0.02 - 1.0).abs() < 0.1,
        "the swell comes in 2 cm high: {east}"
    );
    assert!(west > 0.01, "the swell reached the far wall: {west}");
    // Refusals name what is wrong.
    let short = ShoreState {
        depth_m: vec![1.0; 3],
        ..state.clone()
    };
    assert!(matches!(
        Shore::new(bed.clone(), edges.clone(), short),
        Err(ShoreError::State(_))
    ));
    let mut flat = bed.clone();
    flat.cell_m = 0.0;
    assert!(matches!(
        Shore::new(flat, edges.clone(), state.clone()),
        Err(ShoreError::Bathymetry(_))
    ));
    let bad = IncomingWaves {
        still_level_m: 0.0,
        components: vec![WaveComponent {
            along_edge_per_m: 0.0,
            amplitude_m: 0.02,
            period_s: 0.0,
            phase_rad: 0.0,
        }],
    };
    assert!(matches!(
        Shore::new(
            bed.clone(),
            [Edge::Incoming(bad), Edge::Wall, Edge::Wall, Edge::Wall],
            state.clone()
        ),
        Err(ShoreError::Waves(_))
    ));
    let mut ok = Shore::new(bed, edges, state).expect("valid");
    let stable = ok.stable_dt_s();
    assert!(matches!(
        ok.step(2.0 * stable),
        Err(ShoreError::Step { .. })
    ));
    assert!(matches!(ok.step(f32::NAN), Err(ShoreError::Step { .. })));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Any still bed and any hump of water: depths stay non-negative, the walls keep
    /// every drop.
    #[test]
    fn depths_stay_positive_and_walls_keep_the_water(
        seed in 0u32..1_000,
        hump in 0.0f32..2.0,
        level in -0.5f32..0.5,
    ) {
        let bed = Bathymetry::from_fn(16, 12, 0.5, |x, y| {
            let s = seed as f32 * 0.37;
            -0.6 + 0.5 * (x * 0.9 + s).sin() * (y * 0.7 - s).cos()
        });
        let mut state = ShoreState::at_rest(&bed, level);
        for (k, h) in state.depth_m.iter_mut().enumerate() {
            let (i, j) = ((k % 16) as f32, (k / 16) as f32);
            *h += hump * (-((i - 5.0).powi(2) + (j - 6.0).powi(2)) / 4.0).exp();
        }
        let mut shore = Shore::new(bed, WALLS, state).expect("valid");
        let before = shore.volume_m3();
        for _ in 0..150 {
            let dt = shore.stable_dt_s();
            shore.step(dt).expect("steps");
        }
        prop_assert!(shore.state().depth_m.iter().all(|&h| h >= 0.0 && h.is_finite()));
        let after = shore.volume_m3();
        prop_assert!(((after - before) / before.max(1e-9)).abs() < 1e-5, "{} → {}", before, after);
    }
}

#[test]
fn an_oblique_wave_s_crests_run_along_the_edge_at_its_speed_there() {
    // A 10 s wave heading 30° from the normal in deep water: along any straight
    // shore its crests are 2π/κ apart, κ = ω²/g·sin 30°, and run along it at ω/κ.
    let (period, angle) = (10.0f32, 30f32.to_radians());
    let kappa = WaveComponent::along_edge_per_m(period, angle);
    let omega = std::f32::consts::TAU / period;
    assert!((kappa - omega * omega / G * 0.5).abs() < 1e-6, "{kappa}");
    let waves = IncomingWaves {
        still_level_m: 0.0,
        components: vec![WaveComponent {
            amplitude_m: 0.5,
            period_s: period,
            phase_rad: 0.3,
            along_edge_per_m: kappa,
        }],
    };
    // A crest at s = 0, t = t0 is at s = (ω/κ)·Δt a time Δt later.
    let t0 = f64::from(-0.3 / omega);
    assert!((waves.elevation_at_m(t0, 0.0) - 0.5).abs() < 1e-5);
    let dt = 2.0f32;
    let s = omega / kappa * dt;
    assert!((waves.elevation_at_m(t0 + f64::from(dt), s) - 0.5).abs() < 1e-4);
    // One wavelength along the edge: the same rise.
    let wavelength = std::f32::consts::TAU / kappa;
    for s in [3.0f32, 40.0] {
        let a = waves.elevation_at_m(1.7, s);
        let b = waves.elevation_at_m(1.7, s + wavelength);
        assert!((a - b).abs() < 1e-4, "{a} {b}");
    }
    assert!((waves.elevation_m(1.7) - waves.elevation_at_m(1.7, 0.0)).abs() < 1e-7);
}

#[test]
fn the_open_sea_s_waves_enter_with_its_energy() {
    use precip_sea::ocean::WindSea;
    // A 12 m/s wind over 30 km: the incoming edge's surface over ten minutes has the
    // spectrum's variance (H_s within 5 %).
    let sea = WindSea::jonswap(12.0, 30_000.0, [1.0, 0.0]);
    let waves = IncomingWaves::from_sea(&sea, 0.0, 64, 5);
    let n = 60_000;
    let variance = (0..n)
        .map(|i| f64::from(waves.elevation_m(f64::from(i) * 0.01)).powi(2))
        .sum::<f64>()
        / f64::from(n);
    let hs = 4.0 * variance.sqrt() as f32;
    let want = sea.significant_height_m(1.0e-4, 50.0);
    println!("incoming H_s {hs:.3} m against the spectrum's {want:.3} m");
    assert!((hs / want - 1.0).abs() < 0.05, "{hs} against {want}");
    assert!(
        waves
            .components
            .iter()
            .all(|c| c.period_s > 1.0 && c.period_s < 20.0)
    );
}

#[test]
fn a_breakwater_reflects_the_wave_and_shelters_the_water_behind_it() {
    // 2 m of water, a long wave 2 cm high running +x; a breakwater (its top 1 m above
    // the water) across the lower two thirds of the channel at x = 80 m, a gap above.
    // Before its face the wave stands twice as high; in its lee far less comes; through
    // the gap the wave passes.
    let (nx, ny, a) = (140usize, 45usize, 0.02f32);
    let bed = Bathymetry::from_fn(nx, ny, 1.0, |x, y| {
        if (80.0..82.0).contains(&x) && y < 30.0 {
            1.0
        } else {
            -2.0
        }
    });
    let mut state = ShoreState::at_rest(&bed, 0.0);
    let c = (G * 2.0).sqrt();
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            if state.depth_m[k] > 0.0 {
                let x = i as f32 + 0.5;
                let eta = a * (-((x - 40.0) / 8.0).powi(2)).exp();
                state.depth_m[k] += eta;
                state.discharge_x_m2ps[k] = state.depth_m[k] * eta * c / 2.0;
            }
        }
    }
    let mut shore = Shore::new(bed, WALLS, state).expect("valid");
    let (mut face, mut lee, mut gap) = (0.0f32, 0.0f32, 0.0f32);
    while shore.time_s() < 25.0 {
        let dt = shore.stable_dt_s();
        shore.step(dt).expect("steps");
        for j in 5..20 {
            face = face.max(shore.surface_m(79, j));
        }
        // Before the reflections from the channel's far walls come back (18 s): the
        // lee behind the breakwater, far from its tip, and the water past the gap.
        if shore.time_s() < 18.0 {
            for j in 1..8 {
                lee = lee.max(shore.surface_m(88, j));
            }
            gap = gap.max(shore.surface_m(95, 38));
        }
    }
    let top = shore.state().depth_m[20 * nx + 80];
    println!("before the face {face:.4} m, in the lee {lee:.4} m, past the gap {gap:.4} m");
    assert!(top <= DRY_DEPTH_M, "the breakwater's top stays dry: {top}");
    assert!((face / (2.0 * a) - 1.0).abs() < 0.1, "{face}");
    assert!(
        lee < 0.6 * a && lee < 0.75 * gap && gap > 0.6 * a,
        "{lee} {gap}"
    );
}
