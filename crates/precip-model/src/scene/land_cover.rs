//! [`LandCover`]: what a terrain's ground is — forest, town, fields, open water —
//! from a land-cover raster in the classes of ESA WorldCover (Zanaga et al. 2022,
//! *ESA WorldCover 10 m 2021 v200*, doi:10.5281/zenodo.7254221), the global map at
//! 10 m whose GeoTIFF tiles carry one byte a pixel: 10 tree cover, 20 shrubland,
//! 30 grassland, 40 cropland, 50 built-up, 60 bare or sparse vegetation, 70 snow
//! and ice, 80 permanent water, 90 herbaceous wetland, 95 mangroves, 100 moss and
//! lichen; 0 (and 255) no data. Other sources (CORINE, NLCD) are reclassified to
//! these before use.
//!
//! The raster spans the terrain's extent whatever its resolution: pixel `(i, j)`
//! of `n × m` covers `[i/n, (i+1)/n) × [j/m, (j+1)/m)` of it, row `j` along z as
//! the height map's. A class gives, where the raster has one (else the slope rule of
//! [`crate::scene::terrain::Terrain::surface_for`] and
//! [`crate::scene::terrain::Terrain::eligibility_for`] alone):
//!
//! - the **surface** the cover's water physics runs on ([`LandClass::surface`]):
//!   built-up land is paved, water is a water body (all that lands goes into it:
//!   no snow lies on open water), fields and bare land are soil, the rest turf;
//! - the **share of the ground's snow seen from above** ([`LandClass::snow_share`]),
//!   which weighs the snow drawn there (not the snow that lies: what falls through
//!   a canopy or is unloaded from it lies on the floor, in the books as any other
//!   snow; the ground map's eligibility is the slope's, none on open water): under
//!   a forest's canopy the snow on
//!   the floor shows through its gaps only (the canopy's *viewable gap fraction*,
//!   which Klein, Hall & Riggs 1998, *Hydrological Processes* 12, 1723–1744, model
//!   for satellites' snow maps over forests); we take half the floor for a closed
//!   canopy, a choice of ours, not a measured constant; shrubs hide a little; open
//!   water shows none (what lands there joins the water);
//! - the terrain's **colour** ([`crate::scene::terrain::terrain_ramp`]'s row of the
//!   class, blending into soil and rock on steep slopes as the slope rule's).
//!
//! The GPU reads the classes one `f32` a pixel after the pyramid in the ground
//! buffer ([`LandCover::gpu_samples`]), decimated (nearest) to fit
//! [`LAND_COVER_GPU_BUDGET_BYTES`]; the ground map where snow lies reads the raster
//! at its full resolution.

use glam::{UVec2, Vec2};
use precip_cover::Surface;

/// Most bytes the classes take on the GPU: 4 Mi pixels (10 km at 5 m); a finer
/// raster is drawn from every `f`-th pixel.
pub const LAND_COVER_GPU_BUDGET_BYTES: u64 = 16 << 20;

/// Most pixels along a side (as a height map's).
pub const MAX_LAND_COVER_PIXELS: u32 = crate::scene::terrain::MAX_TERRAIN_SAMPLES;

/// A land-cover class (ESA WorldCover's, see the module docs); its `u32` is its row
/// of the terrain's colour ramp and its index in [`LandClass::ALL`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[repr(u32)]
pub enum LandClass {
    /// No class given: the slope decides.
    #[default]
    NoData = 0,
    /// Tree cover (10).
    Trees = 1,
    /// Shrubland (20).
    Shrubs = 2,
    /// Grassland (30).
    Grassland = 3,
    /// Cropland (40).
    Cropland = 4,
    /// Built-up (50): towns, roads.
    BuiltUp = 5,
    /// Bare or sparse vegetation (60).
    Bare = 6,
    /// Snow and ice (70): glaciers, permanent snow.
    SnowAndIce = 7,
    /// Permanent water bodies (80).
    Water = 8,
    /// Herbaceous wetland (90).
    Wetland = 9,
    /// Mangroves (95).
    Mangroves = 10,
    /// Moss and lichen (100).
    MossAndLichen = 11,
}

/// Classes, and rows of the terrain's colour ramp.
pub const LAND_CLASSES: usize = 12;

impl LandClass {
    /// Every class, in `u32` order.
    pub const ALL: [Self; LAND_CLASSES] = [
        Self::NoData,
        Self::Trees,
        Self::Shrubs,
        Self::Grassland,
        Self::Cropland,
        Self::BuiltUp,
        Self::Bare,
        Self::SnowAndIce,
        Self::Water,
        Self::Wetland,
        Self::Mangroves,
        Self::MossAndLichen,
    ];

