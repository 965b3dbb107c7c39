//! The clouds' detail: tiling 3D Perlin–Worley noise (docs/model.md (6.9b)).
//!
//! The coverage map says which columns stand under a cloud; inside a column the
//! cloud's surface is carved by a volume of noise that tiles in all three axes,
//! [`CLOUD_DETAIL_PX`]³ texels over [`super::CLOUD_DETAIL_PERIOD_M`] of air, as
//! Schneider & Vos 2015 carve theirs:
//!
//! - **Perlin–Worley** (`pw`): Perlin noise of three octaves remapped by the
//!   inverted Worley noise of three octaves,
//!   `pw = (perlin − (worley − 1)) / (1 − (worley − 1))` — Perlin's connected
//!   shapes with Worley's round billows at their edges;
//! - **billows** (`w`): the inverted Worley noise at twice the frequency, smaller
//!   heaps on the first.
//!
//! Each is replaced by its rank (spread evenly over `[0, 1)`, as the coverage map
//! is), and the detail is `d = (1 − B)·pw + B·w` ([`CLOUD_BILLOW_SHARE`]).
//!
//! ## On the GPU: slices side by side
//!
//! The volume is one 2D texture of its slices, [`CLOUD_DETAIL_ATLAS_COLUMNS`] a row,
//! each with a border of one texel copied from the opposite side (so the sampler's
//! bilinear filter wraps within a slice instead of bleeding into its neighbour).
//! A texel of slice `k` holds `(pw, pw of k + 1, w, w of k + 1)`: one bilinear read
//! gives both slices around a point, and the shader mixes them by the point's
//! height between them — a trilinear read for the price of one, with no 3D
//! texture in the frame's plan.
//!
//! WGSL twins: `cloud_detail_point`, `cloud_detail_atlas`, `cloud_detail`
//! (drawing.wgsl).

