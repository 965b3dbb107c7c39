//! An X server for window tests: Xvfb on a free display, killed on drop.

use std::process::Command;

/// An X server for a window test: Xvfb on a free display, killed on drop.
pub struct Xvfb {
    child: std::process::Child,
    /// Its `DISPLAY`, e.g. `:61`.
    pub display: String,
}

impl Xvfb {
    /// Starts one, or `None` when Xvfb is not installed.
    pub fn start() -> Option<Self> {
        for n in 0..40 {
            let number = 60 + (std::process::id() as usize + n) % 400;
            if std::path::Path::new(&format!("/tmp/.X11-unix/X{number}")).exists() {
                continue;
            }
            let display = format!(":{number}");
            let child = Command::new("Xvfb")
                .args([
                    display.as_str(),
                    "-screen",
                    "0",
                    "640x480x24",
                    "-nolisten",
                    "tcp",
                ])
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .ok()?;
            let socket = format!("/tmp/.X11-unix/X{number}");
            for _ in 0..100 {
                if std::path::Path::new(&socket).exists() {
                    return Some(Self { child, display });
                }
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
            let mut child = child;
            let _ = child.kill();
            let _ = child.wait();
        }
        None
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
