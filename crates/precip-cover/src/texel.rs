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

    /// This texel's ground (eligibility, masks, feed, height, surface, wind
    /// factor) holding the cover of `source`, per unit area: its snow, water, dust
    /// and books. The scratch of the last drift and flow passes (outflows, the
    /// density sent away, saltation) is cleared; a pass writes it before it reads
    /// it. A texel that enters a moving cover grid takes the cover of the land it
    /// came from this way (`precip_model::host::FarCover::lend`).
    #[must_use]
    pub fn with_cover_of(self, source: &Self) -> Self {
        Self {
            swe_mm: source.swe_mm,
            liquid_mm: source.liquid_mm,
            depth_mm: source.depth_mm,
            age_days: source.age_days,
            peak_swe_mm: source.peak_swe_mm,
            wetness: source.wetness,
            runoff_mm: source.runoff_mm,
            deposited_mm: source.deposited_mm,
            film_mm: source.film_mm,
            standing_mm: source.standing_mm,
            infiltrated_mm: source.infiltrated_mm,
            evaporated_mm: source.evaporated_mm,
            net_inflow_mm: source.net_inflow_mm,
            drifted_mm: source.drifted_mm,
            edge_drifted_mm: source.edge_drifted_mm,
            dust_kg_m2: source.dust_kg_m2,
            moving_density_kg_m3: 0.0,
            outflow_mm: [0.0; 4],
            saltation_kg_per_m_s: 0.0,
            ..self
        }
    }

    /// This texel standing for `area_m2` of land merged with `other` standing for
    /// `other_area_m2`: the cover of the two together per unit area, on this
    /// texel's ground. Every column of the books, the depth, wetness, peak SWE and
    /// dust are area-weighted means (the books are linear, so a merge of balanced
    /// texels balances and the mass of the two is kept to rounding); the snow's age
    /// is weighted by its SWE. A texel that leaves a moving cover grid goes into
    /// the cover beyond it this way (`precip_model::host::FarCover::take_in`).
    #[must_use]
    pub fn merged(self, area_m2: f64, other: &Self, other_area_m2: f64) -> Self {
        let total = area_m2 + other_area_m2;
        if total <= 0.0 {
            return self.with_cover_of(other);
        }
        let (a, b) = (area_m2 / total, other_area_m2 / total);
        let mean = |x: f32, y: f32| (a * f64::from(x) + b * f64::from(y)) as f32;
        let snow = a * f64::from(self.swe_mm) + b * f64::from(other.swe_mm);
        let age_days = if snow > 0.0 {
            ((a * f64::from(self.swe_mm) * f64::from(self.age_days)
                + b * f64::from(other.swe_mm) * f64::from(other.age_days))
                / snow) as f32
        } else {
            0.0
        };
        Self {
            swe_mm: mean(self.swe_mm, other.swe_mm),
            liquid_mm: mean(self.liquid_mm, other.liquid_mm),
            depth_mm: mean(self.depth_mm, other.depth_mm),
            age_days,
            peak_swe_mm: mean(self.peak_swe_mm, other.peak_swe_mm),
            wetness: mean(self.wetness, other.wetness),
            runoff_mm: mean(self.runoff_mm, other.runoff_mm),
            deposited_mm: mean(self.deposited_mm, other.deposited_mm),
            film_mm: mean(self.film_mm, other.film_mm),
            standing_mm: mean(self.standing_mm, other.standing_mm),
            infiltrated_mm: mean(self.infiltrated_mm, other.infiltrated_mm),
            evaporated_mm: mean(self.evaporated_mm, other.evaporated_mm),
            net_inflow_mm: mean(self.net_inflow_mm, other.net_inflow_mm),
            drifted_mm: mean(self.drifted_mm, other.drifted_mm),
            edge_drifted_mm: mean(self.edge_drifted_mm, other.edge_drifted_mm),
            dust_kg_m2: mean(self.dust_kg_m2, other.dust_kg_m2),
            moving_density_kg_m3: 0.0,
            outflow_mm: [0.0; 4],
            saltation_kg_per_m_s: 0.0,
            ..self
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

#[cfg(test)]
#[expect(
    clippy::float_cmp,
    reason = "a copied or cleared field is the source's bit for bit"
)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// A texel whose books balance: snow, water and losses drawn, what it received
    /// their sum.
    fn balanced() -> impl Strategy<Value = CoverTexel> {
        (
            (0.0f32..200.0, 0.0f32..20.0, 0.0f32..5.0, 0.0f32..30.0),
            (0.0f32..10.0, 0.0f32..50.0, 0.0f32..5.0, 0.0f32..40.0),
            (-20.0f32..20.0, -30.0f32..30.0, 0.0f32..30.0, 0.0f32..1.0),
        )
            .prop_map(
                |(
                    (swe_mm, liquid_mm, film_mm, standing_mm),
                    (infiltrated_mm, evaporated_mm, runoff_mm, age_days),
                    (net_inflow_mm, drifted_mm, dust_kg_m2, wetness),
                )| {
                    let stored = swe_mm
                        + liquid_mm
                        + film_mm
                        + standing_mm
                        + infiltrated_mm
                        + evaporated_mm
                        + runoff_mm;
                    CoverTexel {
                        swe_mm,
                        liquid_mm,
                        depth_mm: swe_mm * 8.0,
                        age_days,
                        peak_swe_mm: swe_mm * 1.5,
                        wetness,
                        runoff_mm,
                        deposited_mm: stored - net_inflow_mm - drifted_mm,
                        film_mm,
                        standing_mm,
                        infiltrated_mm,
                        evaporated_mm,
                        net_inflow_mm,
                        drifted_mm,
                        dust_kg_m2,
                        eligibility: 1.0,
                        outflow_mm: [1.0, 2.0, 3.0, 4.0],
                        saltation_kg_per_m_s: 0.5,
                        ..CoverTexel::default()
                    }
                },
            )
    }

    proptest! {
        /// A merge keeps the mass of the two (each column's), balances as they did,
        /// keeps this texel's ground and clears the passes' scratch.
        #[test]
        fn a_merge_keeps_the_mass_and_the_books_of_the_two(
            mine in balanced(),
            other in balanced(),
            area in 0.0f64..1.0e5,
            other_area in 1.0e-3f64..100.0,
        ) {
            let ground = CoverTexel { ground_m: 12.5, surface: 3, eligibility: 0.25, ..mine };
            let merged = ground.merged(area, &other, other_area);
            let total = area + other_area;
            let column = |f: fn(&CoverTexel) -> f32| {
                let before = f64::from(f(&mine)) * area + f64::from(f(&other)) * other_area;
                let after = f64::from(f(&merged)) * total;
                (before - after).abs() <= 1.0e-6 * (before.abs() + total)
            };
            prop_assert!(column(|t| t.swe_mm));
            prop_assert!(column(|t| t.deposited_mm));
            prop_assert!(column(|t| t.standing_mm));
            prop_assert!(column(|t| t.drifted_mm));
            prop_assert!(column(|t| t.dust_kg_m2));
            prop_assert!(merged.imbalance_mm().abs() <= 1.0e-4 * (1.0 + f64::from(merged.deposited_mm.abs())));
            prop_assert_eq!((merged.ground_m, merged.surface, merged.eligibility), (12.5, 3, 0.25));
            prop_assert_eq!(merged.outflow_mm, [0.0; 4]);
            prop_assert_eq!(merged.saltation_kg_per_m_s, 0.0);
            let (lo, hi) = (mine.age_days.min(other.age_days), mine.age_days.max(other.age_days));
            prop_assert!(merged.swe_mm == 0.0 || (lo - 1.0e-5..=hi + 1.0e-5).contains(&merged.age_days));
        }

        /// A texel that takes another's cover holds it per unit area on its own
        /// ground; merged with no area of its own it becomes the other's cover.
        #[test]
        fn a_lent_cover_is_the_source_s_on_the_texel_s_ground(
            source in balanced(),
            ground_m in -10.0f32..100.0,
        ) {
            let texel = CoverTexel { ground_m, surface: 2, accumulation_mask: 0.3, ..CoverTexel::default() };
            let lent = texel.with_cover_of(&source);
            prop_assert_eq!(lent.swe_mm, source.swe_mm);
            prop_assert_eq!(lent.deposited_mm, source.deposited_mm);
            prop_assert_eq!(lent.imbalance_mm(), source.imbalance_mm());
            prop_assert_eq!((lent.ground_m, lent.surface, lent.accumulation_mask), (ground_m, 2, 0.3));
            prop_assert_eq!(lent.outflow_mm, [0.0; 4]);
            let empty = texel.merged(0.0, &source, 4.0);
            prop_assert_eq!(empty.swe_mm, source.swe_mm);
            prop_assert_eq!(empty.ground_m, ground_m);
        }
    }
}
