//! The shore as the frame runs it on the GPU (docs/model.md (13.10)): the
//! shallow-water equations of `precip_sea::shore` over a grid laid on the scene's
//! coast, stepped by the frame's `shore` kernels (render_shore.wgsl), their
//! surface drawn in place of the open sea's longest waves.
//!
//! ## The grid
//!
//! [`ShoreGrid::of_scene`] finds the coast of a scene with a sea: the texels of
//! the land's bounds whose bed lies under the sea's still level by at most
//! [`SHORE_DEPTH_M`] (the shoaling water, where waves feel the bed), and the land
//! up to [`SHORE_RUN_UP_M`] above the level within [`SHORE_LANDWARD_M`] of them
//! (where they run up). Their bounding box, in cells of [`SHORE_CELL_M`] (larger
//! where the box is longer than [`SHORE_MAX_CELLS_PER_SIDE`] cells), is the grid.
//! Its bed at each cell centre ([`shore_bed_m`]) is the top-most surface of
//! every mesh but the sea, except where that surface floats over the water: a
//! deck whose underside lies above the bed under it (a pier) lets the water pass
//! under it, a wall standing on the bed (a breakwater) does not.
//!
//! Each side of the grid is an edge of the solver ([`ShoreEdge`]): where nine in
//! ten of its cells lie [`SHORE_INCOMING_DEPTH_M`] or more under the level, the
//! open sea's waves come in by it; where nine in ten are dry, it is a wall;
//! otherwise it is open.
//!
//! ## The waves coming in
//!
//! The open sea's frequency spectrum (the weather's wind over the sea's fetch) cut
//! into [`SHORE_WAVE_COMPONENTS`] sinusoids ([`precip_sea::IncomingWaves::from_sea`]),
//! scaled to what the incoming edge's depth holds (`H_s ≤ γ_b·d`,
//! [`crate::drawing::sea::BREAKER_INDEX`]) and to the share of the wind blowing
//! toward the shore (`√max(cos θ, 0.1)`: an offshore wind sends the coast little).
//!
//! ## The step
//!
//! A frame runs [`SHORE_STEPS_PER_FRAME`] steps of one length ([`ShoreClock`]):
//! the time since the shore's last frame, split, each at most the step the
//! scheme is stable for with the water no faster than the speed cap
//! ([`ShoreGrid::step_bounds`]): `Δt = C·Δx/(2·(u_max + √(g·d_max)))`, `d_max` the
//! deepest still water plus twice the waves' summed amplitudes (a wave doubles
//! against a wall), `u_max = √(g·d_max)`. A slow frame slows the shore's clock
//! rather than adding steps (the frame's cost stays fixed); the waves' phases
//! follow the shore's own clock, so the sea and the shore stay one sea.
//!
//! The CPU reference is `precip_sea::Shore` with the same bathymetry, edges, waves
//! and cap ([`ShoreGrid::reference`]); the conformance suite steps both.

use glam::{UVec2, Vec2, Vec4};
use precip_cover::GridFrame;
use precip_sea::ocean::SeaState;
use precip_sea::{
    Bathymetry, COURANT, Edge, GRAVITY_MPS2, IncomingWaves, Shore, ShoreError, ShoreState,
    WaveComponent,
};

use crate::drawing::sea::{BREAKER_INDEX, SEA_DEPTH_RANGE_M, SeaSettings, sea_level_m};
use crate::particles::ground::GroundMap;
use crate::scene::Scene;
use crate::scene::top_down::lowest_undersides;

