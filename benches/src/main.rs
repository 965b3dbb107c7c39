//! `cargo run --release -p precip-benches --bin report -- [out.json [before.json]]
//! [--size WxH] [--no-peer]` (`before.json`: an earlier report, or
//! `docs/performance-before.json`, whose frames are plotted beside today's; `--size`:
//! the full frames' size, 1280×720 unless given, 1920×1080 for a GPU's 10⁷
//! particles; `--no-peer`: without the window runs): every backend side
//! by side — particles per second of a step, the step's bytes per second against the
//! device's own buffer-copy bandwidth (and `step_over_copy_64b`: step particles/s at
//! 10⁶ over copy bytes/s ÷ 128, the rate of a kernel that only copies a 64-byte
//! particle; `step_particles_over_copy_64b` the same of the particles' kernel's GPU
//! time alone), GPU time per kernel and per render pass and the bytes each moves
//! ([`precip_benches::traffic`]), a full frame (step + render at
//! `--size`) from 10⁴ to 10⁷ particles and vk ÷ wgpu for both, and the peer in the
//! same run ([`precip_benches::peer`]: `osgprecipitation --snow 0.5` and precip's
//! viewer in windows of the same size over the demo scene); printed as a table,
//! written as JSON and plotted as a PNG beside it. Build the viewer first
//! (`cargo build --release`) for its window run; `report --peer` runs only that
//! (the peer, then precip's viewer at each `--quality`), `report --terrain` only
//! the frame over the demo against the demo on 10 km of terrain
//! ([`precip_benches::terrain`]).

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Parser;

use precip_benches::peer::{Display, osgprecipitation_fps, viewer_run, write_obj};
use precip_benches::plot::{Series, write_png};
use precip_benches::traffic::pass_traffic;
use precip_benches::{
    COUNTS, DT_S, FRAME_COUNTS, FRAME_SIZE, MEASURE_S, WARM_UP_S, backends, frame, frame_scenario,
    repeat_for, scenario, step_bytes_per_particle,
};
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

/// Adds `timings` / `n` to the running mean per pass `passes`.
fn passes_text(passes: &[(&str, f64)]) -> String {
    passes
        .iter()
        .map(|(n, ms)| format!("{n} {ms:.2} ms"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The report's command line.
#[derive(Parser)]
#[command(
    name = "report",
    about = "Every backend side by side: steps, full frames, the peer and the terrain"
)]
struct Args {
    /// The report's JSON (its plot is written beside it as a PNG)
    #[arg(default_value = "target/precip-report.json")]
    out: PathBuf,
    /// An earlier report (or docs/performance-before.json) whose frames are plotted
    /// beside today's
    before: Option<PathBuf>,
    /// Only the side-by-side window run against osgprecipitation
    #[arg(long, conflicts_with_all = ["terrain", "before", "size", "no_peer"])]
    peer: bool,
    /// Only the demo's frame against the demo's on 10 km of terrain
    #[arg(long, conflicts_with_all = ["before", "size", "no_peer"])]
    terrain: bool,
    /// The full frames' size, WIDTHxHEIGHT px
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    size: (u32, u32),
    /// Leave out the window runs (osgprecipitation and the viewer under a display)
    #[arg(long)]
    no_peer: bool,
}

/// `WIDTHxHEIGHT` in pixels, each 1 to 8192.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}` is not WIDTHxHEIGHT in pixels (e.g. 1920x1080)");
    let (w, h) = text.split_once(['x', '×']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
        return Err(format!("{w}x{h}: each side must be 1 to 8192 px"));
    }
    Ok((w, h))
}

/// Frames drawn after each configure before the measured ones.
const WARM_UP_FRAMES: u32 = 10;

