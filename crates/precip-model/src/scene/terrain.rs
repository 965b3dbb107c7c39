//! [`Terrain`]: the ground from elevation data — a regular grid of heights (a 16-bit
//! PNG or GeoTIFF height map read by the viewer, or one generated in code) under
//! the scene's meshes, kilometres across.
//!
//! ## What it is for
//!
//! - **The ground map** ([`crate::GroundMap::from_scene_and_terrain`]): within the
//!   cover grid the terrain is part of the top-most surface, at its full resolution,
//!   so particles land on it and snow lies, drifts and melts on it. Its snow
//!   eligibility comes from its slope ([`crate::scene::slope_eligibility`], as a
//!   mesh's without tags), its surface is grass where it is gentle, soil where it is
//!   steep ([`TERRAIN_GRASS_SLOPE_DEG`]) — or, where it has a land cover
//!   ([`Terrain::with_land_cover`], [`crate::scene::land_cover`]), its class's
//!   surface (open water holding no snow); its class's share of snow seen from
//!   above weighs the snow drawn there, not the snow that lies.
//! - **The picture**: drawn as a *geometry clipmap* (Losasso & Hoppe 2004, *ACM
//!   Transactions on Graphics* 23(3)): nested square grids of [`CLIPMAP_QUADS`]²
//!   quads centred on the camera, each level's quads twice the size of the level
//!   inside it, its heights read from a pyramid of the terrain
//!   ([`TerrainPyramid`]) whose level `k` has samples `2^k` times as far apart. The
//!   count of triangles drawn is the same over a 100 m field and a 16 km range: the
//!   frame does not grow with the terrain. Levels finer than the camera's height
//!   above the ground needs are not drawn ([`TerrainPyramid::clipmap`]). Near its
//!   outer edge a level's heights and normals blend into the next level's over
//!   [`CLIPMAP_MORPH_QUADS`] quads, so at the edge both meet on the same line: no
//!   cracks, no popping. The vertex shader (`vs_terrain`,
//!   `precip-gpu/shaders/render_terrain.wgsl`) is the twin of [`clipmap_vertex`].
//!
//! ## The GPU's copy: a window of each level round the camera
//!
//! The host keeps the whole pyramid at the terrain's full resolution (level 0 is
//! the terrain's own heights, shared; the coarser levels add a third: 16 384²
//! samples take 1 GiB of `f32` and the pyramid 0.33 GiB more); the GPU holds, for each level, only the
//! [`CLIPMAP_WINDOW_SAMPLES`]² samples round where that level is drawn now
//! ([`TerrainPyramid::window_origin`], [`TerrainPyramid::window`]), one copy per
//! frame in flight ([`CLIPMAP_WINDOW_SLOTS`]), in the ground buffer after the
//! ground map's words. A level's window is written again only when the camera
//! has moved it (every other sample of that level), so a camera at rest uploads
//! nothing and one flying at 70 m/s over a 0.6 m terrain a few windows of 16 KiB a
//! frame. The GPU's memory for the terrain is bounded whatever its size (16 KiB
//! a level and a frame slot: at most 16 levels × 16 KiB × 2; 384 KiB for
//! 16 384², 256 KiB for 1 000²), and every level is drawn from every sample.
//! The clipmap reads no sample beyond its window: [`ClipmapWindows`] evaluates the
//! vertices from the windows alone, and a property test checks they are the
//! pyramid's bit for bit wherever the camera is, on the terrain or off it.

use std::sync::Arc;

use glam::{UVec2, Vec2, Vec3};

use crate::scene::land_cover::{LAND_CLASSES, LandClass, LandCover};
use crate::scene::slope_eligibility;

/// Quads along a side of each level of the clipmap. WGSL twin: `CLIPMAP_QUADS`.
pub const CLIPMAP_QUADS: u32 = 48;
/// Quads over which a level blends into the next near its outer edge. WGSL twin:
/// `CLIPMAP_MORPH_QUADS`.
pub const CLIPMAP_MORPH_QUADS: u32 = 8;
/// A level's grid vertices, shared by the quads around them: `(CLIPMAP_QUADS + 1)²`.
pub const CLIPMAP_GRID_VERTICES: u32 = (CLIPMAP_QUADS + 1) * (CLIPMAP_QUADS + 1);
/// The quads round a level's hole that are in it or not by where the finer level
/// stands (its centre is 0 or 1 of this level's quads off along each axis): the
/// ring of side `CLIPMAP_QUADS / 2 + 1` quads from quad `CLIPMAP_QUADS / 4`,
/// `2 · CLIPMAP_QUADS` of them. Each has six vertices of its own, so it is drawn or
/// not by itself ([`clipmap_vertex`]).
pub const CLIPMAP_EDGE_QUADS: u32 = 2 * CLIPMAP_QUADS;
/// Vertex numbers a level takes: its grid's, then its edge quads' six each. WGSL
/// twin: `CLIPMAP_LEVEL_VERTICES`.
pub const CLIPMAP_LEVEL_VERTICES: u32 = CLIPMAP_GRID_VERTICES + 6 * CLIPMAP_EDGE_QUADS;
/// Indices a level draws: two triangles a quad ([`clipmap_indices`]).
pub const CLIPMAP_LEVEL_INDICES: u32 = CLIPMAP_QUADS * CLIPMAP_QUADS * 6;
/// The most levels of a pyramid (the frame block's rows hold their offsets).
pub const MAX_TERRAIN_LEVELS: usize = 16;
/// The most samples along a side of a terrain.
pub const MAX_TERRAIN_SAMPLES: u32 = 16_384;
/// Samples along a side of a level's window on the GPU (its clipmap reaches
/// `CLIPMAP_QUADS / 2 + 1` samples round the level's centre, and a level's morph
/// half as far into the next: [`ClipmapWindows`]). WGSL twin:
/// `CLIPMAP_WINDOW_SAMPLES`.
pub const CLIPMAP_WINDOW_SAMPLES: u32 = 64;
/// Words of a level's window.
pub const CLIPMAP_WINDOW_WORDS: u32 = CLIPMAP_WINDOW_SAMPLES * CLIPMAP_WINDOW_SAMPLES;
/// Copies of the windows on the GPU, one per frame in flight: a frame's windows
/// are written while the frame before may still read its own. At least every
/// backend's slots (`precip_gpu::Gpu::slots`).
pub const CLIPMAP_WINDOW_SLOTS: u32 = 2;
/// Heights beyond this, m, are refused (a datum or a scale gone wrong).
pub const MAX_TERRAIN_HEIGHT_M: f32 = 20_000.0;
/// Slope up to which the terrain is grass, beyond it soil, degrees.
pub const TERRAIN_GRASS_SLOPE_DEG: f32 = 25.0;

/// What is wrong with a terrain.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// Too few or too many samples along a side.
    #[error("the terrain has {x} × {z} samples: give 2 to {MAX_TERRAIN_SAMPLES} along each side")]
    Samples {
        /// Along x.
        x: u32,
        /// Along z.
        z: u32,
    },
    /// The spacing is not a positive finite length.
    #[error("the terrain's spacing is {0} m: give the metres between samples, above 0")]
    Spacing(f32),
    /// The centre is not finite.
    #[error("the terrain's centre is not finite: give x and z in metres")]
    Centre,
    /// The heights do not match the samples.
    #[error("the terrain has {got} heights for {x} × {z} samples: give one per sample")]
    HeightCount {
        /// Heights given.
        got: usize,
        /// Along x.
        x: u32,
        /// Along z.
        z: u32,
    },
    /// A height is not finite or out of range.
    #[error(
        "the terrain's sample ({x}, {z}) is {height_m} m: heights must be finite and within ±{MAX_TERRAIN_HEIGHT_M} m (check the height scale and offset)"
    )]
    Height {
        /// Column.
        x: u32,
        /// Row.
        z: u32,
        /// Its height, m.
        height_m: f32,
    },
}

/// Heights on a regular grid: sample `(i, j)` at world
/// `(corner.x + i·spacing, height, corner.z + j·spacing)`, rows along z.
#[derive(Debug, Clone, PartialEq)]
pub struct Terrain {
    samples: UVec2,
    spacing_m: f32,
    corner_m: Vec2,
    heights_m: Vec<f32>,
    land_cover: Option<LandCover>,
}