/// The shore's cell, m (larger where the coast is longer than
/// [`SHORE_MAX_CELLS_PER_SIDE`] cells of it).
pub const SHORE_CELL_M: f32 = 2.0;
/// The most cells along a side of the shore's grid.
pub const SHORE_MAX_CELLS_PER_SIDE: u32 = 256;
/// The deepest still water the shore's grid takes in, m: waves of a sea the
/// wind raises feel the bed from about here (shallower than half a wavelength).
pub const SHORE_DEPTH_M: f32 = 6.0;
/// The highest land above the still level the grid takes in, m: the run-up.
pub const SHORE_RUN_UP_M: f32 = 4.0;
/// How far inland of the shoaling water the grid reaches for that land, m.
pub const SHORE_LANDWARD_M: f32 = 40.0;
/// An edge is the open sea's where nine in ten of its cells are this deep, m.
pub const SHORE_INCOMING_DEPTH_M: f32 = 1.0;
/// Steps of the shore a frame.
pub const SHORE_STEPS_PER_FRAME: u32 = 4;
/// Stable steps the shore is spun up by before its first frame (on the host, by
/// the CPU reference: [`ShoreFrames::new`]): the sea's waves come in and run up
/// the beach before the first frame is seen (some 20 to 30 s of the shore's time,
/// what the waves take to cross its shoaling water).
pub const SHORE_SPIN_UP_STEPS: u32 = 1024;
/// The shore's bed roughness, Manning's `n` in s/m^⅓: sand (Chow 1959, *Open-channel
/// hydraulics*: 0.020–0.026 for a sand bed; a beach's ripples and shells at the top).
pub const SHORE_MANNING_N: f32 = 0.025;
/// Sinusoids of the waves coming in. WGSL twin: `shore_waves`' length.
pub const SHORE_WAVE_COMPONENTS: usize = 8;
/// A dry cell's surface is drawn this far under its bed (or under the still level,
/// whichever is lower), m: the sea's mesh over dry land sinks out of sight, and
/// the waterline is where the drawn surface meets the ground. WGSL twin:
/// `SHORE_DRY_SINK_M`.
pub const SHORE_DRY_SINK_M: f32 = 0.3;
/// The frame block's rows of the shore (`RenderParams::shore_grid`, `shore_size`,
/// `shore_edges`, `shore_steps`, `shore_waves`).
pub const SHORE_ROWS: usize = 4 + SHORE_WAVE_COMPONENTS;
/// The share of a side's cells that makes it an incoming or a wall edge.
const SIDE_SHARE: f32 = 0.9;
/// The finest search for the coast: at most this many texels along a side.
const SEARCH_MAX_TEXELS: f32 = 1024.0;
/// The clock jumps rather than chase a frame further ahead than this, s.
const MOST_LAG_S: f64 = 1.0;

/// What a side of the shore's grid is. WGSL twin: `shore_edges`' codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShoreEdge {
    /// A wall: waves are reflected (the land's side).
    Wall = 0,
    /// Open: waves leave (along the coast).
    Open = 1,
    /// The open sea's waves come in.
    Incoming = 2,
}

/// The shore's grid on a scene's coast (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ShoreGrid {
    /// The bed at each cell's centre, m.
    pub bathymetry: Bathymetry,
    /// The grid's corner (x, z), m.
    pub origin_m: Vec2,
    /// The sea's still level, m.
    pub still_level_m: f32,
    /// West (x min), east, south (z min), north.
    pub edges: [ShoreEdge; 4],
}

/// The bed of the shore at each texel of `frame` (module docs): the top-most
/// surface of `scene`'s land unless it floats over the bed under the level.
#[must_use]
pub fn shore_bed_m(scene: &Scene, frame: GridFrame, level_m: f32) -> Vec<f32> {
    let land = || scene.meshes.iter().filter(|m| !m.is_sea());
    let under = GroundMap::top_down(land(), frame, f32::NEG_INFINITY, Some(level_m)).height_m;
    let top = GroundMap::top_down(land(), frame, f32::NEG_INFINITY, None).height_m;
    let undersides = lowest_undersides(land(), frame);
    under
        .iter()
        .zip(&top)
        .zip(&undersides)
        .map(|((&bed, &top), &underside)| {
            if !top.is_finite() {
                level_m - SEA_DEPTH_RANGE_M
            } else if top <= level_m || !bed.is_finite() {
                top
            } else if underside > bed + 0.05 && underside < top {
                // A deck over the water: the water runs under it.
                bed
            } else {
                top
            }
        })
        .collect()
}

