//! The coastal zone: the nonlinear shallow-water equations over a bathymetry
//! (docs/model.md (13.1)–(13.3)).
//!
//! ## The equations
//!
//! Over a bed of elevation `b(x, y)` (m, up), water of depth `h` moving at `(u, v)`:
//!
//! ```text
//! h_t  + (hu)_x + (hv)_y                     = 0
//! (hu)_t + (hu² + g h²/2)_x + (huv)_y        = −g h b_x
//! (hv)_t + (huv)_x + (hv² + g h²/2)_y        = −g h b_y
//! ```
//!
//! ## The scheme
//!
//! Finite volumes on square cells (cell-centred `b`, `h`, `hu`, `hv`):
//!
//! - **MUSCL reconstruction**: in each cell, monotonized-central-limited slopes
//!   (van Leer 1977) of `h`, the
//!   surface `η = h + b`, `u` and `v` give the values at its faces, the bed at a face
//!   `η − h` (so a surface at rest stays flat to its faces, and `h ≥ 0` there);
//! - **hydrostatic reconstruction** (Audusse, Bouchut, Bristeau, Klein & Perthame
//!   2004, *SIAM J. Sci. Comput.* 25): at a face the bed is `b* = max(b_L, b_R)`, the
//!   depths `h*_L,R = max(0, η_L,R − b*)`; the HLL flux of those states, plus the
//!   pressure difference `g/2·(h² − h*²)` each side keeps, plus the centred source
//!   `−g·(h₋ + h₊)/2·(b₊ − b₋)` in each cell: a lake at rest stays at rest over any
//!   bed, dry land and islands included (*well-balanced*), and depths stay
//!   non-negative (wetting and drying without special cases);
//! - **two-stage Runge–Kutta** (Heun's, strong-stability preserving): second order
//!   in time as in space;
//! - the step from the fastest wave: `Δt = C·Δx/(max(|u| + c) + max(|v| + c))`,
//!   `c = √(g h)`, `C` = [`COURANT`].
//!
//! The seed (004) solves the same equations by a flux-splitting scheme with a
//! monotonicity correction; the hydrostatic reconstruction is the widely used
//! well-balanced alternative the issue names, chosen because its balance and its
//! positivity are proven, not tuned.
//!
//! ## Edges
//!
//! Each side of the grid is an [`Edge`]: a vertical wall (reflecting), open
//! (waves leave: the state continued outward), or the open sea's waves coming in
//! ([`IncomingWaves`]: the surface set outside the edge and the water moving in with
//! it as a linear long wave does, `u = η·√(g/d)`).

mod scheme;

use thiserror::Error;

/// Gravity, m/s².
pub const GRAVITY_MPS2: f32 = 9.81;
/// Water shallower than this is dry: it has no velocity, m.
pub const DRY_DEPTH_M: f32 = 1.0e-5;
/// The Courant number of the step ([`Shore::stable_dt_s`]).
pub const COURANT: f32 = 0.45;

