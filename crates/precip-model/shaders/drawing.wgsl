// drawing.wgsl: the drawing formulas of docs/model.md §5. Rust twins: precip_model::drawing.

// turned_sprite_sides: A', B' of a sprite facing the camera along `n`.
fn turned_sprite_sides(n: vec3<f32>, spin_rad: f32, tumble: f32) -> array<vec3<f32>, 2> {
    var a = cross(vec3<f32>(0.0, 1.0, 0.0), n);
    if (dot(a, a) < 1.0e-12) {
        a = cross(vec3<f32>(0.0, 0.0, 1.0), n);
    }
    a = normalize(a);
    let b = normalize(cross(n, a));
    let s = sin(spin_rad);
    let c = cos(spin_rad);
    return array<vec3<f32>, 2>(c * a + s * b, tumble * (c * b - s * a));
}

// snow_sprite_corners_turned: corner `corner` (0..3, strip order V0 V1 V2 V3).
fn snow_sprite_corner(centre_m: vec3<f32>, camera_m: vec3<f32>, side_m: f32, spin_rad: f32, tumble: f32, corner: u32) -> vec3<f32> {
    let to_camera = camera_m - centre_m;
    if (dot(to_camera, to_camera) <= 0.0) {
        return centre_m;
    }
    let sides = turned_sprite_sides(normalize(to_camera), spin_rad, tumble);
    let a2 = sides[0];
    let b2 = sides[1];
    let v0 = centre_m + 0.5 * side_m * (a2 - b2);
    switch corner {
        case 0u: { return v0; }
        case 1u: { return v0 + side_m * b2; }
        case 2u: { return v0 - side_m * a2; }
        default: { return v0 + side_m * b2 - side_m * a2; }
    }
}

struct StreakCorner {
    position_m: vec3<f32>,
    uv: vec2<f32>,
    stretch: f32,
}

// snow_quad_axes: a flake's quad as its two sides, corner k at
// centre + (u − ½)·across + (v − ½)·along for its uv (u, v) (snow_sprite_uv), its
// texture's v that v × stretch.
struct SnowQuadAxes {
    across_m: vec3<f32>,
    along_m: vec3<f32>,
    stretch: f32,
}

fn snow_quad_axes(centre_m: vec3<f32>, camera_m: vec3<f32>, side_m: f32, spin_tumble: vec2<f32>, velocity_mps: vec3<f32>, exposure_s: f32) -> SnowQuadAxes {
    let to_camera = camera_m - centre_m;
    if (dot(to_camera, to_camera) <= 0.0) {
        return SnowQuadAxes(vec3<f32>(0.0), vec3<f32>(0.0), 1.0);
    }
    let n = normalize(to_camera);
    let sweep = exposure_s * (velocity_mps - n * dot(n, velocity_mps));
    let length = sqrt(dot(sweep, sweep));
    if (!(length >= 0.5 * side_m)) {
        let sides = turned_sprite_sides(n, spin_tumble.x, spin_tumble.y);
        return SnowQuadAxes(side_m * sides[0], side_m * sides[1], 1.0);
    }
    let along = sweep / length;
    let across = normalize(cross(n, along));
    let stretch = (side_m + length) / side_m;
    return SnowQuadAxes(side_m * across, stretch * side_m * along, stretch);
}

// SnowQuadAxes::corner
fn snow_quad_corner(centre_m: vec3<f32>, axes: SnowQuadAxes, corner: u32) -> StreakCorner {
    let uv = snow_sprite_uv(corner);
    let p = centre_m + (uv.x - 0.5) * axes.across_m + (uv.y - 0.5) * axes.along_m;
    return StreakCorner(p, vec2<f32>(uv.x, uv.y * axes.stretch), axes.stretch);
}

// snow_streak_corners: corner `corner` of a flake swept over the exposure.
fn snow_streak_corner(centre_m: vec3<f32>, camera_m: vec3<f32>, side_m: f32, spin_tumble: vec2<f32>, velocity_mps: vec3<f32>, exposure_s: f32, corner: u32) -> StreakCorner {
    let axes = snow_quad_axes(centre_m, camera_m, side_m, spin_tumble, velocity_mps, exposure_s);
    return snow_quad_corner(centre_m, axes, corner);
}

// snow_streak_texture_v
fn snow_streak_texture_v(v: f32, stretch: f32) -> f32 {
    if (v < 0.5) {
        return v;
    }
    if (v > stretch - 0.5) {
        return v - (stretch - 1.0);
    }
    return 0.5;
}

// SNOW_SPRITE_UV
fn snow_sprite_uv(corner: u32) -> vec2<f32> {
    switch corner {
        case 0u: { return vec2<f32>(1.0, 0.0); }
        case 1u: { return vec2<f32>(1.0, 1.0); }
        case 2u: { return vec2<f32>(0.0, 0.0); }
        default: { return vec2<f32>(0.0, 1.0); }
    }
}

