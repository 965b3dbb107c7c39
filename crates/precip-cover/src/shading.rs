//! [`shade_texel`]: coverage, masks and wet darkening composed for a surface shader
//! (seed 003, equations 15–17; WGSL twin `cover_shading` in cover.wgsl).
//!
//! ## Reading of the seed
//!
//! Equation 15 gives `A_M = T_M.g − A_S` and `M_M = T_M.r − M_S`, and the text says a
//! mask value is the threshold at which a point becomes covered (or bare). We read
//! `A_M ≤ 0` as *covered* and `M_M ≤ 0` as *melted bare*, with a soft edge of width
//! `mask_edge` so patch borders are not aliased. The thresholds are rescaled by
//! `1 + edge` so that `A_S = 0` shows no snow anywhere and `A_S = 1` shows it
//! everywhere. Wet darkening multiplies the ground by `1 − R_d·wetness`.
//!
//! Sand and dust that settled ([`CoverTexel::dust_kg_m2`]) tint the bare surface
//! under the snow: grains scattered at random hide `1 − e^(−m/m₀)` of it
//! ([`settled_grain_cover`]; a layer of mass `m` of grains of diameter `d` projects
//! `3m/(2ρd)` of area per area, so `m₀ = 2ρd/3`: 0.35 kg/m² for 0.2 mm sand, 0.02
//! for 10 µm dust; [`GRAINS_COVERING_KG_M2`] takes 0.1, between them).

use crate::params::CoverParams;
use crate::texel::CoverTexel;

/// What a surface shader needs from the cover at one point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverShading {
    /// Opacity of the snow layer over the surface, `[0, 1]` (`C_out.a`).
    pub snow_alpha: f32,
    /// Factor on the bare surface's colour for wetness, `[1 − R_d, 1]`.
    pub ground_darkening: f32,
    /// Snow depth for displacement, metres.
    pub depth_m: f32,
    /// `A_M`: accumulation mask result (≤ 0: covered).
    pub accumulation_mask_result: f32,
    /// `M_M`: melt mask result (≤ 0: melted bare).
    pub melt_mask_result: f32,
}

/// The mass of settled grains that hides `1 − 1/e` of a surface, kg/m² (module docs).
pub const GRAINS_COVERING_KG_M2: f32 = 0.1;

/// The fraction of a surface that settled sand and dust hide (module docs).
/// WGSL twin: `settled_grain_cover` in `shaders/shading.wgsl`.
#[must_use]
pub fn settled_grain_cover(dust_kg_m2: f32) -> f32 {
    1.0 - (-dust_kg_m2.max(0.0) / GRAINS_COVERING_KG_M2).exp()
}

/// `A_S`: the fraction of the area the accumulated snow covers, from its depth.
#[must_use]
pub fn accumulated_fraction(texel: &CoverTexel, params: &CoverParams) -> f32 {
    (texel.depth_mm / params.full_cover_depth_mm).clamp(0.0, 1.0)
}

/// `M_S`: the fraction of the pack's peak that has melted.
#[must_use]
pub fn melted_fraction(texel: &CoverTexel) -> f32 {
    if texel.peak_swe_mm > 0.0 {
        (1.0 - texel.swe_mm / texel.peak_swe_mm).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Composes the cover of one texel, using its own threshold masks.
#[must_use]
pub fn shade_texel(texel: &CoverTexel, params: &CoverParams) -> CoverShading {
    shade_with_masks(texel, texel.accumulation_mask, texel.melt_mask, params)
}

/// Composes the cover with mask values `(T_M.g, T_M.r)` given by the caller (a shader
/// samples a finer mask texture per fragment).
#[must_use]
pub fn shade_with_masks(
    texel: &CoverTexel,
    mask_g: f32,
    mask_r: f32,
    params: &CoverParams,
) -> CoverShading {
    let edge = params.mask_edge;
    let a_s = accumulated_fraction(texel, params);
    let m_s = melted_fraction(texel);
    let a_m = mask_g - a_s;
    let m_m = mask_r - m_s;
    let covered = ((a_s * (1.0 + edge) - mask_g) / edge).clamp(0.0, 1.0);
    let remaining = ((mask_r + edge - m_s * (1.0 + edge)) / edge).clamp(0.0, 1.0);
    CoverShading {
        snow_alpha: covered * remaining,
        ground_darkening: 1.0 - params.wet_darkening * texel.wetness.clamp(0.0, 1.0),
        depth_m: texel.depth_mm * 1.0e-3,
        accumulation_mask_result: a_m,
        melt_mask_result: m_m,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settled_grains_hide_the_surface_as_their_layer_grows() {
        assert!(settled_grain_cover(0.0).abs() < 1e-7);
        assert!(
            (settled_grain_cover(GRAINS_COVERING_KG_M2) - (1.0 - (-1.0f32).exp())).abs() < 1e-6
        );
        assert!(settled_grain_cover(1.0) > 0.99);
        assert!(settled_grain_cover(-1.0).abs() < 1e-7);
    }

    #[test]
    fn no_snow_shows_nothing_full_snow_shows_everywhere() {
        let p = CoverParams::default();
        for g in [0.0, 0.01, 0.5, 0.99, 1.0] {
            let bare = CoverTexel {
                accumulation_mask: g,
                melt_mask: g,
                ..CoverTexel::default()
            };
            assert!(shade_texel(&bare, &p).snow_alpha.abs() < f32::MIN_POSITIVE);
            let deep = CoverTexel {
                depth_mm: 1000.0,
                swe_mm: 100.0,
                peak_swe_mm: 100.0,
                ..bare
            };
            assert!((shade_texel(&deep, &p).snow_alpha - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn a_texel_is_covered_once_a_s_passes_its_threshold_and_bare_once_m_s_passes_its_own() {
        let p = CoverParams::default();
        let t = CoverTexel {
            accumulation_mask: 0.3,
            melt_mask: 0.6,
            swe_mm: 10.0,
            peak_swe_mm: 10.0,
            ..CoverTexel::default()
        };
        let at = |depth_frac: f32, melted: f32| {
            let x = CoverTexel {
                depth_mm: depth_frac * p.full_cover_depth_mm,
                swe_mm: 10.0 * (1.0 - melted),
                ..t
            };
            shade_texel(&x, &p).snow_alpha
        };
        assert!(at(0.2, 0.0) < 0.01);
        assert!(at(0.4, 0.0) > 0.99);
        assert!(at(1.0, 0.5) > 0.99);
        assert!(at(1.0, 0.7) < 0.01);
    }

    #[test]
    fn wet_ground_is_darker() {
        let p = CoverParams::default();
        let wet = CoverTexel {
            wetness: 1.0,
            ..CoverTexel::default()
        };
        assert!((shade_texel(&wet, &p).ground_darkening - (1.0 - p.wet_darkening)).abs() < 1e-6);
        assert!((shade_texel(&CoverTexel::default(), &p).ground_darkening - 1.0).abs() < 1e-6);
    }
}