/// What was wrong with a shore's setup or step.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ShoreError {
    /// The grid is empty, its cells not positive, or the bed's length is not
    /// `nx·ny` or holds a value that is not finite.
    #[error("bathymetry: {0}")]
    Bathymetry(&'static str),
    /// The state's arrays do not match the grid, or hold negative depths or values
    /// that are not finite.
    #[error("shore state: {0}")]
    State(&'static str),
    /// An incoming wave's amplitude or period is not finite, or its period not
    /// positive.
    #[error("incoming waves: {0}")]
    Waves(&'static str),
    /// A step that is not finite and positive, or longer than the stable step.
    #[error("step of {dt_s} s: it must be finite, positive and at most the stable {stable_s} s")]
    Step {
        /// The step asked for, s.
        dt_s: f32,
        /// The stable step, s.
        stable_s: f32,
    },
    /// A speed cap that is not finite and positive.
    #[error("speed cap of {0} m/s: it must be finite and positive")]
    SpeedCap(f32),
    /// A Manning roughness that is not finite or outside `[0, 0.2]` s/m^⅓.
    #[error("Manning roughness of {0} s/m^(1/3): it must be in [0, 0.2] (sand 0.02 to 0.03)")]
    Friction(f32),
}

/// The bed's elevation over a grid of square cells, m (up), cell-centred, row by
/// row (`x` fastest).
#[derive(Debug, Clone, PartialEq)]
pub struct Bathymetry {
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// A cell's side, m.
    pub cell_m: f32,
    /// The bed's elevation at each cell's centre, m.
    pub bed_m: Vec<f32>,
}

impl Bathymetry {
    /// `nx × ny` cells of `cell_m`, the bed `bed(x, y)` at their centres (m from the
    /// grid's corner).
    #[must_use]
    pub fn from_fn(nx: usize, ny: usize, cell_m: f32, bed: impl Fn(f32, f32) -> f32) -> Self {
        let bed_m = (0..nx * ny)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                bed((i as f32 + 0.5) * cell_m, (j as f32 + 0.5) * cell_m)
            })
            .collect();
        Self {
            nx,
            ny,
            cell_m,
            bed_m,
        }
    }

    /// Checks the grid.
    ///
    /// # Errors
    ///
    /// [`ShoreError::Bathymetry`] naming what is wrong.
    pub fn validate(&self) -> Result<(), ShoreError> {
        if self.nx == 0 || self.ny == 0 {
            return Err(ShoreError::Bathymetry("the grid has no cells"));
        }
        if !(self.cell_m.is_finite() && self.cell_m > 0.0) {
            return Err(ShoreError::Bathymetry("cell_m must be finite and positive"));
        }
        if self.bed_m.len() != self.nx * self.ny {
            return Err(ShoreError::Bathymetry("bed_m must hold nx·ny values"));
        }
        if !self.bed_m.iter().all(|b| b.is_finite()) {
            return Err(ShoreError::Bathymetry(
                "bed_m holds a value that is not finite",
            ));
        }
        Ok(())
    }
}

/// One sinusoid of the waves coming in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveComponent {
    /// Its amplitude, m.
    pub amplitude_m: f32,
    /// Its period, s.
    pub period_s: f32,
    /// Its phase at time 0, rad.
    pub phase_rad: f32,
    /// Its wavenumber along the edge, rad/m: `k·sin θ`, `θ` the angle its crests
    /// make with the edge (0: square to the shore, the same all along the edge).
    /// Snell's law keeps it from deep water to the shore: `ω²/g·sin θ_deep`
    /// ([`WaveComponent::along_edge_per_m`]).
    pub along_edge_per_m: f32,
}

impl WaveComponent {
    /// The wavenumber along a straight shore of a wave of period `period_s`
    /// heading `deep_angle_rad` from the shore's normal in deep water, rad/m: the
    /// deep wavenumber `ω²/g` times `sin θ` — the same at every depth (Snell's law
    /// over depth contours parallel to the shore: the wave turns toward the normal
    /// as it slows, its crests' spacing along the shore unchanged).
    #[must_use]
    pub fn along_edge_per_m(period_s: f32, deep_angle_rad: f32) -> f32 {
        let omega = std::f32::consts::TAU / period_s;
        omega * omega / GRAVITY_MPS2 * deep_angle_rad.sin()
    }
}

/// The open sea's waves at an edge: the still water's level and the sum of
/// sinusoids the surface rises and falls by there.
#[derive(Debug, Clone, PartialEq)]
pub struct IncomingWaves {
    /// The still water's level, m (the bed's datum).
    pub still_level_m: f32,
    /// The sinusoids.
    pub components: Vec<WaveComponent>,
}

impl IncomingWaves {
    /// The surface's rise above the still level at `time_s` at the edge's start
    /// (along it 0 m), m.
    #[must_use]
    pub fn elevation_m(&self, time_s: f64) -> f32 {
        self.elevation_at_m(time_s, 0.0)
    }

