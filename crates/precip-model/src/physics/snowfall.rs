//! Snowfall size spectrum (Gunn & Marshall 1958): number density of flakes.

/// Rate below which the Gunn–Marshall fit (which diverges as `S → 0`) is held, mm/h.
pub const GUNN_MARSHALL_MIN_RATE_MM_PER_H: f32 = 0.1;

/// Gunn–Marshall intercept `N0 = 3800·S^−0.87`, m⁻³·mm⁻¹ (melted diameter).
#[must_use]
pub fn gunn_marshall_intercept(snow_rate_mm_per_h: f32) -> f32 {
    3800.0
        * snow_rate_mm_per_h
            .max(GUNN_MARSHALL_MIN_RATE_MM_PER_H)
            .powf(-0.87)
}

/// Gunn–Marshall slope `Λ = 2.55·S^−0.48`, mm⁻¹ (melted diameter).
#[must_use]
pub fn gunn_marshall_slope_per_mm(snow_rate_mm_per_h: f32) -> f32 {
    2.55 * snow_rate_mm_per_h
        .max(GUNN_MARSHALL_MIN_RATE_MM_PER_H)
        .powf(-0.48)
}

/// Flakes per m³, `N0/Λ` (0 for no snow).
#[must_use]
pub fn snow_number_density_per_m3(snow_rate_mm_per_h: f32) -> f32 {
    if snow_rate_mm_per_h > 0.0 {
        gunn_marshall_intercept(snow_rate_mm_per_h) / gunn_marshall_slope_per_mm(snow_rate_mm_per_h)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gunn_marshall_numbers() {
        assert!((gunn_marshall_intercept(1.0) - 3800.0).abs() < 1e-2);
        assert!((gunn_marshall_slope_per_mm(1.0) - 2.55).abs() < 1e-5);
        assert!((snow_number_density_per_m3(1.0) - 1490.2).abs() < 0.5);
        assert!(snow_number_density_per_m3(0.0).abs() < f32::MIN_POSITIVE);
        assert!(snow_number_density_per_m3(1e-9).is_finite());
    }
}
