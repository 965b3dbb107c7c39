//! [`FarCover`]: the cover beyond the cover grid, kept per place.
//!
//! The cover grid (`precip_cover::CoverGrid`) is fed by the particles that land on
//! it and is at most 1024² texels; a terrain reaches kilometres beyond it. There the
//! cover is a coarse grid of cells over the terrain's extent (at most
//! [`FAR_CELLS_MAX`] along a side), each holding a texel of every one of
//! [`FAR_COVER_SURFACES`] (grass, soil, paving, water), fed by the weather's rate
//! and stepped with the grid's own texel physics (`precip_cover::update_texel`): no
//! particles, drift or flow. Each cell keeps its own state, so the cover of a
//! valley the camera left is there when it comes back, and each cell's air is the
//! weather's at the cell's mean height — the standard atmosphere's lapse rate
//! ([`LAPSE_RATE_C_PER_M`], docs/model.md (4.18)) from the site's height, where the
//! weather is set — with the snow's share of what falls moved by the sleet ramp's
//! difference between the two temperatures ([`local_snow_share`]): a wet snowfall
//! at the site is rain in the valley below and dry snow on the ridge above, and the
//! snow line is where the cells' melt stops. A cell's melt is also its slope's
//! under the sun drawn ([`slope_irradiance_factor`], (4.19)): in a thaw the faces
//! toward the sun go bare first. Without a terrain it is one cell that stands for
//! everywhere (a scene's far meshes), level, at the site's air.
//!
//! The weather set is the weather around the camera (docs/model.md (6.16)): a cell
//! whose centre is within [`LOCAL_WEATHER_RADIUS_M`] of the camera takes its water;
//! one beyond takes the rate set for the land beyond ([`WaterBeyond`], the
//! weather's own unless `--rate-beyond` sets another), and under a cloud layer only
//! where the drawn shafts fall — under the lowest layer's clouds, at `rate/s` (`s`
//! the share of the land under them), none between — so showers seen from a dry town wet and whiten the
//! land they are seen falling on, and the mean over the land beyond is the rate set.
//!
//! The cells are stepped every [`FAR_STEP_EVERY`] steps with the weather those
//! steps had (their water summed, their air time-weighted), in pieces of at most
//! [`FAR_PIECE_DAYS`] days; each step's shading rows go to the GPU into one of two
//! regions of the ground buffer, in turn, so a frame in flight never reads the
//! region being written (the steps between two writes of a region outnumber the
//! frames in flight). The books count each texel for the terrain's land of its
//! surface in its cell off the grid, so with the grid's they close over the whole
//! terrain.

use glam::{UVec2, UVec4, Vec2, Vec3, Vec4};
use precip_cover::{
    CoverInput, CoverParams, CoverTexel, CoverTotals, GridFrame, Surface, update_texel,
};
use rayon::prelude::*;

use crate::drawing::clouds::{LOCAL_WEATHER_RADIUS_M, shaft_share};
use crate::host::far_air::{
    LAPSE_RATE_C_PER_M, local_relative_humidity, local_snow_share, slope_irradiance_factor,
};
use crate::host::far_water::WaterBeyond;
use crate::scene::terrain::Terrain;

/// The surfaces a far cell keeps a texel of, in the order of its shading rows: a
/// mesh's fragments and gentle untagged terrain read the grass, steep terrain,
/// fields and forest floors the soil, a town the paving, a lake the water
/// ([`far_cover_slot`]).
pub const FAR_COVER_SURFACES: [Surface; 4] = [
    Surface::Grass,
    Surface::Soil,
    Surface::Asphalt,
    Surface::Water,
];

/// Which of [`FAR_COVER_SURFACES`] stands for `surface` (roofing as paving, sand
/// as soil).
#[must_use]
pub const fn far_cover_slot(surface: Surface) -> usize {
    match surface {
        Surface::Grass => 0,
        Surface::Soil | Surface::Sand => 1,
        Surface::Asphalt | Surface::Roof => 2,
        Surface::Water => 3,
    }
}

/// The share of the cover grid's shorter side over which, inside its edge, the
/// grid's cover gives way to the far cover's ([`grid_blend`]). WGSL twin:
/// `GRID_BLEND_SHARE`.
pub const GRID_BLEND_SHARE: f32 = 1.0 / 16.0;

