// ocean.wgsl: the open sea's formulas, twins of precip_sea::ocean (spectrum.rs,
// synthesis.rs, fft.rs); docs/model.md (13.5)-(13.7). The kernels that will run
// them over a patch each frame are issue 28's next step; the probe kernel checks
// these against Rust on the GPU today.

const SEA_GRAVITY: f32 = 9.81;
// spectrum.rs SPREADING_EXPONENT, and directional_spreading's normalisation for it:
// Γ(s + 1)²/Γ(2s + 1)·2^(2s)/(2π).
const SPREADING_EXPONENT: f32 = 5.0;
const SPREADING_NORM: f32 = 0.646724848;
// spectrum.rs PHILLIPS_AMPLITUDE: 2·(0.21/4)²/π.
const PHILLIPS_AMPLITUDE: f32 = 0.001754683;
const SEA_TAU: f32 = 6.283185307;

// dispersion_rad_per_s: ω = √(g·k·tanh(k·d)).
fn sea_dispersion(k: f32, depth_m: f32) -> f32 {
    return sqrt(SEA_GRAVITY * k * tanh(min(k * depth_m, 20.0)));
}

// deep_group_speed_mps: g/(2ω) in deep water.
fn sea_deep_group_speed(k: f32) -> f32 {
    return 0.5 * SEA_GRAVITY / max(sqrt(SEA_GRAVITY * k), 1.0e-6);
}

// jonswap_peak_rad_per_s and jonswap_rad: S(ω), m²·s/rad.
fn sea_jonswap(omega: f32, wind_mps: f32, fetch_m: f32, peak_enhancement: f32) -> f32 {
    if (omega <= 0.0 || wind_mps <= 0.0 || fetch_m <= 0.0) {
        return 0.0;
    }
    let alpha = 0.076 * pow(wind_mps * wind_mps / (fetch_m * SEA_GRAVITY), 0.22);
    let peak = 22.0 * pow(SEA_GRAVITY * SEA_GRAVITY / (wind_mps * fetch_m), 1.0 / 3.0);
    let sigma = select(0.09, 0.07, omega <= peak);
    let r = exp(-(omega - peak) * (omega - peak) / (2.0 * sigma * sigma * peak * peak));
    let o2 = omega * omega;
    let ratio = peak / omega;
    return alpha * SEA_GRAVITY * SEA_GRAVITY / (o2 * o2 * omega) * exp(-1.25 * ratio * ratio * ratio * ratio) * pow(peak_enhancement, r);
}

// directional_spreading at s = SPREADING_EXPONENT: N·cos²ˢ(θ/2).
fn sea_spreading(cos_theta: f32) -> f32 {
    let half = max(0.5 * (1.0 + clamp(cos_theta, -1.0, 1.0)), 0.0);
    return SPREADING_NORM * half * half * half * half * half;
}

// WindSea::density_m4: the variance density over the wavenumber plane, m⁴;
// jonswap: JONSWAP of `wind` = (speed m/s, fetch m) blowing toward `direction`, else
// Phillips of that speed; waves shorter than `shortest_m` rolled off.
fn sea_density(k_vec: vec2<f32>, wind: vec2<f32>, direction: vec2<f32>, shortest_m: f32, jonswap: bool) -> f32 {
    let k = length(k_vec);
    if (k <= 0.0) {
        return 0.0;
    }
    let roll = k * shortest_m / SEA_TAU;
    let cut = exp(-roll * roll);
    let c = dot(k_vec, direction) / k;
    if (jonswap) {
        let omega = sqrt(SEA_GRAVITY * k);
        return sea_jonswap(omega, wind.x, wind.y, 3.3) * sea_spreading(c) * sea_deep_group_speed(k) / k * cut;
    }
    let l = wind.x * wind.x / SEA_GRAVITY;
    let kl = k * l;
    let k2 = k * k;
    return PHILLIPS_AMPLITUDE * exp(-1.0 / (kl * kl)) / (k2 * k2) * c * c * cut;
}

// synthesis.rs amplitude_normals: two standard normal numbers for point `index`
// of `seed` (Box-Muller over rng.wgsl's pcg_hash, which a program joining this file
// joins first).
fn sea_normal_pair(seed: u32, index: u32) -> vec2<f32> {
    let a = pcg_hash(pcg_hash(seed) ^ index);
    let b = pcg_hash(a ^ 0x9e3779b9u);
    let u1 = (f32(a >> 8u) + 0.5) / 16777216.0;
    let u2 = f32(b >> 8u) / 16777216.0;
    let r = sqrt(-2.0 * log(u1));
    let t = SEA_TAU * u2;
    return vec2<f32>(r * cos(t), r * sin(t));
}

// fft.rs butterfly, on two complex numbers at once (xy, zw): (a + w·b, a − w·b),
// w = e^(iπk/m), the inverse transform's twiddle of Stockham's stage m = 2^stage.
fn sea_butterfly(a: vec4<f32>, b: vec4<f32>, k: u32, m: u32) -> array<vec4<f32>, 2> {
    let angle = 3.14159265 * f32(k) / f32(m);
    let w = vec2<f32>(cos(angle), sin(angle));
    let wb = vec4<f32>(
        b.x * w.x - b.y * w.y,
        b.x * w.y + b.y * w.x,
        b.z * w.x - b.w * w.y,
        b.z * w.y + b.w * w.x,
    );
    return array<vec4<f32>, 2>(a + wb, a - wb);
}
