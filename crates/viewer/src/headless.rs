//! Headless frames: step, render, write `frame_NNNN.png` (encoded beside the loop,
//! [`crate::png_writer`]), with a progress bar, and a
//! summary (frame times, particles simulated and drawn, cover water, the water on
//! the surfaces, the snow); at the end the snow's depth map, `snow_depth_mm.png`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use precip_model::{Backend, View};

use crate::frame_stats::FrameStats;
use crate::png_writer::PngWriter;

/// How a headless run went.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Frames written.
    pub frames: u32,
    /// Mean wall time of a frame (step + render + read-back; the PNG only where its
    /// encoding falls behind, [`crate::png_writer`]), ms.
    pub mean_frame_ms: f64,
    /// 95th percentile, ms.
    pub p95_frame_ms: f64,
    /// Render-loop statistics: frame time after the warm-up (step + render +
    /// read-back, as [`Summary::mean_frame_ms`]) and particles drawn.
    pub stats: FrameStats,
    /// Particles simulated.
    pub particles: u64,
    /// Water in the snow cover (snow water equivalent + held water), mean mm.
    pub cover_water_mm: f64,
    /// Largest snow depth on any texel, mm.
    pub max_depth_mm: f32,
    /// The water on the surfaces: films, puddles, where the water went.
    pub water: crate::water_summary::WaterSummary,
    /// The books of the cover beyond the grid, over the terrain's land off it
    /// (`None` without a terrain).
    pub far_cover: Option<precip_model::cover::CoverTotals>,
    /// The snow line beyond the grid, m (`None` without a terrain or where no
    /// place holds snow).
    pub far_snow_line_m: Option<f32>,
    /// Where the cover grid ended, as it followed the camera over a terrain.
    pub cover_window: Option<precip_model::host::CoverWindow>,
    /// The snow: depths, the steepest face, blowing snow.
    pub snow: crate::snow_summary::SnowSummary,
    /// The PNGs.
    pub files: Vec<PathBuf>,
    /// With a LiDAR: the points its scans held in all, and how many of them were
    /// echoes from particles.
    pub lidar_points: Option<(u64, u64)>,
    /// The camera of the last frame (a CIGI host may have flown it).
    pub last_camera: precip_model::Camera,
    /// Lockstep: frames drawn without a new host frame (the wait timed out).
    pub host_frames_missed: u32,
    /// The scenario's changes as applied, one line each.
    pub scenario_log: Vec<String>,
}

/// What a headless run does besides drawing.
#[derive(Debug, Default)]
pub struct HeadlessExtras<'a> {
    /// Take the weather and the eyepoint from this CIGI host (read before each
    /// frame; a change takes effect in it) and answer it with Start of Frame after
    /// each frame.
    pub cigi: Option<&'a mut precip_cigi::CigiReceiver>,
    /// A flight: the camera where it is at each frame's simulated time (a CIGI
    /// host's eyepoint, once placed, wins).
    pub flight: Option<crate::flight::Flight>,
    /// An OpenSCENARIO timeline: each change applied when the simulated clock
    /// (frames × `dt_s`) reaches it.
    pub scenario: Option<crate::scenario::apply::ScenarioClock>,
    /// With `cigi`: lockstep with a host running synchronously — each frame waits
    /// for the host's next frame (at most [`LOCKSTEP_TIMEOUT`]), so N host frames
    /// draw N frames.
    pub lockstep: bool,
    /// Scan with this LiDAR after each frame, writing `scan_NNNN.ply` beside the
    /// frame's PNG ([`crate::lidar_scan`]).
    pub lidar: Option<crate::lidar_scan::SpinningLidar>,
}

/// How long a lockstep frame waits for the host's next frame before it draws
/// without one (counted in [`Summary::host_frames_missed`]).
pub const LOCKSTEP_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(5);

/// Something that stopped a headless run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HeadlessError {
    /// The backend refused.
    #[error(transparent)]
    Backend(#[from] precip_model::BackendError),
    /// A PNG could not be written.
    #[error("{file}: {detail}")]
    Write {
        /// The file.
        file: PathBuf,
        /// Why.
        detail: String,
    },
}

/// Runs `frames` frames of `dt_s` each on a configured `backend` for `view`, writing
/// PNGs into `out` (created if missing). `progress` shows a bar on the terminal.
pub fn run_headless(
    backend: &mut dyn Backend,
    view: &View,
    frames: u32,
    dt_s: f32,
    out: &Path,
    progress: bool,
) -> Result<Summary, HeadlessError> {
    run_headless_with(
        backend,
        view,
        frames,
        dt_s,
        out,
        progress,
        HeadlessExtras::default(),
    )
}

