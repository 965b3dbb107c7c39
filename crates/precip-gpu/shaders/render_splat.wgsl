// render_splat.wgsl: sub-pixel particles drawn by compute (docs/model.md §5 sizing, docs/architecture.md
// §2 step 4). A particle whose sprite or streak would be drawn below `min px` (so the
// sprite would be enlarged to it, its opacity scaled down) is not rasterised: the
// kernel `splat_particles` projects its centre, tests it against the scene's depth at
// the four nearest pixel centres, and adds its light there with bilinear weights —
// the same ink (opacity × px²), colour, shadow and fog as its sprite would have — into
// an accumulation buffer of fixed-point sums, so the result is order-independent and
// identical on every backend. `vs/fs_splat_resolve` blend the sums over the frame
// (before the near particles' sprites) and zero them for the next frame.
//
// Accumulation: 4 × u32 per pixel, row-major: Σ a·r, Σ a·g, Σ a·b, Σ a, in units of
// 1 / SPLAT_UNITS, where a is the opacity a particle adds to the pixel. Coverage is
// 1 − exp(−Σ a) (the product of (1 − a) for small a), the colour Σ a·c / Σ a.

// Group 2 of the splat kernel: the scene's depth (read), the sums, and the frame's
// draws (the splat list's count; the list is `drawn` from 2N).
@group(2) @binding(3) var scene_depth: texture_depth_2d;
@group(2) @binding(4) var<storage, read_write> splat_sums: array<atomic<u32>>;
@group(2) @binding(6) var<storage, read> splat_draws: FrameDraws;
// Group 2 of the resolve: the same sums, read and zeroed by one fragment per pixel
// (no atomics: nothing else touches them during the draw).
@group(2) @binding(5) var<storage, read_write> resolved_sums: array<u32>;

// Fixed-point units per unit of opacity (2^14: a pixel saturates long before 2^18
// opaque particles overflow it).
const SPLAT_UNITS: f32 = 16384.0;

// The sprites' sizing in the frame's pixels: params.sizing is in the particles'
// image's (precip_model::ParticleResolution), lens.z frame pixels a drawn one.
fn frame_sizing() -> vec4<f32> {
    let f = max(params.lens.z, 1.0);
    return vec4<f32>(params.sizing.x, params.sizing.y / f, params.sizing.z * f * f, params.sizing.w);
}

// Colour and ink (opacity·px²) of a sub-pixel particle, as its sprite or streak of
// the frame's resolution would draw it with `weight` particles' ink (up to opaque):
// what the particles' image leaves to the splat below its own minimum size keeps
// the light the frame's sprite would have.
fn splat_look(p: Particle, distance_m: f32, weight: f32) -> vec4<f32> {
    let pixel_angle = params.view_dir_pixel_angle.w;
    let sizing = frame_sizing();
    if (kind_is_drop(particle_kind(p.flags))) {
        let size = raindrop_sizing(length(p.velocity_mps), p.diameter_m, distance_m, pixel_angle, sizing);
        let to_viewer = normalize_or_zero(params.camera_m_cone_cos.xyz - p.position_m);
        let air = air_between(switches.camera_m_cone_cos.xyz, p.position_m, switches.fog_layer);
        let environment = drop_environment_factor(-to_viewer.y, drop_ground_albedo[0]);
        let colour = rain_colour(to_viewer, to_viewer, shadow_lit(p.position_m), air, environment);
        let opacity = min(1.0, weight * size.z * params.cover_look.x);
        let ink = splat_ink(true, vec3<f32>(size.x, size.y, opacity), distance_m, pixel_angle, 0.0);
        return vec4<f32>(colour, ink);
    }
    let size = snow_sprite_sizing(p.diameter_m, distance_m, pixel_angle, sizing);
    let opacity = min(1.0, weight * size.y);
    let ink = splat_ink(false, vec3<f32>(size.x, opacity, 0.0), distance_m, pixel_angle, params.cover_look2.w);
    return vec4<f32>(snow_colour(p), ink);
}

// Over the splat list (the cull's, `drawn` from 2N): each invocation walks it with
// the dispatch's stride (precip_gpu::recipe::DispatchOver::ParticleList), so the
// kernel's lanes are all splatting particles.
@compute @workgroup_size(64)
fn splat_particles(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let lanes = groups.x * groups.y * 64u;
    let list = 2u * params.counts.x;
    let count = splat_draws.splatted;
    for (var k = linear_index(id, groups); k < count; k += lanes) {
        splat_particle(drawn[list + k]);
    }
}

