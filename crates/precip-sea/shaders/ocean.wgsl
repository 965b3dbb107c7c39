// ocean.wgsl: the open sea's formulas, twins of precip_sea::ocean (spectrum.rs,
// synthesis.rs, fft.rs, cascades.rs); docs/model.md (13.5)-(13.8). precip-gpu's
// ocean kernels run them over the cascades each frame; its probe kernel checks
// them one by one against Rust.

const SEA_GRAVITY: f32 = 9.81;
// spectrum.rs SPREADING_EXPONENT, and directional_spreading's normalisation for it:
// Γ(s + 1)²/Γ(2s + 1)·2^(2s)/(2π).
const SPREADING_EXPONENT: f32 = 5.0;
const SPREADING_NORM: f32 = 0.646724848;
// spectrum.rs PHILLIPS_AMPLITUDE: 2·(0.21/4)²/π.
const PHILLIPS_AMPLITUDE: f32 = 0.001754683;
const SEA_TAU: f32 = 6.283185307;
// cascades.rs OCEAN_N, OCEAN_CASCADES, CASCADE_SIZES_M, SHORTEST_WAVE_M.
const OCEAN_N: u32 = 128u;
const OCEAN_CASCADES: u32 = 3u;
const OCEAN_CASCADE_0_M: f32 = 263.0;
const OCEAN_CASCADE_1_M: f32 = 47.0;
const OCEAN_CASCADE_2_M: f32 = 8.3;
const SHORTEST_WAVE_M: f32 = 0.1;

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

// synthesis.rs wavenumber: the signed wavenumber index of FFT index i of n.
fn sea_wavenumber(i: u32, n: u32) -> f32 {
    return select(f32(i) - f32(n), f32(i), i < n / 2u);
}

// synthesis.rs amplitude: h0(k) of the wavenumber k (rad/m) at point `index` of a
// grid of cells dk rad/m wide, 0 outside band = [lo, hi) (hi < 0: no upper end);
// the sea of wind = (speed m/s, fetch m) toward `direction`, JONSWAP or Phillips.
fn sea_amplitude(k_vec: vec2<f32>, dk: f32, band: vec2<f32>, seed: u32, index: u32, wind: vec2<f32>, direction: vec2<f32>, shortest_m: f32, jonswap: bool) -> vec2<f32> {
    let k = length(k_vec);
    let in_band = k >= band.x && (band.y < 0.0 || k < band.y);
    let f = select(0.0, sea_density(k_vec, wind, direction, shortest_m, jonswap), in_band);
    return sea_normal_pair(seed, index) * sqrt(f * dk * dk * 0.25);
}

// synthesis.rs spectrum_at: h~(k, t) = h0(k)·e^(-iωt) + conj(h0(-k))·e^(iωt).
fn sea_evolved(h0: vec2<f32>, h0_mirror: vec2<f32>, omega: f32, time_s: f32) -> vec2<f32> {
    let c = cos(omega * time_s);
    let s = sin(omega * time_s);
    // h0·(c − i s) + conj(m)·(c + i s)
    let a = vec2<f32>(h0.x * c + h0.y * s, h0.y * c - h0.x * s);
    let b = vec2<f32>(h0_mirror.x * c + h0_mirror.y * s, h0_mirror.x * s - h0_mirror.y * c);
    return a + b;
}

// synthesis.rs surface_at: the spectra of the surface's eight real fields from
// h~ at k, two a complex number (a + i·b transforms to the real fields a and b):
// [0] = (h + i·Dx, Dz + i·∂h/∂x), [1] = (∂h/∂z + i·∂Dx/∂x, ∂Dz/∂z + i·∂Dx/∂z), with
// D = i·k/|k|·h~, ∂h/∂x_a = i·k_a·h~, ∂D_a/∂x_b = −k_a·k_b/|k|·h~.
fn sea_fields(k_vec: vec2<f32>, h: vec2<f32>) -> array<vec4<f32>, 2> {
    let k = length(k_vec);
    let over_k = select(0.0, 1.0 / k, k > 0.0);
    let ih = vec2<f32>(-h.y, h.x);
    let dx = ih * k_vec.x * over_k;
    let dz = ih * k_vec.y * over_k;
    let sx = ih * k_vec.x;
    let sz = ih * k_vec.y;
    let dxx = h * (-k_vec.x * k_vec.x * over_k);
    let dzz = h * (-k_vec.y * k_vec.y * over_k);
    let dxz = h * (-k_vec.x * k_vec.y * over_k);
    // a + i·b, each complex: (a.x − b.y, a.y + b.x).
    return array<vec4<f32>, 2>(
        vec4<f32>(h.x - dx.y, h.y + dx.x, dz.x - sx.y, dz.y + sx.x),
        vec4<f32>(sz.x - dxx.y, sz.y + dxx.x, dzz.x - dxz.y, dzz.y + dxz.x),
    );
}

// synthesis.rs surface_at: the Jacobian of x + λ·D.
fn sea_jacobian(dxx: f32, dzz: f32, dxz: f32, choppiness: f32) -> f32 {
    return (1.0 + choppiness * dxx) * (1.0 + choppiness * dzz) - choppiness * choppiness * dxz * dxz;
}

// cascades.rs CASCADE_SIZES_M[c].
fn sea_cascade_size_m(c: u32) -> f32 {
    return select(select(OCEAN_CASCADE_2_M, OCEAN_CASCADE_1_M, c == 1u), OCEAN_CASCADE_0_M, c == 0u);
}

// cascades.rs cascade_band_per_m: [lo, hi) rad/m, hi −1 for the last (no end).
fn sea_cascade_band(c: u32) -> vec2<f32> {
    let lo = select(3.14159265 * f32(OCEAN_N) / sea_cascade_size_m(max(c, 1u) - 1u), 0.0, c == 0u);
    let hi = select(3.14159265 * f32(OCEAN_N) / sea_cascade_size_m(c), -1.0, c + 1u >= OCEAN_CASCADES);
    return vec2<f32>(lo, hi);
}

// cascades.rs cascade_seed.
fn sea_cascade_seed(seed: u32, c: u32) -> u32 {
    return seed + c;
}

// optics.rs shallow_colour: the colour shallow water depth_m deep over a bottom
// sends out, R∞ + (A − R∞)·e^(−2·K·d) (Maritorena, Morel & Gentili 1994).
fn sea_shallow_colour(deep: vec3<f32>, bottom: vec3<f32>, k: vec3<f32>, depth_m: f32) -> vec3<f32> {
    return deep + (bottom - deep) * exp(-2.0 * k * max(depth_m, 0.0));
}