    /// The class of a WorldCover code (0 and 255: no data); `None` for a code that
    /// is not one of its classes.
    #[must_use]
    pub const fn from_worldcover(code: u8) -> Option<Self> {
        Some(match code {
            0 | 255 => Self::NoData,
            10 => Self::Trees,
            20 => Self::Shrubs,
            30 => Self::Grassland,
            40 => Self::Cropland,
            50 => Self::BuiltUp,
            60 => Self::Bare,
            70 => Self::SnowAndIce,
            80 => Self::Water,
            90 => Self::Wetland,
            95 => Self::Mangroves,
            100 => Self::MossAndLichen,
            _ => return None,
        })
    }

    /// Its WorldCover code (0 for no data).
    #[must_use]
    pub const fn worldcover_code(self) -> u8 {
        match self {
            Self::NoData => 0,
            Self::Trees => 10,
            Self::Shrubs => 20,
            Self::Grassland => 30,
            Self::Cropland => 40,
            Self::BuiltUp => 50,
            Self::Bare => 60,
            Self::SnowAndIce => 70,
            Self::Water => 80,
            Self::Wetland => 90,
            Self::Mangroves => 95,
            Self::MossAndLichen => 100,
        }
    }

    /// The surface under the cover (module docs); `None`: the slope's.
    #[must_use]
    pub const fn surface(self) -> Option<Surface> {
        match self {
            Self::NoData => None,
            Self::Trees | Self::Cropland | Self::Bare | Self::SnowAndIce => Some(Surface::Soil),
            Self::BuiltUp => Some(Surface::Asphalt),
            Self::Water => Some(Surface::Water),
            Self::Shrubs
            | Self::Grassland
            | Self::Wetland
            | Self::Mangroves
            | Self::MossAndLichen => Some(Surface::Grass),
        }
    }

    /// The share of the snow on the ground seen from above (module docs): a
    /// weight of its drawing.
    #[must_use]
    pub const fn snow_share(self) -> f32 {
        match self {
            Self::Trees | Self::Mangroves => 0.5,
            Self::Shrubs => 0.85,
            Self::Water => 0.0,
            _ => 1.0,
        }
    }

    /// Its colour on flat ground (sRGB 0–255): a winter photograph's — dark
    /// conifers, grass the green of the demo's lawn, stubble, grey town, dark water.
    #[must_use]
    pub const fn colour(self) -> [u8; 3] {
        match self {
            Self::NoData | Self::Grassland => [135, 149, 110],
            Self::Trees => [44, 60, 38],
            Self::Shrubs => [84, 90, 56],
            Self::Cropland => [130, 114, 82],
            Self::BuiltUp => [116, 114, 110],
            Self::Bare => [128, 116, 96],
            Self::SnowAndIce => [232, 236, 242],
            Self::Water => [36, 54, 62],
            Self::Wetland => [90, 96, 66],
            Self::Mangroves => [40, 58, 36],
            Self::MossAndLichen => [112, 108, 82],
        }
    }
}

/// The raster cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum LandCoverError {
    /// Too few or too many pixels along a side.
    #[error(
        "the land cover has {x} × {z} pixels: give 1 to {MAX_LAND_COVER_PIXELS} along each side"
    )]
    Pixels {
        /// Along x.
        x: u32,
        /// Along z.
        z: u32,
    },
    /// Not as many codes as pixels.
    #[error("the land cover has {got} codes for {x} × {z} pixels")]
    CodeCount {
        /// Codes given.
        got: usize,
        /// Along x.
        x: u32,
        /// Along z.
        z: u32,
    },
    /// A code that is not a WorldCover class.
    #[error(
        "land cover code {code} at pixel ({x}, {z}) is not an ESA WorldCover class: give 10, 20, \
         30, 40, 50, 60, 70, 80, 90, 95 or 100 (0 for no data), reclassifying other maps first"
    )]
    Code {
        /// The code.
        code: u8,
        /// Its pixel along x.
        x: u32,
        /// Along z.
        z: u32,
    },
}

/// A land-cover raster over a terrain's extent (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct LandCover {
    pixels: UVec2,
    classes: Vec<LandClass>,
}