impl Terrain {
    /// A terrain of `samples` (x, z) heights `spacing_m` apart, centred on
    /// `centre_m` (x, z); `heights_m` row by row (x fastest), m.
    pub fn new(
        samples: UVec2,
        spacing_m: f32,
        centre_m: Vec2,
        heights_m: Vec<f32>,
    ) -> Result<Self, TerrainError> {
        let (x, z) = (samples.x, samples.y);
        if !(2..=MAX_TERRAIN_SAMPLES).contains(&x) || !(2..=MAX_TERRAIN_SAMPLES).contains(&z) {
            return Err(TerrainError::Samples { x, z });
        }
        if !(spacing_m.is_finite() && spacing_m > 0.0 && spacing_m < 1.0e5) {
            return Err(TerrainError::Spacing(spacing_m));
        }
        if !centre_m.is_finite() {
            return Err(TerrainError::Centre);
        }
        if heights_m.len() != (x as usize) * (z as usize) {
            return Err(TerrainError::HeightCount {
                got: heights_m.len(),
                x,
                z,
            });
        }
        if let Some(k) = heights_m
            .iter()
            .position(|h| !(h.is_finite() && h.abs() <= MAX_TERRAIN_HEIGHT_M))
        {
            return Err(TerrainError::Height {
                x: (k % x as usize) as u32,
                z: (k / x as usize) as u32,
                height_m: heights_m[k],
            });
        }
        let size = (samples - 1).as_vec2() * spacing_m;
        Ok(Self {
            samples,
            spacing_m,
            corner_m: centre_m - 0.5 * size,
            heights_m,
            land_cover: None,
        })
    }

    /// The terrain with `land_cover` over its extent (module docs of
    /// [`crate::scene::land_cover`]).
    #[must_use]
    pub fn with_land_cover(mut self, land_cover: LandCover) -> Self {
        self.land_cover = Some(land_cover);
        self
    }

    /// Its land cover, if it has one.
    #[must_use]
    pub fn land_cover(&self) -> Option<&LandCover> {
        self.land_cover.as_ref()
    }

    /// The land-cover class at world `(x, z)` (no data without a raster or off it).
    #[must_use]
    pub fn land_class_at(&self, xz_m: Vec2) -> LandClass {
        self.land_cover.as_ref().map_or(LandClass::NoData, |l| {
            l.class_at((xz_m - self.corner_m) / self.size_m())
        })
    }

    /// The surface at world `(x, z)` where the normal is `normal`: its land class's,
    /// else the slope's ([`Terrain::surface_for`]).
    #[must_use]
    pub fn surface_at(&self, xz_m: Vec2, normal: Vec3) -> precip_cover::Surface {
        self.land_class_at(xz_m)
            .surface()
            .unwrap_or_else(|| Self::surface_for(normal))
    }

    /// Snow eligibility at world `(x, z)` where the normal is `normal`: the
    /// slope's, none on open water (what lands there joins it). The share of a
    /// class's snow seen from above ([`LandClass::snow_share`]: half under a
    /// forest's canopy) weighs only its drawing: the snow under the trees lies and
    /// is in the books as any other.
    #[must_use]
    pub fn eligibility_at(&self, xz_m: Vec2, normal: Vec3) -> f32 {
        if self.land_class_at(xz_m) == LandClass::Water {
            0.0
        } else {
            Self::eligibility_for(normal)
        }
    }

    /// Samples along x and z.
    #[must_use]
    pub fn samples(&self) -> UVec2 {
        self.samples
    }

    /// Metres between samples.
    #[must_use]
    pub fn spacing_m(&self) -> f32 {
        self.spacing_m
    }

    /// World (x, z) of sample (0, 0), m.
    #[must_use]
    pub fn corner_m(&self) -> Vec2 {
        self.corner_m
    }

    /// The side lengths along x and z, m.
    #[must_use]
    pub fn size_m(&self) -> Vec2 {
        (self.samples - 1).as_vec2() * self.spacing_m
    }

    /// The heights, row by row, m.
    #[must_use]
    pub fn heights_m(&self) -> &[f32] {
        &self.heights_m
    }

    /// The lowest and highest heights, m.
    #[must_use]
    pub fn height_range_m(&self) -> (f32, f32) {
        self.heights_m
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &h| {
                (lo.min(h), hi.max(h))
            })
    }

    /// The terrain raised or lowered as a whole so that its height at `xz_m` is
    /// `height_m` (unchanged where `xz_m` is off it).
    #[must_use]
    pub fn with_height_at(mut self, xz_m: Vec2, height_m: f32) -> Self {
        if let Some(h) = self.height_at(xz_m) {
            let shift = height_m - h;
            for v in &mut self.heights_m {
                *v += shift;
            }
        }
        self
    }

    fn sample(&self, i: i64, j: i64) -> f32 {
        let i = i.clamp(0, i64::from(self.samples.x) - 1) as usize;
        let j = j.clamp(0, i64::from(self.samples.y) - 1) as usize;
        self.heights_m[i + self.samples.x as usize * j]
    }

    /// The height at world `(x, z)` between samples (bilinear), m; `None` off the
    /// terrain.
    #[must_use]
    pub fn height_at(&self, xz_m: Vec2) -> Option<f32> {
        let t = (xz_m - self.corner_m) / self.spacing_m;
        let last = (self.samples - 1).as_vec2();
        if !(t.x >= 0.0 && t.y >= 0.0 && t.x <= last.x && t.y <= last.y) {
            return None;
        }
        let base = t.floor();
        let w = t - base;
        let (i, j) = (base.x as i64, base.y as i64);
        let low = self.sample(i, j) + (self.sample(i + 1, j) - self.sample(i, j)) * w.x;
        let high =
            self.sample(i, j + 1) + (self.sample(i + 1, j + 1) - self.sample(i, j + 1)) * w.x;
        Some(low + (high - low) * w.y)
    }

    /// The unit normal at world `(x, z)` (central differences one spacing apart,
    /// clamped at the edges); up off the terrain.
    #[must_use]
    pub fn normal_at(&self, xz_m: Vec2) -> Vec3 {
        let s = self.spacing_m;
        let h = |dx: f32, dz: f32| self.height_at(xz_m + Vec2::new(dx, dz));
        match (h(-s, 0.0), h(s, 0.0), h(0.0, -s), h(0.0, s), h(0.0, 0.0)) {
            (Some(w), Some(e), Some(n), Some(so), _) => {
                Vec3::new(w - e, 2.0 * s, n - so).normalize_or(Vec3::Y)
            }
            (w, e, n, so, Some(c)) => {
                let (w, e, n, so) = (
                    w.unwrap_or(c),
                    e.unwrap_or(c),
                    n.unwrap_or(c),
                    so.unwrap_or(c),
                );
                Vec3::new(w - e, 2.0 * s, n - so).normalize_or(Vec3::Y)
            }
            _ => Vec3::Y,
        }
    }

    /// What the terrain is made of where its normal is `normal`: grass up to
    /// [`TERRAIN_GRASS_SLOPE_DEG`], soil beyond.
    #[must_use]
    pub fn surface_for(normal: Vec3) -> precip_cover::Surface {
        if normal.y >= TERRAIN_GRASS_SLOPE_DEG.to_radians().cos() {
            precip_cover::Surface::Grass
        } else {
            precip_cover::Surface::Soil
        }
    }

    /// Snow eligibility where the normal is `normal` (the slope's, as an untagged
    /// mesh's).
    #[must_use]
    pub fn eligibility_for(normal: Vec3) -> f32 {
        slope_eligibility(normal)
    }
}

/// The cosine between a terrain fragment's bent normal and the view
/// ([`facing_normal`]). WGSL twin: `TERRAIN_EDGE_ON`.
pub const TERRAIN_EDGE_ON: f32 = 0.001;

/// A terrain fragment's shading normal for a viewer in direction `to_viewer`
/// (unit): the normal itself where it faces the viewer; where the normal
/// interpolated over a face seen edge-on turns away (a crest's outline against
/// the ground behind it), the normal bent to lie across the view, at
/// [`TERRAIN_EDGE_ON`] toward it. A height field is seen from above: flipped as a
/// mesh's underside is, such a normal pointed down and lit every crest's outline
/// dark. WGSL twin: `terrain_facing_normal`.
#[must_use]
pub fn facing_normal(normal: Vec3, to_viewer: Vec3) -> Vec3 {
    let n = normal.normalize_or_zero();
    let d = n.dot(to_viewer);
    if d >= 0.0 {
        return n;
    }
    (n - (d - TERRAIN_EDGE_ON) * to_viewer).normalize_or_zero()
}

/// Texels of the terrain's colour ramp ([`terrain_ramp`]).
pub const TERRAIN_RAMP_TEXELS: u32 = 16;

