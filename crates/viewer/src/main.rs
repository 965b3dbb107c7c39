//! `precip`: the viewer's command line. `cargo run --release` shows snow falling and
//! settling on the built-in demo scene; `precip SCENE.glb` views your own glTF.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context as _;
use clap::{Parser, Subcommand};
use glam::Vec3;
use precip_model::{Camera, PrecipitationKind, View};
use precip_viewer::backends::{BackendName, open_headless};
use precip_viewer::coast::{BEACH_VIEW, coast_glb};
use precip_viewer::demo::{DEMO_GLB, demo_glb};
use precip_viewer::headless::run_headless_with;
use precip_viewer::presets::{Preset, kind_name};
use precip_viewer::scene_setup::{SceneOptions, scene_setup};
use precip_viewer::window::{WindowError, display_available, run_window};
use precip_viewer::{LoadedScene, load_scene, load_scene_from_slice};

/// Frames a headless fallback writes when no display is available.
const FALLBACK_FRAMES: u32 = 60;

#[derive(Parser, Debug)]
#[command(
    name = "precip",
    version,
    about = "Real-time snow and rain over any glTF scene"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    run: RunArgs,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Load a scene without a GPU and print its summary.
    Inspect {
        /// A .gltf or .glb file.
        file: PathBuf,
    },
    /// Print the optics of a weather: extinction and backscatter at 550, 905 and
    /// 1550 nm and the meteorological optical range, from its size spectra and from
    /// the particles the CPU reference simulates for it.
    Optics {
        #[command(flatten)]
        weather: WeatherArgs,
    },
    /// Write the built-in demo scene as a .glb.
    Demo {
        /// Where to write it (default: crates/viewer/assets/demo.glb, or coast.glb
        /// with --coast).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The coastal scene instead.
        #[arg(long)]
        coast: bool,
    },
}

/// The weather, from a preset and the options that override it.
#[derive(clap::Args, Debug)]
struct WeatherArgs {
    /// A weather preset: a TOML file or a shipped name (a file of presets/:
    /// light-snow, blizzard, downpour, sleet, sandstorm, thunderstorm, gale, …; an
    /// unknown name lists them all); the options below override it.
    #[arg(long)]
    preset: Option<String>,
    /// Kind of precipitation.
    #[arg(long, value_parser = kind_name::parser())]
    kind: Option<PrecipitationKind>,
    /// Intensity as water, mm/h.
    #[arg(long)]
    intensity: Option<f32>,
    /// Air temperature, °C.
    #[arg(long, allow_negative_numbers = true)]
    temperature: Option<f32>,
    /// Mean wind speed, m/s.
    #[arg(long)]
    wind: Option<f32>,
    /// Where the wind blows from, degrees clockwise from north (−Z).
    #[arg(long, allow_negative_numbers = true)]
    wind_from: Option<f32>,
    /// Gust factor μ.
    #[arg(long)]
    gust: Option<f32>,
    /// A fog layer up to this height, m (valley or ground fog, lit by the sky and
    /// the sun; docs/model.md (6.5)).
    #[arg(long, allow_negative_numbers = true)]
    fog_top: Option<f32>,
    /// The visibility inside the fog layer, m (200 when only --fog-top is given).
    #[arg(long)]
    fog_visibility: Option<f32>,
    /// A layer of volumetric clouds of this type (docs/model.md (6.9)).
    #[arg(long, value_enum)]
    cloud_type: Option<precip_viewer::presets::CloudTypeName>,
    /// The share of the sky the cloud layer covers, 0–1 (oktas / 8; 0.6 when only
    /// --cloud-type is given; alone, the deck the weather falls from).
    #[arg(long)]
    cloud_cover: Option<f32>,
    /// The cloud layer's base, m (the type's typical base).
    #[arg(long, allow_negative_numbers = true)]
    cloud_base: Option<f32>,
    /// The cloud layer's thickness, m (the type's typical thickness).
    #[arg(long)]
    cloud_thickness: Option<f32>,
    /// The band below and above the cloud layer over which the air thickens toward
    /// it, m (CIGI's transition band; 0, a sharp edge, by default).
    #[arg(long)]
    cloud_transition_band: Option<f32>,
    /// The rate falling beyond the camera's 3 km, averaged over the land, mm/h:
    /// shafts of rain or snow under the lowest cloud layer's clouds, seen from afar,
    /// and landing there on a terrain's cells (the weather's own rate by default;
    /// docs/model.md (6.16), (4.16)).
    #[arg(long)]
    rate_beyond: Option<f32>,
    /// Another cloud layer, `TYPE[:COVER[:BASE_M[:THICKNESS_M]]]` (e.g.
    /// stratus:0.9:4000:400); repeat for a third. Added to the preset's; at most
    /// three layers in all, none reaching into another (docs/model.md (6.15)).
    #[arg(long, value_name = "TYPE[:COVER[:BASE_M[:THICKNESS_M]]]")]
    more_clouds: Vec<precip_viewer::presets::MoreClouds>,
}

