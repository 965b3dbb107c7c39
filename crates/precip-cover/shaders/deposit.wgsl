// deposit.wgsl: landed water in fixed point. Rust twin: precip_cover::deposit.
// One unit is 2^-20 mm (grains: kg/m²); a u32 per texel and channel, interleaved
// [snow, rain, grains].

const DEPOSIT_UNITS_PER_MM: f32 = 1048576.0;
const DEPOSIT_SNOW: u32 = 0u;
const DEPOSIT_RAIN: u32 = 1u;
const DEPOSIT_GRAINS: u32 = 2u;
const DEPOSIT_CHANNELS: u32 = 3u;

fn deposit_units(water_mm: f32) -> u32 {
    return u32(clamp(water_mm * DEPOSIT_UNITS_PER_MM + 0.5, 0.0, 2147483648.0));
}
