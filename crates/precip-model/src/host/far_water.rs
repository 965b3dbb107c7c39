//! What falls on the land beyond the camera's surroundings (docs/model.md (6.16),
//! (4.16)): the weather set is the camera's surroundings', within
//! [`crate::drawing::clouds::LOCAL_WEATHER_RADIUS_M`]; beyond, the rate set for the land beyond falls under
//! the lowest cloud layer's clouds alone, where the shafts are drawn, concentrated
//! by the share of the land under them ([`shaft_share`]), so that the mean is the
//! rate set. [`crate::host::FarCover`] takes it per cell.

use glam::{Vec2, Vec3};

use crate::drawing::clouds::{
    cloud_column, cloud_map_uv, cloud_noise, sample_coverage_map, shaft_share,
};

/// What falls on the land beyond the camera's surroundings in a step (model
/// (6.16)): the cells whose centres are farther than [`crate::drawing::clouds::LOCAL_WEATHER_RADIUS_M`]
/// from the camera take it instead of the weather's water.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WaterBeyond {
    /// The camera's x and z, m.
    pub camera_xz_m: Vec2,
    /// Snow's water over the step, as the mean over the land beyond, mm.
    pub snow_mm: f32,
    /// Rain's, mm.
    pub rain_mm: f32,
    /// The lowest cloud layer's shafts, where it has one: the water falls under
    /// its clouds alone.
    pub shafts: Option<Shafts>,
}

/// Where the lowest cloud layer's shafts fall: under its clouds, at `1/s` of the
/// mean rate (`s` the share of the land under its columns, [`shaft_share`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Shafts {
    /// The layer's coverage `[0, 1]`.
    pub coverage: f32,
    /// The coverage map's drift with the wind (`cloud_drift_m`), m.
    pub drift_m: Vec2,
}

/// Samples along each side of a cell that [`Shafts::mean_rate_factor`] averages.
pub const SHAFT_SAMPLES_PER_SIDE: u32 = 4;

impl Shafts {
    /// The rate at (x, z) over the layer's mean rate: `column(c − m)/s`, `m` the
    /// coverage map's value there (WGSL: `precipitation_haze`'s shafts,
    /// render_clouds.wgsl, read the same map and column).
    #[must_use]
    pub fn rate_factor(&self, xz_m: Vec2) -> f32 {
        self.column_at(xz_m) / shaft_share(self.coverage)
    }

    /// The rate over the square from `corner_m` of side `size_m` over the
    /// layer's mean rate: [`Shafts::rate_factor`]'s mean over its area
    /// ([`SHAFT_SAMPLES_PER_SIDE`]² midpoints), so a cell on a cloud's edge takes
    /// the part of its land under the cloud, not its centre's all or nothing.
    #[must_use]
    pub fn mean_rate_factor(&self, corner_m: Vec2, size_m: Vec2) -> f32 {
        self.mean_column(corner_m, size_m) / shaft_share(self.coverage)
    }

    /// `column(c − m)`'s mean over the square from `corner_m` of side `size_m`.
    pub(crate) fn mean_column(&self, corner_m: Vec2, size_m: Vec2) -> f32 {
        let n = SHAFT_SAMPLES_PER_SIDE;
        let step = size_m / n as f32;
        let sum: f32 = (0..n * n)
            .map(|k| {
                let at = Vec2::new((k % n) as f32 + 0.5, (k / n) as f32 + 0.5);
                self.column_at(corner_m + at * step)
            })
            .sum();
        sum / (n * n) as f32
    }

    /// How much a column stands under a cloud at (x, z): `column(c − m)`.
    fn column_at(&self, xz_m: Vec2) -> f32 {
        let m = sample_coverage_map(
            &cloud_noise().coverage,
            cloud_map_uv(Vec3::new(xz_m.x, 0.0, xz_m.y), self.drift_m),
        );
        cloud_column(self.coverage, m)
    }
}
