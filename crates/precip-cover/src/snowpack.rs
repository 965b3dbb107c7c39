//! Snow density: fresh snow by air temperature, and settling of the pack.

/// Density of new snow from the air temperature, kg/m³ (WGSL twin in cover.wgsl).
///
/// Anderson (1976), as used by the SNOW-17 model:
/// `ρ = 50 + 1.7·(T + 15)^1.5` for `T > −15 °C`, `50` below, clamped to the
/// 50–250 kg/m³ of docs/model.md §7: ~70 at −10 °C, ~104 at −5 °C, ~149 at 0 °C,
/// ~214 at +6 °C (wet snow). So 1 mm/h of water is about 1 cm/h of snow.
#[must_use]
pub fn new_snow_density(air_temperature_c: f32) -> f32 {
    let above = (air_temperature_c + 15.0).max(0.0);
    (50.0 + 1.7 * above * above.sqrt()).clamp(50.0, 250.0)
}

/// The pack's bulk density after `dt_days` of settling toward `settled_kg_m3`
/// with time constant `tau_days` (a pack already denser does not loosen).
#[must_use]
pub fn compacted_density(
    density_kg_m3: f32,
    settled_kg_m3: f32,
    tau_days: f32,
    dt_days: f32,
) -> f32 {
    if density_kg_m3 >= settled_kg_m3 {
        density_kg_m3
    } else {
        settled_kg_m3 + (density_kg_m3 - settled_kg_m3) * (-dt_days / tau_days).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_snow_density_follows_temperature_within_50_to_250() {
        assert!((new_snow_density(-30.0) - 50.0).abs() < 1e-3);
        assert!((60.0..80.0).contains(&new_snow_density(-10.0)));
        assert!(
            (90.0..115.0).contains(&new_snow_density(-5.0)),
            "~100 typical"
        );
        assert!((140.0..160.0).contains(&new_snow_density(0.0)));
        let mut last = 0.0;
        for t in -60..=10 {
            let rho = new_snow_density(t as f32);
            assert!((50.0..=250.0).contains(&rho));
            assert!(rho >= last, "monotone in temperature");
            last = rho;
        }
        // 1 mm/h water equivalent at -5 °C is about 1 cm/h of snow.
        let depth_mm = 1.0 * 1000.0 / new_snow_density(-5.0);
        assert!((8.0..12.0).contains(&depth_mm), "{depth_mm}");
    }

    #[test]
    fn settling_approaches_but_never_passes_the_settled_density() {
        let mut rho = 100.0;
        for _ in 0..1000 {
            let next = compacted_density(rho, 350.0, 4.0, 0.1);
            assert!(next >= rho && next <= 350.0);
            rho = next;
        }
        assert!((rho - 350.0).abs() < 1.0);
        assert!((compacted_density(400.0, 350.0, 4.0, 1.0) - 400.0).abs() < 1e-6);
    }
}
