//! The `precip` binary: inspect's exit status, the demo writer, and the headless
//! fallback when there is no display.

use std::process::Command;

fn precip() -> Command {
    Command::new(env!("CARGO_BIN_EXE_precip"))
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("precip-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn inspect_succeeds_on_a_scene_and_fails_with_the_reason_on_a_bad_file() {
    let dir = temp_dir("inspect");
    let demo = dir.join("demo.glb");
    let out = precip()
        .args(["demo", "--out"])
        .arg(&demo)
        .output()
        .expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(&demo).expect("written"),
        precip_viewer::demo::DEMO_GLB
    );

    let out = precip().arg("inspect").arg(&demo).output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(
        text.contains("triangles") && text.contains("_SNOW_MASK"),
        "{text}"
    );

    let bad = dir.join("bad.glb");
    std::fs::write(&bad, b"glTF\x02\x00\x00\x00garbage").expect("write");
    let out = precip().arg("inspect").arg(&bad).output().expect("runs");
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.glb"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn without_a_display_the_viewer_says_so_and_renders_frames_headless() {
    if precip_gpu_wgpu::adapters().is_empty() {
        assert!(
            std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
            "PRECIP_REQUIRE_GPU=1 but no wgpu adapter found"
        );
        eprintln!("SKIPPED headless fallback: no wgpu adapter found");
        return;
    }
    let dir = temp_dir("fallback");
    let out = precip()
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .args([
            "--size",
            "64x36",
            "--particles",
            "2000",
            "--preset",
            "drizzle",
            "--out",
        ])
        .arg(&dir)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("no display"), "{err}");
    let frames = std::fs::read_dir(&dir).expect("frames").count();
    assert_eq!(frames, 60, "the default frame count");
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("p95") && summary.contains("particles"),
        "{summary}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
