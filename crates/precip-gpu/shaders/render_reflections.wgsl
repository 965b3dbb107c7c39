// render_reflections.wgsl: the scene mirrored in standing water (screen-space
// reflections over the frame before), for the scene pass's water.
//
// After the scene pass the frame's colour and depth are copied (the `scene_copy`
// pass: scene_copy, depth_copy); the next frame's water follows its mirrored ray —
// the view ray reflected about the level water surface — across that frame, through
// its camera (previous_view_proj). Where the ray passes behind a surface that frame
// shows, it has met the scene: the sky the mirror reflects (water_look.wgsl's
// water_surface) is replaced by what the frame shows there. Where it leaves the
// frame, reaches the sky or runs past REFLECTION_REACH_M, the sky stays, faded over
// the frame's edge and the reach so no seam shows. A frame late (as game engines'
// screen-space reflections read the last frame's colour), so only the pixels that
// hold water pay for it and no pass over every pixel is added. The rain's rings and
// the waves tilt the surface the ray leaves (water_slope), so they break up the
// scene's image as they do the sky's.
// No Rust twin: a drawing technique over the frame, no formula of the model
// (Fresnel and the sky are water_look's, twinned there).
// Program: the Render program's files, after render_scene.wgsl (which calls it).

@group(3) @binding(0) var scene_copy: texture_2d<f32>;
@group(3) @binding(1) var depth_copy: texture_depth_2d;
// The water bodies' mirror (precip_model::drawing::water_mirror): the scene drawn
// through params.mirror_view_proj at half the frame's side, transparent where
// nothing stands (the sky).
@group(3) @binding(2) var mirror_image: texture_2d<f32>;

// Steps along the ray, spaced geometrically from REFLECTION_NEAR_M to
// REFLECTION_REACH_M, then halved REFLECTION_REFINE times around the first crossing.
// Clip coordinates are affine along a ray, so a step is four multiply-adds and one
// depth texel, no matrix.
const REFLECTION_STEPS: u32 = 16u;
const REFLECTION_REFINE: u32 = 3u;
const REFLECTION_NEAR_M: f32 = 0.1;
const REFLECTION_REACH_M: f32 = 100.0;
// What a level mirror shows lies above it: a crossing less than this above the
// water is the water's own surface or its banks' (a pixel's footprint at a grazing
// view is longer than the first steps), and the march goes on.
const REFLECTION_ABOVE_M: f32 = 0.05;
// Below this weight of the mirror (1/255 of the pixel at most) no ray is followed.
const REFLECTION_LEAST: f32 = 1.5 / 255.0;

