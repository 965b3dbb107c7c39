//! The peer in the same run: OpenSceneGraph's `osgprecipitation --snow 0.5` (what
//! FlightGear's precipitation is built on) and precip's own viewer, each in a window
//! of the same size over the same scene, on the same display, one after the other.
//!
//! `osgprecipitation` draws its own frame counter nowhere, so its frame rate comes
//! from Mesa's heads-up display: `GALLIUM_HUD=fps` with `GALLIUM_HUD_DUMP_DIR` writes
//! the frames per second of every half-second to a file `fps`, read after the run
//! (the first second, which loads the scene, is left out). The scene is the viewer's
//! built-in demo written as Wavefront OBJ (OpenSceneGraph reads OBJ, not glTF).
//! Without a display an `Xvfb` server of the window's size is started for the runs
//! and stopped after them.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use precip_model::Scene;

/// Why a peer measurement has no number.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PeerError {
    /// A program is not installed or did not start.
    #[error("{program} did not start ({detail}); install it (Debian: {package})")]
    Missing {
        /// The program.
        program: &'static str,
        /// The Debian package that has it.
        package: &'static str,
        /// What failed.
        detail: String,
    },
    /// A run gave no frame rate.
    #[error("{program} gave no frame rate: {detail}")]
    NoRate {
        /// The program.
        program: &'static str,
        /// Why.
        detail: String,
    },
    /// A file could not be written or read.
    #[error("{file}: {detail}")]
    File {
        /// The file.
        file: PathBuf,
        /// Why.
        detail: String,
    },
}

fn file_error(file: &Path, e: &std::io::Error) -> PeerError {
    PeerError::File {
        file: file.to_path_buf(),
        detail: e.to_string(),
    }
}

/// Writes `scene`'s triangles as Wavefront OBJ (positions and faces; Y up, metres).
pub fn write_obj(scene: &Scene, path: &Path) -> Result<(), PeerError> {
    let mut text = String::new();
    let mut first = 1u64;
    for mesh in &scene.meshes {
        text.push_str(&format!(
            "o {}\n",
            mesh.name.replace(char::is_whitespace, "_")
        ));
        for p in &mesh.positions_m {
            text.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
        let count = mesh.positions_m.len() as u32;
        let indices: Vec<u32> = if mesh.indices.is_empty() {
            (0..count).collect()
        } else {
            mesh.indices.clone()
        };
        for t in indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| first + u64::from(i));
            text.push_str(&format!("f {a} {b} {c}\n"));
        }
        first += u64::from(count);
    }
    let mut file = std::fs::File::create(path).map_err(|e| file_error(path, &e))?;
    file.write_all(text.as_bytes())
        .map_err(|e| file_error(path, &e))
}

/// An X display for the runs: the caller's, or an `Xvfb` started for them (stopped
/// on drop).
#[derive(Debug)]
pub struct Display {
    /// `DISPLAY`'s value.
    pub name: String,
    server: Option<Child>,
}

