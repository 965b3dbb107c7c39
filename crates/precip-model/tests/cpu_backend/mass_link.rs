//! The mass link: particles falling on flat eligible ground deposit, per m² per hour,
//! the weather's intensity (within 5 %).

use crate::common;

use precip_model::cover::CoverFeed;
use precip_model::{Backend, PrecipitationKind, Setup, Weather};

/// Deposit rate over the interior of the grid (a border of `border` texels left out:
/// particles near the edge can drift off the map, and the interior gains as much from
/// its neighbours as it loses to them), mm/h.
fn measured_rate_mm_per_h(weather: Weather, particles: u32, seconds: f32) -> f64 {
    let texels = 40;
    let border = 6;
    let mut setup = Setup::over_flat_ground(40.0, texels, 15.0, particles);
    setup.weather = weather;
    setup.seed = 17;
    let mut backend = common::configured(&setup);
    let dt = 0.05;
    common::run(&mut backend, (seconds / dt).round() as usize, dt);
    let cover = backend.read_cover().expect("configured");
    let mut deposited_mm = 0.0f64;
    let mut count = 0usize;
    for (index, t) in cover.texels.iter().enumerate() {
        let (i, j) = (index as u32 % texels, index as u32 / texels);
        if (border..texels - border).contains(&i) && (border..texels - border).contains(&j) {
            assert_eq!(CoverFeed::from_raw(t.feed), CoverFeed::Particles);
            deposited_mm += f64::from(t.deposited_mm);
            count += 1;
        }
    }
    deposited_mm / count as f64 / (f64::from(seconds) / 3600.0)
}

#[test]
fn snow_deposits_the_intensity() {
    let weather = Weather {
        intensity_mm_per_h: 2.0,
        ..Weather::default()
    };
    let rate = measured_rate_mm_per_h(weather, 12_000, 240.0);
    println!("snow: deposited {rate:.4} mm/h for 2 mm/h");
    assert!(
        (rate / 2.0 - 1.0).abs() < 0.05,
        "deposited {rate} mm/h for 2 mm/h"
    );
}

#[test]
fn rain_deposits_the_intensity() {
    let weather = Weather {
        kind: PrecipitationKind::Rain,
        intensity_mm_per_h: 8.0,
        air_temperature_c: 12.0,
        ..Weather::default()
    };
    let rate = measured_rate_mm_per_h(weather, 12_000, 120.0);
    println!("rain: deposited {rate:.4} mm/h for 8 mm/h");
    assert!(
        (rate / 8.0 - 1.0).abs() < 0.05,
        "deposited {rate} mm/h for 8 mm/h"
    );
}