use glam::{IVec3, UVec3, Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::{CLOUD_DETAIL_PERIOD_M, ranks};
use crate::particles::rng::pcg_hash;

/// Texels of the detail volume along each axis (its period).
pub const CLOUD_DETAIL_PX: u32 = 64;
/// Slices of the volume in each row of its atlas.
pub const CLOUD_DETAIL_ATLAS_COLUMNS: u32 = 8;
/// A slice's side in the atlas, texels: the slice and its wrapped border.
pub const CLOUD_DETAIL_TILE_PX: u32 = CLOUD_DETAIL_PX + 2;
/// The atlas's side, texels (square: [`CLOUD_DETAIL_PX`] slices in rows of
/// [`CLOUD_DETAIL_ATLAS_COLUMNS`]).
pub const CLOUD_DETAIL_ATLAS_PX: u32 = CLOUD_DETAIL_ATLAS_COLUMNS * CLOUD_DETAIL_TILE_PX;
/// The billows' share `B` of the detail.
pub const CLOUD_BILLOW_SHARE: f32 = 0.35;

/// Where `p` reads the detail volume, in its periods: the point drifted by
/// `offset_m` with the coverage map, so the carving sails with the clouds.
#[must_use]
pub fn cloud_detail_point(p: Vec3, offset_m: Vec2) -> Vec3 {
    Vec3::new(p.x + offset_m.x, p.y, p.z + offset_m.y) / CLOUD_DETAIL_PERIOD_M
}

/// The atlas's `uv` of the slice below `q` (a point in periods) and the weight of
/// the slice above it.
#[must_use]
pub fn cloud_detail_atlas(q: Vec3) -> (Vec2, f32) {
    let n = CLOUD_DETAIL_PX as f32;
    // x − floor(x), as WGSL's fract (f32::fract truncates toward zero).
    let s = (q - q.floor()) * n;
    let z = s.z - 0.5;
    let below = z.floor();
    let k = ((below + n) as u32) % CLOUD_DETAIL_PX;
    let tile = Vec2::new(
        (k % CLOUD_DETAIL_ATLAS_COLUMNS) as f32,
        (k / CLOUD_DETAIL_ATLAS_COLUMNS) as f32,
    );
    let uv = (tile * CLOUD_DETAIL_TILE_PX as f32 + Vec2::ONE + Vec2::new(s.x, s.y))
        / CLOUD_DETAIL_ATLAS_PX as f32;
    (uv, z - below)
}

/// The detail `d` from an atlas texel read at [`cloud_detail_atlas`]'s `uv` and
/// its weight `w` of the slice above.
#[must_use]
pub fn cloud_detail(texel: Vec4, w: f32) -> f32 {
    let pw = texel.x + w * (texel.y - texel.x);
    let billows = texel.z + w * (texel.w - texel.z);
    pw + CLOUD_BILLOW_SHARE * (billows - pw)
}

/// The atlas's texel at `uv`, bilinear as the GPU's sampler (RGBA8, in `[0, 1]`).
#[must_use]
pub fn sample_cloud_detail_atlas(atlas: &[u8], uv: Vec2) -> Vec4 {
    super::sample_repeating(CLOUD_DETAIL_ATLAS_PX, uv, |texel| {
        let i = texel * 4;
        atlas.get(i..i + 4).map_or(Vec4::ZERO, |t| {
            Vec4::new(
                f32::from(t[0]),
                f32::from(t[1]),
                f32::from(t[2]),
                f32::from(t[3]),
            ) / 255.0
        })
    })
}

/// The detail at `p` (the map drifted by `offset_m`) read from `atlas` as the GPU
/// reads it.
#[must_use]
pub fn cloud_detail_at(atlas: &[u8], p: Vec3, offset_m: Vec2) -> f32 {
    let (uv, w) = cloud_detail_atlas(cloud_detail_point(p, offset_m));
    cloud_detail(sample_cloud_detail_atlas(atlas, uv), w)
}

/// The detail volume's atlas: [`CLOUD_DETAIL_ATLAS_PX`]² RGBA8 texels (module
/// docs), deterministic.
#[must_use]
pub fn cloud_detail_atlas_texels() -> Vec<u8> {
    let n = CLOUD_DETAIL_PX;
    let count = (n * n * n) as usize;
    let index = |t: UVec3| (t.x + n * (t.y + n * t.z)) as usize;
    let (coarse, fine) = (WorleyCells::octaves(2), WorleyCells::octaves(4));
    // Each texel on its own (made at the first configure: in parallel, the same
    // values whatever the threads).
    let (perlin_worley, billows): (Vec<f32>, Vec<f32>) = (0..count)
        .into_par_iter()
        .map(|i| {
            let t = UVec3::new(i as u32 % n, (i as u32 / n) % n, i as u32 / (n * n));
            let p = (t.as_vec3() + 0.5) / n as f32;
            let perlin = 0.5 + perlin_octaves(p);
            let worley = worley_octaves(p, &coarse);
            (
                (perlin - (worley - 1.0)) / (2.0 - worley),
                worley_octaves(p, &fine),
            )
        })
        .unzip();
    let pw = ranks(&perlin_worley);
    let w = ranks(&billows);
    let side = CLOUD_DETAIL_ATLAS_PX as usize;
    let mut atlas = vec![0u8; side * side * 4];
    let wrap = |i: u32| (i + n - 1) % n;
    for k in 0..n {
        let above = (k + 1) % n;
        let corner_x = (k % CLOUD_DETAIL_ATLAS_COLUMNS) * CLOUD_DETAIL_TILE_PX;
        let corner_y = (k / CLOUD_DETAIL_ATLAS_COLUMNS) * CLOUD_DETAIL_TILE_PX;
        for ty in 0..CLOUD_DETAIL_TILE_PX {
            for tx in 0..CLOUD_DETAIL_TILE_PX {
                // Tile texel tx holds the slice's texel tx − 1, wrapped.
                let (x, y) = (wrap(tx), wrap(ty));
                let at = index(UVec3::new(x, y, k));
                let up = index(UVec3::new(x, y, above));
                let o = (((corner_y + ty) as usize) * side + (corner_x + tx) as usize) * 4;
                atlas[o..o + 4].copy_from_slice(&[pw[at], pw[up], w[at], w[up]]);
            }
        }
    }
    atlas
}

/// Three octaves of tiling 3D Perlin noise (periods 4, 8 and 16 lattice cells
/// over the unit cube) at `p` in `[0, 1)³`, about `[−0.5, 0.5]`.
fn perlin_octaves(p: Vec3) -> f32 {
    super::octaves(3, |period, octave| {
        tiling_perlin_3d(p * period as f32, period, octave)
    }) / 1.75
        * 0.9
}

/// Three octaves of inverted tiling Worley noise (`1 − F1`, cells `cells`, twice
/// and four times as many along each axis, weights 0.625, 0.25, 0.125) at `p` in
/// `[0, 1)³`, in `[0, 1]`.
fn worley_octaves(p: Vec3, octaves: &[WorleyCells; 3]) -> f32 {
    0.625 * (1.0 - tiling_worley(p, &octaves[0]))
        + 0.25 * (1.0 - tiling_worley(p, &octaves[1]))
        + 0.125 * (1.0 - tiling_worley(p, &octaves[2]))
}

/// The random point of each cell of a tiling Worley lattice, drawn once: its
/// offset in the cell, by wrapped cell.
struct WorleyCells {
    cells: u32,
    offsets: Vec<Vec3>,
}

impl WorleyCells {
    /// `cells` along each axis of the unit cube, the points of `seed`.
    fn new(cells: u32, seed: u32) -> Self {
        let offsets = (0..cells * cells * cells)
            .map(|i| {
                let c = IVec3::new(
                    (i % cells) as i32,
                    ((i / cells) % cells) as i32,
                    (i / (cells * cells)) as i32,
                );
                let h = cell_hash(c, cells, seed);
                Vec3::new(
                    unit(h),
                    unit(pcg_hash(h ^ 0x68e3_1da4)),
                    unit(pcg_hash(h ^ 0xb529_7a4d)),
                )
            })
            .collect();
        Self { cells, offsets }
    }

    /// Three octaves from `cells` (twice and four times as many), seeds 11–13.
    fn octaves(cells: u32) -> [Self; 3] {
        [
            Self::new(cells, 11),
            Self::new(cells * 2, 12),
            Self::new(cells * 4, 13),
        ]
    }
}

/// A lattice hash of a cell wrapped to `period`.
fn cell_hash(cell: IVec3, period: u32, seed: u32) -> u32 {
    let period = period as i32;
    let c = UVec3::new(
        cell.x.rem_euclid(period) as u32,
        cell.y.rem_euclid(period) as u32,
        cell.z.rem_euclid(period) as u32,
    );
    pcg_hash(
        c.x.wrapping_mul(0x9e37_79b1)
            ^ c.y.wrapping_mul(0x85eb_ca77)
            ^ c.z.wrapping_mul(0xc2b2_ae3d)
            ^ seed.wrapping_mul(0x27d4_eb2f),
    )
}

/// A unit `[0, 1)` from a hash.
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 / 16_777_216.0
}