/// A grid of `texels` over `size_m` from `origin_m`.
fn grid(origin_m: Vec2, cell_m: f32, texels: UVec2) -> GridFrame {
    GridFrame {
        origin_m,
        size_m: texels.as_vec2() * cell_m,
        texels,
        reserved: UVec2::ZERO,
    }
}

impl ShoreGrid {
    /// The shore of `scene`'s coast, `None` without a sea or shoaling water (the
    /// module docs).
    #[must_use]
    pub fn of_scene(scene: &Scene) -> Option<Self> {
        let level = sea_level_m(scene)?;
        let (lo, hi) = scene.land_bounds_m()?;
        let extent = Vec2::new(hi.x - lo.x, hi.z - lo.z);
        if !(extent.min_element() > 0.0 && extent.is_finite()) {
            return None;
        }
        let cell = SHORE_CELL_M.max(extent.max_element() / SEARCH_MAX_TEXELS);
        let texels = (extent / cell).ceil().as_uvec2().max(UVec2::ONE);
        let search = grid(Vec2::new(lo.x, lo.z), cell, texels);
        let bed = shore_bed_m(scene, search, level);
        let (nx, nz) = (texels.x as usize, texels.y as usize);
        let at = |i: usize, j: usize| bed[j * nx + i];
        // The shoaling water's box, then the land it runs up within reach.
        let take = |boxed: Option<(UVec2, UVec2)>, i: usize, j: usize| {
            let p = UVec2::new(i as u32, j as u32);
            Some(boxed.map_or((p, p), |(a, b)| (a.min(p), b.max(p))))
        };
        let mut boxed: Option<(UVec2, UVec2)> = None;
        for j in 0..nz {
            for i in 0..nx {
                let depth = level - at(i, j);
                if depth > 0.0 && depth <= SHORE_DEPTH_M {
                    boxed = take(boxed, i, j);
                }
            }
        }
        let (wet_lo, wet_hi) = boxed?;
        let reach = (SHORE_LANDWARD_M / cell).ceil() as u32;
        let (reach_lo, reach_hi) = (
            wet_lo.saturating_sub(UVec2::splat(reach)),
            (wet_hi + reach).min(texels - 1),
        );
        for j in reach_lo.y as usize..=reach_hi.y as usize {
            for i in reach_lo.x as usize..=reach_hi.x as usize {
                let rise = at(i, j) - level;
                if (0.0..=SHORE_RUN_UP_M).contains(&rise) {
                    boxed = take(boxed, i, j);
                }
            }
        }
        let (box_lo, box_hi) = boxed?;
        let size_m = (box_hi - box_lo + 1).as_vec2() * cell;
        let shore_cell = SHORE_CELL_M.max(size_m.max_element() / SHORE_MAX_CELLS_PER_SIDE as f32);
        let cells = (size_m / shore_cell).ceil().as_uvec2().max(UVec2::splat(2));
        let origin = search.origin_m + box_lo.as_vec2() * cell;
        let frame = grid(origin, shore_cell, cells);
        let bathymetry = Bathymetry {
            nx: cells.x as usize,
            ny: cells.y as usize,
            cell_m: shore_cell,
            bed_m: shore_bed_m(scene, frame, level),
        };
        let edges = side_edges(&bathymetry, level);
        Some(Self {
            bathymetry,
            origin_m: origin,
            still_level_m: level,
            edges,
        })
    }

    /// The grid as a [`GridFrame`] (cells as texels).
    #[must_use]
    pub fn frame(&self) -> GridFrame {
        let b = &self.bathymetry;
        grid(
            self.origin_m,
            b.cell_m,
            UVec2::new(b.nx as u32, b.ny as u32),
        )
    }

