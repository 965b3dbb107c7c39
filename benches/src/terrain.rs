//! The frame over the built-in demo against the same frame with the demo standing on
//! 10 km of generated terrain (`precip --terrain generated`): the clipmap draws the
//! same count of triangles over any terrain, so the frame may grow only by the
//! terrain's own pixels and vertices (issue 29's target: within 1.2×). Both as the
//! viewer sets them up (300 000 particles, its default view), same-minute pairs.
//! Each frame is split into the host's share (the calling thread's CPU time in the
//! step and the render, [`thread_cpu_ms`]) and the GPU's passes, so a GPU run says
//! which of them the terrain grows.

use std::sync::Arc;
use std::time::Instant;

use precip_model::{Backend, View};
use precip_viewer::scene_setup::{SceneOptions, scene_setup};
use precip_viewer::terrain_file::{TerrainScale, TerrainSource, load_terrain};
use serde_json::json;

use crate::{DT_S, FRAME_SIZE, backends, frame};

/// Frames measured a setup (after as many unmeasured).
const FRAMES: u32 = 8;

/// The calling thread's CPU time, ms (the `cpu-time` crate's `ThreadTime`:
/// `CLOCK_THREAD_CPUTIME_ID` on Linux).
/// `None` where the system does not give it.
#[must_use]
pub fn thread_cpu_ms() -> Option<f64> {
    cpu_time::ThreadTime::try_now()
        .ok()
        .map(|t| t.as_duration().as_secs_f64() * 1e3)
}

/// A setup's measured frames: wall-clock ms, the host thread's CPU ms and the
/// GPU's ms per pass, each a frame's mean.
#[derive(Debug, Default)]
pub struct FrameCost {
    /// Wall-clock ms a frame (step, render, the wait for the GPU).
    pub wall_ms: f64,
    /// The calling thread's CPU ms a frame (recording, uploads, host physics);
    /// NaN where the system gives no thread CPU time.
    pub host_ms: f64,
    /// GPU ms a frame per pass, in the order first met.
    pub passes_ms: Vec<(&'static str, f64)>,
}

impl FrameCost {
    /// The passes' GPU ms, summed.
    #[must_use]
    pub fn gpu_ms(&self) -> f64 {
        self.passes_ms.iter().map(|(_, ms)| ms).sum()
    }

    /// The passes whose GPU ms differ most between `self` and `other` (the
    /// largest first), as `name a → b ms`.
    #[must_use]
    pub fn largest_changes(&self, other: &Self, count: usize) -> String {
        let ms = |c: &Self, name: &str| {
            c.passes_ms
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(0.0, |(_, ms)| *ms)
        };
        let mut names: Vec<&str> = self.passes_ms.iter().map(|(n, _)| *n).collect();
        for (n, _) in &other.passes_ms {
            if !names.contains(n) {
                names.push(n);
            }
        }
        names.sort_by(|a, b| {
            let d = |n: &str| (ms(other, n) - ms(self, n)).abs();
            d(b).total_cmp(&d(a))
        });
        names
            .iter()
            .take(count)
            .map(|n| format!("{n} {:.2} → {:.2}", ms(self, n), ms(other, n)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

fn mean_frame_cost(backend: &mut dyn Backend, on_terrain: bool) -> Result<FrameCost, String> {
    let loaded = precip_viewer::gltf_scene::load_scene_from_slice(
        &precip_viewer::demo::demo_glb(),
        "the built-in demo",
    )
    .map_err(|e| e.to_string())?;
    let mut scene = loaded.scene;
    if on_terrain {
        let terrain = load_terrain(
            &TerrainSource::Generated,
            TerrainScale {
                spacing_m: None,
                heights_m: None,
            },
        )
        .map_err(|e| e.to_string())?;
        scene = scene.on_terrain(Arc::new(terrain));
    }
    let options = SceneOptions {
        particle_budget: 300_000,
        seed: 1,
        texel_m: 0.5,
        cover_days_per_second: 0.05,
        weather: precip_model::Weather::default(),
        camera: None,
    };
    let setup = scene_setup(scene, &options).map_err(|e| e.to_string())?;
    backend.configure(&setup).map_err(|e| e.to_string())?;
    let view = View {
        camera: setup.camera,
        width_px: FRAME_SIZE.0,
        height_px: FRAME_SIZE.1,
    };
    for _ in 0..FRAMES {
        frame(backend, &view);
    }
    let n = f64::from(FRAMES);
    let mut cost = FrameCost::default();
    let start = Instant::now();
    for _ in 0..FRAMES {
        let host = thread_cpu_ms();
        backend.step(DT_S).map_err(|e| e.to_string())?;
        backend.render(&view).map_err(|e| e.to_string())?;
        cost.host_ms += match (host, thread_cpu_ms()) {
            (Some(before), Some(after)) => (after - before) / n,
            _ => f64::NAN,
        };
        let timings = backend.timings().map_err(|e| e.to_string())?;
        for p in timings.passes {
            match cost.passes_ms.iter_mut().find(|(name, _)| *name == p.pass) {
                Some(k) => k.1 += p.milliseconds / n,
                None => cost.passes_ms.push((p.pass, p.milliseconds / n)),
            }
        }
    }
    cost.wall_ms = start.elapsed().as_secs_f64() * 1e3 / n;
    Ok(cost)
}

/// Each GPU backend's frame over the demo and over the demo on the terrain, and
/// their ratio, printed.
#[must_use]
pub fn measure_terrain() -> serde_json::Value {
    let mut rows = Vec::new();
    for (name, mut backend) in backends() {
        if !backend.info().renders {
            continue;
        }
        let (demo, terrain) = match (
            mean_frame_cost(backend.as_mut(), false),
            mean_frame_cost(backend.as_mut(), true),
        ) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                eprintln!("{name} terrain: {e}");
                continue;
            }
        };
        let ratio = terrain.wall_ms / demo.wall_ms;
        println!(
            "{name:>5} terrain: the demo {:.1} ms/frame, on 10 km of terrain {:.1} ms/frame ({ratio:.2}×); host {:.2} → {:.2} ms, GPU {:.2} → {:.2} ms; most changed: {}",
            demo.wall_ms,
            terrain.wall_ms,
            demo.host_ms,
            terrain.host_ms,
            demo.gpu_ms(),
            terrain.gpu_ms(),
            demo.largest_changes(&terrain, 4),
        );
        let passes = |c: &FrameCost| {
            c.passes_ms
                .iter()
                .map(|(n, ms)| json!({"pass": n, "ms": ms}))
                .collect::<Vec<_>>()
        };
        rows.push(json!({
            "backend": name, "demo_frame_ms": demo.wall_ms, "terrain_frame_ms": terrain.wall_ms,
            "ratio": ratio,
            "demo_host_ms": demo.host_ms, "terrain_host_ms": terrain.host_ms,
            "demo_passes_ms": passes(&demo), "terrain_passes_ms": passes(&terrain),
        }));
    }
    json!(rows)
}
