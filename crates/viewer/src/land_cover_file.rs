//! The terrain's land cover (`--land-cover`): an ESA WorldCover-coded raster
//! (`precip_model::scene::land_cover`) read from an 8-bit greyscale PNG with
//! `image` or a GeoTIFF with `tiff` (WorldCover's own tiles: one byte a pixel,
//! greyscale or with its colour map, whose indices are the codes), spanning the
//! terrain's extent at any resolution; or the generated terrain's own
//! ([`generated_land_cover`]): its river, its town, forests on the valleys' sides,
//! fields on their floors, bare rock high up.

use std::path::{Path, PathBuf};

use glam::{UVec2, Vec2};
use precip_model::scene::land_cover::{LandClass, LandCover, LandCoverError};
use precip_model::scene::terrain::Terrain;

use crate::terrain_file::{GENERATED_TOWN_RADIUS_M, river_z_m};

/// A land-cover raster that cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LandCoverFileError {
    /// The file could not be read or decoded.
    #[error("{file}: not a readable land cover: {detail}")]
    Unreadable {
        /// The file.
        file: PathBuf,
        /// What the decoder said.
        detail: String,
    },
    /// A kind of file that is not read.
    #[error(
        "{file}: a land cover is an 8-bit greyscale .png or a .tif/.tiff (GeoTIFF) of ESA WorldCover codes"
    )]
    Kind {
        /// The file.
        file: PathBuf,
    },
    /// The codes make no land cover.
    #[error("{file}: {problem}")]
    LandCover {
        /// The file.
        file: PathBuf,
        /// The check that failed.
        problem: LandCoverError,
    },
}

fn unreadable(file: &Path, detail: impl std::fmt::Display) -> LandCoverFileError {
    LandCoverFileError::Unreadable {
        file: file.to_path_buf(),
        detail: detail.to_string(),
    }
}

/// Reads the land cover in `file` (see the module docs).
pub fn load_land_cover(file: &Path) -> Result<LandCover, LandCoverFileError> {
    let ext = file
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (pixels, codes) = match ext.as_deref() {
        Some("png") => read_png(file)?,
        Some("tif" | "tiff") => read_geotiff(file)?,
        _ => {
            return Err(LandCoverFileError::Kind {
                file: file.to_path_buf(),
            });
        }
    };
    LandCover::from_worldcover(pixels, &codes).map_err(|problem| LandCoverFileError::LandCover {
        file: file.to_path_buf(),
        problem,
    })
}

/// The pixels a raster may have (a decoder is not asked for more).
fn check_size(file: &Path, w: u32, h: u32) -> Result<UVec2, LandCoverFileError> {
    let most = precip_model::scene::land_cover::MAX_LAND_COVER_PIXELS;
    if w == 0 || h == 0 || w > most || h > most {
        return Err(LandCoverFileError::LandCover {
            file: file.to_path_buf(),
            problem: LandCoverError::Pixels { x: w, z: h },
        });
    }
    Ok(UVec2::new(w, h))
}

fn read_png(file: &Path) -> Result<(UVec2, Vec<u8>), LandCoverFileError> {
    let reader = image::ImageReader::open(file)
        .and_then(image::ImageReader::with_guessed_format)
        .map_err(|e| unreadable(file, e))?;
    let (w, h) = reader.into_dimensions().map_err(|e| unreadable(file, e))?;
    let pixels = check_size(file, w, h)?;
    match image::open(file).map_err(|e| unreadable(file, e))? {
        image::DynamicImage::ImageLuma8(grey) => Ok((pixels, grey.into_raw())),
        other => Err(unreadable(
            file,
            format!(
                "{:?} pixels: give one 8-bit grey channel whose values are the codes",
                other.color()
            ),
        )),
    }
}

fn read_geotiff(file: &Path) -> Result<(UVec2, Vec<u8>), LandCoverFileError> {
    use tiff::decoder::{Decoder, DecodingResult, Limits};
    let reader = std::fs::File::open(file).map_err(|e| unreadable(file, e))?;
    let mut decoder = Decoder::new(std::io::BufReader::new(reader))
        .map_err(|e| unreadable(file, e))?
        .with_limits(Limits::unlimited());
    let (w, h) = decoder.dimensions().map_err(|e| unreadable(file, e))?;
    let pixels = check_size(file, w, h)?;
    match decoder.colortype().map_err(|e| unreadable(file, e))? {
        tiff::ColorType::Gray(8) | tiff::ColorType::Palette(8) => {}
        other => {
            return Err(unreadable(
                file,
                format!("{other:?} samples: give one band of 8-bit codes"),
            ));
        }
    }
    match decoder.read_image().map_err(|e| unreadable(file, e))? {
        DecodingResult::U8(codes) => Ok((pixels, codes)),
        _ => Err(unreadable(file, "samples other than 8-bit codes")),
    }
}

/// Metres a pixel of the generated land cover spans (WorldCover's).
pub const GENERATED_LAND_PIXEL_M: f32 = 10.0;

/// The land cover of the generated valleys (`terrain`, from
/// [`crate::terrain_file::generated_valleys`]) at [`GENERATED_LAND_PIXEL_M`]: the
/// river 24 m wide along its course, grass round the demo's site, the town's
/// built-up ground around it out to 260 m,
/// fields on the valley floor (under 6°), forests in patches on the slopes from 8°
/// to 42°, bare rock on steeper or the highest ground, grass elsewhere.
pub fn generated_land_cover(terrain: &Terrain) -> Result<LandCover, LandCoverError> {
    let size = terrain.size_m();
    let pixels = (size / GENERATED_LAND_PIXEL_M)
        .ceil()
        .as_uvec2()
        .clamp(UVec2::ONE, UVec2::splat(16_384));
    let (_, high) = terrain.height_range_m();
    let mut codes = Vec::with_capacity((pixels.x * pixels.y) as usize);
    for j in 0..pixels.y {
        for i in 0..pixels.x {
            let uv = (UVec2::new(i, j).as_vec2() + 0.5) / pixels.as_vec2();
            let p = terrain.corner_m() + uv * size;
            codes.push(generated_class(terrain, p, high).worldcover_code());
        }
    }
    LandCover::from_worldcover(pixels, &codes)
}