    /// Cells.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.bathymetry.nx * self.bathymetry.ny
    }

    /// The still water's depth at the incoming edge, m (mean of its cells; 0
    /// without one).
    #[must_use]
    pub fn incoming_depth_m(&self) -> f32 {
        let b = &self.bathymetry;
        let Some(side) = self.edges.iter().position(|e| *e == ShoreEdge::Incoming) else {
            return 0.0;
        };
        let cells = side_cells(b, side);
        let n = cells.len().max(1) as f32;
        cells
            .iter()
            .filter_map(|&k| b.bed_m.get(k))
            .map(|bed| (self.still_level_m - bed).max(0.0))
            .sum::<f32>()
            / n
    }

    /// The open sea's waves coming in over the incoming edge from `sea` (module
    /// docs; none without an incoming edge).
    #[must_use]
    pub fn incoming_waves(&self, sea: &SeaState) -> IncomingWaves {
        let mut waves = IncomingWaves::from_sea(
            &sea.wind_sea(),
            self.still_level_m,
            SHORE_WAVE_COMPONENTS,
            sea.seed,
        );
        // The incoming edge's inward normal and the way along it (cells counted
        // from the grid's corner: z on the west and east sides, x on the others).
        let (inward, along) = match self.edges.iter().position(|e| *e == ShoreEdge::Incoming) {
            Some(0) => (Vec2::X, Vec2::Y),
            Some(1) => (Vec2::NEG_X, Vec2::Y),
            Some(2) => (Vec2::Y, Vec2::X),
            Some(_) => (Vec2::NEG_Y, Vec2::X),
            None => (Vec2::ZERO, Vec2::ZERO),
        };
        let wind = Vec2::from_array(sea.wind_direction);
        let mean_rad = wind.dot(along).atan2(wind.dot(inward));
        let variance: f32 = waves
            .components
            .iter()
            .map(|c| 0.5 * c.amplitude_m * c.amplitude_m)
            .sum();
        let significant = 4.0 * variance.sqrt();
        let held = BREAKER_INDEX * self.incoming_depth_m();
        let depth_share = if significant > held && significant > 0.0 {
            held / significant
        } else {
            1.0
        };
        let n = waves.components.len();
        for (i, c) in waves.components.iter_mut().enumerate() {
            // Each its own heading: the spreading's quantiles about the wind's,
            // dealt out of step with the frequencies.
            let quantile = (((i * 5 + 3) % n.max(1)) as f32 + 0.5) / n.max(1) as f32;
            let heading = mean_rad + spreading_quantile_rad(quantile);
            let toward_shore = heading.cos();
            let scale = if inward == Vec2::ZERO {
                0.0
            } else {
                depth_share * toward_shore.max(0.1).sqrt()
            };
            c.amplitude_m *= scale;
            c.along_edge_per_m = WaveComponent::along_edge_per_m(
                c.period_s,
                heading.clamp(-MOST_HEADING_RAD, MOST_HEADING_RAD),
            );
        }
        waves
    }

    /// The water's speed cap m/s and the longest step stable under it, s, with
    /// `waves` coming in (module docs).
    #[must_use]
    pub fn step_bounds(&self, waves: &IncomingWaves) -> (f32, f32) {
        let deepest = self
            .bathymetry
            .bed_m
            .iter()
            .map(|b| self.still_level_m - b)
            .fold(0.0f32, f32::max);
        let swing: f32 = waves.components.iter().map(|c| c.amplitude_m.abs()).sum();
        let depth = deepest + 2.0 * swing + 0.5;
        let c = (GRAVITY_MPS2 * depth).sqrt();
        let dt = COURANT * self.bathymetry.cell_m / (2.0 * (c + c));
        (c, dt)
    }

    /// The CPU reference of this shore: its bed of roughness [`SHORE_MANNING_N`],
    /// its edges with `waves` at the incoming one, the water at rest at the still
    /// level, the speed cut to `speed_cap_mps`.
    ///
    /// # Errors
    ///
    /// What [`Shore::new`] or [`Shore::with_speed_cap`] refuses.
    pub fn reference(
        &self,
        waves: &IncomingWaves,
        speed_cap_mps: f32,
    ) -> Result<Shore, ShoreError> {
        let edges = self.edges.map(|e| match e {
            ShoreEdge::Wall => Edge::Wall,
            ShoreEdge::Open => Edge::Open,
            ShoreEdge::Incoming => Edge::Incoming(waves.clone()),
        });
        let state = ShoreState::at_rest(&self.bathymetry, self.still_level_m);
        Shore::new(self.bathymetry.clone(), edges, state)?
            .with_speed_cap(speed_cap_mps)?
            .with_bed_friction(SHORE_MANNING_N)
    }

    /// The frame block's shore rows for `count` steps `steps` with `waves` coming
    /// in and the speed cut to `speed_cap_mps` (`RenderParams::shore_*`).
    #[must_use]
    pub fn rows(
        &self,
        waves: &IncomingWaves,
        steps: ShoreSteps,
        count: u32,
        speed_cap_mps: f32,
    ) -> [Vec4; SHORE_ROWS] {
        let b = &self.bathymetry;
        let mut rows = [Vec4::ZERO; SHORE_ROWS];
        rows[0] = Vec4::new(
            self.origin_m.x,
            self.origin_m.y,
            b.cell_m,
            self.still_level_m,
        );
        rows[1] = Vec4::new(b.nx as f32, b.ny as f32, steps.dt_s, speed_cap_mps);
        rows[2] = Vec4::from_array(self.edges.map(|e| e as u32 as f32));
        rows[3] = Vec4::new(count as f32, SHORE_MANNING_N, 0.0, 0.0);
        for (row, c) in rows[4..].iter_mut().zip(&waves.components) {
            let omega = std::f64::consts::TAU / f64::from(c.period_s);
            let phase =
                (omega * steps.start_s + f64::from(c.phase_rad)).rem_euclid(std::f64::consts::TAU);
            *row = Vec4::new(
                c.amplitude_m,
                omega as f32,
                phase as f32,
                c.along_edge_per_m,
            );
        }
        rows
    }

    /// `vec4`s of the shore's buffer: a header (the step within the frame), two
    /// states, the faces along x and along y, the cells' bed sources
    /// (render_shore.wgsl).
    #[must_use]
    pub fn buffer_vec4s(&self) -> usize {
        let (nx, ny) = (self.bathymetry.nx, self.bathymetry.ny);
        1 + 3 * nx * ny + (nx + 1) * ny + nx * (ny + 1)
    }

    /// The shore's buffer at first: both states the water at rest at the still
    /// level, each cell `(h, q_x, q_z, bed)`.
    #[must_use]
    pub fn initial_buffer(&self) -> Vec<[f32; 4]> {
        let b = &self.bathymetry;
        let rest: Vec<[f32; 4]> = b
            .bed_m
            .iter()
            .map(|&bed| [(self.still_level_m - bed).max(0.0), 0.0, 0.0, bed])
            .collect();
        let mut words = vec![[0.0; 4]];
        words.extend_from_slice(&rest);
        words.extend_from_slice(&rest);
        words.resize(self.buffer_vec4s(), [0.0; 4]);
        words
    }

    /// The water of the shore's buffer `words` (as [`ShoreGrid::initial_buffer`]
    /// lays it out); `None` for a buffer too short.
    #[must_use]
    pub fn state_of_buffer(&self, words: &[[f32; 4]]) -> Option<ShoreState> {
        let cells = words.get(1..1 + self.cells())?;
        Some(ShoreState {
            depth_m: cells.iter().map(|c| c[0]).collect(),
            discharge_x_m2ps: cells.iter().map(|c| c[1]).collect(),
            discharge_y_m2ps: cells.iter().map(|c| c[2]).collect(),
        })
    }
}

