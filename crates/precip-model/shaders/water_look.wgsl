// water_look.wgsl: how water on the scene looks (docs/model.md §6, seed 004). Rust twins:
// precip_model::drawing::water_look, function by function.

const WATER_REFRACTIVE_INDEX: f32 = 1.333;
const WET_GLOSS: f32 = 0.5;
const RING_CELL_M: f32 = 0.15;
const RING_WAVELENGTH_M: f32 = 0.025;
const RING_LIFE_S: f32 = 0.6;
const RING_AMPLITUDE_M: f32 = 1.5e-3;
const WATER_ABSORPTION_PER_M: vec3<f32> = vec3<f32>(0.35, 0.06, 0.015);
const DEEP_WATER_COLOUR: vec3<f32> = vec3<f32>(0.01, 0.035, 0.045);
const TAU: f32 = 6.283185307;

fn fresnel_unpolarised(cos_incidence: f32, n: f32) -> f32 {
    let ci = clamp(cos_incidence, 0.0, 1.0);
    let si2 = max(1.0 - ci * ci, 0.0);
    let ct = sqrt(max(1.0 - si2 / (n * n), 0.0));
    let rs = (ci - n * ct) / (ci + n * ct);
    let rp = (n * ci - ct) / (n * ci + ct);
    return clamp(0.5 * (rs * rs + rp * rp), 0.0, 1.0);
}

fn puddle_cover(puddle_ratio: f32) -> f32 {
    return smoothstep(0.5, 1.5, puddle_ratio);
}

fn ring_wave_slope(offset_m: vec2<f32>, age_s: f32) -> vec2<f32> {
    let speed = ripple_phase_speed_mps(RING_WAVELENGTH_M);
    let k = TAU / RING_WAVELENGTH_M;
    let r = length(offset_m);
    let front = r - speed * age_s;
    let x = front / RING_WAVELENGTH_M;
    let envelope = exp(-x * x) * max(1.0 - age_s / RING_LIFE_S, 0.0) * RING_AMPLITUDE_M;
    let dh_dr = -envelope * k * sin(k * front);
    if (r > 1.0e-5) {
        return offset_m / r * dh_dr;
    }
    return vec2<f32>(0.0);
}

fn ring_slope(xz_m: vec2<f32>, time_s: f32, rate_per_m2_s: f32) -> vec2<f32> {
    if (rate_per_m2_s <= 0.0) {
        return vec2<f32>(0.0);
    }
    let period = max(1.0 / (rate_per_m2_s * RING_CELL_M * RING_CELL_M), RING_LIFE_S);
    var slope = vec2<f32>(0.0);
    for (var layer = 0u; layer < 2u; layer += 1u) {
        let shifted = xz_m / RING_CELL_M + vec2<f32>(0.5 * f32(layer));
        let cell = floor(shifted);
        let key = pcg_hash(pcg_hash(u32(i32(cell.x)) ^ (layer << 30u)) ^ u32(i32(cell.y)));
        let phase = f32(key >> 8u) / 16777216.0;
        let t = time_s / period + phase;
        let cycle = u32(i32(floor(t)));
        let age_s = (t - floor(t)) * period;
        if (age_s > RING_LIFE_S) {
            continue;
        }
        let strike = pcg_hash(key ^ cycle);
        let centre = vec2<f32>(
            0.2 + 0.6 * (f32(strike & 0xffffu) / 65536.0),
            0.2 + 0.6 * (f32(strike >> 16u) / 65536.0),
        );
        slope += ring_wave_slope((shifted - cell - centre) * RING_CELL_M, age_s);
    }
    return slope;
}

fn overcast_sky(horizon: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return min(horizon * (1.0 + 2.0 * max(dir.y, 0.0)), vec3<f32>(1.0));
}

fn water_body_colour(bottom_colour: vec3<f32>, depth_m: f32) -> vec3<f32> {
    let t = exp(-2.0 * max(depth_m, 0.0) * WATER_ABSORPTION_PER_M);
    return bottom_colour * t + DEEP_WATER_COLOUR * (vec3<f32>(1.0) - t);
}

// The slope of standing water at `xz_m`: the rain's rings where a puddle or a water
// body (`body`: 1 on its mesh) lies, faded by `ring_fade` (0 where a pixel spans a
// ring's wavelength: no aliasing), and on a water body the simulated waves (longer
// than the grid's 4 cm cells), to which the rings add the capillary waves below
// the grid's scale.
fn water_slope(puddle_ratio: f32, body: f32, xz_m: vec2<f32>, ring_fade: f32) -> vec2<f32> {
    let puddle = puddle_cover(puddle_ratio);
    let rings = ring_slope(xz_m, params.sky_colour_time.w, params.water_look.x) * (ring_fade * max(puddle, body));
    return rings + wave_slope(xz_m).xy * body;
}

// What a lit surface `shaded` looks like under its water: a wet film's blurred
// sheen, a puddle's mirror with rain rings, a water body's (`body`: 1 on its mesh)
// Fresnel surface with its simulated waves (water_waves.wgsl) and rings over its
// depths, its surface sloping by `slope` (water_slope).
// In w, the weight its sharp mirrors (the puddle's and the water body's, not the
// film's blurred sheen) give the sky they reflect: where the renderer's reflections
// find the scene instead.
fn water_surface(shaded: vec3<f32>, puddle_ratio: f32, wetness: f32, body: f32, slope: vec2<f32>, to_viewer: vec3<f32>, lit: f32) -> vec4<f32> {
    let puddle = puddle_cover(puddle_ratio);
    let n = normalize(vec3<f32>(-slope.x, 1.0, -slope.y));
    let f = fresnel_unpolarised(dot(n, to_viewer), WATER_REFRACTIVE_INDEX);
    let sky = overcast_sky(params.sky_colour_time.xyz, reflect(-to_viewer, n));
    let half_vector = normalize_or_zero(params.to_sun_extinction.xyz + to_viewer);
    let glint = lit * params.light.z * pow(max(dot(half_vector, n), 0.0), 400.0);
    let gloss = WET_GLOSS * clamp(wetness, 0.0, 1.0);
    var out = shaded * (1.0 - f * gloss) + f * gloss * sky;
    out = mix(out, (1.0 - f) * shaded + f * sky + vec3<f32>(glint), puddle);
    let depths = water_body_colour(shaded, params.water_look.z) ;
    out = mix(out, (1.0 - f) * depths + f * sky + vec3<f32>(glint), body);
    return vec4<f32>(out, f * mix(puddle, 1.0, body));
}