/// 3D Perlin noise of period `period` (lattice cells) at `p`, about `[−1, 1]`
/// (gradients toward the twelve edges of a cube, Perlin 2002).
fn tiling_perlin_3d(p: Vec3, period: u32, seed: u32) -> f32 {
    const GRADIENTS: [Vec3; 12] = [
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(0.0, 1.0, 1.0),
        Vec3::new(0.0, -1.0, 1.0),
        Vec3::new(0.0, 1.0, -1.0),
        Vec3::new(0.0, -1.0, -1.0),
    ];
    let cell = p.floor();
    let f = p - cell;
    let base = cell.as_ivec3();
    let corner = |d: IVec3| {
        let g = GRADIENTS[(cell_hash(base + d, period, seed) % 12) as usize];
        g.dot(f - d.as_vec3())
    };
    let fade = |t: f32| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let lerp = |a: f32, b: f32, t: f32| a + t * (b - a);
    let face = |dz: i32| {
        let a = lerp(
            corner(IVec3::new(0, 0, dz)),
            corner(IVec3::new(1, 0, dz)),
            u,
        );
        let b = lerp(
            corner(IVec3::new(0, 1, dz)),
            corner(IVec3::new(1, 1, dz)),
            u,
        );
        lerp(a, b, v)
    };
    lerp(face(0), face(1), w)
}

