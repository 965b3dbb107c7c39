//! Snow moved on the ground: by the wind (drifts) and by gravity (slides) (WGSL
//! twins in `shaders/cover_update.wgsl`: `snow_wind_factor_of`, and the
//! `snow_outflow` and `snow_inflow` kernels, where the outflow is written inline).
//!
//! ## The wind over the ground
//!
//! The weather's mean wind `U` ([`crate::blowing`]) is scaled per texel by a factor
//! read off the snow's surface `H = z + depth` along the wind's line, so drifts that
//! fill a hollow also end its shelter:
//!
//! - **Terrain** (MicroMet, Liston & Elder 2006, *J. Hydrometeorology* 7):
//!   `W = 1 + γ_s·Ω_s + γ_c·Ω_c`, `γ_s = γ_c = ½`, with `Ω_s` the slope along the
//!   wind (up-wind positive: windward faces speed up, lee faces slow) and `Ω_c` the
//!   curvature along the wind, `(H − ½(H_up + H_down)) / (2η)` over
//!   [`FULL_CURVATURE`] (crests speed up, hollows and the foot of a wall slow),
//!   each within `±½`, so `W ∈ [½, 3/2]`. `H_up`, `H_down` are the mean surfaces
//!   over [`TERRAIN_SPAN_M`] up and down the wind, `η` their mean distance (a scene's
//!   walls and banks, where MicroMet's η is a valley's).
//! - **Shelter** behind obstacles: Winstral et al.'s (2002, *Hydrological
//!   Processes* 16) upwind shelter `S_x`, the steepest tangent to the surface
//!   upwind within [`SHELTER_REACH_M`] (of relief above [`SHELTER_RELIEF_M`]),
//!   gives the wake's share
//!   `1 / (1 + (L·S_x)²)`, `L = ` [`WAKE_LENGTH_RATIO`]: the flow behind a solid
//!   barrier of height `h` reattaches about 12 h downwind (Tabler 1991, *Snow Fence
//!   Guide*), so half the wind is back at 12 h, 80 % at 24 h.
//!
//! ## Transport
//!
//! Each texel whose wind exceeds its snow's threshold sends `Q_salt·τ/Δx` (mm of
//! water over its area, `Q_salt` by Pomeroy & Gray) toward its down-wind
//! neighbours along x and z in proportion to the wind's components, from its own
//! pack; arriving snow joins the receiver's pack and leaves again in the next
//! iteration if the wind there can carry it. So snow is eroded where the flux grows
//! (windward faces, crests) and deposited where it falls (lee of walls, fences,
//! hollows), as the divergence of the flux. Snow that meets a wall or fence is
//! carried over it by the flow that rises there (Tabler's solid barriers hold a
//! short windward drift in the slowed air at their foot, the curvature term here,
//! and a longer lee drift). Wind-blown snow settles at the
//! wind-packed density (≥ [`WIND_PACKED_DENSITY_KG_M3`], Pomeroy & Gray 1995 give
//! 250–400 kg/m³). At the grid's up-wind edges the field beyond is taken to be
//! like the edge texel (it sends what the edge texel sends on); at the down-wind
//! edges snow leaves.
//!
//! ## Slides
//!
//! A snow surface steeper than the repose angle θ toward a neighbour sends the part
//! above the repose line, `e = H − max(H_j + tanθ·Δx, z + tanθ·Δx/2)` (the second
//! term: snow at a ledge stands only up to the repose line from the ledge's edge),
//! half of it shared among the faces that go down (as the water's limiter), at its
//! own density. Slides never cross the grid's edge.
//!
//! Both are one exchange: every texel computes its four outflows (SWE, mm) into
//! [`CoverTexel::outflow_mm`], then every texel takes its neighbours' toward it:
//! each amount computed once and added once (deterministic, conservative up to
//! rounding); [`SNOW_DRIFT_ITERATIONS`] iterations a step. The GPU runs them only
//! over the tiles of the grid within reach of a texel that would send snow
//! (`precip_gpu::recipe::COVER_TILE_SIDE`), with the same result as the whole
//! grid's: a texel starts to send only once it or a neighbour took or sent snow. Snow reaching a texel
//! where none may lie (a fence's top, heated paving, water) passes on while the
//! wind there can lift fresh wind-packed snow; where it cannot, the share of
//! [`CoverTexel::eligibility`] stays and the rest melts. The receiver's age is weighted
//! as for fresh snow (blown snow renews the surface). Sublimation of blowing snow
//! is not modelled.

