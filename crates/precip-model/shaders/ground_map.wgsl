// ground_map.wgsl: the ground height map. Rust twin: precip_model::particles::ground::GroundMap.
// Needs the globals `frames: Frames` and `ground_height: array<f32>` (the heights of
// the texels, then their erodibility: GroundMap::gpu_words).

// (1, height) on the map, (0, 0) off it. Nearest texel: an eave must not catch
// particles beside it.
fn ground_height_at(xz_m: vec2<f32>) -> vec2<f32> {
    let i = grid_texel_index(frames.ground, xz_m);
    if (i < 0) {
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(1.0, ground_height[u32(i)]);
}

// The share of the surface at xz whose grains the wind lifts, 0 off the map (Rust:
// GroundMap::erodibility_at).
fn erodibility_at(xz_m: vec2<f32>) -> f32 {
    let i = grid_texel_index(frames.ground, xz_m);
    if (i < 0) {
        return 0.0;
    }
    let n = frames.ground.texels.x * frames.ground.texels.y;
    return ground_height[n + u32(i)];
}
