// cover_texture.wgsl: the cover texels as the three filtered textures surfaces read
// (render_scene.wgsl's cover_a, cover_b, cover_c), written once a frame before the
// shadow pass. Its own bind group 0: the texels (binding 1, as the cover update's)
// and the three storage views (bindings 8, 9, 14) — never bound with the sampled
// views.

@group(0) @binding(1) var<storage, read> cover: array<CoverTexel>;
@group(0) @binding(8) var cover_a_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(9) var cover_b_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(14) var cover_c_out: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(64)
fn cover_texture(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = (wid.x + wid.y * groups.x) * 64u + lid;
    let size = textureDimensions(cover_a_out);
    if (i >= size.x * size.y || i >= arrayLength(&cover)) {
        return;
    }
    let t = cover[i];
    let xy = vec2<u32>(i % size.x, i / size.x);
    textureStore(cover_a_out, xy, vec4<f32>(t.depth_mm, t.swe_mm, t.peak_swe_mm, t.wetness));
    // Standing water over the surface's roughness (CoverTexel::puddle_ratio; a
    // water body holds none: its mesh says what it is).
    var puddle_ratio = 0.0;
    let roughness_mm = surface_water(t.surface).roughness_mm;
    if (roughness_mm > 0.0) {
        puddle_ratio = t.standing_mm / roughness_mm;
    }
    textureStore(cover_b_out, xy, vec4<f32>(t.accumulation_mask, t.melt_mask, t.age_days, puddle_ratio));
    // The surface's roughness length under snow (shading.wgsl), interpolated between
    // texels like the rest so coverage has no texel edges where surfaces meet.
    textureStore(cover_c_out, xy, vec4<f32>(t.dust_kg_m2, surface_snow_roughness_m(t.surface), 0.0, 0.0));
}