/// How much of the grid's cover a fragment at world (x, z) shows against the far
/// cover's: 1 inside `grid` beyond [`GRID_BLEND_SHARE`] of its shorter side from
/// its edge, falling smoothly (`t²(3 − 2t)`) to 0 at the edge, 0 off it (and for
/// a NaN). A grid whose cover differs from the land round it — its drifts, its
/// particles' snow, a grid that follows the camera over a snowy land — shows no
/// seam. WGSL twin: `grid_blend` (render_scene.wgsl).
#[must_use]
pub fn grid_blend(grid: &GridFrame, xz_m: Vec2) -> f32 {
    let band = GRID_BLEND_SHARE * grid.size_m.min_element();
    let inside = (xz_m - grid.origin_m)
        .min(grid.origin_m + grid.size_m - xz_m)
        .min_element();
    // (glam's min passes a NaN over: the point is checked itself.)
    if xz_m.is_nan() || inside.is_nan() || inside <= 0.0 {
        return 0.0;
    }
    let t = (inside / band).min(1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Where on `grid` a surface shows the grid's cover alone — [`grid_blend`] is 1 —
/// even read a texel off its point (the scene's fragments read the cover through
/// `cover_warp_m`, under half a texel): the grid less [`GRID_BLEND_SHARE`] of its
/// shorter side and a texel at each edge, as the (x, z) corners (lower, upper), m.
/// Empty (lower above upper) on a grid too small to have one. A scene tile wholly
/// inside is drawn by a fragment shader without the far cover's reads
/// (`fs_scene_on_grid`).
#[must_use]
pub fn grid_interior_m(grid: &GridFrame) -> (Vec2, Vec2) {
    let texel = grid.size_m / grid.texels.max(UVec2::ONE).as_vec2();
    let margin = Vec2::splat(GRID_BLEND_SHARE * grid.size_m.min_element()) + texel;
    (grid.origin_m + margin, grid.origin_m + grid.size_m - margin)
}

/// Most cells along a side of the far cover (10 km of terrain: ~104 m cells).
pub const FAR_CELLS_MAX: u32 = 96;

/// The far cover is stepped once every this many steps (at least the frames in
/// flight plus one, so its two GPU regions are never written while read).
pub const FAR_STEP_EVERY: u32 = 4;

/// The longest piece a far step advances its texels by at once, days (the texel
/// physics' limits are explicit; a far step at 2 days a second of the time scale
/// is cut into such pieces).
pub const FAR_PIECE_DAYS: f32 = 0.25;

/// The far texels' threshold masks (`T_M.g`, `T_M.r`): at their middle, each
/// fragment's patch noise moves them (WGSL twin `FAR_MASK`).
pub const FAR_MASK: f32 = 0.5;

/// The snow depth a cell holds to count as snowy for [`FarCover::snow_line_m`], mm.
pub const SNOW_LINE_DEPTH_MM: f32 = 10.0;

/// The height bands [`FarCover::snow_line_m`] looks at, m.
pub const SNOW_LINE_BAND_M: f32 = 25.0;

/// Floats of one texel's shading rows (two `vec4`s: what varies of the three the
/// grid's textures hold a texel, `cover_texture.wgsl`, and the cell's height).
pub const FAR_ROW_FLOATS: usize = 8;

/// Most terrain samples classified at configure (every `s`-th along each side
/// beyond).
const FAR_AREA_SAMPLES: u64 = 1 << 20;

/// The weather accumulated over the steps since the last far step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Pending {
    steps: u32,
    snow_mm: f64,
    rain_mm: f64,
    snow_beyond_mm: f64,
    rain_beyond_mm: f64,
    /// The last step's camera and shafts.
    beyond: WaterBeyond,
    /// The last step's way to the sun.
    to_sun: Vec3,
    dt_days: f64,
    /// Time-weighted sums (divided by `dt_days` at the step).
    temperature_c_days: f64,
    humidity_days: f64,
    wind_mps_days: f64,
}

/// The cover beyond the grid, per place (the module's docs).
#[derive(Debug, Clone, PartialEq)]
pub struct FarCover {
    corner_m: Vec2,
    cell_m: Vec2,
    cells: UVec2,
    /// Each cell's texels, [`FAR_COVER_SURFACES`]' order within a cell, cells row
    /// by row along x.
    texels: Vec<CoverTexel>,
    /// Each cell's mean height, m.
    height_m: Vec<f32>,
    /// Each cell's mean unit normal (its slope and aspect).
    normal: Vec<Vec3>,
    /// Each cell's air temperature less the site's, °C.
    air_offset_c: Vec<f32>,
    /// The land off the cover grid each texel stands for, m².
    area_m2: Vec<f64>,
    /// Whether the cells are places (a terrain's) rather than one cell for
    /// everywhere, which always takes the weather's water.
    per_place: bool,
    pending: Pending,
    /// Which of the GPU's two regions holds the rows now.
    region: u32,
    /// Whether a step has made rows the GPU does not have yet.
    fresh: bool,
}

/// Where the GPU reads the far cover (`RenderParams::far_cover_grid` and
/// `far_cover_cells`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FarCoverRows {
    /// The cells' corner x, z and a cell's size along x, z, m.
    pub grid: Vec4,
    /// Cells along x and z, the first word of the current region in the ground
    /// buffer, 0.
    pub cells: UVec4,
}

fn bare_texels() -> [CoverTexel; FAR_COVER_SURFACES.len()] {
    FAR_COVER_SURFACES.map(|surface| CoverTexel {
        eligibility: if surface == Surface::Water { 0.0 } else { 1.0 },
        accumulation_mask: FAR_MASK,
        melt_mask: FAR_MASK,
        surface: surface as u32,
        ..CoverTexel::default()
    })
}

impl FarCover {
    /// One cell for everywhere at the site's air, standing for no land (a scene
    /// without a terrain: its far meshes read it).
    #[must_use]
    pub fn everywhere() -> Self {
        Self {
            corner_m: Vec2::ZERO,
            cell_m: Vec2::ONE,
            cells: UVec2::ONE,
            texels: bare_texels().to_vec(),
            height_m: vec![0.0],
            normal: vec![Vec3::Y],
            air_offset_c: vec![0.0],
            area_m2: vec![0.0; FAR_COVER_SURFACES.len()],
            per_place: false,
            pending: Pending::default(),
            region: 0,
            fresh: false,
        }
    }

