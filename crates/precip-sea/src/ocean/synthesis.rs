//! The sea's surface from its spectrum (Tessendorf 2001; docs/model.md (13.7)): on a
//! square patch `L` m wide of `N × N` points that tiles, the amplitude of each
//! wavenumber `k = 2π·(i, j)/L` is drawn once, `h₀(k) = (ξ₁ + iξ₂)·√(F(k)·Δk²/4)`
//! (`ξ` standard normal, `Δk = 2π/L`), and at time `t`
//! `h̃(k, t) = h₀(k)·e^(−iωt) + conj(h₀(−k))·e^(iωt)` (`ω` the dispersion
//! relation; Tessendorf's signs swapped so a wave of `k` runs toward `+k`):
//! Hermitian, so its inverse transform is the real surface. The choppy
//! displacement `D̃ = i·k/|k|·h̃` moves each point toward the crest ahead of it (a
//! Gerstner wave's `x₀ − k̂·A·sin θ` for `h = A·cos θ`: sharp crests, flat troughs;
//! Tessendorf's `−i` with a positive λ sharpens the troughs instead); where the
//! surface folds, at the crests, the Jacobian of `x + λ·D` falls below 1 and foam is
//! whipped up.

use super::fft::{Complex, inverse_2d};
use super::spectrum::{WindSea, dispersion_rad_per_s};

/// One patch of the sea: its drawn amplitudes and their frequencies.
#[derive(Debug, Clone)]
pub struct OceanCascade {
    /// Points along each side (a power of two).
    pub n: usize,
    /// The patch's side, m.
    pub size_m: f32,
    /// `h₀(k)` at each point of the wavenumber grid (FFT order: index `i` is
    /// wavenumber `i` for `i < N/2`, `i − N` beyond).
    amplitudes: Vec<Complex>,
    /// `ω(k)`, rad/s.
    frequencies: Vec<f32>,
}

/// The sea's surface over a patch at one time: heights, choppy displacements and the
/// Jacobian of the displaced surface, `N × N` row by row (x fastest).
#[derive(Debug, Clone, PartialEq)]
pub struct OceanSurface {
    /// Elevation above the still level, m.
    pub height_m: Vec<f32>,
    /// Horizontal displacement along x, m (times the choppiness λ to apply).
    pub displacement_x_m: Vec<f32>,
    /// Horizontal displacement along z, m.
    pub displacement_z_m: Vec<f32>,
    /// The Jacobian of `x + λ·D` with the λ asked for: below 0 the surface folds.
    pub jacobian: Vec<f32>,
    /// The slope `∂h/∂x` (of the undisplaced surface: the normal's tilt).
    pub slope_x: Vec<f32>,
    /// The slope `∂h/∂z`.
    pub slope_z: Vec<f32>,
}

impl OceanCascade {
    /// A patch of `n × n` points `size_m` wide of `sea` over water `depth_m` deep,
    /// its amplitudes drawn from `seed`. `None` if `n` is not a power of two of at
    /// least 4 or the size is not finite and positive.
    #[must_use]
    pub fn new(sea: &WindSea, n: usize, size_m: f32, depth_m: f32, seed: u32) -> Option<Self> {
        Self::banded(sea, n, size_m, depth_m, seed, (0.0, f32::INFINITY))
    }

