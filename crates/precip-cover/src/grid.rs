//! [`CoverGrid`]: the snow cover over a world rectangle, and its step.

use rayon::prelude::*;

use crate::deposit::{DepositBuffer, Landed};
use crate::drift::{
    SNOW_DRIFT_ITERATIONS, apply_drift, snow_inflow_of, snow_outflow_of, snow_wind_factor_of,
};
use crate::error::CoverError;
use crate::frame::GridFrame;
use crate::gpu::CoverAir;
use crate::masks::ThresholdMasks;
use crate::params::CoverParams;
use crate::shading::{CoverShading, shade_texel};
use crate::surface::Surface;
use crate::texel::{CoverFeed, CoverTexel};
use crate::update::{CoverInput, update_texel};
use crate::water::{
    NEIGHBOURS, WATER_FLOW_ITERATIONS, apply_flow, neighbour, water_inflow_of, water_outflow_of,
};

/// The cover's water books over the whole grid, kg (mm × m²), summed in f64.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverTotals {
    /// All water received.
    pub deposited_kg: f64,
    /// Frozen snow stored.
    pub swe_kg: f64,
    /// Liquid water held in packs.
    pub liquid_kg: f64,
    /// Water that left: over the grid's edge, or into a water body.
    pub runoff_kg: f64,
    /// Water held as films on the surfaces.
    pub film_kg: f64,
    /// Standing water (puddles and water on its way).
    pub standing_kg: f64,
    /// Water soaked into the ground.
    pub infiltrated_kg: f64,
    /// Water evaporated.
    pub evaporated_kg: f64,
    /// The flow's net inflow summed over the grid: zero up to rounding (what left
    /// over the edge is in `runoff_kg`).
    pub net_inflow_kg: f64,
    /// Snow the wind brought over the grid's edges minus what it blew off them
    /// (moves inside the grid sum to zero up to rounding).
    pub drifted_kg: f64,
    /// Of `drifted_kg`, what crossed the grid's edges (the rest sums to zero).
    pub edge_drifted_kg: f64,
    /// Sand and dust settled on the grid, kg (outside the water books).
    pub dust_kg: f64,
    /// Area where snow is blowing (saltation in the last drift iteration), m².
    pub blowing_area_m2: f64,
    /// Area holding snow, m².
    pub snow_area_m2: f64,
    /// The deepest snow, mm.
    pub max_snow_depth_mm: f64,
    /// Snow volume, m³ (depth × area).
    pub snow_volume_m3: f64,
    /// Area with a wet surface (wetness ≥ ½), m².
    pub wet_area_m2: f64,
    /// Area under puddles: standing water over the surface's texture
    /// ([`CoverTexel::puddle_ratio`] ≥ 1; water bodies aside), m².
    pub puddle_area_m2: f64,
    /// Area of the grid, m².
    pub area_m2: f64,
}

impl CoverTotals {
    /// `deposited + net inflow − (every column)`: zero up to rounding.
    #[must_use]
    pub fn imbalance_kg(&self) -> f64 {
        self.deposited_kg + self.net_inflow_kg + self.drifted_kg
            - (self.swe_kg
                + self.liquid_kg
                + self.runoff_kg
                + self.film_kg
                + self.standing_kg
                + self.infiltrated_kg
                + self.evaporated_kg)
    }

    /// Water on the surfaces (films + standing), kg.
    #[must_use]
    pub fn surface_water_kg(&self) -> f64 {
        self.film_kg + self.standing_kg
    }

    /// Mean snow depth over the grid, mm.
    #[must_use]
    pub fn mean_snow_depth_mm(&self) -> f64 {
        if self.area_m2 > 0.0 {
            self.snow_volume_m3 * 1.0e3 / self.area_m2
        } else {
            0.0
        }
    }
}

/// The snow cover: a frame and one [`CoverTexel`] per grid cell.
#[derive(Debug, Clone, PartialEq)]
pub struct CoverGrid {
    /// Where the grid lies.
    pub frame: GridFrame,
    /// The texels, `i + nx·j`.
    pub texels: Vec<CoverTexel>,
}

