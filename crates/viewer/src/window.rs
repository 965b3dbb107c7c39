//! The interactive window (winit 0.30): a fly camera over the scene, keys to change
//! the weather, and the frame time, particles and weather in the title. Frames go to
//! the window through a wgpu surface or, with `--backend vk`, straight into a Vulkan
//! swapchain ([`precip_gpu_vk::VkBackend::present`]).
//!
//! Keys: W/A/S/D and Q/E fly, arrows or the mouse (left button held) look, Shift flies
//! faster; 1 dry snow, 2 wet snow, 3 rain, 4 sleet, 5 sand, 6 dust; +/− intensity ×1.5;
//! [ ] wind speed
//! −/+ 1 m/s; , . wind direction −/+ 15°; T/G cover time scale ×2 / ÷2; C culling;
//! Escape quits. Once a CIGI host places the view (Entity Control), it flies the
//! camera and the keys no longer move it.

use std::collections::HashSet;
use std::sync::Arc;
use std::time::Instant;

use glam::Vec3;
use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::WgpuBackend;
use precip_model::{
    Backend, BackendError, FrameRateControl, PrecipitationKind, Setup, View, Weather,
};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use crate::BackendName;
use crate::fly_camera::FlyCamera;
use crate::frame_stats::FrameStats;
use crate::snow_summary::SnowSummary;
use crate::water_summary::WaterSummary;

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

/// wgpu with the window's surface.
struct WgpuWindow {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    backend: WgpuBackend,
}

/// The GPU side of the window.
enum Presenter {
    /// wgpu with its surface.
    Wgpu(Box<WgpuWindow>),
    /// Vulkan with its swapchain (inside the backend).
    Vk(Box<VkBackend>),
}

impl Presenter {
    fn backend(&mut self) -> &mut dyn Backend {
        match self {
            Self::Wgpu(w) => &mut w.backend,
            Self::Vk(backend) => backend.as_mut(),
        }
    }

    /// Follows the window's new size (the Vulkan swapchain follows the view's size by
    /// itself).
    fn resize(&mut self, (width, height): (u32, u32)) {
        if let Self::Wgpu(w) = self {
            w.config.width = width;
            w.config.height = height;
            w.surface.configure(&w.backend.device().device, &w.config);
        }
    }

    /// Draws `view` into the window and presents it.
    fn present(&mut self, view: &View) -> Result<(), WindowError> {
        match self {
            Self::Wgpu(w) => {
                let WgpuWindow {
                    surface,
                    config,
                    backend,
                } = w.as_mut();
                let frame = match surface.get_current_texture() {
                    wgpu::CurrentSurfaceTexture::Success(f)
                    | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
                    wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                        surface.configure(&backend.device().device, config);
                        return Ok(());
                    }
                    _ => return Ok(()),
                };
                let target = frame
                    .texture
                    .create_view(&wgpu::TextureViewDescriptor::default());
                backend.render_to(view, &target)?;
                backend.device().queue.present(frame);
            }
            Self::Vk(backend) => {
                backend.present(view)?;
            }
        }
        Ok(())
    }
}

struct Running {
    window: Arc<Window>,
    presenter: Presenter,
    size: (u32, u32),
    fly: FlyCamera,
    lens: precip_model::Camera,
    /// The camera a CIGI host flies, once it placed the view (the keys and mouse
    /// then do not move it).
    host_camera: Option<precip_model::Camera>,
    weather: Weather,
    time_scale: f32,
    keys: HashSet<KeyCode>,
    looking: bool,
    last_cursor: Option<(f64, f64)>,
    last_frame: Instant,
    frame_ms: f64,
    /// Simulated seconds per real second, smoothed as `frame_ms` is.
    sim_rate: f64,
    /// Seconds simulated since the window opened.
    simulated_s: f64,
    particles: u64,
    frames: u32,
    started: Instant,
    stats: FrameStats,
    /// The heap's free pages returned after each move of the cover grid.
    trim: crate::heap::TrimAfterMoves,
    /// The water on the surfaces, sampled every [`WaterSummary::EVERY_FRAMES`].
    water: Option<WaterSummary>,
    /// The snow, sampled with the water.
    snow: Option<SnowSummary>,
    /// `--quality auto`: the frame-rate control over the particles' resolution and
    /// the shadow map's refresh.
    control: Option<FrameRateControl>,
}