// Clip coordinates `clip` as pixel coordinates of the frame before (y down) and depth.
fn clip_to_pixel(clip: vec4<f32>, size: vec2<f32>) -> vec3<f32> {
    let ndc = clip.xyz / clip.w;
    return vec3<f32>((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y, ndc.z);
}

// What the mirror at `surface_m` sloping by `slope` (water_slope), seen from
// `to_viewer`, shows instead of the sky: (the scene met − the sky) along the
// mirrored ray, faded at the frame's edge and the reach; zero where the ray meets
// nothing or the frame before is not there.
fn mirrored_scene(surface_m: vec3<f32>, to_viewer: vec3<f32>, slope: vec2<f32>) -> vec3<f32> {
    let ray = reflect(-to_viewer, normalize(vec3<f32>(-slope.x, 1.0, -slope.y)));
    if (params.water_look.y < 0.5 || ray.y <= 0.0) {
        return vec3<f32>(0.0);
    }
    let size = vec2<f32>(textureDimensions(scene_copy));
    let c0 = params.previous_view_proj * vec4<f32>(surface_m, 1.0);
    let dc = params.previous_view_proj * vec4<f32>(ray, 0.0);
    let grow = pow(REFLECTION_REACH_M / REFLECTION_NEAR_M, 1.0 / f32(REFLECTION_STEPS - 1u));
    var before = 0.0;
    var t = REFLECTION_NEAR_M;
    for (var i = 0u; i < REFLECTION_STEPS; i += 1u) {
        let clip = c0 + dc * t;
        if (clip.w <= 1e-4) {
            break;
        }
        let at = clip_to_pixel(clip, size);
        if (at.x < 0.0 || at.y < 0.0 || at.x >= size.x || at.y >= size.y) {
            break;
        }
        let depth = textureLoad(depth_copy, vec2<i32>(at.xy), 0);
        if (depth < 1.0 && at.z > depth && t * ray.y > REFLECTION_ABOVE_M) {
            // Behind the surface shown there: crossed it since `before`. Halve the
            // interval around the crossing.
            var lo = before;
            var hi = t;
            for (var k = 0u; k < REFLECTION_REFINE; k += 1u) {
                let mid = 0.5 * (lo + hi);
                let m = clip_to_pixel(c0 + dc * mid, size);
                if (m.z > textureLoad(depth_copy, vec2<i32>(m.xy), 0)) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let hit = clip_to_pixel(c0 + dc * hi, size);
            let found = textureLoad(scene_copy, vec2<i32>(hit.xy), 0).rgb;
            let uv = hit.xy / size;
            let edge = min(min(uv.x, 1.0 - uv.x), min(uv.y, 1.0 - uv.y));
            let weight = smoothstep(0.0, 0.08, edge)
                * (1.0 - smoothstep(0.7 * REFLECTION_REACH_M, REFLECTION_REACH_M, hi));
            return weight * (found - overcast_sky(params.sky_colour_time.xyz, ray));
        }
        before = t;
        t *= grow;
    }
    return vec3<f32>(0.0);
}

// The planar mirror (precip_model::drawing::water_mirror): constants twinned there.
const MIRROR_LEVEL_TOLERANCE_M: f32 = 0.05;
const MIRROR_SLOPE_REACH: f32 = 0.02;
// What lies this far below the mirror's level is under the water: not reflected.
const MIRROR_CUT_M: f32 = 0.005;

// The scene but the water bodies, reflected about the water's level, into the
// mirror image: lit and fogged as seen from the reflected camera; what lies below
// the level cut.
@fragment
fn fs_mirror(in: SceneVarying) -> @location(0) vec4<f32> {
    return mirror_fragment(in);
}

fn mirror_fragment(in: SceneVarying) -> vec4<f32> {
    // From the storage copy: a branch tests it (render_scene.wgsl's `switches`).
    let level = switches.mirror.x;
    if (in.world_m.y < level - MIRROR_CUT_M) {
        discard;
    }
    let camera = params.camera_m_cone_cos.xyz;
    let reflected = vec3<f32>(camera.x, 2.0 * level - camera.y, camera.z);
    let look = surface_look(in, reflected, true);
    // The fog layer reflected with the camera: the path's part above the water, in
    // fog below the top, lies between the reflected top and the level; the sun's
    // scattered light is left out (its dimming from the top is not a line there).
    let fog = switches.fog_layer;
    let layer = vec4<f32>(fog.x, 2.0 * level - fog.x, fog.z, 0.0);
    return vec4<f32>(with_air(look.shaded, air_between(reflected, in.world_m, layer)), 1.0);
}

// The water bodies when the mirror is drawn: as fs_water_body, what their mirror
// shows read from its image at the pixel (no ray); a body at another level mirrors
// the sky.
@fragment
fn fs_water_body_planar(in: SceneVarying) -> @location(0) vec4<f32> {
    let camera = params.camera_m_cone_cos.xyz;
    var look = surface_look(in, camera, true);
    if (look.mirror > REFLECTION_LEAST && abs(in.surface_m.y - switches.mirror.x) <= MIRROR_LEVEL_TOLERANCE_M) {
        let to_viewer = normalize_or_zero(camera - in.world_m);
        look.shaded += look.mirror * planar_mirrored_scene(in.clip.xy, to_viewer, look.water_slope);
    }
    let seen = with_air(look.shaded, air_between(camera, in.world_m, switches.fog_layer));
    return vec4<f32>(with_unresolved_streaks(seen, in.clip.xy, distance(camera, in.world_m)), 1.0);
}

// What the mirror shows instead of the sky at pixel `frag_xy`: (the mirror image
// − the sky it covers). Waves tilt the surface: the image is read where the tilted
// ray's reflection points, at most MIRROR_SLOPE_REACH of the frame away — the shift
// of the ray's vanishing point (exact for what is far, more than enough for what is
// near).
fn planar_mirrored_scene(frag_xy: vec2<f32>, to_viewer: vec3<f32>, slope: vec2<f32>) -> vec3<f32> {
    let size = vec2<f32>(textureDimensions(scene_copy));
    var uv = frag_xy / size;
    let ray = reflect(-to_viewer, normalize(vec3<f32>(-slope.x, 1.0, -slope.y)));
    if (dot(slope, slope) > 0.0) {
        // The reflections of the level and the tilted rays, seen through the mirror.
        // The storage copy of the camera: a branch tests what it gives.
        let level = switches.view_proj * vec4<f32>(-to_viewer, 0.0);
        let tilted = switches.view_proj * vec4<f32>(ray.x, -ray.y, ray.z, 0.0);
        if (level.w > 1.0e-4 && tilted.w > 1.0e-4) {
            let shift = (tilted.xy / tilted.w - level.xy / level.w) * vec2<f32>(0.5, -0.5);
            let reach = length(shift);
            uv += shift * min(1.0, MIRROR_SLOPE_REACH / max(reach, 1.0e-6));
        }
    }
    let found = textureSampleLevel(mirror_image, cover_sampler, uv, 0.0);
    return found.rgb - found.a * overcast_sky(params.sky_colour_time.xyz, ray);
}
