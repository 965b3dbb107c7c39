//! [`CoverParams`]: the constants of accumulation, melt, ageing and shading.

use crate::error::{CoverError, check_range};

/// Constants of the cover model (docs/model.md §4), with defaults that reproduce the
/// measured degree-day factors of seasonal snow (docs/model.md §7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoverParams {
    /// T_m: the air temperature above which snow melts, °C (normally 0).
    pub melt_threshold_c: f32,
    /// k_m·R_l together as the seed uses them: melt per °C·day of a snow pack with
    /// albedo 0 and no vegetation, mm/(°C·day). The default 7.0 gives fresh snow
    /// (A = 0.8) 1.4, week-old snow (A ≈ 0.5) 3.5 and old snow (A → 0.4) 4.2
    /// mm/(°C·day): Kuusisto's 3.51 (open) for the snow of a typical melt period.
    pub melt_proportionality_mm_per_c_day: f32,
    /// R_l: solar irradiance factor, 1 for an open site at mid latitude; scale it for
    /// shade, latitude or season.
    pub solar_irradiance_factor: f32,
    /// C_v: vegetation density in `[0, 1]`; k_v = exp(−4·C_v). About 0.09 reproduces
    /// Kuusisto's forest factor (2.42 vs 3.51 open).
    pub vegetation_density: f32,
    /// k_e: albedo decay rate, per day (seed: ≈ 0.2).
    pub albedo_decay_per_day: f32,
    /// Refreezing of held melt water below T_m, mm/(°C·day).
    pub refreeze_factor_mm_per_c_day: f32,
    /// Liquid water the pack holds, as a fraction of its SWE; the rest drains away.
    pub water_holding_fraction: f32,
    /// `m` of the snow-cover depletion curve (Niu & Yang 2007,
    /// [`crate::shading::snow_cover_fraction`]): how much a denser (older, melting)
    /// pack of the same depth covers less. 1.0 as in the Community Land Model.
    pub cover_depletion_exponent: f32,
    /// Density the pack settles toward, kg/m³.
    pub settled_density_kg_m3: f32,
    /// Time constant of settling, days.
    pub compaction_time_days: f32,
    /// R_d: how much wet ground darkens, `[0, 1]`.
    pub wet_darkening: f32,
    /// Standing or held water that wets a surface fully, mm (a film wets it fully at
    /// the surface's own capacity, [`crate::SurfaceWater::film_capacity_mm`]).
    pub wetting_mm: f32,
    /// Width of the soft edge of mask patches, in mask units `(0, 1]`.
    pub mask_edge: f32,
    /// The steepest a snow surface stands, degrees: steeper snow slides to the
    /// neighbour below ([`crate::drift`]). 38° lies inside the 30–45° at which dry
    /// slabs release (McClung & Schaerer, *The Avalanche Handbook*, 2006).
    pub snow_repose_angle_deg: f32,
}

impl Default for CoverParams {
    fn default() -> Self {
        Self {
            melt_threshold_c: 0.0,
            melt_proportionality_mm_per_c_day: 7.0,
            solar_irradiance_factor: 1.0,
            vegetation_density: 0.0,
            albedo_decay_per_day: 0.2,
            refreeze_factor_mm_per_c_day: 0.5,
            water_holding_fraction: 0.1,
            cover_depletion_exponent: 1.0,
            settled_density_kg_m3: 350.0,
            compaction_time_days: 4.0,
            wet_darkening: 0.4,
            wetting_mm: 1.0,
            mask_edge: 0.2,
            snow_repose_angle_deg: 38.0,
        }
    }
}

impl CoverParams {
    /// Checks every parameter; the error names it and its range.
    pub fn validate(&self) -> Result<(), CoverError> {
        check_range(
            "melt_threshold_c",
            self.melt_threshold_c,
            -10.0,
            10.0,
            "[-10, 10] °C",
        )?;
        check_range(
            "melt_proportionality_mm_per_c_day",
            self.melt_proportionality_mm_per_c_day,
            0.0,
            100.0,
            "[0, 100] mm/(°C·day)",
        )?;
        check_range(
            "solar_irradiance_factor",
            self.solar_irradiance_factor,
            0.0,
            10.0,
            "[0, 10]",
        )?;
        check_range(
            "vegetation_density",
            self.vegetation_density,
            0.0,
            1.0,
            "[0, 1]",
        )?;
        check_range(
            "albedo_decay_per_day",
            self.albedo_decay_per_day,
            0.0,
            10.0,
            "[0, 10] per day",
        )?;
        check_range(
            "refreeze_factor_mm_per_c_day",
            self.refreeze_factor_mm_per_c_day,
            0.0,
            100.0,
            "[0, 100] mm/(°C·day)",
        )?;
        check_range(
            "water_holding_fraction",
            self.water_holding_fraction,
            0.0,
            1.0,
            "[0, 1]",
        )?;
        check_range(
            "cover_depletion_exponent",
            self.cover_depletion_exponent,
            0.1,
            5.0,
            "[0.1, 5]",
        )?;
        check_range(
            "settled_density_kg_m3",
            self.settled_density_kg_m3,
            50.0,
            917.0,
            "[50, 917] kg/m³",
        )?;
        check_range(
            "compaction_time_days",
            self.compaction_time_days,
            0.01,
            1.0e4,
            "[0.01, 10000] days",
        )?;
        check_range("wet_darkening", self.wet_darkening, 0.0, 1.0, "[0, 1]")?;
        check_range(
            "wetting_mm",
            self.wetting_mm,
            0.001,
            1.0e3,
            "[0.001, 1000] mm",
        )?;
        check_range("mask_edge", self.mask_edge, 0.001, 1.0, "(0, 1]")?;
        check_range(
            "snow_repose_angle_deg",
            self.snow_repose_angle_deg,
            10.0,
            80.0,
            "[10, 80] degrees",
        )
    }
}