    /// The surface's rise above the still level at `time_s`, `along_m` along the
    /// edge from its start, m: `Σ a·cos(ω·t + φ − κ·s)`, `κ` each component's
    /// wavenumber along the edge. WGSL twin: `shore_rise` (render_shore.wgsl).
    #[must_use]
    pub fn elevation_at_m(&self, time_s: f64, along_m: f32) -> f32 {
        self.components
            .iter()
            .map(|c| {
                let phase = std::f64::consts::TAU * time_s / f64::from(c.period_s)
                    + f64::from(c.phase_rad)
                    - f64::from(c.along_edge_per_m) * f64::from(along_m);
                c.amplitude_m * phase.cos() as f32
            })
            .sum()
    }

    /// The open sea's waves `sea` as `components` sinusoids (its frequency spectrum,
    /// [`crate::ocean::frequency_spectrum_rad`], cut into bins of equal width over
    /// the frequencies holding all but 1 % of its energy at each end, each bin's
    /// energy in one sinusoid of amplitude `√(2·S(ω)·Δω)` at a phase drawn from
    /// `seed`): their variance is the spectrum's (docs/model.md (13.3)). The shore's
    /// equations carry them without dispersion: they stand for the sea's long
    /// waves and swell.
    #[must_use]
    pub fn from_sea(
        sea: &crate::ocean::WindSea,
        still_level_m: f32,
        components: usize,
        seed: u32,
    ) -> Self {
        let spectrum = |w: f32| crate::ocean::frequency_spectrum_rad(sea, w);
        // The cumulative energy over a fine grid, to find the 1 % and 99 % points.
        let (lo, hi, steps) = (0.02f32, 20.0f32, 4_000);
        let dw = (hi - lo) / steps as f32;
        let mut cumulative = Vec::with_capacity(steps);
        let mut total = 0.0f32;
        for i in 0..steps {
            total += spectrum(lo + (i as f32 + 0.5) * dw) * dw;
            cumulative.push(total);
        }
        let at = |share: f32| {
            let i = cumulative.partition_point(|&c| c < share * total);
            lo + i as f32 * dw
        };
        let (first, last) = (at(0.01), at(0.99));
        let n = components.max(1);
        let width = (last - first) / n as f32;
        let components = (0..n)
            .map(|i| {
                let omega = first + (i as f32 + 0.5) * width;
                let h = crate::ocean::synthesis::hash(seed ^ (i as u32).wrapping_mul(0x9e37_79b9));
                WaveComponent {
                    amplitude_m: (2.0 * spectrum(omega) * width).sqrt(),
                    period_s: std::f32::consts::TAU / omega,
                    phase_rad: (h >> 8) as f32 / 16_777_216.0 * std::f32::consts::TAU,
                    along_edge_per_m: 0.0,
                }
            })
            .collect();
        Self {
            still_level_m,
            components,
        }
    }

    fn validate(&self) -> Result<(), ShoreError> {
        if !self.still_level_m.is_finite() {
            return Err(ShoreError::Waves("still_level_m must be finite"));
        }
        for c in &self.components {
            if !(c.amplitude_m.is_finite()
                && c.phase_rad.is_finite()
                && c.along_edge_per_m.is_finite())
            {
                return Err(ShoreError::Waves(
                    "amplitude, phase and wavenumber along the edge must be finite",
                ));
            }
            if !(c.period_s.is_finite() && c.period_s > 0.0) {
                return Err(ShoreError::Waves("period_s must be finite and positive"));
            }
        }
        Ok(())
    }
}

/// What one side of the grid is.
#[derive(Debug, Clone, PartialEq)]
pub enum Edge {
    /// A vertical wall: waves are reflected.
    Wall,
    /// Open: waves leave (the state continued outward).
    Open,
    /// The open sea's waves come in.
    Incoming(IncomingWaves),
}