const MIN_TUMBLE: f32 = 0.3;

// flake_spin_tumble: (spin, tumble).
fn flake_spin_tumble(rotation0_rad: vec3<f32>, rotation_rad: vec3<f32>) -> vec2<f32> {
    let o = rotation0_rad + rotation_rad;
    return vec2<f32>(o.y + o.z, max(abs(cos(o.x)), MIN_TUMBLE));
}

// snow_sprite_sizing: (side_m, opacity). sizing = (snow scale, min px, min opacity, _).
fn snow_sprite_sizing(diameter_m: f32, distance_m: f32, pixel_angle_rad: f32, sizing: vec4<f32>) -> vec2<f32> {
    let side = diameter_m * sizing.x;
    let min_side = sizing.y * pixel_angle_rad * distance_m;
    if (side >= min_side) {
        return vec2<f32>(side, 1.0);
    }
    let ratio = side / min_side;
    return vec2<f32>(min_side, max(ratio * ratio, sizing.z));
}

// sub_pixel: whether a particle `length_m` long is drawn below `min_px` pixels.
fn sub_pixel(length_m: f32, distance_m: f32, pixel_angle_rad: f32, min_px: f32) -> bool {
    return length_m < min_px * pixel_angle_rad * distance_m;
}

// splat_ink: (opacity·px²) of a snow sprite (is_rain false: side × side × opacity ×
// the flake texture's mean) or a rain tetrahedron (h × a / 2 × opacity) of the given
// sizes, seen from `distance_m`.
fn splat_ink(is_rain: bool, size: vec3<f32>, distance_m: f32, pixel_angle_rad: f32, flake_mean_opacity: f32) -> f32 {
    let px = 1.0 / max(pixel_angle_rad * distance_m, 1.0e-12);
    if (is_rain) {
        return 0.5 * size.x * px * size.y * px * size.z;
    }
    let side_px = size.x * px;
    return side_px * side_px * size.y * flake_mean_opacity;
}

// defocus_blur_m: the thin lens's blur circle at `distance_m`, m across.
fn defocus_blur_m(aperture_m: f32, focus_distance_m: f32, distance_m: f32) -> f32 {
    return aperture_m * abs(1.0 - distance_m / max(focus_distance_m, 1.0e-3));
}

// defocused: (width, opacity) spread by `blur_m`, the ink kept (power 2: a sprite).
fn defocused(width_m: f32, opacity: f32, blur_m: f32, power: i32) -> vec2<f32> {
    let wide = width_m + max(blur_m, 0.0);
    if (wide <= 0.0) {
        return vec2<f32>(width_m, opacity);
    }
    let r = width_m / wide;
    return vec2<f32>(wide, opacity * select(r, r * r, power == 2));
}

// NEAR_FADE_START_M, NEAR_FADE_END_M
const NEAR_FADE_START_M: f32 = 0.5;
const NEAR_FADE_END_M: f32 = 1.5;

// near_fade: opacity factor of a particle `distance_m` from the camera.
fn near_fade(distance_m: f32) -> f32 {
    return smoothstep(NEAR_FADE_START_M, NEAR_FADE_END_M, distance_m);
}

// raindrop_sizing: (h_m, a_m, opacity). sizing.w = the exposure, s.
fn raindrop_sizing(speed_mps: f32, diameter_m: f32, distance_m: f32, pixel_angle_rad: f32, sizing: vec4<f32>) -> vec3<f32> {
    let d = max(diameter_m, 1.0e-5);
    let h = max(sizing.w * speed_mps, d);
    let opacity = min(1.5707964 * d / h, 1.0);
    let min_a = sizing.y * pixel_angle_rad * distance_m;
    if (d >= min_a) {
        return vec3<f32>(h, d, opacity);
    }
    return vec3<f32>(h, min_a, opacity * d / min_a);
}

struct TetrahedronVertex {
    position_m: vec3<f32>,
    normal: vec3<f32>,
}

fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l2 = dot(v, v);
    if (l2 > 0.0) {
        return v * inverseSqrt(l2);
    }
    return vec3<f32>(0.0);
}

