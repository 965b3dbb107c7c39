//! The CPU reference in a scene: roofs, masked ground, wind, the camera volume, melt.

use crate::common;

use glam::{UVec2, Vec2, Vec3};
use precip_model::cover::{CoverFeed, GridFrame};
use precip_model::particles::step::StepEvent;
use precip_model::wind::WindField;
use precip_model::{
    Backend, Camera, CameraVolume, CameraVolumeSetup, GroundMap, ParticleSource, PrecipitationKind,
    Setup, Weather,
};

/// 32 × 32 m with a 1 m grid: a flat roof at 6 m over x, z ∈ [−6, 2) × [−4, 4), a
/// road at the ground masked off (eligibility 0) over x ∈ [6, 10).
fn village() -> Setup {
    let mut setup = Setup::over_flat_ground(32.0, 32, 20.0, 8_000);
    let frame = setup.ground.frame;
    let mut ground = GroundMap::flat(frame, 0.0, 1.0);
    for index in 0..frame.texel_count() {
        let c = frame.texel_centre(index);
        if (-6.0..2.0).contains(&c.x) && (-4.0..4.0).contains(&c.y) {
            ground.height_m[index] = 6.0;
        }
        if (6.0..10.0).contains(&c.x) {
            ground.eligibility[index] = 0.0;
        }
    }
    setup.ground = ground;
    setup.cover.time_scale = 200.0;
    setup.weather = Weather {
        intensity_mm_per_h: 3.0,
        air_temperature_c: -4.0,
        ..Weather::default()
    };
    setup
}

#[test]
fn snow_lies_on_roofs_and_ground_but_not_on_the_masked_road_and_nothing_falls_through() {
    let mut backend = common::configured(&village());
    for _ in 0..400 {
        backend.step(0.05).expect("valid");
        for p in backend
            .read_particles()
            .expect("configured")
            .iter()
            .take(2000)
        {
            let roof =
                (-6.0..2.0).contains(&p.position_m.x) && (-4.0..4.0).contains(&p.position_m.z);
            if roof {
                assert!(
                    p.position_m.y > 5.8,
                    "fell through the roof: {:?}",
                    p.position_m
                );
            }
        }
    }
    let cover = backend.read_cover().expect("configured");
    let at = |x: f32, z: f32| *cover.texel_at(x, z).expect("on grid");
    assert!(
        at(-2.5, 0.5).swe_mm > 0.05,
        "roof holds snow: {:?}",
        at(-2.5, 0.5)
    );
    assert!(at(-12.5, 10.5).swe_mm > 0.05, "open ground holds snow");
    assert!(
        at(8.5, 0.5).swe_mm.abs() < f32::MIN_POSITIVE,
        "the road holds none"
    );
    let road = at(8.5, 0.5);
    assert!(
        road.surface_water_mm()
            + road.infiltrated_mm
            + road.evaporated_mm
            + road.runoff_mm
            + road.net_inflow_mm.max(0.0)
            > 0.05,
        "its snow melted on contact instead: {road:?}"
    );
    let books = cover.totals();
    assert!(
        books.imbalance_kg().abs() < 1e-3 * books.deposited_kg.max(1.0),
        "{books:?}"
    );
}

#[test]
fn flakes_drift_with_the_mean_wind() {
    let mut setup = Setup::over_flat_ground(200.0, 20, 60.0, 3_000);
    let wind = Vec3::new(6.0, 0.0, -2.0);
    setup.weather.wind = WindField {
        mean_wind_mps: wind,
        ..WindField::calm()
    };
    let mut backend = common::configured(&setup);
    common::run(&mut backend, 200, 0.05);
    let particles = backend.read_particles().expect("configured");
    let moving: Vec<_> = particles.iter().filter(|p| p.age_s > 3.0).collect();
    assert!(moving.len() > 1000);
    let mean = moving.iter().map(|p| p.velocity_mps).sum::<Vec3>() / moving.len() as f32;
    // Seed 003's gust μ·V̄·sin α has sin α ∈ [0, 1]: gusts only add to the mean wind,
    // by at most μ (4 %) of it.
    let mu = setup.weather.wind.gust_factor;
    for (got, mean_wind) in [(mean.x, wind.x), (mean.z, wind.z)] {
        let (lo, hi) = if mean_wind > 0.0 {
            (mean_wind, mean_wind * (1.0 + mu))
        } else {
            (mean_wind * (1.0 + mu), mean_wind)
        };
        assert!((lo - 0.05..=hi + 0.05).contains(&got), "{mean} vs {wind}");
    }
    assert!(
        (-1.5..-0.5).contains(&mean.y),
        "dry snow falls at 0.5–1.5 m/s: {mean}"
    );
}

