//! [`CoverTexel`]: one cell of the snow cover, the GPU's layout.

use bytemuck::{Pod, Zeroable};

/// Where a texel's snow comes from (docs/architecture.md §2): never both.
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

/// State of the snow cover and the surface water in one texel. Water amounts are mm
/// of water (kg/m²).
///
/// Books, at all times: `deposited_mm + net_inflow_mm + drifted_mm = swe_mm +
/// liquid_mm + film_mm + standing_mm + infiltrated_mm + evaporated_mm + runoff_mm`.
/// WGSL twin: `CoverTexel` in `shaders/cover.wgsl` (128 bytes).
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
    /// Surface wetness in `[0, 1]` (drives wet darkening): the film over its capacity
    /// plus standing and held water over [`crate::CoverParams::wetting_mm`].
    pub wetness: f32,
    /// Water that left: over the grid's edge, or into a water body; cumulative, mm.
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
    /// Water held by the surface's texture, not flowing, mm (up to the surface's
    /// film capacity).
    pub film_mm: f32,
    /// Standing water above the film, mm: it flows, and where it gathers it is a
    /// puddle.
    pub standing_mm: f32,
    /// Water that soaked into the ground, cumulative, mm.
    pub infiltrated_mm: f32,
    /// Water that evaporated, cumulative, mm.
    pub evaporated_mm: f32,
    /// Water that flowed in from neighbours minus what flowed out to them,
    /// cumulative, mm (sums to zero over the grid up to rounding).
    pub net_inflow_mm: f32,
    /// Height of the surface at the texel's centre, m (from the ground map).
    pub ground_m: f32,
    /// [`crate::Surface`] as `u32`.
    pub surface: u32,
    /// Density of the snow this texel sent away in the last drift iteration, kg/m³
    /// (scratch of the drift's two passes: the receivers' depth).
    pub moving_density_kg_m3: f32,
    /// Water (standing, in the flow's passes) or snow (SWE, in the drift's) sent to
    /// the −x, +x, −z, +z neighbours in the last iteration, mm (scratch of each
    /// pair of passes).
    pub outflow_mm: [f32; 4],
    /// Snow that the wind and slides brought minus what they took, cumulative, mm
    /// of water (over the grid: what crossed its edges).
    pub drifted_mm: f32,
    /// The wind's speed here over the weather's (speed-up over crests, shelter
    /// behind obstacles; [`crate::drift`]), this step.
    pub wind_factor: f32,
    /// Snow carried in saltation from this texel in the last drift iteration,
    /// kg/(m·s) (0: no blowing snow here).
    pub saltation_kg_per_m_s: f32,
    /// Of [`Self::drifted_mm`], what crossed the grid's edge here (in from beyond
    /// an up-wind edge minus out over a down-wind one), cumulative, mm.
    pub edge_drifted_mm: f32,
    /// Sand and dust that settled here, cumulative, kg/m² (not water: outside the
    /// water books; the wind does not move it again).
    pub dust_kg_m2: f32,
    /// Unused (`0`).
    pub reserved1: [u32; 3],
}
const _: () = assert!(size_of::<CoverTexel>() == 128);

impl CoverTexel {
    /// Height of the snow's (or the bare ground's) surface, m.
    #[must_use]
    pub fn surface_m(&self) -> f32 {
        self.ground_m + self.depth_mm * 1.0e-3
    }

    /// Bulk density of the pack, kg/m³ (`None` without snow).
    #[must_use]
    pub fn snow_density_kg_m3(&self) -> Option<f32> {
        (self.swe_mm > 0.0 && self.depth_mm > 0.0).then(|| self.swe_mm * 1000.0 / self.depth_mm)
    }

    /// Water stored in the snow pack (frozen + liquid), mm.
    #[must_use]
    pub fn stored_mm(&self) -> f32 {
        self.swe_mm + self.liquid_mm
    }

    /// Water on the surface (film + standing), mm.
    #[must_use]
    pub fn surface_water_mm(&self) -> f32 {
        self.film_mm + self.standing_mm
    }

    /// Standing water over the depth at which it tops the surface's texture: ≥ 1 is
    /// open water (a puddle); a water body (no roughness) reads as 0.
    #[must_use]
    pub fn puddle_ratio(&self) -> f32 {
        let roughness = crate::Surface::from_raw(self.surface).water().roughness_mm;
        if roughness > 0.0 {
            self.standing_mm / roughness
        } else {
            0.0
        }
    }

    /// `deposited + net inflow + drifted − (every column)`: zero up to rounding, mm.
    #[must_use]
    pub fn imbalance_mm(&self) -> f64 {
        let f = f64::from;
        f(self.deposited_mm) + f(self.net_inflow_mm) + f(self.drifted_mm)
            - (f(self.swe_mm)
                + f(self.liquid_mm)
                + f(self.film_mm)
                + f(self.standing_mm)
                + f(self.infiltrated_mm)
                + f(self.evaporated_mm)
                + f(self.runoff_mm))
    }
}
