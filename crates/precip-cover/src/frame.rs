//! [`GridFrame`]: a regular grid over a world rectangle in the XZ plane.

use bytemuck::{Pod, Zeroable};
use glam::{UVec2, Vec2};

use crate::error::{CoverError, check_range};

/// A grid of `texels.x × texels.y` cells over the world rectangle
/// `[origin_m.x, origin_m.x + size_m.x] × [origin_m.y, origin_m.y + size_m.y]` in world
/// X and Z (`Vec2` here is `(x, z)`). Texel `(i, j)` is stored at `i + texels.x · j`.
///
/// WGSL twin: `GridFrame` in `shaders/layout.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GridFrame {
    /// World (x, z) of the grid's minimum corner, metres.
    pub origin_m: Vec2,
    /// World size along x and z, metres.
    pub size_m: Vec2,
    /// Texels along x and z.
    pub texels: UVec2,
    /// Unused (`0`): pads the struct to 32 bytes.
    pub reserved: UVec2,
}
const _: () = assert!(size_of::<GridFrame>() == 32);

impl GridFrame {
    /// The largest grid side accepted, texels.
    pub const MAX_TEXELS_PER_SIDE: u32 = 16_384;

    /// A grid centred on `(centre_x, centre_z)`.
    #[must_use]
    pub fn centred(centre_m: Vec2, size_m: Vec2, texels: UVec2) -> Self {
        Self {
            origin_m: centre_m - 0.5 * size_m,
            size_m,
            texels,
            reserved: UVec2::ZERO,
        }
    }

    /// Checks sizes: finite origin, positive size, `1..=16384` texels per side.
    pub fn validate(&self, what: &'static str) -> Result<(), CoverError> {
        check_range(
            what,
            self.origin_m.x,
            -1.0e7,
            1.0e7,
            "finite origin within ±10000 km",
        )?;
        check_range(
            what,
            self.origin_m.y,
            -1.0e7,
            1.0e7,
            "finite origin within ±10000 km",
        )?;
        check_range(
            what,
            self.size_m.x,
            1.0e-3,
            1.0e7,
            "size in [1 mm, 10000 km]",
        )?;
        check_range(
            what,
            self.size_m.y,
            1.0e-3,
            1.0e7,
            "size in [1 mm, 10000 km]",
        )?;
        for n in [self.texels.x, self.texels.y] {
            if !(1..=Self::MAX_TEXELS_PER_SIDE).contains(&n) {
                return Err(CoverError::OutOfRange {
                    field: what,
                    value: f64::from(n),
                    allowed: "1..=16384 texels per side",
                });
            }
        }
        Ok(())
    }

    /// The same grid moved by `shift` whole texels along x and z (texel `(i, j)`
    /// of the moved grid lies where texel `(i + shift.x, j + shift.y)` of this one
    /// does).
    #[must_use]
    pub fn moved_by_texels(&self, shift: glam::IVec2) -> Self {
        Self {
            origin_m: self.origin_m + shift.as_vec2() * self.cell_m(),
            ..*self
        }
    }

    /// The texels of this grid (moved by `shift` texels from where it was: the
    /// old grid is `self.moved_by_texels(-shift)`) that the old grid did not
    /// cover, as at most two rectangles, each its first texel and size: the
    /// columns that entered (every row), then the rows that entered (the other
    /// columns). None for no shift; the whole grid for a shift of a side or more.
    #[must_use]
    pub fn entering_strips(&self, shift: glam::IVec2) -> Vec<(UVec2, UVec2)> {
        let n = self.texels.as_ivec2();
        if shift.x.abs() >= n.x || shift.y.abs() >= n.y {
            return vec![(UVec2::ZERO, self.texels)];
        }
        let mut strips = Vec::with_capacity(2);
        let (w, h) = (shift.x.abs(), shift.y.abs());
        if w > 0 {
            let x0 = if shift.x > 0 { n.x - w } else { 0 };
            strips.push((glam::IVec2::new(x0, 0), glam::IVec2::new(w, n.y)));
        }
        if h > 0 {
            let z0 = if shift.y > 0 { n.y - h } else { 0 };
            let x0 = if shift.x < 0 { w } else { 0 };
            strips.push((glam::IVec2::new(x0, z0), glam::IVec2::new(n.x - w, h)));
        }
        strips
            .into_iter()
            .map(|(first, size)| (first.as_uvec2(), size.as_uvec2()))
            .collect()
    }

    /// The grid of texels `first .. first + size` of this one.
    #[must_use]
    pub fn sub_grid(&self, first: UVec2, size: UVec2) -> Self {
        let cell = self.cell_m();
        Self {
            origin_m: self.origin_m + first.as_vec2() * cell,
            size_m: size.as_vec2() * cell,
            texels: size,
            reserved: UVec2::ZERO,
        }
    }

