//! One step (dt = 20 ms, one sub-step) at 10⁴, 10⁵ and 10⁶ particles on the wgpu
//! backend and, beside it, the CPU reference; throughput in particles per second.
//! The GPU step is timed to completion (submit + wait), as a frame would see it.
//!
//! `cargo bench -p precip-gpu-wgpu --bench step`

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::wind::WindField;
use precip_model::{Backend, CpuBackend, Setup};

const COUNTS: [u32; 3] = [10_000, 100_000, 1_000_000];
const DT_S: f32 = 0.02;

fn setup(count: u32) -> Setup {
    let mut setup = Setup::over_flat_ground(200.0, 128, 40.0, count);
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(5.0, 0.0, 2.0),
        vertical_gust_mps: 0.5,
        ..WindField::calm()
    };
    setup
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(4))
        .warm_up_time(Duration::from_secs(1));
    let mut gpu = match WgpuBackend::new() {
        Ok(gpu) => Some(gpu),
        Err(e) => {
            eprintln!("wgpu benches skipped: {e}");
            None
        }
    };
    for count in COUNTS {
        group.throughput(Throughput::Elements(u64::from(count)));
        if let Some(gpu) = gpu.as_mut() {
            match gpu.configure(&setup(count)) {
                Ok(()) => {
                    group.bench_function(BenchmarkId::new("wgpu", count), |b| {
                        b.iter(|| {
                            gpu.step(DT_S).expect("valid step");
                            gpu.device().wait().expect("device alive");
                        });
                    });
                }
                Err(e) => eprintln!("wgpu at {count}: {e}"),
            }
        }
        let mut cpu = CpuBackend::new();
        cpu.configure(&setup(count)).expect("valid setup");
        group.bench_function(BenchmarkId::new("cpu", count), |b| {
            b.iter(|| cpu.step(DT_S).expect("valid step"))
        });
    }
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