#[derive(clap::Args, Debug)]
struct RunArgs {
    /// The scene (.gltf or .glb); the built-in demo when absent.
    scene: Option<PathBuf>,
    /// The built-in coastal scene (the open sea, a beach, a breakwater, a pier)
    /// instead of the demo; its view from the beach unless --camera is given.
    #[arg(long, conflicts_with = "scene")]
    coast: bool,
    /// The distance the wind has blown over open water to the scene, km (how high
    /// a wind raises the sea: 10 a bay, 100 and more the open ocean).
    #[arg(long, default_value_t = 100.0)]
    sea_fetch_km: f32,
    /// The sea's spectrum: JONSWAP over the fetch, or Phillips (a fully developed
    /// sea, as Tessendorf's).
    #[arg(long, value_enum, default_value_t = SeaSpectrumName::Jonswap)]
    sea_spectrum: SeaSpectrumName,
    /// The GPU backend: wgpu, or vk (precip's own Vulkan backend; with
    /// PRECIP_VK_VALIDATION=1 it runs under the Khronos validation layer).
    #[arg(long, value_enum, default_value_t = BackendName::Wgpu)]
    backend: BackendName,
    #[command(flatten)]
    weather: WeatherArgs,
    /// Particles in all (at least 1).
    #[arg(long, default_value_t = 300_000, value_parser = clap::value_parser!(u32).range(1..))]
    particles: u32,
    /// Seed of every random draw.
    #[arg(long, default_value_t = 1)]
    seed: u32,
    /// Simulated cover days per real second (0.05 ≈ 1 h 12 min per second), 0 to 2.
    #[arg(long, default_value_t = 0.05, value_parser = parse_time_scale)]
    time_scale: f32,
    /// Ground and cover texel size, m.
    #[arg(long, default_value_t = 0.5)]
    texel: f32,
    /// The ground map's and cover grid's side, m (default: the scene's size; at
    /// most 1024 texels). Over a terrain the grid follows the camera, the cover
    /// beyond it kept per place.
    #[arg(long, value_parser = parse_grid_side)]
    grid_side: Option<f32>,
    /// Window or image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    size: (u32, u32),
    /// Camera position x,y,z (m); with --look-at.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    camera: Option<Vec3>,
    /// Point the camera looks at x,y,z (m).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    look_at: Option<Vec3>,
    /// The camera's exposure (shutter) time, s: rain and snow are drawn over their
    /// motion during it (0: frozen).
    #[arg(long, default_value_t = 1.0 / 60.0)]
    shutter: f32,
    /// The lens's f-number: near flakes out of focus blur (`inf`: a pinhole).
    #[arg(long, default_value_t = 4.0)]
    f_number: f32,
    /// Distance in focus, m.
    #[arg(long, default_value_t = 10.0)]
    focus: f32,
    /// Which water mirrors the scene (not only the sky), over what --quality says
    /// (auto, except at low: the water bodies): all of it on a GPU and the water
    /// bodies only on a CPU rasteriser such as lavapipe (auto), the water bodies
    /// only, or every puddle too.
    #[arg(long, value_enum)]
    mirrors: Option<MirrorsName>,
    /// How much the look may cost: high draws everything at the frame's resolution;
    /// medium draws rain and snow at half of it; low at a quarter, with a smaller
    /// shadow map kept up to 4 frames when stale and only the water bodies
    /// mirroring the scene; auto, in a window, holds --target-fps by the particles'
    /// resolution and the shadow map's refresh (headless: as high). The same
    /// weather, density and light at every level.
    #[arg(long, value_enum, default_value_t = QualityName::High)]
    quality: QualityName,
    /// The frame rate `--quality auto` holds in a window.
    #[arg(long, default_value_t = 30.0)]
    target_fps: f32,
    /// The resolution rain and snow are drawn at, against the frame's (the scene is
    /// always drawn at the frame's), over what --quality says: half or a quarter of
    /// its side; what is smaller than a sprite there is splatted at the frame's.
    #[arg(long, value_enum)]
    particle_resolution: Option<ParticleResolutionName>,
    /// Headless: render this many frames into --out instead of opening a window.
    #[arg(long)]
    frames: Option<u32>,
    /// Headless: where the PNGs go.
    #[arg(long, default_value = "precip-frames")]
    out: PathBuf,
    /// Window: close after this many frames and print the frame rate (demos, tests).
    #[arg(long)]
    quit_after: Option<u32>,
    /// Seconds of simulation per headless frame.
    #[arg(long, default_value_t = 1.0 / 30.0)]
    dt: f32,
    /// Take the weather and the eyepoint from a CIGI 3.3 host on this UDP port (IG
    /// Control, global Weather Control, Entity Control, View Control, View
    /// Definition; applied at the next frame).
    #[arg(long)]
    cigi: Option<u16>,
    /// Where the scene's origin lies on the Earth for a CIGI host's geodetic
    /// positions: `LAT,LON[,ALT]` (degrees, degrees, m above the WGS 84 ellipsoid;
    /// the scene's y = 0 at ALT). The scene is the tangent plane there.
    #[arg(long, value_parser = precip_viewer::cigi_view::parse_origin, allow_negative_numbers = true)]
    origin: Option<precip_cigi::GeodeticOrigin>,
    /// Fly the camera along waypoints: a file of `t_s x_m y_m z_m heading_deg
    /// pitch_deg [roll_deg]` lines, or `orbit` (once around the demo house in 24 s), or `valley` (up the valley of `--terrain generated` at 70 m/s, 250 m up);
    /// on the simulated clock, headless and in the window.
    #[arg(long, value_parser = precip_viewer::flight::Flight::load)]
    flight: Option<precip_viewer::flight::Flight>,
    /// The CIGI view this IG draws (View Control and View Definition of this view;
    /// the ownship's eyepoint before any).
    #[arg(long, default_value_t = 0)]
    cigi_view: u16,
    /// Headless: run in lockstep with a CIGI host running synchronously — each
    /// frame waits (up to 5 s) for the host's next frame.
    #[arg(long)]
    cigi_lockstep: bool,
    /// Take the weather (precipitation, temperature, wind, fog) from the
    /// Environment/Weather of an OpenSCENARIO 1.x file instead of a preset.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// Display rig: this channel looks this many degrees right of the camera (the
    /// rig's forward); channels of one rig show the same precipitation from the seed
    /// and the clock alone.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    channel_yaw: f32,
    /// Display rig: this channel looks this many degrees above the camera's forward.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    channel_pitch: f32,
    /// Tiled display rig: this channel shows its window of the rig's image plane, the
    /// image's centre moved X half-widths right and Y half-heights up (e.g. two
    /// channels at -0.5,0 and 0.5,0 overlap by half and span a view 1.5 times as
    /// wide); overlapping windows draw the same pixels.
    #[arg(long, value_parser = parse_vec2, allow_hyphen_values = true)]
    channel_shift: Option<glam::Vec2>,
    /// Headless: scan with a 32-channel spinning LiDAR at the camera after each frame
    /// (905 nm, 3 mrad, 120 m) and write `scan_NNNN.ply` beside the frame: the
    /// stronger echo of each beam, from the ground or a particle.
    #[arg(long)]
    lidar: bool,
    /// Stand the scene on a terrain: a height map (16- or 8-bit greyscale .png, or
    /// a GeoTIFF .tif), or `generated` (10 km of valleys and ridges with the town's
    /// flat ground at the origin). Centred on the origin, its height there 0 m.
    #[arg(long, value_parser = |s: &str| Ok::<_, String>(precip_viewer::terrain_file::TerrainSource::parse(s)))]
    terrain: Option<precip_viewer::terrain_file::TerrainSource>,
    /// Metres between the height map's samples (default: a GeoTIFF's pixel
    /// scale, else 1 m; 2.5 m for `generated`).
    #[arg(long, requires = "terrain", allow_negative_numbers = true)]
    terrain_spacing: Option<f32>,
    /// The heights of the smallest and largest integer sample, m: `LOW,HIGH`
    /// (default for a PNG 0,1000; a GeoTIFF's samples are metres unless given).
    #[arg(long, requires = "terrain", value_parser = parse_heights, allow_hyphen_values = true)]
    terrain_heights: Option<glam::Vec2>,
    /// The terrain's land cover: an 8-bit greyscale .png or a GeoTIFF of ESA
    /// WorldCover codes (10 trees, 20 shrubs, 30 grass, 40 crops, 50 built-up, 60
    /// bare, 70 snow and ice, 80 water, 90 wetland, 95 mangroves, 100 moss; 0 no
    /// data) over the terrain's extent at any resolution: each class its colour,
    /// its surface (paved towns, open water) and how much of its snow shows from
    /// above (half under forest). `--terrain generated` has its own.
    #[arg(long, requires = "terrain")]
    land_cover: Option<PathBuf>,
}

