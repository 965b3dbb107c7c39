//! One rendered frame (shadow, cull, scene, particles; submit + wait) of the built-in
//! house under snow at 10⁴ and 10⁵ particles, 640×360, culling on and off.
//!
//! `cargo bench -p precip-gpu-wgpu --bench render`

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use precip_gpu_wgpu::WgpuBackend;
use precip_model::scene::builtin::house_on_plane;
use precip_model::{Backend, Setup, View};

fn render(c: &mut Criterion) {
    let mut group = c.benchmark_group("render");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(4))
        .warm_up_time(Duration::from_secs(1));
    let mut gpu = match WgpuBackend::new() {
        Ok(gpu) => gpu,
        Err(e) => {
            eprintln!("render benches skipped: {e}");
            return;
        }
    };
    for count in [10_000u32, 100_000] {
        for culling in [true, false] {
            let Ok((mut setup, _)) = Setup::over_scene(house_on_plane(), 128, 8.0, count) else {
                return;
            };
            setup.render.view_cone_culling = culling;
            let view = View {
                camera: setup.camera,
                width_px: 640,
                height_px: 360,
            };
            if let Err(e) = gpu.configure(&setup).and_then(|()| gpu.step(0.05)) {
                eprintln!("{count} particles skipped: {e}");
                continue;
            }
            group.throughput(Throughput::Elements(u64::from(count)));
            let name = if culling { "culled" } else { "unculled" };
            group.bench_function(BenchmarkId::new(name, count), |b| {
                b.iter(|| {
                    gpu.render(&view).expect("renders");
                    gpu.device().wait().expect("device alive");
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
