//! Terrain from elevation data (`--terrain`): a 16-bit (or 8-bit) greyscale PNG read
//! with `image`, a GeoTIFF read with `tiff` (the pure-Rust decoder `image` itself
//! uses; any sample type, its `ModelPixelScale` giving the spacing and its
//! `GDAL_NODATA` holes filled), or one generated in code ([`generated_valleys`]).
//!
//! The terrain is centred on the world's origin and raised or lowered as a whole so
//! that its height there is 0 m: a glTF scene (the built-in demo) modelled around
//! its own origin at ground level stands on it.

use std::path::{Path, PathBuf};

use glam::{UVec2, Vec2};
use precip_model::scene::terrain::{MAX_TERRAIN_SAMPLES, Terrain, TerrainError};

/// Where the terrain comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum TerrainSource {
    /// A height map file (`.png`, `.tif`, `.tiff`).
    File(PathBuf),
    /// [`generated_valleys`]: 10 km of valleys and ridges with a town's flat ground
    /// at the origin.
    Generated,
}

impl TerrainSource {
    /// `generated`, or a file's path.
    #[must_use]
    pub fn parse(text: &str) -> Self {
        if text == "generated" {
            Self::Generated
        } else {
            Self::File(PathBuf::from(text))
        }
    }
}

/// How the samples become metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TerrainScale {
    /// Metres between samples; `None`: a GeoTIFF's pixel scale, else 1 m.
    pub spacing_m: Option<f32>,
    /// The heights of the smallest and largest integer sample (0 and 65 535 in a
    /// 16-bit map, 0 and 255 in an 8-bit one), m; `None`: 0 and 1 000 m for a PNG,
    /// the samples as metres for a GeoTIFF.
    pub heights_m: Option<(f32, f32)>,
}

/// A height map that cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TerrainFileError {
    /// The file could not be read or decoded.
    #[error("{file}: not a readable height map: {detail}")]
    Unreadable {
        /// The file.
        file: PathBuf,
        /// What the decoder said.
        detail: String,
    },
    /// A kind of file that is not read.
    #[error("{file}: a height map is a .png (16- or 8-bit greyscale) or a .tif/.tiff (GeoTIFF)")]
    Kind {
        /// The file.
        file: PathBuf,
    },
    /// The samples make no terrain.
    #[error("{file}: {problem}")]
    Terrain {
        /// The file.
        file: PathBuf,
        /// The check that failed.
        problem: TerrainError,
    },
    /// A GeoTIFF in degrees, and no spacing given.
    #[error(
        "{file} is in geographic coordinates ({pixel_deg}° a pixel), not metres: reproject it (gdalwarp -t_srs EPSG:<its UTM zone> {file} out.tif) or give --terrain-spacing in metres"
    )]
    Degrees {
        /// The file.
        file: PathBuf,
        /// Its pixel's size, degrees.
        pixel_deg: f64,
    },
    /// The heights option is not a range.
    #[error("--terrain-heights {low},{high}: give the lowest height below the highest, in metres")]
    Heights {
        /// Of the smallest sample.
        low: f32,
        /// Of the largest.
        high: f32,
    },
}

