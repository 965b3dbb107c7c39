//! The finite-volume scheme of [`super`]: the grid padded with two cells of each
//! edge's ghosts, MUSCL faces, the hydrostatic reconstruction at each face, the HLL
//! flux, the centred bed source, two Runge–Kutta stages.

use super::{Bathymetry, COURANT, DRY_DEPTH_M, Edge, GRAVITY_MPS2 as G, ShoreState};

/// Ghost cells around the grid (the MUSCL slopes of the edge cells' neighbours).
const GHOSTS: usize = 2;

/// Conserved variables and the bed on the padded grid, row by row.
#[derive(Debug, Clone)]
struct Padded {
    /// Padded cells along x.
    width: usize,
    h: Vec<f32>,
    qx: Vec<f32>,
    qy: Vec<f32>,
    b: Vec<f32>,
}

impl Padded {
    fn new(bathymetry: &Bathymetry, state: &ShoreState) -> Self {
        let (width, height) = (bathymetry.nx + 2 * GHOSTS, bathymetry.ny + 2 * GHOSTS);
        let mut padded = Self {
            width,
            h: vec![0.0; width * height],
            qx: vec![0.0; width * height],
            qy: vec![0.0; width * height],
            b: vec![0.0; width * height],
        };
        for j in 0..bathymetry.ny {
            for i in 0..bathymetry.nx {
                let (k, p) = (j * bathymetry.nx + i, padded.at(i + GHOSTS, j + GHOSTS));
                padded.h[p] = state.depth_m[k];
                padded.qx[p] = state.discharge_x_m2ps[k];
                padded.qy[p] = state.discharge_y_m2ps[k];
                padded.b[p] = bathymetry.bed_m[k];
            }
        }
        padded
    }

    const fn at(&self, i: usize, j: usize) -> usize {
        j * self.width + i
    }

    /// Copies cell `from` into ghost `to`, the normal discharge (x if `normal_x`)
    /// negated for a wall.
    fn mirror(&mut self, to: usize, from: usize, normal_x: bool, negate: bool) {
        let sign = if negate { -1.0 } else { 1.0 };
        self.h[to] = self.h[from];
        self.b[to] = self.b[from];
        let (normal, tangent) = if normal_x {
            (self.qx[from], self.qy[from])
        } else {
            (self.qy[from], self.qx[from])
        };
        self.set_discharge(to, normal_x, sign * normal, tangent);
    }

    fn set_discharge(&mut self, k: usize, normal_x: bool, normal: f32, tangent: f32) {
        if normal_x {
            self.qx[k] = normal;
            self.qy[k] = tangent;
        } else {
            self.qy[k] = normal;
            self.qx[k] = tangent;
        }
    }
}

/// A velocity from a discharge: none where the cell is dry.
fn velocity(h: f32, q: f32) -> f32 {
    if h > DRY_DEPTH_M { q / h } else { 0.0 }
}

/// The monotonized-central slope of van Leer 1977 from the differences to either
/// neighbour: `minmod(2a, (a + b)/2, 2b)` — sharper than minmod on smooth waves, still
/// without new extrema (a face value lies between the neighbours', so depths stay
/// non-negative at the faces).
fn limited_slope(a: f32, b: f32) -> f32 {
    if a * b <= 0.0 {
        0.0
    } else {
        let m = (2.0 * a.abs()).min(2.0 * b.abs()).min(0.5 * (a + b).abs());
        m.copysign(a)
    }
}

/// The stable step ([`super::Shore::stable_dt_s`]).
pub(super) fn stable_dt_s(bathymetry: &Bathymetry, state: &ShoreState) -> f32 {
    let (mut ax, mut ay) = (0.0f32, 0.0f32);
    for (k, &h) in state.depth_m.iter().enumerate() {
        if h <= DRY_DEPTH_M {
            continue;
        }
        let c = (G * h).sqrt();
        ax = ax.max(velocity(h, state.discharge_x_m2ps[k]).abs() + c);
        ay = ay.max(velocity(h, state.discharge_y_m2ps[k]).abs() + c);
    }
    if ax + ay <= 0.0 {
        1.0
    } else {
        COURANT * bathymetry.cell_m / (ax + ay)
    }
}

