//! [`GroundMap`]: the scene seen from above, which particles land on.
//!
//! A height per texel (the top-most surface) and the snow eligibility of that surface.
//! The rendering issue renders it from the scene; here it is any grid. Particles land
//! against the nearest texel (no interpolation: an eave must not catch particles in
//! mid-air beside it).

use glam::Vec2;
use precip_cover::{GridFrame, Surface};

use crate::backend::error::BackendError;

/// Heights and eligibility of the top-most surface on a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundMap {
    /// Where the grid lies.
    pub frame: GridFrame,
    /// World height of the top-most surface per texel, m.
    pub height_m: Vec<f32>,
    /// Snow eligibility of that surface per texel, `[0, 1]`.
    pub eligibility: Vec<f32>,
    /// What that surface is made of, per texel; empty: from the eligibility
    /// ([`Surface::from_eligibility`]).
    pub surface: Vec<Surface>,
}

impl GroundMap {
    /// Flat ground at `height_m`, uniformly eligible.
    #[must_use]
    pub fn flat(frame: GridFrame, height_m: f32, eligibility: f32) -> Self {
        let n = frame.texel_count();
        Self {
            frame,
            height_m: vec![height_m; n],
            eligibility: vec![eligibility; n],
            surface: Vec::new(),
        }
    }

    /// This map over `frame`, the same grid moved by whole texels: the texels the
    /// two share copied, the strips that enter made by `make` over frames of their
    /// own — a grid that follows the camera makes only what is new
    /// (`crate::host::CoverWindow`). A frame of another size, or moved by a
    /// fraction of a texel or by its whole side, is made whole.
    #[must_use]
    pub fn moved_to(&self, frame: GridFrame, make: impl Fn(GridFrame) -> Self) -> Self {
        let cell = self.frame.cell_m();
        let moved = (frame.origin_m - self.frame.origin_m) / cell;
        let shift = moved.round();
        let n = self.frame.texels.as_ivec2();
        let whole = frame.texels != self.frame.texels
            || frame.size_m != self.frame.size_m
            // (Origins kilometres out round to a thousandth of a texel.)
            || (moved - shift).abs().max_element() > 0.05
            || shift.x.abs() >= n.x as f32
            || shift.y.abs() >= n.y as f32
            || self.surface.len() != self.height_m.len();
        if whole {
            return make(frame);
        }
        let shift = shift.as_ivec2();
        let count = frame.texel_count();
        let mut out = Self {
            frame,
            height_m: vec![0.0; count],
            eligibility: vec![0.0; count],
            surface: vec![Surface::default(); count],
        };
        let index = |x: i32, z: i32| (x + n.x * z) as usize;
        for z in 0..n.y {
            for x in 0..n.x {
                let (ox, oz) = (x + shift.x, z + shift.y);
                if ox >= 0 && oz >= 0 && ox < n.x && oz < n.y {
                    let (k, o) = (index(x, z), index(ox, oz));
                    out.height_m[k] = self.height_m[o];
                    out.eligibility[k] = self.eligibility[o];
                    out.surface[k] = self.surface[o];
                }
            }
        }
        // The strips that enter, each made over its own frame.
        for (first, size) in frame.entering_strips(shift) {
            let strip = make(frame.sub_grid(first, size));
            let (first, size) = (first.as_ivec2(), size.as_ivec2());
            for z in 0..size.y {
                for x in 0..size.x {
                    let (k, o) = (index(first.x + x, first.y + z), (x + size.x * z) as usize);
                    out.height_m[k] = strip.height_m[o];
                    out.eligibility[k] = strip.eligibility[o];
                    out.surface[k] = strip
                        .surface
                        .get(o)
                        .copied()
                        .unwrap_or_else(|| Surface::from_eligibility(strip.eligibility[o]));
                }
            }
        }
        out
    }