/// Where along the terrain's colour ramp a surface of unit normal `normal` reads
/// (texel centres only, so the repeating sampler never wraps): flat at the first
/// texel's centre, 60° and steeper at the last's. WGSL twin:
/// `terrain_scene_vertex`'s `uv`.
#[must_use]
pub fn terrain_ramp_u(normal: Vec3) -> f32 {
    let steep = ((1.0 - normal.y) * 2.0).clamp(0.0, 1.0);
    let n = TERRAIN_RAMP_TEXELS as f32;
    (0.5 + (n - 1.0) * steep) / n
}

/// Where down the terrain's colour ramp land class `class` reads (its row's
/// centre). WGSL twin: `fs_terrain`'s `uv.y`.
#[must_use]
pub fn terrain_ramp_v(class: LandClass) -> f32 {
    (class as u32 as f32 + 0.5) / LAND_CLASSES as f32
}

/// The terrain's colours (sRGB): a row per land class ([`LandClass`] order; row 0,
/// no data, what the slope alone says), by slope along it, flat to steep. Each
/// class's colour holds to 35° (forests grow on steep sides) and gives way to grey
/// rock from 35° to 50°; row 0 is winter grass up to about 25°, bare soil to 45°,
/// rock beyond.
#[must_use]
pub fn terrain_ramp() -> crate::TextureRgba8 {
    const SOIL: [f32; 3] = [112.0, 96.0, 74.0];
    const ROCK: [f32; 3] = [122.0, 120.0, 114.0];
    let n = TERRAIN_RAMP_TEXELS;
    let mut rgba8 = Vec::with_capacity(4 * n as usize * LAND_CLASSES);
    let blend = |a: [f32; 3], b: [f32; 3], t: f32| {
        let t = t.clamp(0.0, 1.0);
        [0, 1, 2].map(|c| a[c] + (b[c] - a[c]) * t)
    };
    for class in LandClass::ALL {
        let flat = class.colour().map(f32::from);
        let to_rock = class != LandClass::NoData;
        for i in 0..n {
            // The texel's slope: back from terrain_ramp_u.
            let steep = i as f32 / (n - 1) as f32;
            let up = 1.0 - 0.5 * steep;
            let slope_deg = up.clamp(-1.0, 1.0).acos().to_degrees();
            let rock = (slope_deg - 35.0) / 15.0;
            let colour = if to_rock {
                blend(flat, ROCK, rock)
            } else if slope_deg < 35.0 {
                blend(flat, SOIL, (slope_deg - 20.0) / 15.0)
            } else {
                blend(SOIL, ROCK, rock)
            };
            rgba8.extend(colour.map(|c| c.round() as u8));
            rgba8.push(255);
        }
    }
    crate::TextureRgba8 {
        width_px: n,
        height_px: LAND_CLASSES as u32,
        rgba8,
    }
}

/// A terrain shared between the scene and the backends.
pub type SharedTerrain = Arc<Terrain>;

/// One level of a [`TerrainPyramid`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PyramidLevel {
    /// Samples along x and z.
    pub samples: UVec2,
    /// Metres between samples.
    pub spacing_m: f32,
    /// Its first word in [`TerrainPyramid::heights_m`] (level 0's in the
    /// terrain's own heights: 0).
    pub offset: u32,
}

/// The terrain's levels for the clipmap: level 0 the terrain at its full
/// resolution, level `k + 1` level `k` filtered by `[1 2 1]/4`
/// along each axis and kept at every other sample, so its sample `i` lies on level
/// `k`'s sample `2i`, down to a level of at most [`CLIPMAP_QUADS`]` / 4` samples a
/// side (whose clipmap level covers the whole terrain from anywhere on it).
#[derive(Debug, Clone, PartialEq)]
pub struct TerrainPyramid {
    /// The levels, finest first.
    pub levels: Vec<PyramidLevel>,
    /// Level 0: the terrain itself, shared (its heights are not copied).
    pub terrain: SharedTerrain,
    /// The coarser levels' heights, row by row, one after the other, m.
    pub heights_m: Vec<f32>,
    /// World (x, z) of every level's sample (0, 0), m.
    pub corner_m: Vec2,
}

/// The rows of the frame block that place the clipmap (`RenderParams::terrain*`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClipmapRows {
    /// The pyramid's corner x, z m, level 0's spacing m, the levels drawn (0: none).
    pub placement: glam::Vec4,
    /// The first level drawn, the pyramid's levels, the word where the frame's
    /// windows start in the ground buffer ([`TerrainPyramid::window`], level by
    /// level), the first level the water's mirror draws ([`MIRROR_SKIPPED_LEVELS`]
    /// coarser, at most the last).
    pub levels: glam::UVec4,
    /// Level `k`'s samples along x (`.x` of row `k / 2`'s pair) and z, two levels a
    /// row: (x₀, z₀, x₁, z₁), …
    pub samples: [glam::UVec4; MAX_TERRAIN_LEVELS / 2],
    /// Level `k`'s window origin ([`TerrainPyramid::window_origin`]), x and z as
    /// two `i16` in a word (x low), four levels a row
    /// ([`ClipmapRows::window_origin`]).
    pub windows: [glam::UVec4; MAX_TERRAIN_LEVELS / 4],
}

/// The rows of the frame block that place the terrain's land cover
/// (`RenderParams::land_cover*`; [`crate::host::HostState::land_cover_rows`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LandCoverRows {
    /// The GPU copy's pixels along x and z, its first word in the ground buffer,
    /// and 1 (0: no land cover).
    pub pixels: glam::UVec4,
    /// The terrain's corner x, z and its size along x and z, m.
    pub extent_m: glam::Vec4,
}

impl ClipmapRows {
    /// Level `k`'s window origin as the frame block holds it (WGSL twin:
    /// `terrain_window_origin`).
    #[must_use]
    pub fn window_origin(&self, k: usize) -> glam::IVec2 {
        let w = self.windows[(k / 4) % (MAX_TERRAIN_LEVELS / 4)][k % 4];
        glam::IVec2::new(
            i32::from(w as u16 as i16),
            i32::from((w >> 16) as u16 as i16),
        )
    }

    /// Indices the clipmap draws, from the start of [`clipmap_indices`] (0
    /// without a terrain).
    #[must_use]
    pub fn indices(&self) -> u32 {
        self.placement.w as u32 * CLIPMAP_LEVEL_INDICES
    }

    /// Indices the clipmap draws into the water's mirror: from its first level
    /// (`levels.w`) to the last (0 without a terrain).
    #[must_use]
    pub fn mirror_indices(&self) -> u32 {
        if self.placement.w < 1.0 {
            return 0;
        }
        self.levels.y.saturating_sub(self.levels.w) * CLIPMAP_LEVEL_INDICES
    }
}

/// Levels of the clipmap the water's mirror leaves out at the fine end: its image
/// is drawn at half the frame's side and shows the distant terrain above the
/// water (the near ground round a pond is the scene's meshes), so its finest
/// levels would be all vertices and no pixels; the coarser level fills the hole.
pub const MIRROR_SKIPPED_LEVELS: u32 = 2;

impl TerrainPyramid {
    /// The pyramid of `terrain`, level 0 every sample of it (the terrain's own
    /// heights, shared).
    #[must_use]
    pub fn of(terrain: &SharedTerrain) -> Self {
        let mut samples = terrain.samples;
        let mut spacing = terrain.spacing_m;
        let mut levels = vec![PyramidLevel {
            samples,
            spacing_m: spacing,
            offset: 0,
        }];
        let mut heights_m = Vec::new();
        // The last level's words in `heights_m` (`None`: the terrain's own).
        let mut last: Option<std::ops::Range<usize>> = None;
        while samples.max_element() > CLIPMAP_QUADS / 4 && levels.len() < MAX_TERRAIN_LEVELS {
            let level: &[f32] = match &last {
                None => &terrain.heights_m,
                Some(r) => &heights_m[r.clone()],
            };
            let next = (samples - 1) / 2 + 1;
            let at = |i: i64, j: i64| {
                let i = i.clamp(0, i64::from(samples.x) - 1) as usize;
                let j = j.clamp(0, i64::from(samples.y) - 1) as usize;
                level[i + samples.x as usize * j]
            };
            let mut coarse = Vec::with_capacity((next.x * next.y) as usize);
            for j in 0..i64::from(next.y) {
                for i in 0..i64::from(next.x) {
                    let (ci, cj) = (2 * i, 2 * j);
                    let row = |dj: i64| {
                        0.25 * at(ci - 1, cj + dj)
                            + 0.5 * at(ci, cj + dj)
                            + 0.25 * at(ci + 1, cj + dj)
                    };
                    coarse.push(0.25 * row(-1) + 0.5 * row(0) + 0.25 * row(1));
                }
            }
            let first = heights_m.len();
            heights_m.extend_from_slice(&coarse);
            last = Some(first..heights_m.len());
            samples = next;
            spacing *= 2.0;
            levels.push(PyramidLevel {
                samples,
                spacing_m: spacing,
                offset: first as u32,
            });
        }
        Self {
            levels,
            terrain: Arc::clone(terrain),
            heights_m,
            corner_m: terrain.corner_m,
        }
    }