#[test]
fn the_camera_volume_follows_the_camera_and_never_empties() {
    let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(100.0), UVec2::splat(10));
    let mut setup = Setup::over_flat_ground(100.0, 10, 30.0, 0);
    setup.world_emitter = None;
    setup.ground = GroundMap::flat(frame, -1000.0, 1.0);
    let volume = CameraVolume {
        half_extent_m: Vec3::new(15.0, 10.0, 15.0),
        ..CameraVolume::default()
    };
    setup.camera_volume = Some(CameraVolumeSetup {
        volume,
        particle_count: 5_000,
    });
    setup.weather = Weather {
        kind: PrecipitationKind::Rain,
        intensity_mm_per_h: 5.0,
        air_temperature_c: 8.0,
        wind: WindField {
            mean_wind_mps: Vec3::new(9.0, 0.0, 0.0),
            ..WindField::calm()
        },
        relative_humidity: Weather::DEFAULT_RELATIVE_HUMIDITY,
        grain: None,
    };
    let mut backend = common::configured(&setup);
    let mut camera = Camera::default();
    for frame_index in 0..200 {
        camera.position_m += Vec3::new(3.0, 0.0, -2.0); // flying at ~70 m/s
        backend.set_camera(&camera).expect("valid");
        backend.step(0.05).expect("valid");
        if frame_index % 20 == 19 {
            let particles = backend.read_particles().expect("configured");
            assert_eq!(particles.len(), 5_000);
            for p in &particles {
                assert_eq!(p.source(), ParticleSource::CameraVolume);
                let local = p.position_m - camera.position_m;
                assert!(
                    local.x.abs() <= 15.01 && local.z.abs() <= 15.01 && local.y.abs() <= 10.5,
                    "{local}"
                );
            }
            // Spread through the box, not bunched at a face.
            let mean_y = particles
                .iter()
                .map(|p| p.position_m.y - camera.position_m.y)
                .sum::<f32>()
                / 5000.0;
            assert!(mean_y.abs() < 1.5, "mean height in box {mean_y}");
        }
    }
    let cover = backend.read_cover().expect("configured");
    assert!(
        cover
            .texels
            .iter()
            .all(|t| CoverFeed::from_raw(t.feed) == CoverFeed::WeatherRate)
    );
}

/// Pearson's χ² of `counts` against equal expected counts.
fn chi_square(counts: &[u32]) -> f64 {
    let total: u32 = counts.iter().sum();
    let expected = f64::from(total) / counts.len() as f64;
    counts
        .iter()
        .map(|&c| (f64::from(c) - expected).powi(2) / expected)
        .sum()
}

