//! Drifting snow: where the cover's snow blows, particles rise from it and stream
//! low over it; in a light wind there are none.

use glam::Vec3;
use precip_model::wind::WindField;
use precip_model::{Backend, CpuBackend, PrecipitationKind, Setup, Weather};

fn blizzard(wind_mps: f32) -> Setup {
    let mut setup = Setup::over_flat_ground(40.0, 40, 12.0, 8_000);
    setup.weather = Weather {
        kind: PrecipitationKind::DrySnow,
        intensity_mm_per_h: 6.0,
        air_temperature_c: -12.0,
        wind: WindField {
            mean_wind_mps: Vec3::new(wind_mps, 0.0, 0.0),
            ..WindField::calm()
        },
        ..Weather::default()
    };
    // Snow piles up fast enough to blow within the run.
    setup.cover.time_scale = 3_000.0;
    setup
}

#[test]
fn drifting_snow_streams_low_where_the_snow_blows_and_not_in_a_light_wind() {
    let setup = blizzard(14.0);
    let (world, _) = setup.particle_counts();
    let lift = setup.grain_lift(&setup.weather, world);
    assert!(lift.lift_from < world, "a share is set aside: {lift:?}");
    assert!(
        lift.per_particle_kg_per_s.abs() < f32::MIN_POSITIVE,
        "it carries no mass"
    );
    let mut cpu = CpuBackend::new();
    cpu.configure(&setup).expect("valid");
    for _ in 0..80 {
        cpu.step(0.1).expect("step");
    }
    let cover = cpu.read_cover().expect("cover");
    let totals = cover.totals();
    assert!(totals.blowing_area_m2 > 0.0, "snow blows: {totals:?}");
    let particles = cpu.read_particles().expect("particles");
    let drifting: Vec<_> = particles[lift.lift_from as usize..world as usize]
        .iter()
        .filter(|p| p.position_m.y > setup.ground.floor_m())
        .collect();
    let share = drifting.len() as f64 / f64::from(world - lift.lift_from);
    let highest = drifting
        .iter()
        .map(|p| p.position_m.y)
        .fold(f32::NEG_INFINITY, f32::max);
    let mean_speed = drifting
        .iter()
        .map(|p| f64::from(p.velocity_mps.x))
        .sum::<f64>()
        / drifting.len().max(1) as f64;
    println!(
        "{} drifting ({:.0} % of the share) over {:.0} m² of blowing snow, highest {highest:.2} m, mean speed {mean_speed:.1} m/s; mean water landed {:.2} mm",
        drifting.len(),
        100.0 * share,
        totals.blowing_area_m2,
        totals.deposited_kg / totals.area_m2
    );
    assert!(share > 0.3, "most of the share is drifting: {share}");
    assert!(highest < 2.5, "low over the snow: {highest} m");
    assert!(
        mean_speed > 5.0,
        "streaming with the wind: {mean_speed} m/s"
    );
    // The water landed is the weather's, the drifting particles carry none.
    let water = particles
        .iter()
        .skip(lift.lift_from as usize)
        .take((world - lift.lift_from) as usize)
        .map(|p| p.water_kg)
        .fold(0.0f32, f32::max);
    assert!(water.abs() < f32::MIN_POSITIVE);

    let calm = blizzard(3.0);
    let (world, _) = calm.particle_counts();
    assert_eq!(
        calm.grain_lift(&calm.weather, world).lift_from,
        world,
        "no drifting in a light wind"
    );
}
