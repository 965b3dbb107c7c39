//! The seed's two threshold masks (T_M.g accumulation, T_M.r melt), generated from
//! Perlin noise over the cover grid.
//!
//! Each mask value is the fraction of coverage (or of melt) at which its texel turns
//! covered (or bare). The noise is rank-transformed to a uniform distribution, so when
//! `A_S` of the snow has accumulated, almost exactly a fraction `A_S` of the texels is
//! covered, in spatially coherent patches. The melt mask is anti-correlated with the
//! accumulation mask (the patches covered last melt first), plus noise of its own.

use noise::{Fbm, MultiFractal, NoiseFn, Perlin};
use rayon::prelude::*;

use crate::frame::GridFrame;

/// Both masks, one value per texel of the grid, each in `(0, 1)`.
#[derive(Debug, Clone, PartialEq)]
pub struct ThresholdMasks {
    /// T_M.g per texel.
    pub accumulation: Vec<f32>,
    /// T_M.r per texel.
    pub melt: Vec<f32>,
}

/// Generates the masks for `frame`, with patches about `patch_scale_m` across.
#[must_use]
pub fn generate_threshold_masks(
    frame: &GridFrame,
    seed: u32,
    patch_scale_m: f32,
) -> ThresholdMasks {
    let frequency = 1.0 / f64::from(patch_scale_m.max(1.0e-3));
    let coarse = Fbm::<Perlin>::new(seed)
        .set_octaves(4)
        .set_frequency(frequency);
    let own = Fbm::<Perlin>::new(seed.wrapping_add(0x85EB_CA6B))
        .set_octaves(3)
        .set_frequency(2.0 * frequency);
    // Each texel's noise on its own, in parallel (made at configure and again at
    // each move of a grid that follows the camera).
    let (raw_g, raw_r): (Vec<f64>, Vec<f64>) = (0..frame.texel_count())
        .into_par_iter()
        .map(|index| {
            let c = frame.texel_centre(index);
            let p = [f64::from(c.x), f64::from(c.y)];
            let g = coarse.get(p);
            (g, -g + 0.5 * own.get(p))
        })
        .unzip();
    ThresholdMasks {
        accumulation: rank_uniform(&raw_g),
        melt: rank_uniform(&raw_r),
    }
}

/// Replaces each value by `(rank + 0.5) / n`: a uniform distribution, same order.
fn rank_uniform(values: &[f64]) -> Vec<f32> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    // A total order (ties by index): the same ranks on any thread count.
    order.par_sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
    let n = values.len() as f64;
    let mut out = vec![0.0f32; values.len()];
    for (rank, &index) in order.iter().enumerate() {
        out[index] = ((rank as f64 + 0.5) / n) as f32;
    }
    out
}

#[cfg(test)]
mod tests {
    use glam::{UVec2, Vec2};

    use super::*;

    #[test]
    fn masks_are_uniform_coherent_and_seeded() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(100.0), UVec2::splat(64));
        let m = generate_threshold_masks(&frame, 1, 20.0);
        let below_half = m.accumulation.iter().filter(|&&g| g < 0.5).count();
        assert_eq!(below_half, frame.texel_count() / 2);
        // Neighbours are close (patches), unlike a shuffled mask.
        let nx = 64;
        let mean_step: f32 = (0..frame.texel_count() - 1)
            .filter(|i| i % nx != nx - 1)
            .map(|i| (m.accumulation[i + 1] - m.accumulation[i]).abs())
            .sum::<f32>()
            / (63.0 * 64.0);
        assert!(
            mean_step < 0.12,
            "mean neighbour step {mean_step} (random would be ~0.33)"
        );
        assert_eq!(m, generate_threshold_masks(&frame, 1, 20.0));
        assert_ne!(m, generate_threshold_masks(&frame, 2, 20.0));
    }
}
