//! The Vulkan backend's swapchain through a real window (winit under Xvfb): frames
//! follow the window through resizes, the old swapchains are retired and freed, and
//! the validation layer reports nothing, leaks at device destruction included.
//!
//! The window needs `DISPLAY`, which a test cannot set for its own process without
//! racing the other tests, so the test re-runs itself in a child process with the
//! Xvfb display set.

use std::process::Command;
use std::sync::Arc;

use precip_gpu_vk::{Presented, VkBackend};
use precip_model::{Backend, Setup, View};
use winit::event_loop::EventLoop;
use winit::platform::x11::EventLoopBuilderExtX11;

use crate::xvfb::Xvfb;

const CHILD: &str = "PRECIP_SWAPCHAIN_CHILD";

#[test]
fn the_vulkan_swapchain_follows_window_resizes_without_leaks() {
    if std::env::var_os(CHILD).is_some() {
        in_the_window();
        return;
    }
    if VkBackend::new(false).is_err() {
        assert!(
            std::env::var("PRECIP_REQUIRE_GPU").as_deref() != Ok("1"),
            "PRECIP_REQUIRE_GPU=1 but no Vulkan device"
        );
        eprintln!("SKIPPED swapchain: no Vulkan device");
        return;
    }
    let Some(x) = Xvfb::start() else {
        eprintln!("SKIPPED swapchain: Xvfb is not installed (apt-get install xvfb)");
        return;
    };
    let out = Command::new(std::env::current_exe().expect("the test binary"))
        .args([
            "--exact",
            "swapchain::the_vulkan_swapchain_follows_window_resizes_without_leaks",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .env("DISPLAY", &x.display)
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{text}\n{err}");
    assert!(text.contains("1 passed"), "{text}\n{err}");
}

/// In the child: a window, frames at three sizes, a drop, a clean log.
#[expect(
    deprecated,
    reason = "winit 0.30 creates windows outside an app handler only through the deprecated EventLoop::create_window"
)]
fn in_the_window() {
    let event_loop = EventLoop::builder()
        .with_any_thread(true)
        .build()
        .expect("an X11 event loop");
    let window = Arc::new(
        event_loop
            .create_window(
                winit::window::Window::default_attributes()
                    .with_inner_size(winit::dpi::PhysicalSize::new(160, 120)),
            )
            .expect("a window"),
    );
    let mut vk = VkBackend::for_display(true, &event_loop).expect("a Vulkan backend for X11");
    let log = vk.validation_log();
    vk.attach_window(window.clone()).expect("a surface");
    let setup = Setup::over_flat_ground(40.0, 32, 12.0, 2_000);
    vk.configure(&setup).expect("valid");
    let mut sizes = Vec::new();
    for (i, wanted) in [(160, 120), (160, 120), (240, 180), (240, 180), (96, 64)]
        .into_iter()
        .enumerate()
    {
        if i > 0 && sizes.last() != Some(&wanted) {
            let _ = window.request_inner_size(winit::dpi::PhysicalSize::new(wanted.0, wanted.1));
        }
        // The X server applies the new size asynchronously: present until the
        // surface reports it (a surface that imposes its size wins over the view's).
        let mut reached = false;
        for _ in 0..50 {
            vk.step(0.03).expect("valid step");
            let view = View {
                camera: setup.camera,
                width_px: wanted.0,
                height_px: wanted.1,
            };
            match vk.present(&view).expect("presents") {
                Presented::Frame {
                    width_px,
                    height_px,
                } if (width_px, height_px) == wanted => {
                    reached = true;
                    break;
                }
                _ => std::thread::sleep(std::time::Duration::from_millis(20)),
            }
        }
        assert!(reached, "no frame of {wanted:?} after a second");
        sizes.push(wanted);
    }
    assert!(vk.timings().is_ok());
    drop(vk);
    drop(window);
    let messages = log.lock().map(|m| m.clone()).unwrap_or_default();
    assert!(messages.is_empty(), "{}", messages.join("\n"));
}