/// The generated class at `p` (x, z) on `terrain` whose highest point is `high`.
fn generated_class(terrain: &Terrain, p: Vec2, high: f32) -> LandClass {
    if (p.y - river_z_m(p.x)).abs() < 12.0 {
        return LandClass::Water;
    }
    // The demo's garden, then the town around it.
    let town_edge = GENERATED_TOWN_RADIUS_M + 110.0 * patches(p, 90.0, 5);
    if p.abs().max_element() < 70.0 {
        return LandClass::Grassland;
    }
    if p.length() < town_edge {
        return LandClass::BuiltUp;
    }
    let up = terrain.normal_at(p).y;
    let slope_deg = up.clamp(-1.0, 1.0).acos().to_degrees();
    let height = terrain.height_at(p).unwrap_or(0.0);
    if slope_deg > 42.0 || height > high - 60.0 {
        return LandClass::Bare;
    }
    let patch = patches(p, 420.0, 11);
    if slope_deg < 6.0 {
        return if patches(p, 260.0, 23) > 0.45 {
            LandClass::Cropland
        } else {
            LandClass::Grassland
        };
    }
    if slope_deg > 8.0 && patch > 0.35 {
        return LandClass::Trees;
    }
    if patch > 0.25 {
        LandClass::Shrubs
    } else {
        LandClass::Grassland
    }
}

/// Smooth patches in [0, 1) about `scale_m` across (two octaves of value noise).
fn patches(p: Vec2, scale_m: f32, seed: u32) -> f32 {
    let q = p / scale_m;
    0.65 * crate::terrain_file::value_noise(q, seed)
        + 0.35 * crate::terrain_file::value_noise(2.3 * q, seed + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("precip-land-cover-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch folder");
        dir.join(name)
    }

    #[test]
    fn an_8_bit_png_and_a_geotiff_of_codes_become_classes() {
        let codes = [10_u8, 50, 80, 0, 30, 95];
        let png = scratch("lc.png");
        image::GrayImage::from_raw(3, 2, codes.to_vec())
            .expect("pixels")
            .save(&png)
            .expect("written");
        let lc = load_land_cover(&png).expect("read");
        assert_eq!(lc.pixels(), UVec2::new(3, 2));
        assert_eq!(lc.class_at(Vec2::new(0.5, 0.25)), LandClass::BuiltUp);
        assert_eq!(lc.class_at(Vec2::new(0.9, 0.9)), LandClass::Mangroves);
        let tif = scratch("lc.tif");
        {
            let f = std::fs::File::create(&tif).expect("created");
            let mut e = tiff::encoder::TiffEncoder::new(f).expect("encoder");
            e.write_image::<tiff::encoder::colortype::Gray8>(3, 2, &codes)
                .expect("written");
        }
        assert_eq!(load_land_cover(&tif).expect("read"), lc);
    }

    #[test]
    fn bad_land_covers_say_what_to_give() {
        let e = load_land_cover(Path::new("x.jpg")).unwrap_err();
        assert!(e.to_string().contains("8-bit greyscale .png"), "{e}");
        let e = load_land_cover(Path::new("/nonexistent/lc.png")).unwrap_err();
        assert!(e.to_string().contains("not a readable land cover"), "{e}");
        // Codes of another map.
        let png = scratch("corine.png");
        image::GrayImage::from_raw(2, 1, vec![10, 211])
            .expect("pixels")
            .save(&png)
            .expect("written");
        let e = load_land_cover(&png).unwrap_err();
        assert!(e.to_string().contains("code 211 at pixel (1, 0)"), "{e}");
        // Colour, not codes.
        let rgb = scratch("rgb.png");
        image::RgbImage::new(2, 2).save(&rgb).expect("written");
        let e = load_land_cover(&rgb).unwrap_err();
        assert!(e.to_string().contains("one 8-bit grey channel"), "{e}");
    }

    #[test]
    fn the_generated_valleys_have_a_river_a_town_forests_and_fields() {
        let (samples, heights) = crate::terrain_file::generated_valleys(10_000.0, 20.0);
        let terrain = Terrain::new(samples, 20.0, Vec2::ZERO, heights).expect("valid");
        let lc = generated_land_cover(&terrain).expect("valid codes");
        assert_eq!(lc.pixels(), UVec2::splat(1000));
        let counts = lc.class_counts();
        let share = |c: LandClass| counts[c as usize] as f32 / 1.0e6;
        for (class, least) in [
            (LandClass::Water, 0.002),
            (LandClass::BuiltUp, 0.001),
            (LandClass::Trees, 0.1),
            (LandClass::Cropland, 0.01),
            (LandClass::Grassland, 0.05),
            (LandClass::Bare, 0.005),
        ] {
            assert!(share(class) > least, "{class:?}: {}", share(class));
        }
        assert_eq!(counts[LandClass::NoData as usize], 0);
        // The town under the demo, the river on its course.
        let at = |p: Vec2| terrain.clone().with_land_cover(lc.clone()).land_class_at(p);
        assert_eq!(at(Vec2::ZERO), LandClass::Grassland);
        assert_eq!(at(Vec2::new(120.0, -80.0)), LandClass::BuiltUp);
        assert_eq!(at(Vec2::new(-3000.0, river_z_m(-3000.0))), LandClass::Water);
    }
}