impl CoverGrid {
    /// A bare grid with the given eligibility, masks and feed per texel.
    pub fn new(
        frame: GridFrame,
        eligibility: &[f32],
        masks: &ThresholdMasks,
        feed: &[CoverFeed],
    ) -> Result<Self, CoverError> {
        frame.validate("cover frame")?;
        let n = frame.texel_count();
        for (what, got) in [
            ("eligibility", eligibility.len()),
            ("accumulation mask", masks.accumulation.len()),
            ("melt mask", masks.melt.len()),
            ("feed", feed.len()),
        ] {
            if got != n {
                return Err(CoverError::SizeMismatch {
                    what,
                    got,
                    expected: n,
                });
            }
        }
        let texels = (0..n)
            .map(|i| CoverTexel {
                eligibility: if eligibility[i].is_finite() {
                    eligibility[i].clamp(0.0, 1.0)
                } else {
                    0.0
                },
                accumulation_mask: masks.accumulation[i],
                melt_mask: masks.melt[i],
                feed: feed[i] as u32,
                wind_factor: 1.0,
                ..CoverTexel::default()
            })
            .collect();
        Ok(Self { frame, texels })
    }

    /// Sets each texel's ground height (m) and surface; a water body holds no snow.
    pub fn with_ground(
        mut self,
        height_m: &[f32],
        surface: &[Surface],
    ) -> Result<Self, CoverError> {
        let n = self.texels.len();
        for (what, got) in [
            ("ground height", height_m.len()),
            ("surface", surface.len()),
        ] {
            if got != n {
                return Err(CoverError::SizeMismatch {
                    what,
                    got,
                    expected: n,
                });
            }
        }
        for ((t, &h), &s) in self.texels.iter_mut().zip(height_m).zip(surface) {
            t.ground_m = if h.is_finite() { h } else { 0.0 };
            t.surface = s as u32;
            if s == Surface::Water {
                t.eligibility = 0.0;
            }
        }
        Ok(self)
    }

    /// Advances every texel by `dt_days`.
    ///
    /// A texel fed by particles takes its landed water from `deposits` (which this
    /// drains); a texel fed by the weather takes `snow_rate`/`rain_rate` (mm/day of
    /// water, `D_s = C_a·t`) and ignores any deposit, which is dropped: never both.
    ///
    /// Then standing water flows ([`WATER_FLOW_ITERATIONS`] iterations of
    /// [`crate::water`]'s scheme).
    pub fn step(
        &mut self,
        deposits: &mut DepositBuffer,
        air: CoverAir,
        dt_days: f32,
        params: &CoverParams,
    ) {
        let landed: Vec<Landed> = (0..self.texels.len())
            .map(|i| deposits.take_mm(i))
            .collect();
        self.texels
            .par_iter_mut()
            .zip(landed.par_iter())
            .for_each(|(texel, landed)| {
                // Grains come from particles alone, whatever the texel's feed.
                texel.dust_kg_m2 += landed.grains_kg_m2;
                let (snow_mm, rain_mm) = match CoverFeed::from_raw(texel.feed) {
                    CoverFeed::Particles => (landed.snow_mm, landed.rain_mm),
                    CoverFeed::WeatherRate => (
                        air.snow_rate_mm_per_day * dt_days,
                        air.rain_rate_mm_per_day * dt_days,
                    ),
                };
                let input = CoverInput {
                    snow_mm,
                    rain_mm,
                    air_temperature_c: air.air_temperature_c,
                    relative_humidity: air.relative_humidity,
                    wind_speed_mps: air.wind_speed_mps,
                    dt_days,
                };
                *texel = update_texel(*texel, input, params);
            });
        self.drift_snow(air, dt_days, params);
        let iteration_s = dt_days * 86_400.0 / WATER_FLOW_ITERATIONS as f32;
        for _ in 0..WATER_FLOW_ITERATIONS {
            self.flow_water(iteration_s);
        }
    }

