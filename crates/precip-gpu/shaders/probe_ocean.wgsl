// probe_ocean.wgsl: a test kernel that evaluates the open sea's formulas
// (ocean.wgsl, twins of precip_sea::ocean) for a list of inputs, so tests compare
// them with the Rust ones. Program: rng, ocean, this file.

struct ProbeOcean {
    k: vec2<f32>,
    wind_mps: f32,
    fetch_m: f32,
    direction: vec2<f32>,
    shortest_m: f32,
    omega: f32,
    cos_theta: f32,
    depth_m: f32,
    seed: u32,
    index: u32,
    stage_k: u32,
    stage_m: u32,
    pad0: u32,
    pad1: u32,
    a: vec4<f32>,
    b: vec4<f32>,
}

@group(0) @binding(0) var<storage, read> probe_ocean_in: array<ProbeOcean>;
// Per input: (the JONSWAP density at k, the dispersion at |k| over depth, S(ω), the
// spreading at cos θ), (the Phillips density at k, the deep group speed at |k|, the
// normal pair of (seed, index)), then the butterfly of (a, b) at (k, m): its sum and
// its difference.
@group(0) @binding(1) var<storage, read_write> probe_ocean_out: array<vec4<f32>>;

@compute @workgroup_size(64)
fn probe_ocean(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&probe_ocean_in)) {
        return;
    }
    let q = probe_ocean_in[i];
    let wind = vec2<f32>(q.wind_mps, q.fetch_m);
    probe_ocean_out[4u * i] = vec4<f32>(
        sea_density(q.k, wind, q.direction, q.shortest_m, true),
        sea_dispersion(length(q.k), q.depth_m),
        sea_jonswap(q.omega, q.wind_mps, q.fetch_m, 3.3),
        sea_spreading(q.cos_theta),
    );
    probe_ocean_out[4u * i + 1u] = vec4<f32>(
        sea_density(q.k, wind, q.direction, q.shortest_m, false),
        sea_deep_group_speed(length(q.k)),
        sea_normal_pair(q.seed, q.index),
    );
    let pair = sea_butterfly(q.a, q.b, q.stage_k, q.stage_m);
    probe_ocean_out[4u * i + 2u] = pair[0];
    probe_ocean_out[4u * i + 3u] = pair[1];
}
