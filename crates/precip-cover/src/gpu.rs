//! The cover kernel's uniform block.

use bytemuck::{Pod, Zeroable};

use crate::params::CoverParams;

/// Everything one cover step needs besides the texels.
///
/// WGSL twin: `CoverStepParams` in `shaders/cover.wgsl` (80 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct CoverStepParams {
    /// [`CoverParams::melt_threshold_c`].
    pub melt_threshold_c: f32,
    /// [`CoverParams::melt_proportionality_mm_per_c_day`].
    pub melt_proportionality_mm_per_c_day: f32,
    /// [`CoverParams::solar_irradiance_factor`].
    pub solar_irradiance_factor: f32,
    /// [`CoverParams::vegetation_density`].
    pub vegetation_density: f32,
    /// [`CoverParams::albedo_decay_per_day`].
    pub albedo_decay_per_day: f32,
    /// [`CoverParams::refreeze_factor_mm_per_c_day`].
    pub refreeze_factor_mm_per_c_day: f32,
    /// [`CoverParams::water_holding_fraction`].
    pub water_holding_fraction: f32,
    /// [`CoverParams::full_cover_depth_mm`].
    pub full_cover_depth_mm: f32,
    /// [`CoverParams::settled_density_kg_m3`].
    pub settled_density_kg_m3: f32,
    /// [`CoverParams::compaction_time_days`].
    pub compaction_time_days: f32,
    /// [`CoverParams::wet_darkening`].
    pub wet_darkening: f32,
    /// [`CoverParams::wetting_mm`].
    pub wetting_mm: f32,
    /// [`CoverParams::drying_time_days`].
    pub drying_time_days: f32,
    /// [`CoverParams::mask_edge`].
    pub mask_edge: f32,
    /// Snow rate on texels fed by the weather, mm/day of water.
    pub snow_rate_mm_per_day: f32,
    /// Rain rate on texels fed by the weather, mm/day.
    pub rain_rate_mm_per_day: f32,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Step, days of cover time.
    pub dt_days: f32,
    /// Texels in the grid.
    pub texel_count: u32,
    /// Unused (`0`).
    pub reserved: u32,
}
const _: () = assert!(size_of::<CoverStepParams>() == 80);

impl CoverStepParams {
    /// The block for one step.
    #[must_use]
    pub fn new(
        params: &CoverParams,
        snow_rate_mm_per_day: f32,
        rain_rate_mm_per_day: f32,
        air_temperature_c: f32,
        dt_days: f32,
        texel_count: u32,
    ) -> Self {
        Self {
            melt_threshold_c: params.melt_threshold_c,
            melt_proportionality_mm_per_c_day: params.melt_proportionality_mm_per_c_day,
            solar_irradiance_factor: params.solar_irradiance_factor,
            vegetation_density: params.vegetation_density,
            albedo_decay_per_day: params.albedo_decay_per_day,
            refreeze_factor_mm_per_c_day: params.refreeze_factor_mm_per_c_day,
            water_holding_fraction: params.water_holding_fraction,
            full_cover_depth_mm: params.full_cover_depth_mm,
            settled_density_kg_m3: params.settled_density_kg_m3,
            compaction_time_days: params.compaction_time_days,
            wet_darkening: params.wet_darkening,
            wetting_mm: params.wetting_mm,
            drying_time_days: params.drying_time_days,
            mask_edge: params.mask_edge,
            snow_rate_mm_per_day,
            rain_rate_mm_per_day,
            air_temperature_c,
            dt_days,
            texel_count,
            reserved: 0,
        }
    }
}
