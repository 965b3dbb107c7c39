//! A CIGI host flies the headless viewer's eyepoint in lockstep: Entity Control
//! moves the ownship, View Control hangs the view on it, and each host frame draws
//! one frame.

use std::net::UdpSocket;
use std::time::{Duration, Instant};

use crate::cli::{gpu_or_skip, precip, temp_dir};

/// IG Control (big-endian, host frame `frame`) and Entity Control for the ownship
/// at `lat`, `lon` (°), `alt` (m), heading `yaw` (°).
fn ownship_message(frame: u32, lat: f64, lon: f64, alt: f64, yaw: f32) -> Vec<u8> {
    let mut m = vec![1u8, 24, 3, 0, 0x31, 0, 0x80, 0];
    m.extend(frame.to_be_bytes());
    m.extend([0u8; 12]);
    m.extend([2u8, 48, 0, 0, 1, 0, 255, 0, 0, 0, 0, 0]);
    for v in [0.0f32, 0.0, yaw] {
        m.extend(v.to_be_bytes());
    }
    for v in [lat, lon, alt] {
        m.extend(v.to_bits().to_be_bytes());
    }
    m
}

fn pixels(path: &std::path::Path) -> Vec<u8> {
    image::open(path).expect("a frame").to_rgb8().into_raw()
}

/// The share of values differing by more than 24 of 255.
fn changed(a: &[u8], b: &[u8]) -> f32 {
    let n = a
        .iter()
        .zip(b)
        .filter(|(x, y)| x.abs_diff(**y) > 24)
        .count();
    n as f32 / a.len() as f32
}

#[test]
fn a_cigi_host_flies_the_eyepoint_in_lockstep_and_the_view_follows() {
    if !gpu_or_skip("a_cigi_host_flies_the_eyepoint_in_lockstep_and_the_view_follows") {
        return;
    }
    let port = UdpSocket::bind("127.0.0.1:0")
        .and_then(|s| s.local_addr())
        .expect("a free port")
        .port();
    let dir = temp_dir("cigi-eyepoint");
    let mut child = precip()
        .args([
            "--frames",
            "6",
            "--size",
            "96x54",
            "--particles",
            "5000",
            "--origin",
            "0,0,0",
            "--cigi-lockstep",
            "--cigi",
        ])
        .arg(port.to_string())
        .arg("--out")
        .arg(&dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    // On the tangent plane at 0° N 0° E: x east = a·Δλ, z = −north = −a(1 − e²)·Δφ
    // (the radii of curvature there), y up.
    let a = 6_378_137.0f64;
    let m = a * (1.0 - 0.006_694_379_990_14);
    let at = |x: f64, z: f64| ((-z / m).to_degrees(), (x / a).to_degrees());
    // Host frames 1–3: by the house's lawn looking north at it; 4–6: 40 m east of
    // it, 10 m up, looking west.
    let (south_lat, south_lon) = at(5.0, 25.0);
    let (east_lat, east_lon) = at(40.0, 0.0);
    let host = UdpSocket::bind("127.0.0.1:0").expect("host socket");
    host.set_read_timeout(Some(Duration::from_millis(200)))
        .expect("timeout");
    let mut sent = 0u32;
    let mut last_send = Instant::now();
    let mut echoed = Vec::new();
    let mut buffer = [0u8; 256];
    let start = Instant::now();
    while child.try_wait().expect("alive").is_none() && start.elapsed() < Duration::from_secs(300) {
        // The host sends its next frame when the IG has drawn the last one (its
        // Start of Frame), as a synchronous host does; the first one at once.
        // Until the IG listens (it binds after configuring) a message is lost: the
        // host sends its frame again each second until it is answered (the IG draws
        // each host frame once, whatever it hears twice).
        let next = (sent == 0 || echoed.len() as u32 == sent) && sent < 6;
        let again = sent > 0
            && (echoed.len() as u32) < sent
            && last_send.elapsed() > Duration::from_secs(1);
        if next || again {
            if next {
                sent += 1;
            }
            let message = if sent <= 3 {
                ownship_message(sent, south_lat, south_lon, 1.7, 0.0)
            } else {
                ownship_message(sent, east_lat, east_lon, 10.0, 270.0)
            };
            host.send_to(&message, ("127.0.0.1", port)).expect("sent");
            last_send = Instant::now();
        }
        if let Ok((len, _)) = host.recv_from(&mut buffer) {
            let (sof, _) = precip_cigi::parse_start_of_frame(&buffer[..len]).expect("well formed");
            echoed.push(sof.last_host_frame);
        }
    }
    let out = child.wait_with_output().expect("finishes");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    // Lockstep: frame k was drawn from host frame k + 1, and no wait timed out.
    assert_eq!(echoed, [1, 2, 3, 4, 5, 6], "{text}");
    let line = text
        .lines()
        .find(|l| l.starts_with("CIGI: Entity Control"))
        .unwrap_or_else(|| panic!("no eyepoint line: {text}"));
    assert!(!line.contains("Entity Control 0 placed"), "{line}");
    assert!(line.contains("0 host frames missed"), "{line}");
    // The last eyepoint: 40 m east, 10 m up, looking west.
    let triple = |after: &str| -> [f32; 3] {
        let start = line
            .find(after)
            .unwrap_or_else(|| panic!("{after} in {line}"))
            + after.len();
        let inner = &line[start..line[start..].find(')').map_or(line.len(), |e| start + e)];
        let v: Vec<f32> = inner
            .split(',')
            .map(|t| t.trim().parse().expect("a number"))
            .collect();
        [v[0], v[1], v[2]]
    };
    let (eye, forward) = (triple("last eyepoint ("), triple("looking ("));
    assert!(
        (eye[0] - 40.0).abs() < 0.1 && (eye[1] - 10.0).abs() < 0.1 && eye[2].abs() < 0.1,
        "{line}"
    );
    assert!(
        (forward[0] + 1.0).abs() < 1e-3 && forward[1].abs() < 1e-3,
        "{line}"
    );
    // The view follows: the same eyepoint draws nearly the same frame, the moved
    // one another.
    let frame = |k: u32| pixels(&dir.join(format!("frame_{k:04}.png")));
    let still = changed(&frame(1), &frame(2));
    let moved = changed(&frame(2), &frame(3));
    assert!(
        still < 0.05 && moved > 0.3,
        "changed: {still} between frames at one eyepoint, {moved} after the move"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
