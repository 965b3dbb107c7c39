//! Wind-wave spectra (docs/model.md (13.5)–(13.6)): how the wind's energy is spread
//! over the waves' wavenumbers.

use crate::GRAVITY_MPS2 as G;

/// The dispersion relation of surface gravity waves on water `depth_m` deep:
/// `ω = √(g·k·tanh(k·d))`, rad/s (deep water: `√(g·k)`).
#[must_use]
pub fn dispersion_rad_per_s(k_per_m: f32, depth_m: f32) -> f32 {
    (G * k_per_m * (k_per_m * depth_m).min(20.0).tanh()).sqrt()
}

/// `dω/dk` of [`dispersion_rad_per_s`] in deep water: `g/(2ω)`, m/s (the group
/// speed).
#[must_use]
pub fn deep_group_speed_mps(k_per_m: f32) -> f32 {
    0.5 * G / dispersion_rad_per_s(k_per_m, f32::INFINITY).max(1.0e-6)
}

/// Tessendorf's Phillips amplitude `A` that gives the fully developed sea of
/// Pierson & Moskowitz 1964: `H_s = 0.21·U²/g`. The spectrum's variance is
/// `A·π·L²/2` (`L = U²/g`; `∫ e^(−1/(kL)²)/k³ dk = L²/2`), so
/// `A = 2·(0.21/4)²/π`.
pub const PHILLIPS_AMPLITUDE: f32 = 2.0 * (0.21 / 4.0) * (0.21 / 4.0) / std::f32::consts::PI;

/// Which spectrum a sea follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpectrumKind {
    /// Phillips (Tessendorf 2001): a fully developed sea of the wind's speed,
    /// `P(k) = A·e^(−1/(kL)²)/k⁴·|k̂·ŵ|²`, `L = U²/g` (the short waves rolled off by
    /// `e^(−(k·ℓ/2π)²)`, `ℓ` = [`WindSea::shortest_m`], as every spectrum here).
    Phillips {
        /// Tessendorf's amplitude `A` (dimensionless; 8.1·10⁻³ is Phillips's
        /// constant).
        amplitude: f32,
    },
    /// JONSWAP (Hasselmann et al. 1973): a sea growing over a fetch,
    /// `S(ω) = α·g²/ω⁵·e^(−5/4·(ω_p/ω)⁴)·γ^r`, spread over directions by
    /// `cos²ˢ(θ/2)`.
    Jonswap {
        /// The distance the wind has blown over open water, m.
        fetch_m: f32,
        /// The peak enhancement γ (3.3 the mean of the experiment).
        peak_enhancement: f32,
    },
}

/// A wind sea: its spectrum, the wind 10 m above the water and where it blows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindSea {
    /// The spectrum.
    pub kind: SpectrumKind,
    /// The wind's speed 10 m above the water, m/s.
    pub wind_speed_mps: f32,
    /// The direction it blows toward, a unit vector on the water (x, z).
    pub wind_direction: [f32; 2],
    /// Waves shorter than this are left out (capillaries, and the cascade's
    /// aliasing), m.
    pub shortest_m: f32,
}

impl WindSea {
    /// A JONSWAP sea (γ = 3.3) of a wind `wind_mps` blowing toward `direction` over
    /// `fetch_m`, every wave length kept.
    #[must_use]
    pub const fn jonswap(wind_mps: f32, fetch_m: f32, direction: [f32; 2]) -> Self {
        Self {
            kind: SpectrumKind::Jonswap {
                fetch_m,
                peak_enhancement: 3.3,
            },
            wind_speed_mps: wind_mps,
            wind_direction: direction,
            shortest_m: 0.0,
        }
    }

