//! An X server for window tests: Xvfb on a display it picks itself, killed on drop.
//!
//! Two tests of this binary run at once, each with its own server. Xvfb chooses a free
//! display and writes its number to us (`-displayfd`), so two servers never race for the
//! same one (a server that lost that race used to leave its test on the winner's
//! display, which vanished when the winner's test ended). `-noreset` keeps the server up
//! between the clients a test starts one after another.

use std::io::BufRead;
use std::process::{Command, Stdio};

/// An X server for a window test: Xvfb on a free display, killed on drop.
pub struct Xvfb {
    child: std::process::Child,
    /// Its `DISPLAY`, e.g. `:61`.
    pub display: String,
}

impl Xvfb {
    /// Starts one, or `None` when Xvfb is not installed; panics when it is installed
    /// but does not start (a window test must not pass by doing nothing).
    pub fn start() -> Option<Self> {
        let mut child = Command::new("Xvfb")
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "640x480x24",
                "-nolisten",
                "tcp",
                "-noreset",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .ok()?;
        // Xvfb writes the display's number once it accepts connections; a server that
        // fails exits, and the read ends empty.
        let mut line = String::new();
        let stdout = child.stdout.take()?;
        let read = std::io::BufReader::new(stdout).read_line(&mut line);
        match (read, line.trim().parse::<u32>()) {
            (Ok(_), Ok(number)) => Some(Self {
                child,
                display: format!(":{number}"),
            }),
            (read, _) => {
                let _ = child.kill();
                let status = child.wait();
                panic!("Xvfb did not start (read {read:?}, said {line:?}, exit {status:?})");
            }
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
