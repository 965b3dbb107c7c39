//! `cargo run --release -p precip-benches --bin report [out.json]`: every backend side
//! by side — particles per second of a step, the step's bytes per second against the
//! device's own buffer-copy bandwidth, GPU time per kernel, and vk ÷ wgpu step time;
//! printed as a table and written as JSON.

use std::time::Instant;

use precip_benches::{COUNTS, DT_S, STEP_BYTES_PER_PARTICLE, backends, scenario};
use precip_gpu_wgpu::WgpuBackend;
use serde_json::json;

/// Buffer-copy bandwidth of the wgpu device (read + write bytes per second).
fn wgpu_copy_bandwidth() -> Option<f64> {
    let gpu = WgpuBackend::new().ok()?;
    let d = &gpu.device().device;
    let size: u64 = 128 << 20;
    let make = |usage| {
        d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("bandwidth"),
            size,
            usage,
            mapped_at_creation: false,
        })
    };
    let (a, b) = (
        make(wgpu::BufferUsages::COPY_SRC),
        make(wgpu::BufferUsages::COPY_DST),
    );
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let mut encoder = d.create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        encoder.copy_buffer_to_buffer(&a, 0, &b, 0, size);
        let start = Instant::now();
        gpu.device().queue.submit([encoder.finish()]);
        gpu.device().wait().ok()?;
        best = best.min(start.elapsed().as_secs_f64());
    }
    Some(2.0 * size as f64 / best)
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/precip-report.json".into());
    let bandwidth = wgpu_copy_bandwidth();
    if let Some(bw) = bandwidth {
        println!("device buffer copy: {:.1} GB/s (read + write)", bw * 1e-9);
    }
    let mut rows = Vec::new();
    for (name, mut backend) in backends() {
        for count in COUNTS {
            if let Err(e) = backend.configure(&scenario(count)) {
                eprintln!("{name} at {count}: {e}");
                continue;
            }
            backend.step(DT_S).ok();
            let _ = backend.timings();
            let steps = 10;
            let start = Instant::now();
            let mut kernels: Vec<(&str, f64)> = Vec::new();
            for _ in 0..steps {
                backend.step(DT_S).expect("valid step");
                if let Ok(t) = backend.timings() {
                    for p in t.passes {
                        match kernels.iter_mut().find(|(n, _)| *n == p.pass) {
                            Some(k) => k.1 += p.milliseconds / f64::from(steps),
                            None => kernels.push((p.pass, p.milliseconds / f64::from(steps))),
                        }
                    }
                }
            }
            let seconds = start.elapsed().as_secs_f64() / f64::from(steps);
            let per_second = f64::from(count) / seconds;
            let bytes_per_second = (STEP_BYTES_PER_PARTICLE * u64::from(count)) as f64 / seconds;
            let ratio = bandwidth
                .filter(|_| name != "cpu")
                .map(|bw| bytes_per_second / bw);
            println!(
                "{name:>5} {count:>8}: {:>8.2} ms/step, {:>6.2} M particles/s{}{}",
                seconds * 1e3,
                per_second * 1e-6,
                ratio.map_or(String::new(), |r| format!(", {:.2} of copy bandwidth", r)),
                if kernels.is_empty() {
                    String::new()
                } else {
                    format!(
                        "; {}",
                        kernels
                            .iter()
                            .map(|(n, ms)| format!("{n} {ms:.2} ms"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                }
            );
            rows.push(json!({
                "backend": name, "particles": count, "step_ms": seconds * 1e3,
                "particles_per_second": per_second, "bandwidth_ratio": ratio,
                "kernels_ms": kernels.iter().map(|(n, ms)| json!({"pass": n, "ms": ms})).collect::<Vec<_>>(),
            }));
        }
    }
    for count in COUNTS {
        let step = |b: &str| {
            rows.iter()
                .find(|r| r["backend"] == b && r["particles"] == count)
                .and_then(|r| r["step_ms"].as_f64())
        };
        if let (Some(vk), Some(wgpu)) = (step("vk"), step("wgpu")) {
            println!("vk ÷ wgpu step time at {count}: {:.2}", vk / wgpu);
        }
    }
    let report = json!({ "copy_bandwidth_bytes_per_second": bandwidth, "rows": rows });
    match std::fs::write(
        &out,
        serde_json::to_string_pretty(&report).unwrap_or_default(),
    ) {
        Ok(()) => println!("wrote {out}"),
        Err(e) => eprintln!("could not write {out}: {e}"),
    }
}
