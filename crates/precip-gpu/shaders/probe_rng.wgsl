// probe_rng.wgsl: a test kernel that writes random_u32 for a list of keys, so tests
// can compare the WGSL hash with the Rust one bit for bit. Program: rng, this file.

struct ProbeKey {
    seed: u32,
    index: u32,
    generation: u32,
    draw: u32,
}

@group(0) @binding(0) var<storage, read> probe_keys: array<ProbeKey>;
@group(0) @binding(1) var<storage, read_write> probe_out: array<vec2<u32>>;

@compute @workgroup_size(64)
fn probe_rng(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&probe_keys)) {
        return;
    }
    let k = probe_keys[i];
    let key = particle_key(k.seed, k.index, k.generation);
    probe_out[i] = vec2<u32>(random_u32(key, k.draw), bitcast<u32>(random_unit(key, k.draw)));
}