/// Worley's F1 (the distance to the nearest of one random point a cell, in cells,
/// at most 1) of `cells` cells along each axis of the unit cube, tiling, at `p` in
/// `[0, 1)³`.
fn tiling_worley(p: Vec3, lattice: &WorleyCells) -> f32 {
    let cells = lattice.cells;
    let q = p * cells as f32;
    let base = q.floor().as_ivec3();
    let period = cells as i32;
    let mut nearest = f32::MAX;
    for dz in -1..=1 {
        for dy in -1..=1 {
            for dx in -1..=1 {
                let cell = base + IVec3::new(dx, dy, dz);
                let w = IVec3::new(
                    cell.x.rem_euclid(period),
                    cell.y.rem_euclid(period),
                    cell.z.rem_euclid(period),
                );
                let k = (w.x + period * (w.y + period * w.z)) as usize;
                let point = cell.as_vec3() + lattice.offsets[k];
                nearest = nearest.min(point.distance_squared(q));
            }
        }
    }
    nearest.sqrt().min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn atlas() -> &'static [u8] {
        &super::super::cloud_noise().detail
    }

    /// The volume's texel `t` (wrapped) as stored: (pw, w).
    fn stored(atlas: &[u8], t: IVec3) -> (u8, u8) {
        let n = CLOUD_DETAIL_PX as i32;
        let k = t.z.rem_euclid(n) as u32;
        let x =
            t.x.rem_euclid(n) as u32 + 1 + (k % CLOUD_DETAIL_ATLAS_COLUMNS) * CLOUD_DETAIL_TILE_PX;
        let y =
            t.y.rem_euclid(n) as u32 + 1 + (k / CLOUD_DETAIL_ATLAS_COLUMNS) * CLOUD_DETAIL_TILE_PX;
        let o = ((y * CLOUD_DETAIL_ATLAS_PX + x) * 4) as usize;
        (atlas[o], atlas[o + 2])
    }

    #[test]
    fn the_volume_s_values_are_spread_evenly_and_made_alike_each_time() {
        let atlas = atlas();
        let n = CLOUD_DETAIL_PX as i32;
        let mut histogram = [[0usize; 8]; 2];
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    let (pw, w) = stored(atlas, IVec3::new(x, y, z));
                    histogram[0][usize::from(pw) / 32] += 1;
                    histogram[1][usize::from(w) / 32] += 1;
                }
            }
        }
        let each = (n * n * n) as usize / 8;
        assert!(
            histogram.iter().flatten().all(|&h| h == each),
            "{histogram:?}"
        );
        assert_eq!(atlas, cloud_detail_atlas_texels(), "deterministic");
    }

    #[test]
    fn the_volume_tiles_in_every_axis_without_a_seam() {
        // Neighbours across the period's seam differ no more than neighbours inside.
        let atlas = atlas();
        let n = CLOUD_DETAIL_PX as i32;
        for axis in [IVec3::X, IVec3::Y, IVec3::Z] {
            let (mut seam, mut inside) = (0i32, 0i32);
            for a in 0..n {
                for b in 0..n {
                    let across = match axis {
                        IVec3 { x: 1, .. } => IVec3::new(0, a, b),
                        IVec3 { y: 1, .. } => IVec3::new(a, 0, b),
                        _ => IVec3::new(a, b, 0),
                    };
                    let jump = |from: IVec3| {
                        let (p, _) = stored(atlas, from);
                        let (q, _) = stored(atlas, from + axis);
                        (i32::from(p) - i32::from(q)).abs()
                    };
                    seam += jump(across - axis);
                    inside += jump(across + axis * (n / 2));
                }
            }
            assert!(
                seam * 10 < inside * 13,
                "{axis}: seam {seam} against inside {inside}"
            );
        }
    }

    #[test]
    fn reading_the_atlas_is_reading_the_volume_trilinearly_and_it_wraps() {
        let atlas = atlas();
        let n = CLOUD_DETAIL_PX as f32;
        let texel = |t: IVec3| {
            let (pw, w) = stored(atlas, t);
            f32::from(pw) / 255.0 + CLOUD_BILLOW_SHARE * (f32::from(w) - f32::from(pw)) / 255.0
        };
        let mut worst = 0.0f32;
        for i in 0..2_000u32 {
            let h = |salt: u32| unit(pcg_hash(i.wrapping_mul(3) ^ salt)) * 3.0 - 1.5;
            let q = Vec3::new(h(1), h(2), h(3));
            // Trilinear over the volume's texels, centres at (i + 0.5)/n.
            let s = (q - q.floor()) * n - Vec3::splat(0.5);
            let cell = s.floor();
            let f = s - cell;
            let c = cell.as_ivec3();
            let mut expected = 0.0;
            for corner in 0..8 {
                let d = IVec3::new(corner & 1, (corner >> 1) & 1, corner >> 2);
                let weight = Vec3::select(d.cmpeq(IVec3::ONE), f, Vec3::ONE - f);
                expected += weight.x * weight.y * weight.z * texel(c + d);
            }
            let (uv, w) = cloud_detail_atlas(q);
            let got = cloud_detail(sample_cloud_detail_atlas(atlas, uv), w);
            worst = worst.max((got - expected).abs());
            // One period away reads the same.
            let (uv2, w2) = cloud_detail_atlas(q + Vec3::new(1.0, -2.0, 1.0));
            let again = cloud_detail(sample_cloud_detail_atlas(atlas, uv2), w2);
            assert!((again - got).abs() < 1e-3, "{q}: {got} against {again}");
        }
        assert!(worst < 1e-4, "worst {worst}");
    }

    #[test]
    fn the_carving_is_billowed_not_white_noise() {
        // Neighbouring texels are alike (correlated), texels half a period apart
        // are not: the detail has shapes a few texels across.
        let atlas = atlas();
        let n = CLOUD_DETAIL_PX as i32;
        let samples: Vec<IVec3> = (0..4_000u32)
            .map(|i| {
                let c = |salt: u32| (pcg_hash(i ^ salt) % n as u32) as i32;
                IVec3::new(c(5), c(6), c(7))
            })
            .collect();
        let correlation = |offset: IVec3| {
            let pairs: Vec<(f32, f32)> = samples
                .iter()
                .map(|&t| {
                    (
                        f32::from(stored(atlas, t).0),
                        f32::from(stored(atlas, t + offset).0),
                    )
                })
                .collect();
            let m = pairs.len() as f32;
            let (ma, mb) = (
                pairs.iter().map(|p| p.0).sum::<f32>() / m,
                pairs.iter().map(|p| p.1).sum::<f32>() / m,
            );
            let cov: f32 = pairs.iter().map(|p| (p.0 - ma) * (p.1 - mb)).sum();
            let va: f32 = pairs.iter().map(|p| (p.0 - ma).powi(2)).sum();
            let vb: f32 = pairs.iter().map(|p| (p.1 - mb).powi(2)).sum();
            cov / (va * vb).sqrt()
        };
        let near = correlation(IVec3::new(1, 0, 0));
        let up = correlation(IVec3::new(0, 0, 1));
        let far = correlation(IVec3::new(n / 2, 0, n / 2));
        assert!(near > 0.8 && up > 0.8, "neighbours: {near}, {up}");
        assert!(far.abs() < 0.2, "half a period apart: {far}");
    }
}
