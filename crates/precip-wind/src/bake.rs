//! Baking Perlin noise into periodic wind texels.

use glam::Vec3;
use noise::{Fbm, MultiFractal, NoiseFn, Perlin};
use rayon::prelude::*;

use crate::field::WindField;
use crate::volume::{WindTexel, WindVolumeSpec};

/// Fractal Perlin noise made periodic over `period_m` by blending shifted copies.
struct PeriodicNoise {
    fbm: Fbm<Perlin>,
    period_m: Vec3,
}

impl PeriodicNoise {
    fn new(seed: u32, field: &WindField, period_m: Vec3) -> Self {
        let fbm = Fbm::<Perlin>::new(seed)
            .set_octaves(field.octaves as usize)
            .set_frequency(1.0 / f64::from(field.noise_scale_m));
        Self { fbm, period_m }
    }

    /// Periodic noise in about `[-1, 1]` at `p` (inside one period).
    ///
    /// `Σ_c w_c·f(p − c⊙L) / sqrt(Σ_c w_c²)` over the eight corners `c ∈ {0,1}³`, with
    /// trilinear weights in `t = p / L`: at `t → 1` all weight moves to the copy that
    /// `t = 0` reads, so the function wraps continuously; the root normalisation keeps
    /// the blend's spread close to the noise's own.
    fn sample(&self, p: Vec3) -> f32 {
        let t = p / self.period_m;
        let mut sum = 0.0f64;
        let mut sum_w2 = 0.0f64;
        for corner in 0..8u32 {
            let c = Vec3::new(
                (corner & 1) as f32,
                ((corner >> 1) & 1) as f32,
                ((corner >> 2) & 1) as f32,
            );
            let w3 = Vec3::ONE - c + (2.0 * c - Vec3::ONE) * t;
            let w = f64::from(w3.x * w3.y * w3.z);
            if w == 0.0 {
                continue;
            }
            let q = p - c * self.period_m;
            sum += w * self
                .fbm
                .get([f64::from(q.x), f64::from(q.y), f64::from(q.z)]);
            sum_w2 += w * w;
        }
        (sum / sum_w2.sqrt()) as f32
    }
}

/// Bakes every texel of the volume: `sin α` with `α = π·clamp((n + 1)/2, 0, 1)` and the
/// vertical gust `w = vertical_gust_mps · clamp(n_v, -1, 1)`, two independent noises.
pub(crate) fn bake_texels(field: &WindField, spec: &WindVolumeSpec) -> Vec<WindTexel> {
    let phase_noise = PeriodicNoise::new(field.seed, field, spec.extent_m);
    let vertical_noise =
        PeriodicNoise::new(field.seed.wrapping_add(0x9E37_79B9), field, spec.extent_m);
    let cell = spec.cell_m();
    let (nx, ny) = (spec.texels.x as usize, spec.texels.y as usize);
    (0..spec.texel_count())
        .into_par_iter()
        .map(|index| {
            let i = index % nx;
            let j = (index / nx) % ny;
            let k = index / (nx * ny);
            let centre = (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * cell;
            let alpha =
                std::f32::consts::PI * (0.5 * (phase_noise.sample(centre) + 1.0)).clamp(0.0, 1.0);
            let vertical = field.vertical_gust_mps * vertical_noise.sample(centre).clamp(-1.0, 1.0);
            WindTexel {
                sin_alpha: alpha.sin().clamp(0.0, 1.0),
                vertical_mps: vertical,
                reserved: [0.0; 2],
            }
        })
        .collect()
}
