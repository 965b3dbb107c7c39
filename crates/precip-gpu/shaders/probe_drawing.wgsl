// probe_drawing.wgsl: a test kernel that builds sprite corners and tetrahedron vertices,
// and evaluates the snow cover's depletion curve and sub-texel threshold, for a list of
// inputs, so tests compare the WGSL drawing and cover shading with the Rust ones.
// Program: drawing, cover, shading, this file.

struct ProbeDrawing {
    centre_m: vec3<f32>,
    side_m: f32,
    camera_m: vec3<f32>,
    spin_rad: f32,
    velocity_mps: vec3<f32>,
    tumble: f32,
    h_m: f32,
    a_m: f32,
    cover: vec2<f32>,
}

@group(0) @binding(0) var<storage, read> probe_drawing_in: array<ProbeDrawing>;
// Per input: 4 sprite corners, 4 tetrahedron vertices, 4 normals (xyz; w = 0), then
// (cover fraction, threshold, value noise, drawn weight of input i at m = 2·side), then
// 4 snow streak corners at a 1/60 s exposure (xyz; w = uv.y), then (the blur at
// 50·h of an aperture a focused at 10 m, a sprite of side `side` at 0.8 defocused by
// it, a streak's opacity), then (the cover warp at the centre's x, z over cells
// (a + 0.1, side + 0.1), the flake's sun phase at cos = spin/6, a drop's
// environment factor at sin e = spin/6 over ground of albedo `tumble`), then (the
// clouds' march slot of the pixel |centre.xz|, the history's uv and whether it is
// there for the point centre through probe_history_camera(camera)), then (a drop's
// oscillation frequency and brightness, a cloud column, a layer's map offset), then
// (the clouds' pixel that the fresh image's pixel |centre.xz| marches in frame i mod
// 16, a history (tumble, 0, 0, spin) clamped to 0.3 … 0.6: its x and w), then (the
// clamp's weight from centre to centre + velocity through probe_history_camera(camera)
// on a 320 × 180 image, the new march's weight at clamp weight tumble − 0.3 and
// history at centre.xz px, the clouds' shadow map's weight at uv centre.xz/60 + ½,
// its texel |centre.xz|'s point's x + z on a map at camera.xz), then (where the
// centre reads the clouds' detail atlas with the map drifted by camera.xz: uv and
// the weight of the slice above; the detail of a texel (side, tumble, a, spin/6) at
// that weight), then (the density of cloud kind i mod 4 covering tumble at map value
// side, detail a·5, height fraction h/2; the map's uv of the centre drifted by
// camera.xz; 0), then (the streaks' H at 4·side, the unresolved ink's variance of a
// grain (tumble, 100·a + 1, h, 5) out to |centre.x| + 1, the grain at the pixel
// 10·centre.xz along the unit (velocity.xy) streaks 20·side + 1 long in exposure i, the
// land class drawn among probe_land_corners(i) at fract(|centre.xz|/4)).
@group(0) @binding(1) var<storage, read_write> probe_drawing_out: array<vec4<f32>>;

// A projection-like matrix from a point: clip = (p.x + c.x/100, p.y + c.y/100, p.z, −p.z)
// (the Rust test builds the same).
fn probe_history_camera(c: vec3<f32>) -> mat4x4<f32> {
    return mat4x4<f32>(
        vec4<f32>(1.0, 0.0, 0.0, 0.0),
        vec4<f32>(0.0, 1.0, 0.0, 0.0),
        vec4<f32>(0.0, 0.0, 1.0, -1.0),
        vec4<f32>(c.x / 100.0, c.y / 100.0, 0.0, 0.0),
    );
}

// Four land classes (0–2) of input i, for land_class_pick.
fn probe_land_corners(i: u32) -> vec4<u32> {
    return vec4<u32>(i % 3u, (i / 3u) % 3u, (i / 9u) % 3u, (i / 27u) % 3u);
}

