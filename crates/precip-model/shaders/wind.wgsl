// wind.wgsl: the wind sampler. Rust twin: precip_wind::WindVolume::sample and
// precip_wind::wind_velocity. Needs the globals `wind: WindParams` and
// `wind_volume: texture_3d<f32>` (declared by the kernel file).

fn wind_texel(i: vec3<i32>) -> vec2<f32> {
    let n = vec3<i32>(wind.texels);
    let w = ((i % n) + n) % n;
    return textureLoad(wind_volume, w, 0).xy;
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
    let b = vec3<i32>(base);
    let x00 = lerp2(wind_texel(b + vec3<i32>(0, 0, 0)), wind_texel(b + vec3<i32>(1, 0, 0)), f.x);
    let x10 = lerp2(wind_texel(b + vec3<i32>(0, 1, 0)), wind_texel(b + vec3<i32>(1, 1, 0)), f.x);
    let x01 = lerp2(wind_texel(b + vec3<i32>(0, 0, 1)), wind_texel(b + vec3<i32>(1, 0, 1)), f.x);
    let x11 = lerp2(wind_texel(b + vec3<i32>(0, 1, 1)), wind_texel(b + vec3<i32>(1, 1, 1)), f.x);
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
