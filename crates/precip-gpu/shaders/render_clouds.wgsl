// render_clouds.wgsl: the cloud layers marched into the clouds' image (a quarter of
// the frame's side), which the sky lays over itself (fs_sky_clouds). The formulas are
// drawing.wgsl's twins of precip_model::drawing::clouds; docs/model.md (6.9)-(6.15).
//
// Temporal reuse (docs/model.md (6.14)): there are two images, written on
// alternate frames (pass "clouds" into A, "clouds_b" into B), each reading the other
// as the frame before's (`cloud_image`, group 1). First the pass "clouds_fresh"
// marches one pixel of each 4 × 4 block (cloud_fresh_pixel, slot
// switches.cloud_shadow.y) into the fresh image, a quarter of the side (group 2);
// then the clouds' pass takes those, and every other pixel from where the frame
// before's camera saw its ray's entry into the nearest layer, clamped to the range
// of the fresh pixels around it (cloud_history_clamped) as far as the camera
// moved across the ray (cloud_history_clamp_weight); where that lies outside
// the image, it leaves the pixel (discard) to the march that follows in the same
// pass (fs_clouds_all at the far plane: the depth test lets it through only where
// the reuse wrote nothing, at depth 0). With no history (slot CLOUD_MARCH_ALL) the
// fresh pass and the reuse do not run and the march covers every pixel. The reuse
// has no march in it: a CPU rasteriser pays for the code of a loop in every
// fragment, run or not.

@group(2) @binding(8) var cloud_fresh: texture_2d<f32>;
// The clouds' shadow map the cloud_shadow_map kernel writes.
@group(0) @binding(20) var cloud_shadow_out: texture_storage_2d<rgba16float, write>;

// The clouds' shadow map: each texel the share of the sun's light that reaches its
// ground point (at the land's height) through every layer (docs/model.md (6.12)),
// one invocation a texel. Rust: precip_model::drawing::clouds::cloud_shadow_map.
@compute @workgroup_size(64)
fn cloud_shadow_map(@builtin(local_invocation_index) lid: u32, @builtin(workgroup_id) wid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = (wid.x + wid.y * groups.x) * 64u + lid;
    if (i >= CLOUD_SHADOW_MAP_PX * CLOUD_SHADOW_MAP_PX) {
        return;
    }
    let texel = vec2<u32>(i % CLOUD_SHADOW_MAP_PX, i / CLOUD_SHADOW_MAP_PX);
    let xz = cloud_shadow_map_point_m(switches.cloud_shadow_map.xy, texel);
    let p = vec3<f32>(xz.x, switches.far_ground.x, xz.y);
    let to_sun = switches.to_sun_extinction.xyz;
    var share = 1.0;
    let count = cloud_layer_count();
    for (var l = 0u; l < count; l += 1u) {
        share *= cloud_sun_transmittance(l, p, to_sun);
    }
    textureStore(cloud_shadow_out, texel, vec4<f32>(share, 0.0, 0.0, 1.0));
}

// cloud_sun_transmittance (precip_model::drawing::clouds::cloud_sun_transmittance):
// the share of the sun's light that reaches `p` through layer `i`: Beer's law over
// CLOUD_SHADOW_SAMPLES points of the sun's ray's part in it.
fn cloud_sun_transmittance(i: u32, p: vec3<f32>, to_sun: vec3<f32>) -> f32 {
    let layer = layer_row(i);
    let slab = cloud_slab(p.y, to_sun.y, layer.x, layer.y);
    if (slab.y <= slab.x) {
        return 1.0;
    }
    let offset = switches.cloud_drift.xy + cloud_layer_map_offset_m(i);
    var density = 0.0;
    for (var k = 0u; k < CLOUD_SHADOW_SAMPLES; k += 1u) {
        let q = p + to_sun * (slab.x + (slab.y - slab.x) * (f32(k) + 0.5) / f32(CLOUD_SHADOW_SAMPLES));
        density += cloud_density_at(q, layer, offset);
    }
    return exp(-layer_extinction(i) * density * (slab.y - slab.x) / f32(CLOUD_SHADOW_SAMPLES));
}

