//! Snow moved by the wind and by gravity over a cover grid ([`precip_cover::drift`]):
//! conservation, the threshold, the repose angle, and the drifts a fence builds.

use glam::{UVec2, Vec2};
use precip_cover::drift::snow_wind_factor_of;
use precip_cover::{
    CoverAir, CoverFeed, CoverGrid, CoverParams, CoverTexel, DepositBuffer, GridFrame, Surface,
    generate_threshold_masks,
};

/// Cells along the wind and across it.
const ALONG: u32 = 240;
const ACROSS: u32 = 3;
/// Cell size, m.
const CELL_M: f32 = 0.5;
/// The fence's height, m, and its column.
const FENCE_M: f32 = 1.5;
const FENCE_COLUMN: u32 = 80;

/// A strip of level ground along x with a solid fence across it (a column of
/// texels `FENCE_M` high that holds no snow); with `bare_ends`, the columns at
/// both ends hold none either, so no snow crosses the edges (else the field goes
/// on beyond the up-wind edge).
fn fence_strip(with_fence: bool, bare_ends: bool) -> CoverGrid {
    let frame = GridFrame::centred(
        Vec2::ZERO,
        Vec2::new(ALONG as f32 * CELL_M, ACROSS as f32 * CELL_M),
        UVec2::new(ALONG, ACROSS),
    );
    let n = frame.texel_count();
    let column = |i: usize| i as u32 % ALONG;
    let fence = |i: usize| with_fence && column(i) == FENCE_COLUMN;
    let eligibility: Vec<f32> = (0..n)
        .map(|i| {
            let c = column(i);
            if fence(i) || (bare_ends && (c == 0 || c == ALONG - 1)) {
                0.0
            } else {
                1.0
            }
        })
        .collect();
    let heights: Vec<f32> = (0..n)
        .map(|i| if fence(i) { FENCE_M } else { 0.0 })
        .collect();
    let masks = generate_threshold_masks(&frame, 1, 8.0);
    CoverGrid::new(
        frame,
        &eligibility,
        &masks,
        &vec![CoverFeed::WeatherRate; n],
    )
    .and_then(|g| g.with_ground(&heights, &vec![Surface::Soil; n]))
    .expect("valid strip")
}

fn air(snow_mm_per_h: f32, wind_x_mps: f32, air_temperature_c: f32) -> CoverAir {
    CoverAir {
        snow_rate_mm_per_day: snow_mm_per_h * 24.0,
        rain_rate_mm_per_day: 0.0,
        air_temperature_c,
        relative_humidity: 0.8,
        wind_speed_mps: wind_x_mps.abs(),
        wind_mps: [wind_x_mps, 0.0],
    }
}

/// Runs `hours` of cover time in 2-minute steps.
fn run(grid: &mut CoverGrid, air: CoverAir, hours: f32) {
    let params = CoverParams::default();
    let mut deposits = DepositBuffer::new(grid.texels.len());
    let step_days = 2.0 / 1440.0;
    for _ in 0..(hours * 30.0) as u32 {
        grid.step(&mut deposits, air, step_days, &params);
    }
}

/// Snow depth along the middle row, m.
fn profile_m(grid: &CoverGrid) -> Vec<f32> {
    let row = ACROSS / 2;
    (0..ALONG)
        .map(|c| grid.texels[(c + row * ALONG) as usize].depth_mm * 1.0e-3)
        .collect()
}

fn books_close(grid: &CoverGrid) {
    let totals = grid.totals();
    assert!(
        totals.imbalance_kg().abs() <= 1.0e-4 * totals.deposited_kg.max(1.0),
        "books: {totals:?}"
    );
    let worst = grid
        .texels
        .iter()
        .map(|t| t.imbalance_mm().abs())
        .fold(0.0, f64::max);
    assert!(worst < 1.0e-2, "a texel's books are off by {worst} mm");
}

#[test]
fn no_snow_moves_below_the_threshold() {
    // Li & Pomeroy: dry snow at −12 °C moves above a 7.75 m/s wind at 10 m.
    let mut still = fence_strip(true, true);
    run(&mut still, air(2.0, 0.0, -12.0), 3.0);
    let mut breezy = fence_strip(true, true);
    run(&mut breezy, air(2.0, 7.0, -12.0), 3.0);
    let moved = breezy
        .texels
        .iter()
        .map(|t| t.drifted_mm.abs())
        .fold(0.0f32, f32::max);
    assert!(moved < 1.0e-6, "snow moved below the threshold: {moved} mm");
    assert!(breezy.texels.iter().all(|t| t.saltation_kg_per_m_s <= 0.0));
    // The only difference the breeze makes is none.
    for (a, b) in still.texels.iter().zip(&breezy.texels) {
        assert!((a.swe_mm - b.swe_mm).abs() < 1.0e-4);
    }
}

