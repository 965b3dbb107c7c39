//! What the rain has done to the scene, in a line: the headless summary and the
//! window's title report it from the cover read back (the window every
//! [`WaterSummary::EVERY_FRAMES`] frames: a read-back waits for the GPU).

use precip_model::cover::{CoverGrid, CoverTotals};

/// The water on the scene's surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WaterSummary {
    /// Water on the surfaces (films + standing), mean over the grid, mm.
    pub surface_water_mm: f64,
    /// The deepest standing water, mm (water bodies aside).
    pub deepest_standing_mm: f32,
    /// Area with a wet surface, m².
    pub wet_area_m2: f64,
    /// Area under puddles (standing water ≥ 1 mm), m².
    pub puddle_area_m2: f64,
    /// Share of the grid that is wet, `[0, 1]`.
    pub wet_share: f64,
    /// The cover's books.
    pub totals: CoverTotals,
}

impl WaterSummary {
    /// How often the window samples it, frames.
    pub const EVERY_FRAMES: u32 = 60;

    /// From a cover read back.
    #[must_use]
    pub fn of(cover: &CoverGrid) -> Self {
        let totals = cover.totals();
        let area = totals.area_m2.max(f64::MIN_POSITIVE);
        Self {
            surface_water_mm: totals.surface_water_kg() / area,
            deepest_standing_mm: cover
                .texels
                .iter()
                .filter(|t| t.surface != precip_model::cover::Surface::Water as u32)
                .map(|t| t.standing_mm)
                .fold(0.0, f32::max),
            wet_area_m2: totals.wet_area_m2,
            puddle_area_m2: totals.puddle_area_m2,
            wet_share: totals.wet_area_m2 / area,
            totals,
        }
    }

    /// In words, for a title or a summary line.
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "wet {:.0} % ({:.0} m²), puddles {:.0} m² up to {:.0} mm, surface water {:.2} mm",
            100.0 * self.wet_share,
            self.wet_area_m2,
            self.puddle_area_m2,
            self.deepest_standing_mm,
            self.surface_water_mm
        )
    }

    /// The books, in words: where the water that landed went.
    #[must_use]
    pub fn describe_books(&self) -> String {
        let t = &self.totals;
        format!(
            "water landed {:.0} kg + drifted in over the edges {:.0} kg = snow {:.0} + held {:.0} + films {:.0} + standing {:.0} + infiltrated {:.0} + evaporated {:.0} + run off {:.0} (imbalance {:.2e} kg)",
            t.deposited_kg,
            t.drifted_kg,
            t.swe_kg,
            t.liquid_kg,
            t.film_kg,
            t.standing_kg,
            t.infiltrated_kg,
            t.evaporated_kg,
            t.runoff_kg,
            t.imbalance_kg()
        )
    }
}