/// One line on a land cover: its pixels and the share of each class it holds.
fn land_cover_summary(land_cover: &precip_model::scene::LandCover) -> String {
    let counts = land_cover.class_counts();
    let total = counts.iter().sum::<usize>().max(1) as f64;
    let shares: Vec<String> = precip_model::scene::LandClass::ALL
        .iter()
        .zip(counts)
        .filter(|(_, n)| *n > 0)
        .map(|(c, n)| format!("{c:?} {:.1} %", 100.0 * n as f64 / total))
        .collect();
    let p = land_cover.pixels();
    format!(
        "land cover: {} × {} pixels: {}",
        p.x,
        p.y,
        shares.join(", ")
    )
}

/// A rig channel's forward: `forward` turned `yaw_deg` to the right about the
/// vertical, then `pitch_deg` up about its right-hand axis.
fn channel_forward(forward: Vec3, yaw_deg: f32, pitch_deg: f32) -> Vec3 {
    let turned = glam::Quat::from_rotation_y(-yaw_deg.to_radians()) * forward;
    let right = turned.cross(Vec3::Y).normalize_or_zero();
    if right == Vec3::ZERO {
        return turned;
    }
    glam::Quat::from_axis_angle(right, pitch_deg.to_radians()) * turned
}

/// Cover days per real second: 0 (the cover still) to
/// [`precip_viewer::scene_setup::MOST_COVER_DAYS_PER_SECOND`].
fn parse_time_scale(s: &str) -> Result<f32, String> {
    let v: f32 = s
        .parse()
        .map_err(|_| format!("`{s}` is not a number of days per second"))?;
    if v.is_finite() && (0.0..=MOST_DAYS_PER_SECOND).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "{s} days per second is outside 0 to {MOST_DAYS_PER_SECOND}: faster, a frame's step of the cover (melt, drift, flow) runs for hours and stops being physical"
        ))
    }
}

const MOST_DAYS_PER_SECOND: f32 = precip_viewer::scene_setup::MOST_COVER_DAYS_PER_SECOND;