/// Full frames of `size_px` on every backend that renders: wall-clock ms per frame and
/// GPU ms per pass.
fn measure_frames(rows: &mut Vec<serde_json::Value>, size_px: (u32, u32)) {
    for (name, mut backend) in backends() {
        if !backend.info().renders {
            continue;
        }
        for count in FRAME_COUNTS {
            if u64::from(count) > backend.info().max_particles {
                eprintln!(
                    "{name} frame at {count}: more than the device holds ({})",
                    backend.info().max_particles
                );
                continue;
            }
            let (setup, view) = frame_scenario(count, size_px);
            if let Err(e) = backend.configure(&setup) {
                eprintln!("{name} frame at {count}: {e}");
                continue;
            }
            // Frames before the measured ones, so the measured ones are the steady
            // state's (the device's clock too: WARM_UP_S).
            repeat_for(WARM_UP_FRAMES, WARM_UP_S, || {
                frame(backend.as_mut(), &view);
            });
            let least = match count {
                10_000_000.. => 2,
                1_000_000.. => 3,
                _ => 6,
            };
            let mut passes = Vec::new();
            let start = Instant::now();
            let frames = repeat_for(least, MEASURE_S, || {
                let t = frame(backend.as_mut(), &view);
                precip_benches::accumulate_passes(&mut passes, t, 1.0);
            });
            for (_, ms) in &mut passes {
                *ms /= f64::from(frames);
            }
            let ms = start.elapsed().as_secs_f64() * 1e3 / f64::from(frames);
            let drawn = backend.drawn().ok().flatten().unwrap_or_default();
            println!(
                "{name:>5} {count:>8}: {ms:>8.1} ms/frame ({}×{}); {}; drawn {} sprites, {} streaks, {} splats",
                size_px.0,
                size_px.1,
                passes_text(&passes),
                drawn.sprites,
                drawn.streaks,
                drawn.splats,
            );
            let traffic = pass_traffic(count, drawn, &passes);
            if count == 1_000_000 {
                println!("{name:>5} {count:>8}: bytes a particle and GB/s per pass: {traffic}");
            }
            let shares = precip_gpu::recipe::feature_shares(&passes);
            println!(
                "{name:>5} {count:>8}: share of the GPU time: {}",
                precip_gpu::recipe::feature_shares_text(&passes)
            );
            rows.push(json!({
                "backend": name, "particles": count, "frame_ms": ms,
                "width_px": size_px.0, "height_px": size_px.1,
                "passes_ms": passes.iter().map(|(n, ms)| json!({"pass": n, "ms": ms})).collect::<Vec<_>>(),
                "features": shares.iter().map(|(f, ms, share)| json!({"feature": f, "ms": ms, "share": share})).collect::<Vec<_>>(),
                "drawn": json!({"sprites": drawn.sprites, "streaks": drawn.streaks, "splats": drawn.splats}),
                "traffic": traffic,
            }));
        }
    }
}

/// `step_over_copy_64b` of each GPU backend: step particles/s at 10⁶ divided by
/// (copy bytes/s ÷ 128), printed; and the same of `step_particles` alone (its GPU
/// time, without the step's fixed cost: the cover grid's kernels, the submit and
/// the wait), as `step_particles_over_copy_64b`.
fn step_over_copy(
    rows: &[serde_json::Value],
    bandwidth: Option<f64>,
) -> (serde_json::Value, serde_json::Value) {
    let mut step = serde_json::Map::new();
    let mut kernel = serde_json::Map::new();
    if let Some(bw) = bandwidth {
        let per_second_64b = bw / 128.0;
        for r in rows {
            if r["particles"] != 1_000_000 || r["backend"] == "cpu" {
                continue;
            }
            let Some(name) = r["backend"].as_str() else {
                continue;
            };
            if let Some(rate) = r["particles_per_second"].as_f64() {
                let ratio = rate / per_second_64b;
                println!("step_over_copy_64b {name}: {ratio:.3}");
                step.insert(name.to_string(), json!(ratio));
            }
            let kernel_ms = r["kernels_ms"].as_array().and_then(|k| {
                k.iter()
                    .find(|p| p["pass"] == "step_particles")
                    .and_then(|p| p["ms"].as_f64())
            });
            if let Some(ms) = kernel_ms.filter(|ms| *ms > 0.0) {
                let ratio = 1e6 / (ms * 1e-3) / per_second_64b;
                println!(
                    "step_particles_over_copy_64b {name}: {ratio:.3} (the particles' kernel alone, {ms:.2} GPU ms)"
                );
                kernel.insert(name.to_string(), json!(ratio));
            }
        }
    }
    (
        serde_json::Value::Object(step),
        serde_json::Value::Object(kernel),
    )
}

