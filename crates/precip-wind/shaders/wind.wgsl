// wind.wgsl: the wind sampler. Rust twin: precip_wind::WindVolume::sample and
// precip_wind::wind_velocity. Needs the globals `wind: WindParams` and
// `wind_volume: texture_3d<f32>` (declared by the kernel file).

// Texel `i` of the volume, `i` already wrapped into it.
fn wind_texel(i: vec3<i32>) -> vec2<f32> {
    return textureLoad(wind_volume, i, 0).xy;
}

// a + (c − a)·t, written out as the Rust sampler does (mix() may round differently).
fn lerp2(a: vec2<f32>, c: vec2<f32>, t: f32) -> vec2<f32> {
    return a + (c - a) * t;
}

// Returns (sin α, vertical m/s) at a world position and time.
fn wind_sample(position_m: vec3<f32>, time_s: f32) -> vec2<f32> {
    let extent = wind.extent_m;
    let drifted = position_m - wind.mean_wind_mps * time_s;
    let wrapped = drifted - extent * floor(drifted / extent);
    let texel_space = wrapped / (extent / vec3<f32>(wind.texels)) - 0.5;
    let base = floor(texel_space);
    let f = texel_space - base;
    // The two texel rows along each axis, wrapped as the Rust sampler's rem_euclid
    // (once for the base, not for each of the eight texels: integer division is
    // slow on CPU-emulated devices).
    let n = vec3<i32>(wind.texels);
    let lo = ((vec3<i32>(base) % n) + n) % n;
    let hi = select(lo + 1, vec3<i32>(0), lo + 1 >= n);
    let x00 = lerp2(wind_texel(lo), wind_texel(vec3<i32>(hi.x, lo.y, lo.z)), f.x);
    let x10 = lerp2(wind_texel(vec3<i32>(lo.x, hi.y, lo.z)), wind_texel(vec3<i32>(hi.x, hi.y, lo.z)), f.x);
    let x01 = lerp2(wind_texel(vec3<i32>(lo.x, lo.y, hi.z)), wind_texel(vec3<i32>(hi.x, lo.y, hi.z)), f.x);
    let x11 = lerp2(wind_texel(vec3<i32>(lo.x, hi.y, hi.z)), wind_texel(hi), f.x);
    let y0 = lerp2(x00, x10, f.y);
    let y1 = lerp2(x01, x11, f.y);
    return lerp2(y0, y1, f.z);
}

fn wind_velocity(mean_wind_mps: vec3<f32>, gust_factor: f32, sample: vec2<f32>) -> vec3<f32> {
    return mean_wind_mps + mean_wind_mps * (gust_factor * sample.x) + vec3<f32>(0.0, sample.y, 0.0);
}

fn wind_velocity_at(position_m: vec3<f32>, time_s: f32) -> vec3<f32> {
    return wind_velocity(wind.mean_wind_mps, wind.gust_factor, wind_sample(position_m, time_s));
}