/// The camera volume holds the weather's number density of flakes seen one by one
/// (`Weather::simulated_particle_count`) and keeps it even through the box while the
/// flakes fall, wrap and are re-born under a gusting wind with the camera moving:
/// the counts in its eight octants and in ten height slabs are those of a uniform
/// (Poisson) field within sampling error (χ² under its 0.1 % critical value).
#[test]
fn the_camera_volume_keeps_the_weather_s_density_evenly() {
    let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(100.0), UVec2::splat(10));
    let mut setup = Setup::over_flat_ground(100.0, 10, 30.0, 0);
    setup.world_emitter = None;
    setup.ground = GroundMap::flat(frame, -1000.0, 1.0);
    setup.weather = Weather {
        intensity_mm_per_h: 2.0,
        wind: WindField {
            mean_wind_mps: Vec3::new(4.0, 0.0, 1.0),
            ..WindField::default()
        },
        ..Weather::default()
    };
    let half = Vec3::new(4.0, 3.0, 4.0);
    let box_m3 = 8.0 * half.element_product();
    let (count, fraction) = setup.weather.simulated_particle_count(box_m3, 1_000_000);
    assert!((fraction - 1.0).abs() < 1e-6, "the budget covers reality");
    let density = setup.weather.simulated_number_density_per_m3();
    assert!(
        (count as f32 / box_m3 - density).abs() <= 1.0 / box_m3,
        "{count} particles in {box_m3} m³ for {density} per m³"
    );
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume {
            half_extent_m: half,
            ..CameraVolume::default()
        },
        particle_count: count,
    });
    let mut backend = common::configured(&setup);
    let mut camera = Camera::default();
    for _ in 0..40 {
        camera.position_m += Vec3::new(0.05, 0.0, -0.03);
        backend.set_camera(&camera).expect("valid");
        backend.step(0.05).expect("valid");
    }
    let particles = backend.read_particles().expect("configured");
    let mut octants = [0u32; 8];
    let mut slabs = [0u32; 10];
    for p in &particles {
        let local = p.position_m - camera.position_m;
        let octant = usize::from(local.x >= 0.0)
            | usize::from(local.y >= 0.0) << 1
            | usize::from(local.z >= 0.0) << 2;
        octants[octant] += 1;
        let slab = (((local.y + half.y) / (2.0 * half.y)) * 10.0).floor();
        slabs[(slab.max(0.0) as usize).min(9)] += 1;
    }
    // χ² critical values at p = 0.001: 24.32 (7 degrees of freedom), 27.88 (9).
    let (x8, x10) = (chi_square(&octants), chi_square(&slabs));
    assert!(x8 < 24.32, "octants {octants:?}: χ² {x8}");
    assert!(x10 < 27.88, "height slabs {slabs:?}: χ² {x10}");
}

#[test]
fn a_warm_spell_melts_the_cover_and_wets_the_ground() {
    // Only a camera volume: the cover is fed by the weather's rate.
    let mut setup = Setup::over_flat_ground(16.0, 8, 10.0, 0);
    setup.world_emitter = None;
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume::default(),
        particle_count: 1_000,
    });
    setup.cover.time_scale = 86_400.0; // a day per second
    let mut backend = common::configured(&setup);
    common::run(&mut backend, 40, 0.05); // two days of snow
    let snowy = backend.read_cover().expect("configured").totals();
    assert!(snowy.swe_kg > 0.0);
    let warm = Weather {
        intensity_mm_per_h: 0.0,
        air_temperature_c: 6.0,
        kind: PrecipitationKind::Rain,
        ..Weather::default()
    };
    backend.set_weather(&warm).expect("valid");
    let mut last = snowy.swe_kg;
    for _ in 0..20 {
        common::run(&mut backend, 1, 0.05); // an hour and 12 minutes a step: one warm day
        let swe = backend.read_cover().expect("configured").totals().swe_kg;
        assert!(swe <= last, "snow only melts in the warm: {last} -> {swe}");
        last = swe;
    }
    let cover = backend.read_cover().expect("configured");
    let melting = cover.totals();
    assert!(
        melting.swe_kg < snowy.swe_kg,
        "melted: {} -> {}",
        snowy.swe_kg,
        melting.swe_kg
    );
    let reached_ground = |t: &precip_model::cover::CoverTotals| {
        t.film_kg + t.standing_kg + t.infiltrated_kg + t.evaporated_kg + t.runoff_kg
    };
    assert!(
        reached_ground(&melting) > reached_ground(&snowy),
        "melt water drains from the pack to the ground"
    );
    assert!(
        cover.texels.iter().any(|t| t.wetness > 0.1),
        "melt water wets the ground"
    );
    assert!(
        melting.imbalance_kg().abs() < 1e-3 * melting.deposited_kg,
        "{melting:?}"
    );
}