/// Loads `source` scaled by `scale` (see the module docs).
pub fn load_terrain(
    source: &TerrainSource,
    scale: TerrainScale,
) -> Result<Terrain, TerrainFileError> {
    if let Some((low, high)) = scale.heights_m
        && !(low.is_finite() && high.is_finite() && low < high)
    {
        return Err(TerrainFileError::Heights { low, high });
    }
    let (file, samples, spacing, heights) = match source {
        TerrainSource::Generated => {
            let file = PathBuf::from("generated");
            let spacing = scale.spacing_m.unwrap_or(GENERATED_SPACING_M);
            let (samples, heights) = generated_valleys(GENERATED_SIDE_M, spacing);
            (file, samples, spacing, heights)
        }
        TerrainSource::File(file) => {
            let ext = file
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            let (samples, heights, pixel_m) = match ext.as_deref() {
                Some("png") => {
                    let (samples, heights) = read_png(file, scale.heights_m)?;
                    (samples, heights, None)
                }
                Some("tif" | "tiff") => read_geotiff(file, scale.heights_m, scale.spacing_m)?,
                _ => return Err(TerrainFileError::Kind { file: file.clone() }),
            };
            let spacing = scale.spacing_m.or(pixel_m).unwrap_or(1.0);
            (file.clone(), samples, spacing, heights)
        }
    };
    let generated = matches!(source, TerrainSource::Generated);
    Terrain::new(samples, spacing, Vec2::ZERO, heights)
        .map(|t| {
            if generated {
                // Its town is graded for the demo already; it comes with its own
                // land cover (whose codes are all WorldCover's: it cannot fail).
                match crate::land_cover_file::generated_land_cover(&t) {
                    Ok(cover) => t.with_land_cover(cover),
                    Err(_) => t,
                }
            } else {
                t.with_height_at(Vec2::ZERO, 0.0)
            }
        })
        .map_err(|problem| TerrainFileError::Terrain { file, problem })
}

fn unreadable(file: &Path, detail: impl std::fmt::Display) -> TerrainFileError {
    TerrainFileError::Unreadable {
        file: file.to_path_buf(),
        detail: detail.to_string(),
    }
}

/// The size a height map may have (a decoder is not asked for more).
fn check_size(file: &Path, w: u32, h: u32) -> Result<UVec2, TerrainFileError> {
    if w > MAX_TERRAIN_SAMPLES || h > MAX_TERRAIN_SAMPLES || w < 2 || h < 2 {
        return Err(TerrainFileError::Terrain {
            file: file.to_path_buf(),
            problem: TerrainError::Samples { x: w, z: h },
        });
    }
    Ok(UVec2::new(w, h))
}

/// A greyscale PNG's samples as heights (16-bit kept, others to 16 bits).
fn read_png(
    file: &Path,
    heights_m: Option<(f32, f32)>,
) -> Result<(UVec2, Vec<f32>), TerrainFileError> {
    let reader = image::ImageReader::open(file)
        .and_then(image::ImageReader::with_guessed_format)
        .map_err(|e| unreadable(file, e))?;
    let (w, h) = reader.into_dimensions().map_err(|e| unreadable(file, e))?;
    let samples = check_size(file, w, h)?;
    let image = image::open(file).map_err(|e| unreadable(file, e))?;
    let grey = image.to_luma16();
    let (low, high) = heights_m.unwrap_or((0.0, 1000.0));
    let step = (high - low) / 65535.0;
    Ok((
        samples,
        grey.as_raw()
            .iter()
            .map(|&v| low + step * f32::from(v))
            .collect(),
    ))
}

/// TIFF tags GeoTIFF and GDAL add.
const MODEL_PIXEL_SCALE_TAG: u16 = 33550;
const GDAL_NODATA_TAG: u16 = 42113;

