//! The cover kernel's uniform block.

use bytemuck::{Pod, Zeroable};

use crate::drift::SNOW_DRIFT_ITERATIONS;
use crate::frame::GridFrame;
use crate::params::CoverParams;
use crate::water::WATER_FLOW_ITERATIONS;

/// The air over the cover during one step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CoverAir {
    /// Snow rate on texels fed by the weather, mm/day of water.
    pub snow_rate_mm_per_day: f32,
    /// Rain rate on texels fed by the weather, mm/day.
    pub rain_rate_mm_per_day: f32,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Relative humidity, `[0, 1]`.
    pub relative_humidity: f32,
    /// Mean wind speed near the ground, m/s.
    pub wind_speed_mps: f32,
    /// The weather's mean wind at [`crate::blowing::WIND_REFERENCE_HEIGHT_M`], along
    /// world x and z, m/s (blowing snow).
    pub wind_mps: [f32; 2],
}

/// Everything one cover step needs besides the texels.
///
/// WGSL twin: `CoverStepParams` in `shaders/cover.wgsl` (128 bytes).
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
    /// [`CoverParams::cover_depletion_exponent`].
    pub cover_depletion_exponent: f32,
    /// [`CoverParams::settled_density_kg_m3`].
    pub settled_density_kg_m3: f32,
    /// [`CoverParams::compaction_time_days`].
    pub compaction_time_days: f32,
    /// [`CoverParams::wet_darkening`].
    pub wet_darkening: f32,
    /// [`CoverParams::wetting_mm`].
    pub wetting_mm: f32,
    /// [`CoverParams::mask_edge`].
    pub mask_edge: f32,
    /// Snow rate on texels fed by the weather, mm/day of water.
    pub snow_rate_mm_per_day: f32,
    /// Rain rate on texels fed by the weather, mm/day.
    pub rain_rate_mm_per_day: f32,
    /// Air temperature, °C.
    pub air_temperature_c: f32,
    /// Relative humidity, `[0, 1]`.
    pub relative_humidity: f32,
    /// Mean wind speed near the ground, m/s.
    pub wind_speed_mps: f32,
    /// Step, days of cover time.
    pub dt_days: f32,
    /// One flow iteration, s of cover time (the step over
    /// [`WATER_FLOW_ITERATIONS`]).
    pub flow_iteration_s: f32,
    /// Texel size along x, m.
    pub cell_x_m: f32,
    /// Texel size along z, m.
    pub cell_z_m: f32,
    /// Texels in the grid.
    pub texel_count: u32,
    /// Texels along x.
    pub texels_x: u32,
    /// Mean wind at 10 m along world x, m/s.
    pub wind_x_mps: f32,
    /// Mean wind at 10 m along world z, m/s.
    pub wind_z_mps: f32,
    /// Tangent of [`CoverParams::snow_repose_angle_deg`].
    pub snow_repose_tan: f32,
    /// One drift iteration, s of cover time (the step over
    /// [`crate::drift::SNOW_DRIFT_ITERATIONS`]).
    pub drift_iteration_s: f32,
    /// The grid's corner of least x, m.
    pub origin_x_m: f32,
    /// The grid's corner of least z, m.
    pub origin_z_m: f32,
    /// Unused (`0`).
    pub reserved: [u32; 2],
}
const _: () = assert!(size_of::<CoverStepParams>() == 128);

impl CoverStepParams {
    /// The block for one step of `dt_days` over the grid `frame`.
    #[must_use]
    pub fn new(params: &CoverParams, air: CoverAir, dt_days: f32, frame: &GridFrame) -> Self {
        let cell = frame.cell_m();
        Self {
            melt_threshold_c: params.melt_threshold_c,
            melt_proportionality_mm_per_c_day: params.melt_proportionality_mm_per_c_day,
            solar_irradiance_factor: params.solar_irradiance_factor,
            vegetation_density: params.vegetation_density,
            albedo_decay_per_day: params.albedo_decay_per_day,
            refreeze_factor_mm_per_c_day: params.refreeze_factor_mm_per_c_day,
            water_holding_fraction: params.water_holding_fraction,
            cover_depletion_exponent: params.cover_depletion_exponent,
            settled_density_kg_m3: params.settled_density_kg_m3,
            compaction_time_days: params.compaction_time_days,
            wet_darkening: params.wet_darkening,
            wetting_mm: params.wetting_mm,
            mask_edge: params.mask_edge,
            snow_rate_mm_per_day: air.snow_rate_mm_per_day,
            rain_rate_mm_per_day: air.rain_rate_mm_per_day,
            air_temperature_c: air.air_temperature_c,
            relative_humidity: air.relative_humidity,
            wind_speed_mps: air.wind_speed_mps,
            dt_days,
            flow_iteration_s: dt_days * 86_400.0 / WATER_FLOW_ITERATIONS as f32,
            cell_x_m: cell.x,
            cell_z_m: cell.y,
            texel_count: frame.texel_count() as u32,
            texels_x: frame.texels.x,
            wind_x_mps: air.wind_mps[0],
            wind_z_mps: air.wind_mps[1],
            snow_repose_tan: params.snow_repose_angle_deg.to_radians().tan(),
            drift_iteration_s: dt_days * 86_400.0 / SNOW_DRIFT_ITERATIONS as f32,
            origin_x_m: frame.origin_m.x,
            origin_z_m: frame.origin_m.y,
            reserved: [0; 2],
        }
    }

    /// The air of the block.
    #[must_use]
    pub fn air(&self) -> CoverAir {
        CoverAir {
            snow_rate_mm_per_day: self.snow_rate_mm_per_day,
            rain_rate_mm_per_day: self.rain_rate_mm_per_day,
            air_temperature_c: self.air_temperature_c,
            relative_humidity: self.relative_humidity,
            wind_speed_mps: self.wind_speed_mps,
            wind_mps: [self.wind_x_mps, self.wind_z_mps],
        }
    }
}