/// osgprecipitation and precip's viewer in windows of [`FRAME_SIZE`] over the demo.
fn measure_peer() -> serde_json::Value {
    let display = match Display::open(FRAME_SIZE) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("peer not measured: {e}");
            return json!({"error": e.to_string()});
        }
    };
    let demo = precip_viewer::gltf_scene::load_scene_from_slice(
        &precip_viewer::demo::demo_glb(),
        "the built-in demo",
    );
    let obj = std::env::temp_dir().join(format!("precip-demo-{}.obj", std::process::id()));
    let osg = demo
        .map_err(|e| e.to_string())
        .and_then(|d| write_obj(&d.scene, &obj).map_err(|e| e.to_string()))
        .and_then(|()| {
            osgprecipitation_fps(&display, &obj, FRAME_SIZE, 14).map_err(|e| e.to_string())
        });
    let _ = std::fs::remove_file(&obj);
    let ours = viewer_run(&display, FRAME_SIZE, 40, "high").map_err(|e| e.to_string());
    // The lower quality levels: the particles at half and a quarter of the frame's
    // resolution (`precip_model::Quality`).
    let lower: Vec<(&str, Result<_, String>)> = ["medium", "low"]
        .into_iter()
        .map(|q| {
            (
                q,
                viewer_run(&display, FRAME_SIZE, 40, q).map_err(|e| e.to_string()),
            )
        })
        .collect();
    match &osg {
        Ok(fps) => println!(
            "osgprecipitation --snow 0.5 over the demo, {}×{}: {fps:.1} fps",
            FRAME_SIZE.0, FRAME_SIZE.1
        ),
        Err(e) => eprintln!("osgprecipitation not measured: {e}"),
    }
    match &ours {
        Ok(run) => println!(
            "precip viewer (wgpu, defaults), {}×{}: {:.1} fps ({:.1} ms), {:.0} particles drawn",
            FRAME_SIZE.0,
            FRAME_SIZE.1,
            1e3 / run.frame_ms,
            run.frame_ms,
            run.particles_drawn
        ),
        Err(e) => eprintln!("precip viewer not measured: {e}"),
    }
    let ratio = match (&osg, &ours) {
        (Ok(fps), Ok(run)) => {
            let r = 1e3 / run.frame_ms / fps;
            println!("precip ÷ osgprecipitation frame rate: {r:.2}");
            Some(r)
        }
        _ => None,
    };
    let mut by_quality = serde_json::Map::new();
    for (quality, run) in &lower {
        match run {
            Ok(run) => {
                let r = osg.as_ref().ok().map(|fps| 1e3 / run.frame_ms / fps);
                println!(
                    "precip viewer --quality {quality}: {:.1} ms, {:.0} particles drawn; ÷ osgprecipitation {}",
                    run.frame_ms,
                    run.particles_drawn,
                    r.map_or_else(|| "—".to_string(), |r| format!("{r:.2}"))
                );
                by_quality.insert(
                    (*quality).to_string(),
                    json!({"frame_ms": run.frame_ms, "particles_drawn": run.particles_drawn,
                           "over_osgprecipitation_fps": r}),
                );
            }
            Err(e) => eprintln!("precip viewer --quality {quality} not measured: {e}"),
        }
    }
    json!({
        "width_px": FRAME_SIZE.0, "height_px": FRAME_SIZE.1,
        "osgprecipitation_fps": osg.as_ref().ok(),
        "osgprecipitation_error": osg.as_ref().err(),
        "precip_viewer_frame_ms": ours.as_ref().ok().map(|r| r.frame_ms),
        "precip_viewer_particles_drawn": ours.as_ref().ok().map(|r| r.particles_drawn),
        "precip_viewer_error": ours.as_ref().err(),
        "precip_over_osgprecipitation_fps": ratio,
        "precip_viewer_lower_quality": by_quality,
    })
}

/// `vk ÷ wgpu` of `key` at each count, printed.
fn ratios(rows: &[serde_json::Value], key: &str, what: &str) -> Vec<serde_json::Value> {
    let mut out = Vec::new();
    for count in FRAME_COUNTS {
        let value = |b: &str| {
            rows.iter()
                .find(|r| r["backend"] == b && r["particles"] == count)
                .and_then(|r| r[key].as_f64())
        };
        if let (Some(vk), Some(wgpu)) = (value("vk"), value("wgpu")) {
            println!("vk ÷ wgpu {what} at {count}: {:.2}", vk / wgpu);
            out.push(json!({"particles": count, "vk_over_wgpu": vk / wgpu}));
        }
    }
    out
}

/// One line per backend of `key` against particles.
fn series(rows: &[serde_json::Value], key: &str, job: &str) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for r in rows {
        let (Some(b), Some(n), Some(ms)) = (
            r["backend"].as_str(),
            r["particles"].as_f64(),
            r[key].as_f64(),
        ) else {
            continue;
        };
        let label = format!("{b} {job}");
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push((n, ms)),
            None => out.push(Series {
                label,
                points: vec![(n, ms)],
            }),
        }
    }
    out
}