impl LandCover {
    /// The raster of `pixels` (x, z) WorldCover `codes`, row by row (x fastest).
    pub fn from_worldcover(pixels: UVec2, codes: &[u8]) -> Result<Self, LandCoverError> {
        let (x, z) = (pixels.x, pixels.y);
        if !(1..=MAX_LAND_COVER_PIXELS).contains(&x) || !(1..=MAX_LAND_COVER_PIXELS).contains(&z) {
            return Err(LandCoverError::Pixels { x, z });
        }
        if codes.len() != x as usize * z as usize {
            return Err(LandCoverError::CodeCount {
                got: codes.len(),
                x,
                z,
            });
        }
        let classes = codes
            .iter()
            .enumerate()
            .map(|(k, &code)| {
                LandClass::from_worldcover(code).ok_or(LandCoverError::Code {
                    code,
                    x: (k % x as usize) as u32,
                    z: (k / x as usize) as u32,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { pixels, classes })
    }

    /// Pixels along x and z.
    #[must_use]
    pub fn pixels(&self) -> UVec2 {
        self.pixels
    }

    /// The class at `uv` of the extent (`[0, 1)²`; outside it, no data): its
    /// pixel's (what the ground map and the far cover classify by).
    #[must_use]
    pub fn class_at(&self, uv: Vec2) -> LandClass {
        if !(uv.x >= 0.0 && uv.y >= 0.0 && uv.x < 1.0 && uv.y < 1.0) {
            return LandClass::NoData;
        }
        let p = (uv * self.pixels.as_vec2()).as_uvec2().min(self.pixels - 1);
        self.classes[(p.x + self.pixels.x * p.y) as usize]
    }

    /// The class drawn at `uv` of the extent (`[0, 1)²`; outside it, no data): of
    /// the four pixels round it, the class with the most bilinear weight
    /// ([`crate::drawing::land_borders`]), so borders run smoothly across the
    /// pixels. At a pixel's centre it is the pixel's class.
    /// WGSL twin: `land_class_at` (render_terrain.wgsl), which draws the GPU's
    /// copy: its twin is `gpu_copy().drawn_class_at(uv)` ([`LandCover::gpu_copy`]).
    #[must_use]
    pub fn drawn_class_at(&self, uv: Vec2) -> LandClass {
        if !(uv.x >= 0.0 && uv.y >= 0.0 && uv.x < 1.0 && uv.y < 1.0) {
            return LandClass::NoData;
        }
        let t = uv * self.pixels.as_vec2() - 0.5;
        let base = t.floor();
        let last = self.pixels.as_ivec2() - 1;
        let class = |dx: i32, dz: i32| {
            let p = (base.as_ivec2() + glam::IVec2::new(dx, dz)).clamp(glam::IVec2::ZERO, last);
            self.classes[(p.x + self.pixels.x as i32 * p.y) as usize] as u32
        };
        let corners = [class(0, 0), class(1, 0), class(0, 1), class(1, 1)];
        let drawn = crate::drawing::land_borders::land_class_pick(corners, t - base);
        LandClass::ALL[drawn as usize]
    }

    /// How many of each class, in [`LandClass::ALL`] order.
    #[must_use]
    pub fn class_counts(&self) -> [usize; LAND_CLASSES] {
        let mut counts = [0; LAND_CLASSES];
        for c in &self.classes {
            counts[*c as usize] += 1;
        }
        counts
    }

    /// The smallest `f` for which every `f`-th pixel fits `budget_bytes`.
    #[must_use]
    pub fn decimation(&self, budget_bytes: u64) -> u32 {
        (1..=MAX_LAND_COVER_PIXELS)
            .find(|&f| {
                let n = UVec2::new(self.pixels.x.div_ceil(f), self.pixels.y.div_ceil(f));
                u64::from(n.x) * u64::from(n.y) * 4 <= budget_bytes
            })
            .unwrap_or(MAX_LAND_COVER_PIXELS)
    }

    /// The raster the GPU draws with ([`LandCover::gpu_samples`]) as a land
    /// cover: the whole raster within [`LAND_COVER_GPU_BUDGET_BYTES`], else
    /// every `f`-th pixel. The WGSL `land_class_at` is its
    /// [`LandCover::drawn_class_at`].
    #[must_use]
    pub fn gpu_copy(&self) -> Self {
        let (pixels, classes) = self.gpu_samples();
        Self {
            pixels,
            classes: classes
                .iter()
                .map(|&c| LandClass::ALL[(c as usize).min(LAND_CLASSES - 1)])
                .collect(),
        }
    }

    /// The GPU's copy: its pixels along x and z and each class as an `f32` (its
    /// index), from every `f`-th pixel ([`LandCover::decimation`] within
    /// [`LAND_COVER_GPU_BUDGET_BYTES`]; pixel `i` of the copy covers `[i/n,
    /// (i+1)/n)` of the extent and holds the raster's class at that span's centre).
    #[must_use]
    pub fn gpu_samples(&self) -> (UVec2, Vec<f32>) {
        let f = self.decimation(LAND_COVER_GPU_BUDGET_BYTES);
        if f == 1 {
            return (
                self.pixels,
                self.classes.iter().map(|&c| c as u32 as f32).collect(),
            );
        }
        // Pixel i of the copy covers [i/n, (i+1)/n): its class is the raster's at
        // the centre of that span.
        let n = UVec2::new(self.pixels.x.div_ceil(f), self.pixels.y.div_ceil(f));
        let mut v = Vec::with_capacity((n.x * n.y) as usize);
        for j in 0..n.y {
            for i in 0..n.x {
                let uv = (UVec2::new(i, j).as_vec2() + 0.5) / n.as_vec2();
                v.push(self.class_at(uv) as u32 as f32);
            }
        }
        (n, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worldcover_codes_name_their_classes_and_back() {
        for c in LandClass::ALL {
            assert_eq!(LandClass::from_worldcover(c.worldcover_code()), Some(c));
            assert_eq!(LandClass::ALL[c as usize], c);
        }
        assert_eq!(LandClass::from_worldcover(255), Some(LandClass::NoData));
        for bad in [1_u8, 11, 41, 85, 96, 101, 211, 254] {
            assert_eq!(LandClass::from_worldcover(bad), None, "{bad}");
        }
    }

    #[test]
    fn towns_are_paved_water_holds_no_snow_and_forests_hide_half() {
        assert_eq!(LandClass::BuiltUp.surface(), Some(Surface::Asphalt));
        assert_eq!(LandClass::Water.surface(), Some(Surface::Water));
        assert_eq!(LandClass::Grassland.surface(), Some(Surface::Grass));
        assert_eq!(LandClass::Cropland.surface(), Some(Surface::Soil));
        assert_eq!(LandClass::NoData.surface(), None);
        assert!(LandClass::Water.snow_share().abs() < 1e-6);
        assert!((LandClass::Trees.snow_share() - 0.5).abs() < 1e-6);
        assert!((LandClass::Grassland.snow_share() - 1.0).abs() < 1e-6);
        // A forest and water are darker than a field, ice the brightest.
        let lum = |c: LandClass| c.colour().iter().map(|&v| u32::from(v)).sum::<u32>();
        assert!(lum(LandClass::Trees) < lum(LandClass::Grassland));
        assert!(lum(LandClass::Water) < lum(LandClass::Grassland));
        assert!(
            LandClass::ALL
                .iter()
                .all(|&c| lum(c) <= lum(LandClass::SnowAndIce))
        );
    }

    #[test]
    fn bad_rasters_say_what_to_give() {
        let e = LandCover::from_worldcover(UVec2::new(0, 3), &[]).unwrap_err();
        assert!(e.to_string().contains("give 1 to"), "{e}");
        let e = LandCover::from_worldcover(UVec2::new(2, 2), &[10, 20, 30]).unwrap_err();
        assert!(matches!(e, LandCoverError::CodeCount { got: 3, .. }), "{e}");
        let e = LandCover::from_worldcover(UVec2::new(2, 2), &[10, 20, 30, 211]).unwrap_err();
        assert_eq!(
            e,
            LandCoverError::Code {
                code: 211,
                x: 1,
                z: 1
            }
        );
        assert!(e.to_string().contains("reclassifying"), "{e}");
    }

    #[test]
    fn each_pixel_covers_its_share_of_the_extent() {
        // 4 × 2: x in quarters, z in halves.
        let codes = [10, 20, 30, 40, 50, 60, 70, 80];
        let lc = LandCover::from_worldcover(UVec2::new(4, 2), &codes).expect("valid");
        assert_eq!(lc.class_at(Vec2::new(0.01, 0.01)), LandClass::Trees);
        assert_eq!(lc.class_at(Vec2::new(0.26, 0.49)), LandClass::Shrubs);
        assert_eq!(lc.class_at(Vec2::new(0.99, 0.51)), LandClass::Water);
        assert_eq!(lc.class_at(Vec2::new(0.5, 0.75)), LandClass::SnowAndIce);
        assert_eq!(lc.class_at(Vec2::new(-0.1, 0.5)), LandClass::NoData);
        assert_eq!(lc.class_at(Vec2::new(0.5, 1.0)), LandClass::NoData);
        assert_eq!(lc.class_at(Vec2::NAN), LandClass::NoData);
        let counts = lc.class_counts();
        assert_eq!(counts.iter().sum::<usize>(), 8);
        assert_eq!(counts[LandClass::NoData as usize], 0);
    }

    /// The drawn class is each pixel's at its centre and off the raster's edge
    /// pixels, and a staircase of pixels is drawn with a diagonal border: along a
    /// row through the steps' corners the border moves by as much as the row.
    #[test]
    fn the_drawn_class_is_the_pixel_s_at_its_centre_and_smooth_between() {
        let codes = [10, 20, 30, 40, 50, 60, 70, 80];
        let lc = LandCover::from_worldcover(UVec2::new(4, 2), &codes).expect("valid");
        for z in 0..2 {
            for x in 0..4 {
                let uv = (Vec2::new(x as f32, z as f32) + 0.5) / Vec2::new(4.0, 2.0);
                assert_eq!(lc.drawn_class_at(uv), lc.class_at(uv), "pixel {x} {z}");
            }
        }
        assert_eq!(lc.drawn_class_at(Vec2::new(0.001, 0.001)), LandClass::Trees);
        assert_eq!(lc.drawn_class_at(Vec2::new(0.999, 0.999)), LandClass::Water);
        assert_eq!(lc.drawn_class_at(Vec2::new(0.5, 1.0)), LandClass::NoData);
        assert_eq!(lc.drawn_class_at(Vec2::NAN), LandClass::NoData);
        // Trees (10) below a staircase, ice (70) above it, 8 × 8 pixels.
        let n = 8;
        let stairs: Vec<u8> = (0..n * n)
            .map(|k| if k % n > k / n { 70 } else { 10 })
            .collect();
        let lc = LandCover::from_worldcover(UVec2::splat(n as u32), &stairs).expect("valid");
        // Where along x, on row z (uv), the ice begins: nearest pixel jumps a
        // whole pixel every pixel of z; the drawn border moves with z.
        let border = |z: f32, at: fn(&LandCover, Vec2) -> LandClass| {
            (0..=800)
                .map(|k| k as f32 / 800.0 * 0.999)
                .find(|&x| at(&lc, Vec2::new(x, z)) == LandClass::SnowAndIce)
                .expect("ice along the row")
        };
        let rows: Vec<f32> = (0..=10)
            .map(|k| 0.3 + 0.1 * k as f32 / 10.0 * 1.25)
            .collect();
        let nearest: Vec<f32> = rows
            .iter()
            .map(|&z| border(z, LandCover::class_at))
            .collect();
        let drawn: Vec<f32> = rows
            .iter()
            .map(|&z| border(z, LandCover::drawn_class_at))
            .collect();
        let distinct = |v: &[f32]| {
            let mut d = v.to_vec();
            d.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
            d.len()
        };
        // Over one pixel of z, the nearest pixel's border takes 2 places, the
        // drawn one more than 5 (it slides along the diagonal).
        assert!(distinct(&nearest) <= 2, "{nearest:?}");
        assert!(distinct(&drawn) > 5, "{drawn:?}");
        for (z, x) in rows.iter().zip(&drawn) {
            assert!((x - z).abs() < 1.0 / n as f32, "row {z}: border at {x}");
        }
    }

    #[test]
    fn a_raster_over_the_budget_is_sent_from_every_f_th_pixel_and_fits() {
        let n = 3000_u32;
        let codes: Vec<u8> = (0..n * n)
            .map(|k| if (k % n) < n / 2 { 10 } else { 80 })
            .collect();
        let lc = LandCover::from_worldcover(UVec2::splat(n), &codes).expect("valid");
        let f = lc.decimation(LAND_COVER_GPU_BUDGET_BYTES);
        assert_eq!(f, 2, "9 Mi pixels of 4 bytes are over 16 MiB; 2.25 Mi fit");
        let (m, v) = lc.gpu_samples();
        assert_eq!(m, UVec2::splat(1500));
        assert_eq!(v.len(), 1500 * 1500);
        assert!(v.len() * 4 <= LAND_COVER_GPU_BUDGET_BYTES as usize);
        // West half trees, east half water, in the copy as in the raster.
        assert_eq!(v[10] as u32, LandClass::Trees as u32);
        assert_eq!(v[1490] as u32, LandClass::Water as u32);
        // A small one goes whole.
        let small = LandCover::from_worldcover(UVec2::new(2, 1), &[50, 80]).expect("valid");
        assert_eq!(small.gpu_samples(), (UVec2::new(2, 1), vec![5.0, 8.0]));
        assert_eq!(small.gpu_copy(), small);
        // The copy as a land cover: the GPU's pixels, the same classes.
        let copy = lc.gpu_copy();
        assert_eq!(copy.pixels(), m);
        assert_eq!(copy.class_at(Vec2::new(0.1, 0.5)), LandClass::Trees);
        assert_eq!(copy.drawn_class_at(Vec2::new(0.9, 0.5)), LandClass::Water);
    }
}