    /// The spectrum's density over the wavenumber plane at `(kx, kz)`, m⁴ (so that
    /// `∫∫ F dk_x dk_z` is the surface's variance, m²).
    #[must_use]
    pub fn density_m4(&self, kx: f32, kz: f32) -> f32 {
        let k = kx.hypot(kz);
        if k <= 0.0 {
            return 0.0;
        }
        let cut = (-(k * self.shortest_m / std::f32::consts::TAU).powi(2)).exp();
        let (wx, wz) = (self.wind_direction[0], self.wind_direction[1]);
        let cos = (kx * wx + kz * wz) / k;
        match self.kind {
            SpectrumKind::Phillips { amplitude } => {
                let l = self.wind_speed_mps * self.wind_speed_mps / G;
                // Tessendorf's P(k) is the variance density over the wavenumber
                // plane; its waves run both with and against the wind (|k̂·ŵ|²).
                amplitude * (-1.0 / (k * l).powi(2)).exp() / k.powi(4) * cos * cos * cut
            }
            SpectrumKind::Jonswap {
                fetch_m,
                peak_enhancement,
            } => {
                let omega = dispersion_rad_per_s(k, f32::INFINITY);
                let s_omega = jonswap_rad(omega, self.wind_speed_mps, fetch_m, peak_enhancement);
                let spread = directional_spreading(cos, SPREADING_EXPONENT);
                // S(ω)·D(θ) over (ω, θ) → over (k_x, k_z): dω/dk / k.
                s_omega * spread * deep_group_speed_mps(k) / k * cut
            }
        }
    }

    /// The surface's variance, m² (`∫∫` of [`WindSea::density_m4`] over a polar
    /// grid of wavenumbers up to `k_max`).
    #[must_use]
    pub fn variance_m2(&self, k_min: f32, k_max: f32) -> f32 {
        let (nk, nt) = (2_000, 180);
        let (lo, hi) = (k_min.max(1.0e-5).ln(), k_max.ln());
        let dl = (hi - lo) / nk as f32;
        let dt = std::f32::consts::TAU / nt as f32;
        let mut sum = 0.0f64;
        for a in 0..nk {
            let k = (lo + (a as f32 + 0.5) * dl).exp();
            for b in 0..nt {
                let theta = (b as f32 + 0.5) * dt;
                let f = self.density_m4(k * theta.cos(), k * theta.sin());
                // dk_x dk_z = k dk dθ = k² d(ln k) dθ.
                sum += f64::from(f * k * k * dl * dt);
            }
        }
        sum as f32
    }

    /// The significant wave height `H_s = 4·√(variance)`, m.
    #[must_use]
    pub fn significant_height_m(&self, k_min: f32, k_max: f32) -> f32 {
        4.0 * self.variance_m2(k_min, k_max).sqrt()
    }
}

/// The exponent `s` of the spreading `cos²ˢ(θ/2)` (Mitsuyasu et al. 1975 give
/// `s` of 10 and more near the peak of a young sea; 5 a broad wind sea).
pub const SPREADING_EXPONENT: f32 = 5.0;

/// The directional spreading `D(θ) = N·cos²ˢ(θ/2)` (Longuet-Higgins, Cartwright &
/// Smith 1963), `cos θ` from the wind, normalised so `∫ D dθ = 1` over the circle.
#[must_use]
pub fn directional_spreading(cos_theta: f32, s: f32) -> f32 {
    // cos²(θ/2) = (1 + cos θ)/2; N = Γ(s + 1)² / (2π·Γ(2s + 1))·2^(2s).
    let half = (0.5 * (1.0 + cos_theta.clamp(-1.0, 1.0))).max(0.0);
    let norm = gamma_ratio(s) * 2f32.powf(2.0 * s) / std::f32::consts::TAU;
    norm * half.powf(s)
}

/// `Γ(s + 1)²/Γ(2s + 1)` by the log-gamma of Stirling's series (s ≥ 0).
fn gamma_ratio(s: f32) -> f32 {
    (2.0 * ln_gamma(f64::from(s) + 1.0) - ln_gamma(2.0 * f64::from(s) + 1.0)).exp() as f32
}