fn main() {
    let args = Args::parse();
    if args.terrain {
        let rows = precip_benches::terrain::measure_terrain();
        println!(
            "{}",
            serde_json::to_string_pretty(&rows).unwrap_or_default()
        );
        return;
    }
    if args.peer {
        let peer = measure_peer();
        println!(
            "{}",
            serde_json::to_string_pretty(&peer).unwrap_or_default()
        );
        return;
    }
    let out = args.out.display().to_string();
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
            repeat_for(1, WARM_UP_S, || {
                backend.step(DT_S).ok();
                let _ = backend.timings();
            });
            let start = Instant::now();
            let mut kernels: Vec<(&str, f64)> = Vec::new();
            let steps = repeat_for(10, MEASURE_S, || {
                backend.step(DT_S).expect("valid step");
                if let Ok(t) = backend.timings() {
                    precip_benches::accumulate_passes(&mut kernels, t, 1.0);
                }
            });
            for (_, ms) in &mut kernels {
                *ms /= f64::from(steps);
            }
            let seconds = start.elapsed().as_secs_f64() / f64::from(steps);
            let per_second = f64::from(count) / seconds;
            let bytes_per_second = (step_bytes_per_particle() * u64::from(count)) as f64 / seconds;
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
                    format!("; {}", passes_text(&kernels))
                }
            );
            rows.push(json!({
                "backend": name, "particles": count, "step_ms": seconds * 1e3,
                "particles_per_second": per_second, "bandwidth_ratio": ratio,
                "kernels_ms": kernels.iter().map(|(n, ms)| json!({"pass": n, "ms": ms})).collect::<Vec<_>>(),
            }));
        }
    }
    let step_ratios = ratios(&rows, "step_ms", "step time");
    let (step_over_copy_64b, step_particles_over_copy_64b) = step_over_copy(&rows, bandwidth);
    let mut frame_rows = Vec::new();
    measure_frames(&mut frame_rows, args.size);
    let frame_ratios = ratios(&frame_rows, "frame_ms", "frame time");
    let peer = if args.no_peer {
        json!({"error": "left out (--no-peer)"})
    } else {
        measure_peer()
    };
    let terrain = precip_benches::terrain::measure_terrain();
    let mut plotted = series(&rows, "step_ms", "step");
    plotted.extend(series(
        &frame_rows,
        "frame_ms",
        &format!("frame {}×{}", args.size.0, args.size.1),
    ));
    // An earlier report's (or docs/performance-before.json's) frames, for comparison.
    if let Some(before) = &args.before {
        match std::fs::read_to_string(before)
            .map_err(|e| e.to_string())
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).map_err(|e| e.to_string()))
        {
            Ok(v) => {
                let rows = v["frames"].as_array().cloned().unwrap_or_default();
                plotted.extend(series(&rows, "frame_ms", "frame before"));
            }
            Err(e) => eprintln!("{}: {e}", before.display()),
        }
    }
    let device = backends()
        .into_iter()
        .find(|(n, _)| *n == "vk" || *n == "wgpu")
        .map(|(_, b)| b.info().device)
        .unwrap_or_default();
    let report = json!({
        "device": device,
        "copy_bandwidth_bytes_per_second": bandwidth,
        "rows": rows,
        "frames": frame_rows,
        "vk_over_wgpu_step": step_ratios,
        "vk_over_wgpu_frame": frame_ratios,
        "step_over_copy_64b": step_over_copy_64b,
        "step_particles_over_copy_64b": step_particles_over_copy_64b,
        "peer": peer,
        "terrain": terrain,
    });
    let png = Path::new(&out).with_extension("png");
    match write_png(
        &png,
        &format!("precip: ms per step and per frame — {device}"),
        &plotted,
    ) {
        Ok(()) => println!("wrote {}", png.display()),
        Err(e) => eprintln!("no plot: {e}"),
    }
    match std::fs::write(
        &out,
        serde_json::to_string_pretty(&report).unwrap_or_default(),
    ) {
        Ok(()) => println!("wrote {out}"),
        Err(e) => eprintln!("could not write {out}: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kernel_s_ratio_leaves_the_step_s_fixed_cost_out() {
        let rows = vec![
            json!({"backend": "cpu", "particles": 1_000_000, "particles_per_second": 1.0e7,
                   "kernels_ms": [{"pass": "step_particles", "ms": 100.0}]}),
            json!({"backend": "wgpu", "particles": 100_000, "particles_per_second": 1.0e8,
                   "kernels_ms": [{"pass": "step_particles", "ms": 0.05}]}),
            json!({"backend": "wgpu", "particles": 1_000_000, "particles_per_second": 8.0e8,
                   "kernels_ms": [{"pass": "birth_particles", "ms": 0.01},
                                  {"pass": "step_particles", "ms": 0.16}]}),
        ];
        // 640 GB/s of copy: 5·10⁹ 64-byte particles read and written a second.
        let (step, kernel) = step_over_copy(&rows, Some(640.0e9));
        assert!((step["wgpu"].as_f64().unwrap() - 0.16).abs() < 1e-9);
        assert!((kernel["wgpu"].as_f64().unwrap() - 1.25).abs() < 1e-9);
        assert!(step.get("cpu").is_none() && kernel.get("cpu").is_none());
        let (step, kernel) = step_over_copy(&rows, None);
        assert_eq!((step, kernel), (json!({}), json!({})));
    }

    #[test]
    fn sizes_are_width_by_height_within_bounds() {
        assert_eq!(parse_size("1920x1080"), Ok((1920, 1080)));
        assert_eq!(parse_size("640×360"), Ok((640, 360)));
        assert!(parse_size("1920").is_err());
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("9000x10").is_err());
    }
}
