//! The interactive window (winit 0.30 + a wgpu surface): a fly camera over the scene,
//! keys to change the weather, and the frame time, particles and weather in the title.
//!
//! Keys: W/A/S/D and Q/E fly, arrows or the mouse (left button held) look, Shift flies
//! faster; 1 dry snow, 2 wet snow, 3 rain, 4 sleet; +/− intensity ×1.5; [ ] wind speed
//! −/+ 1 m/s; , . wind direction −/+ 15°; T/G cover time scale ×2 / ÷2; C culling;
//! Escape quits.

use std::collections::HashSet;
use std::sync::Arc;
use std::time::Instant;

use glam::Vec3;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::{Backend, BackendError, PrecipitationKind, Setup, View, Weather};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use crate::fly_camera::FlyCamera;

/// Why the window could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WindowError {
    /// No display to open a window on.
    #[error("no display available ({0}): run headless with --frames N --out DIR")]
    NoDisplay(String),
    /// The GPU side failed.
    #[error(transparent)]
    Backend(#[from] BackendError),
    /// The surface could not be made.
    #[error("the window's surface: {0}")]
    Surface(String),
}

/// Whether a display seems available (X11 or Wayland on Unix; always elsewhere).
#[must_use]
pub fn display_available() -> bool {
    if cfg!(unix) && !cfg!(target_os = "macos") {
        std::env::var_os("DISPLAY").is_some() || std::env::var_os("WAYLAND_DISPLAY").is_some()
    } else {
        true
    }
}

struct Running {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    backend: WgpuBackend,
    fly: FlyCamera,
    lens: precip_model::Camera,
    weather: Weather,
    time_scale: f32,
    keys: HashSet<KeyCode>,
    looking: bool,
    last_cursor: Option<(f64, f64)>,
    last_frame: Instant,
    frame_ms: f64,
    particles: u64,
}

struct App {
    setup: Setup,
    size: (u32, u32),
    running: Option<Running>,
    error: Option<WindowError>,
}

fn title(r: &Running) -> String {
    let w = &r.weather;
    let wind = w.wind.mean_wind_mps;
    format!(
        "precip — {:.1} ms/frame, {} particles — {:?} {:.1} mm/h, {:.1} °C, wind {:.1} m/s, cover ×{:.0}",
        r.frame_ms,
        r.particles,
        w.kind,
        w.intensity_mm_per_h,
        w.air_temperature_c,
        wind.length(),
        r.time_scale
    )
}

impl App {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<Running, WindowError> {
        let attributes = Window::default_attributes()
            .with_title("precip")
            .with_inner_size(winit::dpi::PhysicalSize::new(self.size.0, self.size.1));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| WindowError::NoDisplay(e.to_string()))?,
        );
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle(
            Box::new(event_loop.owned_display_handle()),
        ));
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| WindowError::Surface(e.to_string()))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .map_err(|e| precip_gpu_wgpu::conv::no_adapter(&e))?;
        let mut backend = WgpuBackend::on_adapter(&adapter)?;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| {
                WindowError::Surface("the adapter cannot present to this window".into())
            })?;
        let caps = surface.get_capabilities(&adapter);
        if let Some(srgb) = caps.formats.iter().find(|f| f.is_srgb()) {
            config.format = *srgb;
        }
        surface.configure(&backend.device().device, &config);
        backend.configure(&self.setup)?;
        let particles =
            u64::from(self.setup.particle_counts().0) + u64::from(self.setup.particle_counts().1);
        Ok(Running {
            fly: FlyCamera::from_camera(&self.setup.camera),
            lens: self.setup.camera,
            weather: self.setup.weather,
            time_scale: self.setup.cover.time_scale,
            window,
            surface,
            config,
            backend,
            keys: HashSet::new(),
            looking: false,
            last_cursor: None,
            last_frame: Instant::now(),
            frame_ms: 0.0,
            particles,
        })
    }
}

fn held(r: &Running, a: KeyCode, b: KeyCode) -> f32 {
    f32::from(u8::from(r.keys.contains(&a))) - f32::from(u8::from(r.keys.contains(&b)))
}

/// A weather key: returns the new weather, or `None` for other keys.
fn weather_key(key: KeyCode, w: &Weather) -> Option<Weather> {
    let mut w = *w;
    match key {
        KeyCode::Digit1 => {
            w.kind = PrecipitationKind::DrySnow;
            w.air_temperature_c = w.air_temperature_c.min(-2.0);
        }
        KeyCode::Digit2 => {
            w.kind = PrecipitationKind::WetSnow;
            w.air_temperature_c = 0.0;
        }
        KeyCode::Digit3 => {
            w.kind = PrecipitationKind::Rain;
            w.air_temperature_c = w.air_temperature_c.max(5.0);
        }
        KeyCode::Digit4 => {
            w.kind = PrecipitationKind::Sleet;
            w.air_temperature_c = 1.0;
        }
        KeyCode::Equal | KeyCode::NumpadAdd => {
            w.intensity_mm_per_h = (w.intensity_mm_per_h * 1.5).clamp(0.1, 100.0)
        }
        KeyCode::Minus | KeyCode::NumpadSubtract => {
            w.intensity_mm_per_h = (w.intensity_mm_per_h / 1.5).clamp(0.1, 100.0)
        }
        KeyCode::BracketLeft | KeyCode::BracketRight => {
            let v = w.wind.mean_wind_mps;
            let dir = if v.length() > 1e-3 {
                v.normalize()
            } else {
                Vec3::X
            };
            let step = if key == KeyCode::BracketRight {
                1.0
            } else {
                -1.0
            };
            w.wind.mean_wind_mps = dir * (v.length() + step).clamp(0.0, 40.0);
        }
        KeyCode::Comma | KeyCode::Period => {
            let angle = if key == KeyCode::Period { 15f32 } else { -15.0 }.to_radians();
            w.wind.mean_wind_mps = glam::Quat::from_rotation_y(angle) * w.wind.mean_wind_mps;
        }
        _ => return None,
    }
    Some(w)
}

