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

/// Particles as bytes.
pub fn bytes(particles: &[Particle]) -> Vec<u8> {
    bytemuck::cast_slice(particles).to_vec()
}
