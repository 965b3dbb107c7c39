//! Helpers for the GPU tests: run on every adapter found, skip loudly without one
//! (fail instead when `PRECIP_REQUIRE_GPU=1`), and compare with the CPU reference.

use precip_gpu_wgpu::{WgpuBackend, adapters};
use precip_model::{Backend, CpuBackend, Particle, Setup};

/// Every adapter as a fresh backend, with its name; empty (after printing why, or
/// panicking under `PRECIP_REQUIRE_GPU=1`) when there is none.
pub fn gpu_backends(test: &str) -> Vec<(String, WgpuBackend)> {
    let found = adapters();
    if found.is_empty() {
        let reason = "no wgpu adapter found (install mesa-vulkan-drivers for lavapipe)";
        if std::env::var("PRECIP_REQUIRE_GPU").is_ok_and(|v| v == "1") {
            panic!("{test}: PRECIP_REQUIRE_GPU=1 but {reason}");
        }
        eprintln!("SKIPPED {test}: {reason}");
        return Vec::new();
    }
    found
        .iter()
        .map(|adapter| {
            let name = format!(
                "{} ({:?})",
                adapter.get_info().name,
                adapter.get_info().backend
            );
            let backend =
                WgpuBackend::on_adapter(adapter).unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, backend)
        })
        .collect()
}

/// Configures and steps a backend `steps` times by `dt`.
pub fn run(backend: &mut dyn Backend, setup: &Setup, steps: usize, dt: f32) {
    backend.configure(setup).expect("valid setup");
    for _ in 0..steps {
        backend.step(dt).expect("valid step");
    }
}

/// The CPU reference after the same run.
pub fn cpu_run(setup: &Setup, steps: usize, dt: f32) -> CpuBackend {
    let mut cpu = CpuBackend::new();
    run(&mut cpu, setup, steps, dt);
    cpu
}

/// Runs test kernel `program` (entry point = its only one) over `items` inputs:
/// binding 0 the input bytes, binding 1 an output of `output_bytes`; returns the output.
pub fn run_probe(
    gpu: &precip_gpu_wgpu::GpuDevice,
    program: precip_gpu::shaders::Program,
    input: &[u8],
    items: u32,
    output_bytes: u64,
) -> Vec<u8> {
    use wgpu::util::DeviceExt;
    let device = &gpu.device;
    let module = precip_gpu_wgpu::gpu::shader_module(device, program);
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(program.label()),
        layout: None,
        module: &module,
        entry_point: Some(program.entry_points()[0]),
        compilation_options: wgpu::PipelineCompilationOptions::default(),
        cache: None,
    });
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("probe input"),
        contents: input,
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("probe output"),
        size: output_bytes,
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
        pass.dispatch_workgroups(items.div_ceil(64), 1, 1);
    }
    gpu.queue.submit([encoder.finish()]);
    precip_gpu_wgpu::transfer::read_buffer(gpu, &output, output_bytes).expect("read back")
}

/// Particles as bytes.
pub fn bytes(particles: &[Particle]) -> Vec<u8> {
    bytemuck::cast_slice(particles).to_vec()
}