    /// As [`OceanCascade::new`], holding only the wavenumbers `|k|` in
    /// `[band.0, band.1)` rad/m (one cascade of several:
    /// [`super::cascades::cascade_band_per_m`]). WGSL twin: `sea_amplitude`.
    #[must_use]
    pub fn banded(
        sea: &WindSea,
        n: usize,
        size_m: f32,
        depth_m: f32,
        seed: u32,
        band: (f32, f32),
    ) -> Option<Self> {
        if !(n >= 4 && n.is_power_of_two() && size_m.is_finite() && size_m > 0.0) {
            return None;
        }
        let dk = std::f32::consts::TAU / size_m;
        let mut amplitudes = Vec::with_capacity(n * n);
        let mut frequencies = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                let (kx, kz) = (wavenumber(i, n) * dk, wavenumber(j, n) * dk);
                // The Nyquist lines hold no wave: a wavenumber there is its own
                // mirror, so its choppy and slope fields (i·k·h̃) would not be real.
                let nyquist = i == n / 2 || j == n / 2;
                amplitudes.push(if nyquist {
                    Complex::default()
                } else {
                    amplitude(sea, [kx, kz], dk, band, seed, (j * n + i) as u32)
                });
                frequencies.push(dispersion_rad_per_s(kx.hypot(kz), depth_m));
            }
        }
        Some(Self {
            n,
            size_m,
            amplitudes,
            frequencies,
        })
    }

    /// `h̃(k, t)` over the wavenumber grid.
    #[must_use]
    pub fn spectrum_at(&self, time_s: f32) -> Vec<Complex> {
        let n = self.n;
        (0..n * n)
            .map(|p| {
                let (i, j) = (p % n, p / n);
                let mirror = ((n - j) % n) * n + (n - i) % n;
                // e^(−iωt) on h₀(k): the wave runs toward +k (downwind).
                let phase = Complex::cis(-self.frequencies[p] * time_s);
                self.amplitudes[p] * phase + self.amplitudes[mirror].conj() * phase.conj()
            })
            .collect()
    }

    /// The surface at `time_s`, its displacements and the Jacobian with the
    /// choppiness `choppiness` (λ; 0: none, 1: Tessendorf's full lean).
    #[must_use]
    pub fn surface_at(&self, time_s: f32, choppiness: f32) -> OceanSurface {
        let n = self.n;
        let dk = std::f32::consts::TAU / self.size_m;
        let h = self.spectrum_at(time_s);
        // Each field's spectrum from h̃: i·k̂·h̃ for the displacements (a point moves
        // toward the crest ahead of it, as a Gerstner wave's: x₀ − k̂·A·sin θ for
        // h = A·cos θ), −k_a·k_b/|k|·h̃ for their derivatives.
        let field = |f: &dyn Fn(f32, f32, Complex) -> Complex| {
            let mut grid: Vec<Complex> = (0..n * n)
                .map(|p| {
                    let (kx, kz) = (wavenumber(p % n, n) * dk, wavenumber(p / n, n) * dk);
                    f(kx, kz, h[p])
                })
                .collect();
            inverse_2d(&mut grid, n);
            grid.iter().map(|c| c.re).collect::<Vec<f32>>()
        };
        let over_k = |kx: f32, kz: f32| {
            let k = kx.hypot(kz);
            if k > 0.0 { 1.0 / k } else { 0.0 }
        };
        let height_m = field(&|_, _, c| c);
        let displacement_x_m =
            field(&|kx, kz, c| Complex::new(-c.im, c.re).scale(kx * over_k(kx, kz)));
        let displacement_z_m =
            field(&|kx, kz, c| Complex::new(-c.im, c.re).scale(kz * over_k(kx, kz)));
        let slope_x = field(&|kx, _, c| Complex::new(-c.im, c.re).scale(kx));
        let slope_z = field(&|_, kz, c| Complex::new(-c.im, c.re).scale(kz));
        let dxx = field(&|kx, kz, c| c.scale(-kx * kx * over_k(kx, kz)));
        let dzz = field(&|kx, kz, c| c.scale(-kz * kz * over_k(kx, kz)));
        let dxz = field(&|kx, kz, c| c.scale(-kx * kz * over_k(kx, kz)));
        let jacobian = (0..n * n)
            .map(|p| {
                (1.0 + choppiness * dxx[p]) * (1.0 + choppiness * dzz[p])
                    - choppiness * choppiness * dxz[p] * dxz[p]
            })
            .collect();
        OceanSurface {
            height_m,
            displacement_x_m,
            displacement_z_m,
            jacobian,
            slope_x,
            slope_z,
        }
    }
}

/// `h₀(k)` of the wavenumber `k` (rad/m) at point `index` of a grid of cells
/// `dk` rad/m wide, 0 outside `band`: `(ξ₁ + iξ₂)·√(F(k)·Δk²/4)` — E|h₀|² = F·Δk²/2,
/// so with its mirror's each wavenumber carries the spectrum's variance over its
/// cell. WGSL twin: `sea_amplitude`.
#[must_use]
pub fn amplitude(
    sea: &WindSea,
    k: [f32; 2],
    dk: f32,
    band: (f32, f32),
    seed: u32,
    index: u32,
) -> Complex {
    let in_band = (band.0..band.1).contains(&k[0].hypot(k[1]));
    let f = if in_band {
        sea.density_m4(k[0], k[1])
    } else {
        0.0
    };
    let (g1, g2) = amplitude_normals(seed, index);
    let scale = (f * dk * dk * 0.25).sqrt();
    Complex::new(g1 * scale, g2 * scale)
}