impl Display {
    /// The current display, or a new `Xvfb` of `size` px.
    pub fn open(size: (u32, u32)) -> Result<Self, PeerError> {
        if let Ok(name) = std::env::var("DISPLAY")
            && !name.is_empty()
        {
            return Ok(Self { name, server: None });
        }
        let name = format!(":{}", 50 + std::process::id() % 200);
        let server = Command::new("Xvfb")
            .args([
                name.as_str(),
                "-screen",
                "0",
                &format!("{}x{}x24", size.0, size.1),
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .map_err(|e| PeerError::Missing {
                program: "Xvfb",
                package: "xvfb",
                detail: e.to_string(),
            })?;
        std::thread::sleep(Duration::from_millis(1500));
        Ok(Self {
            name,
            server: Some(server),
        })
    }
}

impl Drop for Display {
    fn drop(&mut self) {
        if let Some(server) = self.server.as_mut() {
            let _ = server.kill();
            let _ = server.wait();
        }
    }
}

/// Mean of Mesa's `fps` dump, leaving out the first `skip` samples.
fn mean_fps(dump: &str, skip: usize) -> Option<f64> {
    let samples: Vec<f64> = dump
        .lines()
        .filter_map(|l| l.trim().parse::<f64>().ok())
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    let kept = samples.get(skip.min(samples.len().saturating_sub(1))..)?;
    (!kept.is_empty()).then(|| kept.iter().sum::<f64>() / kept.len() as f64)
}

/// `osgprecipitation --snow 0.5 scene.obj` in a `size` window on `display` for
/// `seconds`: its mean frames per second.
pub fn osgprecipitation_fps(
    display: &Display,
    obj: &Path,
    size: (u32, u32),
    seconds: u64,
) -> Result<f64, PeerError> {
    let dump = std::env::temp_dir().join(format!("precip-osg-hud-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dump);
    std::fs::create_dir_all(&dump).map_err(|e| file_error(&dump, &e))?;
    let mut child = Command::new("osgprecipitation")
        .arg("--snow")
        .arg("0.5")
        .arg(obj)
        .env("DISPLAY", &display.name)
        .env("OSG_WINDOW", format!("0 0 {} {}", size.0, size.1))
        .env("GALLIUM_HUD", "fps")
        .env("GALLIUM_HUD_DUMP_DIR", &dump)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|e| PeerError::Missing {
            program: "osgprecipitation",
            package: "openscenegraph",
            detail: e.to_string(),
        })?;
    std::thread::sleep(Duration::from_secs(seconds));
    let _ = child.kill();
    let _ = child.wait();
    let file = dump.join("fps");
    let text = std::fs::read_to_string(&file).map_err(|e| PeerError::NoRate {
        program: "osgprecipitation",
        detail: format!("{}: {e} (is the OpenGL driver Mesa's?)", file.display()),
    })?;
    let _ = std::fs::remove_dir_all(&dump);
    mean_fps(&text, 2).ok_or(PeerError::NoRate {
        program: "osgprecipitation",
        detail: "the HUD's dump holds no sample".into(),
    })
}

/// What precip's viewer printed after `--quit-after`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewerRun {
    /// Mean frame time after the warm-up, ms.
    pub frame_ms: f64,
    /// Mean particles drawn.
    pub particles_drawn: f64,
}

/// Parses `window: … mean frame time X ms, N particles drawn …`.
#[must_use]
pub fn parse_viewer_line(line: &str) -> Option<ViewerRun> {
    let after = |key: &str| -> Option<f64> {
        let at = line.find(key)? + key.len();
        line[at..]
            .split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .find(|s| !s.is_empty())?
            .parse()
            .ok()
    };
    let frame_ms = after("mean frame time ")?;
    let drawn_at = line.find(" particles drawn")?;
    let particles_drawn = line[..drawn_at].rsplit(' ').next()?.parse().ok()?;
    Some(ViewerRun {
        frame_ms,
        particles_drawn,
    })
}

/// precip's viewer (the binary `precip` beside this one: `cargo build --release`
/// makes it) with its defaults in a `size` window on `display` for `frames` frames.
pub fn viewer_run(
    display: &Display,
    size: (u32, u32),
    frames: u32,
    quality: &str,
) -> Result<ViewerRun, PeerError> {
    let exe = std::env::current_exe()
        .map_err(|e| PeerError::Missing {
            program: "precip",
            package: "cargo build --release",
            detail: e.to_string(),
        })?
        .with_file_name("precip");
    let output = Command::new(&exe)
        .args([
            "--size",
            &format!("{}x{}", size.0, size.1),
            "--quit-after",
            &frames.to_string(),
            "--quality",
            quality,
        ])
        .env("DISPLAY", &display.name)
        .output()
        .map_err(|e| PeerError::Missing {
            program: "precip",
            package: "cargo build --release",
            detail: format!("{}: {e}", exe.display()),
        })?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    stdout
        .lines()
        .find(|l| l.starts_with("window:"))
        .and_then(parse_viewer_line)
        .ok_or_else(|| PeerError::NoRate {
            program: "precip",
            detail: format!(
                "no `window:` line ({}): {}",
                output.status,
                String::from_utf8_lossy(&output.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
            ),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hud_dump_and_the_viewer_line_parse() {
        let fps = mean_fps("9.0\n20.0\n24.0\n26.0\n", 2).expect("samples");
        assert!((fps - 25.0).abs() < 1e-9);
        assert_eq!(mean_fps("", 2), None);
        let run = parse_viewer_line(
            "window: 40 frames in 9.1 s; mean frame time 180.4 ms, 104512 particles drawn (Wgpu, 1280×720)",
        )
        .expect("parses");
        assert!((run.frame_ms - 180.4).abs() < 1e-9);
        assert!((run.particles_drawn - 104_512.0).abs() < 1e-9);
        assert_eq!(parse_viewer_line("window: 3 frames; no frame timed"), None);
    }
}
