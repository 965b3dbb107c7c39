//! The same seed gives bit-identical particles and cover; another seed does not; a
//! long step equals its sub-steps.

use crate::common;

use glam::Vec3;
use precip_model::wind::WindField;
use precip_model::{PrecipitationKind, Setup, Weather};

fn gusty_sleet(seed: u32) -> Setup {
    let mut setup = Setup::over_flat_ground(30.0, 24, 12.0, 4_000);
    setup.seed = seed;
    setup.weather = Weather {
        kind: PrecipitationKind::Sleet,
        intensity_mm_per_h: 3.0,
        air_temperature_c: 1.0,
        wind: WindField {
            mean_wind_mps: Vec3::new(4.0, 0.0, 1.0),
            vertical_gust_mps: 0.5,
            ..WindField::calm()
        },
        relative_humidity: Weather::DEFAULT_RELATIVE_HUMIDITY,
        grain: None,
    };
    setup.cover.time_scale = 600.0;
    setup
}

#[test]
fn same_seed_bit_identical_other_seed_different() {
    let mut a = common::configured(&gusty_sleet(5));
    let mut b = common::configured(&gusty_sleet(5));
    let mut c = common::configured(&gusty_sleet(6));
    for backend in [&mut a, &mut b, &mut c] {
        common::run(backend, 120, 0.05);
    }
    assert_eq!(
        common::particle_bytes(&mut a),
        common::particle_bytes(&mut b)
    );
    assert_eq!(common::cover_bytes(&mut a), common::cover_bytes(&mut b));
    assert_ne!(
        common::particle_bytes(&mut a),
        common::particle_bytes(&mut c)
    );
}

#[test]
fn a_long_step_is_its_sub_steps() {
    let mut long = common::configured(&gusty_sleet(9));
    let mut short = common::configured(&gusty_sleet(9));
    common::run(&mut long, 10, 0.2);
    common::run(&mut short, 40, 0.05);
    assert_eq!(
        common::particle_bytes(&mut long),
        common::particle_bytes(&mut short)
    );
    assert_eq!(
        common::cover_bytes(&mut long),
        common::cover_bytes(&mut short)
    );
}