    /// The cells over `terrain`: each texel's land off `grid` (samples classified
    /// by [`Terrain::surface_at`], every `s`-th, at most 2²⁰) and each cell's mean
    /// height against the terrain's under the grid's centre.
    #[must_use]
    pub fn over(terrain: &Terrain, grid: &GridFrame) -> Self {
        let n = terrain.samples();
        let spans = (n.saturating_sub(UVec2::ONE)).max(UVec2::ONE);
        let cells = spans.min(UVec2::splat(FAR_CELLS_MAX));
        let size = terrain.size_m().max(Vec2::splat(f32::MIN_POSITIVE));
        let cell_m = size / cells.as_vec2();
        let corner = terrain.corner_m();
        let count = (cells.x * cells.y) as usize;
        let total = u64::from(n.x) * u64::from(n.y);
        let stride = ((total as f64 / FAR_AREA_SAMPLES as f64).sqrt().ceil() as u32).max(1);
        let sample_m = terrain.spacing_m() * stride as f32;
        let sample_m2 = f64::from(sample_m) * f64::from(sample_m);
        let mut area_m2 = vec![0.0; count * FAR_COVER_SURFACES.len()];
        let mut height_sum = vec![0.0_f64; count];
        let mut height_count = vec![0_u32; count];
        let mut normal_sum = vec![Vec3::ZERO; count];
        for j in (0..n.y).step_by(stride as usize) {
            for i in (0..n.x).step_by(stride as usize) {
                let xz = corner + Vec2::new(i as f32, j as f32) * terrain.spacing_m();
                let cell = ((xz - corner) / cell_m).as_uvec2().min(cells - UVec2::ONE);
                let c = (cell.x + cells.x * cell.y) as usize;
                let h = terrain.heights_m()[(i + n.x * j) as usize];
                height_sum[c] += f64::from(h);
                height_count[c] += 1;
                let normal = terrain.normal_at(xz);
                normal_sum[c] += normal;
                if grid.texel_index(xz).is_some() {
                    continue;
                }
                let surface = terrain.surface_at(xz, normal);
                area_m2[c * FAR_COVER_SURFACES.len() + far_cover_slot(surface)] += sample_m2;
            }
        }
        let site = terrain
            .height_at(grid.origin_m + 0.5 * grid.size_m)
            .unwrap_or_else(|| {
                let (low, high) = terrain.height_range_m();
                0.5 * (low + high)
            });
        let height_m: Vec<f32> = height_sum
            .iter()
            .zip(&height_count)
            .map(|(&sum, &k)| {
                if k > 0 {
                    (sum / f64::from(k)) as f32
                } else {
                    site
                }
            })
            .collect();
        let normal = normal_sum.iter().map(|n| n.normalize_or(Vec3::Y)).collect();
        let air_offset_c = height_m
            .iter()
            .map(|&h| -LAPSE_RATE_C_PER_M * (h - site))
            .collect();
        Self {
            corner_m: corner,
            cell_m,
            cells,
            texels: (0..count).flat_map(|_| bare_texels()).collect(),
            height_m,
            normal,
            air_offset_c,
            area_m2,
            per_place: true,
            pending: Pending::default(),
            region: 0,
            fresh: false,
        }
    }

    /// Cells along x and z.
    #[must_use]
    pub fn cells(&self) -> UVec2 {
        self.cells
    }

    /// The texels, [`FAR_COVER_SURFACES`]' order within a cell, cells row by row.
    #[must_use]
    pub fn texels(&self) -> &[CoverTexel] {
        &self.texels
    }

    /// The cell over world (x, z), clamped to the cells.
    #[must_use]
    pub fn cell_at(&self, xz_m: Vec2) -> UVec2 {
        ((xz_m - self.corner_m) / self.cell_m)
            .max(Vec2::ZERO)
            .as_uvec2()
            .min(self.cells - UVec2::ONE)
    }

    /// The texel of `surface` in the cell over (x, z).
    #[must_use]
    pub fn texel_at(&self, xz_m: Vec2, surface: Surface) -> &CoverTexel {
        let c = self.cell_at(xz_m);
        &self.texels[(c.x + self.cells.x * c.y) as usize * FAR_COVER_SURFACES.len()
            + far_cover_slot(surface)]
    }

    /// The air temperature of the cell over (x, z) less the site's, °C.
    #[must_use]
    pub fn air_offset_c_at(&self, xz_m: Vec2) -> f32 {
        let c = self.cell_at(xz_m);
        self.air_offset_c[(c.x + self.cells.x * c.y) as usize]
    }

    /// The land off the grid all its texels stand for, m² (0 without a terrain).
    #[must_use]
    pub fn area_m2(&self) -> f64 {
        self.area_m2.iter().sum()
    }

    /// The books of the land off the grid (`None` where it stands for none).
    #[must_use]
    pub fn totals(&self) -> Option<CoverTotals> {
        (self.area_m2() > 0.0).then(|| {
            CoverTotals::of_texels(
                self.texels
                    .iter()
                    .zip(self.area_m2.iter().copied())
                    .filter(|(_, a)| *a > 0.0),
            )
        })
    }

    /// The snow line beyond the grid, m: the cells (by their land off the grid)
    /// in bands of [`SNOW_LINE_BAND_M`] of height, from the highest down, while
    /// at least half of a band's land holds [`SNOW_LINE_DEPTH_MM`] of snow or
    /// more; the lowest such band's foot. `None` where the highest band is not
    /// snowy (or there is no terrain).
    #[must_use]
    pub fn snow_line_m(&self) -> Option<f32> {
        let per_cell = FAR_COVER_SURFACES.len();
        let mut cells: Vec<(f32, f64, f64)> = self
            .texels
            .chunks(per_cell)
            .zip(self.area_m2.chunks(per_cell))
            .zip(&self.height_m)
            .filter_map(|((texels, areas), &h)| {
                let land: f64 = areas.iter().sum();
                let snowy: f64 = texels
                    .iter()
                    .zip(areas)
                    .filter(|(t, _)| t.depth_mm >= SNOW_LINE_DEPTH_MM)
                    .map(|(_, a)| a)
                    .sum();
                (land > 0.0).then_some((h, land, snowy))
            })
            .collect();
        cells.sort_by(|a, b| b.0.total_cmp(&a.0));
        let top = cells.first()?.0;
        let mut line = None;
        let mut k = 0;
        while k < cells.len() {
            let foot = top
                - SNOW_LINE_BAND_M * ((top - cells[k].0) / SNOW_LINE_BAND_M).floor()
                - SNOW_LINE_BAND_M;
            let (mut land, mut snowy) = (0.0, 0.0);
            while k < cells.len() && cells[k].0 > foot {
                land += cells[k].1;
                snowy += cells[k].2;
                k += 1;
            }
            if snowy < 0.5 * land {
                break;
            }
            line = Some(foot.max(cells[k.saturating_sub(1)].0));
        }
        line
    }

    /// The index of the texel of `surface` in the cell over (x, z).
    fn slot_index(&self, xz_m: Vec2, surface: Surface) -> usize {
        let c = self.cell_at(xz_m);
        (c.x + self.cells.x * c.y) as usize * FAR_COVER_SURFACES.len() + far_cover_slot(surface)
    }

    /// Takes in a texel of the cover grid that the grid left (it moved with the
    /// camera): `texel`, standing for `area_m2` of land at (x, z), merges into its
    /// cell's texel of its surface ([`CoverTexel::merged`]), which stands for that
    /// land from now on — the cover beyond the grid keeps its snow, water and
    /// books, to rounding.
    pub fn take_in(&mut self, xz_m: Vec2, texel: &CoverTexel, area_m2: f64) {
        let k = self.slot_index(xz_m, Surface::from_raw(texel.surface));
        self.texels[k] = self.texels[k].merged(self.area_m2[k], texel, area_m2);
        self.area_m2[k] += area_m2;
        self.rows_changed();
    }