fn parse_grid_side(s: &str) -> Result<f32, String> {
    let v: f32 = s
        .parse()
        .map_err(|_| format!("`{s}` is not a side in metres"))?;
    if v.is_finite() && (1.0..=100_000.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "a grid side of {s} m is outside 1 to 100000 m (the grid holds at most 1024 texels a side: raise --texel for a larger one)"
        ))
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or("expected WIDTHxHEIGHT, e.g. 1280x720")?;
    let w: u32 = w.trim().parse().map_err(|e| format!("width: {e}"))?;
    let h: u32 = h.trim().parse().map_err(|e| format!("height: {e}"))?;
    if w == 0 || h == 0 || w > 16_384 || h > 16_384 {
        return Err("each side must be 1 to 16384 pixels".into());
    }
    Ok((w, h))
}

fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let parts: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|e| format!("{p}: {e}")))
        .collect::<Result<_, _>>()?;
    match parts[..] {
        [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok(Vec3::new(x, y, z)),
        _ => Err("expected x,y,z".into()),
    }
}

/// Comma-separated numbers.
fn parse_numbers(s: &str) -> Result<Vec<f32>, String> {
    s.split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|e| format!("{p}: {e}")))
        .collect()
}

fn parse_vec2(s: &str) -> Result<glam::Vec2, String> {
    let parts = parse_numbers(s)?;
    match parts[..] {
        [x, y] if x.abs() <= 4.0 && y.abs() <= 4.0 => Ok(glam::Vec2::new(x, y)),
        _ => Err("expected x,y, each within ±4 (half-widths, half-heights)".into()),
    }
}

/// `LOW,HIGH` metres (checked when the terrain is read: low below high).
fn parse_heights(s: &str) -> Result<glam::Vec2, String> {
    let parts = parse_numbers(s)?;
    match parts[..] {
        [low, high] => Ok(glam::Vec2::new(low, high)),
        _ => Err("expected LOW,HIGH in metres".into()),
    }
}

fn inspect(file: &std::path::Path) -> anyhow::Result<()> {
    let LoadedScene { scene, report } = load_scene(file)?;
    let (lo, hi) = scene.bounds_m().unwrap_or_default();
    let vertices: usize = scene.meshes.iter().map(|m| m.positions_m.len()).sum();
    let eligibility: Vec<f32> = scene
        .meshes
        .iter()
        .flat_map(|m| m.snow_eligibility.iter().copied())
        .collect();
    let none = eligibility.iter().filter(|e| **e <= 0.0).count();
    let full = eligibility.iter().filter(|e| **e >= 1.0).count();
    let mean =
        eligibility.iter().map(|e| f64::from(*e)).sum::<f64>() / eligibility.len().max(1) as f64;
    println!("{}", file.display());
    println!(
        "  meshes: {} ({} primitives read)",
        scene.meshes.len(),
        report.primitives
    );
    println!(
        "  triangles: {}, vertices: {vertices}",
        report.scene.triangles
    );
    println!("  bounds: {lo:.2} .. {hi:.2} m (size {:.2})", hi - lo);
    println!(
        "  snow eligibility: mean {mean:.2}; {full} vertices full, {none} none; from _SNOW_MASK: {} primitives, from extras: {}, from slope: {} meshes",
        report.snow_mask_attribute, report.snow_extras, report.scene.slope_eligibility
    );
    println!(
        "  dropped: {} degenerate triangles, {} empty meshes; normals computed for {} meshes",
        report.scene.degenerate_triangles, report.scene.empty_meshes, report.scene.computed_normals
    );
    for line in &report.skipped {
        println!("  skipped: {line}");
    }
    for m in &scene.meshes {
        let e = &m.snow_eligibility;
        let mean = e.iter().sum::<f32>() / e.len().max(1) as f32;
        // What it is made of, as its extras said (or the default the slope picks).
        let surface = match (m.surface, m.is_sea()) {
            (_, true) => "the sea".to_owned(),
            (Some(s), false) if m.is_water_body() => format!("water body ({})", s.name()),
            (Some(s), false) => s.name().to_owned(),
            (None, false) => "untagged (paved where no snow lies, else soil)".to_owned(),
        };
        // Where each came from: an attribute, extras on a material, mesh or node,
        // or nothing (the slope, the default).
        let from = report.tags.iter().find(|t| t.primitive == m.name);
        let (eligibility_from, surface_from) = from.map_or_else(
            || ("the scene".to_owned(), String::new()),
            |t| {
                let eligibility = match t.eligibility {
                    precip_viewer::TagSource::Untagged => "the slope (no tag)".to_owned(),
                    ref other => other.to_string(),
                };
                let surface = match t.surface {
                    precip_viewer::TagSource::Untagged => String::new(),
                    ref other => format!(" from {other}"),
                };
                (eligibility, surface)
            },
        );
        println!(
            "    {}: {} triangles, eligibility mean {mean:.2} from {eligibility_from}, surface {surface}{surface_from}",
            m.name,
            m.indices.len() / 3
        );
    }
    Ok(())
}

