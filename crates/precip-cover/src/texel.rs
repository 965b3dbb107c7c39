//! [`CoverTexel`]: one cell of the snow cover, the GPU's layout.

use bytemuck::{Pod, Zeroable};

/// Where a texel's snow comes from (DESIGN.md §2): never both.
#[repr(u32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CoverFeed {
    /// The weather's rate, applied directly (particles fill only a camera volume here).
    #[default]
    WeatherRate = 0,
    /// The water of the particles that land here (a world emitter covers this texel).
    Particles = 1,
}

impl CoverFeed {
    /// From the stored `u32` (anything but 1 reads as the weather rate).
    #[must_use]
    pub const fn from_raw(raw: u32) -> Self {
        if raw == 1 {
            Self::Particles
        } else {
            Self::WeatherRate
        }
    }
}

/// State of the snow cover in one texel. Water amounts are mm of water (kg/m²).
///
/// Books: `deposited_mm = swe_mm + liquid_mm + runoff_mm` at all times.
/// WGSL twin: `CoverTexel` in `shaders/cover.wgsl` (48 bytes, 12 scalars).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct CoverTexel {
    /// Frozen snow water equivalent, mm.
    pub swe_mm: f32,
    /// Liquid water held in the pack (melt and rain), mm; refreezes without heat.
    pub liquid_mm: f32,
    /// Snow depth, mm.
    pub depth_mm: f32,
    /// Mass-weighted age of the snow, days since it fell (albedo ageing).
    pub age_days: f32,
    /// The largest SWE since the pack began, mm: `M_S = 1 − swe/peak`.
    pub peak_swe_mm: f32,
    /// Surface wetness in `[0, 1]` (drives wet darkening).
    pub wetness: f32,
    /// Water that left the texel: melt drained, rain on bare ground, snow that fell
    /// where none may lie; cumulative, mm.
    pub runoff_mm: f32,
    /// All water received, cumulative, mm.
    pub deposited_mm: f32,
    /// Snow eligibility in `[0, 1]` (masks and slope; 0 holds no snow).
    pub eligibility: f32,
    /// T_M.g: coverage threshold of this texel, in `[0, 1]`.
    pub accumulation_mask: f32,
    /// T_M.r: melt threshold of this texel, in `[0, 1]`.
    pub melt_mask: f32,
    /// [`CoverFeed`] as `u32`.
    pub feed: u32,
}
const _: () = assert!(size_of::<CoverTexel>() == 48);

impl CoverTexel {
    /// Water stored in the texel (frozen + liquid), mm.
    #[must_use]
    pub fn stored_mm(&self) -> f32 {
        self.swe_mm + self.liquid_mm
    }
}