    /// Lends the cover of the land at (x, z) to `texel`, a texel of the cover grid
    /// that enters it there (the grid moved with the camera), standing for
    /// `area_m2`: the cover of its cell's texel of its surface per unit area
    /// ([`CoverTexel::with_cover_of`]), that texel standing for `area_m2` less
    /// land. Where the cell holds less land of that surface off the grid (its
    /// land was classified from every few terrain samples, the grid's texel by
    /// texel) the cell's texel with the most land lends; where the whole cell
    /// holds less, the texel enters bare — nothing is created either way.
    #[must_use]
    pub fn lend(&mut self, xz_m: Vec2, texel: CoverTexel, area_m2: f64) -> CoverTexel {
        let own = self.slot_index(xz_m, Surface::from_raw(texel.surface));
        let first = own - own % FAR_COVER_SURFACES.len();
        let lender = if self.area_m2[own] >= area_m2 {
            Some(own)
        } else {
            (first..first + FAR_COVER_SURFACES.len())
                .filter(|&k| self.area_m2[k] >= area_m2)
                .max_by(|&a, &b| self.area_m2[a].total_cmp(&self.area_m2[b]))
        };
        match lender {
            Some(k) => {
                self.area_m2[k] -= area_m2;
                texel.with_cover_of(&self.texels[k])
            }
            None => texel.with_cover_of(&CoverTexel::default()),
        }
    }

    /// The site the weather is set for moved to the cover grid's centre at
    /// `site_m` height: each cell's air is the weather's less the lapse rate over
    /// its height above the new site.
    pub fn move_site(&mut self, site_m: f32) {
        for (offset, &h) in self.air_offset_c.iter_mut().zip(&self.height_m) {
            *offset = -LAPSE_RATE_C_PER_M * (h - site_m);
        }
    }

    /// The texels changed (a far step, a move of the grid): their rows go to the
    /// GPU with the next upload, into the region frames do not read — flipped
    /// once an upload, so a move and a far step in one step write one region.
    fn rows_changed(&mut self) {
        if !self.fresh {
            self.region ^= 1;
            self.fresh = true;
        }
    }

    /// Adds a step's weather, `input` (its snow and rain, its air at the site),
    /// what fell beyond the camera's surroundings, `beyond`, and the way to the
    /// sun, `to_sun`; every [`FAR_STEP_EVERY`] steps the cells take what came
    /// since ([`FarCover::step_now`]).
    pub fn add_step(
        &mut self,
        input: CoverInput,
        beyond: WaterBeyond,
        to_sun: Vec3,
        params: &CoverParams,
    ) {
        let p = &mut self.pending;
        let days = f64::from(input.dt_days);
        p.steps += 1;
        p.snow_mm += f64::from(input.snow_mm);
        p.rain_mm += f64::from(input.rain_mm);
        p.snow_beyond_mm += f64::from(beyond.snow_mm);
        p.rain_beyond_mm += f64::from(beyond.rain_mm);
        p.beyond = beyond;
        p.to_sun = to_sun;
        p.dt_days += days;
        p.temperature_c_days += f64::from(input.air_temperature_c) * days;
        p.humidity_days += f64::from(input.relative_humidity) * days;
        p.wind_mps_days += f64::from(input.wind_speed_mps) * days;
        if p.steps >= FAR_STEP_EVERY {
            self.step_now(params);
        }
    }

    /// The water a cell takes over a far step and the snow's share of it at the
    /// site's air: the weather's within [`LOCAL_WEATHER_RADIUS_M`] of the camera
    /// (and everywhere for the one cell without a terrain), the land beyond's
    /// beyond it, under the lowest layer's clouds alone where it has one.
    /// `share_under_columns` is the shafts' [`shaft_share`], computed once a step.
    fn cell_water(&self, p: &Pending, share_under_columns: f32, cell: usize) -> (f64, f32) {
        let share = |snow: f64, rain: f64| {
            if snow + rain > 0.0 {
                (snow / (snow + rain)) as f32
            } else {
                0.0
            }
        };
        let centre = self.corner_m
            + (Vec2::new(
                (cell as u32 % self.cells.x) as f32,
                (cell as u32 / self.cells.x) as f32,
            ) + 0.5)
                * self.cell_m;
        if !self.per_place || centre.distance(p.beyond.camera_xz_m) <= LOCAL_WEATHER_RADIUS_M {
            return (p.snow_mm + p.rain_mm, share(p.snow_mm, p.rain_mm));
        }
        let factor = p.beyond.shafts.map_or(1.0, |s| {
            f64::from(s.mean_column(centre - 0.5 * self.cell_m, self.cell_m))
                / f64::from(share_under_columns)
        });
        (
            (p.snow_beyond_mm + p.rain_beyond_mm) * factor,
            share(p.snow_beyond_mm, p.rain_beyond_mm),
        )
    }

