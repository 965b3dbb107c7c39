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
    use super::*;

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
