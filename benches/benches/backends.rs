//! One step (20 ms, one sub-step) at 10⁴, 10⁵, 10⁶ particles on every backend present,
//! and a full frame (step + render at 1280×720 over the built-in house) on every
//! backend that renders; timed to completion (a read of the timings waits for the
//! GPU).
//!
//! `cargo bench -p precip-benches --bench backends`

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use precip_benches::{COUNTS, DT_S, FRAME_SIZE, backends, frame, frame_scenario, scenario};

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(4))
        .warm_up_time(Duration::from_secs(1));
    for (name, mut backend) in backends() {
        for count in COUNTS {
            if backend.configure(&scenario(count)).is_err() {
                continue;
            }
            group.throughput(Throughput::Elements(u64::from(count)));
            group.bench_function(BenchmarkId::new(name, count), |b| {
                b.iter(|| {
                    backend.step(DT_S).expect("valid step");
                    backend.timings().expect("waits for the GPU");
                });
            });
        }
    }
    group.finish();
}

fn full_frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame_1280x720");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(6))
        .warm_up_time(Duration::from_secs(1));
    for (name, mut backend) in backends() {
        if !backend.info().renders {
            continue;
        }
        for count in COUNTS {
            let (setup, view) = frame_scenario(count, FRAME_SIZE);
            if backend.configure(&setup).is_err() {
                continue;
            }
            group.throughput(Throughput::Elements(u64::from(count)));
            group.bench_function(BenchmarkId::new(name, count), |b| {
                b.iter(|| frame(backend.as_mut(), &view));
            });
        }
    }
    group.finish();
}

criterion_group!(benches, step, full_frame);
criterion_main!(benches);