/// One step of `dt_s` from `time_s`: Heun's two stages.
pub(super) fn step(
    bathymetry: &Bathymetry,
    edges: &[Edge; 4],
    state: &mut ShoreState,
    time_s: f64,
    dt_s: f32,
    speed_cap_mps: Option<f32>,
    manning_n: f32,
) {
    let mut first = Padded::new(bathymetry, state);
    fill_edges(&mut first, bathymetry, edges, time_s);
    let rates = rates_of(&first, bathymetry);
    let mut second = first.clone();
    for k in interior(bathymetry, &first) {
        second.h[k] = first.h[k] + dt_s * rates[0][k];
        second.qx[k] = first.qx[k] + dt_s * rates[1][k];
        second.qy[k] = first.qy[k] + dt_s * rates[2][k];
        keep_dry_at_rest(&mut second, k);
        (second.qx[k], second.qy[k]) =
            bed_friction(second.h[k], second.qx[k], second.qy[k], dt_s, manning_n);
        if let Some(cap) = speed_cap_mps {
            (second.qx[k], second.qy[k]) =
                capped_discharge(second.h[k], second.qx[k], second.qy[k], cap);
        }
    }
    fill_edges(&mut second, bathymetry, edges, time_s + f64::from(dt_s));
    let rates = rates_of(&second, bathymetry);
    for j in 0..bathymetry.ny {
        for i in 0..bathymetry.nx {
            let k = first.at(i + GHOSTS, j + GHOSTS);
            let mut h = 0.5 * (first.h[k] + second.h[k] + dt_s * rates[0][k]);
            let mut qx = 0.5 * (first.qx[k] + second.qx[k] + dt_s * rates[1][k]);
            let mut qy = 0.5 * (first.qy[k] + second.qy[k] + dt_s * rates[2][k]);
            if h <= DRY_DEPTH_M {
                h = h.max(0.0);
                qx = 0.0;
                qy = 0.0;
            }
            (qx, qy) = bed_friction(h, qx, qy, dt_s, manning_n);
            if let Some(cap) = speed_cap_mps {
                (qx, qy) = capped_discharge(h, qx, qy, cap);
            }
            let s = j * bathymetry.nx + i;
            state.depth_m[s] = h;
            state.discharge_x_m2ps[s] = qx;
            state.discharge_y_m2ps[s] = qy;
        }
    }
}

/// The padded indices of the grid's own cells.
fn interior<'a>(
    bathymetry: &'a Bathymetry,
    padded: &'a Padded,
) -> impl Iterator<Item = usize> + 'a {
    (0..bathymetry.ny)
        .flat_map(move |j| (0..bathymetry.nx).map(move |i| padded.at(i + GHOSTS, j + GHOSTS)))
}

/// The discharge `(qx, qy)` of water `h` deep after a step `dt_s` of the bed's
/// friction by Manning's `n` (s/m^⅓), taken implicitly:
/// `q ← q / (1 + Δt·g·n²·|q|/h^(7/3))` (the friction slope `n²·|u|·u/h^(4/3)`; it
/// slows a thin film on a beach, hardly a deep wave, and never reverses the flow).
/// WGSL twin: `shore_bed_friction`.
pub(super) fn bed_friction(h: f32, qx: f32, qy: f32, dt_s: f32, manning_n: f32) -> (f32, f32) {
    if h <= DRY_DEPTH_M || manning_n <= 0.0 {
        return (qx, qy);
    }
    let q = (qx * qx + qy * qy).sqrt();
    let f = 1.0 + dt_s * G * manning_n * manning_n * q / (h * h * h.powf(1.0 / 3.0));
    (qx / f, qy / f)
}

/// The discharge `(qx, qy)` of water `h` deep, its speed cut to `cap_mps` where it
/// moves faster ([`super::Shore::with_speed_cap`]). WGSL twin: `shore_capped`.
pub(super) fn capped_discharge(h: f32, qx: f32, qy: f32, cap_mps: f32) -> (f32, f32) {
    let most = cap_mps * h;
    let q = (qx * qx + qy * qy).sqrt();
    if q > most && q > 0.0 {
        let s = most / q;
        (qx * s, qy * s)
    } else {
        (qx, qy)
    }
}

/// A depth below nothing is none; a dry cell does not move.
fn keep_dry_at_rest(padded: &mut Padded, k: usize) {
    if padded.h[k] <= DRY_DEPTH_M {
        padded.h[k] = padded.h[k].max(0.0);
        padded.qx[k] = 0.0;
        padded.qy[k] = 0.0;
    }
}

