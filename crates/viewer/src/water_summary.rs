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
        describe_totals(&self.totals)
    }
}

/// The books of the cover beyond the grid (`far`, over the terrain's land off it)
/// and of the whole terrain (with the grid's, `grid`), in words.
#[must_use]
pub fn describe_far_books(far: &CoverTotals, grid: &CoverTotals) -> String {
    let mut whole = *far;
    for (sum, part) in [
        (&mut whole.deposited_kg, grid.deposited_kg),
        (&mut whole.drifted_kg, grid.drifted_kg),
        (&mut whole.swe_kg, grid.swe_kg),
        (&mut whole.liquid_kg, grid.liquid_kg),
        (&mut whole.film_kg, grid.film_kg),
        (&mut whole.standing_kg, grid.standing_kg),
        (&mut whole.infiltrated_kg, grid.infiltrated_kg),
        (&mut whole.evaporated_kg, grid.evaporated_kg),
        (&mut whole.runoff_kg, grid.runoff_kg),
        (&mut whole.net_inflow_kg, grid.net_inflow_kg),
        (&mut whole.area_m2, grid.area_m2),
    ] {
        *sum += part;
    }
    format!(
        "beyond the grid ({:.2} km² of terrain): {}\nthe whole terrain ({:.2} km²): imbalance {:.2e} kg of {:.3e}",
        far.area_m2 * 1e-6,
        describe_totals(far),
        whole.area_m2 * 1e-6,
        whole.imbalance_kg(),
        whole.deposited_kg
    )
}

/// A cover's books in words: where the water that landed went.
fn describe_totals(t: &CoverTotals) -> String {
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