/// A shore's grid and its water (what a backend reads back).
#[derive(Debug, Clone, PartialEq)]
pub struct ShoreGridState {
    /// The grid.
    pub grid: ShoreGrid,
    /// The water.
    pub state: ShoreState,
}

/// The most a wave coming in turns from the shore's normal, rad (80°: beyond, it
/// runs along the shore, not onto it).
const MOST_HEADING_RAD: f32 = 1.4;

/// The angle from the mean direction below which `quantile` of a wind sea's
/// energy travels, rad: the spreading `cos²ˢ(θ/2)` ([`precip_sea::ocean::directional_spreading`],
/// `s` = [`precip_sea::ocean::SPREADING_EXPONENT`]) summed over 720 steps of the
/// circle.
fn spreading_quantile_rad(quantile: f32) -> f32 {
    use precip_sea::ocean::{SPREADING_EXPONENT, directional_spreading};
    let steps = 720;
    let d = std::f32::consts::TAU / steps as f32;
    let mut sum = 0.0;
    for i in 0..steps {
        let theta = -std::f32::consts::PI + (i as f32 + 0.5) * d;
        sum += directional_spreading(theta.cos(), SPREADING_EXPONENT) * d;
        if sum >= quantile {
            return theta;
        }
    }
    std::f32::consts::PI
}