    /// Steps every cell by the weather accumulated since the last step, in pieces
    /// of at most [`FAR_PIECE_DAYS`], and flips the GPU's region.
    pub fn step_now(&mut self, params: &CoverParams) {
        let p = std::mem::take(&mut self.pending);
        let all_water = p.snow_mm + p.rain_mm + p.snow_beyond_mm + p.rain_beyond_mm;
        if p.dt_days <= 0.0 && all_water <= 0.0 {
            return;
        }
        let days = p.dt_days.max(f64::MIN_POSITIVE);
        let site_c = (p.temperature_c_days / days) as f32;
        let humidity = (p.humidity_days / days) as f32;
        let wind = (p.wind_mps_days / days) as f32;
        let pieces = ((p.dt_days / f64::from(FAR_PIECE_DAYS)).ceil() as u32).max(1);
        let piece = 1.0 / f64::from(pieces);
        let per_cell = FAR_COVER_SURFACES.len();
        let share = p.beyond.shafts.map_or(1.0, |s| shaft_share(s.coverage));
        let waters: Vec<(f64, f32)> = (0..self.height_m.len())
            .map(|cell| self.cell_water(&p, share, cell))
            .collect();
        let offsets = &self.air_offset_c;
        let normals = &self.normal;
        self.texels
            .par_chunks_mut(per_cell)
            .zip(offsets.par_iter().zip(waters.par_iter()))
            .zip(normals.par_iter())
            .for_each(|((cell, (&offset, &(water, site_share))), &normal)| {
                // Its slope and aspect under the sun scale the melt's sun part.
                let params = &CoverParams {
                    solar_irradiance_factor: params.solar_irradiance_factor
                        * slope_irradiance_factor(normal, p.to_sun),
                    ..*params
                };
                let local_c = site_c + offset;
                let share = local_snow_share(site_share, site_c, local_c);
                let input = CoverInput {
                    snow_mm: (water * piece) as f32 * share,
                    rain_mm: (water * piece) as f32 * (1.0 - share),
                    air_temperature_c: local_c,
                    relative_humidity: local_relative_humidity(humidity, site_c, local_c),
                    wind_speed_mps: wind,
                    dt_days: (p.dt_days * piece) as f32,
                };
                for texel in cell.iter_mut() {
                    for _ in 0..pieces {
                        *texel = update_texel(*texel, input, params);
                    }
                }
            });
        self.rows_changed();
    }

    /// The shading rows of every texel (cells row by row, [`FAR_COVER_SURFACES`]'
    /// order within a cell, [`FAR_ROW_FLOATS`] each): (depth mm, SWE mm, peak SWE
    /// mm, wetness), (age days, puddle ratio, dust kg/m², the cell's mean height
    /// m) — what varies of a grid texel's rows (`cover_texture.wgsl`: the far
    /// texels' masks are ½, their roughness their surface's) and the height
    /// `far_cover_rows` weighs the cells by.
    #[must_use]
    pub fn shading_rows(&self) -> Vec<f32> {
        let per_cell = FAR_COVER_SURFACES.len();
        self.texels
            .iter()
            .enumerate()
            .flat_map(|(k, t)| {
                [
                    t.depth_mm,
                    t.swe_mm,
                    t.peak_swe_mm,
                    t.wetness,
                    t.age_days,
                    t.puddle_ratio(),
                    t.dust_kg_m2,
                    self.height_m[k / per_cell],
                ]
            })
            .collect()
    }

    /// The words of the two GPU regions at configure (both the rows now).
    #[must_use]
    pub fn initial_words(&self) -> Vec<f32> {
        let rows = self.shading_rows();
        [rows.as_slice(), rows.as_slice()].concat()
    }

    /// Words of one region.
    #[must_use]
    pub fn region_words(&self) -> u32 {
        (self.texels.len() * FAR_ROW_FLOATS) as u32
    }

    /// Where the GPU reads the rows now, the regions starting at word `first_word`
    /// of the ground buffer.
    #[must_use]
    pub fn rows(&self, first_word: u32) -> FarCoverRows {
        FarCoverRows {
            grid: Vec4::new(
                self.corner_m.x,
                self.corner_m.y,
                self.cell_m.x,
                self.cell_m.y,
            ),
            cells: UVec4::new(
                self.cells.x,
                self.cells.y,
                first_word + self.region * self.region_words(),
                0,
            ),
        }
    }

