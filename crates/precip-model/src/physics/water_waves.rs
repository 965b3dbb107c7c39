//! Rain on water bodies: a height field over the scene's water excited by every drop
//! that lands on it and propagated by the damped wave equation (seed 004's water
//! surface, its near-shore part). WGSL twins in `shaders/water_waves.wgsl`.
//!
//! ## The model
//!
//! - **Grid** — [`wave_frame`]: square cells of [`WAVE_CELL_M`] over the box of the
//!   cover texels that are water, at most [`MAX_WAVE_CELLS_PER_SIDE`] a side (a larger
//!   body is covered round its centre; beyond the grid its surface shows the
//!   procedural rings of [`crate::drawing::water_look`]).
//! - **Excitation** — a drop of diameter `D` striking at `v` opens a crater of
//!   diameter `D·We^(1/4)` (`We = ρDv²/σ`; Engel 1966, Pumphrey & Elmore 1990): the
//!   hemisphere's volume is taken from the cell it strikes ([`crater_volume_m3`]),
//!   summed in fixed point ([`WAVE_UNITS_PER_M`]), so the order of the strikes does
//!   not matter.
//! - **Propagation** — `∂²h/∂t² = c²∇²h − γ·∂h/∂t`, explicit leapfrog on the
//!   five-point Laplacian ([`wave_next_height`]), `c` the capillary–gravity phase speed of
//!   the shortest wave the grid carries well (four cells: 0.5 m/s at 4 cm cells;
//!   [`crate::drawing::water_look::ripple_phase_speed_mps`]), `γ` = 1/s. Stable while
//!   `c·dt/Δx ≤ 1/√2` (0.63 at the longest sub-step, 0.05 s). Its dispersion: a
//!   wave of wavenumber `k` along an axis travels at
//!   `ω/k = (2/(k·dt))·asin((c·dt/Δx)·sin(k·Δx/2))`, `c` for long waves and slower
//!   toward the grid's scale ([`discrete_phase_speed_mps`]); the test measures it.
//! - The edge of the grid and the shore reflect nothing back: heights beyond them
//!   read as zero (an absorbing edge in the long run, with the damping).

use glam::{UVec2, Vec2};
use precip_cover::{CoverGrid, GridFrame, Surface};

/// Side of a wave cell, m.
pub const WAVE_CELL_M: f32 = 0.04;

/// The most cells along a side of the wave grid.
pub const MAX_WAVE_CELLS_PER_SIDE: u32 = 512;

/// Fixed-point units per metre of height (0.1 µm).
pub const WAVE_UNITS_PER_M: f32 = 1.0e7;

/// Damping of the waves, per s.
pub const WAVE_DAMPING_PER_S: f32 = 1.0;

/// Words per cell in the wave buffer (`i32`): height now, height a sub-step before,
/// the strikes being summed (then the next height), and 1 where the cell is water.
pub const WAVE_WORDS_PER_CELL: u32 = 4;

/// The phase speed the grid propagates at, m/s (the capillary–gravity speed of a
/// wave four cells long).
#[must_use]
pub fn wave_speed_mps() -> f32 {
    crate::drawing::water_look::ripple_phase_speed_mps(4.0 * WAVE_CELL_M)
}

/// The wave grid over the water texels of `cover` (a single cell when there is no
/// water: nothing strikes it and nothing reads it).
#[must_use]
pub fn wave_frame(cover: &CoverGrid) -> GridFrame {
    wave_frame_over(
        &cover.frame,
        cover
            .texels
            .iter()
            .enumerate()
            .filter(|(_, t)| t.surface == Surface::Water as u32)
            .map(|(i, _)| i),
    )
}

/// The wave grid over the texels `water` of `frame`.
#[must_use]
pub fn wave_frame_over(frame: &GridFrame, water: impl IntoIterator<Item = usize>) -> GridFrame {
    let centres: Vec<Vec2> = water.into_iter().map(|i| frame.texel_centre(i)).collect();
    if centres.is_empty() {
        return GridFrame::centred(Vec2::ZERO, Vec2::splat(WAVE_CELL_M), UVec2::ONE);
    }
    let half_texel = 0.5 * frame.cell_m();
    let lo = centres
        .iter()
        .fold(Vec2::splat(f32::INFINITY), |a, &c| a.min(c))
        - half_texel;
    let hi = centres
        .iter()
        .fold(Vec2::splat(f32::NEG_INFINITY), |a, &c| a.max(c))
        + half_texel;
    let cells = ((hi - lo) / WAVE_CELL_M)
        .ceil()
        .as_uvec2()
        .clamp(UVec2::ONE, UVec2::splat(MAX_WAVE_CELLS_PER_SIDE));
    GridFrame::centred(0.5 * (lo + hi), cells.as_vec2() * WAVE_CELL_M, cells)
}

/// The wave buffer's first contents for `frame` over `ground`: every cell at rest,
/// marked water (1 in its fourth word) where the top-most surface at its centre is.
#[must_use]
pub fn initial_waves(frame: &GridFrame, ground: &crate::GroundMap) -> Vec<i32> {
    (0..frame.texel_count())
        .flat_map(|i| {
            let water = ground.surface_at(frame.texel_centre(i)) == Surface::Water;
            [0, 0, 0, i32::from(water)]
        })
        .collect()
}

/// Volume of the crater a drop of `diameter_m` opens striking water at `speed_mps`,
/// m³: a hemisphere of diameter `D·We^(1/4)`.
#[must_use]
pub fn crater_volume_m3(diameter_m: f32, speed_mps: f32) -> f32 {
    let weber = crate::physics::splash::weber_number(diameter_m, speed_mps);
    let crater = diameter_m.max(0.0) * weber.sqrt().sqrt();
    std::f32::consts::PI / 12.0 * crater * crater * crater
}