/// The cells along side `side` (west, east, south, north) of `b`.
fn side_cells(b: &Bathymetry, side: usize) -> Vec<usize> {
    match side {
        0 => (0..b.ny).map(|j| j * b.nx).collect(),
        1 => (0..b.ny).map(|j| j * b.nx + b.nx - 1).collect(),
        2 => (0..b.nx).collect(),
        _ => (0..b.nx).map(|i| (b.ny - 1) * b.nx + i).collect(),
    }
}

/// Each side's edge (module docs).
fn side_edges(b: &Bathymetry, level_m: f32) -> [ShoreEdge; 4] {
    std::array::from_fn(|side| {
        let cells = side_cells(b, side);
        let n = cells.len().max(1) as f32;
        let share = |f: &dyn Fn(f32) -> bool| {
            cells
                .iter()
                .filter(|&&k| b.bed_m.get(k).is_some_and(|&bed| f(bed)))
                .count() as f32
                / n
        };
        if share(&|bed| level_m - bed >= SHORE_INCOMING_DEPTH_M) >= SIDE_SHARE {
            ShoreEdge::Incoming
        } else if share(&|bed| bed >= level_m) >= SIDE_SHARE {
            ShoreEdge::Wall
        } else {
            ShoreEdge::Open
        }
    })
}

/// One frame's shore steps: the shore's time at the first, s, and the length of
/// each ([`SHORE_STEPS_PER_FRAME`] of them), s.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShoreSteps {
    /// The shore's time at the first step, s.
    pub start_s: f64,
    /// Each step, s (0: the shore stands still this frame).
    pub dt_s: f32,
}

/// The shore's own clock (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShoreClock {
    time_s: f64,
}

impl ShoreClock {
    /// The shore's time, s.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// The `count` steps of the frame at `frame_time_s`, each at most
    /// `dt_max_s`: the time since the last frame split in `count`; a frame too far
    /// ahead of the shore moves its clock on without steps.
    pub fn advance(&mut self, frame_time_s: f64, dt_max_s: f32, count: u32) -> ShoreSteps {
        let count = count.max(1);
        let most = f64::from(dt_max_s.max(0.0)) * f64::from(count);
        let mut behind = frame_time_s - self.time_s;
        if !(behind.is_finite()) || behind < 0.0 {
            behind = 0.0;
        }
        if behind > MOST_LAG_S.max(most) {
            self.time_s = frame_time_s - most;
            behind = most;
        }
        let advance = behind.min(most);
        let start_s = self.time_s;
        self.time_s += advance;
        ShoreSteps {
            start_s,
            dt_s: (advance / f64::from(count)) as f32,
        }
    }
}