/// The water on the grid: depth and discharges per cell, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct ShoreState {
    /// Depth `h`, m.
    pub depth_m: Vec<f32>,
    /// Discharge `hu` along x, m²/s.
    pub discharge_x_m2ps: Vec<f32>,
    /// Discharge `hv` along y, m²/s.
    pub discharge_y_m2ps: Vec<f32>,
}

impl ShoreState {
    /// Still water up to `level_m` over `bathymetry` (dry where the bed is higher).
    #[must_use]
    pub fn at_rest(bathymetry: &Bathymetry, level_m: f32) -> Self {
        let n = bathymetry.bed_m.len();
        Self {
            depth_m: bathymetry
                .bed_m
                .iter()
                .map(|b| (level_m - b).max(0.0))
                .collect(),
            discharge_x_m2ps: vec![0.0; n],
            discharge_y_m2ps: vec![0.0; n],
        }
    }
}

/// The shore's water over its bathymetry, stepped in time.
#[derive(Debug, Clone)]
pub struct Shore {
    bathymetry: Bathymetry,
    /// West (x = 0), east, south (y = 0), north.
    edges: [Edge; 4],
    state: ShoreState,
    time_s: f64,
    /// The fastest the water may move, m/s ([`Shore::with_speed_cap`]).
    speed_cap_mps: Option<f32>,
    /// The bed's Manning roughness, s/m^⅓ ([`Shore::with_bed_friction`]).
    manning_n: f32,
}

impl Shore {
    /// The water `state` over `bathymetry` with `edges` (west, east, south, north).
    ///
    /// # Errors
    ///
    /// The first thing wrong with the grid, the waves or the state.
    pub fn new(
        bathymetry: Bathymetry,
        edges: [Edge; 4],
        state: ShoreState,
    ) -> Result<Self, ShoreError> {
        bathymetry.validate()?;
        for edge in &edges {
            if let Edge::Incoming(waves) = edge {
                waves.validate()?;
            }
        }
        let n = bathymetry.nx * bathymetry.ny;
        if state.depth_m.len() != n
            || state.discharge_x_m2ps.len() != n
            || state.discharge_y_m2ps.len() != n
        {
            return Err(ShoreError::State("each array must hold nx·ny values"));
        }
        if !state.depth_m.iter().all(|h| h.is_finite() && *h >= 0.0) {
            return Err(ShoreError::State("depths must be finite and not negative"));
        }
        if !state
            .discharge_x_m2ps
            .iter()
            .chain(&state.discharge_y_m2ps)
            .all(|q| q.is_finite())
        {
            return Err(ShoreError::State("discharges must be finite"));
        }
        Ok(Self {
            bathymetry,
            edges,
            state,
            time_s: 0.0,
            speed_cap_mps: None,
            manning_n: 0.0,
        })
    }

    /// The same shore over a bed of Manning roughness `manning_n` s/m^⅓ (sand
    /// 0.02–0.03, Chow 1959; 0, the default: frictionless, as the laboratory
    /// benchmarks are run): each stage of a step slows the water by
    /// `q ← q / (1 + Δt·g·n²·|q|/h^(7/3))`, implicitly, so a thin film running up a
    /// beach stops where it would otherwise race on.
    ///
    /// # Errors
    ///
    /// [`ShoreError::Friction`] for a roughness that is not finite or outside
    /// `[0, 0.2]`.
    pub fn with_bed_friction(mut self, manning_n: f32) -> Result<Self, ShoreError> {
        if !(manning_n.is_finite() && (0.0..=0.2).contains(&manning_n)) {
            return Err(ShoreError::Friction(manning_n));
        }
        self.manning_n = manning_n;
        Ok(self)
    }