/// The ghosts of each edge at `time_s` (module docs of [`super`]).
fn fill_edges(padded: &mut Padded, bathymetry: &Bathymetry, edges: &[Edge; 4], time_s: f64) {
    let (nx, ny) = (bathymetry.nx, bathymetry.ny);
    // Each side: its ghosts (distance 1 and 2 out), the cells they mirror, the cell
    // on the edge, the normal's axis and which way is inward.
    for (side, edge) in edges.iter().enumerate() {
        let along = if side < 2 { ny } else { nx };
        for a in 0..along {
            for d in 1..=GHOSTS {
                let (ghost, mirrored, edge_cell, normal_x, inward) = match side {
                    0 => (
                        padded.at(GHOSTS - d, a + GHOSTS),
                        padded.at(GHOSTS + d - 1, a + GHOSTS),
                        padded.at(GHOSTS, a + GHOSTS),
                        true,
                        1.0,
                    ),
                    1 => (
                        padded.at(GHOSTS + nx - 1 + d, a + GHOSTS),
                        padded.at(GHOSTS + nx - d, a + GHOSTS),
                        padded.at(GHOSTS + nx - 1, a + GHOSTS),
                        true,
                        -1.0,
                    ),
                    2 => (
                        padded.at(a + GHOSTS, GHOSTS - d),
                        padded.at(a + GHOSTS, GHOSTS + d - 1),
                        padded.at(a + GHOSTS, GHOSTS),
                        false,
                        1.0,
                    ),
                    _ => (
                        padded.at(a + GHOSTS, GHOSTS + ny - 1 + d),
                        padded.at(a + GHOSTS, GHOSTS + ny - d),
                        padded.at(a + GHOSTS, GHOSTS + ny - 1),
                        false,
                        -1.0,
                    ),
                };
                match edge {
                    Edge::Wall => padded.mirror(ghost, mirrored, normal_x, true),
                    Edge::Open => padded.mirror(ghost, edge_cell, normal_x, false),
                    Edge::Incoming(waves) => {
                        // The ghost's place along the edge, m from its start.
                        let along = (a as f32 + 0.5) * bathymetry.cell_m;
                        let rise = waves.elevation_at_m(time_s, along);
                        let (h, speed) =
                            incoming_ghost(padded, edge_cell, waves, rise, normal_x, inward);
                        padded.h[ghost] = h;
                        padded.b[ghost] = padded.b[edge_cell];
                        padded.set_discharge(ghost, normal_x, h * speed, 0.0);
                    }
                }
            }
        }
    }
}

/// The ghost's depth and normal velocity at an edge where `waves` come in, their surface `rise` over the still level there: the
/// characteristic moving inward, `w + 2c`, the wave's (a linear long wave of rise
/// `η`: `w = η·√(g/d)`, `c = √(g·(d + η))`), the one moving out, `w − 2c`, the edge
/// cell's (`w` the velocity inward, `inward` its sign along the axis): so the waves
/// come in and what the shore reflects leaves.
fn incoming_ghost(
    padded: &Padded,
    edge_cell: usize,
    waves: &super::IncomingWaves,
    rise: f32,
    normal_x: bool,
    inward: f32,
) -> (f32, f32) {
    let bed = padded.b[edge_cell];
    let still = waves.still_level_m - bed;
    if still <= DRY_DEPTH_M {
        return (0.0, 0.0);
    }
    let wave_depth = (still + rise).max(0.0);
    let coming = rise * (G / still).sqrt() + 2.0 * (G * wave_depth).sqrt();
    let h = padded.h[edge_cell];
    let q = if normal_x {
        padded.qx[edge_cell]
    } else {
        padded.qy[edge_cell]
    };
    let leaving = inward * velocity(h, q) - 2.0 * (G * h).sqrt();
    let c = (0.25 * (coming - leaving)).max(0.0);
    (c * c / G, inward * 0.5 * (coming + leaving))
}

/// A face's state: depth, bed, normal and tangential velocity.
#[derive(Debug, Clone, Copy, Default)]
struct Face {
    h: f32,
    b: f32,
    normal: f32,
    tangent: f32,
}

/// The rates of change of `(h, hu, hv)` of every cell (padded indices; ghosts 0).
fn rates_of(padded: &Padded, bathymetry: &Bathymetry) -> [Vec<f32>; 3] {
    let n = padded.h.len();
    let mut rates = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let w = padded.width;
    // Along x: lines are rows; along y: columns.
    sweep(
        padded,
        bathymetry.cell_m,
        bathymetry.nx,
        bathymetry.ny,
        1,
        w,
        true,
        &mut rates,
    );
    sweep(
        padded,
        bathymetry.cell_m,
        bathymetry.ny,
        bathymetry.nx,
        w,
        1,
        false,
        &mut rates,
    );
    rates
}