/// One frame of the shore: its block rows, its steps and how many.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShoreFrame {
    /// The frame block's rows.
    pub rows: [Vec4; SHORE_ROWS],
    /// The steps' start and length.
    pub steps: ShoreSteps,
    /// How many steps the frame runs ([`SHORE_STEPS_PER_FRAME`]).
    pub count: u32,
    /// The water's speed cap, m/s.
    pub speed_cap_mps: f32,
}

/// The host's side of the frame's shore: its grid, its clock, the waves coming in
/// (drawn again when the sea's wind changes), and the water it starts from: the
/// sea at rest spun up by [`SHORE_SPIN_UP_STEPS`] stable steps of the CPU
/// reference under the first weather, its clock ending at 0 — a GPU's spin-up
/// would be as fast, but a device that computes on the CPU (lavapipe) takes tens
/// of milliseconds for each of its thousands of dispatches in a first frame.
#[derive(Debug, Clone)]
pub struct ShoreFrames {
    grid: ShoreGrid,
    clock: ShoreClock,
    waves: Option<(SeaState, IncomingWaves)>,
    spun_up: Shore,
}

impl ShoreFrames {
    /// For `grid` under the sea `sea` raises in a wind of `wind_mps` (x, z): the
    /// water spun up, its clock at 0.
    ///
    /// # Errors
    ///
    /// What the reference refuses of the grid or the waves (a grid from
    /// [`ShoreGrid::of_scene`] has none).
    pub fn new(grid: ShoreGrid, sea: &SeaSettings, wind_mps: [f32; 2]) -> Result<Self, ShoreError> {
        let state = sea.state(wind_mps);
        let waves = grid.incoming_waves(&state);
        let (cap, dt) = grid.step_bounds(&waves);
        let mut shore = grid
            .reference(&waves, cap)?
            .starting_at(-f64::from(SHORE_SPIN_UP_STEPS) * f64::from(dt));
        for _ in 0..SHORE_SPIN_UP_STEPS {
            shore.step(dt)?;
        }
        let spun_up = shore.starting_at(0.0);
        Ok(Self {
            grid,
            clock: ShoreClock::default(),
            waves: Some((state, waves)),
            spun_up,
        })
    }

    /// The water the shore starts from, its clock at 0, as the CPU reference.
    #[must_use]
    pub fn spun_up(&self) -> &Shore {
        &self.spun_up
    }

    /// The shore's buffer at first ([`ShoreGrid::initial_buffer`] with the water
    /// spun up).
    #[must_use]
    pub fn initial_buffer(&self) -> Vec<[f32; 4]> {
        let mut words = self.grid.initial_buffer();
        let state = self.spun_up.state();
        for (k, cell) in words[1..=self.grid.cells()].iter_mut().enumerate() {
            cell[0] = state.depth_m[k];
            cell[1] = state.discharge_x_m2ps[k];
            cell[2] = state.discharge_y_m2ps[k];
        }
        let n = self.grid.cells();
        let (a, b) = words.split_at_mut(1 + n);
        b[..n].copy_from_slice(&a[1..]);
        words
    }

    /// The grid.
    #[must_use]
    pub fn grid(&self) -> &ShoreGrid {
        &self.grid
    }

    /// The waves coming in for the sea `sea` raises in a wind of `wind_mps`
    /// (x, z), and its speed cap and stable step.
    pub fn waves(&mut self, sea: &SeaSettings, wind_mps: [f32; 2]) -> (&IncomingWaves, f32, f32) {
        let state = sea.state(wind_mps);
        if self.waves.as_ref().is_some_and(|(s, _)| *s != state) {
            self.waves = None;
        }
        let waves = self
            .waves
            .get_or_insert_with(|| (state, self.grid.incoming_waves(&state)));
        let (cap, dt) = self.grid.step_bounds(&waves.1);
        (&waves.1, cap, dt)
    }