#[test]
fn wind_moves_snow_without_losing_any() {
    let mut g = fence_strip(true, true);
    run(&mut g, air(2.0, 14.0, -12.0), 6.0);
    let totals = g.totals();
    books_close(&g);
    // The moves inside sum to zero: all the net drift crossed the edges (snow
    // passes over the bare ends, where the wind carries it).
    let moved: f64 = g
        .texels
        .iter()
        .map(|t| f64::from(t.drifted_mm.abs()))
        .sum::<f64>()
        * f64::from(g.frame.texel_area_m2());
    assert!(moved > 100.0, "the wind moved little snow: {moved} kg");
    let inside = totals.drifted_kg - totals.edge_drifted_kg;
    assert!(
        inside.abs() <= 1.0e-4 * moved,
        "drift made or lost snow inside the grid: {inside} kg of {moved} kg moved"
    );
    eprintln!(
        "moved {moved:.1} kg of {:.1} kg fallen; over the edges {:.1} kg; inside {inside:.2e} kg; imbalance {:.2e} kg",
        totals.deposited_kg,
        totals.edge_drifted_kg,
        totals.imbalance_kg()
    );
}

/// A level strip of `surface` with no fence and no bare ends: the field goes on
/// beyond the up-wind edge.
fn level_strip(surface: Surface) -> CoverGrid {
    let g = fence_strip(false, false);
    let n = g.texels.len();
    g.with_ground(&vec![0.0; n], &vec![surface; n])
        .expect("valid strip")
}

#[test]
fn turf_holds_its_first_snow_against_the_wind_and_bare_soil_does_not() {
    // A blizzard (14 m/s at −12 °C) for 3 h: 6 mm of water, about 10 cm of fresh
    // snow — below the 15 cm a lawn holds, above the 1 cm of bare soil.
    let mut lawn = level_strip(Surface::Grass);
    run(&mut lawn, air(2.0, 14.0, -12.0), 3.0);
    let mut soil = level_strip(Surface::Soil);
    run(&mut soil, air(2.0, 14.0, -12.0), 3.0);
    books_close(&lawn);
    books_close(&soil);
    let deepest = lawn
        .texels
        .iter()
        .map(|t| t.depth_mm)
        .fold(0.0f32, f32::max);
    assert!(
        deepest > 50.0 && deepest < 150.0,
        "the lawn's snow should lie between 5 and 15 cm: {deepest} mm"
    );
    let moved = |g: &CoverGrid| {
        g.texels
            .iter()
            .map(|t| t.drifted_mm.abs())
            .fold(0.0f32, f32::max)
    };
    assert!(
        moved(&lawn) < 1.0e-6,
        "the wind moved a lawn's held snow: {} mm",
        moved(&lawn)
    );
    assert!(lawn.texels.iter().all(|t| t.saltation_kg_per_m_s <= 0.0));
    // The soil's snow saltates (on level ground as much arrives as leaves).
    assert!(
        soil.texels.iter().all(|t| t.saltation_kg_per_m_s > 0.0),
        "the wind left bare soil's snow"
    );
}

#[test]
fn a_lawn_drifts_once_its_grass_is_buried() {
    // 12 h of the same blizzard: 24 mm of water, over 30 cm of snow; the depth
    // above 15 cm moves.
    let mut lawn = level_strip(Surface::Grass);
    run(&mut lawn, air(2.0, 14.0, -12.0), 12.0);
    books_close(&lawn);
    assert!(
        lawn.texels.iter().any(|t| t.saltation_kg_per_m_s > 0.0),
        "a buried lawn's snow should saltate"
    );
    assert!(lawn.totals().edge_drifted_kg < 0.0, "{:?}", lawn.totals());
    // None of it goes below what the grass holds.
    let shallowest = lawn
        .texels
        .iter()
        .map(|t| t.depth_mm)
        .fold(f32::INFINITY, f32::min);
    assert!(
        shallowest >= 150.0 - 1.0e-3,
        "the wind dug into the lawn's held snow: {shallowest} mm"
    );
}

/// A pile of 3 m of snow in one texel of level ground.
fn pile() -> CoverGrid {
    let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(20.0), UVec2::splat(40));
    let n = frame.texel_count();
    let masks = generate_threshold_masks(&frame, 1, 8.0);
    let mut g = CoverGrid::new(frame, &vec![1.0; n], &masks, &vec![CoverFeed::Particles; n])
        .and_then(|g| g.with_ground(&vec![0.0; n], &vec![Surface::Soil; n]))
        .expect("valid");
    let centre = frame
        .texel_index(Vec2::new(0.1, 0.1))
        .expect("inside the grid");
    g.texels[centre] = CoverTexel {
        swe_mm: 600.0,
        depth_mm: 3000.0,
        peak_swe_mm: 600.0,
        deposited_mm: 600.0,
        ..g.texels[centre]
    };
    g
}

