//! Raindrops (docs/model.md §2): measured terminal speeds and the Marshall–Palmer size
//! distribution. WGSL twins in `shaders/physics.wgsl`.

use crate::particles::rng::{draw, random_unit};

/// Smallest drop diameter simulated, mm (the Atlas fit turns negative below 0.11).
pub const RAIN_DIAMETER_MIN_MM: f32 = 0.3;
/// Largest drop diameter simulated, mm (larger drops break up).
pub const RAIN_DIAMETER_MAX_MM: f32 = 6.0;
/// Marshall–Palmer intercept N0, m⁻³·mm⁻¹.
pub const MARSHALL_PALMER_N0: f32 = 8000.0;
/// Tries of the flux-weighted rejection draw before the last candidate is kept.
pub const RAIN_DIAMETER_TRIES: u32 = 32;

/// Terminal fall speed of a drop of diameter `diameter_mm`, m/s:
/// `v = 9.65 − 10.3·exp(−0.6·D)` (Atlas et al. 1973), with D clamped to
/// `[0.3, 6]` mm where the fit holds.
#[must_use]
pub fn raindrop_terminal_speed_mps(diameter_mm: f32) -> f32 {
    let d = diameter_mm.clamp(RAIN_DIAMETER_MIN_MM, RAIN_DIAMETER_MAX_MM);
    9.65 - 10.3 * (-0.6 * d).exp()
}

/// Marshall–Palmer slope `Λ = 4.1·R^−0.21`, mm⁻¹, for rain rate `R` mm/h (> 0).
#[must_use]
pub fn marshall_palmer_slope_per_mm(rain_rate_mm_per_h: f32) -> f32 {
    4.1 * rain_rate_mm_per_h.powf(-0.21)
}

/// Drops per m³, `N0/Λ` (0 for no rain).
#[must_use]
pub fn rain_number_density_per_m3(rain_rate_mm_per_h: f32) -> f32 {
    if rain_rate_mm_per_h > 0.0 {
        MARSHALL_PALMER_N0 / marshall_palmer_slope_per_mm(rain_rate_mm_per_h)
    } else {
        0.0
    }
}

/// The rain rate that the Marshall–Palmer spectrum for `R` carries at the Atlas
/// speeds, mm/h: `3.6·10⁻³ · π/6 · ∫ N(D)·D³·v(D) dD` over 0.1–8 mm (Simpson's rule).
/// docs/model.md §7: it recovers `R` within +20 %.
#[must_use]
pub fn rain_rate_from_spectrum_mm_per_h(rain_rate_mm_per_h: f32) -> f64 {
    let slope = f64::from(marshall_palmer_slope_per_mm(rain_rate_mm_per_h));
    let integrand = |d: f64| {
        let v = 9.65 - 10.3 * (-0.6 * d.clamp(0.11, 6.0)).exp();
        f64::from(MARSHALL_PALMER_N0) * (-slope * d).exp() * d.powi(3) * v.max(0.0)
    };
    let (a, b, n) = (0.1f64, 8.0f64, 2000);
    let h = (b - a) / f64::from(n);
    let mut sum = integrand(a) + integrand(b);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        sum += w * integrand(a + f64::from(i) * h);
    }
    3.6e-3 * std::f64::consts::PI / 6.0 * sum * h / 3.0
}

/// A size from an exponential spectrum `e^(−ΛD)` truncated to `[from_mm, to_mm]`,
/// mm: its inverse CDF at `f ∈ [0, 1)`,
/// `D = from − ln(1 − f·(1 − e^(−Λ·(to − from))))/Λ` (drops and hailstones).
#[must_use]
pub fn truncated_exponential_mm(from_mm: f32, to_mm: f32, slope_per_mm: f32, f: f32) -> f32 {
    let span = to_mm - from_mm;
    let tail = 1.0 - (-slope_per_mm * span).exp();
    from_mm - (1.0 - f * tail).ln() / slope_per_mm
}

/// A drop diameter from Marshall–Palmer truncated to `[0.3, 6]` mm, mm
/// ([`truncated_exponential_mm`], `f ∈ [0, 1)`).
#[must_use]
pub fn marshall_palmer_diameter_mm(slope_per_mm: f32, f: f32) -> f32 {
    truncated_exponential_mm(RAIN_DIAMETER_MIN_MM, RAIN_DIAMETER_MAX_MM, slope_per_mm, f)
}

