//! Water on surfaces: evaporation and overland flow (docs/model.md §6; WGSL twins:
//! `saturation_vapour_pressure_hpa` and `evaporation_mm_per_day` in
//! `shaders/cover.wgsl`, `water_outflow_of` and the `water_outflow`/`water_inflow`
//! kernels in `shaders/cover_update.wgsl`, where the inflow and its application are
//! written inline).
//!
//! ## Evaporation
//!
//! The aerodynamic (Dalton) term of Penman's equation with the FAO-24 wind function
//! (Doorenbos & Pruitt 1977):
//!
//! ```text
//! E   = f(u) · e_s(T) · (1 − RH)            mm/day
//! f(u) = 0.26 · (1 + 0.54 · u)              mm/(day·hPa), u wind speed at 2 m, m/s
//! e_s(T) = 6.1094 · exp(17.625 T / (T + 243.04))   hPa (Magnus form, Alduchov & Eskridge 1996)
//! ```
//!
//! The surface is taken at air temperature and the sun's radiative term is left
//! out, so this is the drying of a shaded or overcast surface: at 18 °C, 70 % and
//! 2 m/s it is 3.4 mm/day, a 0.5 mm film on asphalt dries in 3.6 h.
//!
//! ## Overland flow
//!
//! Standing water moves between the four neighbours of a texel as in the raster
//! flood model of Bates & De Roo (2000, *J. Hydrology* 236): the water surface
//! `H = z + d` drives a Manning flow through each face,
//!
//! ```text
//! Q/w = h_flow^(5/3) · √S / n,   h_flow = max(H_i, H_j) − max(z_i, z_j),   S = (H_i − H_j)/Δx
//! ```
//!
//! and none where the surfaces are level to [`LEVEL_WATER_M`] (0.1 mm), so water
//! at rest is at rest, bit for bit;
//!
//! over an iteration of `τ` seconds that moves `Δd = h_flow^(5/3)·√S·τ/(n·Δx)` of
//! depth, limited to half the level difference shared among the faces that go down
//! (the flow limiter of Hunter et al. 2005, *J. Hydrology* 310, is ΔH/4 on every
//! face; sharing lets a slope drain through its one low face at ΔH/2 while a
//! texel above four neighbours still gives each at most ΔH/8) and together to the
//! water there. Each iteration is two passes: every texel computes
//! its four outflows, then every texel takes what its neighbours send it, so every
//! amount is computed once and added once, in a fixed order (deterministic, and
//! conservative up to float rounding). Water leaving the grid's edge (onto ground
//! that continues the edge texel's slope, or level ground) runs off; a water body
//! takes what flows in.
//! A cover step makes [`WATER_FLOW_ITERATIONS`] iterations: at accelerated cover
//! time water then moves at most that many texels a step, which is what lets
//! depressions fill while slopes drain. That bound is also what lets the GPU flow
//! only over the tiles of the grid within reach of standing water
//! (`precip_gpu::recipe::COVER_TILE_SIDE`) with the same result as the whole grid's.

use crate::frame::GridFrame;
use crate::surface::Surface;
use crate::texel::CoverTexel;

/// Flow iterations a cover step makes (two kernels each on the GPU).
pub const WATER_FLOW_ITERATIONS: u32 = 16;

/// Standing water below this depth, mm, does not flow (it is part of the film's
/// roughness and only evaporates or infiltrates).
pub const STILL_WATER_MM: f32 = 1.0e-4;

/// Water surfaces within this of each other, m, are level: no flow between them.
/// Without it water never rests: the exchanges shrink as the surfaces level but
/// do not reach zero (a bowl of water still traded some after 20 000 iterations),
/// so the GPU could not leave a resting puddle out of the flow
/// (`precip_gpu::recipe::FLOW_GROUPS`: only tiles where water moved run most of
/// the iterations). 0.1 mm: a water surface that much off level over half a
/// metre shows nothing. The levels are compared by their differences,
/// `(z_i − z_j) + (d_i − d_j)`, not as `z + d` (a kilometre up, `f32` rounds that
/// to 0.06 mm, which the drying's rounding crossed).
pub const LEVEL_WATER_M: f32 = 1.0e-4;