use glam::Vec2;

use crate::blowing::{
    WET_SNOW_LIQUID_FRACTION, air_density_kg_m3, friction_velocity_mps, movable_swe_mm,
    saltation_flux_kg_per_m_s, threshold_friction_velocity_mps,
};
use crate::frame::GridFrame;
use crate::surface::Surface;
use crate::texel::CoverTexel;
use crate::water::{NEIGHBOURS, neighbour};

/// Drift iterations a cover step makes (two kernels each on the GPU).
pub const SNOW_DRIFT_ITERATIONS: u32 = 8;
/// Density of snow that the wind deposits, at least, kg/m³.
pub const WIND_PACKED_DENSITY_KG_M3: f32 = 300.0;
/// Reattachment length behind a solid barrier, in barrier heights.
pub const WAKE_LENGTH_RATIO: f32 = 12.0;
/// How far upwind an obstacle shelters, m.
pub const SHELTER_REACH_M: f32 = 60.0;
/// Most samples along the upwind line (one a texel up to [`SHELTER_REACH_M`] on
/// grids of texels ≥ 0.47 m, so no fence is stepped over).
pub const SHELTER_SAMPLES: u32 = 128;
/// Relief lower than this above a texel is roughness (in `z0`), not an obstacle
/// that shelters it, m: without it the drift's own ripples would shelter their lee
/// and grow into texel-sized dunes.
pub const SHELTER_RELIEF_M: f32 = 0.3;
/// η: the span over which the terrain's slope and curvature are read, m.
pub const TERRAIN_SPAN_M: f32 = 3.0;
/// Most samples each side for the terrain's means.
pub const TERRAIN_SAMPLES: u32 = 16;
/// Curvature `(H − ½(H_up + H_down))/(2η)` that counts fully (`Ω_c = ½`).
pub const FULL_CURVATURE: f32 = 0.05;
/// Below this SWE, mm, a texel has no snow to move.
const NO_SNOW_MM: f32 = 1.0e-6;

/// The surface height at world `xz`, the nearest texel's (off the grid: the edge
/// texel's, the field continuing level).
fn surface_at(texels: &[CoverTexel], frame: &GridFrame, xz: Vec2) -> Option<f32> {
    let t = (xz - frame.origin_m) / frame.cell_m();
    let max = frame.texels.as_vec2() - 1.0;
    let f = t.floor().clamp(Vec2::ZERO, max.max(Vec2::ZERO));
    let index = f.x as usize + frame.texels.x as usize * f.y as usize;
    texels.get(index).map(CoverTexel::surface_m)
}

/// The wind's speed at texel `index` over the weather's, for a wind blowing along
/// `wind_mps` (see the module docs). 1 in calm air.
#[must_use]
pub fn snow_wind_factor_of(
    texels: &[CoverTexel],
    frame: &GridFrame,
    index: usize,
    wind_mps: Vec2,
) -> f32 {
    let (Some(t), Some(dir)) = (texels.get(index), wind_mps.try_normalize()) else {
        return 1.0;
    };
    let p = frame.texel_centre(index);
    let h = t.surface_m();
    let at = |d: f32| surface_at(texels, frame, p + dir * d).unwrap_or(h);
    let cell = frame.cell_m().min_element().max(1.0e-3);
    // The terrain up and down the wind: mean surfaces over the span each side (a
    // single sample at the span would echo every bump one span downwind).
    let steps = ((TERRAIN_SPAN_M / cell).ceil() as u32).clamp(1, TERRAIN_SAMPLES);
    let (mut up, mut down) = (0.0f32, 0.0f32);
    for k in 1..=steps {
        let d = TERRAIN_SPAN_M * k as f32 / steps as f32;
        up += at(-d);
        down += at(d);
    }
    let (up, down) = (up / steps as f32, down / steps as f32);
    let reach = TERRAIN_SPAN_M * (steps + 1) as f32 / (2 * steps) as f32;
    let slope = ((h - up) / reach).clamp(-0.5, 0.5);
    let curvature =
        ((h - 0.5 * (up + down)) / (2.0 * reach) / FULL_CURVATURE * 0.5).clamp(-0.5, 0.5);
    let terrain = 1.0 + 0.5 * slope + 0.5 * curvature;
    let samples = ((SHELTER_REACH_M / cell).ceil() as u32).clamp(1, SHELTER_SAMPLES);
    let spacing = SHELTER_REACH_M / samples as f32;
    let mut shelter = 0.0f32;
    for k in 1..=samples {
        let d = spacing * k as f32;
        shelter = shelter.max((at(-d) - h - SHELTER_RELIEF_M) / d);
    }
    let wake = WAKE_LENGTH_RATIO * shelter;
    terrain / (1.0 + wake * wake)
}

