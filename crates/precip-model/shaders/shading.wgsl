// shading.wgsl: the cover as a surface shader sees it. Rust twins:
// precip_cover::shading::{accumulated_fraction, melted_fraction, shade_with_masks}.

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