/// Saturation vapour pressure over water at `air_temperature_c`, hPa (Magnus form).
#[must_use]
pub fn saturation_vapour_pressure_hpa(air_temperature_c: f32) -> f32 {
    let t = air_temperature_c.clamp(-60.0, 60.0);
    6.1094 * (17.625 * t / (t + 243.04)).exp()
}

/// Evaporation from a wet surface at air temperature, mm/day (Penman's aerodynamic
/// term, FAO-24 wind function; see the module docs). Zero in saturated air.
#[must_use]
pub fn evaporation_mm_per_day(
    air_temperature_c: f32,
    relative_humidity: f32,
    wind_speed_mps: f32,
) -> f32 {
    let wind = 0.26 * (1.0 + 0.54 * wind_speed_mps.max(0.0));
    wind * saturation_vapour_pressure_hpa(air_temperature_c)
        * (1.0 - relative_humidity.clamp(0.0, 1.0))
}

/// Texel index of `(i, j) + offset` on `frame`, or `None` off the grid.
pub(crate) fn neighbour(frame: &GridFrame, index: usize, offset: (i64, i64)) -> Option<usize> {
    let nx = i64::from(frame.texels.x);
    let nz = i64::from(frame.texels.y);
    let (i, j) = (index as i64 % nx, index as i64 / nx);
    let (a, b) = (i + offset.0, j + offset.1);
    (a >= 0 && a < nx && b >= 0 && b < nz).then(|| (a + nx * b) as usize)
}

/// The four neighbours' offsets, in the order of [`CoverTexel::outflow_mm`]:
/// −x, +x, −z, +z.
pub const NEIGHBOURS: [(i64, i64); 4] = [(-1, 0), (1, 0), (0, -1), (0, 1)];

/// The four outflows of texel `index` over one iteration of `tau_s` seconds, mm
/// (WGSL twin: `water_outflow_of`). A texel or neighbour that `texels` lacks (a
/// grid whose texels do not fit its frame) moves nothing.
#[must_use]
pub fn water_outflow_of(
    texels: &[CoverTexel],
    frame: &GridFrame,
    index: usize,
    tau_s: f32,
) -> [f32; 4] {
    let Some(t) = texels.get(index) else {
        return [0.0; 4];
    };
    let d_mm = t.standing_mm;
    if d_mm <= STILL_WATER_MM || Surface::from_raw(t.surface) == Surface::Water {
        return [0.0; 4];
    }
    let n = Surface::from_raw(t.surface).water().manning_n;
    let cell = frame.cell_m();
    let z_i = t.ground_m;
    let mut out = [0.0f32; 4];
    let mut total = 0.0f32;
    let mut drops = [0.0f32; 4];
    let mut faces_down = 0u32;
    for (k, offset) in NEIGHBOURS.into_iter().enumerate() {
        let dx = if k < 2 { cell.x } else { cell.y };
        let inside = neighbour(frame, index, offset).and_then(|j| texels.get(j));
        let (z_j, d_j_mm) = match inside {
            Some(o) => (o.ground_m, o.standing_mm),
            // Free outflow: the ground beyond the edge continues the slope across
            // the edge texel, and holds no water.
            None => {
                let opposite = neighbour(frame, index, (-offset.0, -offset.1))
                    .and_then(|o| texels.get(o))
                    .map_or(z_i, |o| o.ground_m);
                (z_i.min(2.0 * z_i - opposite), 0.0)
            }
        };
        // H_i − H_j and H_i − max(z_i, z_j) from the differences: a kilometre up,
        // z + d in f32 rounds the water's surface to 0.06 mm.
        let drop_m = (z_i - z_j) + (d_mm - d_j_mm) * 1.0e-3;
        let h_flow = d_mm * 1.0e-3 - (z_j - z_i).max(0.0);
        if drop_m <= LEVEL_WATER_M || h_flow <= 0.0 {
            continue;
        }
        out[k] = h_flow.powf(5.0 / 3.0) * (drop_m / dx).sqrt() * tau_s / (n * dx);
        // Beyond the edge no water can rise back: only the water here limits it.
        drops[k] = if inside.is_some() {
            drop_m
        } else {
            f32::INFINITY
        };
        faces_down += u32::from(inside.is_some());
    }
    // The limiter: each face at most half its level difference shared among the
    // faces that go down (a quarter with two, as Hunter et al.'s ΔH/4 with four).
    let share = 0.5 / faces_down.max(1) as f32;
    for k in 0..4 {
        out[k] = out[k].min(share * drops[k]) * 1.0e3;
        total += out[k];
    }
    if total > d_mm {
        let scale = d_mm / total;
        for o in &mut out {
            *o *= scale;
        }
    }
    out
}