/// The fixed-point units a strike takes from its cell's height (WGSL twin:
/// `strike_units`).
#[must_use]
pub fn strike_units(diameter_m: f32, speed_mps: f32, cell_area_m2: f32) -> i32 {
    let depth_m = crater_volume_m3(diameter_m, speed_mps) / cell_area_m2.max(1.0e-6);
    -((depth_m * WAVE_UNITS_PER_M).min(1.0e9) as i32)
}

/// One leapfrog step of the damped wave equation at one cell, heights in m: `now`,
/// `before` (a step earlier), the four neighbours' `now` (beyond the grid: 0), over
/// `dt_s` (WGSL twin: `wave_next_height`; the kernels `wave_step` and `wave_shift` apply
/// it to every cell).
#[must_use]
pub fn wave_next_height(now: f32, before: f32, neighbours: [f32; 4], dt_s: f32) -> f32 {
    let c = wave_speed_mps();
    let courant2 = (c * dt_s / WAVE_CELL_M).powi(2);
    let laplacian = neighbours.iter().sum::<f32>() - 4.0 * now;
    let g = 0.5 * WAVE_DAMPING_PER_S * dt_s;
    ((2.0 * now - (1.0 - g) * before) + courant2 * laplacian) / (1.0 + g)
}

/// The phase speed of the discrete scheme for a wave of `wavenumber_per_m` along an
/// axis over steps of `dt_s`, m/s (undamped).
#[must_use]
pub fn discrete_phase_speed_mps(wavenumber_per_m: f32, dt_s: f32) -> f32 {
    let r = wave_speed_mps() * dt_s / WAVE_CELL_M;
    let s = (r * (0.5 * wavenumber_per_m * WAVE_CELL_M).sin()).clamp(-1.0, 1.0);
    2.0 * s.asin() / (wavenumber_per_m * dt_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square grid of `n` cells stepped `steps` times from one strike at its centre;
    /// returns the heights.
    fn ring(n: usize, steps: usize, dt: f32) -> Vec<f32> {
        let mut now = vec![0.0f32; n * n];
        let mut before = vec![0.0f32; n * n];
        now[n / 2 + n * (n / 2)] = -1.0e-3;
        for _ in 0..steps {
            let mut next = vec![0.0f32; n * n];
            for j in 0..n {
                for i in 0..n {
                    let at = |a: i64, b: i64| {
                        if a < 0 || b < 0 || a >= n as i64 || b >= n as i64 {
                            0.0
                        } else {
                            now[a as usize + n * b as usize]
                        }
                    };
                    let (a, b) = (i as i64, j as i64);
                    next[i + n * j] = wave_next_height(
                        now[i + n * j],
                        before[i + n * j],
                        [at(a - 1, b), at(a + 1, b), at(a, b - 1), at(a, b + 1)],
                        dt,
                    );
                }
            }
            before = now;
            now = next;
        }
        now
    }

    #[test]
    fn a_ring_travels_at_the_schemes_stated_speed() {
        let (n, dt) = (161usize, 0.02f32);
        // The radius of the largest |h| along +x, at two times.
        let front = |steps: usize| {
            let h = ring(n, steps, dt);
            let row = &h[n * (n / 2) + n / 2..n * (n / 2 + 1)];
            let (i, _) = row
                .iter()
                .enumerate()
                .skip(3)
                .fold(
                    (0, 0.0f32),
                    |a, (i, v)| if v.abs() > a.1 { (i, v.abs()) } else { a },
                );
            i as f32 * WAVE_CELL_M
        };
        let measured = (front(90) - front(40)) / (50.0 * dt);
        // The front is carried by the waves the grid resolves: between the long-wave
        // speed and that of a wave eight cells long.
        let c = wave_speed_mps();
        let k8 = std::f32::consts::TAU / (8.0 * WAVE_CELL_M);
        let slowest = discrete_phase_speed_mps(k8, dt);
        println!(
            "ring front {measured:.3} m/s; scheme: {c:.3} long waves, {slowest:.3} at 8 cells"
        );
        assert!((0.49..0.52).contains(&c), "c = {c}");
        assert!(
            measured <= c * 1.05 && measured >= slowest * 0.9,
            "front {measured} m/s outside [{slowest}, {c}]"
        );
    }

    #[test]
    fn the_scheme_is_stable_at_the_longest_sub_step_and_damps() {
        let h = ring(41, 400, crate::physics::drag::MAX_SUBSTEP_S);
        let peak = h.iter().fold(0.0f32, |a, v| a.max(v.abs()));
        assert!(peak.is_finite() && peak < 1.0e-4, "decays: {peak}");
        assert!(
            wave_speed_mps() * crate::physics::drag::MAX_SUBSTEP_S / WAVE_CELL_M
                < std::f32::consts::FRAC_1_SQRT_2
        );
    }

    #[test]
    fn craters_grow_with_the_drop_and_its_speed() {
        let small = crater_volume_m3(1.0e-3, 4.0);
        let large = crater_volume_m3(3.0e-3, 8.0);
        assert!(large > 20.0 * small);
        // A 2 mm drop at 6.5 m/s: a crater about 12 mm across.
        let v = crater_volume_m3(2.0e-3, 6.5);
        let d = (v * 12.0 / std::f32::consts::PI).cbrt();
        assert!((d - 0.0116).abs() < 0.001, "{d}");
        assert!(strike_units(2.0e-3, 6.5, WAVE_CELL_M * WAVE_CELL_M) < 0);
    }
}