    /// Moves snow by the wind and by gravity over `dt_days` ([`crate::drift`]): every
    /// texel's wind factor, then [`SNOW_DRIFT_ITERATIONS`] iterations of two passes
    /// (the GPU's `snow_wind`, `snow_outflow` and `snow_inflow` kernels).
    pub fn drift_snow(&mut self, air: CoverAir, dt_days: f32, params: &CoverParams) {
        let frame = self.frame;
        let wind = glam::Vec2::from(air.wind_mps);
        let factors: Vec<f32> = (0..self.texels.len())
            .into_par_iter()
            .map(|i| snow_wind_factor_of(&self.texels, &frame, i, wind))
            .collect();
        for (t, f) in self.texels.iter_mut().zip(factors) {
            t.wind_factor = f;
        }
        let tau_s = dt_days * 86_400.0 / SNOW_DRIFT_ITERATIONS as f32;
        let repose_tan = params.snow_repose_angle_deg.to_radians().tan();
        for _ in 0..SNOW_DRIFT_ITERATIONS {
            let outflows: Vec<_> = (0..self.texels.len())
                .into_par_iter()
                .map(|i| {
                    snow_outflow_of(
                        &self.texels,
                        &frame,
                        i,
                        wind,
                        air.air_temperature_c,
                        tau_s,
                        repose_tan,
                    )
                })
                .collect();
            for (t, o) in self.texels.iter_mut().zip(outflows) {
                t.outflow_mm = o.outflow_mm;
                t.moving_density_kg_m3 = o.density_kg_m3;
                t.saltation_kg_per_m_s = o.saltation_kg_per_m_s;
            }
            let exchanges: Vec<_> = (0..self.texels.len())
                .into_par_iter()
                .map(|i| {
                    snow_inflow_of(&self.texels, &frame, i, wind, air.air_temperature_c, tau_s)
                })
                .collect();
            for (t, e) in self.texels.iter_mut().zip(exchanges) {
                apply_drift(t, e);
            }
        }
    }

    /// The steepest face of snow over the grid, degrees: over every texel with snow
    /// and each neighbour, the rise of its surface above the higher of the
    /// neighbour's surface and its own ground, over the texels' spacing (a drift
    /// against a wall is measured by its own face, not the wall's).
    #[must_use]
    pub fn steepest_snow_slope_deg(&self) -> f32 {
        let cell = self.frame.cell_m();
        let mut steepest = 0.0f32;
        for (i, t) in self.texels.iter().enumerate() {
            if t.depth_mm <= 0.0 {
                continue;
            }
            for (k, offset) in NEIGHBOURS.into_iter().enumerate() {
                let dx = if k < 2 { cell.x } else { cell.y };
                if let Some(o) = neighbour(&self.frame, i, offset).and_then(|j| self.texels.get(j))
                {
                    let rise = t.surface_m() - o.surface_m().max(t.ground_m);
                    steepest = steepest.max(rise / dx);
                }
            }
        }
        steepest.atan().to_degrees()
    }

    /// One iteration of overland flow of `iteration_s` seconds: every texel's
    /// outflows, then every texel's exchange (the GPU's two kernels).
    pub fn flow_water(&mut self, iteration_s: f32) {
        let frame = self.frame;
        let outflows: Vec<[f32; 4]> = (0..self.texels.len())
            .into_par_iter()
            .map(|i| water_outflow_of(&self.texels, &frame, i, iteration_s))
            .collect();
        for (t, o) in self.texels.iter_mut().zip(outflows) {
            t.outflow_mm = o;
        }
        let exchanges: Vec<(f32, f32, f32)> = (0..self.texels.len())
            .into_par_iter()
            .map(|i| water_inflow_of(&self.texels, &frame, i))
            .collect();
        for (t, e) in self.texels.iter_mut().zip(exchanges) {
            apply_flow(t, e);
        }
    }