/// What one texel sends in a drift iteration.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SnowOutflow {
    /// SWE to the −x, +x, −z, +z neighbours (or over the edge), mm.
    pub outflow_mm: [f32; 4],
    /// Density of the snow sent, kg/m³.
    pub density_kg_m3: f32,
    /// The saltation flux carried from here, kg/(m·s) (after the pack's limit).
    pub saltation_kg_per_m_s: f32,
}

/// The drift iteration's outflows of texel `index`, for a mean wind `wind_mps` at
/// 10 m, air at `air_temperature_c`, an iteration of `tau_s` seconds and a repose
/// tangent `repose_tan` (WGSL twin: inline in the `snow_outflow` kernel).
#[must_use]
pub fn snow_outflow_of(
    texels: &[CoverTexel],
    frame: &GridFrame,
    index: usize,
    wind_mps: Vec2,
    air_temperature_c: f32,
    tau_s: f32,
    repose_tan: f32,
) -> SnowOutflow {
    let Some(t) = texels.get(index) else {
        return SnowOutflow::default();
    };
    let Some(density) = t.snow_density_kg_m3().filter(|_| t.swe_mm > NO_SNOW_MM) else {
        return SnowOutflow::default();
    };
    let cell = frame.cell_m();
    let h_i = t.surface_m();
    let speed = wind_mps.length();
    let wet = t.liquid_mm > WET_SNOW_LIQUID_FRACTION * t.swe_mm;
    let threshold = threshold_friction_velocity_mps(air_temperature_c, density, wet);
    let mut flux = saltation_flux_kg_per_m_s(
        friction_velocity_mps(speed * t.wind_factor),
        threshold,
        air_density_kg_m3(air_temperature_c),
    );
    let mut wind = [0.0f32; 4];
    let mut slide = [0.0f32; 4];
    let mut excess = [0.0f32; 4];
    let mut faces_down = 0u32;
    for (k, offset) in NEIGHBOURS.into_iter().enumerate() {
        let dx = if k < 2 { cell.x } else { cell.y };
        let component = if k < 2 { wind_mps.x } else { wind_mps.y };
        let downwind = if k % 2 == 0 {
            component < 0.0
        } else {
            component > 0.0
        };
        let other = neighbour(frame, index, offset).and_then(|j| texels.get(j));
        if downwind && speed > 0.0 {
            wind[k] = flux * component.abs() / speed * tau_s / dx;
        }
        if let Some(o) = other {
            let rest = (o.surface_m() + repose_tan * dx).max(t.ground_m + 0.5 * repose_tan * dx);
            excess[k] = (h_i - rest).max(0.0);
            faces_down += u32::from(excess[k] > 0.0);
        }
    }
    let share = 0.5 / faces_down.max(1) as f32;
    for k in 0..4 {
        slide[k] = share * excess[k] * density;
    }
    // The wind takes only what lies above the surface's snow-holding depth, in the
    // share of the texel where snow may lie (none where it passes in transit).
    let mut wind_total: f32 = wind.iter().sum();
    if wind_total > 0.0 {
        let holding_m =
            Surface::from_raw(t.surface).snow_holding_depth_m() * t.eligibility.clamp(0.0, 1.0);
        let movable = movable_swe_mm(t.swe_mm, t.depth_mm, holding_m);
        let held = (movable / wind_total).min(1.0);
        for w in &mut wind {
            *w *= held;
        }
        flux *= held;
        wind_total = wind.iter().sum();
    }
    let slide_total: f32 = slide.iter().sum();
    let total = wind_total + slide_total;
    if total <= 0.0 {
        return SnowOutflow::default();
    }
    let scale = (t.swe_mm / total).min(1.0);
    flux *= scale;
    let wind_density = density.max(WIND_PACKED_DENSITY_KG_M3);
    let volume = wind_total / wind_density + slide_total / density;
    SnowOutflow {
        outflow_mm: std::array::from_fn(|k| (wind[k] + slide[k]) * scale),
        density_kg_m3: total / volume,
        saltation_kg_per_m_s: if wind_total > 0.0 { flux } else { 0.0 },
    }
}