    /// Level 0's height at its sample nearest `xz_m` (clamped to the terrain), m.
    #[must_use]
    pub fn height_under(&self, xz_m: Vec2) -> f32 {
        let Some(level) = self.levels.first() else {
            return 0.0;
        };
        let t = ((xz_m - self.corner_m) / level.spacing_m).round();
        self.height(0, t.x as i32, t.y as i32)
    }

    /// Level `k`'s height at its sample `(i, j)` (clamped to the level), m.
    #[must_use]
    pub fn height(&self, k: usize, i: i32, j: i32) -> f32 {
        let Some(l) = self.levels.get(k).filter(|l| l.samples.min_element() > 0) else {
            return 0.0;
        };
        let i = i.clamp(0, l.samples.x as i32 - 1) as u32;
        let j = j.clamp(0, l.samples.y as i32 - 1) as u32;
        let words = if k == 0 {
            &self.terrain.heights_m
        } else {
            &self.heights_m
        };
        words
            .get((l.offset + i + l.samples.x * j) as usize)
            .copied()
            .unwrap_or(0.0)
    }

    /// The levels the clipmap draws for a camera at `camera_m` whose ground is
    /// `ground_m` below it… : from the finest whose half side
    /// (`CLIPMAP_QUADS / 2` quads) reaches twice the camera's height above the
    /// terrain's highest point under it (finer ones would be under a pixel), to
    /// the last; `windows_word` is where the frame's windows start in the ground
    /// buffer, and each level's window is placed round the camera
    /// ([`TerrainPyramid::window_origin`]).
    #[must_use]
    pub fn clipmap(&self, camera_m: Vec3, ground_m: f32, windows_word: u32) -> ClipmapRows {
        // A pyramid built by hand without levels draws nothing.
        if self.levels.is_empty() || self.levels.len() > MAX_TERRAIN_LEVELS {
            return ClipmapRows::default();
        }
        let above = (camera_m.y - ground_m).max(0.0);
        let half_side = |k: usize| (CLIPMAP_QUADS / 2) as f32 * self.levels[k].spacing_m;
        let last = self.levels.len() - 1;
        let first = (0..=last)
            .find(|&k| half_side(k) >= 2.0 * above)
            .unwrap_or(last);
        let mut rows = ClipmapRows {
            placement: glam::Vec4::new(
                self.corner_m.x,
                self.corner_m.y,
                self.levels[0].spacing_m,
                (last - first + 1) as f32,
            ),
            levels: glam::UVec4::new(
                first as u32,
                self.levels.len() as u32,
                windows_word,
                (first as u32 + MIRROR_SKIPPED_LEVELS).min(last as u32),
            ),
            ..ClipmapRows::default()
        };
        for (k, l) in self.levels.iter().enumerate() {
            let row = &mut rows.samples[k / 2];
            if k % 2 == 0 {
                row.x = l.samples.x;
                row.y = l.samples.y;
            } else {
                row.z = l.samples.x;
                row.w = l.samples.y;
            }
            let o = self
                .window_origin(k, Vec2::new(camera_m.x, camera_m.z))
                .unwrap_or_default();
            rows.windows[k / 4][k % 4] =
                u32::from(o.x as i16 as u16) | u32::from(o.y as i16 as u16) << 16;
        }
        rows
    }

    /// Words of one frame's windows: [`CLIPMAP_WINDOW_WORDS`] a level.
    #[must_use]
    pub fn window_words(&self) -> u32 {
        self.levels.len() as u32 * CLIPMAP_WINDOW_WORDS
    }

    /// Level `k`'s sample at the corner of its window for a camera over
    /// `camera_xz_m`: the window's middle on the level's centre
    /// ([`clipmap_centre`]), clamped to the level (a camera off the terrain draws
    /// its edge). Between `−CLIPMAP_WINDOW_SAMPLES / 2` and the level's last
    /// sample, so it fits an `i16` ([`MAX_TERRAIN_SAMPLES`]).
    #[must_use]
    pub fn window_origin(&self, k: usize, camera_xz_m: Vec2) -> Option<glam::IVec2> {
        let last = self.levels.get(k)?.samples.as_ivec2() - 1;
        let centre = clipmap_centre(self, k, camera_xz_m)?;
        Some(
            centre.clamp(glam::IVec2::ZERO, last.max(glam::IVec2::ZERO))
                - (CLIPMAP_WINDOW_SAMPLES / 2) as i32,
        )
    }

    /// Level `k`'s window from `origin`: [`CLIPMAP_WINDOW_SAMPLES`]² heights row
    /// by row, its sample `p` the level's `origin + p` (clamped to the level).
    #[must_use]
    pub fn window(&self, k: usize, origin: glam::IVec2) -> Vec<f32> {
        let n = CLIPMAP_WINDOW_SAMPLES as i32;
        let mut words = Vec::with_capacity(CLIPMAP_WINDOW_WORDS as usize);
        for j in 0..n {
            for i in 0..n {
                words.push(self.height(k, origin.x + i, origin.y + j));
            }
        }
        words
    }
}

/// The heights the GPU holds for a frame: every level's window placed by
/// [`TerrainPyramid::clipmap`]'s rows. The clipmap's vertices evaluated from them
/// ([`ClipmapWindows::vertex`]) are the GPU's (`terrain_height` reads the window,
/// its sample clamped to it); a property test holds them to [`clipmap_vertex`]'s
/// from the whole pyramid.
#[derive(Debug, Clone, PartialEq)]
pub struct ClipmapWindows {
    /// Each level's origin.
    pub origins: Vec<glam::IVec2>,
    /// Each level's window, one after the other.
    pub heights_m: Vec<f32>,
}

impl ClipmapWindows {
    /// The windows of `pyramid` placed as `rows` say.
    #[must_use]
    pub fn of(pyramid: &TerrainPyramid, rows: &ClipmapRows) -> Self {
        let origins: Vec<_> = (0..pyramid.levels.len())
            .map(|k| rows.window_origin(k))
            .collect();
        let heights_m = origins
            .iter()
            .enumerate()
            .flat_map(|(k, &o)| pyramid.window(k, o))
            .collect();
        Self { origins, heights_m }
    }

    /// Level `k`'s height at its sample `(i, j)` as the GPU reads it: the
    /// window's sample, clamped to the window. WGSL twin: `terrain_height`.
    #[must_use]
    pub fn height(&self, k: usize, i: i32, j: i32) -> f32 {
        let Some(o) = self.origins.get(k) else {
            return 0.0;
        };
        let last = CLIPMAP_WINDOW_SAMPLES as i32 - 1;
        let p = (glam::IVec2::new(i, j) - *o).clamp(glam::IVec2::ZERO, glam::IVec2::splat(last));
        self.heights_m
            .get(k * CLIPMAP_WINDOW_WORDS as usize + (p.x + (last + 1) * p.y) as usize)
            .copied()
            .unwrap_or(0.0)
    }

    /// [`clipmap_vertex`] from the windows alone (the GPU's `clipmap_vertex`).
    #[must_use]
    pub fn vertex(
        &self,
        pyramid: &TerrainPyramid,
        first: usize,
        camera_xz_m: Vec2,
        v: u32,
    ) -> Option<(Vec3, Vec3)> {
        vertex_from(
            pyramid,
            &|k, i, j| self.height(k, i, j),
            first,
            camera_xz_m,
            v,
        )
    }
}

/// The snapped centre of clipmap level `k` in its own samples: the camera's sample
/// rounded down to an even one, so the level's vertices lie on the next level's
/// samples every other one. WGSL twin: `clipmap_centre`.
#[must_use]
pub fn clipmap_centre(
    pyramid: &TerrainPyramid,
    k: usize,
    camera_xz_m: Vec2,
) -> Option<glam::IVec2> {
    let spacing = pyramid.levels.get(k)?.spacing_m;
    let t = ((camera_xz_m - pyramid.corner_m) / spacing).floor();
    let even = |v: f32| 2 * ((v as i32).div_euclid(2));
    Some(glam::IVec2::new(even(t.x), even(t.y)))
}

