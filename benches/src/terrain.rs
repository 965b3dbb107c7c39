//! The frame over the built-in demo against the same frame with the demo standing on
//! 10 km of generated terrain (`precip --terrain generated`): the clipmap draws the
//! same count of triangles over any terrain, so the frame may grow only by the
//! terrain's own pixels and vertices (issue 29's target: within 1.2×). Both as the
//! viewer sets them up (300 000 particles, its default view), same-minute pairs.

use std::sync::Arc;
use std::time::Instant;

use precip_model::{Backend, View};
use precip_viewer::scene_setup::{SceneOptions, scene_setup};
use precip_viewer::terrain_file::{TerrainScale, TerrainSource, load_terrain};
use serde_json::json;

use crate::{FRAME_SIZE, backends, frame};

/// Frames measured a setup (after as many unmeasured).
const FRAMES: u32 = 8;

fn mean_frame_ms(backend: &mut dyn Backend, on_terrain: bool) -> Result<f64, String> {
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
    let start = Instant::now();
    for _ in 0..FRAMES {
        frame(backend, &view);
    }
    Ok(start.elapsed().as_secs_f64() * 1e3 / f64::from(FRAMES))
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
            mean_frame_ms(backend.as_mut(), false),
            mean_frame_ms(backend.as_mut(), true),
        ) {
            (Ok(a), Ok(b)) => (a, b),
            (Err(e), _) | (_, Err(e)) => {
                eprintln!("{name} terrain: {e}");
                continue;
            }
        };
        println!(
            "{name:>5} terrain: the demo {demo:.1} ms/frame, on 10 km of terrain {terrain:.1} ms/frame ({:.2}×)",
            terrain / demo
        );
        rows.push(json!({
            "backend": name, "demo_frame_ms": demo, "terrain_frame_ms": terrain,
            "ratio": terrain / demo,
        }));
    }
    json!(rows)
}