#[test]
fn no_snow_stands_steeper_than_its_repose_angle() {
    let mut g = pile();
    assert!(g.steepest_snow_slope_deg() > 80.0);
    // Still, cold air: only gravity moves the snow.
    run(&mut g, air(0.0, 0.0, -10.0), 1.0);
    let steepest = g.steepest_snow_slope_deg();
    let repose = CoverParams::default().snow_repose_angle_deg;
    assert!(
        steepest <= repose + 0.5,
        "{steepest:.1}° after relaxation, repose {repose}°"
    );
    let totals = g.totals();
    assert!(totals.max_snow_depth_mm < 3000.0 * 0.5, "the pile spread");
    assert!(
        (totals.swe_kg - 600.0 * 0.25).abs() < 1.0e-3 * 150.0,
        "600 mm over 0.25 m² stays 150 kg: {}",
        totals.swe_kg
    );
    assert!(totals.drifted_kg.abs() < 1.0e-3, "{}", totals.drifted_kg);
    books_close(&g);
    eprintln!(
        "pile: steepest {steepest:.2}° (repose {repose}°), deepest {:.0} mm, {:.1} m² under snow",
        totals.max_snow_depth_mm, totals.snow_area_m2
    );
}

#[test]
fn the_wind_slows_behind_a_fence_and_speeds_up_over_a_crest() {
    let g = fence_strip(true, false);
    let row = ACROSS / 2;
    let factor = |column: u32| {
        snow_wind_factor_of(
            &g.texels,
            &g.frame,
            (column + row * ALONG) as usize,
            Vec2::new(12.0, 0.0),
        )
    };
    let behind = |h: f32| factor(FENCE_COLUMN + (h * FENCE_M / CELL_M).round() as u32);
    // Half the wind back at the reattachment, 12 H; most of it at 30 H.
    assert!(behind(2.0) < 0.1, "{}", behind(2.0));
    assert!((0.35..0.65).contains(&behind(12.0)), "{}", behind(12.0));
    assert!(behind(30.0) > 0.8, "{}", behind(30.0));
    // The fence's top is a crest: the wind speeds up there.
    assert!(factor(FENCE_COLUMN) > 1.2, "{}", factor(FENCE_COLUMN));
    // Far upwind, open ground: the weather's wind.
    assert!((factor(20) - 1.0).abs() < 1.0e-3, "{}", factor(20));
}

#[test]
fn a_fence_builds_a_lee_drift_deeper_and_longer_than_the_windward_one() {
    let mut g = fence_strip(true, false);
    let mut open = fence_strip(false, false);
    let weather = air(2.0, 14.0, -12.0);
    run(&mut g, weather, 8.0);
    run(&mut open, weather, 8.0);
    books_close(&g);
    let with = profile_m(&g);
    let without = profile_m(&open);
    let f = FENCE_COLUMN as usize;
    // The drift: depth over the open field's at the same place.
    let excess: Vec<f32> = with.iter().zip(&without).map(|(a, b)| a - b).collect();
    let threshold = 0.05 * FENCE_M;
    let extent = |range: Box<dyn Iterator<Item = usize>>| {
        let mut n = 0usize;
        for c in range {
            if excess[c] > threshold {
                n += 1;
            } else if n > 0 {
                break;
            }
        }
        n as f32 * CELL_M / FENCE_M
    };
    let lee_len = extent(Box::new(f + 1..ALONG as usize - 1));
    let windward_len = extent(Box::new((1..f).rev()));
    let lee_max = excess[f + 1..].iter().copied().fold(0.0, f32::max);
    let windward_max = excess[1..f].iter().copied().fold(0.0, f32::max);
    eprintln!(
        "fence H = {FENCE_M} m, 8 h of 2 mm/h at 14 m/s, −12 °C: lee drift {lee_len:.1} H long, {:.2} H deep; windward {windward_len:.1} H, {:.2} H",
        lee_max / FENCE_M,
        windward_max / FENCE_M
    );
    let shape: Vec<String> = (0..40)
        .map(|k| format!("{:.2}", with[f - 10 + k]))
        .collect();
    eprintln!("depth from 5 m upwind of the fence, m: {}", shape.join(" "));
    assert!(
        lee_max > windward_max,
        "lee {lee_max} m vs windward {windward_max} m"
    );
    assert!(
        lee_len > windward_len,
        "lee {lee_len} H vs windward {windward_len} H"
    );
    assert!(g.steepest_snow_slope_deg() <= CoverParams::default().snow_repose_angle_deg + 0.5);
}