/// The corners of a quad's two triangles, `(i, j)` steps from its first sample:
/// (0,0) (0,1) (1,0), (1,0) (0,1) (1,1).
const QUAD_CORNERS: [(u32, u32); 6] = [(0, 0), (0, 1), (1, 0), (1, 0), (0, 1), (1, 1)];

/// Edge quad `m` of a level ([`CLIPMAP_EDGE_QUADS`]): its quad `(a, b)` in the
/// level's `CLIPMAP_QUADS`² (the ring's bottom row, its top row, then its left and
/// right columns between them).
fn clipmap_edge_quad(m: u32) -> (u32, u32) {
    let lo = CLIPMAP_QUADS / 4;
    let side = CLIPMAP_QUADS / 2 + 1;
    let hi = lo + side - 1;
    match m {
        m if m < side => (lo + m, lo),
        m if m < 2 * side => (lo + m - side, hi),
        m if m < 3 * side - 2 => (lo, lo + 1 + m - 2 * side),
        m => (hi, lo + 1 + m - (3 * side - 2)),
    }
}

/// The clipmap's index buffer for `levels` levels (at most
/// [`MAX_TERRAIN_LEVELS`]): level by level, its quads row by row, two triangles a
/// quad; a quad's corners are the level's shared grid vertices, but an edge quad's
/// are its own six ([`CLIPMAP_LEVEL_VERTICES`] numbers a level). Sharing lets a
/// GPU shade a grid vertex once for the up to six triangles round it, where the
/// unindexed draw shaded it for each.
#[must_use]
pub fn clipmap_indices(levels: u32) -> Vec<u32> {
    let levels = levels.min(MAX_TERRAIN_LEVELS as u32);
    let side = CLIPMAP_QUADS + 1;
    let mut edge_of = vec![u32::MAX; (CLIPMAP_QUADS * CLIPMAP_QUADS) as usize];
    for m in 0..CLIPMAP_EDGE_QUADS {
        let (a, b) = clipmap_edge_quad(m);
        edge_of[(a + CLIPMAP_QUADS * b) as usize] = m;
    }
    let mut indices = Vec::with_capacity((levels * CLIPMAP_LEVEL_INDICES) as usize);
    for level in 0..levels {
        let base = level * CLIPMAP_LEVEL_VERTICES;
        for b in 0..CLIPMAP_QUADS {
            for a in 0..CLIPMAP_QUADS {
                let edge = edge_of[(a + CLIPMAP_QUADS * b) as usize];
                for (c, (ci, cj)) in (0..).zip(QUAD_CORNERS) {
                    indices.push(if edge == u32::MAX {
                        base + (a + ci) + side * (b + cj)
                    } else {
                        base + CLIPMAP_GRID_VERTICES + 6 * edge + c
                    });
                }
            }
        }
    }
    indices
}

/// A vertex of the clipmap: vertex number `v` of the draw whose first level is
/// `first` ([`clipmap_indices`]' numbers): its world position and normal, or
/// `None` where it is not drawn — a grid vertex inside the hole the finer level
/// fills whatever its place (only the hole's quads use them), an edge quad's in
/// the hole where the finer level stands now. Samples beyond the terrain are
/// clamped to its edge, so a quad wholly off it collapses to a line and draws
/// nothing. WGSL twin: `vs_terrain`'s `clipmap_vertex` (which reads the heights
/// from the windows: [`ClipmapWindows::vertex`]).
#[must_use]
pub fn clipmap_vertex(
    pyramid: &TerrainPyramid,
    first: usize,
    camera_xz_m: Vec2,
    v: u32,
) -> Option<(Vec3, Vec3)> {
    vertex_from(
        pyramid,
        &|k, i, j| pyramid.height(k, i, j),
        first,
        camera_xz_m,
        v,
    )
}

/// Level `k`'s height at its sample `(i, j)`, from the whole pyramid or from the
/// windows.
type LevelHeight<'a> = dyn Fn(usize, i32, i32) -> f32 + 'a;

/// [`clipmap_vertex`] with its heights from `height`.
fn vertex_from(
    pyramid: &TerrainPyramid,
    height: &LevelHeight<'_>,
    first: usize,
    camera_xz_m: Vec2,
    v: u32,
) -> Option<(Vec3, Vec3)> {
    let n = CLIPMAP_QUADS as i32;
    let k = first + (v / CLIPMAP_LEVEL_VERTICES) as usize;
    let level = pyramid
        .levels
        .get(k)
        .filter(|l| l.samples.min_element() >= 2)?;
    let local = v % CLIPMAP_LEVEL_VERTICES;
    let centre = clipmap_centre(pyramid, k, camera_xz_m)?;
    let (i, j) = if local < CLIPMAP_GRID_VERTICES {
        let (i, j) = (local % (CLIPMAP_QUADS + 1), local / (CLIPMAP_QUADS + 1));
        // The grid vertices only the hole's quads use (never any edge quad's).
        let hole = (CLIPMAP_QUADS / 4 + 1)..=(3 * CLIPMAP_QUADS / 4);
        if k > first && hole.contains(&i) && hole.contains(&j) {
            return None;
        }
        (i, j)
    } else {
        let m = (local - CLIPMAP_GRID_VERTICES) / 6;
        let (a, b) = clipmap_edge_quad(m);
        if k > first {
            // Inside level k − 1 (its centre in level k's samples ± n/4).
            let inner = clipmap_centre(pyramid, k - 1, camera_xz_m)? / 2;
            let q = centre + glam::IVec2::new(a as i32 - n / 2, b as i32 - n / 2);
            let lo = inner - n / 4;
            let hi = inner + n / 4;
            if q.x >= lo.x && q.x < hi.x && q.y >= lo.y && q.y < hi.y {
                return None;
            }
        }
        let (ci, cj) = QUAD_CORNERS[((local - CLIPMAP_GRID_VERTICES) % 6) as usize];
        (a + ci, b + cj)
    };
    let last = level.samples.as_ivec2() - 1;
    let g = (centre + glam::IVec2::new(i as i32 - n / 2, j as i32 - n / 2))
        .clamp(glam::IVec2::ZERO, last);
    let (height, normal) = morphed(pyramid, height, k, g, centre);
    let xz = pyramid.corner_m + g.as_vec2() * level.spacing_m;
    Some((Vec3::new(xz.x, height, xz.y), normal))
}

/// The height and normal of level `k`'s sample `g`, blended into level `k + 1`'s
/// (interpolated along the coarse quad's edges) over the last
/// [`CLIPMAP_MORPH_QUADS`] quads before the level's edge. WGSL twin:
/// `clipmap_morphed`.
fn morphed(
    pyramid: &TerrainPyramid,
    height: &LevelHeight<'_>,
    k: usize,
    g: glam::IVec2,
    centre: glam::IVec2,
) -> (f32, Vec3) {
    let fine = height(k, g.x, g.y);
    let fine_normal = level_normal(pyramid, height, k, g);
    if k + 1 >= pyramid.levels.len() {
        return (fine, fine_normal);
    }
    let d = (g - centre).abs().max_element() as f32;
    let start = (CLIPMAP_QUADS / 2 - CLIPMAP_MORPH_QUADS) as f32;
    let alpha = ((d - start) / CLIPMAP_MORPH_QUADS as f32).clamp(0.0, 1.0);
    if alpha <= 0.0 {
        return (fine, fine_normal);
    }
    // On level k + 1: the mean of the coarse samples the fine one lies between.
    let c0 = glam::IVec2::new(g.x.div_euclid(2), g.y.div_euclid(2));
    let c1 = glam::IVec2::new((g.x + 1).div_euclid(2), (g.y + 1).div_euclid(2));
    let coarse = 0.25
        * (height(k + 1, c0.x, c0.y)
            + height(k + 1, c1.x, c0.y)
            + height(k + 1, c0.x, c1.y)
            + height(k + 1, c1.x, c1.y));
    let coarse_normal = level_normal(pyramid, height, k + 1, c0);
    (
        fine + (coarse - fine) * alpha,
        (fine_normal + (coarse_normal - fine_normal) * alpha).normalize_or(Vec3::Y),
    )
}