// The clear sky between the clouds: the haze's colour at the horizon, deeper blue
// toward the zenith (a look, not a sky model).
fn clear_sky(horizon: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let zenith = vec3<f32>(0.16, 0.3, 0.62);
    return mix(horizon, zenith, 1.0 - exp(-3.0 * max(dir.y, 0.0)));
}

// The triangle covering the clouds' image at depth 0 (the march after it fills
// what it leaves): into image A, reading B.
@vertex
fn vs_clouds(@builtin(vertex_index) v: u32) -> SkyVarying {
    return near_triangle(v);
}

fn near_triangle(v: u32) -> SkyVarying {
    var out = sky_triangle(v);
    out.clip.z = 0.0;
    return out;
}

@fragment
fn fs_clouds(in: SkyVarying) -> @location(0) vec4<f32> {
    return clouds_with_history(in);
}

// Every pixel the reuse left marched, into A or B: all of them without history
// (the first frame, a new layer, a jump, inside a layer).
@vertex
fn vs_clouds_all(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

@fragment
fn fs_clouds_all(in: SkyVarying) -> @location(0) vec4<f32> {
    return clouds_marched(in);
}

// The same into image B, reading A.
@vertex
fn vs_clouds_b(@builtin(vertex_index) v: u32) -> SkyVarying {
    return near_triangle(v);
}

@fragment
fn fs_clouds_b(in: SkyVarying) -> @location(0) vec4<f32> {
    return clouds_with_history(in);
}

// The frame's pixel of each block of the clouds' image, marched into the fresh
// image (`cloud_image` only for the images' size).
@vertex
fn vs_clouds_fresh(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

@fragment
fn fs_clouds_fresh(in: SkyVarying) -> @location(0) vec4<f32> {
    let size = vec2<f32>(textureDimensions(cloud_image));
    let pixel = cloud_fresh_pixel(vec2<u32>(in.clip.xy), u32(switches.cloud_shadow.y));
    let uv = (vec2<f32>(pixel) + 0.5) / size;
    var at: SkyVarying;
    at.clip = vec4<f32>(vec2<f32>(pixel) + 0.5, 1.0, 1.0);
    at.ndc = vec2<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    return clouds_marched(at);
}

// The density at p of the layer `layer` (base, top, coverage, kind), its map read
// at `offset_m` (the drift plus the layer's own offset).
fn cloud_density_at(p: vec3<f32>, layer: vec4<f32>, offset_m: vec2<f32>) -> f32 {
    let h = (p.y - layer.x) / max(layer.y - layer.x, 1.0);
    let m = textureSampleLevel(cloud_map, cloud_sampler, cloud_map_uv(p, offset_m), 0.0).r;
    let at = cloud_detail_atlas(cloud_detail_point(p, offset_m));
    let d = cloud_detail(textureSampleLevel(cloud_detail_atlas_texture, cloud_sampler, at.xy, 0.0), at.z);
    return cloud_density(u32(layer.w), layer.z, m, d, h);
}

// Layer `i`'s row (base, top, coverage, kind), its most extinction and where it
// reads the map. A switch of constant indices: an index the compiler cannot see
// is the same for every pixel costs each pixel a gather on a CPU rasteriser.
fn layer_row(i: u32) -> vec4<f32> {
    switch i {
        case 0u: { return switches.clouds[0]; }
        case 1u: { return switches.clouds[1]; }
        default: { return switches.clouds[2]; }
    }
}

fn layer_extinction(i: u32) -> f32 {
    switch i {
        case 0u: { return switches.cloud_extinction.x; }
        case 1u: { return switches.cloud_extinction.y; }
        default: { return switches.cloud_extinction.z; }
    }
}

// Where the ray crosses layer `i` (empty past the last layer: its rows are zeros).
fn layer_slab(i: u32, camera: vec3<f32>, ray: vec3<f32>) -> vec2<f32> {
    let layer = layer_row(i);
    return cloud_slab(camera.y, ray.y, layer.x, layer.y);
}

// The ray's entry into the nearest layer it crosses, m (< 0: none). One layer, the
// common case, without a loop: a CPU rasteriser pays for each.
fn nearest_layer_entry(camera: vec3<f32>, ray: vec3<f32>, count: u32) -> f32 {
    let first = layer_slab(0u, camera, ray);
    var nearest = select(-1.0, first.x, first.y > first.x);
    for (var i = 1u; i < count; i += 1u) {
        let slab = layer_slab(i, camera, ray);
        if (slab.y > slab.x && (nearest < 0.0 || slab.x < nearest)) {
            nearest = slab.x;
        }
    }
    return nearest;
}

// The camera's ray through the pixel at `ndc`.
fn pixel_ray(ndc: vec2<f32>) -> vec3<f32> {
    let far = switches.inverse_view_proj * vec4<f32>(ndc, 1.0, 1.0);
    return normalize_or_zero(far.xyz / far.w - switches.camera_m_cone_cos.xyz);
}

// The pixel's clouds marched (march_clouds), transparent where its ray meets none.
fn clouds_marched(in: SkyVarying) -> vec4<f32> {
    let camera = switches.camera_m_cone_cos.xyz;
    let ray = pixel_ray(in.ndc);
    let count = cloud_layer_count();
    let nearest = nearest_layer_entry(camera, ray, count);
    if (nearest < 0.0) {
        return vec4<f32>(0.0);
    }
    return march_clouds(in, camera, ray, nearest, count);
}

// The light the layers and the haze in front of them send along the pixel's ray
// (premultiplied) and their opacity: this frame's fresh pixel where it is the one
// of its block the frame marched; else the frame before's image clamped to the
// fresh pixels around; where that image did not see the point, nothing
// (discarded: the march that follows fills it).
fn clouds_with_history(in: SkyVarying) -> vec4<f32> {
    let camera = switches.camera_m_cone_cos.xyz;
    let ray = pixel_ray(in.ndc);
    let nearest = nearest_layer_entry(camera, ray, cloud_layer_count());
    if (nearest < 0.0) {
        return vec4<f32>(0.0);
    }
    let slot = u32(switches.cloud_shadow.y);
    let pixel = vec2<u32>(in.clip.xy);
    let marched = cloud_march_slot(pixel) == slot;
    // The fresh pixels around: the four whose places (4·f + the slot's place in
    // the block) surround this pixel.
    let own = vec2<f32>(cloud_fresh_pixel(vec2<u32>(0u), slot));
    let at = (vec2<f32>(pixel) - own) / f32(CLOUD_MARCH_BLOCK_PX);
    let last = vec2<i32>(textureDimensions(cloud_fresh)) - 1;
    let f = vec2<i32>(floor(at));
    let a = textureLoad(cloud_fresh, clamp(f, vec2<i32>(0), last), 0);
    let b = textureLoad(cloud_fresh, clamp(f + vec2<i32>(1, 0), vec2<i32>(0), last), 0);
    let c = textureLoad(cloud_fresh, clamp(f + vec2<i32>(0, 1), vec2<i32>(0), last), 0);
    let d = textureLoad(cloud_fresh, clamp(f + vec2<i32>(1, 1), vec2<i32>(0), last), 0);
    // The frame before's image where its camera saw the ray's entry into the
    // nearest layer, moved with the clouds' drift since (cloud_shadow.zw: the map
    // is read at p + drift, so what lies at p now lay there at p + Δ).
    let moved = vec3<f32>(switches.cloud_shadow.z, 0.0, switches.cloud_shadow.w);
    let history = cloud_history_uv(switches.previous_view_proj, camera + ray * nearest + moved);
    if (history.z < 0.5) {
        if (marched) {
            return a;
        }
        discard;
    }
    let seen = textureSampleLevel(cloud_image, cover_sampler, history.xy, 0.0);
    let clamped = cloud_history_clamped(seen, min(min(a, b), min(c, d)), max(max(a, b), max(c, d)));
    let entry = camera + ray * nearest + moved;
    let deeper = entry + ray * CLOUD_PARALLAX_DEPTH_M;
    let size = vec2<f32>(textureDimensions(cloud_image));
    let stale = cloud_history_clamp_weight(switches.previous_view_proj, entry, deeper, size);
    let kept = mix(seen, clamped, stale);
    // The frame's own pixel: its march averaged into its history where that is
    // its own (cloud_fresh_weight), else taken.
    return select(kept, mix(kept, a, cloud_fresh_weight(stale, history.xy * size)), marched);
}

// How many layers there are (their rows are packed lowest first; past the last a
// row is zeros).
fn cloud_layer_count() -> u32 {
    let first = switches.clouds[0];
    let second = switches.clouds[1];
    let third = switches.clouds[2];
    return select(0u, 1u, first.y > first.x) + select(0u, 1u, second.y > second.x)
        + select(0u, 1u, third.y > third.x);
}

// The layers marched along the pixel's ray in the order it meets them (upward the
// lowest first, downward the highest), `nearest` the first one's entry. Each
// layer's light is dimmed by the layers in front of it and by the haze up to its
// entry; the haze's own light is laid in front of the first.
fn march_clouds(in: SkyVarying, camera: vec3<f32>, ray: vec3<f32>, nearest: f32, count: u32) -> vec4<f32> {
    // A fixed jitter per pixel hides the steps' banding.
    let pixel = vec2<u32>(in.clip.xy);
    // A jitter per pixel hides the steps' banding; it moves on each round of 16
    // frames (cloud_drift.w), so a pixel marched again samples between its last
    // march's steps and the reuse averages them.
    let jitter = fract(f32(pcg_hash(pixel.x * 7919u + pixel.y * 104729u) >> 8u) / 16777216.0 + switches.cloud_drift.w);
    var light_transmittance = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    // The air between the camera and the first layer (precipitation_haze): its
    // light as a share of the horizon's, and its transmittance. Past the first
    // entry there are no shafts (they hang under the lowest base): a layer
    // further on is dimmed by the clear air between (and from above the base by
    // the precipitation, which falls everywhere there).
    let sigma_p = switches.cloud_extinction.w;
    let sigma_rest = max(switches.to_sun_extinction.w - sigma_p, 0.0);
    let haze = air_to_clouds(camera, ray, nearest, sigma_rest, sigma_p);
    let above = camera.y >= layer_row(0u).x;
    let sigma_on = sigma_rest + select(0.0, sigma_p, above);
    for (var n = 0u; n < count; n += 1u) {
        let i = select(count - 1u - n, n, ray.y >= 0.0);
        let slab = layer_slab(i, camera, ray);
        if (slab.y <= slab.x) {
            continue;
        }
        let before = light_transmittance;
        let lit = march_layer(i, camera, ray, slab, jitter, before.w);
        let dim = haze.y * exp(-sigma_on * max(slab.x - nearest, 0.0));
        light_transmittance = vec4<f32>(before.xyz + lit.xyz * dim, lit.w);
        if (lit.w < 0.01) {
            break;
        }
    }
    // The air's own light in front of the clouds, premultiplied, over the share
    // h·T of the sky behind that passes.
    let horizon = switches.sky_colour_time.xyz;
    return vec4<f32>(
        light_transmittance.xyz + horizon * haze.x,
        1.0 - haze.y * light_transmittance.w,
    );
}

// The air over the ray's first `t` m (precipitation_haze), uniform where nothing
// falls here or beyond (no texture loop run: the branch reads `switches`).
fn air_to_clouds(camera: vec3<f32>, ray: vec3<f32>, t: f32, sigma_rest: f32, sigma_p: f32) -> vec2<f32> {
    if (sigma_p > 0.0 || switches.cloud_drift.z > 0.0) {
        return precipitation_haze(camera, ray, t, sigma_rest, sigma_p, switches.cloud_drift.z);
    }
    let transmittance = exp(-sigma_rest * max(t, 0.0));
    return vec2<f32>(1.0 - transmittance, transmittance);
}

// precipitation_haze (precip_model::drawing::clouds::precipitation_haze): what the
// air between the camera and `t_end` along the ray does to what lies behind it —
// its light as a share of the horizon's (x) and its transmittance (y): the clear
// air and the precipitation within LOCAL_WEATHER_RADIUS_M, the clear air and the
// shafts under the lowest layer's clouds beyond (docs/model.md (6.16)).
fn precipitation_haze(camera: vec3<f32>, ray: vec3<f32>, t_end: f32, rest: f32, local: f32, shaft_max: f32) -> vec2<f32> {
    let lowest = layer_row(0u);
    let near = rest + local;
    if (t_end <= LOCAL_WEATHER_RADIUS_M || camera.y >= lowest.x) {
        let t = exp(-near * max(t_end, 0.0));
        return vec2<f32>(1.0 - t, t);
    }
    var transmittance = exp(-near * LOCAL_WEATHER_RADIUS_M);
    var light = 1.0 - transmittance;
    var t_base = t_end;
    if (ray.y > 0.0) {
        t_base = clamp((lowest.x - camera.y) / ray.y, LOCAL_WEATHER_RADIUS_M, t_end);
    }
    let dt = (t_base - LOCAL_WEATHER_RADIUS_M) / f32(RAIN_SHAFT_SAMPLES);
    for (var k = 0u; k < RAIN_SHAFT_SAMPLES; k += 1u) {
        let p = camera + ray * (LOCAL_WEATHER_RADIUS_M + (f32(k) + 0.5) * dt);
        let uv = cloud_map_uv(p, switches.cloud_drift.xy);
        let shaft = shaft_max * cloud_column(lowest.z, textureSampleLevel(cloud_map, cloud_sampler, uv, 0.0).r);
        let sigma = rest + shaft;
        let step = exp(-sigma * dt);
        if (sigma > 0.0) {
            light += transmittance * (1.0 - step) * (rest + CLOUD_BASE_SKY_SHARE * shaft) / sigma;
        }
        transmittance *= step;
    }
    let step = exp(-rest * (t_end - t_base));
    light += transmittance * (1.0 - step);
    return vec2<f32>(light, transmittance * step);
}

// Layer `i` marched over `slab` behind a transmittance `transmittance_in`: the light
// it sends toward the camera (times the transmittance in front of each step) and the
// transmittance behind it. CLOUD_VIEW_STEPS steps, each lit by the sun through
// CLOUD_SUN_SAMPLES samples toward it up to the layer's top (Beer's law) and the
// two-lobe phase function, and by the sky's light, weaker with depth below the top;
// each step's light integrated over it, S·(1 − e^(−σΔ)).
fn march_layer(i: u32, camera: vec3<f32>, ray: vec3<f32>, slab: vec2<f32>, jitter: f32, transmittance_in: f32) -> vec4<f32> {
    let layer = layer_row(i);
    let offset = switches.cloud_drift.xy + cloud_layer_map_offset_m(i);
    let sigma_max = layer_extinction(i);
    let to_sun = switches.to_sun_extinction.xyz;
    let sin_sun = max(to_sun.y, 0.05);
    // The sun's light a unit of extinction scatters toward the camera is
    // light.y·P/4 (as the fog's, docs/model.md (6.6)), P with its octaves.
    let cos_mu = dot(ray, to_sun);
    let dt = (slab.y - slab.x) / f32(CLOUD_VIEW_STEPS);
    var transmittance = transmittance_in;
    var light = vec3<f32>(0.0);
    for (var k = 0u; k < CLOUD_VIEW_STEPS; k += 1u) {
        let p = camera + ray * (slab.x + (f32(k) + jitter) * dt);
        let rho = cloud_density_at(p, layer, offset);
        if (rho > 0.0) {
            let h = (p.y - layer.x) / max(layer.y - layer.x, 1.0);
            // Toward the sun up to the layer's top (at most 3 km).
            let reach = min((layer.y - p.y) / sin_sun, 3000.0);
            var optical = 0.0;
            for (var s = 0u; s < CLOUD_SUN_SAMPLES; s += 1u) {
                let q = p + to_sun * (reach * (f32(s) + 0.5) / f32(CLOUD_SUN_SAMPLES));
                optical += cloud_density_at(q, layer, offset);
            }
            let sun = switches.light.y * 0.25 * cloud_sun_light(cos_mu, sigma_max * optical * reach / f32(CLOUD_SUN_SAMPLES));
            let scattered = vec3<f32>(sun) + switches.sky_colour_time.xyz * (CLOUD_BASE_SKY_SHARE + (1.0 - CLOUD_BASE_SKY_SHARE) * h);
            let step_transmittance = exp(-sigma_max * rho * dt);
            light += transmittance * scattered * (1.0 - step_transmittance);
            transmittance *= step_transmittance;
            if (transmittance < 0.01) {
                break;
            }
        }
    }
    return vec4<f32>(light, transmittance);
}