// raindrop_tetrahedron_sized: vertex `k` (0..3) with the seed's normal N_k.
fn raindrop_vertex(centre_m: vec3<f32>, velocity_mps: vec3<f32>, h: f32, a: f32, k: u32) -> TetrahedronVertex {
    if (dot(velocity_mps, velocity_mps) <= 0.0) {
        return TetrahedronVertex(centre_m, vec3<f32>(0.0, 1.0, 0.0));
    }
    let e_y = normalize(-velocity_mps);
    var e_z = cross(vec3<f32>(1.0, 0.0, 0.0), e_y);
    if (dot(e_z, e_z) < 1.0e-12) {
        e_z = cross(vec3<f32>(0.0, 0.0, 1.0), e_y);
    }
    e_z = normalize(e_z);
    let e_x = normalize(cross(e_y, e_z));
    let r = sqrt(3.0) / 3.0 * a;
    let v0 = centre_m + h * e_y;
    let v1 = centre_m - 0.5 * r * e_x - 0.5 * a * e_z;
    let v2 = centre_m + r * e_x;
    let v3 = v1 + a * e_z;
    switch k {
        case 0u: { return TetrahedronVertex(v0, e_y); }
        case 1u: { return TetrahedronVertex(v1, normalize_or_zero(v1 - centre_m) + normalize_or_zero(v1 - v0)); }
        case 2u: { return TetrahedronVertex(v2, e_x + normalize_or_zero(v2 - v0)); }
        default: { return TetrahedronVertex(v3, normalize_or_zero(v3 - centre_m) + normalize_or_zero(v3 - v0)); }
    }
}

// RAIN_TETRAHEDRON_STRIP: vertex i (0..5) of the strip 0 1 2 3 0 1.
fn rain_tetrahedron_strip_vertex(i: u32) -> u32 {
    return i % 4u;
}

// in_view_cone
fn in_view_cone(position_m: vec3<f32>, camera_m: vec3<f32>, view_dir: vec3<f32>, cone_cos: f32) -> bool {
    let d = position_m - camera_m;
    let l2 = dot(d, d);
    if (!(l2 > 0.0)) {
        return false;
    }
    return dot(d * inverseSqrt(l2), view_dir) >= cone_cos;
}

// drop_oscillation_hz, drop_oscillation_brightness
// (precip_model::drawing::drop_oscillation): a drop's fundamental oscillation,
// √(8σ/(ρ_w r³))/2π, and its brightness 1 + A·cos(2π·cycles).
const WATER_SURFACE_TENSION_N_PER_M: f32 = 0.074;
const DROP_OSCILLATION_CONTRAST: f32 = 0.25;
fn drop_oscillation_hz(diameter_m: f32) -> f32 {
    let r = 0.5 * max(diameter_m, 1.0e-5);
    return sqrt(8.0 * WATER_SURFACE_TENSION_N_PER_M / (1000.0 * r * r * r)) / 6.2831855;
}
fn drop_oscillation_brightness(cycles: f32) -> f32 {
    return 1.0 + DROP_OSCILLATION_CONTRAST * cos(6.2831855 * cycles);
}

// flake_sun_phase (precip_model::drawing::flake_sun_phase): ½ Henyey–Greenstein of
// the delta-Eddington asymmetry g/(1 + g), g = FLAKE_ASYMMETRY.
const FLAKE_ASYMMETRY: f32 = 0.75;
fn flake_sun_phase(cos_scatter: f32) -> f32 {
    let g = FLAKE_ASYMMETRY / (1.0 + FLAKE_ASYMMETRY);
    let d = 1.0 + g * g - 2.0 * g * clamp(cos_scatter, -1.0, 1.0);
    return 0.5 * (1.0 - g * g) / (d * sqrt(d));
}

// drop_field_shares, drop_environment_factor (precip_model::drawing::drop_environment):
// the CIE overcast sky's mean over a drop's 165° field of view, in units of the
// horizon's radiance, and the share of the field below the horizon; the radiance the
// drop passes on, with ground of albedo `ground_albedo` below.
const DROP_HALF_FIELD_RAD: f32 = 1.4398966;
const DROP_REFRACTED_SHARE: f32 = 0.94;
const OVERCAST_GROUND_RADIANCE_PER_ALBEDO: f32 = 2.3333333;
const DROP_PI: f32 = 3.14159265;
const BARE_GROUND_ALBEDO: f32 = 0.2;
fn drop_field_shares(sin_elevation: f32) -> vec2<f32> {
    let s = clamp(sin_elevation, -1.0, 1.0);
    let sin_a = sin(DROP_HALF_FIELD_RAD);
    let cos_a = cos(DROP_HALF_FIELD_RAD);
    let solid_angle = 2.0 * DROP_PI * (1.0 - cos_a);
    let cos_e = sqrt(max(1.0 - s * s, 0.0));
    if (cos_e <= cos_a) {
        if (s > 0.0) {
            return vec2<f32>((solid_angle + 2.0 * DROP_PI * sin_a * sin_a * s) / solid_angle, 0.0);
        }
        return vec2<f32>(0.0, 1.0);
    }
    let rim = acos(clamp(-s * cos_a / (sin_a * cos_e), -1.0, 1.0));
    let chord = acos(clamp(cos_a / cos_e, -1.0, 1.0));
    let upper = 2.0 * (DROP_PI - acos(clamp(s / sin_a, -1.0, 1.0)) - cos_a * rim);
    let first_moment = chord + sin_a * sin_a * s * rim - cos_a * sin_a * cos_e * sin(rim);
    return vec2<f32>((upper + 2.0 * first_moment) / solid_angle, clamp(1.0 - upper / solid_angle, 0.0, 1.0));
}
fn drop_environment_factor(sin_elevation: f32, ground_albedo: f32) -> f32 {
    let shares = drop_field_shares(sin_elevation);
    return DROP_REFRACTED_SHARE * (shares.x + shares.y * max(ground_albedo, 0.0) * OVERCAST_GROUND_RADIANCE_PER_ALBEDO);
}

