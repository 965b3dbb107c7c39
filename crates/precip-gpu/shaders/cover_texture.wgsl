// cover_texture.wgsl: the cover texels as the three filtered textures surfaces read
// (render_scene.wgsl's cover_a, cover_b, cover_c), written once a frame before the
// shadow pass; then (drop_ground) the albedo of the ground the drops refract. Their
// own bind group 0: the frame's RenderParams (binding 0), the texels (binding 1, as
// the cover update's), the three storage views (bindings 8, 9, 14) and the drops'
// ground (binding 16) — never bound with the sampled views.

@group(0) @binding(1) var<storage, read> cover: array<CoverTexel>;
@group(0) @binding(8) var cover_a_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(9) var cover_b_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(14) var cover_c_out: texture_storage_2d<rgba16float, write>;
@group(0) @binding(16) var<storage, read_write> drop_ground_out: array<f32>;

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

// The ground the drops refract, one number a frame: the mean of the cover's ground
// albedo (shading.wgsl's ground_albedo) over the lattice within DROP_GROUND_RADIUS_M
// of the camera (drawing.wgsl's drop_ground_offset_m), bare off the grid. Rust:
// precip_model::drawing::drop_ground_albedo (summed in order; here per invocation,
// then in a tree: equal within rounding). Then the land's beyond the scene: the
// same albedo's mean over a lattice spread over the whole grid
// (precip_model::drawing::far_ground::far_ground_albedo).
var<workgroup> drop_ground_sums: array<vec4<f32>, 64>;

fn cover_albedo_at(xz_m: vec2<f32>) -> f32 {
    let i = grid_texel_index(params.cover, xz_m);
    if (i >= 0 && u32(i) < arrayLength(&cover)) {
        let t = cover[i];
        return ground_albedo(t, surface_snow_roughness_m(t.surface), params.cover_look.z, params.cover_look.w, params.cover_look2.y, BARE_GROUND_ALBEDO);
    }
    return BARE_GROUND_ALBEDO;
}

@compute @workgroup_size(64)
fn drop_ground(@builtin(local_invocation_index) lid: u32) {
    let n = DROP_GROUND_SAMPLES_PER_SIDE * DROP_GROUND_SAMPLES_PER_SIDE;
    let camera = params.camera_m_cone_cos.xz;
    var sum = vec4<f32>(0.0);
    for (var k = lid; k < n; k += 64u) {
        let land = cover_albedo_at(far_ground_lattice_m(params.cover.origin_m, params.cover.size_m, k));
        sum += vec4<f32>(0.0, 0.0, land, 1.0);
        let offset = drop_ground_offset_m(k);
        if (dot(offset, offset) > DROP_GROUND_RADIUS_M * DROP_GROUND_RADIUS_M) {
            continue;
        }
        sum += vec4<f32>(cover_albedo_at(camera + offset), 1.0, 0.0, 0.0);
    }
    drop_ground_sums[lid] = sum;
    workgroupBarrier();
    for (var half = 32u; half > 0u; half >>= 1u) {
        if (lid < half) {
            drop_ground_sums[lid] += drop_ground_sums[lid + half];
        }
        workgroupBarrier();
    }
    if (lid == 0u) {
        let total = drop_ground_sums[0];
        drop_ground_out[0] = total.x / max(total.y, 1.0);
        drop_ground_out[1] = total.z / max(total.w, 1.0);
    }
}