/// The signed wavenumber index of FFT index `i` of `n`. WGSL twin:
/// `sea_wavenumber`.
#[must_use]
pub fn wavenumber(i: usize, n: usize) -> f32 {
    if i < n / 2 {
        i as f32
    } else {
        i as f32 - n as f32
    }
}

/// The PCG hash (Jarzynski & Olano 2020): `precip_model::particles::rng::pcg_hash`
/// (whose WGSL the GPU's draws use), copied here so this crate stays free of the
/// model's.
pub(crate) const fn hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// Two independent standard normal numbers for point `index` of `seed` (Box–Muller
/// over PCG hashes): the amplitudes' draws. WGSL twin: `sea_normal_pair`.
#[must_use]
pub fn amplitude_normals(seed: u32, index: u32) -> (f32, f32) {
    let a = hash(hash(seed) ^ index);
    let b = hash(a ^ 0x9e37_79b9);
    let u1 = ((a >> 8) as f32 + 0.5) / 16_777_216.0;
    let u2 = (b >> 8) as f32 / 16_777_216.0;
    let r = (-2.0 * u1.ln()).sqrt();
    let t = std::f32::consts::TAU * u2;
    (r * t.cos(), r * t.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn jonswap(wind: f32) -> WindSea {
        WindSea {
            shortest_m: 0.5,
            ..WindSea::jonswap(wind, 50_000.0, [0.8, 0.6])
        }
    }

    /// The variance of `field` in the annulus of wavenumber indices `[lo, hi)`: its
    /// forward transform's energy there (the forward transform by the inverse of
    /// the conjugate).
    fn band_variance(field: &[f32], n: usize, lo: f32, hi: f32) -> f32 {
        let mut grid: Vec<Complex> = field.iter().map(|&v| Complex::new(v, 0.0)).collect();
        inverse_2d(&mut grid, n);
        let scale = 1.0 / (n * n) as f32;
        (0..n * n)
            .filter(|p| {
                let k = wavenumber(p % n, n).hypot(wavenumber(p / n, n));
                (lo..hi).contains(&k)
            })
            .map(|p| {
                let c = grid[p].scale(scale);
                c.re * c.re + c.im * c.im
            })
            .sum()
    }

    #[test]
    fn the_surface_carries_the_spectrum_s_energy_in_every_band() {
        // A 15 m/s wind over 50 km, a 512 m patch of 256²: each octave of
        // wavenumbers holds the spectrum's variance there within 10 %.
        let sea = jonswap(15.0);
        let (n, size) = (256usize, 512.0f32);
        let cascade = OceanCascade::new(&sea, n, size, f32::INFINITY, 7).expect("valid");
        let surface = cascade.surface_at(3.0, 1.0);
        let dk = std::f32::consts::TAU / size;
        for (lo, hi) in [(8.0f32, 16.0f32), (16.0, 32.0), (32.0, 64.0), (64.0, 128.0)] {
            let got = band_variance(&surface.height_m, n, lo, hi);
            let want = sea.variance_m2(lo * dk, hi * dk);
            println!("k {lo}–{hi}·Δk: {got:.4e} m² against the spectrum's {want:.4e}");
            assert!(
                (got / want - 1.0).abs() < 0.1,
                "{lo}–{hi}: {got} against {want}"
            );
        }
        // The whole patch: mean 0, variance the spectrum's over the patch's
        // wavenumbers.
        let m = surface.height_m.iter().sum::<f32>() / (n * n) as f32;
        assert!(m.abs() < 1e-3, "{m}");
    }

    #[test]
    fn the_chop_sharpens_the_crests_and_folds_them_first() {
        // One wave: the Jacobian is least at its crest (the points crowd there) and
        // greatest at its trough, and the points beside a crest move toward it.
        let (n, size) = (64usize, 256.0f32);
        let mut cascade =
            OceanCascade::new(&jonswap(10.0), n, size, f32::INFINITY, 1).expect("valid");
        for (p, a) in cascade.amplitudes.iter_mut().enumerate() {
            *a = if p == 4 {
                Complex::new(0.5, 0.0)
            } else {
                Complex::default()
            };
        }
        let s = cascade.surface_at(0.0, 1.0);
        let row = |v: &[f32]| v[..n].to_vec();
        let (h, j, d) = (row(&s.height_m), row(&s.jacobian), row(&s.displacement_x_m));
        // (The patch holds four wavelengths: the crests tie.)
        let crest = (0..n).max_by(|&a, &b| h[a].total_cmp(&h[b])).unwrap_or(0);
        let least = (0..n).min_by(|&a, &b| j[a].total_cmp(&j[b])).unwrap_or(0);
        let most = (0..n).max_by(|&a, &b| j[a].total_cmp(&j[b])).unwrap_or(0);
        let top = h[crest];
        assert!(
            (h[least] - top).abs() < 1e-4 * top.abs(),
            "crest {h:?} {j:?}"
        );
        assert!(
            (h[most] + top).abs() < 1e-4 * top.abs(),
            "trough {h:?} {j:?}"
        );
        // A quarter wavelength behind the crest (x smaller) a point moves +x, ahead
        // of it −x.
        let quarter = n / 16;
        assert!(
            d[(crest + n - quarter) % n] > 0.0 && d[(crest + quarter) % n] < 0.0,
            "{d:?}"
        );
    }

    #[test]
    fn a_wave_runs_at_the_dispersion_relation_s_phase_speed() {
        // One wave of the patch alone (k = 8·Δk along x): its crest moves at ω/k,
        // downwind (toward +k).
        let (n, size, depth) = (64usize, 256.0f32, 10.0f32);
        let sea = jonswap(10.0);
        let mut cascade = OceanCascade::new(&sea, n, size, depth, 1).expect("valid");
        for (p, a) in cascade.amplitudes.iter_mut().enumerate() {
            *a = if p == 8 {
                Complex::new(0.5, 0.0)
            } else {
                Complex::default()
            };
        }
        let k = 8.0 * std::f32::consts::TAU / size;
        let phase_at = |t: f32| {
            let row = &cascade.surface_at(t, 0.0).height_m[..n];
            let (mut c, mut s) = (0.0f32, 0.0f32);
            for (i, h) in row.iter().enumerate() {
                let x = i as f32 * size / n as f32;
                c += h * (k * x).cos();
                s += h * (k * x).sin();
            }
            s.atan2(c)
        };
        let dt = 0.4;
        let moved = (phase_at(dt) - phase_at(0.0)).rem_euclid(std::f32::consts::TAU);
        // cos(kx − ωt): the crest at x = ωt/k, its phase atan2 advancing by ωt.
        let speed = moved / (k * dt);
        let want = dispersion_rad_per_s(k, depth) / k;
        println!("phase speed {speed:.3} m/s, the dispersion relation's {want:.3} m/s");
        assert!((speed / want - 1.0).abs() < 0.005, "{speed} against {want}");
    }

    #[test]
    fn a_gale_stretches_and_folds_the_surface_more_than_a_breeze() {
        // A 64 m patch of 0.5 m cells (the steep short waves that fold), full chop:
        // the Jacobian's spread about 1 and its least value.
        let stretch = |wind: f32, choppiness: f32| {
            let cascade =
                OceanCascade::new(&jonswap(wind), 128, 64.0, f32::INFINITY, 3).expect("valid");
            let s = cascade.surface_at(0.0, choppiness);
            let n = s.jacobian.len() as f32;
            let mean = s.jacobian.iter().sum::<f32>() / n;
            assert!(
                (mean - 1.0).abs() < 0.02,
                "{wind}: the mean stretch is none ({mean})"
            );
            let spread = (s.jacobian.iter().map(|j| (j - 1.0).powi(2)).sum::<f32>() / n).sqrt();
            (spread, s.jacobian.iter().copied().fold(f32::MAX, f32::min))
        };
        // The short waves' steepness hardly grows with the wind over a fetch (their
        // saturation range); the gale's surface stretches more and folds deeper,
        // and at twice the chop it folds over (J < 0) where the breeze's does not.
        let (breeze, gale) = (stretch(6.0, 1.0), stretch(22.0, 1.0));
        let (breeze2, gale2) = (stretch(6.0, 2.0), stretch(22.0, 2.0));
        println!(
            "the Jacobian's spread and least: {breeze:?} at 6 m/s, {gale:?} at 22 m/s; at λ = 2 {breeze2:?}, {gale2:?}"
        );
        assert!(
            gale.0 > 1.3 * breeze.0 && gale.1 < breeze.1,
            "{breeze:?} {gale:?}"
        );
        assert!(gale2.1 < 0.0 && breeze2.1 > 0.0, "{breeze2:?} {gale2:?}");
        assert!(OceanCascade::new(&jonswap(6.0), 100, 256.0, 10.0, 1).is_none());
    }
}