    /// The shore's frame at `frame_time_s` in a wind of `wind_mps` over `sea`: its
    /// steps taken from the shore's clock.
    pub fn next_frame(
        &mut self,
        sea: &SeaSettings,
        wind_mps: [f32; 2],
        frame_time_s: f64,
    ) -> ShoreFrame {
        let (_, cap, dt) = self.waves(sea, wind_mps);
        let count = SHORE_STEPS_PER_FRAME;
        let steps = self.clock.advance(frame_time_s, dt, count);
        let rows = self
            .waves
            .as_ref()
            .map_or([Vec4::ZERO; SHORE_ROWS], |(_, w)| {
                self.grid.rows(w, steps, count, cap)
            });
        ShoreFrame {
            rows,
            steps,
            count,
            speed_cap_mps: cap,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 100 m square of grid whose west side lies 5 m deep.
    fn sloping_grid() -> ShoreGrid {
        let bathymetry = Bathymetry::from_fn(50, 50, 2.0, |x, _| -5.0 + x / 14.0);
        ShoreGrid {
            edges: side_edges(&bathymetry, 0.0),
            bathymetry,
            origin_m: Vec2::ZERO,
            still_level_m: 0.0,
        }
    }

    #[test]
    fn the_waves_come_in_spread_about_the_wind_and_turned_by_it_along_the_shore() {
        let grid = sloping_grid();
        assert_eq!(grid.edges[0], ShoreEdge::Incoming);
        let sea = SeaSettings::default();
        // Onshore (+x, square to the western edge): headings either side of it.
        let onshore = grid.incoming_waves(&sea.state([12.0, 0.0]));
        let signs = |w: &IncomingWaves| {
            (
                w.components
                    .iter()
                    .filter(|c| c.along_edge_per_m > 0.0)
                    .count(),
                w.components
                    .iter()
                    .filter(|c| c.along_edge_per_m < 0.0)
                    .count(),
            )
        };
        let (up, down) = signs(&onshore);
        assert!(up >= 3 && down >= 3, "{up} {down}");
        // Blowing along the shore (+z): most run along +z, and less reaches it.
        let along = grid.incoming_waves(&sea.state([0.0, 12.0]));
        let (up, down) = signs(&along);
        assert!(up > 2 * down, "{up} {down}");
        let energy = |w: &IncomingWaves| {
            w.components
                .iter()
                .map(|c| c.amplitude_m.powi(2))
                .sum::<f32>()
        };
        assert!(energy(&along) < 0.8 * energy(&onshore));
        // Snell's invariant: no wavenumber along the shore beyond the deep water's.
        for c in &along.components {
            let deep = (std::f32::consts::TAU / c.period_s).powi(2) / GRAVITY_MPS2;
            assert!(c.along_edge_per_m.abs() <= deep * 1.0001, "{c:?}");
        }
        // The spreading's quantiles: the median at the mean, symmetric about it.
        assert!(spreading_quantile_rad(0.5).abs() < 0.01);
        let (lo, hi) = (spreading_quantile_rad(0.1), spreading_quantile_rad(0.9));
        assert!((lo + hi).abs() < 0.01 && hi > 0.3 && hi < 1.2, "{lo} {hi}");
    }

    #[test]
    fn the_clock_splits_a_frame_and_never_runs_more_than_its_steps() {
        let mut clock = ShoreClock::default();
        let s = clock.advance(0.04, 0.05, 2);
        assert!((s.dt_s - 0.02).abs() < 1e-7 && s.start_s.abs() < 1e-12);
        // A slow frame: the shore runs at most two steps of the most.
        let s = clock.advance(0.5, 0.05, 2);
        assert!((s.dt_s - 0.05).abs() < 1e-7, "{s:?}");
        assert!((clock.time_s() - 0.14).abs() < 1e-7);
        // Far behind: the clock jumps.
        let s = clock.advance(100.0, 0.05, 2);
        assert!((clock.time_s() - 100.0).abs() < 1e-7 && (s.dt_s - 0.05).abs() < 1e-7);
        // Time going back: no step.
        assert!(clock.advance(50.0, 0.05, 2).dt_s.abs() < f32::EPSILON);
    }
}