/// `ln Γ(x)` for `x > 0` (Lanczos, g = 7, n = 9: 15 digits).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * std::f64::consts::TAU.ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// The share of the sea's surface covered by whitecaps in a wind of `wind_mps` 10 m
/// above it: `W = 3.84·10⁻⁶·U^3.41` (Monahan & O'Muircheartaigh 1980), at most 1.
#[must_use]
pub fn whitecap_cover(wind_mps: f32) -> f32 {
    (3.84e-6 * wind_mps.max(0.0).powf(3.41)).min(1.0)
}

/// The frequency spectrum of a sea, `S(ω) = ∫ F(k)·k dθ · dk/dω` in deep water,
/// m²·s/rad: [`jonswap_rad`] for JONSWAP, Phillips's over its directions.
#[must_use]
pub fn frequency_spectrum_rad(sea: &WindSea, omega: f32) -> f32 {
    if omega <= 0.0 {
        return 0.0;
    }
    let k = omega * omega / G;
    let n = 90;
    let dt = std::f32::consts::TAU / n as f32;
    let around: f32 = (0..n)
        .map(|i| {
            let t = (i as f32 + 0.5) * dt;
            sea.density_m4(k * t.cos(), k * t.sin())
        })
        .sum::<f32>()
        * dt;
    // dk/dω = 1/c_g.
    around * k / deep_group_speed_mps(k)
}

/// JONSWAP's peak frequency for a wind `wind_mps` over `fetch_m`:
/// `ω_p = 22·(g²/(U·F))^(1/3)`, rad/s.
#[must_use]
pub fn jonswap_peak_rad_per_s(wind_mps: f32, fetch_m: f32) -> f32 {
    22.0 * (G * G / (wind_mps * fetch_m)).cbrt()
}

/// The fetch over which a wind `wind_mps` raises a fully developed sea, m: where
/// JONSWAP's peak falls to Pierson & Moskowitz's `ω_p = 0.877·g/U` (1964), at
/// `F = (22/0.877)³·U²/g ≈ 1.6·10⁴·U²/g`. Beyond it the sea grows no more: a longer
/// fetch is taken as this one (JONSWAP's fetch laws would raise it without end).
#[must_use]
pub fn fully_developed_fetch_m(wind_mps: f32) -> f32 {
    (22.0f32 / 0.877).powi(3) * wind_mps * wind_mps / G
}