/// The faces, fluxes and sources along one axis.
#[expect(
    clippy::too_many_arguments,
    reason = "the axis is its strides and counts; one call per axis"
)]
fn sweep(
    padded: &Padded,
    dx: f32,
    along: usize,
    across: usize,
    stride: usize,
    line_stride: usize,
    normal_x: bool,
    rates: &mut [Vec<f32>; 3],
) {
    let (normal_rate, tangent_rate) = if normal_x { (1, 2) } else { (2, 1) };
    let mut minus = vec![Face::default(); along + 2 * GHOSTS];
    let mut plus = vec![Face::default(); along + 2 * GHOSTS];
    for line in 0..across {
        let base = (line + GHOSTS) * line_stride;
        let cell = |t: usize| base + t * stride;
        // Each cell's faces, from its own and its neighbours' values.
        let values = |t: usize| {
            let k = cell(t);
            let h = padded.h[k];
            let (qn, qt) = if normal_x {
                (padded.qx[k], padded.qy[k])
            } else {
                (padded.qy[k], padded.qx[k])
            };
            [h, h + padded.b[k], velocity(h, qn), velocity(h, qt)]
        };
        for t in GHOSTS - 1..=GHOSTS + along {
            let (before, here, after) = (values(t - 1), values(t), values(t + 1));
            let slope: [f32; 4] =
                std::array::from_fn(|v| limited_slope(here[v] - before[v], after[v] - here[v]));
            let face = |sign: f32| {
                let h = here[0] + sign * 0.5 * slope[0];
                let eta = here[1] + sign * 0.5 * slope[1];
                Face {
                    h,
                    b: eta - h,
                    normal: here[2] + sign * 0.5 * slope[2],
                    tangent: here[3] + sign * 0.5 * slope[3],
                }
            };
            minus[t] = face(-1.0);
            plus[t] = face(1.0);
        }
        // The faces between t and t + 1.
        for t in GHOSTS - 1..GHOSTS + along {
            let (left, right) = (plus[t], minus[t + 1]);
            let bed = left.b.max(right.b);
            let hl = (left.h + left.b - bed).max(0.0);
            let hr = (right.h + right.b - bed).max(0.0);
            let flux = hll(Face { h: hl, ..left }, Face { h: hr, ..right });
            if t >= GHOSTS {
                let k = cell(t);
                rates[0][k] -= flux[0] / dx;
                rates[normal_rate][k] -= (flux[1] + 0.5 * G * (left.h * left.h - hl * hl)) / dx;
                rates[tangent_rate][k] -= flux[2] / dx;
            }
            if t + 1 < GHOSTS + along {
                let k = cell(t + 1);
                rates[0][k] += flux[0] / dx;
                rates[normal_rate][k] += (flux[1] + 0.5 * G * (right.h * right.h - hr * hr)) / dx;
                rates[tangent_rate][k] += flux[2] / dx;
            }
        }
        // The bed's centred source.
        for t in GHOSTS..GHOSTS + along {
            let (m, p) = (minus[t], plus[t]);
            rates[normal_rate][cell(t)] -= G * 0.5 * (m.h + p.h) * (p.b - m.b) / dx;
        }
    }
}

/// The HLL flux of `(h, h·u_n, h·u_t)` between two face states.
fn hll(left: Face, right: Face) -> [f32; 3] {
    if left.h <= DRY_DEPTH_M && right.h <= DRY_DEPTH_M {
        return [0.0; 3];
    }
    let physical = |f: Face| {
        let (un, ut) = if f.h > DRY_DEPTH_M {
            (f.normal, f.tangent)
        } else {
            (0.0, 0.0)
        };
        (
            [f.h * un, f.h * un * un + 0.5 * G * f.h * f.h, f.h * un * ut],
            [f.h, f.h * un, f.h * ut],
            un,
        )
    };
    let (fl, ul, unl) = physical(left);
    let (fr, ur, unr) = physical(right);
    let (cl, cr) = ((G * left.h).sqrt(), (G * right.h).sqrt());
    let sl = (unl - cl).min(unr - cr);
    let sr = (unl + cl).max(unr + cr);
    if sl >= 0.0 {
        fl
    } else if sr <= 0.0 {
        fr
    } else {
        std::array::from_fn(|v| (sr * fl[v] - sl * fr[v] + sl * sr * (ur[v] - ul[v])) / (sr - sl))
    }
}
