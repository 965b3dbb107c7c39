//! Drifting snow made visible: where the cover's snow is blowing
//! (`CoverTexel::saltation_kg_per_m_s > 0`, precip_cover's drift), particles rise from
//! it and stream low over the ground — a ground blizzard — drawn like the flakes.
//! WGSL twin: `birth_drifting_snow` in `shaders/birth.wgsl`.
//!
//! The cover moves the snow's mass (precip_cover::drift); these particles carry
//! none, so they change no books: they show where and how hard the snow is blowing.
//! In snow weather whose wind can pass the snow's transport threshold, a share of
//! the world particles ([`DRIFTING_SNOW_SHARE`]) is set aside for them: each birth
//! draws a point on the cover grid and keeps it with probability
//! `min(1, Q/Q_ref)` (Q the texel's saltation flux, [`DRIFTING_SNOW_REFERENCE_FLUX`]),
//! a few tries; a particle that finds no blowing snow waits under the ground for
//! the next step.
//!
//! A drifting particle is a rounded ice grain of about 0.2 mm (the mean diameter of
//! blowing-snow particles near the surface, Schmidt 1982, *Boundary-Layer Meteorol.*
//! 23; Pomeroy & Male 1992, *J. Hydrol.* 136), falling at its settling speed
//! ([`crate::physics::grain::grain_settling_speed_mps`] for ice: 0.6 m/s), born at a height of
//! the Rouse profile (as suspended dust, [`crate::physics::grain`]) over the snow's surface up
//! to [`DRIFTING_SNOW_LAYER_TOP_M`], moving with the mean wind. It is drawn at the
//! size of the weather's smallest flakes: one particle stands for a cloud of grains
//! too small to draw one by one (a stand-in for the look, not a size).

use glam::Vec2;
use precip_cover::{CoverTexel, GridFrame};

/// Share of the world particles set aside for drifting snow when the wind can lift
/// it.
pub const DRIFTING_SNOW_SHARE: f32 = 0.1;
/// Saltation flux at which every try on a texel is kept, kg/(m·s) (Pomeroy & Gray's
/// flux at a 14 m/s wind over fresh snow is of this order).
pub const DRIFTING_SNOW_REFERENCE_FLUX: f32 = 0.01;
/// Mean diameter of a drifting snow grain, m.
pub const DRIFTING_SNOW_DIAMETER_M: f32 = 2.0e-4;
/// Density of ice, kg/m³.
pub const ICE_DENSITY_KG_M3: f32 = 917.0;
/// Top of the layer drifting snow is born in, m above the snow.
pub const DRIFTING_SNOW_LAYER_TOP_M: f32 = 2.0;
/// A drifting-snow slot that found no blowing snow waits this far under the ground
/// map's floor, m.
pub const PARKED_BELOW_FLOOR_M: f32 = 1.0;

/// Words of a cover texel (the GPU reads the texels as `array<f32>`).
pub const COVER_TEXEL_WORDS: usize = size_of::<CoverTexel>() / 4;
/// Word of the snow depth in a texel.
pub const COVER_WORD_DEPTH: usize = std::mem::offset_of!(CoverTexel, depth_mm) / 4;
/// Word of the saltation flux in a texel.
pub const COVER_WORD_SALTATION: usize = std::mem::offset_of!(CoverTexel, saltation_kg_per_m_s) / 4;

/// The cover as the particles' births read it: the grid and its texels (empty: no
/// snow anywhere, as at the start of a run).
#[derive(Debug, Clone, Copy)]
pub struct CoverView<'a> {
    /// The cover grid.
    pub frame: &'a GridFrame,
    /// Its texels.
    pub texels: &'a [CoverTexel],
}

impl CoverView<'_> {
    /// (saltation flux kg/(m·s), snow depth m) under world `(x, z)`; zeros off the
    /// grid. WGSL twin: `blowing_snow_at`.
    #[must_use]
    pub fn blowing_snow_at(&self, xz_m: Vec2) -> (f32, f32) {
        self.frame
            .texel_index(xz_m)
            .and_then(|i| self.texels.get(i))
            .map_or((0.0, 0.0), |t| {
                (t.saltation_kg_per_m_s, t.depth_mm * 1.0e-3)
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gpu_reads_the_texel_words_the_rust_layout_has() {
        assert_eq!(COVER_TEXEL_WORDS, 32);
        assert_eq!(COVER_WORD_DEPTH, 2);
        assert_eq!(COVER_WORD_SALTATION, 26);
    }

    #[test]
    fn a_drifting_grain_falls_at_about_sixty_centimetres_a_second() {
        let w = crate::physics::grain::grain_settling_speed_mps(
            DRIFTING_SNOW_DIAMETER_M,
            ICE_DENSITY_KG_M3,
        );
        assert!((0.4..0.8).contains(&w), "{w} m/s");
    }
}