/// What texel `index` sends away and takes in over one iteration, mm, from the
/// outflows every texel computed: `(out to neighbours, out over the grid's edge, in)`
/// (WGSL twin: inline in the `water_inflow` kernel).
#[must_use]
pub fn water_inflow_of(texels: &[CoverTexel], frame: &GridFrame, index: usize) -> (f32, f32, f32) {
    let Some(mine) = texels.get(index).map(|t| t.outflow_mm) else {
        return (0.0, 0.0, 0.0);
    };
    let (mut out_inside, mut out_edge, mut inflow) = (0.0f32, 0.0f32, 0.0f32);
    for (k, offset) in NEIGHBOURS.into_iter().enumerate() {
        match neighbour(frame, index, offset).and_then(|j| texels.get(j)) {
            Some(o) => {
                out_inside += mine[k];
                // The neighbour's face toward me is the opposite one (k ^ 1).
                inflow += o.outflow_mm[k ^ 1];
            }
            None => out_edge += mine[k],
        }
    }
    (out_inside, out_edge, inflow)
}

/// Applies one iteration's flow to a texel: its standing water, its books, and
/// what reaches a water body (WGSL twin: in `water_inflow`).
pub fn apply_flow(texel: &mut CoverTexel, (out_inside, out_edge, inflow): (f32, f32, f32)) {
    texel.net_inflow_mm += inflow - out_inside;
    texel.runoff_mm += out_edge;
    if Surface::from_raw(texel.surface) == Surface::Water {
        texel.runoff_mm += inflow;
    } else {
        texel.standing_mm = (texel.standing_mm + inflow - out_inside - out_edge).max(0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_whose_texels_do_not_fit_its_frame_moves_nothing_and_never_panics() {
        let frame = GridFrame::centred(
            glam::Vec2::ZERO,
            glam::Vec2::splat(4.0),
            glam::UVec2::splat(4),
        );
        let texels = vec![
            CoverTexel {
                standing_mm: 5.0,
                ground_m: 1.0,
                ..CoverTexel::default()
            };
            3
        ];
        for i in 0..20 {
            let _ = water_outflow_of(&texels, &frame, i, 10.0);
            let _ = water_inflow_of(&texels, &frame, i);
        }
        assert!(
            water_outflow_of(&texels, &frame, 7, 10.0)
                .iter()
                .all(|o| o.abs() < f32::MIN_POSITIVE)
        );
    }

    #[test]
    fn evaporation_follows_temperature_wind_and_humidity() {
        // e_s(20 °C) = 23.4 hPa (tables: 23.39).
        assert!((saturation_vapour_pressure_hpa(20.0) - 23.37).abs() < 0.1);
        assert!((saturation_vapour_pressure_hpa(0.0) - 6.11).abs() < 0.01);
        let e = evaporation_mm_per_day(18.0, 0.7, 2.0);
        assert!((e - 3.35).abs() < 0.1, "{e}");
        assert!(evaporation_mm_per_day(18.0, 1.0, 5.0).abs() < f32::MIN_POSITIVE);
        assert!(evaporation_mm_per_day(25.0, 0.5, 2.0) > evaporation_mm_per_day(10.0, 0.5, 2.0));
        assert!(evaporation_mm_per_day(18.0, 0.5, 6.0) > evaporation_mm_per_day(18.0, 0.5, 1.0));
    }
}
