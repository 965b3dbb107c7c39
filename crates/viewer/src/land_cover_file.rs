//! The terrain's land cover (`--land-cover`): an ESA WorldCover-coded raster
//! (`precip_model::scene::land_cover`) read from an 8-bit greyscale PNG with
//! `image` or a GeoTIFF with `tiff` (WorldCover's own tiles: one byte a pixel,
//! greyscale or with its colour map, whose indices are the codes), spanning the
//! terrain's extent at any resolution; or the generated terrain's own
//! ([`generated_land_cover`]): its river, its town, forests on the valleys' sides,
//! fields on their floors, bare rock high up.

use std::path::{Path, PathBuf};

use glam::{DVec2, UVec2, Vec2};
use precip_model::scene::land_cover::{
    LandClass, LandCover, LandCoverError, MAX_LAND_COVER_PIXELS,
};
use precip_model::scene::terrain::Terrain;

use crate::geotiff_place::{Crs, GeoPlacement};
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
    /// The land cover and the terrain lie in different coordinate systems.
    #[error(
        "{file} is in {land_cover}, the terrain in {terrain}: reproject the land cover to the terrain's system first (gdalwarp -t_srs <the terrain's EPSG> -r near {file} out.tif)"
    )]
    Crs {
        /// The file.
        file: PathBuf,
        /// The land cover's system.
        land_cover: Crs,
        /// The terrain's.
        terrain: Crs,
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

/// How a land cover was laid over its terrain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Laid {
    /// By where both GeoTIFFs lie, in their one coordinate system.
    ByGeoreference(Crs),
    /// Stretched over the terrain's extent (one of them says not where it lies).
    Stretched,
}

/// Reads the land cover in `file` (see the module docs), stretched over the
/// terrain's extent.
pub fn load_land_cover(file: &Path) -> Result<LandCover, LandCoverFileError> {
    let (pixels, codes, _) = read_codes(file)?;
    land_cover(file, pixels, &codes)
}

/// Reads the land cover in `file` and lays it over `terrain`, read from a GeoTIFF
/// placed at `terrain_place` if it was: where both GeoTIFFs say where they lie (in
/// the same coordinate system) each of the terrain's points takes the class of the
/// land cover's pixel over it (no data where it has none), at the land cover's own
/// pixel size; else it is stretched over the terrain's extent.
pub fn load_land_cover_over(
    file: &Path,
    terrain: &Terrain,
    terrain_place: Option<&GeoPlacement>,
) -> Result<(LandCover, Laid), LandCoverFileError> {
    let (pixels, codes, place) = read_codes(file)?;
    // Validated whole first: as many codes as pixels (a malformed file's short
    // read indexes nothing below), each a class.
    let whole = land_cover(file, pixels, &codes)?;
    let (Some(over), Some(place)) = (terrain_place, place) else {
        return Ok((whole, Laid::Stretched));
    };
    if over.crs != place.crs || matches!(place.crs, Crs::Unknown) {
        return Err(LandCoverFileError::Crs {
            file: file.to_path_buf(),
            land_cover: place.crs,
            terrain: over.crs,
        });
    }
    // The terrain's samples span raster coordinates 0.5 … n − 0.5 of its file.
    let samples = terrain.samples().as_dvec2();
    let from = over.model_at(DVec2::splat(0.5));
    let to = over.model_at(samples - 0.5);
    let out = ((to - from).abs() / place.pixel)
        .ceil()
        .as_uvec2()
        .clamp(UVec2::ONE, UVec2::splat(MAX_LAND_COVER_PIXELS));
    let mut laid = Vec::with_capacity((out.x * out.y) as usize);
    for j in 0..out.y {
        for i in 0..out.x {
            let t = (UVec2::new(i, j).as_dvec2() + 0.5) / out.as_dvec2();
            let raster = DVec2::splat(0.5) + t * (samples - 1.0);
            let p = place.pixel_at(over.model_at(raster)).floor();
            let inside =
                p.x >= 0.0 && p.y >= 0.0 && p.x < f64::from(pixels.x) && p.y < f64::from(pixels.y);
            laid.push(if inside {
                codes[p.x as usize + pixels.x as usize * p.y as usize]
            } else {
                0
            });
        }
    }
    Ok((
        land_cover(file, out, &laid)?,
        Laid::ByGeoreference(place.crs),
    ))
}