// drop_ground_offset_m (precip_model::drawing::drop_environment): lattice point k of
// the square around the camera over which the drops' ground is averaged (the
// drop_ground kernel, cover_texture.wgsl).
const DROP_GROUND_RADIUS_M: f32 = 20.0;
const DROP_GROUND_SAMPLES_PER_SIDE: u32 = 16u;
fn drop_ground_offset_m(k: u32) -> vec2<f32> {
    let n = DROP_GROUND_SAMPLES_PER_SIDE;
    let cell = (vec2<f32>(f32(k % n), f32(k / n)) + 0.5) / f32(n);
    return (cell * 2.0 - 1.0) * DROP_GROUND_RADIUS_M;
}

// blinn_phong. light = (k_A·I_A, k_D·I_D, k_S·I_S, s); shadow = (sc, density, λ, _).
fn blinn_phong(light: vec4<f32>, shadow: vec4<f32>, normal: vec3<f32>, to_light: vec3<f32>, to_viewer: vec3<f32>, lit: f32) -> f32 {
    let sh = shadow.y * (1.0 - lit);
    let half_vector = normalize_or_zero(to_light + to_viewer);
    var highlight = 0.0;
    let hn = max(dot(half_vector, normal), 0.0);
    if (hn > 0.0) {
        highlight = pow(hn, light.w);
    }
    return shadow.z * (light.x
        + (1.0 - sh) * light.y * max(dot(to_light, normal), 0.0)
        + sh * shadow.x
        + lit * light.z * highlight);
}

// fog_transmittance
fn fog_transmittance(distance_m: f32, extinction_per_m: f32) -> f32 {
    return exp(-extinction_per_m * max(distance_m, 0.0));
}

// The fog layer (precip_model::drawing::fog_layer; docs/model.md (6.5)-(6.7)).
const FOG_ASYMMETRY: f32 = 0.85;
const SKY_DISTANCE_M: f32 = 1.0e6;

// fog_phase: the seed's angular function (16) scaled to a mean of 1 over the sphere.
fn fog_phase(cos_mu: f32, l: f32) -> f32 {
    let d = 1.0 + l * l - 2.0 * l * clamp(cos_mu, -1.0, 1.0);
    return (1.0 - l) * (1.0 - l) / (d * sqrt(d)) * (1.0 + l) / (1.0 - l);
}

// fog_layer_segment: the part [s0, s1] of the path in the layer (s0 = s1: none).
fn fog_layer_segment(camera_y_m: f32, dir_y: f32, length_m: f32, bottom_m: f32, top_m: f32) -> vec2<f32> {
    var s = vec2<f32>(0.0, length_m);
    if (abs(dir_y) < 1.0e-6) {
        if (camera_y_m >= top_m || camera_y_m <= bottom_m) {
            return vec2<f32>(0.0);
        }
    } else {
        let to_top = (top_m - camera_y_m) / dir_y;
        let to_bottom = (bottom_m - camera_y_m) / dir_y;
        s.x = max(s.x, select(to_top, to_bottom, dir_y > 0.0));
        s.y = min(s.y, select(to_bottom, to_top, dir_y > 0.0));
    }
    return select(vec2<f32>(0.0), s, s.y > s.x);
}

// (e^x − 1)/x, exact near 0.
fn exp_minus_one_over(x: f32) -> f32 {
    return select((exp(x) - 1.0) / x, 1.0 + 0.5 * x, abs(x) < 1.0e-4);
}

// air_path: (the transmittance T, the sun's scattered light J) between the camera and
// the point distance_m along the unit dir. layer = (top m, bottom m, B per m, sun on).
fn air_path(camera_m: vec3<f32>, dir: vec3<f32>, distance_m: f32, extinction_per_m: f32, layer: vec4<f32>, to_sun: vec3<f32>) -> vec2<f32> {
    let b = layer.z;
    let s = fog_layer_segment(camera_m.y, dir.y, distance_m, layer.y, layer.x);
    let in_fog = s.y - s.x;
    let transmittance = exp(-extinction_per_m * max(distance_m, 0.0) - b * in_fog);
    let sin_sun = max(to_sun.y, 0.05);
    let k = -extinction_per_m - b + b * dir.y / sin_sun;
    let a = b * s.x - b * (layer.x - camera_m.y) / sin_sun;
    let along = exp(a + k * s.x) * in_fog * exp_minus_one_over(k * in_fog);
    let sun = select(0.0, b * along * fog_phase(dot(dir, to_sun), FOG_ASYMMETRY) * 0.25, to_sun.y > 0.0);
    return vec2<f32>(transmittance, sun * layer.w);
}