    /// After a step, the rows the GPU lacks and the word of the ground buffer they
    /// go to (the regions starting at `first_word`); `None` when it has them.
    pub fn take_upload(&mut self, first_word: u32) -> Option<(u32, Vec<f32>)> {
        if !self.fresh {
            return None;
        }
        self.fresh = false;
        Some((
            first_word + self.region * self.region_words(),
            self.shading_rows(),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::host::far_water::Shafts;
    use crate::weather::sleet_snow_fraction;

    /// Adds `input` as the weather here and beyond alike.
    fn add(far: &mut FarCover, input: CoverInput, params: &CoverParams) {
        let beyond = WaterBeyond {
            camera_xz_m: Vec2::ZERO,
            snow_mm: input.snow_mm,
            rain_mm: input.rain_mm,
            shafts: None,
        };
        far.add_step(input, beyond, Vec3::Y, params);
    }

    fn snow_input(air_c: f32) -> CoverInput {
        CoverInput {
            snow_mm: 0.1,
            rain_mm: 0.0,
            air_temperature_c: air_c,
            relative_humidity: 0.9,
            wind_speed_mps: 2.0,
            dt_days: 0.01,
        }
    }

    /// A terrain 2 km square: flat at 0 m in its west half, a plateau 1 200 m up
    /// in its east half.
    fn step_terrain() -> Terrain {
        let n = 201_u32;
        let heights = (0..n * n)
            .map(|k| if k % n > n / 2 { 1200.0 } else { 0.0 })
            .collect();
        Terrain::new(UVec2::splat(n), 10.0, Vec2::ZERO, heights).expect("a terrain")
    }

    fn grid() -> GridFrame {
        GridFrame::centred(Vec2::new(-500.0, 0.0), Vec2::splat(64.0), UVec2::splat(64))
    }

    /// A texel the grid leaves merges into its cell's texel of its surface and
    /// is lent back as it was (the cell's cover per unit area), the land off the
    /// grid and the books as before; a texel entering where the cell has no land
    /// left off the grid enters bare, and the site's move moves the cells' air.
    #[test]
    #[expect(
        clippy::float_cmp,
        reason = "a lent texel is its lender's cover bit for bit"
    )]
    fn a_texel_taken_in_is_lent_back_with_the_books_unchanged() {
        let params = CoverParams::default();
        let mut far = FarCover::over(&step_terrain(), &grid());
        for _ in 0..FAR_STEP_EVERY {
            add(&mut far, snow_input(-5.0), &params);
        }
        let (area, books) = (far.area_m2(), far.totals().expect("books"));
        let at = Vec2::new(-700.0, 10.0);
        let cell = *far.texel_at(at, Surface::Grass);
        let leaving = CoverTexel {
            swe_mm: cell.swe_mm + 40.0,
            deposited_mm: cell.deposited_mm + 40.0,
            surface: Surface::Grass as u32,
            ..cell
        };
        far.take_in(at, &leaving, 4.0);
        assert!((far.area_m2() - area - 4.0).abs() < 1e-6);
        let taken = far.totals().expect("books");
        assert!((taken.swe_kg - books.swe_kg - f64::from(leaving.swe_mm) * 4.0).abs() < 1e-2);
        assert!(taken.imbalance_kg().abs() < 1e-3 * taken.deposited_kg);
        let entering = CoverTexel {
            surface: Surface::Grass as u32,
            ground_m: 3.0,
            ..CoverTexel::default()
        };
        let lent = far.lend(at, entering, 4.0);
        assert_eq!(lent.swe_mm, far.texel_at(at, Surface::Grass).swe_mm);
        assert_eq!(lent.ground_m, 3.0);
        assert!((far.area_m2() - area).abs() < 1e-6);
        let back = far.totals().expect("books");
        let with_lent = back.swe_kg + f64::from(lent.swe_mm) * 4.0;
        assert!(
            (with_lent - taken.swe_kg).abs() < 1e-2,
            "{with_lent} against {}",
            taken.swe_kg
        );
        // More land than the cell holds off the grid: bare, nothing taken.
        let before = far.area_m2();
        let bare = far.lend(at, entering, 1.0e9);
        assert_eq!((bare.swe_mm, bare.deposited_mm), (0.0, 0.0));
        assert_eq!(far.area_m2(), before);
        // The site 1 200 m up, on the plateau: the flat's cells are warmer.
        far.move_site(1200.0);
        assert!((far.air_offset_c_at(Vec2::new(800.0, 0.0))).abs() < 1e-3);
        assert!(far.air_offset_c_at(at) > 5.0);
    }

    /// The grid's cover shows whole inside the band, none off the grid, half
    /// half-way through the band, rising smoothly between.
    #[test]
    fn the_grid_gives_way_to_the_far_cover_over_a_band_inside_its_edge() {
        let grid = GridFrame::centred(Vec2::ZERO, Vec2::new(64.0, 128.0), UVec2::splat(32));
        let band = 64.0 * GRID_BLEND_SHARE;
        assert!((grid_blend(&grid, Vec2::ZERO) - 1.0).abs() < 1e-6);
        assert!((grid_blend(&grid, Vec2::new(32.0 - band, 0.0)) - 1.0).abs() < 1e-6);
        assert!((grid_blend(&grid, Vec2::new(32.0 - 0.5 * band, 10.0)) - 0.5).abs() < 1e-5);
        assert!(grid_blend(&grid, Vec2::new(0.0, 64.0 - 0.5 * band)) > 0.4);
        assert!(grid_blend(&grid, Vec2::new(32.0, 0.0)).abs() < 1e-6);
        assert!(grid_blend(&grid, Vec2::new(40.0, 0.0)).abs() < 1e-6);
        assert!(grid_blend(&grid, Vec2::new(f32::NAN, 0.0)).abs() < 1e-6);
        let mut last = 0.0;
        for k in 0..=100 {
            let w = grid_blend(&grid, Vec2::new(32.0 - band * k as f32 / 100.0, 0.0));
            assert!(w >= last && (0.0..=1.0).contains(&w), "{k}: {w}");
            last = w;
        }
    }

    /// Inside the interior, and a texel round any point of it, the grid's cover
    /// shows alone; the interior reaches to a texel of where it stops doing so.
    #[test]
    fn the_grid_s_interior_shows_its_cover_alone() {
        let grid = GridFrame::centred(
            Vec2::new(3.0, -7.0),
            Vec2::new(64.0, 128.0),
            UVec2::new(32, 64),
        );
        let (lo, hi) = grid_interior_m(&grid);
        let texel = 2.0;
        for k in 0..=200 {
            let t = k as f32 / 200.0;
            for p in [
                Vec2::new(lo.x + (hi.x - lo.x) * t, lo.y),
                Vec2::new(lo.x + (hi.x - lo.x) * t, hi.y),
                Vec2::new(lo.x, lo.y + (hi.y - lo.y) * t),
                Vec2::new(hi.x, lo.y + (hi.y - lo.y) * t),
            ] {
                for off in [
                    Vec2::new(-1.0, -1.0),
                    Vec2::new(1.0, 1.0),
                    Vec2::new(1.0, -1.0),
                ] {
                    let w = grid_blend(&grid, p + 0.5 * texel * off);
                    assert!((w - 1.0).abs() < 1e-6, "{p} {off}: {w}");
                }
            }
        }
        // Two texels further out the band has begun.
        assert!(grid_blend(&grid, Vec2::new(lo.x - 2.0 * texel, 0.5 * (lo.y + hi.y))) < 1.0);
        assert!(grid_blend(&grid, Vec2::new(hi.x, hi.y + 2.0 * texel)) < 1.0);
        // A grid narrower than its bands has none.
        let tiny = GridFrame::centred(Vec2::ZERO, Vec2::splat(2.0), UVec2::splat(1));
        let (lo, hi) = grid_interior_m(&tiny);
        assert!(lo.x > hi.x && lo.y > hi.y);
    }

    #[test]
    fn each_cell_breathes_the_air_at_its_height() {
        let far = FarCover::over(&step_terrain(), &grid());
        assert_eq!(far.cells(), UVec2::splat(96).min(UVec2::splat(200)));
        assert!(far.air_offset_c_at(Vec2::new(-800.0, 0.0)).abs() < 1e-3);
        let high = far.air_offset_c_at(Vec2::new(800.0, 0.0));
        assert!((high + 1200.0 * LAPSE_RATE_C_PER_M).abs() < 1e-3, "{high}");
        // The land off the grid: the terrain's less the grid's 64 m square.
        let expected = 2010.0_f64 * 2010.0 - 64.0 * 64.0;
        assert!(
            (far.area_m2() - expected).abs() / expected < 0.01,
            "{}",
            far.area_m2()
        );
    }

    #[test]
    fn a_snow_line_forms_where_the_cells_melt_stops_and_the_books_close() {
        let params = CoverParams::default();
        // A valley floor 800 m below the site, a ridge 800 m above.
        let n = 301_u32;
        let heights = (0..n * n)
            .map(|k| match k % n {
                i if i < 100 => -800.0,
                i if i > 200 => 800.0,
                _ => 0.0,
            })
            .collect();
        let terrain = Terrain::new(UVec2::splat(n), 10.0, Vec2::ZERO, heights).expect("valid");
        let grid = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(64));
        let mut far = FarCover::over(&terrain, &grid);
        // Sleet at +1.5 °C at the site for four days: rain on the floor (+6.7 °C),
        // snow on the ridge (−3.7 °C).
        let share = sleet_snow_fraction(1.5);
        for _ in 0..400 {
            add(
                &mut far,
                CoverInput {
                    snow_mm: 0.1 * share,
                    rain_mm: 0.1 * (1.0 - share),
                    ..snow_input(1.5)
                },
                &params,
            );
        }
        let floor = far.texel_at(Vec2::new(-1200.0, 0.0), Surface::Grass);
        let ridge = far.texel_at(Vec2::new(1200.0, 0.0), Surface::Grass);
        assert!(ridge.swe_mm > 35.0, "the ridge holds {} mm", ridge.swe_mm);
        assert!(floor.swe_mm < 1e-3, "the floor holds {} mm", floor.swe_mm);
        assert!(floor.infiltrated_mm + floor.film_mm + floor.standing_mm > 30.0);
        let lake = far.texel_at(Vec2::new(1200.0, 0.0), Surface::Water);
        assert!(lake.depth_mm.abs() < 1e-6);
        let books = far.totals().expect("a terrain");
        assert!(books.deposited_kg > 0.0);
        assert!(
            books.imbalance_kg().abs() < 1e-5 * books.deposited_kg,
            "{}",
            books.imbalance_kg()
        );
        // The snow line: the middle third (the site's 0 m, +1.5 °C, 37 % snow)
        // keeps some of its snow after four days, the floor none.
        let line = far.snow_line_m().expect("the ridge holds snow");
        assert!((-1.0..=1.0).contains(&line), "{line}");
        assert!(FarCover::everywhere().snow_line_m().is_none());
    }

