// cover_update.wgsl: the cover kernel. Rust twin: precip_cover::CoverGrid::step.
// Program: layout, deposit, cover, this file (precip_model::shaders::Program::CoverUpdate).

@group(0) @binding(0) var<uniform> cover_params: CoverStepParams;
@group(0) @binding(1) var<storage, read_write> cover: array<CoverTexel>;
@group(0) @binding(2) var<storage, read_write> deposits: array<atomic<u32>>;

@compute @workgroup_size(64)
fn cover_update(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if (i >= cover_params.texel_count) {
        return;
    }
    // Read and clear this texel's landed water (fed by particles) or use the rate.
    let snow_units = atomicExchange(&deposits[2u * i + DEPOSIT_SNOW], 0u);
    let rain_units = atomicExchange(&deposits[2u * i + DEPOSIT_RAIN], 0u);
    let texel = cover[i];
    var snow_mm = cover_params.snow_rate_mm_per_day * cover_params.dt_days;
    var rain_mm = cover_params.rain_rate_mm_per_day * cover_params.dt_days;
    if (texel.feed == COVER_FEED_PARTICLES) {
        snow_mm = f32(snow_units) / DEPOSIT_UNITS_PER_MM;
        rain_mm = f32(rain_units) / DEPOSIT_UNITS_PER_MM;
    }
    cover[i] = update_texel(texel, snow_mm, rain_mm, cover_params);
}