// The cloud layer (precip_model::drawing::clouds; docs/model.md (6.9)-(6.12)).
const CLOUD_MAP_PERIOD_M: f32 = 12000.0;
const CLOUD_DETAIL_PERIOD_M: f32 = 1700.0;
const CLOUD_DETAIL_DEPTH: f32 = 0.12;
const CLOUD_DETAIL_PX: u32 = 64u;
const CLOUD_DETAIL_ATLAS_COLUMNS: u32 = 8u;
const CLOUD_DETAIL_TILE_PX: u32 = 66u;
const CLOUD_DETAIL_ATLAS_PX: u32 = 528u;
const CLOUD_BILLOW_SHARE: f32 = 0.35;
const CLOUD_THRESHOLD: f32 = 0.12;
const CLOUD_EDGE: f32 = 0.04;
const CLOUD_DOME: f32 = 0.25;
const CLOUD_VIEW_STEPS: u32 = 20u;
const CLOUD_SUN_SAMPLES: u32 = 3u;
const CLOUD_MAX_PATH_M: f32 = 30000.0;
const CLOUD_INSIDE_PATH_M: f32 = 2000.0;
const CLOUD_MARCH_BLOCK_PX: u32 = 4u;
const CLOUD_MARCH_ALL: u32 = 16u;
const CLOUD_HISTORY_MARGIN: f32 = 0.25;
const CLOUD_FRESH_WEIGHT: f32 = 0.25;
const CLOUD_HISTORY_SLACK: f32 = 0.02;
const CLOUD_PARALLAX_DEPTH_M: f32 = 500.0;
const CLOUD_PARALLAX_FULL_PX: f32 = 0.25;
const MAX_CLOUD_LAYERS: u32 = 3u;
const LOCAL_WEATHER_RADIUS_M: f32 = 3000.0;
const RAIN_SHAFT_SAMPLES: u32 = 8u;
const CLOUD_BASE_SKY_SHARE: f32 = 0.4;

// cloud_layer_map_offset_m: where layer `index` reads the coverage map, m (added to
// the drift; precip_model::drawing::clouds::cloud_layer_map_offset_m).
fn cloud_layer_map_offset_m(index: u32) -> vec2<f32> {
    let i = f32(index);
    return vec2<f32>((i * 4100.0) % CLOUD_MAP_PERIOD_M, (i * 7300.0) % CLOUD_MAP_PERIOD_M);
}

// cloud_march_slot: the frame of CLOUD_MARCH_ALL that marches the pixel (4 × 4 Bayer
// within its block; precip_model::drawing::clouds::cloud_march_slot).
fn cloud_march_slot(pixel: vec2<u32>) -> u32 {
    let bayer = array<u32, 16>(0u, 8u, 2u, 10u, 12u, 4u, 14u, 6u, 3u, 11u, 1u, 9u, 15u, 7u, 13u, 5u);
    return bayer[(pixel.y % 4u) * 4u + pixel.x % 4u];
}

// cloud_fresh_pixel: the pixel of the clouds' image that pixel `fresh` of the fresh
// image marches in frame `slot` (the Bayer order inverted).
fn cloud_fresh_pixel(fresh: vec2<u32>, slot: u32) -> vec2<u32> {
    let cell = array<u32, 16>(0u, 10u, 2u, 8u, 5u, 15u, 7u, 13u, 1u, 11u, 3u, 9u, 4u, 14u, 6u, 12u);
    let k = cell[slot % CLOUD_MARCH_ALL];
    return fresh * CLOUD_MARCH_BLOCK_PX + vec2<u32>(k % 4u, k / 4u);
}

// cloud_history_clamped: a pixel's history clamped to the range low … high of the
// fresh pixels around it, widened by CLOUD_HISTORY_MARGIN of it, at least
// CLOUD_HISTORY_SLACK.
fn cloud_history_clamped(history: vec4<f32>, low: vec4<f32>, high: vec4<f32>) -> vec4<f32> {
    let slack = max((high - low) * CLOUD_HISTORY_MARGIN, vec4<f32>(CLOUD_HISTORY_SLACK));
    return clamp(history, low - slack, high + slack);
}