struct App {
    setup: Setup,
    size: (u32, u32),
    backend: BackendName,
    quit_after: Option<u32>,
    running: Option<Running>,
    error: Option<WindowError>,
    /// Frames shown, seconds open, seconds simulated and their statistics, when the
    /// window closed.
    shown: Option<(u32, f64, f64, FrameStats)>,
    /// The Vulkan validation layer's log, when it runs.
    validation: Option<crate::backends::ValidationLog>,
    /// A CIGI host's messages, read before each frame.
    cigi: Option<precip_cigi::CigiReceiver>,
    /// An OpenSCENARIO timeline, played on the simulated clock.
    scenario: Option<crate::scenario::apply::ScenarioClock>,
    /// A flight the camera follows on the simulated clock.
    flight: Option<crate::flight::Flight>,
    /// `--quality auto`: the frame rate to hold.
    hold_fps: Option<f32>,
}

/// Simulated seconds a displayed frame may step: one sub-step
/// ([`precip_model::physics::drag::MAX_SUBSTEP_S`]), whatever the frame took.
const SIM_BUDGET_S: f32 = precip_model::physics::drag::MAX_SUBSTEP_S;

fn title(r: &Running) -> String {
    let w = &r.weather;
    let wind = w.wind.mean_wind_mps;
    let water = r
        .water
        .map(|s| format!(" — {}", s.describe()))
        .unwrap_or_default();
    let blowing = r
        .snow
        .filter(SnowSummary::blowing)
        .map(|s| format!(" — BLOWING SNOW over {:.0} m²", s.blowing_area_m2))
        .unwrap_or_default();
    let resolution = r
        .control
        .map(|c| {
            let l = c.level();
            format!(
                " (drawn at {:?} resolution, shadow kept {} frames)",
                l.particle_resolution, l.shadow_refresh_frames
            )
        })
        .unwrap_or_default();
    format!(
        "precip — {:.1} ms/frame, sim ×{:.2}, {} particles{resolution} — {:?} {:.1} mm/h, {:.1} °C, wind {:.1} m/s, cover ×{:.0}{blowing}{water}",
        r.frame_ms,
        r.sim_rate,
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
        let size = window.inner_size();
        let size = (size.width.max(1), size.height.max(1));
        let mut presenter = match self.backend {
            BackendName::Wgpu => wgpu_presenter(event_loop, &window, size)?,
            BackendName::Vk => {
                let mut backend =
                    VkBackend::for_display(crate::backends::vk_validation(), event_loop)?;
                backend.attach_window(window.clone())?;
                Presenter::Vk(Box::new(backend))
            }
        };
        presenter.backend().configure(&self.setup)?;
        let particles =
            u64::from(self.setup.particle_counts().0) + u64::from(self.setup.particle_counts().1);
        Ok(Running {
            fly: FlyCamera::from_camera(&self.setup.camera),
            lens: self.setup.camera,
            host_camera: None,
            weather: self.setup.weather,
            time_scale: self.setup.cover.time_scale,
            window,
            presenter,
            size,
            keys: HashSet::new(),
            looking: false,
            last_cursor: None,
            last_frame: Instant::now(),
            frame_ms: 0.0,
            sim_rate: 1.0,
            simulated_s: 0.0,
            particles,
            frames: 0,
            started: Instant::now(),
            stats: FrameStats::default(),
            trim: crate::heap::TrimAfterMoves::default(),
            water: None,
            snow: None,
            control: self
                .hold_fps
                .map(|fps| FrameRateControl::new(fps, self.setup.render.particle_resolution)),
        })
    }
}

