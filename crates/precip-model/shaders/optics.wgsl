// optics.wgsl: a particle's extinction and backscatter cross-sections per band.
// Rust twins: precip_model::sensors::optics::{Material::refractive_index,
// extinction_efficiency, extinction_cross_section_m2, drop_backscatter_m2_sr,
// backscatter_cross_section_m2_sr, OpticsPartial}. Bands: 0 = 550 nm, 1 = 905 nm,
// 2 = 1550 nm (Rust: Band::ALL).

// One workgroup's sums of optics_sums (Rust: OpticsPartial, 32 bytes).
struct OpticsPartial {
    extinction_m2: vec3<f32>,
    sampled: u32,
    backscatter_m2_sr: vec3<f32>,
    reserved: u32,
}

// Rust: ICE_LIDAR_RATIO_SR, DUST_LIDAR_RATIO_SR.
const ICE_LIDAR_RATIO_SR: f32 = 29.0;
const DUST_LIDAR_RATIO_SR: f32 = 55.0;

// Rust: Band::wavelength_nm.
fn band_wavelength_nm(band: u32) -> f32 {
    if band == 0u {
        return 550.0;
    }
    if band == 1u {
        return 905.0;
    }
    return 1550.0;
}

// Rust: Material::refractive_index(band), as (n, k), of a material (MATERIAL_*,
// kind.wgsl): water (Hale & Querry 1973), ice (Warren & Brandt 2008), quartz's
// ordinary ray.
fn refractive_index(material: u32, band: u32) -> vec2<f32> {
    if material == MATERIAL_WATER {
        if band == 0u {
            return vec2<f32>(1.333, 1.96e-9);
        }
        if band == 1u {
            return vec2<f32>(1.328, 4.86e-7);
        }
        return vec2<f32>(1.318, 9.9e-5);
    }
    if material == MATERIAL_MINERAL {
        if band == 0u {
            return vec2<f32>(1.546, 0.0);
        }
        if band == 1u {
            return vec2<f32>(1.536, 0.0);
        }
        return vec2<f32>(1.528, 0.0);
    }
    if band == 0u {
        return vec2<f32>(1.311, 2.9e-9);
    }
    if band == 1u {
        return vec2<f32>(1.303, 3.3e-7);
    }
    return vec2<f32>(1.296, 5.6e-4);
}

// Rust: extinction_efficiency (van de Hulst's anomalous diffraction).
fn extinction_efficiency(diameter_m: f32, n: f32, wavelength_nm: f32) -> f32 {
    let x = 3.1415927 * diameter_m / (wavelength_nm * 1.0e-9);
    let rho = 2.0 * x * (n - 1.0);
    if rho < 1.0e-3 {
        return 0.5 * rho * rho;
    }
    return 2.0 - 4.0 / rho * sin(rho) + 4.0 / (rho * rho) * (1.0 - cos(rho));
}

// Rust: extinction_cross_section_m2.
fn extinction_cross_section_m2(kind: u32, diameter_m: f32, band: u32) -> f32 {
    let index = refractive_index(kind_material(kind), band);
    return extinction_efficiency(diameter_m, index.x, band_wavelength_nm(band))
        * 0.7853982 * diameter_m * diameter_m;
}

// Rust: drop_backscatter_m2_sr (the front reflection and the once-reflected axial ray).
fn drop_backscatter_m2_sr(diameter_m: f32, band: u32) -> f32 {
    let index = refractive_index(MATERIAL_WATER, band);
    let n = index.x;
    let r = (n - 1.0) / (n + 1.0);
    let r0 = r * r;
    let a2 = 0.25 * diameter_m * diameter_m;
    let absorption_per_m = 4.0 * 3.1415927 * index.y / (band_wavelength_nm(band) * 1.0e-9);
    let front = a2 * r0 / 4.0;
    let t = 1.0 - r0;
    let g = 4.0 / n - 2.0;
    let axial = a2 * t * t * r0 / (g * g) * exp(-2.0 * absorption_per_m * diameter_m);
    return front + axial;
}

// Rust: backscatter_cross_section_m2_sr.
fn backscatter_cross_section_m2_sr(kind: u32, diameter_m: f32, band: u32) -> f32 {
    let material = kind_material(kind);
    if material == MATERIAL_WATER {
        return drop_backscatter_m2_sr(diameter_m, band);
    }
    if material == MATERIAL_MINERAL {
        return extinction_cross_section_m2(kind, diameter_m, band) / DUST_LIDAR_RATIO_SR;
    }
    return extinction_cross_section_m2(kind, diameter_m, band) / ICE_LIDAR_RATIO_SR;
}