// cloud_fresh_weight: the weight of a pixel's new march against its history:
// CLOUD_FRESH_WEIGHT where the history is read at a texel's centre unclamped, up to
// 1 a quarter texel off or clamped.
fn cloud_fresh_weight(clamp_weight: f32, history_px: vec2<f32>) -> f32 {
    let from_centre = history_px - vec2<f32>(0.5);
    let off = from_centre - round(from_centre);
    let resampled = clamp(length(off) * 4.0, 0.0, 1.0);
    return max(CLOUD_FRESH_WEIGHT, max(clamp_weight, resampled));
}

// cloud_history_clamp_weight: how much of the clamp a reused pixel takes: how far
// apart the frame before's camera saw the ray's entry and a point
// CLOUD_PARALLAX_DEPTH_M deeper, over CLOUD_PARALLAX_FULL_PX px of an image of
// `image_px` (1 behind that camera).
fn cloud_history_clamp_weight(previous_view_proj: mat4x4<f32>, entry_m: vec3<f32>, deeper_m: vec3<f32>, image_px: vec2<f32>) -> f32 {
    let a = previous_view_proj * vec4<f32>(entry_m, 1.0);
    let b = previous_view_proj * vec4<f32>(deeper_m, 1.0);
    if (a.w <= 0.0 || b.w <= 0.0) {
        return 1.0;
    }
    let apart_px = length((a.xy / a.w - b.xy / b.w) * 0.5 * image_px);
    return clamp(apart_px / CLOUD_PARALLAX_FULL_PX, 0.0, 1.0);
}

// cloud_history_uv: where the frame before's clouds' image holds p_m (xy), and
// whether it does (z: 1, else 0: behind that camera or outside its image).
fn cloud_history_uv(previous_view_proj: mat4x4<f32>, p_m: vec3<f32>) -> vec3<f32> {
    let clip = previous_view_proj * vec4<f32>(p_m, 1.0);
    if (clip.w <= 0.0) {
        return vec3<f32>(0.0);
    }
    let uv = vec2<f32>(clip.x, -clip.y) / clip.w * 0.5 + 0.5;
    let inside = all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0));
    return vec3<f32>(uv, select(0.0, 1.0, inside));
}

// cloud_profile: the kind's height profile at h (0 at the base, 1 at the top).
fn cloud_profile(kind: u32, h: f32) -> f32 {
    var rise_fall = vec2<f32>(0.05, 0.85);
    switch kind {
        case 0u: { rise_fall = vec2<f32>(0.15, 0.6); }
        case 2u: { rise_fall = vec2<f32>(0.07, 0.35); }
        case 3u: { rise_fall = vec2<f32>(0.02, 0.8); }
        default: {}
    }
    let inside = select(0.0, 1.0, h >= 0.0 && h <= 1.0);
    return inside * smoothstep(0.0, rise_fall.x, h) * (1.0 - smoothstep(rise_fall.y, 1.0, h));
}

// cloud_column: how much a column of map value m stands under a cloud.
fn cloud_column(coverage: f32, m: f32) -> f32 {
    return smoothstep(0.0, CLOUD_EDGE, coverage - m);
}

// cloud_density: [0, 1] at height fraction h of a column of map value m, detail d.
fn cloud_density(kind: u32, coverage: f32, m: f32, d: f32, h: f32) -> f32 {
    let carved = m + CLOUD_DETAIL_DEPTH * d;
    let column = cloud_column(coverage, carved);
    let reach = clamp((coverage - carved) / CLOUD_DOME, 0.05, 1.0);
    let raw = column * cloud_profile(kind, h / reach);
    return max((raw - CLOUD_THRESHOLD) / (1.0 - CLOUD_THRESHOLD), 0.0);
}

// cloud_phase: two Henyey-Greenstein lobes (0.8, -0.3, weights 0.75, 0.25), mean 1.
fn cloud_phase(cos_mu: f32) -> f32 {
    let c = clamp(cos_mu, -1.0, 1.0);
    let d1 = 1.0 + 0.64 - 1.6 * c;
    let d2 = 1.0 + 0.09 + 0.6 * c;
    return 0.75 * (1.0 - 0.64) / (d1 * sqrt(d1)) + 0.25 * (1.0 - 0.09) / (d2 * sqrt(d2));
}

// cloud_sun_light: three octaves of multiple scattering (a = b = c = 1/2) of the
// sun's light behind an optical depth `optical`, per unit extinction.
fn cloud_sun_light(cos_mu: f32, optical: f32) -> f32 {
    let c = clamp(cos_mu, -1.0, 1.0);
    var sum = 0.0;
    var k = 1.0;
    for (var n = 0u; n < 3u; n += 1u) {
        let g1 = 0.8 * k;
        let g2 = -0.3 * k;
        let d1 = 1.0 + g1 * g1 - 2.0 * g1 * c;
        let d2 = 1.0 + g2 * g2 - 2.0 * g2 * c;
        let phase = 0.75 * (1.0 - g1 * g1) / (d1 * sqrt(d1)) + 0.25 * (1.0 - g2 * g2) / (d2 * sqrt(d2));
        sum += k * phase * exp(-k * optical);
        k *= 0.5;
    }
    return sum;
}

