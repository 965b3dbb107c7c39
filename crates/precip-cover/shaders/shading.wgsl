// shading.wgsl: the cover as a surface shader sees it. Rust twins:
// precip_cover::shading::{snow_cover_fraction, accumulated_fraction, value_noise,
// sub_texel_threshold, melted_fraction, shade_with_masks, settled_grain_cover,
// ground_albedo} and
// precip_cover::Surface::snow_roughness_m.

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

// Rust: precip_cover::shading::NEW_SNOW_DENSITY_KG_M3.
const NEW_SNOW_DENSITY_KG_M3: f32 = 100.0;

fn surface_snow_roughness_m(surface: u32) -> f32 {
    switch surface {
        case 0u: { return 0.01; }
        case 2u: { return 0.015; }
        default: { return 0.005; }
    }
}

// Niu & Yang 2007: tanh(h / (2.5·z0·(ρ/ρ_new)^m)).
fn snow_cover_fraction(depth_m: f32, density_kg_m3: f32, roughness_m: f32, exponent: f32) -> f32 {
    if (!(depth_m > 0.0)) {
        return 0.0;
    }
    let density = clamp(density_kg_m3, 30.0, 917.0);
    let scale_m = 2.5 * max(roughness_m, 1.0e-4) * pow(density / NEW_SNOW_DENSITY_KG_M3, exponent);
    return tanh(depth_m / scale_m);
}

fn accumulated_fraction(texel: CoverTexel, roughness_m: f32, exponent: f32) -> f32 {
    var density = NEW_SNOW_DENSITY_KG_M3;
    if (texel.depth_mm > 0.0) {
        density = 1000.0 * texel.swe_mm / texel.depth_mm;
    }
    return snow_cover_fraction(texel.depth_mm * 1.0e-3, density, roughness_m, exponent);
}

// Rust: precip_cover::shading::{THRESHOLD_NOISE_WAVELENGTHS_M, THRESHOLD_NOISE_AMPLITUDE}.
const THRESHOLD_NOISE_COARSE_M: f32 = 0.6;
const THRESHOLD_NOISE_FINE_M: f32 = 0.15;
const THRESHOLD_NOISE_AMPLITUDE: f32 = 0.2;

fn lattice_value(i: i32, j: i32) -> f32 {
    let state = ((bitcast<u32>(i) * 0x8da6b343u) ^ (bitcast<u32>(j) * 0xd8163841u)) * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return f32(((word >> 22u) ^ word) >> 8u) / 16777216.0;
}

fn noise_fade(t: f32) -> f32 {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn value_noise(x: f32, z: f32) -> f32 {
    let fx = floor(x);
    let fz = floor(z);
    let i = i32(fx);
    let j = i32(fz);
    let u = noise_fade(x - fx);
    let v = noise_fade(z - fz);
    let a = lattice_value(i, j) + (lattice_value(i + 1, j) - lattice_value(i, j)) * u;
    let b = lattice_value(i, j + 1) + (lattice_value(i + 1, j + 1) - lattice_value(i, j + 1)) * u;
    return a + (b - a) * v;
}

// Rust: precip_cover::shading::COVER_WARP_WAVELENGTH_TEXELS.
const COVER_WARP_WAVELENGTH_TEXELS: f32 = 1.5;

fn cover_warp_m(xz_m: vec2<f32>, cell_m: vec2<f32>) -> vec2<f32> {
    let scale = cell_m * COVER_WARP_WAVELENGTH_TEXELS;
    let u = xz_m.x / max(scale.x, 1.0e-3);
    let v = xz_m.y / max(scale.y, 1.0e-3);
    return vec2<f32>(
        (value_noise(u, v) - 0.5) * cell_m.x,
        (value_noise(u + 53.0, v + 91.0) - 0.5) * cell_m.y,
    );
}

fn sub_texel_threshold(mask: f32, xz_m: vec2<f32>) -> f32 {
    let n = (2.0 * value_noise(xz_m.x / THRESHOLD_NOISE_COARSE_M, xz_m.y / THRESHOLD_NOISE_COARSE_M)
        + value_noise(xz_m.x / THRESHOLD_NOISE_FINE_M + 17.0, xz_m.y / THRESHOLD_NOISE_FINE_M + 31.0)) / 3.0;
    return mask + THRESHOLD_NOISE_AMPLITUDE * 2.0 * (n - 0.5);
}

fn melted_fraction(texel: CoverTexel) -> f32 {
    if (texel.peak_swe_mm > 0.0) {
        return clamp(1.0 - texel.swe_mm / texel.peak_swe_mm, 0.0, 1.0);
    }
    return 0.0;
}

// shade_with_masks: masks (T_M.g, T_M.r) given per fragment.
fn cover_shading(texel: CoverTexel, mask_g: f32, mask_r: f32, roughness_m: f32, cover_depletion_exponent: f32, edge: f32, wet_darkening: f32) -> CoverShading {
    let a_s = accumulated_fraction(texel, roughness_m, cover_depletion_exponent);
    let m_s = melted_fraction(texel);
    let covered = clamp((a_s * (1.0 + edge) - mask_g) / edge, 0.0, 1.0);
    let remaining = clamp((mask_r + edge - m_s * (1.0 + edge)) / edge, 0.0, 1.0);
    return CoverShading(
        covered * remaining,
        1.0 - wet_darkening * clamp(texel.wetness, 0.0, 1.0),
        texel.depth_mm * 1.0e-3,
    );
}

// The ground's albedo at a texel as a whole: bare where no snow shows, the snow's
// (greying with age) over the share its own masks show. Rust:
// precip_cover::shading::ground_albedo.
fn ground_albedo(texel: CoverTexel, roughness_m: f32, exponent: f32, edge: f32, albedo_decay_per_day: f32, bare_albedo: f32) -> f32 {
    let shown = cover_shading(texel, texel.accumulation_mask, texel.melt_mask, roughness_m, exponent, edge, 0.0).snow_alpha;
    return bare_albedo + (snow_albedo(texel.age_days, albedo_decay_per_day) - bare_albedo) * shown;
}
