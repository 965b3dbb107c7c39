//! Where a GeoTIFF lies: its tie point (`ModelTiepointTag`, 33922), its pixel size
//! (`ModelPixelScaleTag`, 33550) and the coordinate system its `GeoKeyDirectoryTag`
//! (34735) names (GeoTIFF 1.1, OGC 19-008r4: `GTModelTypeGeoKey` 1024 says projected
//! or geographic; `ProjectedCSTypeGeoKey` 3072 and `GeographicTypeGeoKey` 2048 give
//! the EPSG code).
//!
//! The viewer needs it twice: a height map in degrees (SRTM and Copernicus DEM tiles
//! come in EPSG:4326) cannot take its pixel size as metres, and a land cover laid
//! over a terrain must be placed by where both lie when both say so, not stretched
//! over the terrain (a WorldCover tile spans 3°, a DEM a few kilometres).

use std::path::Path;

use glam::DVec2;

/// `ModelPixelScaleTag`.
pub const MODEL_PIXEL_SCALE_TAG: u16 = 33550;
/// `ModelTiepointTag`.
pub const MODEL_TIEPOINT_TAG: u16 = 33922;
/// `GeoKeyDirectoryTag`.
pub const GEO_KEY_DIRECTORY_TAG: u16 = 34735;

/// A GeoTIFF's coordinate system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Crs {
    /// Projected (metres, as a rule): its EPSG code, 0 if user-defined.
    Projected(u16),
    /// Geographic (degrees): its EPSG code, 0 if user-defined.
    Geographic(u16),
    /// The file does not say.
    Unknown,
}

impl std::fmt::Display for Crs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Projected(0) => write!(f, "a user-defined projected system"),
            Self::Geographic(0) => write!(f, "a user-defined geographic system"),
            Self::Projected(code) | Self::Geographic(code) => write!(f, "EPSG:{code}"),
            Self::Unknown => write!(f, "no stated system"),
        }
    }
}

/// Where a GeoTIFF's pixels lie.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeoPlacement {
    /// The model coordinates (x east, y north) of pixel `(0, 0)`'s corner.
    pub corner: DVec2,
    /// A pixel's size along x and y (positive; rows run south).
    pub pixel: DVec2,
    /// The coordinate system.
    pub crs: Crs,
}

impl GeoPlacement {
    /// Reads the placement of the GeoTIFF `decoder` reads, if it gives a tie point
    /// and a pixel scale.
    pub fn of<R: std::io::Read + std::io::Seek>(
        decoder: &mut tiff::decoder::Decoder<R>,
    ) -> Option<Self> {
        use tiff::tags::Tag;
        let scale = decoder
            .get_tag_f64_vec(Tag::Unknown(MODEL_PIXEL_SCALE_TAG))
            .ok()?;
        let tie = decoder
            .get_tag_f64_vec(Tag::Unknown(MODEL_TIEPOINT_TAG))
            .ok()?;
        let (&[sx, sy, ..], &[i, j, _, x, y, ..]) = (scale.as_slice(), tie.as_slice()) else {
            return None;
        };
        let pixel = DVec2::new(sx, sy);
        let corner = DVec2::new(x - i * sx, y + j * sy);
        if !(pixel.is_finite() && corner.is_finite() && pixel.min_element() > 0.0) {
            return None;
        }
        let keys = decoder
            .get_tag_u16_vec(Tag::Unknown(GEO_KEY_DIRECTORY_TAG))
            .unwrap_or_default();
        Some(Self {
            corner,
            pixel,
            crs: crs_of(&keys),
        })
    }

    /// Reads the placement of the GeoTIFF `file` (its tags only), if it gives one.
    #[must_use]
    pub fn of_file(file: &Path) -> Option<Self> {
        let reader = std::fs::File::open(file).ok()?;
        let mut decoder = tiff::decoder::Decoder::new(std::io::BufReader::new(reader)).ok()?;
        Self::of(&mut decoder)
    }

    /// The pixel's continuous `(column, row)` at model coordinates `p`.
    #[must_use]
    pub fn pixel_at(&self, p: DVec2) -> DVec2 {
        DVec2::new(
            (p.x - self.corner.x) / self.pixel.x,
            (self.corner.y - p.y) / self.pixel.y,
        )
    }

    /// The model coordinates of the continuous `(column, row)` `c`.
    #[must_use]
    pub fn model_at(&self, c: DVec2) -> DVec2 {
        DVec2::new(
            self.corner.x + c.x * self.pixel.x,
            self.corner.y - c.y * self.pixel.y,
        )
    }
}

/// The coordinate system a GeoKey directory names.
fn crs_of(keys: &[u16]) -> Crs {
    let Some(count) = keys.get(3) else {
        return Crs::Unknown;
    };
    let mut model = 0;
    let (mut projected, mut geographic) = (None, None);
    for entry in keys[4..].chunks_exact(4).take(usize::from(*count)) {
        // [key, location (0: the value is here), count, value]
        if entry[1] != 0 {
            continue;
        }
        match entry[0] {
            1024 => model = entry[3],
            2048 => geographic = Some(entry[3]),
            3072 => projected = Some(entry[3]),
            _ => {}
        }
    }
    // 32767: user-defined.
    let code = |c: u16| if c == 32767 { 0 } else { c };
    match (model, projected, geographic) {
        (1, p, _) => Crs::Projected(p.map_or(0, code)),
        (2, _, g) => Crs::Geographic(g.map_or(0, code)),
        (_, Some(p), _) => Crs::Projected(code(p)),
        (_, None, Some(g)) => Crs::Geographic(code(g)),
        _ => Crs::Unknown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_geo_keys_name_the_system() {
        // Version 1.1.0, 2 keys: projected, UTM 33N.
        let utm = [1, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32633];
        assert_eq!(crs_of(&utm), Crs::Projected(32633));
        let wgs84 = [1, 1, 0, 2, 1024, 0, 1, 2, 2048, 0, 1, 4326];
        assert_eq!(crs_of(&wgs84), Crs::Geographic(4326));
        assert_eq!(crs_of(&[1, 1, 0, 1, 1024, 0, 1, 1]), Crs::Projected(0));
        assert_eq!(crs_of(&[]), Crs::Unknown);
        // A key whose value lives in another tag is not read as a code.
        assert_eq!(crs_of(&[1, 1, 0, 1, 3072, 34737, 1, 0]), Crs::Unknown);
        assert_eq!(Crs::Geographic(4326).to_string(), "EPSG:4326");
    }

    #[test]
    fn pixels_and_model_coordinates_map_both_ways() {
        let g = GeoPlacement {
            corner: DVec2::new(500_000.0, 5_000_000.0),
            pixel: DVec2::new(10.0, 10.0),
            crs: Crs::Projected(32633),
        };
        assert_eq!(
            g.pixel_at(DVec2::new(500_105.0, 4_999_895.0)),
            DVec2::new(10.5, 10.5)
        );
        assert_eq!(
            g.model_at(DVec2::new(10.5, 10.5)),
            DVec2::new(500_105.0, 4_999_895.0)
        );
    }
}