#[test]
fn landing_events_deposit_and_re_birth() {
    use precip_model::cover::DepositBuffer;
    use precip_model::particles::step::step_particle;
    use precip_model::wind::WindVolume;

    let setup = Setup::over_flat_ground(10.0, 5, 5.0, 10);
    let weather = setup.weather;
    let params = setup.step_params(&weather, Vec3::ZERO, 0.05, 0.0);
    let wind = WindVolume::bake(&weather.wind, &setup.wind_volume).expect("valid");
    let deposits = DepositBuffer::new(setup.cover.frame.texel_count());
    let inputs = common::step_inputs(&setup, &params, &wind, &deposits);
    let mut p = precip_model::particles::birth::birth_on_emitter(3, 0, &params, &setup.ground);
    p.position_m = Vec3::new(1.0, 0.01, 1.0);
    p.velocity_mps = Vec3::new(0.0, -1.0, 0.0);
    p.water_kg = 0.25;
    let (born, event) = step_particle(3, &p, &inputs);
    assert_eq!(event, StepEvent::Landed);
    assert_eq!(born.generation, 1);
    assert!(
        (born.position_m.y - 5.0).abs() < 1e-4,
        "re-born on the emitter"
    );
    let texel = setup
        .cover
        .frame
        .texel_index(Vec2::new(1.0, 1.0))
        .expect("on grid");
    let (snow_mm, _) = deposits.peek_mm(texel);
    let expected =
        (0.25 + params.water_per_particle_kg_per_s * 0.05) / setup.cover.frame.texel_area_m2();
    assert!((snow_mm - expected).abs() < 1e-5, "{snow_mm} vs {expected}");
}

#[test]
fn flakes_blown_against_a_wall_rise_along_it_in_a_strong_wind_and_settle_in_a_light_one() {
    use precip_model::cover::DepositBuffer;
    use precip_model::particles::step::step_particle;
    use precip_model::wind::WindVolume;

    let mut setup = Setup::over_flat_ground(10.0, 10, 5.0, 10);
    // A 3 m wall: the column of 1 m texels at x = 2.5 m. Between the points at
    // which the flow reads the ground (every 1.5 m along the wind from x = 0:
    // physics::terrain_flow) the flow does not see it and blows against it, as it
    // does against what is thinner than that spacing; a wall it sees has still air
    // before it (tests/snowfall_footprint.rs), and a flake settles there.
    let frame = setup.ground.frame;
    for i in 0..frame.texel_count() {
        if (frame.texel_centre(i).x - 2.5).abs() < 0.1 {
            setup.ground.height_m[i] = 3.0;
        }
    }
    setup.weather.air_temperature_c = -12.0;
    for (wind_mps, rebounds) in [(14.0, true), (3.0, false)] {
        setup.weather.wind = WindField {
            mean_wind_mps: Vec3::new(wind_mps, 0.0, 0.0),
            ..WindField::calm()
        };
        let params = setup.step_params(&setup.weather, Vec3::ZERO, 0.05, 0.0);
        let wind = WindVolume::bake(&setup.weather.wind, &setup.wind_volume).expect("valid");
        let deposits = DepositBuffer::new(setup.cover.frame.texel_count());
        let inputs = common::step_inputs(&setup, &params, &wind, &deposits);
        let mut p = precip_model::particles::birth::birth_on_emitter(3, 0, &params, &setup.ground);
        // 1 m up, just before the wall, moving into it with the wind.
        p.position_m = Vec3::new(1.9, 1.0, 0.3);
        p.velocity_mps = Vec3::new(wind_mps, -1.0, 0.0);
        let (next, event) = step_particle(3, &p, &inputs);
        let landed: f32 = (0..setup.cover.frame.texel_count())
            .map(|i| deposits.peek_mm(i).0)
            .sum();
        if rebounds {
            assert_eq!(event, StepEvent::Moved, "{wind_mps} m/s");
            assert_eq!(next.position_m, p.position_m, "back where it was");
            assert!(next.velocity_mps.y > 5.0, "rising: {}", next.velocity_mps);
            assert!(landed.abs() < f32::MIN_POSITIVE, "nothing deposited");
        } else {
            assert_eq!(event, StepEvent::Landed, "{wind_mps} m/s");
            assert!(landed > 0.0, "settled at the wall's foot");
        }
    }
}