// cloud_slab: where the ray crosses [base_m, top_m], at most CLOUD_MAX_PATH_M long.
fn cloud_slab(camera_y_m: f32, dir_y: f32, base_m: f32, top_m: f32) -> vec2<f32> {
    let s = fog_layer_segment(camera_y_m, dir_y, CLOUD_MAX_PATH_M * 4.0, base_m, top_m);
    let inside = camera_y_m >= base_m && camera_y_m <= top_m;
    return vec2<f32>(s.x, min(s.y, s.x + select(CLOUD_MAX_PATH_M, CLOUD_INSIDE_PATH_M, inside)));
}

// cloud_map_uv: where the point's column reads the coverage map (drifting by offset_m).
fn cloud_map_uv(p: vec3<f32>, offset_m: vec2<f32>) -> vec2<f32> {
    return (p.xz + offset_m) / CLOUD_MAP_PERIOD_M;
}

// cloud_detail_point (clouds/detail.rs): where p reads the detail volume, in periods.
fn cloud_detail_point(p: vec3<f32>, offset_m: vec2<f32>) -> vec3<f32> {
    return vec3<f32>(p.x + offset_m.x, p.y, p.z + offset_m.y) / CLOUD_DETAIL_PERIOD_M;
}

// cloud_detail_atlas: the atlas uv of the slice below q and the weight of the one above.
fn cloud_detail_atlas(q: vec3<f32>) -> vec3<f32> {
    let n = f32(CLOUD_DETAIL_PX);
    let s = fract(q) * n;
    let z = s.z - 0.5;
    let below = floor(z);
    let k = u32(below + n) % CLOUD_DETAIL_PX;
    let tile = vec2<f32>(f32(k % CLOUD_DETAIL_ATLAS_COLUMNS), f32(k / CLOUD_DETAIL_ATLAS_COLUMNS));
    let uv = (tile * f32(CLOUD_DETAIL_TILE_PX) + 1.0 + s.xy) / f32(CLOUD_DETAIL_ATLAS_PX);
    return vec3<f32>(uv, z - below);
}

// cloud_detail: the detail d from the atlas's texel (Perlin-Worley and billows of
// the slice below and above) and the weight w of the one above.
fn cloud_detail(texel: vec4<f32>, w: f32) -> f32 {
    let pw = mix(texel.r, texel.g, w);
    let billows = mix(texel.b, texel.a, w);
    return mix(pw, billows, CLOUD_BILLOW_SHARE);
}

// streak_h (precip_model::drawing::unresolved_streaks): H(w) of the ink's variance.
fn streak_h(w: f32) -> f32 {
    if (w <= 1.0) {
        return log(max(w, 1.0e-12)) - w / 3.0;
    }
    return 0.5 - 1.0 / w + 1.0 / (6.0 * w * w);
}

// unresolved_streak_variance (UnresolvedStreaks::variance): the unresolved ink's
// variance from the grain's near end to far_m; grain = (scale, reach m, near m, length px).
fn unresolved_streak_variance(grain: vec4<f32>, far_m: f32) -> f32 {
    if (far_m <= grain.z) {
        return 0.0;
    }
    return grain.x * (streak_h(far_m / grain.y) - streak_h(grain.z / grain.y));
}

// streak_grain: unit variance, zero mean, constant along streaks length_px long in
// the unit screen direction `along`, one pixel wide, new for each exposure number.
fn streak_grain(pixel: vec2<f32>, along: vec2<f32>, length_px: f32, exposure: u32) -> f32 {
    let w = dot(pixel, along);
    let c = pixel.x * along.y - pixel.y * along.x;
    let column = bitcast<u32>(i32(floor(c)));
    let offset = f32(pcg_hash(column ^ 0x5bd1e995u) >> 8u) / 16777216.0;
    let cell = bitcast<u32>(i32(floor(w / max(length_px, 1.0) + offset)));
    let h = pcg_hash((column * 0x9e3779b1u) ^ (cell * 0x85ebca77u) ^ exposure);
    // Three uniforms of ten bits each from the one hash.
    let parts = vec3<f32>(vec3<u32>(h, h >> 10u, h >> 20u) & vec3<u32>(1023u)) / 1023.0;
    return 2.0 * (parts.x + parts.y + parts.z - 1.5);
}

// multiplicity_rank (precip_model::drawing::multiplicity): a particle's rank in [0, 1).
fn multiplicity_rank(index: u32) -> f32 {
    var h = index * 0x9e3779b9u;
    h ^= h >> 16u;
    h *= 0x85ebca6bu;
    h ^= h >> 13u;
    h *= 0xc2b2ae35u;
    h ^= h >> 16u;
    return f32(h >> 8u) / 16777216.0;
}