/// The preset named (light snow at 2 mm/h when none is) with the options applied.
fn preset_of(args: &WeatherArgs) -> anyhow::Result<Preset> {
    let mut preset = match &args.preset {
        Some(p) => Preset::load(p)?,
        None => Preset::load("light-snow")?,
    };
    if args.preset.is_none() {
        preset.intensity_mm_per_h = 2.0;
    }
    if let Some(k) = args.kind {
        if k != preset.kind {
            // The preset's grains are its own kind's.
            preset.grain_diameter_mm = None;
            preset.grain_density_kg_m3 = None;
        }
        preset.kind = k;
        if args.temperature.is_none() {
            preset.air_temperature_c = k.default_air_temperature_c();
        }
    }
    preset.intensity_mm_per_h = args.intensity.unwrap_or(preset.intensity_mm_per_h);
    preset.air_temperature_c = args.temperature.unwrap_or(preset.air_temperature_c);
    preset.wind_speed_mps = args.wind.unwrap_or(preset.wind_speed_mps);
    preset.wind_from_deg = args.wind_from.unwrap_or(preset.wind_from_deg);
    preset.gust_factor = args.gust.unwrap_or(preset.gust_factor);
    preset.fog_top_m = args.fog_top.or(preset.fog_top_m);
    preset.fog_visibility_m = args.fog_visibility.or(preset.fog_visibility_m);
    preset.cloud_type = args.cloud_type.or(preset.cloud_type);
    preset.cloud_cover = args.cloud_cover.or(preset.cloud_cover);
    preset.cloud_base_m = args.cloud_base.or(preset.cloud_base_m);
    preset.cloud_thickness_m = args.cloud_thickness.or(preset.cloud_thickness_m);
    preset.cloud_transition_band_m = args
        .cloud_transition_band
        .or(preset.cloud_transition_band_m);
    preset.rate_beyond_mm_per_h = args.rate_beyond.or(preset.rate_beyond_mm_per_h);
    preset.more_clouds.extend(args.more_clouds.iter().copied());
    Ok(preset)
}

/// The CIGI receiver `--cigi` asks for, drawing `--cigi-view` on the tangent
/// plane at `--origin`.
fn cigi_receiver(
    args: &RunArgs,
    weather: precip_model::Weather,
) -> anyhow::Result<Option<precip_cigi::CigiReceiver>> {
    let Some(port) = args.cigi else {
        if args.origin.is_some() || args.cigi_lockstep {
            eprintln!("warning: --origin and --cigi-lockstep do nothing without --cigi PORT");
        }
        return Ok(None);
    };
    let mut receiver = precip_cigi::CigiReceiver::bind(port, weather)?;
    receiver.set_view(args.origin.unwrap_or_default(), args.cigi_view);
    eprintln!("CIGI: listening on {}", receiver.local_addr()?);
    Ok(Some(receiver))
}