// Adds particle `i`'s ink along the streak it draws during the exposure (sizing.w):
// a drop's from its centre back along its fall, tapering to the tail as its
// tetrahedron does; a flake's across its centre, evenly, as its swept sprite. A
// sample every two pixels of the streak (at most eight), each spreading its share
// bilinearly over the four nearest pixels, depth-tested there; a streak under two
// pixels is one sample at the centre.
fn splat_particle(i: u32) {
    let p = particles[i];
    let camera = params.camera_m_cone_cos.xyz;
    // Drawn or not by its pool's multiplicity, but with its own ink only where it is
    // sub-pixel in the frame: what it stands for beyond itself is already in the
    // haze, whose extinction is the whole air's (precip_model::drawing::multiplicity).
    let look = splat_look(p, distance(p.position_m, camera), resolved_weight(i, p));
    var from_m = p.position_m;
    var to_m = p.position_m;
    let is_rain = kind_is_drop(particle_kind(p.flags));
    if (is_rain) {
        to_m = p.position_m - normalize_or_zero(p.velocity_mps) * params.sizing.w * length(p.velocity_mps);
    } else {
        let n = normalize_or_zero(camera - p.position_m);
        let sweep = params.sizing.w * (p.velocity_mps - n * dot(n, p.velocity_mps));
        from_m = p.position_m - 0.5 * sweep;
        to_m = p.position_m + 0.5 * sweep;
    }
    let size = vec2<f32>(textureDimensions(scene_depth));
    let ends = array<vec4<f32>, 2>(
        params.view_proj * vec4<f32>(from_m, 1.0),
        params.view_proj * vec4<f32>(to_m, 1.0),
    );
    var length_px = 0.0;
    if (ends[0].w > 0.0 && ends[1].w > 0.0) {
        length_px = distance(ends[0].xy / ends[0].w * size, ends[1].xy / ends[1].w * size) * 0.5;
    }
    // A flake's streak a sample every 2 px (at most 8); a drop's, thin and long,
    // every pixel (at most 32).
    let spacing_px = select(2.0, 1.0, is_rain);
    let samples = clamp(u32(ceil(length_px / spacing_px)), 1u, select(8u, 32u, is_rain));
    for (var k = 0u; k < samples; k += 1u) {
        var t = 0.5;
        var share = 1.0;
        if (samples > 1u) {
            t = (f32(k) + 0.5) / f32(samples);
            // The drop's streak tapers from its head to its tail: shares 2(1 − t)/n.
            share = select(1.0, 2.0 * (1.0 - t), is_rain) / f32(samples);
        }
        splat_at(mix(from_m, to_m, t), vec4<f32>(look.rgb, look.a * share));
    }
}

// Adds ink `look.a` of colour `look.rgb` at world point `position_m`: its four
// nearest pixels by bilinear weights, where it is in front of the scene.
fn splat_at(position_m: vec3<f32>, look: vec4<f32>) {
    let clip = params.view_proj * vec4<f32>(position_m, 1.0);
    if (!(clip.w > 0.0)) {
        return;
    }
    let ndc = clip.xyz / clip.w;
    if (ndc.z < 0.0 || ndc.z > 1.0) {
        return;
    }
    let size = vec2<i32>(textureDimensions(scene_depth));
    // Pixel coordinates with pixel centres at integers (rows top to bottom).
    let at = vec2<f32>(0.5 * ndc.x + 0.5, 0.5 - 0.5 * ndc.y) * vec2<f32>(size) - 0.5;
    if (any(at < vec2<f32>(-1.0)) || any(at > vec2<f32>(size))) {
        return;
    }
    let base = vec2<i32>(floor(at));
    let f = at - floor(at);
    for (var k = 0; k < 4; k++) {
        let xy = base + vec2<i32>(k & 1, k >> 1u);
        if (any(xy < vec2<i32>(0)) || any(xy >= size)) {
            continue;
        }
        if (ndc.z > textureLoad(scene_depth, xy, 0)) {
            continue;
        }
        let w = select(1.0 - f.x, f.x, (k & 1) == 1) * select(1.0 - f.y, f.y, k >= 2);
        let a = w * look.a;
        let units = vec4<u32>(round(vec4<f32>(look.rgb * a, a) * SPLAT_UNITS));
        if (units.w == 0u) {
            continue;
        }
        let o = 4u * u32(xy.y * size.x + xy.x);
        atomicAdd(&splat_sums[o], units.x);
        atomicAdd(&splat_sums[o + 1u], units.y);
        atomicAdd(&splat_sums[o + 2u], units.z);
        atomicAdd(&splat_sums[o + 3u], units.w);
    }
}

// A triangle covering the target.
@vertex
fn vs_splat_resolve(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_splat_resolve(@builtin(position) pixel: vec4<f32>) -> @location(0) vec4<f32> {
    return resolved_splat(pixel);
}

// The splat's colour and opacity at `pixel` (straight alpha); zeroes its sums.
fn resolved_splat(pixel: vec4<f32>) -> vec4<f32> {
    let width = frame_counts().w;
    if (width == 0u) {
        return vec4<f32>(0.0);
    }
    let o = 4u * (u32(pixel.y) * width + u32(pixel.x));
    let w = resolved_sums[o + 3u];
    if (w == 0u) {
        return vec4<f32>(0.0);
    }
    let sums = vec4<f32>(f32(resolved_sums[o]), f32(resolved_sums[o + 1u]), f32(resolved_sums[o + 2u]), f32(w)) / SPLAT_UNITS;
    resolved_sums[o] = 0u;
    resolved_sums[o + 1u] = 0u;
    resolved_sums[o + 2u] = 0u;
    resolved_sums[o + 3u] = 0u;
    return vec4<f32>(sums.rgb / sums.w, 1.0 - exp(-sums.w));
}
