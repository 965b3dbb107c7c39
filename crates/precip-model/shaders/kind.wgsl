// kind.wgsl: what a particle is, and every decision that depends on it, one row per
// kind. Rust twin: precip_model::particles::kind (ParticleKind's methods; the names
// here are theirs with a `kind_` prefix). Needs deposit.wgsl's DEPOSIT_* channels.
// Every program that joins layout.wgsl joins this file.

// Rust: ParticleKind as u32 (four bits of Particle.flags, FLAG_KIND_*).
const KIND_DRY_SNOW: u32 = 0u;
const KIND_WET_SNOW: u32 = 1u;
const KIND_RAIN: u32 = 2u;
const KIND_GRAIN: u32 = 3u;
const KIND_HAIL: u32 = 4u;

// Rust: precip_model::sensors::optics::Material as u32.
const MATERIAL_WATER: u32 = 0u;
const MATERIAL_ICE: u32 = 1u;
const MATERIAL_MINERAL: u32 = 2u;

// What the weather's kinds need to draw a newborn's species (Rust: SpeciesParams,
// 32 bytes, the last block of StepParams).
struct SpeciesParams {
    snow_fraction: f32,
    rain_slope_per_mm: f32,
    grain_diameter_m: f32,
    grain_density_kg_m3: f32,
    hail_fraction: f32,
    hail_slope_per_mm: f32,
    reserved0: f32,
    reserved1: f32,
}

// Rust: Particle::kind.
fn particle_kind(flags: u32) -> u32 {
    return (flags >> FLAG_KIND_SHIFT) & FLAG_KIND_MASK;
}

// Rust: ParticleKind::is_snow.
fn kind_is_snow(kind: u32) -> bool {
    return kind == KIND_DRY_SNOW || kind == KIND_WET_SNOW;
}

// Rust: ParticleKind::is_drop (splashes; drawn as a streak).
fn kind_is_drop(kind: u32) -> bool {
    return kind == KIND_RAIN;
}

// Rust: ParticleKind::rings_water (wave_excite, water_waves.wgsl).
fn kind_rings_water(kind: u32) -> bool {
    return kind == KIND_DRY_SNOW || kind == KIND_WET_SNOW || kind == KIND_RAIN || kind == KIND_GRAIN;
}

// Rust: ParticleKind::deposit_channel.
fn kind_deposit_channel(kind: u32) -> u32 {
    if (kind == KIND_RAIN) {
        return DEPOSIT_RAIN;
    }
    if (kind == KIND_GRAIN) {
        return DEPOSIT_GRAINS;
    }
    return DEPOSIT_SNOW;
}

// Rust: ParticleKind::material.
fn kind_material(kind: u32) -> u32 {
    if (kind == KIND_RAIN) {
        return MATERIAL_WATER;
    }
    if (kind == KIND_GRAIN) {
        return MATERIAL_MINERAL;
    }
    return MATERIAL_ICE;
}

// The colour a flake-drawn particle reflects (GPU only: the reference draws nothing):
// dry snow 0.95, wet snow 0.85 (water in its pores darkens it), a grain of quartz
// sand or mineral dust in daylight (sRGB ~ #c8a878, linear), a hailstone's milky
// ice a little grey-blue (clear layers let the light through).
fn kind_albedo(kind: u32) -> vec3<f32> {
    if (kind == KIND_GRAIN) {
        return vec3<f32>(0.58, 0.39, 0.19);
    }
    if (kind == KIND_HAIL) {
        return vec3<f32>(0.78, 0.82, 0.86);
    }
    return vec3<f32>(select(0.95, 0.85, kind == KIND_WET_SNOW));
}