/// The land cover of `codes` read from `file`.
fn land_cover(file: &Path, pixels: UVec2, codes: &[u8]) -> Result<LandCover, LandCoverFileError> {
    LandCover::from_worldcover(pixels, codes).map_err(|problem| LandCoverFileError::LandCover {
        file: file.to_path_buf(),
        problem,
    })
}

/// The codes in `file`, and where a GeoTIFF says they lie.
fn read_codes(file: &Path) -> Result<(UVec2, Vec<u8>, Option<GeoPlacement>), LandCoverFileError> {
    let ext = file
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => read_png(file).map(|(p, c)| (p, c, None)),
        Some("tif" | "tiff") => read_geotiff(file),
        _ => Err(LandCoverFileError::Kind {
            file: file.to_path_buf(),
        }),
    }
}

/// The pixels a raster may have (a decoder is not asked for more).
fn check_size(file: &Path, w: u32, h: u32) -> Result<UVec2, LandCoverFileError> {
    let most = MAX_LAND_COVER_PIXELS;
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

fn read_geotiff(file: &Path) -> Result<(UVec2, Vec<u8>, Option<GeoPlacement>), LandCoverFileError> {
    use tiff::decoder::{Decoder, DecodingResult, Limits};
    let reader = std::fs::File::open(file).map_err(|e| unreadable(file, e))?;
    let mut decoder = Decoder::new(std::io::BufReader::new(reader))
        .map_err(|e| unreadable(file, e))?
        .with_limits(Limits::unlimited());
    let (w, h) = decoder.dimensions().map_err(|e| unreadable(file, e))?;
    let pixels = check_size(file, w, h)?;
    let place = GeoPlacement::of(&mut decoder);
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
        DecodingResult::U8(codes) => Ok((pixels, codes, place)),
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

    /// Writes a GeoTIFF of `w × h` 8-bit `samples` whose pixel (0, 0)'s corner
    /// lies at `corner`, `pixel` apart, in `crs` (GeoKey directory entries).
    fn geotiff(
        file: &Path,
        (w, h): (u32, u32),
        samples: &[u8],
        corner: DVec2,
        pixel: f64,
        crs: [u16; 8],
    ) {
        use crate::geotiff_place::{
            GEO_KEY_DIRECTORY_TAG, MODEL_PIXEL_SCALE_TAG, MODEL_TIEPOINT_TAG,
        };
        use tiff::encoder::{TiffEncoder, colortype};
        use tiff::tags::Tag;
        let out = std::fs::File::create(file).expect("created");
        let mut encoder = TiffEncoder::new(out).expect("an encoder");
        let mut image = encoder
            .new_image::<colortype::Gray8>(w, h)
            .expect("an image");
        let e = image.encoder();
        e.write_tag(
            Tag::Unknown(MODEL_PIXEL_SCALE_TAG),
            &[pixel, pixel, 0.0][..],
        )
        .expect("the scale");
        e.write_tag(
            Tag::Unknown(MODEL_TIEPOINT_TAG),
            &[0.0, 0.0, 0.0, corner.x, corner.y, 0.0][..],
        )
        .expect("the tie point");
        let mut keys = vec![1_u16, 1, 0, 2];
        keys.extend_from_slice(&crs);
        e.write_tag(Tag::Unknown(GEO_KEY_DIRECTORY_TAG), &keys[..])
            .expect("the keys");
        image.write_data(samples).expect("the samples");
    }

    const UTM_33N: [u16; 8] = [1024, 0, 1, 1, 3072, 0, 1, 32633];
    const WGS_84: [u16; 8] = [1024, 0, 1, 2, 2048, 0, 1, 4326];

    #[test]
    fn a_georeferenced_land_cover_is_laid_where_it_lies_over_a_georeferenced_terrain() {
        // The terrain: 11 × 11 heights 100 m apart, its corner pixel at
        // (500 000, 5 001 100) in UTM 33N: samples from x 500 050 to 501 050.
        let dem = scratch("dem.tif");
        geotiff(
            &dem,
            (11, 11),
            &[0; 121],
            DVec2::new(500_000.0, 5_001_100.0),
            100.0,
            UTM_33N,
        );
        let place = GeoPlacement::of_file(&dem).expect("placed");
        assert_eq!(place.crs, Crs::Projected(32633));
        let terrain =
            Terrain::new(UVec2::splat(11), 100.0, Vec2::ZERO, vec![0.0; 121]).expect("valid");
        // The land cover: 9 × 10 pixels of 200 m from (499 000, 5 002 000): forest,
        // water in its last column (x 500 600 – 500 800), nothing east of it.
        let codes: Vec<u8> = (0..90).map(|k| if k % 9 == 8 { 80 } else { 10 }).collect();
        let tile = scratch("tile.tif");
        geotiff(
            &tile,
            (9, 10),
            &codes,
            DVec2::new(499_000.0, 5_002_000.0),
            200.0,
            UTM_33N,
        );
        let (cover, laid) = load_land_cover_over(&tile, &terrain, Some(&place)).expect("laid");
        assert_eq!(laid, Laid::ByGeoreference(Crs::Projected(32633)));
        // 1 km of terrain at the land cover's 200 m: 5 × 5 pixels.
        assert_eq!(cover.pixels(), UVec2::splat(5));
        let row: Vec<LandClass> = (0..5)
            .map(|i| cover.class_at(Vec2::new((i as f32 + 0.5) / 5.0, 0.5)))
            .collect();
        assert_eq!(
            row,
            [
                LandClass::Trees,
                LandClass::Trees,
                LandClass::Trees,
                LandClass::Water,
                LandClass::NoData
            ]
        );
        // Stretched when the terrain says not where it lies.
        let (stretched, laid) = load_land_cover_over(&tile, &terrain, None).expect("laid");
        assert_eq!(laid, Laid::Stretched);
        assert_eq!(stretched.pixels(), UVec2::new(9, 10));
        // Refused in another system, saying what to do.
        let degrees = scratch("tile4326.tif");
        geotiff(
            &degrees,
            (9, 10),
            &codes,
            DVec2::new(15.0, 45.0),
            0.001,
            WGS_84,
        );
        let e = load_land_cover_over(&degrees, &terrain, Some(&place)).unwrap_err();
        assert!(
            e.to_string()
                .contains("is in EPSG:4326, the terrain in EPSG:32633: reproject"),
            "{e}"
        );
    }

    #[test]
    fn a_height_map_in_degrees_asks_for_a_spacing() {
        use crate::terrain_file::{TerrainScale, TerrainSource, load_terrain};
        let dem = scratch("srtm.tif");
        geotiff(
            &dem,
            (4, 4),
            &[7; 16],
            DVec2::new(15.0, 46.0),
            1.0 / 3600.0,
            WGS_84,
        );
        let source = TerrainSource::File(dem);
        let e = load_terrain(
            &source,
            TerrainScale {
                spacing_m: None,
                heights_m: None,
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("geographic coordinates"), "{e}");
        assert!(e.to_string().contains("--terrain-spacing"), "{e}");
        let t = load_terrain(
            &source,
            TerrainScale {
                spacing_m: Some(30.0),
                heights_m: None,
            },
        )
        .expect("a spacing given");
        assert_eq!(t.size_m(), Vec2::splat(90.0));
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
