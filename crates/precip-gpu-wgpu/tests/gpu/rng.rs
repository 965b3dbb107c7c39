//! The WGSL hash equals the Rust hash, bit for bit, for many keys.

use crate::common;

use precip_gpu::shaders::Program;
use precip_model::particles::rng::{particle_key, pcg_hash, random_u32, random_unit};

#[test]
fn wgsl_rng_equals_rust_rng() {
    // Keys: edge values and a spread of hashed ones.
    let mut keys: Vec<[u32; 4]> =
        vec![[0, 0, 0, 0], [u32::MAX; 4], [1, 2, 3, 4], [42, 1000, 7, 13]];
    for i in 0..20_000u32 {
        keys.push([pcg_hash(i), pcg_hash(i ^ 0xA5A5_A5A5), i % 97, i % 211]);
    }
    let expected: Vec<[u32; 2]> = keys
        .iter()
        .map(|&[seed, index, generation, draw]| {
            let key = particle_key(seed, index, generation);
            [random_u32(key, draw), random_unit(key, draw).to_bits()]
        })
        .collect();
    for (name, backend) in common::gpu_backends("wgsl_rng_equals_rust_rng") {
        let gpu = backend.device();
        let bytes = common::run_probe(
            gpu,
            Program::ProbeRng,
            bytemuck::cast_slice(&keys),
            keys.len() as u32,
            (keys.len() * 8) as u64,
        );
        let got: Vec<[u32; 2]> = bytemuck::pod_collect_to_vec(&bytes);
        let mismatches = got.iter().zip(&expected).filter(|(a, b)| a != b).count();
        assert_eq!(
            mismatches,
            0,
            "{name}: {mismatches} of {} keys differ",
            keys.len()
        );
    }
}