/// A newborn drop's diameter, mm, drawn so that the drops **in the air** follow
/// Marshall–Palmer: a particle slot is re-born once per fall, so fast drops would be
/// over-represented at birth and under-represented aloft; births are therefore drawn
/// from the flux `N(D)·v(D)` by rejection (accept with `v(D)/v(6 mm)`, at most
/// [`RAIN_DIAMETER_TRIES`] tries, then the last candidate). Draws
/// `RAIN_DIAMETER + 2k` (candidate) and `+ 2k + 1` (accept).
#[must_use]
pub fn draw_raindrop_diameter_mm(key: u32, slope_per_mm: f32) -> f32 {
    let v_max = raindrop_terminal_speed_mps(RAIN_DIAMETER_MAX_MM);
    let mut d = RAIN_DIAMETER_MIN_MM;
    for k in 0..RAIN_DIAMETER_TRIES {
        d = marshall_palmer_diameter_mm(
            slope_per_mm,
            random_unit(key, draw::RAIN_DIAMETER + 2 * k),
        );
        if random_unit(key, draw::RAIN_DIAMETER + 2 * k + 1) * v_max
            < raindrop_terminal_speed_mps(d)
        {
            break;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::rng::particle_key;

    #[test]
    fn terminal_speed_matches_gunn_and_kinzer() {
        // Gunn & Kinzer 1949 (docs/model.md §7), within 0.2 m/s for D ≥ 0.6 mm.
        for (d, v) in [
            (1.0, 4.03),
            (2.0, 6.49),
            (3.0, 8.06),
            (4.0, 8.83),
            (5.0, 9.09),
            (5.8, 9.17),
        ] {
            let got = raindrop_terminal_speed_mps(d);
            assert!((got - v).abs() <= 0.2, "D = {d} mm: {got} vs {v}");
        }
        // Clamped outside the fit's range: never negative, never above the plateau.
        assert!(raindrop_terminal_speed_mps(0.01) > 1.0);
        assert!(
            (raindrop_terminal_speed_mps(10.0) - raindrop_terminal_speed_mps(6.0)).abs() < 1e-6
        );
    }

    #[test]
    fn marshall_palmer_totals() {
        for (r, n) in [(1.0, 1951.0), (5.0, 2736.0), (10.0, 3165.0), (25.0, 3836.0)] {
            let got = rain_number_density_per_m3(r);
            assert!((got - n).abs() / n < 0.005, "R = {r}: {got} vs {n}");
        }
        assert!(rain_number_density_per_m3(0.0).abs() < f32::MIN_POSITIVE);
    }

    #[test]
    fn the_spectrum_recovers_the_rain_rate_within_plus_20_percent() {
        for r in [1.0f32, 5.0, 10.0, 25.0, 50.0] {
            let got = rain_rate_from_spectrum_mm_per_h(r);
            let ratio = got / f64::from(r);
            assert!((1.0..=1.2).contains(&ratio), "R = {r}: recovered {got}");
        }
    }

    #[test]
    fn drops_aloft_follow_marshall_palmer() {
        // Weight each birth by its fall time 1/v (time spent aloft): the airborne mean
        // diameter must be the truncated exponential's mean.
        let slope = marshall_palmer_slope_per_mm(5.0);
        let n = 200_000;
        let (mut weighted, mut weights) = (0.0f64, 0.0f64);
        for i in 0..n {
            let d = draw_raindrop_diameter_mm(particle_key(3, i, 0), slope);
            assert!((RAIN_DIAMETER_MIN_MM..=RAIN_DIAMETER_MAX_MM).contains(&d));
            let w = 1.0 / f64::from(raindrop_terminal_speed_mps(d));
            weighted += w * f64::from(d);
            weights += w;
        }
        let airborne_mean = weighted / weights;
        let (a, b, l) = (
            f64::from(RAIN_DIAMETER_MIN_MM),
            f64::from(RAIN_DIAMETER_MAX_MM),
            f64::from(slope),
        );
        let expected = a + 1.0 / l - (b - a) * (-l * (b - a)).exp() / (1.0 - (-l * (b - a)).exp());
        assert!(
            (airborne_mean - expected).abs() / expected < 0.02,
            "{airborne_mean} vs {expected}"
        );
    }
}