fn run(args: &RunArgs) -> anyhow::Result<()> {
    let loaded = match &args.scene {
        Some(path) => load_scene(path)?,
        None if args.coast => load_scene_from_slice(&coast_glb(), "built-in coast.glb")?,
        None => load_scene_from_slice(DEMO_GLB, "built-in demo.glb")?,
    };
    for line in &loaded.report.skipped {
        eprintln!("warning: skipped {line}");
    }
    let mut loaded = loaded;
    if let Some(source) = &args.terrain {
        let started = std::time::Instant::now();
        let terrain = precip_viewer::terrain_file::load_terrain(
            source,
            precip_viewer::terrain_file::TerrainScale {
                spacing_m: args.terrain_spacing,
                heights_m: args.terrain_heights.map(|v| (v.x, v.y)),
            },
        )?;
        let (low, high) = terrain.height_range_m();
        let size = terrain.size_m();
        let extent = if size.max_element() >= 2000.0 {
            format!("{:.1} × {:.1} km", size.x / 1000.0, size.y / 1000.0)
        } else {
            format!("{:.0} × {:.0} m", size.x, size.y)
        };
        eprintln!(
            "terrain: {} × {} samples {} m apart ({extent}), heights {low:.0} to {high:.0} m ({:.1} s)",
            terrain.samples().x,
            terrain.samples().y,
            terrain.spacing_m(),
            started.elapsed().as_secs_f32()
        );
        // A file's land cover (placed by where both GeoTIFFs lie, when they say),
        // or the generated terrain's own.
        let (terrain, laid) = match &args.land_cover {
            Some(file) => {
                let place = match source {
                    precip_viewer::terrain_file::TerrainSource::File(f) => {
                        precip_viewer::geotiff_place::GeoPlacement::of_file(f)
                    }
                    precip_viewer::terrain_file::TerrainSource::Generated => None,
                };
                let (cover, laid) = precip_viewer::land_cover_file::load_land_cover_over(
                    file,
                    &terrain,
                    place.as_ref(),
                )?;
                (terrain.with_land_cover(cover), Some(laid))
            }
            None => (terrain, None),
        };
        if let Some(land_cover) = terrain.land_cover() {
            let how = match laid {
                Some(precip_viewer::land_cover_file::Laid::ByGeoreference(crs)) => {
                    format!(" (laid by its georeferencing, {crs})")
                }
                Some(precip_viewer::land_cover_file::Laid::Stretched) => {
                    " (stretched over the terrain's extent: one of the files says not where it lies)".to_owned()
                }
                None => String::new(),
            };
            eprintln!("{}{how}", land_cover_summary(land_cover));
        }
        loaded.scene = loaded.scene.on_terrain(std::sync::Arc::new(terrain));
    }
    let scenario = args
        .scenario
        .as_deref()
        .map(precip_viewer::scenario::load_scenario)
        .transpose()?;
    let mut scenario = scenario;
    if let Some(s) = scenario.as_mut() {
        let origin = args.origin.unwrap_or_default();
        s.light_by_time_of_day(origin.latitude_deg, origin.longitude_deg)
            .map_err(|e| {
                anyhow::anyhow!(
                    "{}: {e}",
                    args.scenario
                        .as_deref()
                        .unwrap_or(std::path::Path::new("?"))
                        .display()
                )
            })?;
        if args.origin.is_none() && s.initial.time_of_day.is_some() {
            eprintln!(
                "note: the scenario's TimeOfDay places the sun as seen from 0° N 0° E; give the scene's place with --origin LAT,LON"
            );
        }
    }
    if let Some(s) = &scenario {
        eprintln!(
            "scenario: from the start {}",
            precip_viewer::scenario::apply::describe(&s.initial)
        );
        for change in &s.changes {
            eprintln!(
                "scenario: at {} s {}: {}",
                change.at_s,
                change.event,
                precip_viewer::scenario::apply::describe(&change.weather)
            );
        }
        for note in &s.notes {
            eprintln!("warning: scenario: {note}");
        }
    }
    let (weather, fog_layer, cloud_layers, rate_beyond) = match &scenario {
        Some(s) => (
            s.initial.weather,
            s.initial.fog_layer,
            s.initial.cloud_layer.into(),
            args.weather.rate_beyond,
        ),
        None => {
            let preset = preset_of(&args.weather)?;
            (
                preset.weather().context("the weather")?,
                preset.fog_layer()?,
                preset.cloud_layers()?,
                preset.rate_beyond_mm_per_h,
            )
        }
    };
    let camera = match (args.camera, args.look_at) {
        (Some(eye), Some(at)) => Some(Camera {
            position_m: eye,
            forward: at - eye,
            ..Camera::default()
        }),
        (Some(eye), None) => Some(Camera {
            position_m: eye,
            ..Camera::default()
        }),
        _ if args.coast => Some(Camera {
            position_m: BEACH_VIEW.0,
            forward: BEACH_VIEW.1 - BEACH_VIEW.0,
            ..Camera::default()
        }),
        _ => None,
    };
    let options = SceneOptions {
        particle_budget: args.particles,
        seed: args.seed,
        texel_m: args.texel,
        grid_side_m: args.grid_side,
        cover_days_per_second: args.time_scale,
        weather,
        camera,
    };
    let mut setup = scene_setup(loaded.scene, &options)?;
    // The clear air's haze a scenario's environment without a Fog returns to.
    let clear_air_extinction_per_m = setup.render.clear_air_extinction_per_m;
    if let Some(s) = &scenario {
        if let Some(fog) = s.initial.fog_extinction_per_m {
            setup.render.clear_air_extinction_per_m = fog;
        }
        if let Some(sun) = s.initial.to_sun {
            setup.render.to_sun = sun;
        }
    }
    let scenario_clock = scenario.map(|s| {
        precip_viewer::scenario::apply::ScenarioClock::new(
            s.changes,
            setup.render.to_sun,
            clear_air_extinction_per_m,
        )
    });
    setup.render.fog_layer = fog_layer;
    setup.render.cloud_layers = cloud_layers;
    setup.render.rate_beyond_mm_per_h = rate_beyond;
    if !(args.sea_fetch_km.is_finite() && (0.1..=10_000.0).contains(&args.sea_fetch_km)) {
        anyhow::bail!(
            "--sea-fetch-km {} must be in [0.1, 10000] km (10 a bay, 100 and more the open ocean)",
            args.sea_fetch_km
        );
    }
    setup.render.sea.fetch_m = args.sea_fetch_km * 1000.0;
    setup.render.sea.spectrum = match args.sea_spectrum {
        SeaSpectrumName::Jonswap => precip_model::drawing::sea::SeaSpectrum::Jonswap,
        SeaSpectrumName::Phillips => precip_model::drawing::sea::SeaSpectrum::Phillips,
    };
    setup.camera.forward =
        channel_forward(setup.camera.forward, args.channel_yaw, args.channel_pitch);
    if let Some(shift) = args.channel_shift {
        setup.camera.lens_shift = shift;
    }
    setup.render = setup.render.at_quality(match args.quality {
        QualityName::Low => precip_model::Quality::Low,
        QualityName::Medium => precip_model::Quality::Medium,
        QualityName::High | QualityName::Auto => precip_model::Quality::High,
    });
    if let Some(mirrors) = args.mirrors {
        setup.render.mirrors = match mirrors {
            MirrorsName::Auto => precip_model::Mirrors::Auto,
            MirrorsName::WaterBodies => precip_model::Mirrors::WaterBodies,
            MirrorsName::AllWater => precip_model::Mirrors::AllWater,
        };
    }
    if let Some(resolution) = args.particle_resolution {
        setup.render.particle_resolution = match resolution {
            ParticleResolutionName::Full => precip_model::ParticleResolution::Full,
            ParticleResolutionName::Half => precip_model::ParticleResolution::Half,
            ParticleResolutionName::Quarter => precip_model::ParticleResolution::Quarter,
        };
    }
    setup.camera.lens = precip_model::Lens {
        exposure_s: args.shutter,
        f_number: args.f_number,
        focus_distance_m: args.focus,
    };
    setup
        .camera
        .lens
        .validate()
        .context("--shutter, --f-number and --focus")?;
    let frames = match args.frames {
        Some(n) => n,
        None if display_available() => {
            if args.lidar {
                eprintln!("warning: --lidar scans in headless runs only (give --frames N)");
            }
            if args.cigi_lockstep {
                eprintln!(
                    "warning: --cigi-lockstep paces headless runs only (give --frames N); the window draws as fast as it can"
                );
            }
            let cigi = cigi_receiver(args, setup.weather)?;
            if !(args.target_fps.is_finite() && args.target_fps > 0.0) {
                anyhow::bail!(
                    "--target-fps {} must be a positive number of frames a second",
                    args.target_fps
                );
            }
            let hold_fps = (args.quality == QualityName::Auto).then_some(args.target_fps);
            match run_window(
                setup.clone(),
                args.size,
                args.backend,
                args.quit_after,
                precip_viewer::window::WindowDrivers {
                    cigi,
                    scenario: scenario_clock.clone(),
                    flight: args.flight.clone(),
                },
                hold_fps,
            ) {
                Ok(shown) => {
                    if shown.frames > 0 {
                        println!(
                            "window: {} frames in {:.1} s, {:.1} s simulated (×{:.2}: one sub-step a frame at most); {} ({:?}, {}×{})",
                            shown.frames,
                            shown.seconds,
                            shown.simulated_s,
                            shown.simulated_s / shown.seconds.max(1e-9),
                            shown.stats.describe(),
                            args.backend,
                            args.size.0,
                            args.size.1,
                        );
                        if let Some(passes) = shown.stats.describe_passes() {
                            println!("window: {passes}");
                        }
                    }
                    if args.backend == BackendName::Vk && precip_viewer::backends::vk_validation() {
                        report_validation(&shown.validation_messages)?;
                    }
                    return Ok(());
                }
                Err(WindowError::NoDisplay(why)) => {
                    eprintln!(
                        "no window ({why}): rendering {FALLBACK_FRAMES} frames headless into {} instead",
                        args.out.display()
                    );
                    FALLBACK_FRAMES
                }
                Err(e) => return Err(e.into()),
            }
        }
        None => {
            eprintln!(
                "no display (DISPLAY and WAYLAND_DISPLAY are unset): rendering {FALLBACK_FRAMES} frames headless into {} instead",
                args.out.display()
            );
            FALLBACK_FRAMES
        }
    };
    let (mut backend, validation) = open_headless(args.backend)?;
    eprintln!("{}", backend.info().device);
    backend.configure(&setup)?;
    let view = View {
        camera: setup.camera,
        width_px: args.size.0,
        height_px: args.size.1,
    };
    let mut cigi = cigi_receiver(args, setup.weather)?;
    let summary = run_headless_with(
        backend.as_mut(),
        &view,
        frames,
        args.dt.clamp(1e-3, 1.0),
        &args.out,
        true,
        precip_viewer::headless::HeadlessExtras {
            cigi: cigi.as_mut(),
            lockstep: args.cigi_lockstep,
            scenario: scenario_clock,
            flight: args.flight.clone(),
            lidar: args.lidar.then(|| {
                precip_viewer::lidar_scan::SpinningLidar::automotive(view.camera.position_m)
            }),
        },
    )?;
    for line in &summary.scenario_log {
        println!("{line}");
    }
    if let Some((points, echoes)) = summary.lidar_points {
        println!(
            "LiDAR: {points} points in {frames} scans (scan_NNNN.ply), {echoes} of them echoes from particles"
        );
    }
    if let Some(receiver) = &cigi {
        let c = receiver.counts();
        let w = receiver.weather();
        println!(
            "CIGI: {} datagrams ({} malformed), {} IG Control, Weather Control {} applied, {} ignored, {} refused, {} other packets, {} Start of Frame sent; weather in effect: {:?} {:.2} mm/h at {:.1} °C, wind {:.1} m/s",
            c.datagrams,
            c.malformed,
            c.ig_control,
            c.weather_applied,
            c.weather_ignored,
            c.weather_refused,
            c.other,
            c.start_of_frame_sent,
            w.kind,
            w.intensity_mm_per_h,
            w.air_temperature_c,
            w.wind.mean_wind_mps.length()
        );
        let eye = summary.last_camera;
        let forward = eye.forward.normalize_or_zero();
        let other: Vec<String> = receiver
            .other_opcodes()
            .iter()
            .map(|(opcode, n)| format!("{n}× opcode {opcode}"))
            .collect();
        println!(
            "CIGI: Entity Control {} placed, View Control/Definition {} taken, Celestial Sphere Control {} placed the sun, {} not used; last eyepoint ({:.1}, {:.1}, {:.1}) m looking ({:.3}, {:.3}, {:.3}); {} host frames missed in lockstep; packets not used: {}",
            c.entity_control,
            c.view_control,
            c.celestial,
            c.view_ignored,
            eye.position_m.x,
            eye.position_m.y,
            eye.position_m.z,
            forward.x,
            forward.y,
            forward.z,
            summary.host_frames_missed,
            if other.is_empty() {
                "none".to_owned()
            } else {
                other.join(", ")
            }
        );
        if let Some(e) = receiver.last_error() {
            println!("CIGI: the last malformed datagram: {e}");
        }
    }
    println!(
        "{} frames in {}: mean {:.1} ms, p95 {:.1} ms per frame (read-back included, PNGs encoded beside; {}); {} particles; snow cover water {:.2} mm on average, deepest snow {:.0} mm; {}",
        summary.frames,
        args.out.display(),
        summary.mean_frame_ms,
        summary.p95_frame_ms,
        summary.stats.describe(),
        summary.particles,
        summary.cover_water_mm,
        summary.max_depth_mm,
        summary.water.describe()
    );
    println!("{}", summary.snow.describe());
    println!("{}", summary.water.describe_books());
    if let Some(far) = &summary.far_cover {
        println!(
            "{}",
            precip_viewer::water_summary::describe_far_books(far, &summary.water.totals)
        );
        if let Some(window) = summary.cover_window.as_ref().filter(|w| w.moves() > 0) {
            let frame = window.cover_at(window.shift());
            let centre = frame.origin_m + 0.5 * frame.size_m;
            println!(
                "the cover grid followed the camera: {} moves, its centre now at x {:.0} m, z {:.0} m ({} texels along x and {} along z from where it began)",
                window.moves(),
                centre.x,
                centre.y,
                window.shift().x,
                window.shift().y
            );
        }
        if let Some(line) = summary.far_snow_line_m {
            println!(
                "snow line beyond the grid: {line:.0} m (from the top down, each {} m of height half covered by {} mm of snow or more)",
                precip_model::host::SNOW_LINE_BAND_M,
                precip_model::host::SNOW_LINE_DEPTH_MM
            );
        }
    }
    if let Some(passes) = summary.stats.describe_passes() {
        println!("{passes}");
    }
    drop(backend);
    if let Some(log) = validation {
        report_validation(&log.lock().map(|m| m.clone()).unwrap_or_default())?;
    }
    Ok(())
}

