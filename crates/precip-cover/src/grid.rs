//! [`CoverGrid`]: the snow cover over a world rectangle, and its step.

use rayon::prelude::*;

use crate::deposit::DepositBuffer;
use crate::error::CoverError;
use crate::frame::GridFrame;
use crate::masks::ThresholdMasks;
use crate::params::CoverParams;
use crate::shading::{CoverShading, shade_texel};
use crate::texel::{CoverFeed, CoverTexel};
use crate::update::{CoverInput, update_texel};

/// The cover's water books over the whole grid, kg (mm × m²), summed in f64.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverTotals {
    /// All water received.
    pub deposited_kg: f64,
    /// Frozen snow stored.
    pub swe_kg: f64,
    /// Liquid water held in packs.
    pub liquid_kg: f64,
    /// Water that left (melt drainage, rain on bare ground, snow where none may lie).
    pub runoff_kg: f64,
}

impl CoverTotals {
    /// `deposited − (swe + liquid + runoff)`: zero up to rounding.
    #[must_use]
    pub fn imbalance_kg(&self) -> f64 {
        self.deposited_kg - (self.swe_kg + self.liquid_kg + self.runoff_kg)
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
                ..CoverTexel::default()
            })
            .collect();
        Ok(Self { frame, texels })
    }

    /// Advances every texel by `dt_days`.
    ///
    /// A texel fed by particles takes its landed water from `deposits` (which this
    /// drains); a texel fed by the weather takes `snow_rate`/`rain_rate` (mm/day of
    /// water, `D_s = C_a·t`) and ignores any deposit, which is dropped: never both.
    pub fn step(
        &mut self,
        deposits: &mut DepositBuffer,
        snow_rate_mm_per_day: f32,
        rain_rate_mm_per_day: f32,
        air_temperature_c: f32,
        dt_days: f32,
        params: &CoverParams,
    ) {
        let landed: Vec<(f32, f32)> = (0..self.texels.len())
            .map(|i| deposits.take_mm(i))
            .collect();
        self.texels
            .par_iter_mut()
            .zip(landed.par_iter())
            .for_each(|(texel, &(snow, rain))| {
                let input = match CoverFeed::from_raw(texel.feed) {
                    CoverFeed::Particles => CoverInput {
                        snow_mm: snow,
                        rain_mm: rain,
                        air_temperature_c,
                        dt_days,
                    },
                    CoverFeed::WeatherRate => CoverInput {
                        snow_mm: snow_rate_mm_per_day * dt_days,
                        rain_mm: rain_rate_mm_per_day * dt_days,
                        air_temperature_c,
                        dt_days,
                    },
                };
                *texel = update_texel(*texel, input, params);
            });
    }

    /// The water books over the grid.
    #[must_use]
    pub fn totals(&self) -> CoverTotals {
        let area = f64::from(self.frame.texel_area_m2());
        self.texels
            .iter()
            .fold(CoverTotals::default(), |acc, t| CoverTotals {
                deposited_kg: acc.deposited_kg + f64::from(t.deposited_mm) * area,
                swe_kg: acc.swe_kg + f64::from(t.swe_mm) * area,
                liquid_kg: acc.liquid_kg + f64::from(t.liquid_mm) * area,
                runoff_kg: acc.runoff_kg + f64::from(t.runoff_mm) * area,
            })
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

#[cfg(test)]
mod tests {
    use glam::{UVec2, Vec2};

    use super::*;
    use crate::masks::generate_threshold_masks;

    fn grid(n: u32, feed: CoverFeed) -> CoverGrid {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(n));
        let masks = generate_threshold_masks(&frame, 3, 12.0);
        let count = frame.texel_count();
        CoverGrid::new(frame, &vec![1.0; count], &masks, &vec![feed; count]).expect("valid")
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
            g.step(&mut deposits, 2.0, 0.0, -5.0, 0.01, &params);
        }
        let a_s = crate::shading::accumulated_fraction(&g.texels[0], &params);
        let alpha: Vec<f32> = g.shading(&params).iter().map(|s| s.snow_alpha).collect();
        let covered = alpha.iter().filter(|&&a| a > 0.99).count() as f32 / alpha.len() as f32;
        let bare = alpha.iter().filter(|&&a| a < 0.01).count() as f32 / alpha.len() as f32;
        assert!(
            (covered - a_s).abs() < 0.08,
            "covered {covered} vs A_S {a_s}"
        );
        assert!(
            covered + bare > 0.85,
            "patches are either covered or bare: {covered} + {bare}"
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
        particles.step(&mut d1, 10.0, 0.0, -5.0, 0.1, &params);
        rate.step(&mut d2, 10.0, 0.0, -5.0, 0.1, &params);
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
}
