//! Helpers shared by the CPU backend's integration tests.

use precip_model::cover::{CoverGrid, DepositBuffer};
use precip_model::particles::step::{StepInputs, StepParams};
use precip_model::wind::WindVolume;
use precip_model::{Backend, CpuBackend, Particle, Setup};

/// A configured CPU backend.
pub fn configured(setup: &Setup) -> CpuBackend {
    let mut backend = CpuBackend::new();
    backend.configure(setup).expect("valid setup");
    backend
}

/// Particles as raw bytes (for bit-identity).
pub fn particle_bytes(backend: &mut CpuBackend) -> Vec<u8> {
    let particles: Vec<Particle> = backend.read_particles().expect("configured");
    bytemuck::cast_slice(&particles).to_vec()
}

/// Cover as raw bytes.
pub fn cover_bytes(backend: &mut CpuBackend) -> Vec<u8> {
    let cover: CoverGrid = backend.read_cover().expect("configured");
    bytemuck::cast_slice(&cover.texels).to_vec()
}

/// Steps `n` times by `dt`.
pub fn run(backend: &mut CpuBackend, n: usize, dt: f32) {
    for _ in 0..n {
        backend.step(dt).expect("valid dt");
    }
}

/// What `step_particle` reads for `setup`, with its block, wind and deposits.
pub fn step_inputs<'a>(
    setup: &'a Setup,
    params: &'a StepParams,
    wind: &'a WindVolume,
    deposits: &'a DepositBuffer,
) -> StepInputs<'a> {
    StepInputs {
        params,
        wind,
        ground: &setup.ground,
        cover_frame: &setup.cover.frame,
        cover_texels: &[],
        deposits,
    }
}