/// Prints what the Vulkan validation layer said and fails when it said anything.
fn report_validation(messages: &[String]) -> anyhow::Result<()> {
    eprintln!("Vulkan validation layer: {} messages", messages.len());
    for m in messages {
        eprintln!("  {m}");
    }
    anyhow::ensure!(
        messages.is_empty(),
        "the validation layer reported problems"
    );
    Ok(())
}

/// Keeps Mesa's device-select Vulkan layer from probing for a Wayland compositor when
/// there can be none: without a valid `XDG_RUNTIME_DIR` its probe fails and libwayland
/// prints `error: XDG_RUNTIME_DIR is invalid or not set in the environment.` (twice, on
/// every headless run), which reads as precip's error. The layer only orders the
/// devices by the session's default GPU; precip picks its device itself. A user's own
/// `NODEVICE_SELECT` is left as it is.
#[expect(
    unsafe_code,
    reason = "setting an environment variable, done first in main before any thread exists"
)]
fn quiet_wayland_probe_without_a_session() {
    let runtime_dir_ok =
        std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| std::path::Path::new(&d).is_dir());
    if !runtime_dir_ok && std::env::var_os("NODEVICE_SELECT").is_none() {
        // SAFETY: called first in `main`, before any other thread is started, so no
        // thread reads the environment concurrently.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}

/// `--sea-spectrum`: `precip_sea::ocean::SeaSpectrum`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum SeaSpectrumName {
    /// JONSWAP over the fetch.
    Jonswap,
    /// Phillips (Tessendorf), a fully developed sea.
    Phillips,
}

