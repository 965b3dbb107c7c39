// ground.wgsl: the ground height map. Rust twin: precip_model::ground::GroundMap.
// Needs the globals `frames: Frames` and `ground_height: array<f32>`.

// (1, height) on the map, (0, 0) off it. Nearest texel: an eave must not catch
// particles beside it.
fn ground_height_at(xz_m: vec2<f32>) -> vec2<f32> {
    let i = grid_texel_index(frames.ground, xz_m);
    if (i < 0) {
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(1.0, ground_height[u32(i)]);
}
