//! [`Activity`]: which of the cover's features may have work, decided on the host
//! from the weather since configure, so the kernels of an idle feature are not
//! dispatched at all (`precip_gpu::recipe::KernelWhen`).
//!
//! Both flags only ever turn on (nothing is read back to see the ground dry or
//! bare again), and each is set by every weather that can start its feature:
//!
//! - **Snow may lie** once any weather with a snow share falls (dry or wet snow,
//!   sleet): until then no texel holds snow, so the drift's kernels (`snow_wind`,
//!   `snow_outflow`, `snow_inflow`) would move nothing, and the blowing snow they
//!   report stays zero.
//! - **Water may stand** once any rain or snow falls: rain reaches the surface;
//!   snow on a partly eligible texel melts on contact, and a texel's first traces
//!   of snow (below the bare threshold) go to the surface as water too. Until then
//!   no texel holds standing water, so the flow's kernels (`water_outflow`,
//!   `water_inflow`) would move nothing. Sand and dust bring no water.
//!
//! The setup's cover starts bare and dry (`Setup::initial_cover`), so a clear sky,
//! a sandstorm or a downpour (for the drift) runs none of an idle feature's kernels.

use precip_cover::DepositBuffer;

use crate::weather::Weather;

/// What may have work on the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Activity {
    /// Some texel may hold snow.
    pub snow_may_lie: bool,
    /// Some texel may hold standing water.
    pub water_may_stand: bool,
}

impl Activity {
    /// The activity after `weather` has fallen (flags only turn on).
    #[must_use]
    pub fn after(self, weather: &Weather) -> Self {
        // What lands as snow (hail too) or as rain.
        let snow = weather.channel_rate_mm_per_h(DepositBuffer::SNOW) > 0.0;
        let rain = weather.channel_rate_mm_per_h(DepositBuffer::RAIN) > 0.0;
        Self {
            snow_may_lie: self.snow_may_lie || snow,
            water_may_stand: self.water_may_stand || snow || rain,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::weather::PrecipitationKind;

    fn weather(
        kind: PrecipitationKind,
        intensity_mm_per_h: f32,
        air_temperature_c: f32,
    ) -> Weather {
        Weather {
            kind,
            intensity_mm_per_h,
            air_temperature_c,
            ..Weather::default()
        }
    }

    #[test]
    fn each_weather_wakes_what_it_can_start_and_nothing_sleeps_again() {
        let bare = Activity::default();
        let rain = bare.after(&weather(PrecipitationKind::Rain, 10.0, 12.0));
        assert_eq!(
            rain,
            Activity {
                snow_may_lie: false,
                water_may_stand: true
            }
        );
        let snow = bare.after(&weather(PrecipitationKind::DrySnow, 1.0, -10.0));
        assert!(snow.snow_may_lie && snow.water_may_stand);
        let sleet = bare.after(&weather(PrecipitationKind::Sleet, 2.0, 1.0));
        assert!(sleet.snow_may_lie && sleet.water_may_stand);
        // Hail lands as snow: it lies, and melts into water.
        let hail = bare.after(&weather(PrecipitationKind::Hail, 20.0, 16.0));
        assert!(hail.snow_may_lie && hail.water_may_stand);
        let sand = weather(PrecipitationKind::Sand, 5.0, 30.0);
        assert_eq!(bare.after(&sand), bare, "grains bring no water or snow");
        let clear = weather(PrecipitationKind::DrySnow, 0.0, -5.0);
        assert_eq!(bare.after(&clear), bare);
        // Clearing up after snow keeps both awake: the snow is still there.
        assert_eq!(snow.after(&clear), snow);
        assert_eq!(rain.after(&sand), rain);
    }
}