/// A GeoTIFF's first band as heights, and its pixel scale (x) if it gives one; one
/// in degrees is refused unless `spacing_m` is given.
fn read_geotiff(
    file: &Path,
    heights_m: Option<(f32, f32)>,
    spacing_m: Option<f32>,
) -> Result<(UVec2, Vec<f32>, Option<f32>), TerrainFileError> {
    use tiff::decoder::{Decoder, DecodingResult, Limits};
    use tiff::tags::Tag;
    let reader = std::fs::File::open(file).map_err(|e| unreadable(file, e))?;
    let mut decoder = Decoder::new(std::io::BufReader::new(reader))
        .map_err(|e| unreadable(file, e))?
        .with_limits(Limits::unlimited());
    let (w, h) = decoder.dimensions().map_err(|e| unreadable(file, e))?;
    let samples = check_size(file, w, h)?;
    let channels = match decoder.colortype().map_err(|e| unreadable(file, e))? {
        tiff::ColorType::Gray(_) => 1,
        other => {
            return Err(unreadable(
                file,
                format!("{other:?} samples: give a single band of heights"),
            ));
        }
    };
    let pixel_m = decoder
        .get_tag_f64_vec(Tag::Unknown(MODEL_PIXEL_SCALE_TAG))
        .ok()
        .and_then(|v| v.first().copied())
        .map(|s| s as f32)
        .filter(|s| s.is_finite() && *s > 0.0);
    // A pixel size in degrees is not a spacing (SRTM and Copernicus DEM tiles are
    // in EPSG:4326): the caller asks for one (TerrainFileError::Degrees).
    if let Some(place) = crate::geotiff_place::GeoPlacement::of(&mut decoder)
        && matches!(place.crs, crate::geotiff_place::Crs::Geographic(_))
        && spacing_m.is_none()
    {
        return Err(TerrainFileError::Degrees {
            file: file.to_path_buf(),
            pixel_deg: place.pixel.x,
        });
    }
    let nodata = decoder
        .get_tag_ascii_string(Tag::Unknown(GDAL_NODATA_TAG))
        .ok()
        .and_then(|s| s.trim().trim_end_matches('\0').parse::<f64>().ok());
    // Integer samples over their type's range when heights are given, else metres.
    let scaled = |v: f64, max: f64| match heights_m {
        Some((low, high)) => f64::from(low) + (f64::from(high) - f64::from(low)) * v / max,
        None => v,
    };
    let values: Vec<f64> = match decoder.read_image().map_err(|e| unreadable(file, e))? {
        DecodingResult::U8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F64(v) => v,
        _ => {
            return Err(unreadable(
                file,
                "a sample type other than 8-64-bit integers or 32/64-bit floats",
            ));
        }
    };
    let max = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(1.0_f64, f64::max);
    // GDAL's no-data value is an exact sentinel: the same bits.
    let hole = |v: f64| !v.is_finite() || nodata.is_some_and(|n| v.to_bits() == n.to_bits());
    // Holes take the lowest height found.
    let lowest = values
        .iter()
        .copied()
        .filter(|&v| !hole(v))
        .fold(f64::INFINITY, f64::min);
    let lowest = if lowest.is_finite() { lowest } else { 0.0 };
    let heights = values
        .iter()
        .step_by(channels)
        .map(|&v| scaled(if hole(v) { lowest } else { v }, max.max(255.0)) as f32)
        .collect();
    Ok((samples, heights, pixel_m))
}

/// The generated terrain's side, m.
pub const GENERATED_SIDE_M: f32 = 10_000.0;
/// Its spacing, m.
pub const GENERATED_SPACING_M: f32 = 2.5;
/// The radius of its town's flat ground around the origin, m.
pub const GENERATED_TOWN_RADIUS_M: f32 = 150.0;

/// A lattice value in [0, 1) (a hash of the lattice point).
fn lattice(i: i32, j: i32, seed: u32) -> f32 {
    let mut h = (i as u32).wrapping_mul(0x8da6_b343)
        ^ (j as u32).wrapping_mul(0xd816_3841)
        ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^= h >> 15;
    (h >> 8) as f32 / 16_777_216.0
}

/// Smooth value noise in [0, 1).
pub(crate) fn value_noise(p: Vec2, seed: u32) -> f32 {
    let base = p.floor();
    let f = p - base;
    let u = f * f * (Vec2::splat(3.0) - 2.0 * f);
    let (i, j) = (base.x as i32, base.y as i32);
    let a = lattice(i, j, seed);
    let b = lattice(i + 1, j, seed);
    let c = lattice(i, j + 1, seed);
    let d = lattice(i + 1, j + 1, seed);
    let low = a + (b - a) * u.x;
    let high = c + (d - c) * u.x;
    low + (high - low) * u.y
}

/// A side of `side_m` at `spacing_m` of valleys and ridges (ridged multifractal
/// noise, Musgrave 1994, up to about 900 m of relief, 1–3 km between ridges), a
/// river valley winding through, and a town's flat ground at the origin, blended
/// into the hills over 250 m: the samples and their heights, m
/// (`generated_height_m`).
#[must_use]
pub fn generated_valleys(side_m: f32, spacing_m: f32) -> (UVec2, Vec<f32>) {
    let n = ((side_m / spacing_m).round() as u32 + 1).clamp(2, MAX_TERRAIN_SAMPLES);
    let half = 0.5 * (n - 1) as f32 * spacing_m;
    let origin = hills_and_river(Vec2::ZERO);
    let mut heights = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let p = Vec2::new(i as f32 * spacing_m - half, j as f32 * spacing_m - half);
            heights.push(generated_height_m(p, origin));
        }
    }
    (UVec2::splat(n), heights)
}