    /// The same shore with the water's speed cut to `cap_mps` wherever a stage of a
    /// step leaves it faster (its discharge scaled down, its depth kept: mass is
    /// untouched). A real-time solver steps at a fixed step chosen before the
    /// water moves; the cap keeps that step stable where a thin film on a beach
    /// would otherwise race ahead (`u = q/h` as `h → 0`). Off by default; the GPU's
    /// shore runs with it (`precip_model::drawing::shore`).
    ///
    /// # Errors
    ///
    /// [`ShoreError::SpeedCap`] for a cap that is not finite and positive.
    pub fn with_speed_cap(mut self, cap_mps: f32) -> Result<Self, ShoreError> {
        if !(cap_mps.is_finite() && cap_mps > 0.0) {
            return Err(ShoreError::SpeedCap(cap_mps));
        }
        self.speed_cap_mps = Some(cap_mps);
        Ok(self)
    }

    /// The same shore with its clock at `time_s` (the incoming waves' phases are
    /// read at the shore's time).
    #[must_use]
    pub fn starting_at(mut self, time_s: f64) -> Self {
        self.time_s = time_s;
        self
    }

    /// The edges: west, east, south, north.
    #[must_use]
    pub fn edges(&self) -> &[Edge; 4] {
        &self.edges
    }

    /// The grid.
    #[must_use]
    pub fn bathymetry(&self) -> &Bathymetry {
        &self.bathymetry
    }

    /// The water now.
    #[must_use]
    pub fn state(&self) -> &ShoreState {
        &self.state
    }

    /// The time stepped, s.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// The surface's elevation `h + b` of cell `(i, j)`, m.
    #[must_use]
    pub fn surface_m(&self, i: usize, j: usize) -> f32 {
        let k = j * self.bathymetry.nx + i;
        self.state.depth_m[k] + self.bathymetry.bed_m[k]
    }

    /// The water's volume, m³ (summed in f64).
    #[must_use]
    pub fn volume_m3(&self) -> f64 {
        let area = f64::from(self.bathymetry.cell_m).powi(2);
        self.state
            .depth_m
            .iter()
            .map(|&h| f64::from(h))
            .sum::<f64>()
            * area
    }

    /// The longest step the scheme is stable for now, s ([`COURANT`]); a still,
    /// dry grid gives one second.
    #[must_use]
    pub fn stable_dt_s(&self) -> f32 {
        scheme::stable_dt_s(&self.bathymetry, &self.state)
    }

    /// One step of `dt_s`.
    ///
    /// # Errors
    ///
    /// [`ShoreError::Step`] for a step that is not finite and positive or is longer
    /// than [`Shore::stable_dt_s`] (by more than rounding).
    pub fn step(&mut self, dt_s: f32) -> Result<(), ShoreError> {
        let stable_s = self.stable_dt_s();
        if !(dt_s.is_finite() && dt_s > 0.0 && dt_s <= stable_s * 1.0001) {
            return Err(ShoreError::Step { dt_s, stable_s });
        }
        scheme::step(
            &self.bathymetry,
            &self.edges,
            &mut self.state,
            self.time_s,
            dt_s,
            self.speed_cap_mps,
            self.manning_n,
        );
        self.time_s += f64::from(dt_s);
        Ok(())
    }

    /// Steps of at most the stable step until `duration_s` more has passed; the
    /// number of steps.
    ///
    /// # Errors
    ///
    /// [`ShoreError::Step`] for a duration that is not finite or is negative.
    pub fn advance(&mut self, duration_s: f64) -> Result<u32, ShoreError> {
        if !(duration_s.is_finite() && duration_s >= 0.0) {
            return Err(ShoreError::Step {
                dt_s: duration_s as f32,
                stable_s: self.stable_dt_s(),
            });
        }
        let end = self.time_s + duration_s;
        let mut steps = 0;
        while self.time_s < end - 1.0e-9 {
            let dt = self.stable_dt_s().min((end - self.time_s) as f32);
            self.step(dt)?;
            steps += 1;
        }
        Ok(steps)
    }
}
