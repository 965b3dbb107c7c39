//! The WGSL hash equals the Rust hash, bit for bit, for many keys.

use crate::common;

use precip_gpu_wgpu::pipelines::shader_module;
use precip_gpu_wgpu::readback::read_buffer;
use precip_model::rng::{particle_key, pcg_hash, random_u32, random_unit};
use precip_model::shaders::Program;
use wgpu::util::DeviceExt;

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
        let device = &gpu.device;
        let module = shader_module(device, Program::ProbeRng);
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("probe_rng"),
            layout: None,
            module: &module,
            entry_point: Some("probe_rng"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("keys"),
            contents: bytemuck::cast_slice(&keys),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let size = (keys.len() * 8) as u64;
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("hashes"),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: input.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: output.as_entire_binding(),
                },
            ],
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups((keys.len() as u32).div_ceil(64), 1, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        let got: Vec<[u32; 2]> =
            bytemuck::pod_collect_to_vec(&read_buffer(gpu, &output, size).expect("read back"));
        let mismatches = got.iter().zip(&expected).filter(|(a, b)| a != b).count();
        assert_eq!(
            mismatches,
            0,
            "{name}: {mismatches} of {} keys differ",
            keys.len()
        );
    }
}
