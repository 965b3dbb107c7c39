//! Hail (docs/model.md §2, (2.16)–(2.19)): stones of 5–50 mm, their measured fall
//! speeds and their exponential size spectrum. WGSL twins in `shaders/physics.wgsl`.
//!
//! The spectrum is `N(D) = N0·e^(−Λ·D)` over the hail sizes (the AMS glossary's
//! hail is 5 mm and up), `Λ` from Cheng & English's diagnostic `N0 = 115·Λ^3.63`
//! (1983, *J. Atmos. Sci.* 40, 204–213: over many hailfalls, fewer stones come
//! with larger ones) solved for the weather's rate, and `N0` then from the rate
//! itself, so the spectrum carries exactly the water the weather gives: a light
//! hailfall is all pea-sized (a median of 5.5 mm at 1 mm/h, 7 mm at 20 mm/h), the
//! heaviest Cheng & English's spectra hold (≈ 38.5 mm/h of water) a median of 11 mm
//! with one stone in twenty past 29 mm. Heavier rates keep that spectrum with more
//! stones.

use crate::particles::rng::{draw, random_unit};
use crate::physics::raindrop::truncated_exponential_mm;

/// Smallest hailstone, mm (hail is 5 mm and up; smaller is graupel).
pub const HAIL_DIAMETER_MIN_MM: f32 = 5.0;
/// Largest hailstone simulated, mm (a hen's egg; larger stones are rare enough to
/// leave out of a rate's spectrum).
pub const HAIL_DIAMETER_MAX_MM: f32 = 50.0;
/// Bulk density of hailstones, kg/m³ (Prodi 1970 measured 820–870).
pub const HAIL_DENSITY_KG_M3: f32 = 850.0;
/// Cheng & English's `N0 = A·Λ^b`: `A`, per m³ per mm (Λ per mm).
pub const CHENG_ENGLISH_A: f32 = 115.0;
/// Cheng & English's `b`.
pub const CHENG_ENGLISH_B: f32 = 3.63;
/// The slopes `Λ` the rate is solved over, per mm: from 0.12, where Cheng &
/// English's spectra carry the most water (≈ 38.5 mm/h; the rate falls on either
/// side, so the solution is one only above it), to pea hail (3).
pub const HAIL_SLOPE_RANGE_PER_MM: (f32, f32) = (0.12, 3.0);
/// Tries of the flux-weighted rejection draw before the last candidate is kept.
pub const HAIL_DIAMETER_TRIES: u32 = 32;

/// Terminal fall speed of a hailstone of diameter `diameter_mm`, m/s:
/// `v = 11.45·√(D / 1 cm)` (Matson & Huggins 1980, *J. Atmos. Sci.* 37, 1107–1125:
/// 600 stones of 5–25 mm near the ground, air of 0.993 kg/m³), with D clamped to
/// the hail sizes.
#[must_use]
pub fn hailstone_terminal_speed_mps(diameter_mm: f32) -> f32 {
    let d = diameter_mm.clamp(HAIL_DIAMETER_MIN_MM, HAIL_DIAMETER_MAX_MM);
    11.45 * (0.1 * d).sqrt()
}

/// The water one `N0 = 1` m⁻³·mm⁻¹ of a spectrum of slope `slope_per_mm` carries
/// down, mm/h: `3.6·10⁶ · ∫ e^(−ΛD)·(π/6)·D³·(ρ_h/ρ_w)·v(D) dD` over the hail
/// sizes (D in m inside; Simpson's rule, 200 intervals).
#[must_use]
pub fn hail_rate_per_intercept_mm_per_h(slope_per_mm: f32) -> f64 {
    let slope = f64::from(slope_per_mm);
    let (a, b) = (
        f64::from(HAIL_DIAMETER_MIN_MM),
        f64::from(HAIL_DIAMETER_MAX_MM),
    );
    let density_ratio = f64::from(HAIL_DENSITY_KG_M3) / 1000.0;
    let integrand = |d_mm: f64| {
        let d_m = d_mm * 1.0e-3;
        // Per m³ per mm × kg × m/s: kg per m² per s per mm of D.
        (-slope * d_mm).exp()
            * std::f64::consts::FRAC_PI_6
            * d_m.powi(3)
            * density_ratio
            * 1000.0
            * f64::from(hailstone_terminal_speed_mps(d_mm as f32))
    };
    let n = 200u32;
    let h = (b - a) / f64::from(n);
    let mut sum = integrand(a) + integrand(b);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        sum += w * integrand(a + f64::from(i) * h);
    }
    // kg/(m²·s) is mm/s of water.
    3600.0 * sum * h / 3.0
}