// drawn_weight: 0 (not drawn) when the rank is at or above m < 1, else max(m, 1).
fn drawn_weight(index: u32, multiplicity: f32) -> f32 {
    return select(0.0, max(multiplicity, 1.0), multiplicity_rank(index) < multiplicity);
}

// The land beyond the scene (precip_model::drawing::far_ground; docs/model.md (6.18)).
const FAR_GROUND_BARE_COLOUR: vec3<f32> = vec3<f32>(0.2, 0.28, 0.12);
const FAR_GROUND_SNOW_TINT: vec3<f32> = vec3<f32>(1.0, 1.0, 1.03);

// far_ground_lattice_m: point k of the DROP_GROUND_SAMPLES_PER_SIDE² lattice spread
// over the grid at origin_m of size_m (cell centres, row by row).
fn far_ground_lattice_m(origin_m: vec2<f32>, size_m: vec2<f32>, k: u32) -> vec2<f32> {
    let n = DROP_GROUND_SAMPLES_PER_SIDE;
    let cell = vec2<f32>(f32(k % n), f32(k / n)) + 0.5;
    return origin_m + size_m * cell / f32(n);
}

// far_ground_distance_m: how far along the ray (unit, vertical part dir_y) from a
// camera at camera_y_m it meets the land at level_m; negative for never.
fn far_ground_distance_m(camera_y_m: f32, dir_y: f32, level_m: f32) -> f32 {
    if (dir_y < -1.0e-4 && camera_y_m > level_m) {
        return (level_m - camera_y_m) / dir_y;
    }
    return -1.0;
}

// far_ground_colour: the land's colour before the air: bare land to snow as the
// ground's albedo goes from bare to old snow's 0.4 (snow as the scene's, min(1, 1.2·albedo)),
// lit by the ambient and diffuse light (lighting), the sun sun_y up with sun_share
// of its light through the clouds.
fn far_ground_colour(albedo: f32, lighting: vec2<f32>, sun_y: f32, sun_share: f32) -> vec3<f32> {
    let snow = clamp((albedo - BARE_GROUND_ALBEDO) / (0.4 - BARE_GROUND_ALBEDO), 0.0, 1.0);
    let white = min(1.2 * max(albedo, 0.4), 1.0);
    let base = mix(FAR_GROUND_BARE_COLOUR, FAR_GROUND_SNOW_TINT * white, snow);
    return base * (lighting.x + lighting.y * max(sun_y, 0.0) * clamp(sun_share, 0.0, 1.0));
}

// The clouds' shadow map (precip_model::drawing::clouds::shadow_map).
const CLOUD_SHADOW_MAP_PX: u32 = 128u;
const CLOUD_SHADOW_MAP_SPAN_M: f32 = 16000.0;
const CLOUD_SHADOW_MAP_FADE: f32 = 0.15;
const CLOUD_SHADOW_SAMPLES: u32 = 3u;

// cloud_shadow_map_weight: how much of the map a point at `uv` on it takes against
// the frame's one share: 1 within, 0 beyond, fading over the outer
// CLOUD_SHADOW_MAP_FADE of each side.
fn cloud_shadow_map_weight(uv: vec2<f32>) -> f32 {
    let inside = min(min(uv.x, uv.y), min(1.0 - uv.x, 1.0 - uv.y));
    return clamp(inside / CLOUD_SHADOW_MAP_FADE, 0.0, 1.0);
}

// cloud_shadow_map_point_m: the ground point texel `texel` of the map at
// `origin_m` stands for (its centre), m.
fn cloud_shadow_map_point_m(origin_m: vec2<f32>, texel: vec2<u32>) -> vec2<f32> {
    return origin_m + (vec2<f32>(texel) + 0.5) * (CLOUD_SHADOW_MAP_SPAN_M / f32(CLOUD_SHADOW_MAP_PX));
}

// land_class_pick (precip_model::drawing::land_borders): the class of the four
// pixels' `corners` (x0z0, x1z0, x0z1, x1z1) with the largest sum of bilinear
// weights at fraction `f` between their centres; the first corner's on a tie.
fn land_class_pick(corners: vec4<u32>, f: vec2<f32>) -> u32 {
    let w = array<f32, 4>(
        (1.0 - f.x) * (1.0 - f.y),
        f.x * (1.0 - f.y),
        (1.0 - f.x) * f.y,
        f.x * f.y,
    );
    var best = 0u;
    var best_weight = -1.0;
    for (var k = 0u; k < 4u; k++) {
        var weight = 0.0;
        for (var j = 0u; j < 4u; j++) {
            if (corners[j] == corners[k]) {
                weight += w[j];
            }
        }
        if (weight > best_weight) {
            best = k;
            best_weight = weight;
        }
    }
    return corners[best];
}