/// `--mirrors`: which water mirrors the scene (`precip_model::Mirrors`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum MirrorsName {
    /// All water on a GPU, the water bodies only on a CPU rasteriser.
    Auto,
    /// The water bodies only.
    WaterBodies,
    /// The water bodies and every puddle.
    AllWater,
}

/// `--quality`: `precip_model::Quality`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum QualityName {
    /// Particles at a quarter of the frame's resolution, a smaller shadow map kept up
    /// to 4 frames when stale, only the water bodies mirroring.
    Low,
    /// Particles at half the frame's resolution.
    Medium,
    /// Everything at the frame's resolution.
    High,
    /// In a window, the particles' resolution and the shadow map's refresh follow
    /// the frame rate (`--target-fps`); headless, as high.
    Auto,
}

/// `--particle-resolution`: `precip_model::ParticleResolution`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum ParticleResolutionName {
    /// The frame's.
    Full,
    /// Half the frame's width and height.
    Half,
    /// A quarter of the frame's width and height.
    Quarter,
}

fn main() -> ExitCode {
    quiet_wayland_probe_without_a_session();
    let cli = Cli::parse();
    let result = match &cli.command {
        Some(Command::Inspect { file }) => inspect(file),
        Some(Command::Optics { weather }) => preset_of(weather).and_then(|p| {
            let weather = p.weather().context("the weather")?;
            precip_viewer::optics_report::print_optics(&weather)
        }),
        Some(Command::Demo { out, coast }) => {
            let (bytes, default) = if *coast {
                (coast_glb(), "crates/viewer/assets/coast.glb")
            } else {
                (demo_glb(), "crates/viewer/assets/demo.glb")
            };
            let out = out.clone().unwrap_or_else(|| PathBuf::from(default));
            std::fs::write(&out, bytes)
                .with_context(|| format!("writing {}", out.display()))
                .map(|()| println!("wrote {}", out.display()))
        }
        None => run(&cli.run),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