/// What a texel exchanges in a drift iteration, from every texel's outflows.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SnowExchange {
    /// SWE sent to neighbours, mm.
    pub out_inside_mm: f32,
    /// SWE blown over the grid's edge, mm.
    pub out_edge_mm: f32,
    /// SWE arriving (from neighbours, and from beyond an up-wind edge), mm.
    pub in_mm: f32,
    /// Of `in_mm`, what came from beyond an up-wind edge, mm.
    pub in_edge_mm: f32,
    /// Depth that arrives with it, mm.
    pub in_depth_mm: f32,
    /// The wind here lifts fresh wind-packed snow: what arrives passes on, even
    /// where snow may not lie.
    pub in_transit: bool,
}

/// Texel `index`'s exchange in a drift iteration (air at `air_temperature_c`),
/// once every texel's
/// [`CoverTexel::outflow_mm`], density and saltation are set (WGSL twin: in
/// `snow_inflow`).
#[must_use]
pub fn snow_inflow_of(
    texels: &[CoverTexel],
    frame: &GridFrame,
    index: usize,
    wind_mps: Vec2,
    air_temperature_c: f32,
    tau_s: f32,
) -> SnowExchange {
    let Some(t) = texels.get(index) else {
        return SnowExchange::default();
    };
    let cell = frame.cell_m();
    let speed = wind_mps.length();
    let mut e = SnowExchange {
        in_transit: friction_velocity_mps(speed * t.wind_factor)
            > threshold_friction_velocity_mps(air_temperature_c, WIND_PACKED_DENSITY_KG_M3, false),
        ..SnowExchange::default()
    };
    for (k, offset) in NEIGHBOURS.into_iter().enumerate() {
        match neighbour(frame, index, offset).and_then(|j| texels.get(j)) {
            Some(o) => {
                e.out_inside_mm += t.outflow_mm[k];
                // The neighbour's face toward me is the opposite one (k ^ 1).
                let arriving = o.outflow_mm[k ^ 1];
                if arriving > 0.0 {
                    e.in_mm += arriving;
                    e.in_depth_mm += arriving * 1000.0 / o.moving_density_kg_m3;
                }
            }
            None => {
                e.out_edge_mm += t.outflow_mm[k];
                // Up-wind edge: the field beyond sends what this texel sends on.
                let dx = if k < 2 { cell.x } else { cell.y };
                let component = if k < 2 { wind_mps.x } else { wind_mps.y };
                let inward = if k % 2 == 0 {
                    component > 0.0
                } else {
                    component < 0.0
                };
                if inward && speed > 0.0 && t.saltation_kg_per_m_s > 0.0 {
                    let arriving = t.saltation_kg_per_m_s * component.abs() / speed * tau_s / dx;
                    e.in_mm += arriving;
                    e.in_edge_mm += arriving;
                    e.in_depth_mm += arriving * 1000.0 / t.moving_density_kg_m3;
                }
            }
        }
    }
    e
}

/// Applies a drift iteration's exchange to a texel (WGSL twin: in `snow_inflow`).
pub fn apply_drift(t: &mut CoverTexel, e: SnowExchange) {
    // What the neighbours received ([`snow_outflow_of`] keeps it within the pack).
    let out = e.out_inside_mm + e.out_edge_mm;
    if out > 0.0 && t.swe_mm > 0.0 {
        t.depth_mm = (t.depth_mm * (1.0 - out / t.swe_mm)).max(0.0);
        t.swe_mm = (t.swe_mm - out).max(0.0);
        t.peak_swe_mm = (t.peak_swe_mm - out).max(t.swe_mm);
    }
    let eligibility = if e.in_transit {
        1.0
    } else {
        t.eligibility.clamp(0.0, 1.0)
    };
    let kept = e.in_mm * eligibility;
    if kept > 0.0 {
        let swe = t.swe_mm + kept;
        t.age_days *= t.swe_mm / swe;
        t.swe_mm = swe;
        t.depth_mm += e.in_depth_mm * eligibility;
        t.peak_swe_mm += kept;
    }
    // Snow where none may lie melts there.
    let melted = e.in_mm - kept;
    if Surface::from_raw(t.surface) == Surface::Water {
        t.runoff_mm += melted;
    } else {
        t.standing_mm += melted;
    }
    t.drifted_mm += e.in_mm - out;
    t.edge_drifted_mm += e.in_edge_mm - e.out_edge_mm;
    if t.swe_mm <= NO_SNOW_MM {
        t.depth_mm = 0.0;
    }
}
