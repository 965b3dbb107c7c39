//! What a LiDAR's beam gets back from water (a pond, a puddle, the sea): water sends
//! almost nothing back diffusely at 905 or 1550 nm (it absorbs what enters), so the
//! echo is the surface's glint — the facets of the wind-roughened surface that face
//! the beam — and the whitecaps' foam.
//!
//! The glint (the sea-surface backscatter of ocean lidars: Bufton, Hoge & Swift 1983;
//! Menzies, Tratt & Hunt 1998; Hu et al. 2008): facets tilted by the slopes of Cox &
//! Munk (1954), whose mean square slope over a clean sea is
//! `σ² = 0.003 + 5.12·10⁻³·U` (`U` the wind 12.5 m above the water, m/s), send back
//! `β = ρ_F/(4π·σ²·cos⁴θ)·e^(−tan²θ/σ²)` per sr at incidence `θ` (`ρ_F` the Fresnel
//! reflectance at normal incidence, 0.02). A Lambertian target of reflectance `R`
//! sends back `R·cos θ/π` per sr, so the water's echo is that of a target of
//! reflectance `R = π·β/cos θ` ([`water_reflectance`]): 0.17 looking straight down
//! at a 5 m/s sea, under 10⁻³ of it 30° off (the little foam a breeze raises): a
//! car's LiDAR, whose beams meet the road at grazing angles, sees nothing of a
//! puddle, a helicopter's sees the sea below it. The foam of whitecaps (their share `W`, (13.6)) is diffuse, of
//! effective reflectance 0.13 at near infrared (Koepke 1984's 0.22 in the visible,
//! less by some 40 % at 860 nm: Frouin, Schwindling & Deschamps 1996).

/// Water's Fresnel reflectance at normal incidence at near infrared (`n = 1.33`).
pub const WATER_NORMAL_REFLECTANCE: f32 = 0.02;

/// The foam's effective reflectance at near infrared.
pub const FOAM_REFLECTANCE_NIR: f32 = 0.13;

/// Cox & Munk's mean square slope of a clean sea in a wind of `wind_mps`.
#[must_use]
pub fn mean_square_slope(wind_mps: f32) -> f32 {
    0.003 + 5.12e-3 * wind_mps.max(0.0)
}

/// The reflectance of the Lambertian target that echoes as water does, met at
/// `cos_incidence` (the beam against the vertical) in a wind of `wind_mps`: its glint
/// over the water's share, the foam's over the whitecaps' share.
#[must_use]
pub fn water_reflectance(cos_incidence: f32, wind_mps: f32) -> f32 {
    let c = cos_incidence.clamp(1.0e-3, 1.0);
    let s2 = mean_square_slope(wind_mps);
    let tan2 = (1.0 - c * c) / (c * c);
    // π·β/cos θ with β = ρ_F/(4π·σ²·cos⁴θ)·e^(−tan²θ/σ²).
    let glint = WATER_NORMAL_REFLECTANCE / (4.0 * s2 * c.powi(5)) * (-tan2 / s2).exp();
    let foam = precip_sea::ocean::whitecap_cover(wind_mps);
    (1.0 - foam) * glint + foam * FOAM_REFLECTANCE_NIR
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn water_echoes_straight_down_and_hardly_aslant() {
        let nadir = water_reflectance(1.0, 5.0);
        assert!((0.15..0.2).contains(&nadir), "{nadir}");
        let aslant = water_reflectance(30f32.to_radians().cos(), 5.0);
        assert!(aslant < 1.0e-3 * nadir, "{aslant}");
        // A rougher sea spreads the glint: less straight down, more aslant.
        assert!(water_reflectance(1.0, 15.0) < nadir);
        assert!(
            water_reflectance(15f32.to_radians().cos(), 15.0)
                > water_reflectance(15f32.to_radians().cos(), 5.0)
        );
        // A gale's foam echoes at any angle.
        let grazing = water_reflectance(0.1, 22.0);
        assert!(grazing > 0.01, "{grazing}");
        assert!(water_reflectance(0.1, 3.0) < 1.0e-3);
    }
}