#[test]
fn particles_land_on_the_roof_of_a_scene_and_never_inside_the_house() {
    use precip_model::scene::builtin::{HousePlan, house_on_plane};
    let plan = HousePlan::default();
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 4.0, 6_000).expect("valid");
    setup.cover.time_scale = 200.0;
    let mut cpu = precip_model::CpuBackend::new();
    cpu.configure(&setup).expect("valid");
    let (rx, rz) = (
        plan.width_m / 2.0 + plan.overhang_m,
        plan.depth_m / 2.0 + plan.overhang_m,
    );
    let under_roof = |p: Vec3| p.x.abs() < rx - 0.3 && p.z.abs() < rz - 0.3;
    for _ in 0..40 {
        cpu.step(0.1).expect("valid step");
        for p in cpu.read_particles().expect("particles") {
            if under_roof(p.position_m) {
                let roof = setup
                    .ground
                    .height_at(Vec2::new(p.position_m.x, p.position_m.z))
                    .expect("on the map");
                assert!(
                    p.position_m.y >= roof - 0.05,
                    "a particle at {} is under the roof at {roof} m",
                    p.position_m
                );
            }
        }
    }
    let cover = cpu.read_cover().expect("cover");
    let (mut roof, mut roof_n, mut open, mut open_n) = (0.0, 0, 0.0, 0);
    for (i, t) in cover.texels.iter().enumerate() {
        let c = cover.frame.texel_centre(i);
        let p = Vec3::new(c.x, 0.0, c.y);
        if under_roof(p) {
            roof += t.deposited_mm;
            roof_n += 1;
        } else if c.x.abs() > rx + 3.0 && c.x.abs() < 15.0 && c.y.abs() < 15.0 {
            open += t.deposited_mm;
            open_n += 1;
        }
    }
    let (roof, open) = (roof / roof_n as f32, open / open_n as f32);
    assert!(roof > 0.0 && open > 0.0, "roof {roof} mm, open {open} mm");
    assert!(
        (0.5..2.0).contains(&(roof / open)),
        "the roof gathers what open ground does: roof {roof} mm, open {open} mm per texel"
    );
}

#[test]
fn flakes_blown_under_an_eave_pile_at_the_wall_not_on_the_roof_edge() {
    use precip_model::scene::builtin::{HousePlan, house_on_plane};
    let plan = HousePlan::default();
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 88, 4.0, 12_000).expect("valid");
    setup.cover.time_scale = 200.0;
    // Cover texels as fine as the ground's (0.5 m), so the roof's edge and the ground
    // at the wall's foot are different texels.
    setup.cover.frame = setup.ground.frame;
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(3.0, 0.0, 0.0),
        ..WindField::calm()
    };
    // The emitter upwind, so the wind carries flakes over the whole scene.
    if let Some(e) = setup.world_emitter.as_mut() {
        let height = e.emitter.model.w_axis.y;
        e.emitter = precip_model::WorldEmitter::horizontal(
            Vec3::new(-20.0, height, 0.0),
            60.0,
            44.0,
            height,
        );
    }
    let mut cpu = precip_model::CpuBackend::new();
    cpu.configure(&setup).expect("valid");
    for _ in 0..150 {
        cpu.step(0.1).expect("valid step");
    }
    let cover = cpu.read_cover().expect("cover");
    let (rx, rz) = (
        plan.width_m / 2.0 + plan.overhang_m,
        plan.depth_m / 2.0 + plan.overhang_m,
    );
    let mean_where = |keep: &dyn Fn(Vec2) -> bool| {
        let values: Vec<f32> = cover
            .texels
            .iter()
            .enumerate()
            .filter(|(i, _)| keep(cover.frame.texel_centre(*i)))
            .map(|(_, t)| t.deposited_mm)
            .collect();
        values.iter().sum::<f32>() / values.len().max(1) as f32
    };
    let along = |c: Vec2| c.y.abs() < rz - 1.0;
    let roof = mean_where(&|c| c.x.abs() < rx - 0.1 && along(c));
    let windward_roof_edge = mean_where(&|c| c.x > -rx && c.x < -rx + 0.6 && along(c));
    let wall_foot = mean_where(&|c| c.x < -rx && c.x > -rx - 0.6 && along(c));
    let summary = format!(
        "roof {roof:.2} mm, its windward edge {windward_roof_edge:.2} mm, the ground at the wall {wall_foot:.2} mm"
    );
    assert!(roof > 0.0, "{summary}");
    assert!(windward_roof_edge < 2.0 * roof, "{summary}");
    assert!(
        wall_foot > roof,
        "a drift forms at the windward wall: {summary}"
    );
}