/// [`run_headless`] with `extras`: the weather from a CIGI host (the backend keeps
/// running: no re-configure), a LiDAR's scans.
pub fn run_headless_with(
    backend: &mut dyn Backend,
    view: &View,
    frames: u32,
    dt_s: f32,
    out: &Path,
    progress: bool,
    extras: HeadlessExtras<'_>,
) -> Result<Summary, HeadlessError> {
    let HeadlessExtras {
        mut cigi,
        lidar,
        lockstep,
        mut scenario,
        flight,
    } = extras;
    let mut scenario_log = Vec::new();
    let mut view = *view;
    let mut host_frames_missed = 0;
    let mut lidar_points = lidar.map(|_| (0u64, 0u64));
    std::fs::create_dir_all(out).map_err(|e| HeadlessError::Write {
        file: out.to_path_buf(),
        detail: e.to_string(),
    })?;
    let bar = if progress {
        indicatif::ProgressBar::new(u64::from(frames))
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} frames, {per_sec}, eta {eta}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let mut times = Vec::with_capacity(frames as usize);
    let mut stats = FrameStats::default();
    let mut files = Vec::with_capacity(frames as usize);
    let mut pngs = PngWriter::for_this_machine();
    let run_started = Instant::now();
    let mut trim = crate::heap::TrimAfterMoves::default();
    for frame in 0..frames {
        let start = Instant::now();
        if lockstep
            && let Some(receiver) = cigi.as_deref_mut()
            && !receiver.wait_for_host_frame(LOCKSTEP_TIMEOUT)
        {
            host_frames_missed += 1;
        }
        if let Some(weather) = cigi
            .as_deref_mut()
            .and_then(precip_cigi::CigiReceiver::poll)
        {
            backend.set_weather(&weather)?;
        }
        if let Some(fog) = cigi
            .as_deref_mut()
            .and_then(precip_cigi::CigiReceiver::take_fog_layer)
        {
            backend.set_fog_layer(fog)?;
        }
        if let Some(clouds) = cigi
            .as_deref_mut()
            .and_then(precip_cigi::CigiReceiver::take_cloud_layers)
        {
            backend.set_cloud_layers(clouds)?;
        }
        if let Some(clock) = scenario.as_mut() {
            scenario_log.extend(clock.advance(f64::from(frame) * f64::from(dt_s), backend)?);
        }
        if let Some(flight) = &flight {
            view.camera = flight.camera_at(f64::from(frame) * f64::from(dt_s), &view.camera);
        }
        if let Some(sun) = cigi
            .as_deref_mut()
            .and_then(precip_cigi::CigiReceiver::take_sun)
        {
            backend.set_atmosphere(Some(sun), None)?;
        }
        let aspect = view.width_px as f32 / view.height_px.max(1) as f32;
        if let Some(eye) = cigi.as_deref_mut().and_then(|r| r.take_eyepoint(aspect)) {
            view.camera = crate::cigi_view::camera_at_eyepoint(&eye, &view.camera);
        }
        backend.set_camera(&view.camera)?;

        backend.step(dt_s)?;
        trim.after_step(backend.cover_window().map(|w| w.moves()));
        backend.render(&view)?;
        let image = backend.read_image()?;
        let file = out.join(format!("frame_{frame:04}.png"));
        pngs.write(file.clone(), image)?;
        files.push(file);
        if let (Some(lidar), Some(totals)) = (&lidar, lidar_points.as_mut()) {
            let (points, echoes) = scan(backend, lidar, &out.join(format!("scan_{frame:04}.ply")))?;
            totals.0 += points;
            totals.1 += echoes;
        }
        if let Some(receiver) = cigi.as_deref_mut() {
            receiver.send_start_of_frame(frame, run_started.elapsed());
        }
        let ms = start.elapsed().as_secs_f64() * 1e3;
        stats.record(ms, backend)?;
        times.push(ms);
        bar.inc(1);
    }
    bar.finish_and_clear();
    pngs.finish()?;
    let particles = backend.read_particles()?.len() as u64;
    let cover = backend.read_cover()?;
    let texels = cover.texels.len().max(1) as f64;
    let water: f64 = cover
        .texels
        .iter()
        .map(|t| f64::from(t.swe_mm + t.liquid_mm))
        .sum::<f64>()
        / texels;
    let max_depth_mm = cover.texels.iter().map(|t| t.depth_mm).fold(0.0, f32::max);
    let map_file = out.join("snow_depth_mm.png");
    crate::snow_summary::snow_depth_map_mm(&cover)
        .save(&map_file)
        .map_err(|e| HeadlessError::Write {
            file: map_file.clone(),
            detail: e.to_string(),
        })?;
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let p95 = sorted
        .get(((sorted.len() as f64 * 0.95).ceil() as usize).saturating_sub(1))
        .copied()
        .unwrap_or(0.0);
    Ok(Summary {
        frames,
        mean_frame_ms: times.iter().sum::<f64>() / times.len().max(1) as f64,
        p95_frame_ms: p95,
        stats,
        particles,
        cover_water_mm: water,
        max_depth_mm,
        water: crate::water_summary::WaterSummary::of(&cover),
        far_cover: backend.far_cover_totals(),
        far_snow_line_m: backend.far_snow_line_m(),
        cover_window: backend.cover_window(),
        snow: crate::snow_summary::SnowSummary::of(&cover),
        files,
        lidar_points,
        last_camera: view.camera,
        host_frames_missed,
        scenario_log,
    })
}

/// One scan of `lidar` into `file`: (points, echoes from particles).
fn scan(
    backend: &mut dyn Backend,
    lidar: &crate::lidar_scan::SpinningLidar,
    file: &Path,
) -> Result<(u64, u64), HeadlessError> {
    let query = precip_model::sensors::lidar::BeamQuery {
        beams: lidar.beams(),
        band: precip_model::sensors::optics::Band::NearInfrared,
        aperture_radius_m: crate::lidar_scan::APERTURE_RADIUS_M,
        extinction_per_m: None,
        sample_unresolved: true,
    };
    let returns = backend.query_beams(&query)?;
    let wind = backend.weather()?.wind.mean_wind_mps;
    let points = crate::lidar_scan::point_cloud(
        &query.beams,
        &returns,
        query.band,
        lidar.detection_threshold(),
        wind.x.hypot(wind.z),
    );
    crate::lidar_scan::write_ply(file, &points).map_err(|e| HeadlessError::Write {
        file: file.to_path_buf(),
        detail: e.to_string(),
    })?;
    let echoes = points.iter().filter(|p| p.from_particle).count();
    Ok((points.len() as u64, echoes as u64))
}