/// Level `k`'s normal at its sample `g` (central differences).
fn level_normal(
    pyramid: &TerrainPyramid,
    height: &LevelHeight<'_>,
    k: usize,
    g: glam::IVec2,
) -> Vec3 {
    let s = pyramid.levels[k].spacing_m;
    let dx = height(k, g.x - 1, g.y) - height(k, g.x + 1, g.y);
    let dz = height(k, g.x, g.y - 1) - height(k, g.x, g.y + 1);
    Vec3::new(dx, 2.0 * s, dz).normalize_or(Vec3::Y)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// `t`'s pyramid.
    fn pyramid_of(t: &Terrain) -> TerrainPyramid {
        TerrainPyramid::of(&Arc::new(t.clone()))
    }

    /// A terrain of `n`² samples `spacing` apart with heights `f(x, z)`.
    fn terrain(n: u32, spacing: f32, f: impl Fn(f32, f32) -> f32) -> Terrain {
        let half = 0.5 * (n - 1) as f32 * spacing;
        let mut h = Vec::new();
        for j in 0..n {
            for i in 0..n {
                h.push(f(i as f32 * spacing - half, j as f32 * spacing - half));
            }
        }
        Terrain::new(UVec2::splat(n), spacing, Vec2::ZERO, h).expect("a valid terrain")
    }

    fn rough(x: f32, z: f32) -> f32 {
        40.0 * (x / 37.0).sin() * (z / 53.0).cos() + 7.0 * (x / 5.3 + z / 7.1).sin()
    }

    #[test]
    fn bad_terrains_are_refused_with_what_to_give() {
        let ok = |n: u32| vec![0.0; (n * n) as usize];
        let e = Terrain::new(UVec2::new(1, 4), 1.0, Vec2::ZERO, vec![0.0; 4]).unwrap_err();
        assert!(matches!(e, TerrainError::Samples { x: 1, z: 4 }), "{e}");
        let e = Terrain::new(UVec2::splat(4), 0.0, Vec2::ZERO, ok(4)).unwrap_err();
        assert!(e.to_string().contains("metres between samples"), "{e}");
        let e = Terrain::new(UVec2::splat(4), f32::NAN, Vec2::ZERO, ok(4)).unwrap_err();
        assert!(matches!(e, TerrainError::Spacing(_)));
        let e = Terrain::new(UVec2::splat(4), 1.0, Vec2::ZERO, ok(3)).unwrap_err();
        assert!(matches!(e, TerrainError::HeightCount { got: 9, .. }));
        let mut h = ok(4);
        h[6] = f32::INFINITY;
        let e = Terrain::new(UVec2::splat(4), 1.0, Vec2::ZERO, h).unwrap_err();
        assert!(matches!(e, TerrainError::Height { x: 2, z: 1, .. }), "{e}");
        let e = Terrain::new(UVec2::splat(4), 1.0, Vec2::NAN, ok(4)).unwrap_err();
        assert_eq!(e, TerrainError::Centre);
    }

    #[test]
    fn heights_are_the_samples_and_bilinear_between_them() {
        let t = terrain(5, 2.0, |x, z| x + 10.0 * z);
        assert_eq!(t.corner_m(), Vec2::new(-4.0, -4.0));
        assert_eq!(t.height_at(Vec2::new(-4.0, -4.0)), Some(-44.0));
        assert_eq!(t.height_at(Vec2::new(4.0, 4.0)), Some(44.0));
        // A plane is its own bilinear interpolation.
        let h = t.height_at(Vec2::new(1.3, -2.7)).expect("on the terrain");
        assert!((h - (1.3 - 27.0)).abs() < 1e-4, "{h}");
        assert_eq!(t.height_at(Vec2::new(4.1, 0.0)), None);
        let n = t.normal_at(Vec2::ZERO);
        let expected = Vec3::new(-1.0, 1.0, -10.0).normalize();
        assert!(n.distance(expected) < 1e-5, "{n}");
        let raised = t.with_height_at(Vec2::new(1.0, 1.0), 3.0);
        assert!((raised.height_at(Vec2::new(1.0, 1.0)).unwrap_or(0.0) - 3.0).abs() < 1e-4);
    }

    #[test]
    fn slopes_pick_grass_soil_and_the_snow_eligibility() {
        let flat = Vec3::Y;
        let steep = Vec3::new(1.0, 1.0, 0.0).normalize();
        assert_eq!(Terrain::surface_for(flat), precip_cover::Surface::Grass);
        assert_eq!(Terrain::surface_for(steep), precip_cover::Surface::Soil);
        assert!((Terrain::eligibility_for(flat) - 1.0).abs() < 1e-6);
        assert!(Terrain::eligibility_for(Vec3::new(1.0, 0.5, 0.0).normalize()) < 1e-6);
        // The ramp reads texel centres only: flat at the first, steep at the last.
        let n = TERRAIN_RAMP_TEXELS as f32;
        assert!((terrain_ramp_u(flat) - 0.5 / n).abs() < 1e-6);
        assert!(
            (terrain_ramp_u(Vec3::new(1.0, 0.2, 0.0).normalize()) - (n - 0.5) / n).abs() < 1e-6
        );
        let ramp = terrain_ramp();
        let row = 4 * TERRAIN_RAMP_TEXELS as usize;
        assert_eq!(ramp.rgba8.len(), row * LAND_CLASSES);
        // Grass is greener than rock.
        assert!(ramp.rgba8[1] > ramp.rgba8[0] && ramp.rgba8[1] > ramp.rgba8[2]);
        let last = row - 4;
        assert!(ramp.rgba8[last + 1] <= ramp.rgba8[last]);
        // Each class's row starts at its colour and ends at the rock's.
        for class in LandClass::ALL {
            let start = class as usize * row;
            assert_eq!(ramp.rgba8[start..start + 3], class.colour(), "{class:?}");
            assert_eq!(
                ramp.rgba8[start + row - 4..start + row - 1],
                ramp.rgba8[last..last + 3],
                "{class:?}"
            );
        }
        assert!((terrain_ramp_v(LandClass::NoData) - 0.5 / LAND_CLASSES as f32).abs() < 1e-6);
        assert!((terrain_ramp_v(LandClass::MossAndLichen) - 1.0 + 0.5 / 12.0).abs() < 1e-6);
    }

    #[test]
    fn a_land_cover_gives_the_surface_and_the_snow_seen_from_above() {
        // West half forest, east half a lake, over a flat 100 m.
        let t = terrain(11, 10.0, |_, _| 0.0).with_land_cover(
            LandCover::from_worldcover(UVec2::new(2, 1), &[10, 80]).expect("valid"),
        );
        let (west, east) = (Vec2::new(-20.0, 0.0), Vec2::new(20.0, 0.0));
        assert_eq!(t.land_class_at(west), LandClass::Trees);
        assert_eq!(t.land_class_at(east), LandClass::Water);
        assert_eq!(t.land_class_at(Vec2::new(80.0, 0.0)), LandClass::NoData);
        assert_eq!(t.surface_at(west, Vec3::Y), precip_cover::Surface::Soil);
        assert_eq!(t.surface_at(east, Vec3::Y), precip_cover::Surface::Water);
        // Under the trees the snow lies (only its drawing is halved); none on water.
        assert!((t.eligibility_at(west, Vec3::Y) - 1.0).abs() < 1e-6);
        assert!((t.land_class_at(west).snow_share() - 0.5).abs() < 1e-6);
        assert!(t.eligibility_at(east, Vec3::Y).abs() < 1e-6);
        // Without a raster, the slope alone.
        let bare = terrain(11, 10.0, |_, _| 0.0);
        assert_eq!(bare.surface_at(west, Vec3::Y), precip_cover::Surface::Grass);
        assert!((bare.eligibility_at(west, Vec3::Y) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn the_pyramid_halves_each_level_on_the_samples_of_the_one_below() {
        let t = Arc::new(terrain(257, 1.0, |x, z| 0.5 * x - 0.25 * z + 3.0));
        let p = TerrainPyramid::of(&t);
        assert!(
            Arc::ptr_eq(&p.terrain, &t),
            "level 0 is the terrain, not a copy"
        );
        let sides: Vec<u32> = p.levels.iter().map(|l| l.samples.x).collect();
        assert_eq!(sides, [257, 129, 65, 33, 17, 9]);
        // Level 0 is the terrain's own heights; the coarser ones follow each
        // other in the pyramid's.
        let mut offset = 0;
        for (k, l) in p.levels.iter().enumerate().skip(1) {
            assert_eq!(l.offset, offset);
            offset += l.samples.x * l.samples.y;
            assert!((l.spacing_m - (1u32 << k) as f32).abs() < 1e-6);
        }
        assert_eq!(p.heights_m.len(), offset as usize);
        // A plane passes the [1 2 1] filter unchanged away from the edges: level k's
        // sample i lies on level 0's sample i·2^k.
        for k in 0..p.levels.len() {
            let h = p.height(k, 3, 2);
            let s = (1u32 << k) as f32;
            let expected = t
                .height_at(t.corner_m() + Vec2::new(3.0, 2.0) * s)
                .unwrap_or(0.0);
            assert!(
                (h - expected).abs() < 1e-3,
                "level {k}: {h} against {expected}"
            );
        }
    }

    #[test]
    fn a_normal_turned_from_the_viewer_is_bent_across_the_view_not_flipped() {
        // Facing the viewer: unchanged.
        let n = Vec3::new(0.3, 0.9, 0.1).normalize();
        let v = Vec3::new(0.0, 0.6, 0.8);
        assert!((facing_normal(n, v) - n).length() < 1e-6);
        // A crest's far face seen edge-on from a camera low over the ground: its
        // normal leans away from the viewer.
        let away = Vec3::new(0.0, 0.7, -0.714).normalize();
        let to_viewer = Vec3::new(0.0, 0.05, 1.0).normalize();
        assert!(away.dot(to_viewer) < 0.0);
        let bent = facing_normal(away, to_viewer);
        assert!((bent.length() - 1.0).abs() < 1e-5);
        assert!(
            (bent.dot(to_viewer)
                - TERRAIN_EDGE_ON
                    / (away - (away.dot(to_viewer) - TERRAIN_EDGE_ON) * to_viewer).length())
            .abs()
                < 1e-5
        );
        assert!(bent.dot(to_viewer) > 0.0, "it faces the viewer");
        assert!(bent.y > 0.9, "it still faces up, lit from above: {bent}");
        // The flip a mesh's underside takes would point it down.
        assert!((-away).y < 0.0);
    }

    #[test]
    fn a_window_holds_its_level_s_samples_round_the_camera_clamped_to_the_level() {
        let t = terrain(257, 1.0, rough);
        let p = pyramid_of(&t);
        let w = CLIPMAP_WINDOW_SAMPLES as i32;
        // Over the terrain: the window's middle on the level's centre.
        let camera = Vec2::new(10.3, -20.7);
        for k in 0..p.levels.len() {
            let centre = clipmap_centre(&p, k, camera).expect("a level");
            let last = p.levels[k].samples.as_ivec2() - 1;
            let origin = p.window_origin(k, camera).expect("a level");
            assert_eq!(origin, centre.clamp(glam::IVec2::ZERO, last) - w / 2);
            let window = p.window(k, origin);
            assert_eq!(window.len(), CLIPMAP_WINDOW_WORDS as usize);
            for (i, j) in [(0, 0), (w - 1, 0), (5, 40), (w - 1, w - 1)] {
                assert_eq!(
                    window[(i + w * j) as usize].to_bits(),
                    p.height(k, origin.x + i, origin.y + j).to_bits()
                );
            }
        }
        // Far off the terrain to the west and north: the window on its edge.
        let off = Vec2::new(-5_000.0, -9_000.0);
        assert_eq!(p.window_origin(0, off), Some(glam::IVec2::splat(-w / 2)));
        let rows = p.clipmap(Vec3::new(off.x, 100.0, off.y), 0.0, 7);
        assert_eq!(rows.window_origin(0), glam::IVec2::splat(-w / 2));
        assert_eq!(rows.levels.z, 7);
        assert_eq!(
            p.window_words(),
            p.levels.len() as u32 * CLIPMAP_WINDOW_WORDS
        );
    }

    #[test]
    fn window_origins_of_the_largest_terrain_fit_the_frame_block_s_words() {
        // Levels described only (no heights): a 16 384² terrain's pyramid.
        let mut levels = Vec::new();
        let mut n = MAX_TERRAIN_SAMPLES;
        let mut spacing = 0.6;
        while levels.len() < MAX_TERRAIN_LEVELS && n > CLIPMAP_QUADS / 4 {
            levels.push(PyramidLevel {
                samples: UVec2::splat(n),
                spacing_m: spacing,
                offset: 0,
            });
            n = (n - 1) / 2 + 1;
            spacing *= 2.0;
        }
        let p = TerrainPyramid {
            levels,
            terrain: Arc::new(terrain(2, 1.0, |_, _| 0.0)),
            heights_m: Vec::new(),
            corner_m: Vec2::ZERO,
        };
        let w = CLIPMAP_WINDOW_SAMPLES as i32;
        // Beyond the far corner (1), before the near one (0), west and south.
        for (camera, ends) in [
            (Vec2::splat(1.0e7), glam::IVec2::ONE),
            (Vec2::splat(-1.0e7), glam::IVec2::ZERO),
            (Vec2::new(-1.0e7, 1.0e7), glam::IVec2::new(0, 1)),
        ] {
            let rows = p.clipmap(Vec3::new(camera.x, 10.0, camera.y), 0.0, 0);
            for (k, l) in p.levels.iter().enumerate() {
                let last = l.samples.as_ivec2() - 1;
                assert_eq!(
                    rows.window_origin(k),
                    ends * last - w / 2,
                    "level {k} from {camera}"
                );
            }
        }
    }

    #[test]
    fn a_pyramid_built_by_hand_wrong_draws_nothing_and_does_not_panic() {
        let empty = TerrainPyramid {
            levels: Vec::new(),
            terrain: Arc::new(terrain(2, 1.0, |_, _| 0.0)),
            heights_m: Vec::new(),
            corner_m: Vec2::ZERO,
        };
        assert_eq!(empty.clipmap(Vec3::ONE, 0.0, 0).indices(), 0);
        assert!((empty.height_under(Vec2::ONE)).abs() < f32::MIN_POSITIVE);
        assert_eq!(clipmap_vertex(&empty, 0, Vec2::ZERO, 0), None);
        let short = TerrainPyramid {
            levels: vec![PyramidLevel {
                samples: UVec2::new(0, 4),
                spacing_m: 1.0,
                offset: 0,
            }],
            ..empty.clone()
        };
        assert!((short.height(0, 2, 2)).abs() < f32::MIN_POSITIVE);
        assert_eq!(clipmap_vertex(&short, 0, Vec2::ZERO, 0), None);
    }

    #[test]
    fn the_first_level_drawn_follows_the_camera_s_height_above_the_ground() {
        let t = terrain(1025, 1.0, |_, _| 10.0);
        let p = pyramid_of(&t);
        let low = p.clipmap(Vec3::new(0.0, 12.0, 0.0), 10.0, 100);
        assert_eq!(low.levels.x, 0);
        assert_eq!(low.placement.w as usize, p.levels.len());
        assert_eq!(low.indices(), p.levels.len() as u32 * CLIPMAP_LEVEL_INDICES);
        // 300 m up: levels whose half side is under 600 m are not drawn.
        let high = p.clipmap(Vec3::new(0.0, 310.0, 0.0), 10.0, 100);
        assert_eq!(high.levels.x, 5, "32 · 2^5 = 1024 m ≥ 600 m");
        assert_eq!(high.levels.z, 100);
        assert_eq!(high.samples[0].z, 513);
        // The water's mirror starts MIRROR_SKIPPED_LEVELS coarser, at most the last.
        assert_eq!(low.levels.w, MIRROR_SKIPPED_LEVELS);
        assert_eq!(
            low.mirror_indices(),
            (p.levels.len() as u32 - MIRROR_SKIPPED_LEVELS) * CLIPMAP_LEVEL_INDICES
        );
        let last = p.levels.len() as u32 - 1;
        let top = p.clipmap(Vec3::new(0.0, 1.0e5, 0.0), 10.0, 100);
        assert_eq!((top.levels.x, top.levels.w), (last, last));
        assert_eq!(top.mirror_indices(), CLIPMAP_LEVEL_INDICES);
        assert_eq!(ClipmapRows::default().mirror_indices(), 0);
    }

    /// Whether quad `(a, b)` of level `k` is drawn from level `first` on: its six
    /// indices' vertices all drawn and its two triangles not collapsed.
    fn quad_drawn(p: &TerrainPyramid, first: usize, camera: Vec2, k: usize, quad: u32) -> bool {
        let indices = clipmap_indices((k - first + 1) as u32);
        let at = ((k - first) as u32 * CLIPMAP_LEVEL_INDICES + 6 * quad) as usize;
        let corners: Option<Vec<Vec3>> = indices[at..at + 6]
            .iter()
            .map(|&v| clipmap_vertex(p, first, camera, v).map(|(pos, _)| pos))
            .collect();
        corners.is_some_and(|c| {
            c.chunks(3)
                .all(|t| (t[1] - t[0]).cross(t[2] - t[0]).length() > 1e-6)
        })
    }

    /// The levels' quads that hold `xz` (its quad's corners' positions), for
    /// `first` level drawn.
    fn quads_over(p: &TerrainPyramid, first: usize, camera: Vec2, xz: Vec2) -> usize {
        let mut count = 0;
        for k in first..p.levels.len() {
            let s = p.levels[k].spacing_m;
            let g = ((xz - p.corner_m) / s).floor().as_ivec2();
            let centre = clipmap_centre(p, k, camera).expect("a level");
            let local = g - centre + glam::IVec2::splat(CLIPMAP_QUADS as i32 / 2);
            if local.min_element() < 0 || local.max_element() >= CLIPMAP_QUADS as i32 {
                continue;
            }
            let quad = (local.x + CLIPMAP_QUADS as i32 * local.y) as u32;
            if quad_drawn(p, first, camera, k, quad) {
                count += 1;
            }
        }
        count
    }

    #[test]
    fn each_level_s_indices_name_its_shared_grid_and_its_edge_quads_own_corners() {
        let indices = clipmap_indices(2);
        assert_eq!(indices.len() as u32, 2 * CLIPMAP_LEVEL_INDICES);
        let mut used = vec![0u32; 2 * CLIPMAP_LEVEL_VERTICES as usize];
        for &v in &indices {
            used[v as usize] += 1;
        }
        // Every vertex number a level has is used; an edge quad's exactly once,
        // a grid vertex by up to six triangles.
        for (v, &n) in (0u32..).zip(&used) {
            let local = v % CLIPMAP_LEVEL_VERTICES;
            if local < CLIPMAP_GRID_VERTICES {
                assert!((1..=6).contains(&n), "grid vertex {v}: {n}");
            } else {
                assert_eq!(n, 1, "edge vertex {v}");
            }
        }
        let side = CLIPMAP_QUADS / 2 + 1;
        let mut edge = std::collections::HashSet::new();
        for m in 0..CLIPMAP_EDGE_QUADS {
            let (a, b) = clipmap_edge_quad(m);
            let lo = CLIPMAP_QUADS / 4;
            assert!(
                (a == lo || a == lo + side - 1 || b == lo || b == lo + side - 1)
                    && a.max(b) < lo + side
            );
            assert!(edge.insert((a, b)), "edge quad {m} twice");
        }
        // The grid vertices the hole's quads use are no quad's outside the hole.
        let hole = (CLIPMAP_QUADS / 4 + 1)..(3 * CLIPMAP_QUADS / 4);
        for quad in 0..CLIPMAP_QUADS * CLIPMAP_QUADS {
            let (a, b) = (quad % CLIPMAP_QUADS, quad / CLIPMAP_QUADS);
            let inside = hole.contains(&a) && hole.contains(&b);
            for &v in &indices[(6 * quad) as usize..(6 * quad + 6) as usize] {
                if v < CLIPMAP_GRID_VERTICES {
                    let (i, j) = (v % (CLIPMAP_QUADS + 1), v / (CLIPMAP_QUADS + 1));
                    let in_block = (hole.start..=hole.end).contains(&i)
                        && (hole.start..=hole.end).contains(&j);
                    assert_eq!(in_block, inside, "quad ({a}, {b}), vertex ({i}, {j})");
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// The GPU's windows hold every sample the clipmap reads: its vertices
        /// from the windows are the whole pyramid's, bit for bit, for any first
        /// level and wherever the camera is (on the terrain, over its edge, or
        /// kilometres off it).
        #[test]
        fn the_windows_give_the_pyramid_s_vertices_wherever_the_camera_is(
            cx in -3_000.0f32..3_000.0, cz in -3_000.0f32..3_000.0, near in proptest::bool::ANY,
        ) {
            let t = terrain(257, 1.5, rough);
            let p = pyramid_of(&t);
            // Half the cases over the terrain (±192 m) and its edge.
            let camera = if near { Vec2::new(cx, cz) * 0.08 } else { Vec2::new(cx, cz) };
            let rows = p.clipmap(Vec3::new(camera.x, 30.0, camera.y), 0.0, 0);
            let windows = ClipmapWindows::of(&p, &rows);
            let mut drawn = 0;
            for first in 0..p.levels.len() {
                for v in 0..(p.levels.len() - first) as u32 * CLIPMAP_LEVEL_VERTICES {
                    let whole = clipmap_vertex(&p, first, camera, v);
                    let windowed = windows.vertex(&p, first, camera, v);
                    let bits = |x: Option<(Vec3, Vec3)>| x.map(|(a, b)| (a.to_array().map(f32::to_bits), b.to_array().map(f32::to_bits)));
                    prop_assert_eq!(bits(whole), bits(windowed), "vertex {} from level {}", v, first);
                    drawn += usize::from(whole.is_some());
                }
            }
            prop_assert!(drawn > 0);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// The levels tile the ground: every point of the terrain within the last
        /// level's square lies in exactly one drawn quad.
        #[test]
        fn the_levels_cover_the_terrain_once(
            cx in -700.0f32..700.0, cz in -700.0f32..700.0,
            px in -1.0f32..1.0, pz in -1.0f32..1.0, first in 0usize..3,
        ) {
            let t = terrain(1025, 1.5, rough);
            let p = pyramid_of(&t);
            let camera = Vec2::new(cx, cz);
            let last = p.levels.len() - 1;
            let reach = 0.5 * CLIPMAP_QUADS as f32 * p.levels[last].spacing_m - 2.0 * p.levels[last].spacing_m;
            let xz = camera + Vec2::new(px, pz) * reach.min(600.0);
            let inside = t.height_at(xz).is_some()
                && (xz - t.corner_m()).min_element() > 2.0 * p.levels[last].spacing_m
                && (t.corner_m() + t.size_m() - xz).min_element() > 2.0 * p.levels[last].spacing_m;
            prop_assume!(inside);
            prop_assert_eq!(quads_over(&p, first, camera, xz), 1);
        }

        /// No cracks: each level's outer edge lies on the next level's quads'
        /// edges — every vertex there at the coarse level's height interpolated
        /// along that edge.
        #[test]
        fn each_level_s_edge_meets_the_next_level(
            cx in -400.0f32..400.0, cz in -400.0f32..400.0, first in 0usize..3,
        ) {
            let t = terrain(1025, 1.5, rough);
            let p = pyramid_of(&t);
            let camera = Vec2::new(cx, cz);
            let mut checked = 0;
            for k in first..p.levels.len() - 1 {
                let n = CLIPMAP_QUADS;
                // The quads of the level's top row (z = −n/2 side) and their
                // upper-left corner (vertex 0 of each quad).
                let centre = clipmap_centre(&p, k, camera).expect("a level");
                let last = p.levels[k].samples.as_ivec2() - 1;
                for qi in 0..=n {
                    // Grid vertex (qi, 0), where it stands on the terrain.
                    let g = centre + glam::IVec2::new(qi as i32 - n as i32 / 2, -(n as i32) / 2);
                    if g.min_element() < 0 || g.x > last.x || g.y > last.y {
                        continue;
                    }
                    let v = (k - first) as u32 * CLIPMAP_LEVEL_VERTICES + qi;
                    let Some((pos, _)) = clipmap_vertex(&p, first, camera, v) else {
                        continue;
                    };
                    // The coarse edge's two ends on level k + 1.
                    let s = p.levels[k + 1].spacing_m;
                    let g = (Vec2::new(pos.x, pos.z) - p.corner_m) / s;
                    let (a, b) = (g.x.floor() as i32, g.x.ceil() as i32);
                    let j = g.y.round() as i32;
                    prop_assert!((g.y - j as f32).abs() < 1e-3, "the edge lies on a coarse row");
                    let w = g.x - a as f32;
                    let coarse = p.height(k + 1, a, j) + (p.height(k + 1, b, j) - p.height(k + 1, a, j)) * w;
                    prop_assert!((pos.y - coarse).abs() < 1e-3, "level {k}: {} against {coarse}", pos.y);
                    checked += 1;
                }
            }
            prop_assert!(checked >= CLIPMAP_QUADS, "{checked} edge vertices on the terrain");
        }
    }
}
