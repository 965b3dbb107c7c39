// render_clouds.wgsl: the cloud layer marched into the clouds' image (a quarter of
// the frame's side), which the sky lays over itself (fs_sky_clouds). The formulas are
// drawing.wgsl's twins of precip_model::drawing::clouds; docs/model.md (6.9)-(6.13).
//
// Temporal reuse (docs/model.md (6.14)): there are two images, written on
// alternate frames (pass "clouds" into A, "clouds_b" into B), each reading the other
// as the frame before's (`cloud_image`, group 1). A frame marches one tile in 16
// (cloud_march_slot, switches.cloud_shadow.y; CLOUD_MARCH_ALL: every tile, when
// there is no history) and takes every other pixel from where the frame before's
// camera saw its ray's entry into the layer; where that lies outside the image it
// marches.

// The clear sky between the clouds: the haze's colour at the horizon, deeper blue
// toward the zenith (a look, not a sky model).
fn clear_sky(horizon: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let zenith = vec3<f32>(0.16, 0.3, 0.62);
    return mix(horizon, zenith, 1.0 - exp(-3.0 * max(dir.y, 0.0)));
}

// The triangle covering the clouds' image (as vs_sky's): into image A, reading B.
@vertex
fn vs_clouds(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

@fragment
fn fs_clouds(in: SkyVarying) -> @location(0) vec4<f32> {
    return clouds_with_history(in);
}

// The same into image B, reading A.
@vertex
fn vs_clouds_b(@builtin(vertex_index) v: u32) -> SkyVarying {
    return sky_triangle(v);
}

@fragment
fn fs_clouds_b(in: SkyVarying) -> @location(0) vec4<f32> {
    return clouds_with_history(in);
}

// The density at p of the layer `layer` (base, top, coverage, kind), drifted by
// `drift.xy`.
fn cloud_density_at(p: vec3<f32>, layer: vec4<f32>, drift: vec4<f32>) -> f32 {
    let h = (p.y - layer.x) / max(layer.y - layer.x, 1.0);
    let uvs = cloud_map_uvs(p, drift.xy);
    let m = textureSampleLevel(cloud_map, cloud_sampler, uvs.xy, 0.0).r;
    let d = textureSampleLevel(cloud_map, cloud_sampler, uvs.zw, 0.0).r;
    return cloud_density(u32(layer.w), layer.z, m, d, h);
}

// The light the layer and the haze in front of it send along the pixel's ray
// (premultiplied) and their opacity: CLOUD_VIEW_STEPS steps through the layer, each lit
// by the sun through CLOUD_SUN_SAMPLES samples toward it (Beer's law) and the
// two-lobe phase function, and by the sky's light, weaker with depth below the
// top; each step's light integrated over it, S·(1 − e^(−σΔ)).
fn clouds_with_history(in: SkyVarying) -> vec4<f32> {
    let far = switches.inverse_view_proj * vec4<f32>(in.ndc, 1.0, 1.0);
    let camera = switches.camera_m_cone_cos.xyz;
    let ray = normalize_or_zero(far.xyz / far.w - camera);
    let layer = switches.clouds;
    let drift = switches.cloud_drift;
    let slab = cloud_slab(camera.y, ray.y, layer.x, layer.y);
    if (slab.y <= slab.x) {
        return vec4<f32>(0.0);
    }
    // Not this tile's frame: the frame before's image where its camera saw the
    // ray's entry into the layer, moved with the clouds' drift since
    // (cloud_shadow.zw: the map is read at p + drift, so what lies at p now lay
    // there at p + Δ).
    let slot = u32(switches.cloud_shadow.y);
    if (slot < CLOUD_MARCH_ALL && cloud_march_slot(vec2<u32>(in.clip.xy)) != slot) {
        let moved = vec3<f32>(switches.cloud_shadow.z, 0.0, switches.cloud_shadow.w);
        let history = cloud_history_uv(switches.previous_view_proj, camera + ray * slab.x + moved);
        if (history.z > 0.5) {
            return textureSampleLevel(cloud_image, cover_sampler, history.xy, 0.0);
        }
    }
    return march_clouds(in, camera, ray, slab);
}

// The layer marched along the pixel's ray over `slab`.
fn march_clouds(in: SkyVarying, camera: vec3<f32>, ray: vec3<f32>, slab: vec2<f32>) -> vec4<f32> {
    let layer = switches.clouds;
    let drift = switches.cloud_drift;
    let to_sun = switches.to_sun_extinction.xyz;
    let sin_sun = max(to_sun.y, 0.05);
    // The sun's light a unit of extinction scatters toward the camera is
    // light.y·P/4 (as the fog's, docs/model.md (6.6)), P with its octaves.
    let cos_mu = dot(ray, to_sun);
    let dt = (slab.y - slab.x) / f32(CLOUD_VIEW_STEPS);
    // A fixed jitter per pixel hides the steps' banding.
    let pixel = vec2<u32>(in.clip.xy);
    let jitter = f32(pcg_hash(pixel.x * 7919u + pixel.y * 104729u) >> 8u) / 16777216.0;
    var transmittance = 1.0;
    var light = vec3<f32>(0.0);
    for (var i = 0u; i < CLOUD_VIEW_STEPS; i += 1u) {
        let p = camera + ray * (slab.x + (f32(i) + jitter) * dt);
        let rho = cloud_density_at(p, layer, drift);
        if (rho > 0.0) {
            let h = (p.y - layer.x) / max(layer.y - layer.x, 1.0);
            // Toward the sun up to the layer's top (at most 3 km).
            let reach = min((layer.y - p.y) / sin_sun, 3000.0);
            var optical = 0.0;
            for (var k = 0u; k < CLOUD_SUN_SAMPLES; k += 1u) {
                let q = p + to_sun * (reach * (f32(k) + 0.5) / f32(CLOUD_SUN_SAMPLES));
                optical += cloud_density_at(q, layer, drift);
            }
            let sun = switches.light.y * 0.25 * cloud_sun_light(cos_mu, drift.z * optical * reach / f32(CLOUD_SUN_SAMPLES));
            let scattered = vec3<f32>(sun) + switches.sky_colour_time.xyz * (0.4 + 0.6 * h);
            let step_transmittance = exp(-drift.z * rho * dt);
            light += transmittance * scattered * (1.0 - step_transmittance);
            transmittance *= step_transmittance;
            if (transmittance < 0.01) {
                break;
            }
        }
    }
    // The haze between the camera and the layer (clear air and the precipitation
    // falling from it) dims the clouds and what lies behind them, and adds its own
    // light: premultiplied h·L + (1 − h)·A over (1 − h·T) of the sky behind.
    let haze = fog_transmittance(slab.x, switches.to_sun_extinction.w);
    return vec4<f32>(light * haze + switches.sky_colour_time.xyz * (1.0 - haze), 1.0 - haze * transmittance);
}