/// A wgpu adapter that presents to `window`, its surface in an sRGB format.
fn wgpu_presenter(
    event_loop: &ActiveEventLoop,
    window: &Arc<Window>,
    (width, height): (u32, u32),
) -> Result<Presenter, WindowError> {
    let mut descriptor = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(
        event_loop.owned_display_handle(),
    ));
    descriptor.flags = precip_gpu_wgpu::device::instance_flags();
    let instance = wgpu::Instance::new(descriptor);
    let surface = instance
        .create_surface(window.clone())
        .map_err(|e| WindowError::Surface(e.to_string()))?;
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        compatible_surface: Some(&surface),
        ..Default::default()
    }))
    .map_err(|e| precip_gpu_wgpu::error::no_adapter(&e))?;
    let backend = WgpuBackend::on_adapter(&adapter)?;
    let mut config = surface
        .get_default_config(&adapter, width, height)
        .ok_or_else(|| WindowError::Surface("the adapter cannot present to this window".into()))?;
    let caps = surface.get_capabilities(&adapter);
    if let Some(srgb) = caps.formats.iter().find(|f| f.is_srgb()) {
        config.format = *srgb;
    }
    // Copied after the scene pass for the water's reflections, where it may be.
    if caps.usages.contains(wgpu::TextureUsages::COPY_SRC) {
        config.usage |= wgpu::TextureUsages::COPY_SRC;
    }
    surface.configure(&backend.device().device, &config);
    Ok(Presenter::Wgpu(Box::new(WgpuWindow {
        surface,
        config,
        backend,
    })))
}

fn held(r: &Running, a: KeyCode, b: KeyCode) -> f32 {
    f32::from(u8::from(r.keys.contains(&a))) - f32::from(u8::from(r.keys.contains(&b)))
}

/// The digit keys, 1 to 9.
const DIGITS: [KeyCode; 9] = [
    KeyCode::Digit1,
    KeyCode::Digit2,
    KeyCode::Digit3,
    KeyCode::Digit4,
    KeyCode::Digit5,
    KeyCode::Digit6,
    KeyCode::Digit7,
    KeyCode::Digit8,
    KeyCode::Digit9,
];

/// The kind digit key `n` picks: the `n`-th of [`PrecipitationKind::ALL`].
fn kind_key(key: KeyCode) -> Option<PrecipitationKind> {
    let n = DIGITS.iter().position(|d| *d == key)?;
    PrecipitationKind::ALL.get(n).copied()
}

#[cfg(test)]
mod kind_key_tests {
    use super::*;

    #[test]
    fn the_digits_pick_the_kinds_in_their_table_s_order() {
        assert_eq!(kind_key(KeyCode::Digit1), Some(PrecipitationKind::ALL[0]));
        for (n, kind) in PrecipitationKind::ALL.into_iter().enumerate() {
            let w = weather_key(
                DIGITS[n],
                &Weather {
                    air_temperature_c: 20.0,
                    ..Weather::default()
                },
            )
            .expect("a kind key");
            assert_eq!(w.kind, kind);
            // The temperature moves to where the kind falls: the weather is valid.
            w.validate().expect("valid");
        }
        assert_eq!(kind_key(DIGITS[PrecipitationKind::ALL.len()]), None);
    }
}