    /// Number of texels.
    #[must_use]
    pub fn texel_count(&self) -> usize {
        self.texels.x as usize * self.texels.y as usize
    }

    /// Size of one texel, metres (x, z).
    #[must_use]
    pub fn cell_m(&self) -> Vec2 {
        self.size_m / self.texels.as_vec2()
    }

    /// Area of one texel, m².
    #[must_use]
    pub fn texel_area_m2(&self) -> f32 {
        let c = self.cell_m();
        c.x * c.y
    }

    /// The texel index under world `(x, z)`, or `None` outside the grid.
    ///
    /// WGSL twin: `grid_texel_index` in layout.wgsl.
    #[must_use]
    pub fn texel_index(&self, xz_m: Vec2) -> Option<usize> {
        let t = ((xz_m - self.origin_m) / self.size_m) * self.texels.as_vec2();
        let f = t.floor();
        // Written so that NaN lands outside.
        let inside =
            f.x >= 0.0 && f.y >= 0.0 && f.x < self.texels.x as f32 && f.y < self.texels.y as f32;
        if !inside {
            return None;
        }
        let (i, j) = (f.x as usize, f.y as usize);
        Some(i + self.texels.x as usize * j)
    }

    /// World (x, z) of texel `index`'s centre.
    #[must_use]
    pub fn texel_centre(&self, index: usize) -> Vec2 {
        let nx = self.texels.x as usize;
        let ij = Vec2::new((index % nx) as f32, (index / nx) as f32);
        self.origin_m + (ij + 0.5) * self.cell_m()
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        /// Moved by any shift, every texel of the grid is either over the old
        /// grid or in exactly one entering strip, and each sub-grid lies where
        /// its texels do.
        #[test]
        fn the_entering_strips_are_what_the_old_grid_did_not_cover(
            nx in 1u32..40, nz in 1u32..40, sx in -50i32..50, sz in -50i32..50,
        ) {
            let old = GridFrame::centred(Vec2::new(3.0, -7.0), Vec2::new(nx as f32 * 0.5, nz as f32 * 2.0), UVec2::new(nx, nz));
            let shift = glam::IVec2::new(sx, sz);
            let moved = old.moved_by_texels(shift);
            let mut covered = vec![0u32; moved.texel_count()];
            for (first, size) in moved.entering_strips(shift) {
                let sub = moved.sub_grid(first, size);
                for o in 0..sub.texel_count() {
                    let k = moved.texel_index(sub.texel_centre(o)).expect("inside the grid");
                    prop_assert_eq!(k as u32, first.x + o as u32 % size.x + nx * (first.y + o as u32 / size.x));
                    covered[k] += 1;
                }
            }
            for (k, &c) in covered.iter().enumerate() {
                let (x, z) = ((k as u32 % nx) as i32 + sx, (k as u32 / nx) as i32 + sz);
                let over_old = x >= 0 && z >= 0 && x < nx as i32 && z < nz as i32;
                prop_assert_eq!(c, u32::from(!over_old), "texel {}", k);
            }
        }
    }

    #[test]
    fn index_and_centre_agree() {
        let f = GridFrame::centred(
            Vec2::new(10.0, -5.0),
            Vec2::new(40.0, 20.0),
            UVec2::new(8, 4),
        );
        for index in 0..f.texel_count() {
            assert_eq!(f.texel_index(f.texel_centre(index)), Some(index));
        }
        assert_eq!(f.texel_index(Vec2::new(-10.1, -5.0)), None);
        assert_eq!(
            f.texel_index(Vec2::new(30.0, -5.0)),
            None,
            "max edge is outside"
        );
        assert_eq!(f.texel_index(Vec2::new(f32::NAN, 0.0)), None);
        assert!((f.texel_area_m2() - 25.0).abs() < 1e-6);
    }

    #[test]
    fn bad_frames_are_refused() {
        let good = GridFrame::centred(Vec2::ZERO, Vec2::splat(10.0), UVec2::splat(4));
        assert!(good.validate("cover").is_ok());
        assert!(
            GridFrame {
                texels: UVec2::new(0, 4),
                ..good
            }
            .validate("cover")
            .is_err()
        );
        assert!(
            GridFrame {
                size_m: Vec2::new(f32::NAN, 1.0),
                ..good
            }
            .validate("cover")
            .is_err()
        );
        assert!(
            GridFrame {
                texels: UVec2::new(4, 20_000),
                ..good
            }
            .validate("cover")
            .is_err()
        );
    }
}