impl Running {
    fn frame(&mut self) -> Result<(), WindowError> {
        let now = Instant::now();
        let dt = now
            .duration_since(self.last_frame)
            .as_secs_f32()
            .clamp(1e-4, 0.1);
        self.last_frame = now;
        self.frame_ms = 0.9 * self.frame_ms + 0.1 * f64::from(dt) * 1e3;
        let fast = if self.keys.contains(&KeyCode::ShiftLeft) {
            5.0
        } else {
            1.0
        };
        let turn = 1.2 * dt;
        self.fly.turn(
            turn * held(self, KeyCode::ArrowLeft, KeyCode::ArrowRight),
            turn * held(self, KeyCode::ArrowUp, KeyCode::ArrowDown),
        );
        self.fly.fly(
            dt * fast,
            held(self, KeyCode::KeyD, KeyCode::KeyA),
            held(self, KeyCode::KeyE, KeyCode::KeyQ),
            held(self, KeyCode::KeyW, KeyCode::KeyS),
        );
        let view = View {
            camera: self.fly.camera(&self.lens),
            width_px: self.config.width,
            height_px: self.config.height,
        };
        self.backend.set_camera(&view.camera)?;
        self.backend.step(dt)?;
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface
                    .configure(&self.backend.device().device, &self.config);
                return Ok(());
            }
            _ => return Ok(()),
        };
        let target = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        self.backend.render_to(&view, &target)?;
        self.backend.device().queue.present(frame);
        self.window.set_title(&title(self));
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.start(event_loop) {
            Ok(r) => {
                r.window.request_redraw();
                self.running = Some(r);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                r.config.width = size.width.max(1);
                r.config.height = size.height.max(1);
                r.surface.configure(&r.backend.device().device, &r.config);
            }
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(key) = event.physical_key else {
                    return;
                };
                if event.state == ElementState::Released {
                    r.keys.remove(&key);
                    return;
                }
                r.keys.insert(key);
                if event.repeat {
                    return;
                }
                if key == KeyCode::Escape {
                    event_loop.exit();
                } else if let Some(w) = weather_key(key, &r.weather) {
                    if r.backend.set_weather(&w).is_ok() {
                        r.weather = w;
                    }
                } else if matches!(key, KeyCode::KeyT | KeyCode::KeyG) {
                    let factor = if key == KeyCode::KeyT { 2.0 } else { 0.5 };
                    let mut setup = self.setup.clone();
                    setup.cover.time_scale = (r.time_scale * factor).clamp(1.0, 1.0e7);
                    setup.weather = r.weather;
                    setup.camera = r.fly.camera(&setup.camera);
                    // The time scale is part of the configuration: re-configure keeps
                    // the weather and camera (the cover restarts).
                    if r.backend.configure(&setup).is_ok() {
                        r.time_scale = setup.cover.time_scale;
                    }
                } else if key == KeyCode::KeyC {
                    let mut setup = self.setup.clone();
                    setup.render.view_cone_culling = !setup.render.view_cone_culling;
                    setup.weather = r.weather;
                    if r.backend.configure(&setup).is_ok() {
                        self.setup.render.view_cone_culling = setup.render.view_cone_culling;
                    }
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                r.looking = state == ElementState::Pressed;
                r.last_cursor = None;
            }
            WindowEvent::CursorMoved { position, .. } if r.looking => {
                if let Some((x, y)) = r.last_cursor {
                    r.fly.turn(
                        -(position.x - x) as f32 * 0.004,
                        -(position.y - y) as f32 * 0.004,
                    );
                }
                r.last_cursor = Some((position.x, position.y));
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = r.frame() {
                    self.error = Some(e);
                    event_loop.exit();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}

/// Opens a window of `size` over `setup` and runs until it is closed.
pub fn run_window(setup: Setup, size: (u32, u32)) -> Result<(), WindowError> {
    if !display_available() {
        return Err(WindowError::NoDisplay(
            "neither DISPLAY nor WAYLAND_DISPLAY is set".into(),
        ));
    }
    let event_loop = EventLoop::new().map_err(|e| WindowError::NoDisplay(e.to_string()))?;
    let mut app = App {
        setup,
        size,
        running: None,
        error: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| WindowError::NoDisplay(e.to_string()))?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}
