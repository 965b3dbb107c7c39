// shading.wgsl: the cover as a surface shader sees it. Rust twins:
// precip_cover::shading::{accumulated_fraction, melted_fraction, shade_with_masks,
// settled_grain_cover}.

// Rust: precip_cover::shading::GRAINS_COVERING_KG_M2.
const GRAINS_COVERING_KG_M2: f32 = 0.1;
// Settled quartz sand and dust (linear RGB).
const SETTLED_GRAIN_COLOUR: vec3<f32> = vec3<f32>(0.55, 0.42, 0.26);

fn settled_grain_cover(dust_kg_m2: f32) -> f32 {
    return 1.0 - exp(-max(dust_kg_m2, 0.0) / GRAINS_COVERING_KG_M2);
}

struct CoverShading {
    snow_alpha: f32,
    ground_darkening: f32,
    depth_m: f32,
}

fn accumulated_fraction(texel: CoverTexel, full_cover_depth_mm: f32) -> f32 {
    return clamp(texel.depth_mm / full_cover_depth_mm, 0.0, 1.0);
}

fn melted_fraction(texel: CoverTexel) -> f32 {
    if (texel.peak_swe_mm > 0.0) {
        return clamp(1.0 - texel.swe_mm / texel.peak_swe_mm, 0.0, 1.0);
    }
    return 0.0;
}

// shade_with_masks: masks (T_M.g, T_M.r) given per fragment.
fn cover_shading(texel: CoverTexel, mask_g: f32, mask_r: f32, full_cover_depth_mm: f32, edge: f32, wet_darkening: f32) -> CoverShading {
    let a_s = accumulated_fraction(texel, full_cover_depth_mm);
    let m_s = melted_fraction(texel);
    let covered = clamp((a_s * (1.0 + edge) - mask_g) / edge, 0.0, 1.0);
    let remaining = clamp((mask_r + edge - m_s * (1.0 + edge)) / edge, 0.0, 1.0);
    return CoverShading(
        covered * remaining,
        1.0 - wet_darkening * clamp(texel.wetness, 0.0, 1.0),
        texel.depth_mm * 1.0e-3,
    );
}