    /// Checks the frame, sizes and values.
    pub fn validate(&self) -> Result<(), BackendError> {
        self.frame.validate("ground.frame")?;
        let n = self.frame.texel_count();
        for (field, len) in [
            ("ground.height_m", self.height_m.len()),
            ("ground.eligibility", self.eligibility.len()),
        ] {
            if len != n {
                return Err(BackendError::Setup {
                    field,
                    problem: format!("has {len} values but the ground frame has {n} texels"),
                });
            }
        }
        if !self.surface.is_empty() && self.surface.len() != n {
            return Err(BackendError::Setup {
                field: "ground.surface",
                problem: format!(
                    "has {} values but the ground frame has {n} texels: give one a texel, or none to derive them from the eligibility",
                    self.surface.len()
                ),
            });
        }
        if let Some(i) = self
            .height_m
            .iter()
            .position(|h| !(h.is_finite() && h.abs() <= 1.0e5))
        {
            return Err(BackendError::Setup {
                field: "ground.height_m",
                problem: format!(
                    "texel {i} is {} : heights must be finite, within ±100 km",
                    self.height_m[i]
                ),
            });
        }
        if let Some(i) = self
            .eligibility
            .iter()
            .position(|e| !(e.is_finite() && (0.0..=1.0).contains(e)))
        {
            return Err(BackendError::Setup {
                field: "ground.eligibility",
                problem: format!(
                    "texel {i} is {}: eligibility must be in [0, 1]",
                    self.eligibility[i]
                ),
            });
        }
        Ok(())
    }

    /// Height of the top-most surface under world `(x, z)`, or `None` off the map.
    #[must_use]
    pub fn height_at(&self, xz_m: Vec2) -> Option<f32> {
        self.frame
            .texel_index(xz_m)
            .and_then(|i| self.height_m.get(i).copied())
    }

    /// Height of the top-most surface at world `(x, z)` interpolated between texel
    /// centres (bilinear, clamped at the grid's edges), or `None` off the map: where a
    /// roof's edge or a wall's foot lies between two texels, the height passes from
    /// one to the other along a line that follows no texel. WGSL twin:
    /// `ground_top_m` (render_scene.wgsl).
    #[must_use]
    pub fn height_between_texels_at(&self, xz_m: Vec2) -> Option<f32> {
        self.frame.texel_index(xz_m)?;
        let n = self.frame.texels.as_ivec2();
        let t = (xz_m - self.frame.origin_m) / self.frame.cell_m() - Vec2::splat(0.5);
        let base = t.floor();
        let w = t - base;
        let at = |dx: i32, dz: i32| {
            let c = (base.as_ivec2() + glam::IVec2::new(dx, dz)).clamp(glam::IVec2::ZERO, n - 1);
            self.height_m
                .get((c.x + n.x * c.y) as usize)
                .copied()
                .unwrap_or(0.0)
        };
        let low = at(0, 0) + (at(1, 0) - at(0, 0)) * w.x;
        let high = at(0, 1) + (at(1, 1) - at(0, 1)) * w.x;
        Some(low + (high - low) * w.y)
    }

    /// Eligibility under world `(x, z)`; 0 off the map.
    #[must_use]
    pub fn eligibility_at(&self, xz_m: Vec2) -> f32 {
        self.frame
            .texel_index(xz_m)
            .and_then(|i| self.eligibility.get(i).copied())
            .unwrap_or(0.0)
    }

    /// The surface under world `(x, z)` (off the map: from its eligibility, 0).
    #[must_use]
    pub fn surface_at(&self, xz_m: Vec2) -> Surface {
        self.frame
            .texel_index(xz_m)
            .and_then(|i| self.surface.get(i).copied())
            .unwrap_or_else(|| Surface::from_eligibility(self.eligibility_at(xz_m)))
    }

    /// The share of the surface under world `(x, z)` whose grains the wind lifts
    /// ([`Surface::erodibility`]); 0 off the map.
    #[must_use]
    pub fn erodibility_at(&self, xz_m: Vec2) -> f32 {
        if self.frame.texel_index(xz_m).is_none() {
            return 0.0;
        }
        self.surface_at(xz_m).erodibility()
    }

    /// The erodible area of the map, m² (texel area × erodibility, summed).
    #[must_use]
    pub fn erodible_area_m2(&self) -> f32 {
        let n = self.frame.texel_count();
        let sum: f32 = (0..n)
            .map(|i| self.erodibility_at(self.frame.texel_centre(i)))
            .sum();
        sum * self.frame.texel_area_m2()
    }

    /// The map as the GPU reads it (`ground_height` in `shaders/ground.wgsl`): the
    /// heights of all texels, then the erodibility of each.
    #[must_use]
    pub fn gpu_words(&self) -> Vec<f32> {
        let n = self.frame.texel_count();
        let mut words = Vec::with_capacity(2 * n);
        words.extend_from_slice(&self.height_m);
        words.extend((0..n).map(|i| self.erodibility_at(self.frame.texel_centre(i))));
        words
    }

    /// The lowest ground height: below it a particle off the map has left the scene.
    #[must_use]
    pub fn floor_m(&self) -> f32 {
        self.height_m.iter().copied().fold(f32::INFINITY, f32::min)
    }
}