/// The JONSWAP frequency spectrum `S(ω)`, m²·s/rad.
#[must_use]
pub fn jonswap_rad(omega: f32, wind_mps: f32, fetch_m: f32, peak_enhancement: f32) -> f32 {
    if omega <= 0.0 || wind_mps <= 0.0 || fetch_m <= 0.0 {
        return 0.0;
    }
    let alpha = 0.076 * (wind_mps * wind_mps / (fetch_m * G)).powf(0.22);
    let peak = jonswap_peak_rad_per_s(wind_mps, fetch_m);
    let sigma = if omega <= peak { 0.07 } else { 0.09 };
    let r = (-(omega - peak).powi(2) / (2.0 * sigma * sigma * peak * peak)).exp();
    alpha * G * G / omega.powi(5)
        * (-1.25 * (peak / omega).powi(4)).exp()
        * peak_enhancement.powf(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deep_water_waves_of_100_m_run_at_12_5_m_per_s() {
        let k = std::f32::consts::TAU / 100.0;
        let c = dispersion_rad_per_s(k, f32::INFINITY) / k;
        assert!((c - 12.49).abs() < 0.01, "{c}");
        // In shallow water, √(g·d) whatever the length.
        let c = dispersion_rad_per_s(1.0e-3, 2.0) / 1.0e-3;
        assert!((c - (G * 2.0).sqrt()).abs() < 1e-3, "{c}");
    }

    #[test]
    fn the_spreading_integrates_to_one_and_points_downwind() {
        for s in [1.0f32, 5.0, 15.0] {
            let n = 3_600;
            let sum: f32 = (0..n)
                .map(|i| {
                    let t = (i as f32 + 0.5) / n as f32 * std::f32::consts::TAU;
                    directional_spreading(t.cos(), s) * std::f32::consts::TAU / n as f32
                })
                .sum();
            assert!((sum - 1.0).abs() < 1e-3, "{s}: {sum}");
            assert!(directional_spreading(1.0, s) > directional_spreading(0.0, s));
            assert!(directional_spreading(-1.0, s) < 1e-6);
        }
    }

    #[test]
    fn jonswap_grows_with_the_fetch_as_the_experiment_found() {
        // JONSWAP's fetch laws: g·H_s/U² = 1.6·10⁻³·(g·F/U²)^½ and the peak
        // ω_p = 22·(g²/(U·F))^⅓. The parametric spectrum (its α and ω_p fitted
        // apart from the energy) carries 20–25 % more height than the energy law:
        // within 30 %.
        for (u, fetch) in [(10.0f32, 20_000.0f32), (20.0, 100_000.0), (15.0, 50_000.0)] {
            let sea = WindSea::jonswap(u, fetch, [1.0, 0.0]);
            let hs = sea.significant_height_m(1.0e-4, 50.0);
            let law = 1.6e-3 * (G * fetch / (u * u)).sqrt() * u * u / G;
            println!("U {u} m/s over {fetch} m: Hs {hs:.2} m, fetch law {law:.2} m");
            assert!(hs > law && hs < 1.3 * law, "{hs} against {law}");
            // The spectrum's peak lies at ω_p.
            let peak = jonswap_peak_rad_per_s(u, fetch);
            let top = (1..2_000)
                .map(|i| i as f32 * 0.002)
                .max_by(|a, b| {
                    jonswap_rad(*a, u, fetch, 3.3).total_cmp(&jonswap_rad(*b, u, fetch, 3.3))
                })
                .unwrap_or(0.0);
            assert!((top / peak - 1.0).abs() < 0.01, "{top} against {peak}");
        }
    }

    #[test]
    fn whitecaps_cover_more_of_the_sea_as_the_wind_rises() {
        // Monahan & O'Muircheartaigh's fit: 0.2 % at 6 m/s, 14 % at 22 m/s.
        assert!(
            (whitecap_cover(6.0) - 0.0017).abs() < 2e-4,
            "{}",
            whitecap_cover(6.0)
        );
        assert!(
            (whitecap_cover(22.0) - 0.14).abs() < 0.01,
            "{}",
            whitecap_cover(22.0)
        );
        assert!(whitecap_cover(0.0) == 0.0 && whitecap_cover(80.0) <= 1.0);
    }

    #[test]
    fn the_frequency_spectrum_is_jonswap_s_over_its_directions() {
        let sea = WindSea::jonswap(12.0, 30_000.0, [1.0, 0.0]);
        for omega in [0.8f32, 1.2, 2.0] {
            let got = frequency_spectrum_rad(&sea, omega);
            let want = jonswap_rad(omega, 12.0, 30_000.0, 3.3);
            assert!(
                (got / want - 1.0).abs() < 0.01,
                "{omega}: {got} against {want}"
            );
        }
    }

    #[test]
    fn a_gale_raises_the_sea_to_pierson_and_moskowitz_s_height() {
        let sea = |u: f32| WindSea {
            kind: SpectrumKind::Phillips {
                amplitude: PHILLIPS_AMPLITUDE,
            },
            wind_speed_mps: u,
            wind_direction: [0.6, 0.8],
            shortest_m: 0.0,
        };
        let calm = sea(5.0).significant_height_m(1.0e-4, 50.0);
        let gale = sea(20.0).significant_height_m(1.0e-4, 50.0);
        // L = U²/g: the height grows as U².
        println!("Phillips: Hs {calm:.2} m at 5 m/s, {gale:.2} m at 20 m/s");
        assert!((gale / calm / 16.0 - 1.0).abs() < 0.05, "{calm} {gale}");
        let pm = 0.21 * 400.0 / G;
        assert!((gale / pm - 1.0).abs() < 0.05, "{gale} against {pm}");
    }
}