    /// The water books over the grid.
    #[must_use]
    pub fn totals(&self) -> CoverTotals {
        let area = f64::from(self.frame.texel_area_m2());
        CoverTotals::of_texels(self.texels.iter().map(|t| (t, area)))
    }

    /// What a shader needs, per texel.
    #[must_use]
    pub fn shading(&self, params: &CoverParams) -> Vec<CoverShading> {
        self.texels.iter().map(|t| shade_texel(t, params)).collect()
    }

    /// The texel under world `(x, z)`.
    #[must_use]
    pub fn texel_at(&self, x_m: f32, z_m: f32) -> Option<&CoverTexel> {
        self.frame
            .texel_index(glam::Vec2::new(x_m, z_m))
            .and_then(|i| self.texels.get(i))
    }
}

impl CoverTotals {
    /// The books of `texels`, each standing for its area, m² (a grid's texels, or
    /// the cover beyond the grid: a texel for all the land of its surface).
    #[must_use]
    pub fn of_texels<'a>(texels: impl Iterator<Item = (&'a CoverTexel, f64)>) -> Self {
        texels.fold(Self::default(), |acc, (t, area)| {
            let kg = |mm: f32| f64::from(mm) * area;
            Self {
                deposited_kg: acc.deposited_kg + kg(t.deposited_mm),
                swe_kg: acc.swe_kg + kg(t.swe_mm),
                liquid_kg: acc.liquid_kg + kg(t.liquid_mm),
                runoff_kg: acc.runoff_kg + kg(t.runoff_mm),
                film_kg: acc.film_kg + kg(t.film_mm),
                standing_kg: acc.standing_kg + kg(t.standing_mm),
                infiltrated_kg: acc.infiltrated_kg + kg(t.infiltrated_mm),
                evaporated_kg: acc.evaporated_kg + kg(t.evaporated_mm),
                net_inflow_kg: acc.net_inflow_kg + kg(t.net_inflow_mm),
                drifted_kg: acc.drifted_kg + kg(t.drifted_mm),
                edge_drifted_kg: acc.edge_drifted_kg + kg(t.edge_drifted_mm),
                dust_kg: acc.dust_kg + kg(t.dust_kg_m2),
                blowing_area_m2: acc.blowing_area_m2
                    + if t.saltation_kg_per_m_s > 0.0 {
                        area
                    } else {
                        0.0
                    },
                snow_area_m2: acc.snow_area_m2 + if t.depth_mm > 0.0 { area } else { 0.0 },
                max_snow_depth_mm: acc.max_snow_depth_mm.max(f64::from(t.depth_mm)),
                snow_volume_m3: acc.snow_volume_m3 + f64::from(t.depth_mm) * 1.0e-3 * area,
                wet_area_m2: acc.wet_area_m2 + if t.wetness >= 0.5 { area } else { 0.0 },
                puddle_area_m2: acc.puddle_area_m2
                    + if t.puddle_ratio() >= 1.0 { area } else { 0.0 },
                area_m2: acc.area_m2 + area,
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::{UVec2, Vec2};

    use super::*;
    use crate::masks::generate_threshold_masks;

    fn air(snow: f32, rain: f32, temperature: f32) -> CoverAir {
        CoverAir {
            snow_rate_mm_per_day: snow,
            rain_rate_mm_per_day: rain,
            air_temperature_c: temperature,
            relative_humidity: 0.8,
            wind_speed_mps: 2.0,
            wind_mps: [0.0, 0.0],
        }
    }

    fn grid(n: u32, feed: CoverFeed) -> CoverGrid {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(n));
        let masks = generate_threshold_masks(&frame, 3, 12.0);
        let count = frame.texel_count();
        CoverGrid::new(frame, &vec![1.0; count], &masks, &vec![feed; count]).expect("valid")
    }

    /// Water poured into a bowl on a hillside 800 m up (where `f32` rounds a
    /// height to 6·10⁻⁵ m) runs down and settles; once at rest, level to
    /// `LEVEL_WATER_M`, it stays at rest while it dries (evaporation takes the same
    /// from every texel between iterations): no texel sends anything and an
    /// iteration changes no bit — what lets the GPU leave resting water out of the
    /// flow. Without the threshold it never came to rest (still trading water
    /// after 20 000 iterations); with the surfaces' heights added before their
    /// difference was taken, the drying's rounding set it flowing again.
    #[test]
    fn water_in_a_bowl_comes_to_rest_bit_for_bit() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(16.0), UVec2::splat(32));
        let masks = generate_threshold_masks(&frame, 3, 4.0);
        let count = frame.texel_count();
        let heights: Vec<f32> = (0..count)
            .map(|i| {
                let c = frame.texel_centre(i);
                // A hillside 800 m up, with a bowl 0.3 m deep in it.
                800.0 + 0.02 * c.x + 0.3 * (c.length() / 5.0).min(1.0).powi(2)
            })
            .collect();
        let surfaces = vec![Surface::Grass; count];
        let mut g = CoverGrid::new(
            frame,
            &vec![1.0; count],
            &masks,
            &vec![CoverFeed::WeatherRate; count],
        )
        .and_then(|g| g.with_ground(&heights, &surfaces))
        .expect("valid");
        for t in &mut g.texels {
            t.standing_mm = 20.0;
        }
        let mut iterations = 0;
        while g
            .texels
            .iter()
            .any(|t| t.outflow_mm.iter().any(|&o| o > 0.0))
            || iterations == 0
        {
            g.flow_water(30.0);
            iterations += 1;
            assert!(iterations < 20_000, "the water never comes to rest");
        }
        for round in 0..50 {
            for t in &mut g.texels {
                if t.standing_mm > 0.0 {
                    t.standing_mm = (t.standing_mm - 2.5e-3).max(0.0);
                }
            }
            let before = g.clone();
            g.flow_water(30.0);
            assert!(
                g.texels
                    .iter()
                    .zip(&before.texels)
                    .all(|(a, b)| a.standing_mm.to_bits() == b.standing_mm.to_bits()),
                "round {round}: resting water moved"
            );
        }
        let held: f32 = g.texels.iter().map(|t| t.standing_mm).sum();
        assert!(
            held > 1_000.0,
            "the bowl holds water: {held} mm over its texels"
        );
    }

    #[test]
    fn sizes_must_match() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(8.0), UVec2::splat(4));
        let masks = generate_threshold_masks(&frame, 0, 4.0);
        let err =
            CoverGrid::new(frame, &[1.0; 3], &masks, &[CoverFeed::Particles; 16]).unwrap_err();
        assert!(matches!(
            err,
            CoverError::SizeMismatch {
                what: "eligibility",
                got: 3,
                expected: 16
            }
        ));
    }

    #[test]
    fn coverage_grows_in_patches_not_uniformly() {
        let mut g = grid(64, CoverFeed::WeatherRate);
        let params = CoverParams::default();
        let mut deposits = DepositBuffer::new(g.texels.len());
        // Snow until A_S is one half everywhere (same depth everywhere: the patches come
        // from the masks alone).
        while crate::shading::accumulated_fraction(&g.texels[0], &params) < 0.5 {
            g.step(&mut deposits, air(2.0, 0.0, -5.0), 0.01, &params);
        }
        let a_s = crate::shading::accumulated_fraction(&g.texels[0], &params);
        let alpha: Vec<f32> = g.shading(&params).iter().map(|s| s.snow_alpha).collect();
        let covered = alpha.iter().filter(|&&a| a > 0.99).count() as f32 / alpha.len() as f32;
        let bare = alpha.iter().filter(|&&a| a < 0.01).count() as f32 / alpha.len() as f32;
        // The soft borders (ε = 0.2 of the mask's range) keep the covered share: the
        // mean opacity is A_S.
        let mean = alpha.iter().sum::<f32>() / alpha.len() as f32;
        assert!(
            (mean - a_s).abs() < 0.05,
            "mean opacity {mean} vs A_S {a_s}"
        );
        // Patches, not a uniform veil: most texels are covered or bare, a fifth or
        // so on a border.
        assert!(
            covered + bare > 0.7,
            "patches are mostly covered or bare: {covered} + {bare}"
        );
        // Coherent: a covered texel's right neighbour is mostly covered too.
        let nx = 64;
        let (mut same, mut pairs) = (0, 0);
        for i in 0..alpha.len() - 1 {
            if i % nx != nx - 1 && alpha[i] > 0.99 {
                pairs += 1;
                same += usize::from(alpha[i + 1] > 0.99);
            }
        }
        assert!(same as f32 / pairs as f32 > 0.8, "{same}/{pairs}");
    }

    #[test]
    fn deposits_feed_particle_texels_and_rates_feed_the_others_never_both() {
        let params = CoverParams::default();
        let mut particles = grid(4, CoverFeed::Particles);
        let mut rate = grid(4, CoverFeed::WeatherRate);
        let mut d1 = DepositBuffer::new(16);
        let mut d2 = DepositBuffer::new(16);
        d1.add(5, DepositBuffer::SNOW, 3.0);
        d2.add(5, DepositBuffer::SNOW, 3.0);
        particles.step(&mut d1, air(10.0, 0.0, -5.0), 0.1, &params);
        rate.step(&mut d2, air(10.0, 0.0, -5.0), 0.1, &params);
        assert!((particles.texels[5].swe_mm - 3.0).abs() < 1e-5);
        assert!(
            particles.texels[4].swe_mm.abs() < f32::MIN_POSITIVE,
            "no rate on particle texels"
        );
        assert!(
            (rate.texels[5].swe_mm - 1.0).abs() < 1e-5,
            "rate only, deposit dropped"
        );
        assert!((particles.totals().deposited_kg - 3.0 * 256.0).abs() < 1e-2);
    }

    /// A 40 m × 40 m asphalt grid of 1 m texels on a 2 % slope along x, with an
    /// optional dip of `dip_m` (Gaussian, radius 3 m) at the centre.
    fn sloped_road(dip_m: f32) -> CoverGrid {
        let n = 40u32;
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(40.0), UVec2::splat(n));
        let count = frame.texel_count();
        let masks = generate_threshold_masks(&frame, 0, 8.0);
        let heights: Vec<f32> = (0..count)
            .map(|i| {
                let c = frame.texel_centre(i);
                -0.02 * c.x - dip_m * (-c.length_squared() / 9.0).exp()
            })
            .collect();
        CoverGrid::new(
            frame,
            &vec![0.0; count],
            &masks,
            &vec![CoverFeed::WeatherRate; count],
        )
        .and_then(|g| g.with_ground(&heights, &vec![Surface::Asphalt; count]))
        .expect("valid")
    }

    fn downpour(g: &mut CoverGrid, minutes: u32, step_s: u32) {
        let params = CoverParams::default();
        let mut deposits = DepositBuffer::new(g.texels.len());
        let rain = CoverAir {
            rain_rate_mm_per_day: 40.0 * 24.0,
            relative_humidity: 1.0,
            air_temperature_c: 15.0,
            ..CoverAir::default()
        };
        for _ in 0..minutes * 60 / step_s {
            g.step(&mut deposits, rain, step_s as f32 / 86_400.0, &params);
        }
    }

    #[test]
    fn a_puddle_gathers_in_a_dip_and_none_stands_on_the_slope() {
        let mut dip = sloped_road(0.08);
        let mut slope = sloped_road(0.0);
        // Two-minute cover steps, as the viewer's default time scale makes them.
        downpour(&mut dip, 60, 120);
        downpour(&mut slope, 60, 120);
        let mut fine = sloped_road(0.0);
        downpour(&mut fine, 60, 10);
        let centre = dip.texel_at(0.5, 0.5).expect("on the grid").standing_mm;
        let rim = dip.texel_at(-12.5, 0.5).expect("on the grid").standing_mm;
        // Away from the outlet (the last two texels before the low edge, where the
        // flow limiter backs the sheet up).
        let deepest_on_slope = slope
            .texels
            .iter()
            .enumerate()
            .filter(|(i, _)| slope.frame.texel_centre(*i).x < 17.0)
            .map(|(_, t)| t.standing_mm)
            .fold(0.0f32, f32::max);
        let slope_centre = slope.texel_at(0.5, 0.5).expect("on the grid").standing_mm;
        // The kinematic wave's steady sheet 20 m down a 2 % asphalt slope under
        // 40 mm/h: q = i·L, h = (q·n/√S)^(3/5).
        let q = 40.0e-3 / 3600.0 * 20.0;
        let sheet_mm = 1.0e3 * (q * 0.015 / 0.02f32.sqrt()).powf(0.6);
        println!(
            "after 1 h of 40 mm/h: dip centre {centre:.1} mm, upslope {rim:.2} mm; plain slope: centre {slope_centre:.2} mm (kinematic wave {sheet_mm:.2} mm), deepest {deepest_on_slope:.2} mm"
        );
        assert!(centre > 20.0, "a puddle in the dip: {centre} mm");
        assert!(rim < 1.0, "upslope drains: {rim} mm");
        let fine_centre = fine.texel_at(0.5, 0.5).expect("on the grid").standing_mm;
        println!("with 10 s steps: slope centre {fine_centre:.2} mm");
        // With short steps the sheet is the kinematic wave's; with two-minute steps
        // it travels as pulses a texel an iteration and is at most a few times
        // thicker: a sheet, never a puddle.
        assert!(
            (fine_centre / sheet_mm - 1.0).abs() < 0.5,
            "the sheet on a slope: {fine_centre} mm vs the kinematic wave's {sheet_mm} mm"
        );
        assert!(
            slope_centre < 2.0 * sheet_mm,
            "no puddle on a plain slope: {slope_centre} mm"
        );
        assert!(
            deepest_on_slope < 4.0 * sheet_mm,
            "the sheet stays thin: {deepest_on_slope} mm"
        );
        // With short steps the puddle's surface is level: its deepest texel's wet
        // neighbours share its water level within a few millimetres (water runs
        // through it). (With two-minute steps the flow limiter holds up the water
        // passing through, and the surface tilts by about a centimetre a metre.)
        let mut dip = sloped_road(0.08);
        downpour(&mut dip, 60, 10);
        let level = |t: &CoverTexel| t.ground_m + t.standing_mm * 1e-3;
        let (deepest, _) = dip
            .texels
            .iter()
            .enumerate()
            .fold((0, 0.0f32), |a, (i, t)| {
                if t.standing_mm > a.1 {
                    (i, t.standing_mm)
                } else {
                    a
                }
            });
        for j in [deepest - 1, deepest + 1, deepest - 40, deepest + 40] {
            let (a, b) = (&dip.texels[deepest], &dip.texels[j]);
            if b.standing_mm > 5.0 {
                assert!(
                    (level(a) - level(b)).abs() < 4e-3,
                    "{} vs {}",
                    level(a),
                    level(b)
                );
            }
        }
    }

    #[test]
    fn flow_conserves_water_and_the_books_balance_per_texel() {
        let mut g = sloped_road(0.08);
        downpour(&mut g, 40, 120);
        let totals = g.totals();
        println!("{totals:?}");
        assert!(totals.runoff_kg > 0.0, "water left over the low edge");
        assert!(
            totals.imbalance_kg().abs() < 1e-5 * totals.deposited_kg,
            "imbalance {} of {}",
            totals.imbalance_kg(),
            totals.deposited_kg
        );
        assert!(
            totals.net_inflow_kg.abs() < 1e-5 * totals.deposited_kg,
            "flow between texels sums to zero: {}",
            totals.net_inflow_kg
        );
        for t in &g.texels {
            assert!(
                t.imbalance_mm().abs() < 1e-3 * f64::from(t.deposited_mm).max(1.0),
                "{t:?}"
            );
        }
    }
}