@compute @workgroup_size(64)
fn probe_drawing(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&probe_drawing_in)) {
        return;
    }
    let q = probe_drawing_in[i];
    for (var k = 0u; k < 4u; k++) {
        probe_drawing_out[26u * i + k] = vec4<f32>(snow_sprite_corner(q.centre_m, q.camera_m, q.side_m, q.spin_rad, q.tumble, k), 0.0);
        let v = raindrop_vertex(q.centre_m, q.velocity_mps, q.h_m, q.a_m, k);
        probe_drawing_out[26u * i + 4u + k] = vec4<f32>(v.position_m, 0.0);
        probe_drawing_out[26u * i + 8u + k] = vec4<f32>(v.normal, 0.0);
    }
    probe_drawing_out[26u * i + 12u] = vec4<f32>(
        snow_cover_fraction(q.h_m, q.cover.x, q.a_m, q.cover.y),
        sub_texel_threshold(q.tumble, q.centre_m.xz),
        value_noise(q.centre_m.x, q.centre_m.z),
        drawn_weight(i, 2.0 * q.side_m),
    );
    for (var k = 0u; k < 4u; k++) {
        let s = snow_streak_corner(q.centre_m, q.camera_m, q.side_m, vec2<f32>(q.spin_rad, q.tumble), q.velocity_mps, 1.0 / 60.0, k);
        probe_drawing_out[26u * i + 13u + k] = vec4<f32>(s.position_m, s.uv.y);
    }
    let blur = defocus_blur_m(q.a_m, 10.0, 50.0 * q.h_m);
    probe_drawing_out[26u * i + 17u] = vec4<f32>(
        blur,
        defocused(q.side_m, 0.8, blur, 2),
        defocused(q.side_m, 0.8, blur, 1).y,
    );
    let history = cloud_history_uv(probe_history_camera(q.camera_m), q.centre_m);
    probe_drawing_out[26u * i + 19u] = vec4<f32>(f32(cloud_march_slot(vec2<u32>(abs(q.centre_m.xz)))), history.xy, history.z);
    // A drop of a_m/20 (0–1 cm) rings at drop_oscillation_hz; its brightness at
    // spin cycles; the cloud column of a layer covering tumble at map value side; the
    // map offset of layer i mod 3 (x).
    probe_drawing_out[26u * i + 20u] = vec4<f32>(
        drop_oscillation_hz(q.a_m / 20.0),
        drop_oscillation_brightness(q.spin_rad),
        cloud_column(q.tumble, q.side_m),
        cloud_layer_map_offset_m(i % 3u).x + cloud_layer_map_offset_m(i % 3u).y,
    );
    let fresh = cloud_fresh_pixel(vec2<u32>(abs(q.centre_m.xz)), i % 16u);
    let clamped = cloud_history_clamped(vec4<f32>(q.tumble, 0.0, 0.0, q.spin_rad), vec4<f32>(0.3), vec4<f32>(0.6));
    probe_drawing_out[26u * i + 21u] = vec4<f32>(vec2<f32>(fresh), clamped.x, clamped.w);
    let weight = cloud_history_clamp_weight(probe_history_camera(q.camera_m), q.centre_m, q.centre_m + q.velocity_mps, vec2<f32>(320.0, 180.0));
    let shadow_texel = vec2<u32>(abs(q.centre_m.xz));
    probe_drawing_out[26u * i + 22u] = vec4<f32>(
        weight,
        cloud_fresh_weight(q.tumble - 0.3, q.centre_m.xz),
        cloud_shadow_map_weight(q.centre_m.xz / 60.0 + 0.5),
        cloud_shadow_map_point_m(q.camera_m.xz, shadow_texel).x + cloud_shadow_map_point_m(q.camera_m.xz, shadow_texel).y,
    );
    let atlas = cloud_detail_atlas(cloud_detail_point(q.centre_m, q.camera_m.xz));
    probe_drawing_out[26u * i + 23u] = vec4<f32>(
        atlas,
        cloud_detail(vec4<f32>(q.side_m, q.tumble, q.a_m, q.spin_rad / 6.0), atlas.z),
    );
    probe_drawing_out[26u * i + 24u] = vec4<f32>(
        cloud_density(i % 4u, q.tumble, q.side_m, q.a_m * 5.0, q.h_m / 2.0),
        cloud_map_uv(q.centre_m, q.camera_m.xz),
        0.0,
    );
    probe_drawing_out[26u * i + 25u] = vec4<f32>(
        streak_h(4.0 * q.side_m),
        unresolved_streak_variance(vec4<f32>(q.tumble, 100.0 * q.a_m + 1.0, q.h_m, 5.0), abs(q.centre_m.x) + 1.0),
        streak_grain(10.0 * q.centre_m.xz, normalize(q.velocity_mps.xy), 20.0 * q.side_m + 1.0, i),
        f32(land_class_pick(probe_land_corners(i), fract(abs(q.centre_m.xz) * 0.25))),
    );
    probe_drawing_out[26u * i + 18u] = vec4<f32>(cover_warp_m(q.centre_m.xz, vec2<f32>(q.a_m + 0.1, q.side_m + 0.1)), flake_sun_phase(q.spin_rad / 6.0), drop_environment_factor(q.spin_rad / 6.0, q.tumble));
}