    #[test]
    fn a_cell_keeps_its_cover_and_the_gpu_gets_each_step_in_the_other_region() {
        let params = CoverParams::default();
        let mut far = FarCover::over(&step_terrain(), &grid());
        let first = 1000;
        let before = far.rows(first).cells.z;
        for _ in 0..FAR_STEP_EVERY - 1 {
            add(&mut far, snow_input(-5.0), &params);
            assert!(far.take_upload(first).is_none());
        }
        add(&mut far, snow_input(-5.0), &params);
        let (word, rows) = far.take_upload(first).expect("a step's rows");
        assert_eq!(word, far.rows(first).cells.z);
        assert_ne!(word, before);
        assert_eq!(rows.len() as u32, far.region_words());
        assert!(far.take_upload(first).is_none());
        // Rows are (depth, SWE, …): the first grass texel holds the snow.
        assert!(rows[1] > 0.0);
        let held = *far.texel_at(Vec2::new(800.0, 500.0), Surface::Grass);
        for _ in 0..FAR_STEP_EVERY {
            add(
                &mut far,
                CoverInput {
                    snow_mm: 0.0,
                    ..snow_input(-5.0)
                },
                &params,
            );
        }
        let after = far.texel_at(Vec2::new(800.0, 500.0), Surface::Grass);
        assert!((after.swe_mm - held.swe_mm).abs() < 1e-3 * held.swe_mm.max(1.0));
        assert_eq!(far.initial_words().len() as u32, 2 * far.region_words());
    }

    #[test]
    fn everywhere_is_one_cell_standing_for_no_land() {
        let far = FarCover::everywhere();
        assert_eq!(far.cells(), UVec2::ONE);
        assert!(far.totals().is_none());
        assert_eq!(far.cell_at(Vec2::splat(1.0e6)), UVec2::ZERO);
    }