/// How far under the demo's ground the generated terrain lies inside its square,
/// m (clear of the pond's hollow and the road's sag between samples), rising to
/// [`SITE_SEAM_M`] under it at its edge.
const UNDER_SITE_M: f32 = 0.5;
/// How far under the demo's ground's edge the generated terrain meets it, m.
const SITE_SEAM_M: f32 = 0.05;

/// The generated terrain's height at `p` (x, z), m, `origin` the hills' height at
/// the origin: under the demo's square its ground [`UNDER_SITE_M`] lower, rising
/// to meet the square's edge [`SITE_SEAM_M`] under it over its last 2 m (so the
/// demo's ground and the terrain join without a step); from the edge the town's
/// ground graded as the demo's site (2 % toward −z) over 30 m; the hills and the
/// river's valley from [`GENERATED_TOWN_RADIUS_M`], blended in over 250 m.
fn generated_height_m(p: Vec2, origin: f32) -> f32 {
    let half = crate::demo::TERRAIN_SIDE_M / 2.0;
    let outside = p.abs().max_element() - half;
    let edge = p.clamp(Vec2::splat(-half), Vec2::splat(half));
    let site = crate::demo::terrain_height_m(edge.x, edge.y);
    if outside <= 0.0 {
        let rise = ((outside + 2.0) / 2.0).clamp(0.0, 1.0);
        return site - UNDER_SITE_M + (UNDER_SITE_M - SITE_SEAM_M) * rise;
    }
    let s = smooth(outside / 30.0);
    let graded = 0.02 * p.y - 0.2;
    let town = site - SITE_SEAM_M + (graded - site + SITE_SEAM_M) * s;
    let t = smooth((p.length() - GENERATED_TOWN_RADIUS_M) / 250.0);
    if t > 0.0 {
        town + (hills_and_river(p) - origin - town) * t
    } else {
        town
    }
}

/// `t` clamped to [0, 1] and eased (smoothstep).
fn smooth(t: f32) -> f32 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The river's course: its z at `x`, m (west to east, past the town).
pub(crate) fn river_z_m(x: f32) -> f32 {
    600.0 * (x / 1700.0).sin() + 250.0 * (x / 610.0 + 1.3).sin()
}

/// The built-in flight over [`generated_valleys`] (`--flight valley`): a helicopter
/// at 70 m/s up the river's valley from 4.5 km west to 4.5 km east, 250 m above the
/// highest ground within 300 m of its track, past the town, looking 8° down — 129 s.
/// Lines of `t_s x_m y_m z_m heading_deg pitch_deg` ([`crate::flight`]).
#[must_use]
pub fn valley_flight() -> String {
    const SPEED_MPS: f32 = 70.0;
    let origin = hills_and_river(Vec2::ZERO);
    let ground = |p: Vec2| generated_height_m(p, origin);
    let points: Vec<Vec2> = (0..=36)
        .map(|k| {
            let x = -4500.0 + 250.0 * k as f32;
            Vec2::new(x, river_z_m(x))
        })
        .collect();
    let mut text = String::from("# t_s x_m y_m z_m heading_deg pitch_deg (the valley flight)\n");
    let mut t = 0.0;
    for (k, p) in points.iter().enumerate() {
        let highest = (-6..=6)
            .flat_map(|i| (-6..=6).map(move |j| Vec2::new(i as f32, j as f32) * 50.0))
            .map(|o| ground(*p + o))
            .fold(f32::MIN, f32::max);
        let next = points
            .get(k + 1)
            .copied()
            .unwrap_or_else(|| *p + (*p - points[k.saturating_sub(1)]));
        let d = next - *p;
        let heading = d.x.atan2(-d.y).to_degrees();
        text.push_str(&format!(
            "{t:.2} {:.1} {:.1} {:.1} {heading:.1} -8\n",
            p.x,
            highest + 250.0,
            p.y
        ));
        t += d.length() / SPEED_MPS;
    }
    text
}