/// The spectrum `(N0 per m³ per mm, Λ per mm)` of a hailfall of `rate_mm_per_h`
/// of water (> 0): `Λ` where Cheng & English's `N0 = 115·Λ^3.63` carries the rate
/// (bisection over [`HAIL_SLOPE_RANGE_PER_MM`], clamped there), then `N0` so that
/// the spectrum carries the rate exactly.
#[must_use]
pub fn hail_spectrum(rate_mm_per_h: f32) -> (f32, f32) {
    let rate = f64::from(rate_mm_per_h.max(0.0));
    let carried = |slope: f32| {
        f64::from(CHENG_ENGLISH_A * slope.powf(CHENG_ENGLISH_B))
            * hail_rate_per_intercept_mm_per_h(slope)
    };
    // The carried rate falls as Λ grows over the range (tests: it is monotone).
    let (mut lo, mut hi) = HAIL_SLOPE_RANGE_PER_MM;
    if carried(lo) <= rate {
        hi = lo;
    } else if carried(hi) >= rate {
        lo = hi;
    } else {
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if carried(mid) > rate {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    let slope = 0.5 * (lo + hi);
    let n0 = rate / hail_rate_per_intercept_mm_per_h(slope);
    (n0 as f32, slope)
}

/// Hailstones per m³ of the spectrum, `(N0/Λ)·(e^(−Λ·D_min) − e^(−Λ·D_max))`.
#[must_use]
pub fn hail_number_density_per_m3(rate_mm_per_h: f32) -> f32 {
    if rate_mm_per_h <= 0.0 {
        return 0.0;
    }
    let (n0, slope) = hail_spectrum(rate_mm_per_h);
    n0 / slope * ((-slope * HAIL_DIAMETER_MIN_MM).exp() - (-slope * HAIL_DIAMETER_MAX_MM).exp())
}

/// Extinction coefficient of the hail, per m: `∫ N(D)·2·πD²/4 dD` (stones large
/// against the wavelength), in closed form over `[D_min, D_max]`:
/// `(π/2)·10⁻⁶·N0·[−e^(−ΛD)·(D²/Λ + 2D/Λ² + 2/Λ³)]`.
#[must_use]
pub fn hail_extinction_per_m(rate_mm_per_h: f32) -> f32 {
    if rate_mm_per_h <= 0.0 {
        return 0.0;
    }
    let (n0, slope) = hail_spectrum(rate_mm_per_h);
    let antiderivative = |d: f32| {
        -(-slope * d).exp() * (d * d / slope + 2.0 * d / slope.powi(2) + 2.0 / slope.powi(3))
    };
    std::f32::consts::FRAC_PI_2
        * 1.0e-6
        * n0
        * (antiderivative(HAIL_DIAMETER_MAX_MM) - antiderivative(HAIL_DIAMETER_MIN_MM))
}

/// A stone's diameter from the spectrum truncated to the hail sizes, mm: inverse
/// CDF of the truncated exponential (`f ∈ [0, 1)`).
#[must_use]
pub fn hail_diameter_mm(slope_per_mm: f32, f: f32) -> f32 {
    truncated_exponential_mm(HAIL_DIAMETER_MIN_MM, HAIL_DIAMETER_MAX_MM, slope_per_mm, f)
}

/// A newborn stone's diameter, mm, drawn from the flux `N(D)·v(D)` so that the
/// stones **in the air** follow the spectrum (as the drops' draw,
/// [`crate::physics::raindrop::draw_raindrop_diameter_mm`], whose draws it uses: a
/// newborn is a drop or a stone, never both): accept with `v(D)/v(50 mm)`, at most
/// [`HAIL_DIAMETER_TRIES`] tries, then the last candidate.
#[must_use]
pub fn draw_hail_diameter_mm(key: u32, slope_per_mm: f32) -> f32 {
    let v_max = hailstone_terminal_speed_mps(HAIL_DIAMETER_MAX_MM);
    let mut d = HAIL_DIAMETER_MIN_MM;
    for k in 0..HAIL_DIAMETER_TRIES {
        d = hail_diameter_mm(slope_per_mm, random_unit(key, draw::RAIN_DIAMETER + 2 * k));
        if random_unit(key, draw::RAIN_DIAMETER + 2 * k + 1) * v_max
            < hailstone_terminal_speed_mps(d)
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
    fn fall_speeds_are_matson_and_huggins() {
        // 11.45·√(D/cm): 5 mm 8.10 m/s, 1 cm 11.45, 2.5 cm 18.10, 5 cm 25.60.
        for (d, v) in [(5.0, 8.096), (10.0, 11.45), (25.0, 18.104), (50.0, 25.603)] {
            let got = hailstone_terminal_speed_mps(d);
            assert!((got - v).abs() < 0.005, "{d} mm: {got} m/s");
        }
        // Clamped to the hail sizes.
        let smallest = hailstone_terminal_speed_mps(HAIL_DIAMETER_MIN_MM);
        assert!((hailstone_terminal_speed_mps(1.0) - smallest).abs() < f32::EPSILON);
    }

    /// The carried rate of Cheng & English's spectra falls as `Λ` grows over the
    /// range solved, so each rate has one `Λ`.
    #[test]
    fn the_rate_falls_as_the_slope_grows_over_the_range() {
        let carried = |slope: f32| {
            f64::from(CHENG_ENGLISH_A * slope.powf(CHENG_ENGLISH_B))
                * hail_rate_per_intercept_mm_per_h(slope)
        };
        let (lo, hi) = HAIL_SLOPE_RANGE_PER_MM;
        let mut last = f64::INFINITY;
        for k in 0..=200 {
            let slope = lo + (hi - lo) * k as f32 / 200.0;
            let rate = carried(slope);
            assert!(rate < last, "Λ {slope}: {rate} mm/h after {last}");
            last = rate;
        }
        // The most is at the range's start: 38.5 mm/h.
        assert!((carried(lo) - 38.56).abs() < 0.1, "{}", carried(lo));
    }

    #[test]
    fn the_spectrum_carries_the_rate_and_heavier_hail_is_larger() {
        // The inversion finds the Λ whose spectrum carries the rate: Federer &
        // Waldvogel's Λ = 0.42 mm⁻¹ back from the rate it carries.
        let rate_042 = f64::from(CHENG_ENGLISH_A * 0.42f32.powf(CHENG_ENGLISH_B))
            * hail_rate_per_intercept_mm_per_h(0.42);
        let (_, slope) = hail_spectrum(rate_042 as f32);
        assert!((slope - 0.42).abs() < 1e-3, "Λ {slope}");
        let mut last_slope = f32::INFINITY;
        for rate in [0.5, 2.0, 10.0, 30.0, 100.0] {
            let (n0, slope) = hail_spectrum(rate);
            let carried = f64::from(n0) * hail_rate_per_intercept_mm_per_h(slope);
            assert!(
                (carried - f64::from(rate)).abs() < 1e-3 * f64::from(rate),
                "{rate} mm/h carries {carried}"
            );
            assert!(
                slope <= last_slope,
                "{rate} mm/h: Λ {slope} after {last_slope}"
            );
            last_slope = slope;
        }
        // Within Cheng & English's range the intercept is theirs.
        let (n0, slope) = hail_spectrum(10.0);
        let theirs = CHENG_ENGLISH_A * slope.powf(CHENG_ENGLISH_B);
        assert!((n0 - theirs).abs() < 1e-3 * theirs, "{n0} vs {theirs}");
        // Federer & Waldvogel's mean Swiss spectrum (Λ = 0.42 mm⁻¹) is a hailfall of
        // about 15 mm/h under this relation.
        let carried = f64::from(CHENG_ENGLISH_A * 0.42f32.powf(CHENG_ENGLISH_B))
            * hail_rate_per_intercept_mm_per_h(0.42);
        assert!((10.0..20.0).contains(&carried), "{carried} mm/h");
    }

    #[test]
    fn hail_is_sparse_and_its_extinction_follows_its_stones() {
        let n = hail_number_density_per_m3(15.0);
        // About one stone in a cubic metre: a thousandth of the drops of the same rain.
        assert!((0.5..5.0).contains(&n), "{n} per m³");
        // The closed form is the sum of two cross-sections over the stones (midpoints).
        let (n0, slope) = hail_spectrum(15.0);
        let bins = 20_000;
        let width = (HAIL_DIAMETER_MAX_MM - HAIL_DIAMETER_MIN_MM) / bins as f32;
        let summed: f32 = (0..bins)
            .map(|k| {
                let d = HAIL_DIAMETER_MIN_MM + (k as f32 + 0.5) * width;
                n0 * (-slope * d).exp() * width * std::f32::consts::FRAC_PI_2 * (d * 1.0e-3).powi(2)
            })
            .sum();
        let sigma = hail_extinction_per_m(15.0);
        assert!((sigma / summed - 1.0).abs() < 1e-3, "{sigma} vs {summed}");
        assert!(hail_extinction_per_m(0.0).abs() < f32::EPSILON);
    }

    #[test]
    fn drawn_stones_follow_the_flux_and_stay_in_the_hail_sizes() {
        let (_, slope) = hail_spectrum(10.0);
        let draws: Vec<f32> = (0..4000)
            .map(|i| draw_hail_diameter_mm(particle_key(7, i, 0), slope))
            .collect();
        assert!(
            draws
                .iter()
                .all(|d| (HAIL_DIAMETER_MIN_MM..=HAIL_DIAMETER_MAX_MM).contains(d))
        );
        // Flux-weighted: the mean drawn exceeds the spectrum's mean in the air.
        let mean = draws.iter().sum::<f32>() / draws.len() as f32;
        let in_air = HAIL_DIAMETER_MIN_MM + 1.0 / slope;
        assert!(mean > in_air, "{mean} mm vs {in_air} mm");
    }
}