    /// An 8 km flat terrain at the site's height, its grid at the centre.
    fn wide_flat() -> (Terrain, GridFrame) {
        let n = 201_u32;
        let terrain = Terrain::new(
            UVec2::splat(n),
            40.0,
            Vec2::ZERO,
            vec![0.0; (n * n) as usize],
        )
        .expect("a terrain");
        let grid = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(64));
        (terrain, grid)
    }

    /// A day of dry air here and 1 mm of snow a step beyond (−8 °C: none melts).
    fn showers_around(far: &mut FarCover, shafts: Option<Shafts>, params: &CoverParams) {
        for _ in 0..100 {
            far.add_step(
                CoverInput {
                    snow_mm: 0.0,
                    ..snow_input(-8.0)
                },
                WaterBeyond {
                    camera_xz_m: Vec2::new(500.0, 0.0),
                    snow_mm: 1.0,
                    rain_mm: 0.0,
                    shafts,
                },
                Vec3::Y,
                params,
            );
        }
    }

    #[test]
    fn the_land_beyond_the_camera_s_surroundings_takes_the_rate_set_for_it() {
        let params = CoverParams::default();
        let (terrain, grid) = wide_flat();
        let mut far = FarCover::over(&terrain, &grid);
        showers_around(&mut far, None, &params);
        // Within 3 km of the camera (at x = 500 m) it stayed dry; beyond, the
        // 100 mm of snow lies (less what the dry air took).
        let here = far.texel_at(Vec2::new(2500.0, 1500.0), Surface::Grass);
        let there = far.texel_at(Vec2::new(-3000.0, 2500.0), Surface::Grass);
        assert!(here.deposited_mm.abs() < 1e-12, "{}", here.deposited_mm);
        assert!(
            (there.deposited_mm - 100.0).abs() < 1e-3,
            "{}",
            there.deposited_mm
        );
        assert!(there.swe_mm > 95.0, "{}", there.swe_mm);
        // The books: what landed is the land beyond's area times 100 mm.
        let books = far.totals().expect("a terrain");
        let beyond_m2: f64 = far
            .texels()
            .iter()
            .zip(&far.area_m2)
            .filter(|(t, _)| t.deposited_mm > 0.0)
            .map(|(_, a)| a)
            .sum();
        assert!((books.deposited_kg - 100.0 * beyond_m2).abs() < 1e-4 * books.deposited_kg);
        assert!(books.imbalance_kg().abs() < 1e-5 * books.deposited_kg);
        // The one cell without a terrain stands for everywhere: the weather's own.
        let mut everywhere = FarCover::everywhere();
        showers_around(&mut everywhere, None, &params);
        assert!(
            everywhere.texels()[0].deposited_mm.abs() < 1e-12,
            "{}",
            everywhere.texels()[0].deposited_mm
        );
    }

    #[test]
    fn under_a_cloud_layer_the_land_beyond_takes_its_shafts_rate_under_its_clouds_alone() {
        let params = CoverParams::default();
        let (terrain, grid) = wide_flat();
        let mut far = FarCover::over(&terrain, &grid);
        let shafts = Shafts {
            coverage: 0.3,
            drift_m: Vec2::new(1500.0, -700.0),
        };
        showers_around(&mut far, Some(shafts), &params);
        let camera = Vec2::new(500.0, 0.0);
        let (mut wet, mut dry, mut factor_sum, mut count) = (0, 0, 0.0_f64, 0);
        for j in 0..far.cells().y {
            for i in 0..far.cells().x {
                let centre = far.corner_m + (Vec2::new(i as f32, j as f32) + 0.5) * far.cell_m;
                let t = far.texel_at(centre, Surface::Grass);
                if centre.distance(camera) <= LOCAL_WEATHER_RADIUS_M {
                    assert!(t.deposited_mm.abs() < 1e-12, "{}", t.deposited_mm);
                    continue;
                }
                let factor = shafts.mean_rate_factor(centre - 0.5 * far.cell_m, far.cell_m);
                // Each cell took 100 mm at its shafts' rate over its land: 1/s
                // under a cloud, 0 between, the part under it on a cloud's edge.
                assert!((t.deposited_mm - 100.0 * factor).abs() < 1e-3 * (1.0 + 100.0 * factor));
                let full = 1.0 / shaft_share(0.3);
                assert!((0.0..=full + 1e-4).contains(&factor), "{factor}");
                if factor > 0.99 * full {
                    wet += 1;
                }
                if factor < 1e-6 {
                    dry += 1;
                }
                factor_sum += f64::from(factor);
                count += 1;
            }
        }
        // Under the clouds at 1/s, clear between; over the land beyond the mean is
        // the share of these 8 km (two thirds of the map's period) the clouds
        // happen to cover over s.
        assert!(
            wet > count / 10 && dry > count / 3,
            "{wet} wet, {dry} dry of {count}"
        );
        let mean = factor_sum / f64::from(count);
        eprintln!(
            "beyond: {count} cells, {wet} under clouds, {dry} clear, mean rate {mean:.3} of the set"
        );
        assert!((0.3..=1.7).contains(&mean), "mean {mean}");
        // Over the map's whole 12 km period the shafts' mean is the rate set.
        let n = 256;
        let period = crate::drawing::clouds::CLOUD_MAP_PERIOD_M;
        let whole: f64 = (0..n * n)
            .map(|k| {
                let xz = Vec2::new((k % n) as f32, (k / n) as f32) * (period / n as f32);
                f64::from(shafts.rate_factor(xz))
            })
            .sum::<f64>()
            / f64::from(n * n);
        eprintln!("over the map's period: mean rate {whole:.3} of the set");
        assert!((whole - 1.0).abs() < 0.01, "{whole}");
    }

    #[test]
    fn a_slope_facing_the_sun_melts_faster_than_one_facing_away() {
        let sun = Vec3::new(0.0, 0.5, 0.866_025_4);
        let (s30, c30) = (0.5, 0.866_025_4);
        let north = slope_irradiance_factor(Vec3::new(0.0, c30, -s30), sun);
        let south = slope_irradiance_factor(Vec3::new(0.0, c30, s30), sun);
        // A ridge along x, 30° faces north and south: a pack laid at −10 °C, then
        // two days at +6 °C at the crest under that sun.
        let params = CoverParams::default();
        let n = 201_u32;
        let heights = (0..n * n)
            .map(|k| 600.0 - 0.577_350_3 * ((k / n) as f32 * 10.0 - 1000.0).abs())
            .collect();
        let terrain = Terrain::new(UVec2::splat(n), 10.0, Vec2::ZERO, heights).expect("valid");
        let grid = GridFrame::centred(Vec2::new(-900.0, 0.0), Vec2::splat(32.0), UVec2::splat(8));
        let mut far = FarCover::over(&terrain, &grid);
        let step = |far: &mut FarCover, input: CoverInput| {
            let beyond = WaterBeyond {
                camera_xz_m: Vec2::ZERO,
                snow_mm: input.snow_mm,
                rain_mm: input.rain_mm,
                shafts: None,
            };
            far.add_step(input, beyond, sun, &params);
        };
        for _ in 0..40 {
            step(
                &mut far,
                CoverInput {
                    snow_mm: 1.5,
                    ..snow_input(-10.0)
                },
            );
        }
        let laid = far.texel_at(Vec2::new(0.0, 500.0), Surface::Grass).swe_mm;
        for _ in 0..200 {
            step(
                &mut far,
                CoverInput {
                    snow_mm: 0.0,
                    ..snow_input(6.0)
                },
            );
        }
        let south_swe = far.texel_at(Vec2::new(0.0, 500.0), Surface::Grass).swe_mm;
        let north_swe = far.texel_at(Vec2::new(0.0, -500.0), Surface::Grass).swe_mm;
        let (south_melt, north_melt) = (laid - south_swe, laid - north_swe);
        eprintln!(
            "laid {laid:.1} mm; after two warm days the south face {south_swe:.1}, the north face {north_swe:.1} mm"
        );
        assert!(
            north_melt > 0.0 && south_swe > 0.0,
            "{south_swe} {north_swe}"
        );
        let ratio = south_melt / north_melt;
        assert!(
            (ratio - south / north).abs() < 0.1 * south / north,
            "{ratio}"
        );
    }
}