/// A weather key: returns the new weather, or `None` for other keys.
fn weather_key(key: KeyCode, w: &Weather) -> Option<Weather> {
    let mut w = *w;
    if let Some(kind) = kind_key(key) {
        w.kind = kind;
        w.grain = None;
        w.air_temperature_c = kind.usual_air_temperature_c(w.air_temperature_c);
        return Some(w);
    }
    match key {
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
        // The time since the last frame began: what a user waits per frame. The
        // camera flies with it (at most 0.1 s of it); the simulation steps at most
        // one sub-step of it (`SIM_BUDGET_S`): a slow frame slows the simulated clock
        // (shown in the title and the summary) instead of adding sub-steps that make
        // the next frame slower still.
        let elapsed_ms = now.duration_since(self.last_frame).as_secs_f64() * 1e3;
        let dt = (elapsed_ms * 1e-3).clamp(1e-4, 0.1) as f32;
        let sim_dt = dt.min(SIM_BUDGET_S);
        self.last_frame = now;
        self.frame_ms = 0.9 * self.frame_ms + 0.1 * elapsed_ms;
        self.sim_rate =
            0.9 * self.sim_rate + 0.1 * f64::from(sim_dt) / (elapsed_ms * 1e-3).max(1e-4);
        self.simulated_s += f64::from(sim_dt);
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
            camera: self
                .host_camera
                .unwrap_or_else(|| self.fly.camera(&self.lens)),
            width_px: self.size.0,
            height_px: self.size.1,
        };
        let backend = self.presenter.backend();
        backend.set_camera(&view.camera)?;
        backend.step(sim_dt)?;
        self.trim
            .after_step(backend.cover_window().map(|w| w.moves()));
        self.presenter.present(&view)?;
        self.stats.record(elapsed_ms, self.presenter.backend())?;
        if let Some(next) = self
            .control
            .as_mut()
            .and_then(|c| c.after_frame(self.frame_ms))
        {
            let backend = self.presenter.backend();
            backend.set_particle_resolution(next.particle_resolution)?;
            backend.set_shadow_refresh_frames(next.shadow_refresh_frames)?;
        }
        self.frames += 1;
        if self.frames.is_multiple_of(WaterSummary::EVERY_FRAMES) {
            let cover = self.presenter.backend().read_cover()?;
            self.water = Some(WaterSummary::of(&cover));
            self.snow = Some(SnowSummary::of(&cover));
        }
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
                r.size = (size.width.max(1), size.height.max(1));
                r.presenter.resize(r.size);
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
                    if r.presenter.backend().set_weather(&w).is_ok() {
                        r.weather = w;
                    }
                } else if matches!(key, KeyCode::KeyT | KeyCode::KeyG) {
                    let factor = if key == KeyCode::KeyT { 2.0 } else { 0.5 };
                    let mut setup = self.setup.clone();
                    setup.cover.time_scale = (r.time_scale * factor).clamp(
                        1.0,
                        crate::scene_setup::MOST_COVER_DAYS_PER_SECOND * 86_400.0,
                    );
                    setup.weather = r.weather;
                    setup.camera = r.fly.camera(&setup.camera);
                    // The time scale is part of the configuration: re-configure keeps
                    // the weather and camera (the cover restarts).
                    if r.presenter.backend().configure(&setup).is_ok() {
                        r.time_scale = setup.cover.time_scale;
                    }
                } else if key == KeyCode::KeyC {
                    let mut setup = self.setup.clone();
                    setup.render.view_cone_culling = !setup.render.view_cone_culling;
                    setup.weather = r.weather;
                    if r.presenter.backend().configure(&setup).is_ok() {
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
                if let Some(weather) = self.cigi.as_mut().and_then(precip_cigi::CigiReceiver::poll)
                    && r.presenter.backend().set_weather(&weather).is_ok()
                {
                    r.weather = weather;
                }
                if let Some(fog) = self
                    .cigi
                    .as_mut()
                    .and_then(precip_cigi::CigiReceiver::take_fog_layer)
                {
                    // A fog the host asks for that is not valid was refused already.
                    let _ = r.presenter.backend().set_fog_layer(fog);
                }
                if let Some(clouds) = self
                    .cigi
                    .as_mut()
                    .and_then(precip_cigi::CigiReceiver::take_cloud_layers)
                {
                    // Likewise: an invalid layer was refused when it arrived.
                    let _ = r.presenter.backend().set_cloud_layers(clouds);
                }
                if let Some(clock) = self.scenario.as_mut() {
                    match clock.advance(r.simulated_s, r.presenter.backend()) {
                        Ok(lines) => {
                            for line in lines {
                                eprintln!("{line}");
                            }
                            if let Ok(w) = r.presenter.backend().weather() {
                                r.weather = w;
                            }
                        }
                        Err(e) => {
                            self.error = Some(e.into());
                            event_loop.exit();
                        }
                    }
                }
                if let Some(flight) = &self.flight {
                    r.host_camera = Some(flight.camera_at(r.simulated_s, &r.lens));
                }
                if let Some(sun) = self
                    .cigi
                    .as_mut()
                    .and_then(precip_cigi::CigiReceiver::take_sun)
                {
                    // A valid direction: the receiver made it from a date and time.
                    let _ = r.presenter.backend().set_atmosphere(Some(sun), None);
                }
                let aspect = r.size.0 as f32 / r.size.1.max(1) as f32;
                if let Some(eye) = self.cigi.as_mut().and_then(|c| c.take_eyepoint(aspect)) {
                    r.host_camera = Some(crate::cigi_view::camera_at_eyepoint(
                        &eye,
                        &r.host_camera.unwrap_or(r.lens),
                    ));
                }
                if let Err(e) = r.frame() {
                    self.error = Some(e);
                    event_loop.exit();
                }
                if let Some(receiver) = self.cigi.as_mut() {
                    receiver.send_start_of_frame(r.frames, r.started.elapsed());
                }
                self.shown = Some((
                    r.frames,
                    r.started.elapsed().as_secs_f64(),
                    r.simulated_s,
                    r.stats.clone(),
                ));
                if self.quit_after.is_some_and(|n| r.frames >= n) {
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

/// How the window ran.
#[derive(Debug, Clone, PartialEq)]
pub struct WindowSummary {
    /// Frames presented.
    pub frames: u32,
    /// Seconds the window was open (from the first frame's setup).
    pub seconds: f64,
    /// Seconds simulated: at most one sub-step a frame, so fewer than `seconds` when
    /// frames take longer than a sub-step.
    pub simulated_s: f64,
    /// Frame times and particles drawn.
    pub stats: FrameStats,
    /// What the Vulkan validation layer said (with `PRECIP_VK_VALIDATION=1`), leak
    /// reports at the device's destruction included.
    pub validation_messages: Vec<String>,
}

/// What drives a window besides its keys.
#[derive(Debug, Default)]
pub struct WindowDrivers {
    /// A CIGI host: its weather and eyepoint take effect at the next frame.
    pub cigi: Option<precip_cigi::CigiReceiver>,
    /// An OpenSCENARIO timeline, played on the simulated clock.
    pub scenario: Option<crate::scenario::apply::ScenarioClock>,
    /// A flight the camera follows on the simulated clock.
    pub flight: Option<crate::flight::Flight>,
}

/// Opens a window of `size` over `setup`, drawing with `backend`, and runs until it
/// is closed (or, with `quit_after`, after that many frames), driven by `drivers`;
/// with `hold_fps`, the particles' resolution and the shadow map's refresh follow
/// the frame rate ([`FrameRateControl`]).
pub fn run_window(
    setup: Setup,
    size: (u32, u32),
    backend: BackendName,
    quit_after: Option<u32>,
    drivers: WindowDrivers,
    hold_fps: Option<f32>,
) -> Result<WindowSummary, WindowError> {
    let WindowDrivers {
        cigi,
        scenario,
        flight,
    } = drivers;
    if !display_available() {
        return Err(WindowError::NoDisplay(
            "neither DISPLAY nor WAYLAND_DISPLAY is set".into(),
        ));
    }
    let event_loop = EventLoop::new().map_err(|e| WindowError::NoDisplay(e.to_string()))?;
    let mut app = App {
        setup,
        size,
        backend,
        quit_after,
        running: None,
        error: None,
        shown: None,
        validation: None,
        cigi,
        scenario,
        flight,
        hold_fps,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| WindowError::NoDisplay(e.to_string()))?;
    // Drop the GPU objects before the event loop's display goes.
    app.running = None;
    match app.error {
        Some(e) => Err(e),
        None => {
            let (frames, seconds, simulated_s, stats) = app.shown.unwrap_or_default();
            let validation_messages = app
                .validation
                .and_then(|log| log.lock().map(|m| m.clone()).ok())
                .unwrap_or_default();
            Ok(WindowSummary {
                frames,
                seconds,
                simulated_s,
                stats,
                validation_messages,
            })
        }
    }
}
