//! Bytes each kernel and draw moves per frame, from the frame recipe's counts
//! ([`precip_gpu::recipe::KERNEL_BYTES`]) and a frame's drawn counts, and the rate that
//! makes with the pass's measured GPU time: the report prints it for every GPU
//! backend's frame at 10⁶ particles.

use precip_gpu::recipe::{BytesPer, KERNEL_BYTES};
use precip_model::DrawnCounts;
use serde_json::{Value, json};

/// The timed pass a kernel or draw runs in.
fn pass_of(entry_point: &str) -> &'static str {
    match entry_point {
        "step_particles" => "step_particles",
        "birth_particles" => "birth_particles",
        "cull_count" | "cull_write" => "cull_particles",
        "splat_particles" => "splat_particles",
        _ => "particles",
    }
}

/// Per timed pass: bytes per particle of the frame (read + written) and GB/s over
/// the pass's GPU time, for `particles` with `drawn` (re-births, a few per step, not
/// counted). `passes_ms` are the frame's `(pass, ms)`.
#[must_use]
pub fn pass_traffic(particles: u32, drawn: DrawnCounts, passes_ms: &[(&str, f64)]) -> Value {
    let mut out: Vec<(&'static str, f64)> = Vec::new();
    for k in KERNEL_BYTES {
        let count = match (k.per, k.entry_point) {
            (BytesPer::Particle, _) => f64::from(particles),
            (BytesPer::Drawn, "splat_particles") => f64::from(drawn.splats),
            (BytesPer::Drawn, "vs_snow") => f64::from(drawn.sprites),
            (BytesPer::Drawn, "vs_rain") => f64::from(drawn.streaks),
            (BytesPer::Drawn, _) => f64::from(drawn.sprites + drawn.streaks + drawn.splats),
            (BytesPer::Birth, _) => 0.0,
        };
        let bytes = count * f64::from(k.read + k.written);
        let pass = pass_of(k.entry_point);
        match out.iter_mut().find(|(p, _)| *p == pass) {
            Some(entry) => entry.1 += bytes,
            None => out.push((pass, bytes)),
        }
    }
    Value::Array(
        out.into_iter()
            .map(|(pass, bytes)| {
                let ms = passes_ms
                    .iter()
                    .find(|(p, _)| *p == pass)
                    .map(|(_, ms)| *ms);
                json!({
                    "pass": pass,
                    "bytes_per_particle": bytes / f64::from(particles.max(1)),
                    "gb_per_s": ms.filter(|ms| *ms > 0.0).map(|ms| bytes / (ms * 1e-3) * 1e-9),
                })
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_step_moves_128_bytes_a_particle() {
        let drawn = DrawnCounts {
            sprites: 10,
            streaks: 0,
            splats: 90,
        };
        let t = pass_traffic(1_000, drawn, &[("step_particles", 1.0)]);
        let step = t
            .as_array()
            .and_then(|a| a.iter().find(|p| p["pass"] == "step_particles"))
            .expect("the step");
        assert_eq!(step["bytes_per_particle"], 128.0);
        // 1 000 × 128 B in 1 ms: 0.128 GB/s.
        assert!((step["gb_per_s"].as_f64().expect("timed") - 0.128).abs() < 1e-9);
    }
}