/// The hills and the river's valley at `p` (x, z), m.
fn hills_and_river(p: Vec2) -> f32 {
    // Ridged octaves: sharp crests, rounded valleys.
    let mut sum = 0.0;
    let mut amplitude = 1.0;
    let mut weight = 1.0;
    let mut q = p / 2400.0;
    for octave in 0..7 {
        let r = 1.0 - (2.0 * value_noise(q, 17 + octave) - 1.0).abs();
        let r = r * r * weight;
        weight = (r * 2.0).clamp(0.0, 1.0);
        sum += r * amplitude;
        amplitude *= 0.5;
        q = Vec2::new(1.6 * q.x - 1.2 * q.y, 1.2 * q.x + 1.6 * q.y);
    }
    let river = ((p.y - river_z_m(p.x)).abs() / 900.0).clamp(0.0, 1.0);
    let river = river * river * (3.0 - 2.0 * river);
    520.0 * sum * (0.15 + 0.85 * river)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("precip-terrain-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch folder");
        dir.join(name)
    }

    /// A ramp along x: sample (i, j) = 1000·i.
    fn ramp(w: u32, h: u32) -> Vec<u16> {
        (0..h)
            .flat_map(|_| (0..w).map(|i| (1000 * i) as u16))
            .collect()
    }

    #[test]
    fn a_16_bit_png_becomes_heights_between_the_given_low_and_high() {
        let file = scratch("ramp.png");
        let image =
            image::ImageBuffer::<image::Luma<u16>, _>::from_raw(9, 5, ramp(9, 5)).expect("sized");
        image.save(&file).expect("writes");
        let scale = TerrainScale {
            spacing_m: Some(2.0),
            heights_m: Some((100.0, 100.0 + 65.535)),
        };
        let t = load_terrain(&TerrainSource::File(file), scale).expect("loads");
        assert_eq!(t.samples(), UVec2::new(9, 5));
        assert_eq!(t.size_m(), Vec2::new(16.0, 8.0));
        // 1 mm a count, so 1 m a sample along x; the origin (the middle sample) at 0.
        let h = |x: f32| t.height_at(Vec2::new(x, 0.0)).expect("on it");
        assert!(h(0.0).abs() < 1e-3);
        assert!((h(2.0) - 1.0).abs() < 1e-3 && (h(-8.0) + 4.0).abs() < 1e-3);
    }

    #[test]
    fn a_geotiff_gives_its_pixel_scale_and_fills_its_holes() {
        use tiff::encoder::{TiffEncoder, colortype};
        use tiff::tags::Tag;
        let file = scratch("dem.tif");
        let (w, h) = (6u32, 4u32);
        let mut samples: Vec<f32> = (0..w * h).map(|k| 50.0 + (k % w) as f32).collect();
        samples[5] = -9999.0;
        {
            let out = std::fs::File::create(&file).expect("creates");
            let mut encoder = TiffEncoder::new(out).expect("an encoder");
            let mut image = encoder
                .new_image::<colortype::Gray32Float>(w, h)
                .expect("an image");
            image
                .encoder()
                .write_tag(
                    Tag::Unknown(MODEL_PIXEL_SCALE_TAG),
                    &[30.0f64, 30.0, 0.0][..],
                )
                .expect("the pixel scale");
            image
                .encoder()
                .write_tag(Tag::Unknown(GDAL_NODATA_TAG), "-9999")
                .expect("the no-data value");
            image.write_data(&samples).expect("writes");
        }
        let t = load_terrain(
            &TerrainSource::File(file),
            TerrainScale {
                spacing_m: None,
                heights_m: None,
            },
        )
        .expect("loads");
        assert!((t.spacing_m() - 30.0).abs() < 1e-6);
        assert_eq!(t.samples(), UVec2::new(6, 4));
        // Metres as they are (then the origin's at 0); the hole at the lowest.
        let (lo, hi) = t.height_range_m();
        assert!((hi - lo - 5.0).abs() < 1e-4, "{lo} … {hi}");
    }

    #[test]
    fn bad_height_maps_say_what_to_give() {
        let scale = TerrainScale {
            spacing_m: None,
            heights_m: None,
        };
        let e = load_terrain(&TerrainSource::File("dem.obj".into()), scale).unwrap_err();
        assert!(e.to_string().contains(".png"), "{e}");
        let e = load_terrain(&TerrainSource::File(scratch("missing.png")), scale).unwrap_err();
        assert!(e.to_string().contains("not a readable height map"), "{e}");
        let file = scratch("line.png");
        image::ImageBuffer::<image::Luma<u16>, _>::from_raw(5, 1, ramp(5, 1))
            .expect("sized")
            .save(&file)
            .expect("writes");
        let e = load_terrain(&TerrainSource::File(file), scale).unwrap_err();
        assert!(e.to_string().contains("2 to 16384"), "{e}");
        let e = load_terrain(
            &TerrainSource::Generated,
            TerrainScale {
                spacing_m: None,
                heights_m: Some((10.0, 5.0)),
            },
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("lowest height below the highest"),
            "{e}"
        );
    }

    #[test]
    fn the_valley_flight_flies_at_70_m_per_s_above_the_ground() {
        let flight = crate::flight::Flight::load("valley").expect("built in");
        let (samples, h) = generated_valleys(GENERATED_SIDE_M, 10.0);
        let t = Terrain::new(samples, 10.0, Vec2::ZERO, h).expect("valid");
        let template = precip_model::Camera::default();
        let mut last = flight.camera_at(0.0, &template).position_m;
        let mut lowest = f32::MAX;
        for k in 1..=((flight.duration_s() * 2.0) as u32) {
            let c = flight.camera_at(f64::from(k) * 0.5, &template).position_m;
            let speed = (c - last).length() / 0.5;
            assert!((60.0..80.0).contains(&speed), "{speed} m/s at {k}");
            let ground = t.height_at(Vec2::new(c.x, c.z)).expect("over the terrain");
            lowest = lowest.min(c.y - ground);
            last = c;
        }
        assert!(lowest > 150.0, "{lowest} m above the ground");
        assert!(
            (100.0..160.0).contains(&flight.duration_s()),
            "{}",
            flight.duration_s()
        );
    }

    #[test]
    fn the_generated_valleys_hold_a_level_town_under_the_demo_and_hills_around() {
        let (samples, h) = generated_valleys(4000.0, 20.0);
        let t = Terrain::new(samples, 20.0, Vec2::ZERO, h).expect("valid");
        // Under the demo's square half a metre under its ground, meeting its edge
        // 5 cm under it; the town's ground graded as the site beyond.
        let at = |x: f32, z: f32| t.height_at(Vec2::new(x, z)).expect("on it");
        let demo = crate::demo::terrain_height_m;
        assert!((at(0.0, 0.0) - (demo(0.0, 0.0) - 0.5)).abs() < 1e-3);
        assert!((at(-40.0, 0.0) - (demo(-40.0, 0.0) - 0.05)).abs() < 1e-3);
        assert!((at(0.0, 100.0) - (2.0 - 0.2)).abs() < 1e-3);
        // Nowhere within the square does the terrain rise through the demo's ground.
        let (s, h) = generated_valleys(200.0, 2.5);
        let fine = Terrain::new(s, 2.5, Vec2::ZERO, h).expect("valid");
        for i in 0..=160 {
            for j in 0..=160 {
                let (x, z) = (-40.0 + 0.5 * i as f32, -40.0 + 0.5 * j as f32);
                let under = fine.height_at(Vec2::new(x, z)).expect("on it");
                assert!(
                    under < demo(x, z) - 0.01,
                    "({x}, {z}): {under} over {}",
                    demo(x, z)
                );
            }
        }
        let (lo, hi) = t.height_range_m();
        assert!(hi > 200.0 && lo > -100.0, "{lo} … {hi}");
    }
}
