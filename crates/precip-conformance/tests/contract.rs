//! The Backend contract, one suite run over every backend (the CPU reference, wgpu on
//! every adapter, Vulkan under the validation layer): calls before configure, bad
//! input refused with the same typed error and the backend unchanged and working
//! afterwards, the device's limits, determinism, sub-step splitting, mass reaching the
//! cover, and the shape of timings. A new backend passes this file or is not done.

use std::mem::discriminant;

use glam::Vec3;
use precip_conformance::{Subject, all_subjects, gpu_subjects};
use precip_model::cover::{CoverError, CoverGrid, CoverTexel, GridFrame};
use precip_model::{Backend, BackendError, Camera, GroundMap, Particle, Setup, View, Weather};

fn setup(seed: u32, count: u32) -> Setup {
    let mut setup = Setup::over_flat_ground(40.0, 16, 15.0, count);
    setup.seed = seed;
    setup.cover.time_scale = 500.0;
    setup
}

fn view(setup: &Setup) -> View {
    View {
        camera: setup.camera,
        width_px: 32,
        height_px: 24,
    }
}

fn bytes(particles: &[Particle]) -> Vec<u8> {
    bytemuck::cast_slice(particles).to_vec()
}

/// Asserts that `f` is refused by every subject with the same error variant.
fn same_refusal<'a>(
    subjects: impl IntoIterator<Item = &'a mut Subject>,
    what: &str,
    f: impl Fn(&mut dyn Backend) -> Result<(), BackendError>,
) {
    let mut first: Option<(String, BackendError)> = None;
    for s in subjects {
        let e = f(s.backend.as_mut())
            .err()
            .unwrap_or_else(|| panic!("{}: {what} was accepted", s.name));
        match &first {
            None => first = Some((s.name.clone(), e)),
            Some((name, f)) => assert_eq!(
                discriminant(f),
                discriminant(&e),
                "{what}: {name} said `{f}`, {} said `{e}`",
                s.name
            ),
        }
        s.check_clean(what);
    }
}

#[test]
fn calls_before_configure_are_refused_alike() {
    let mut subjects = all_subjects("calls_before_configure_are_refused_alike");
    let s = setup(1, 100);
    same_refusal(subjects.iter_mut(), "step", |b| b.step(0.02));
    same_refusal(subjects.iter_mut(), "set_weather", |b| {
        b.set_weather(&Weather::default())
    });
    same_refusal(subjects.iter_mut(), "set_camera", |b| {
        b.set_camera(&Camera::default())
    });
    same_refusal(subjects.iter_mut(), "read_particles", |b| {
        b.read_particles().map(drop)
    });
    same_refusal(subjects.iter_mut(), "read_cover", |b| {
        b.read_cover().map(drop)
    });
    same_refusal(subjects_that_render(&mut subjects), "render", |b| {
        b.render(&view(&s))
    });
    same_refusal(subjects_that_render(&mut subjects), "read_image", |b| {
        b.read_image().map(drop)
    });
}

fn subjects_that_render(subjects: &mut [Subject]) -> impl Iterator<Item = &mut Subject> {
    subjects.iter_mut().filter(|s| s.renders())
}

#[test]
fn bad_input_is_refused_alike_and_leaves_the_backend_as_it_was() {
    let mut subjects = all_subjects("bad_input_is_refused_alike");
    let good = setup(7, 2_000);
    for s in &mut subjects {
        s.backend.configure(&good).expect("configure");
        s.backend.step(0.05).expect("step");
    }
    let before: Vec<Vec<u8>> = subjects
        .iter_mut()
        .map(|s| bytes(&s.backend.read_particles().expect("particles")))
        .collect();

    let mut nan_weather = good.weather;
    nan_weather.intensity_mm_per_h = f32::NAN;
    same_refusal(subjects.iter_mut(), "NaN intensity", |b| {
        b.set_weather(&nan_weather)
    });
    let mut hot_snow = good.weather;
    hot_snow.air_temperature_c = 30.0;
    same_refusal(subjects.iter_mut(), "snow at 30 °C", |b| {
        b.set_weather(&hot_snow)
    });
    for dt in [0.0, -1.0, f32::NAN, f32::INFINITY, 2.0] {
        same_refusal(subjects.iter_mut(), &format!("dt {dt}"), |b| b.step(dt));
    }
    let bad_camera = Camera {
        position_m: Vec3::new(f32::NAN, 0.0, 0.0),
        ..Camera::default()
    };
    same_refusal(subjects.iter_mut(), "NaN camera", |b| {
        b.set_camera(&bad_camera)
    });
    same_refusal(subjects.iter_mut(), "zero particles", |b| {
        b.configure(&setup(7, 0))
    });
    let mut bad_emitter = good.clone();
    if let Some(e) = bad_emitter.world_emitter.as_mut() {
        e.emitter.width_m = -3.0;
    }
    same_refusal(subjects.iter_mut(), "a negative emitter", |b| {
        b.configure(&bad_emitter)
    });
    let mut bad_scale = good.clone();
    bad_scale.cover.time_scale = f32::NAN;
    same_refusal(subjects.iter_mut(), "NaN time scale", |b| {
        b.configure(&bad_scale)
    });
    // More particles than each backend holds (its own maximum + 1).
    for s in &mut subjects {
        let max = s.backend.info().max_particles;
        let too_many = setup(7, u32::try_from(max + 1).unwrap_or(u32::MAX));
        if u64::from(too_many.particle_counts().0) > max {
            let e = s
                .backend
                .configure(&too_many)
                .expect_err("too many particles");
            assert!(
                matches!(e, BackendError::CapacityTooLarge { .. }),
                "{}: {e}",
                s.name
            );
        }
    }
    for (w, h) in [(0, 24), (32, 0), (100_000, 24), (u32::MAX, u32::MAX)] {
        let bad = View {
            width_px: w,
            height_px: h,
            ..view(&good)
        };
        same_refusal(
            subjects_that_render(&mut subjects),
            &format!("a {w}×{h} view"),
            |b| b.render(&bad),
        );
    }
    // Unchanged: the particles are as they were, and the backend still steps.
    for (s, before) in subjects.iter_mut().zip(&before) {
        let now = bytes(&s.backend.read_particles().expect("particles"));
        assert!(
            now == *before,
            "{}: a refused call changed the particles",
            s.name
        );
        s.backend.step(0.05).expect("still steps");
        if s.renders() {
            s.backend.render(&view(&good)).expect("still renders");
            s.backend.read_image().expect("an image");
        }
        s.check_clean("after the refusals");
    }
}

#[test]
fn grids_larger_than_the_device_binds_are_refused_by_every_gpu_backend() {
    for mut s in gpu_subjects("grids_larger_than_the_device_binds") {
        let good = setup(3, 500);
        s.backend.configure(&good).expect("configure");
        // Just over one storage binding of ground heights (4 bytes a texel).
        let device_bytes = s.backend.info().max_particles * size_of::<Particle>() as u64;
        let side = ((device_bytes / 4) as f64).sqrt().ceil() as u32 + 1;
        let mut big = good.clone();
        big.ground = GroundMap::flat(
            GridFrame::centred(
                glam::Vec2::ZERO,
                glam::Vec2::splat(40.0),
                glam::UVec2::splat(side),
            ),
            0.0,
            1.0,
        );
        let e = s
            .backend
            .configure(&big)
            .expect_err("too large a ground map");
        // A device whose bindings hold more than the cover's 16 384 texels a side
        // (an H200 holds 23 172) is refused by that cap instead: the same field.
        assert!(
            matches!(
                e,
                BackendError::Setup {
                    field: "ground.frame",
                    ..
                }
            ) || matches!(
                e,
                BackendError::Cover(CoverError::OutOfRange {
                    field: "ground.frame",
                    ..
                })
            ),
            "{}: {e}",
            s.name
        );
        s.backend
            .step(0.02)
            .expect("the old configuration still steps");
        s.check_clean("after a refused grid");
    }
}

#[test]
fn the_same_seed_gives_the_same_particles_and_another_seed_others() {
    for mut s in all_subjects("determinism") {
        let run = |b: &mut dyn Backend, seed: u32| {
            b.configure(&setup(seed, 3_000)).expect("configure");
            for _ in 0..6 {
                b.step(0.04).expect("step");
            }
            bytes(&b.read_particles().expect("particles"))
        };
        let a = run(s.backend.as_mut(), 11);
        let b = run(s.backend.as_mut(), 11);
        let c = run(s.backend.as_mut(), 12);
        assert!(a == b, "{}: the same seed differs", s.name);
        assert!(a != c, "{}: another seed gives the same particles", s.name);
        s.check_clean("determinism");
    }
}

#[test]
fn a_long_step_is_its_sub_steps() {
    for mut s in all_subjects("sub-steps") {
        let good = setup(5, 2_000);
        s.backend.configure(&good).expect("configure");
        s.backend.step(0.12).expect("one step of 3 sub-steps");
        let whole = bytes(&s.backend.read_particles().expect("particles"));
        s.backend.configure(&good).expect("configure");
        for _ in 0..3 {
            s.backend.step(0.04).expect("a sub-step");
        }
        let split = bytes(&s.backend.read_particles().expect("particles"));
        assert!(whole == split, "{}: step(0.12) ≠ 3 × step(0.04)", s.name);
        s.check_clean("sub-steps");
    }
}

#[test]
fn water_reaches_the_cover_at_the_weather_rate() {
    for mut s in all_subjects("mass") {
        let mut good = setup(9, 6_000);
        good.cover.time_scale = 1.0;
        s.backend.configure(&good).expect("configure");
        // Settle (pre-warmed particles), then measure over 4 s.
        for _ in 0..40 {
            s.backend.step(0.1).expect("step");
        }
        let start = s.backend.read_cover().expect("cover").totals().deposited_kg;
        for _ in 0..40 {
            s.backend.step(0.1).expect("step");
        }
        let landed = s.backend.read_cover().expect("cover").totals().deposited_kg - start;
        let area = good
            .world_emitter
            .map(|e| e.emitter.horizontal_area_m2())
            .unwrap_or(0.0);
        let expected = f64::from(good.weather.intensity_mm_per_h) / 3600.0 * f64::from(area) * 4.0;
        let ratio = landed / expected;
        assert!(
            (0.8..1.2).contains(&ratio),
            "{}: landed {landed} kg against {expected} kg",
            s.name
        );
        s.check_clean("mass");
    }
}

#[test]
fn timings_name_the_same_passes_on_every_gpu_backend() {
    let mut shapes: Vec<(String, Vec<&'static str>)> = Vec::new();
    for mut s in gpu_subjects("timings") {
        let good = setup(2, 1_000);
        s.backend.configure(&good).expect("configure");
        s.backend.step(0.1).expect("step");
        s.backend.render(&view(&good)).expect("render");
        let t = s.backend.timings().expect("timings");
        assert!(
            t.passes
                .iter()
                .all(|p| p.milliseconds.is_finite() && p.milliseconds >= 0.0)
        );
        shapes.push((s.name.clone(), t.passes.iter().map(|p| p.pass).collect()));
    }
    for pair in shapes.windows(2) {
        assert_eq!(
            pair[0].1, pair[1].1,
            "{} and {} time different passes",
            pair[0].0, pair[1].0
        );
    }
}

/// Rain at 40 mm/h on an asphalt plane of 1 m texels sloping 2 % along x with a dip
/// of 8 cm at its centre, at an hour a second of cover time, fed at the weather's
/// rate (particles only around the camera), so every backend's cover gets the same
/// water and differs only by its arithmetic.
fn rain_on_a_dip() -> Setup {
    let mut s = setup(5, 4_000);
    s.world_emitter = None;
    s.camera_volume = Some(precip_model::backend::setup::CameraVolumeSetup {
        volume: precip_model::CameraVolume::default(),
        particle_count: 2_000,
    });
    let frame = GridFrame::centred(
        glam::Vec2::ZERO,
        glam::Vec2::splat(40.0),
        glam::UVec2::splat(40),
    );
    let heights = (0..frame.texel_count())
        .map(|i| {
            let c = frame.texel_centre(i);
            -0.02 * c.x - 0.08 * (-c.length_squared() / 9.0).exp()
        })
        .collect();
    s.ground = GroundMap {
        height_m: heights,
        eligibility: vec![0.0; frame.texel_count()],
        surface: vec![precip_model::cover::Surface::Asphalt; frame.texel_count()],
        frame,
    };
    s.cover.frame = frame;
    s.cover.time_scale = 86_400.0 / 24.0;
    s.weather = Weather {
        kind: precip_model::PrecipitationKind::Rain,
        intensity_mm_per_h: 40.0,
        air_temperature_c: 15.0,
        relative_humidity: 0.8,
        ..Weather::default()
    };
    s
}

#[test]
fn rain_gathers_in_a_dip_conserving_water_alike_on_every_backend() {
    let mut covers = Vec::new();
    for mut s in all_subjects("water") {
        let good = rain_on_a_dip();
        s.backend.configure(&good).expect("configure");
        // 3 s at an hour a second: 3 h of cover time.
        for _ in 0..30 {
            s.backend.step(0.1).expect("step");
        }
        let cover = s.backend.read_cover().expect("cover");
        let totals = cover.totals();
        let centre = cover.texel_at(0.5, 0.5).expect("on the grid").standing_mm;
        let upslope = cover.texel_at(-12.5, 0.5).expect("on the grid").standing_mm;
        println!(
            "{}: dip {centre:.1} mm, upslope {upslope:.2} mm; landed {:.1} kg = films {:.1} + standing {:.1} + evaporated {:.1} + run off {:.1} (imbalance {:.2e} kg)",
            s.name,
            totals.deposited_kg,
            totals.film_kg,
            totals.standing_kg,
            totals.evaporated_kg,
            totals.runoff_kg,
            totals.imbalance_kg()
        );
        assert!(
            centre > 10.0,
            "{}: a puddle in the dip: {centre} mm",
            s.name
        );
        assert!(upslope < 1.0, "{}: the slope drains: {upslope} mm", s.name);
        assert!(
            totals.runoff_kg > 0.0 && totals.evaporated_kg > 0.0,
            "{}",
            s.name
        );
        assert!(
            totals.imbalance_kg().abs() < 1e-4 * totals.deposited_kg,
            "{}: landed = on surfaces + infiltrated + evaporated + run off: {totals:?}",
            s.name
        );
        s.check_clean("water");
        covers.push((s.name.clone(), cover));
    }
    assert_water_alike(&covers);
}

/// Rain on the dip, then a dry spell in which the puddle comes to rest (level to
/// `LEVEL_WATER_M`: the GPUs then flow only the sub-step's first iteration over it,
/// the tiles where nothing moves left out of the rest), then rain again, which
/// must wake it: the books close and every backend's water is the CPU's, which
/// flows over the whole grid every iteration.
#[test]
fn a_puddle_at_rest_sleeps_and_wakes_when_the_rain_comes_back_alike_on_every_backend() {
    let mut covers = Vec::new();
    for mut s in all_subjects("resting water") {
        let good = rain_on_a_dip();
        s.backend.configure(&good).expect("configure");
        let dry = Weather {
            intensity_mm_per_h: 0.0,
            ..good.weather
        };
        for (weather, steps) in [(&good.weather, 10), (&dry, 20), (&good.weather, 5)] {
            s.backend.set_weather(weather).expect("a valid weather");
            for _ in 0..steps {
                s.backend.step(0.1).expect("step");
            }
        }
        let cover = s.backend.read_cover().expect("cover");
        let totals = cover.totals();
        let centre = cover.texel_at(0.5, 0.5).expect("on the grid").standing_mm;
        assert!(
            centre > 5.0,
            "{}: the puddle is still there: {centre} mm",
            s.name
        );
        assert!(
            totals.imbalance_kg().abs() < 1e-4 * totals.deposited_kg,
            "{}: the books close through rest and waking: {totals:?}",
            s.name
        );
        s.check_clean("resting water");
        covers.push((s.name.clone(), cover));
    }
    assert_water_alike(&covers);
}

/// Every backend's water where the CPU reference (`covers[0]`) has it.
fn assert_water_alike(covers: &[(String, CoverGrid)]) {
    // Every backend's water where the CPU reference has it: the same landed water
    // (fixed point) and the same flow up to float rounding. Rounding moves the
    // fronts of water in transit (sheets travelling a texel an iteration at this
    // hour-a-second flux) by up to a texel and puddles by a few per cent: each
    // texel's standing water lies within what the other backend has in the texel
    // or its eight neighbours (H200, whose driver fuses multiplies and adds: a
    // front at texel 478 a texel ahead, 6.7 mm against the reference's 3.9 mm,
    // totals within 0.01 %).
    let (reference_name, reference) = &covers[0];
    for (name, cover) in &covers[1..] {
        let (a, b) = (reference.totals(), cover.totals());
        for (what, x, y) in [
            ("standing", a.standing_kg, b.standing_kg),
            ("films", a.film_kg, b.film_kg),
            ("run off", a.runoff_kg, b.runoff_kg),
        ] {
            assert!(
                (x - y).abs() <= 0.01 * x.max(y),
                "{name} vs {reference_name}: {what} {y} vs {x} kg"
            );
        }
        for i in 0..reference.texels.len() {
            for (what, value) in [
                (
                    "standing",
                    (|t: &CoverTexel| t.standing_mm) as fn(&CoverTexel) -> f32,
                ),
                ("film", |t: &CoverTexel| t.film_mm),
            ] {
                let (x, y) = (value(&reference.texels[i]), value(&cover.texels[i]));
                assert!(
                    within_a_texel(reference, i, value, y) && within_a_texel(cover, i, value, x),
                    "{name} vs {reference_name}, texel {i}: {what} {y} vs {x} mm, \
                     neither within the other's neighbours ({:?} vs {:?})",
                    neighbours(cover, i, value),
                    neighbours(reference, i, value),
                );
            }
        }
    }
}

#[test]
fn runoff_from_a_road_flows_only_where_it_runs_alike_on_every_backend() {
    let mut covers = Vec::new();
    for mut s in all_subjects("road") {
        let good = rain_on_a_road();
        s.backend.configure(&good).expect("configure");
        // 8 min of rain at two minutes a second, then 8 min of the road draining:
        // its upper end dries while water still runs below it.
        for _ in 0..40 {
            s.backend.step(0.1).expect("step");
        }
        let raining = s.backend.read_cover().expect("cover");
        s.backend
            .set_weather(&Weather {
                intensity_mm_per_h: 0.0,
                ..good.weather
            })
            .expect("the rain stops");
        for _ in 0..40 {
            s.backend.step(0.1).expect("step");
        }
        let cover = s.backend.read_cover().expect("cover");
        let totals = cover.totals();
        let wet = |c: &CoverGrid| {
            c.texels
                .iter()
                .filter(|t| t.standing_mm > precip_model::cover::water::STILL_WATER_MM)
                .count()
        };
        let at = |c: &CoverGrid, x: f32| c.texel_at(x, 0.5).expect("on the grid").standing_mm;
        println!(
            "{}: raining, {} of {} texels hold water, the road's foot {:.2} mm, the sand past it \
             (the next tile) {:.3} mm; drained, {} texels, the road's head {:.4} mm, its foot \
             {:.2} mm; imbalance {:.2e} kg",
            s.name,
            wet(&raining),
            cover.texels.len(),
            at(&raining, 31.5),
            at(&raining, 32.5),
            wet(&cover),
            at(&cover, -20.5),
            at(&cover, 31.5),
            totals.imbalance_kg()
        );
        assert!(
            at(&raining, 31.5) > 0.1,
            "{}: the road runs with water",
            s.name
        );
        assert!(
            at(&raining, 32.5) > 0.1,
            "{}: the runoff crosses onto the sand, into the next tile",
            s.name
        );
        assert!(
            at(&cover, -20.5) < 0.5 * at(&raining, -20.5),
            "{}: the road drains",
            s.name
        );
        assert!(
            wet(&raining) < cover.texels.len() / 32,
            "{}: water stands on {} texels",
            s.name,
            wet(&raining)
        );
        assert_eq!(
            cover.texel_at(-20.5, 40.5).map(|t| t.standing_mm),
            Some(0.0),
            "{}: rain sinks into sand",
            s.name
        );
        assert!(
            totals.imbalance_kg().abs() < 1e-6 * totals.deposited_kg
                && totals.net_inflow_kg.abs() < 0.01,
            "{}: what leaves a texel enters its neighbour: {totals:?}",
            s.name
        );
        s.check_clean("road");
        covers.push((s.name.clone(), raining, cover));
    }
    // Thin sheets, far from any front: each texel alike within 0.01 mm and 1 %.
    let (reference_name, reference, drained) = &covers[0];
    for (name, raining, cover) in &covers[1..] {
        for (when, a, b) in [("raining", reference, raining), ("drained", drained, cover)] {
            for (i, (x, y)) in a.texels.iter().zip(&b.texels).enumerate() {
                let (x, y) = (x.standing_mm, y.standing_mm);
                assert!(
                    (x - y).abs() <= 0.01 + 0.01 * x.max(y),
                    "{name} vs {reference_name}, {when}, texel {i}: {y} vs {x} mm"
                );
            }
        }
    }
}

#[test]
fn a_sheet_running_a_texel_an_iteration_loses_no_water_between_tiles() {
    // A 30 % road at an hour a second: the sheet's front runs a texel a flow
    // iteration, as far as the flow lets water go between two lists of its tiles;
    // then the rain stops, and the sheet runs off the road and sinks into the sand
    // in a few sub-steps, the tiles it wetted drying at once.
    for mut s in all_subjects("steep road") {
        let good = rain_on_a_road_of(0.3, 3_600.0);
        s.backend.configure(&good).expect("configure");
        for phase in ["raining", "drained"] {
            if phase == "drained" {
                s.backend
                    .set_weather(&Weather {
                        intensity_mm_per_h: 0.0,
                        ..good.weather
                    })
                    .expect("the rain stops");
            }
            for _ in 0..10 {
                s.backend.step(0.1).expect("step");
            }
            let cover = s.backend.read_cover().expect("cover");
            let t = cover.totals();
            let past_the_end = cover
                .texels
                .iter()
                .enumerate()
                .filter(|(i, c)| cover.frame.texel_centre(*i).x > 40.0 && c.standing_mm > 0.0)
                .count();
            println!(
                "{}, {phase}: {past_the_end} texels 8 m or more past the road's end hold water; \
                 sent {:.3e} kg more than taken; landed {:.0} kg, imbalance {:.2e} kg",
                s.name,
                -t.net_inflow_kg,
                t.deposited_kg,
                t.imbalance_kg()
            );
            assert!(
                phase == "drained" || past_the_end > 0,
                "{}: the sheet runs a tile past the road",
                s.name
            );
            assert!(
                t.net_inflow_kg.abs() < 0.01,
                "{}, {phase}: water a texel sent its neighbour was lost: {t:?}",
                s.name
            );
        }
        s.check_clean("steep road");
    }
}

/// `value` of texel `i` and its eight neighbours (those on the grid), mm.
fn neighbours(grid: &CoverGrid, i: usize, value: fn(&CoverTexel) -> f32) -> Vec<f32> {
    let side = grid.frame.texels;
    let (col, row) = (i64::from(i as u32 % side.x), i64::from(i as u32 / side.x));
    let mut out = Vec::with_capacity(9);
    for dz in -1..=1 {
        for dx in -1..=1 {
            let (c, r) = (col + dx, row + dz);
            if (0..i64::from(side.x)).contains(&c) && (0..i64::from(side.y)).contains(&r) {
                out.push(value(&grid.texels[(r * i64::from(side.x) + c) as usize]));
            }
        }
    }
    out
}

/// Whether `mm` lies within `grid`'s range of `value` over texel `i` and its eight
/// neighbours, widened by 5 % and 0.5 mm (float rounding of the flow; H200: an edge
/// texel 4.05 mm among neighbours of 4.05–6.68 mm against the reference's 3.66 mm).
fn within_a_texel(grid: &CoverGrid, i: usize, value: fn(&CoverTexel) -> f32, mm: f32) -> bool {
    let around = neighbours(grid, i, value);
    let low = around.iter().copied().fold(f32::INFINITY, f32::min);
    let high = around.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    mm >= low * 0.95 - 0.5 && mm <= high * 1.05 + 0.5
}

/// Rain at 40 mm/h on a 128 m square of 1 m texels of sand, which takes it all in,
/// crossed along x by a 3 m asphalt road from x = −30 to 32 m, the whole falling 2 %
/// along x, at two minutes a second of cover time: water runs down the road across
/// tile after tile of the flow and past its end onto the sand of the next tile
/// (`precip_gpu::recipe::COVER_TILE_SIDE`, 8 m from −64 m), and most of the square
/// stays dry, so the GPU flow works on few of its tiles.
fn rain_on_a_road() -> Setup {
    rain_on_a_road_of(0.02, 120.0)
}

/// [`rain_on_a_road`] falling `slope` along x at `time_scale`.
fn rain_on_a_road_of(slope: f32, time_scale: f32) -> Setup {
    let mut s = rain_on_a_dip();
    let frame = GridFrame::centred(
        glam::Vec2::ZERO,
        glam::Vec2::splat(128.0),
        glam::UVec2::splat(128),
    );
    let n = frame.texel_count();
    let road = |c: glam::Vec2| c.x > -30.0 && c.x < 32.0 && c.y.abs() < 1.5;
    s.ground = GroundMap {
        height_m: (0..n).map(|i| -slope * frame.texel_centre(i).x).collect(),
        eligibility: vec![0.0; n],
        surface: (0..n)
            .map(|i| {
                if road(frame.texel_centre(i)) {
                    precip_model::cover::Surface::Asphalt
                } else {
                    precip_model::cover::Surface::Sand
                }
            })
            .collect(),
        frame,
    };
    s.cover.frame = frame;
    s.cover.time_scale = time_scale;
    s
}

/// Dry snow at 3 mm/h and −12 °C under a 14 m/s wind along +x over level ground of
/// 1 m texels with a 2 m wall across it (one texel wide, x from −6 to −5 m), at an hour a second of cover time, fed at
/// the weather's rate (particles only around the camera): every backend's cover
/// gets the same snow and differs only by its arithmetic.
fn snow_over_a_wall() -> Setup {
    let mut s = rain_on_a_dip();
    let frame = s.ground.frame;
    let wall = |i: usize| (frame.texel_centre(i).x + 5.5).abs() < 0.1;
    let n = frame.texel_count();
    s.ground.height_m = (0..n).map(|i| if wall(i) { 2.0 } else { 0.0 }).collect();
    s.ground.eligibility = (0..n).map(|i| if wall(i) { 0.0 } else { 1.0 }).collect();
    // Bare soil: it holds 1 cm against the wind (a lawn holds 15, more than falls).
    s.ground.surface = vec![precip_model::cover::Surface::Soil; n];
    s.weather = Weather {
        kind: precip_model::PrecipitationKind::DrySnow,
        intensity_mm_per_h: 3.0,
        air_temperature_c: -12.0,
        relative_humidity: 0.8,
        wind: precip_model::wind::WindField {
            mean_wind_mps: Vec3::new(14.0, 0.0, 0.0),
            ..precip_model::wind::WindField::calm()
        },
        grain: None,
    };
    s
}

/// A 40 m square of 2.5 m texels whose up-wind quarter (x < −10 m) is loose sand
/// and the rest grass, in a 12 m/s wind along +x, with `kind`'s grains and none
/// settling from the sky: every world particle is lifted from the sand.
fn grains_off_a_sand_strip(kind: precip_model::PrecipitationKind) -> Setup {
    let mut s = setup(7, 6_000);
    let frame = s.ground.frame;
    s.ground.surface = (0..frame.texel_count())
        .map(|i| {
            if frame.texel_centre(i).x < -10.0 {
                precip_model::cover::Surface::Sand
            } else {
                precip_model::cover::Surface::Grass
            }
        })
        .collect();
    s.weather = Weather {
        kind,
        intensity_mm_per_h: 0.0,
        air_temperature_c: 30.0,
        relative_humidity: 0.2,
        wind: precip_model::wind::WindField {
            mean_wind_mps: Vec3::new(12.0, 0.0, 0.0),
            ..precip_model::wind::WindField::calm()
        },
        grain: None,
    };
    s
}

#[test]
fn sand_and_dust_rise_from_sand_and_settle_alike_on_every_backend() {
    use precip_model::PrecipitationKind::{Dust, Sand};
    for kind in [Sand, Dust] {
        let setup = grains_off_a_sand_strip(kind);
        let (world, _) = setup.particle_counts();
        let lift = setup.grain_lift(&setup.weather, world);
        assert_eq!(lift.lift_from, 0, "{kind:?}: every particle is lifted");
        assert!(lift.lifted_kg_per_s > 0.0, "{kind:?}: {lift:?}");
        let steps = 60;
        let dt = 0.05;
        let mut landed = Vec::new();
        for mut s in all_subjects("grains") {
            s.backend.configure(&setup).expect("configure");
            // The run starts with grains part-way through their hops, carrying what
            // they gathered since they left the surface.
            let initial_kg: f64 = s
                .backend
                .read_particles()
                .expect("particles")
                .iter()
                .map(|p| f64::from(p.water_kg))
                .sum();
            for _ in 0..steps {
                s.backend.step(dt).expect("step");
            }
            let particles = s.backend.read_particles().expect("particles");
            let cover = s.backend.read_cover().expect("cover");
            let totals = cover.totals();
            // Cover mass is scaled by the cover's time scale; particles carry real kg.
            let landed_kg = totals.dust_kg / f64::from(setup.cover.time_scale);
            let airborne_kg: f64 = particles.iter().map(|p| f64::from(p.water_kg)).sum();
            let lifted_kg =
                f64::from(lift.lifted_kg_per_s) * f64::from(dt) * f64::from(steps) + initial_kg;
            let down_wind_kg: f64 = cover
                .texels
                .iter()
                .enumerate()
                .filter(|(i, _)| cover.frame.texel_centre(*i).x > -10.0)
                .map(|(_, t)| f64::from(t.dust_kg_m2))
                .sum::<f64>()
                * f64::from(cover.frame.texel_area_m2())
                / f64::from(setup.cover.time_scale);
            let top_m = particles
                .iter()
                .map(|p| p.position_m.y)
                .fold(f32::NEG_INFINITY, f32::max);
            println!(
                "{} {kind:?}: lifted {lifted_kg:.3} kg, landed {landed_kg:.3} kg ({down_wind_kg:.3} kg beyond the sand), in the air {airborne_kg:.3} kg, highest grain {top_m:.2} m",
                s.name
            );
            assert!(
                particles
                    .iter()
                    .all(|p| p.kind() == precip_model::ParticleKind::Grain),
                "{}: only grains",
                s.name
            );
            // What was lifted is on the ground or in the air, less what blew off the
            // map (dust does: it rides the wind).
            assert!(
                landed_kg + airborne_kg <= lifted_kg * 1.001,
                "{}: no grains made",
                s.name
            );
            match kind {
                Sand => {
                    assert!(
                        landed_kg + airborne_kg >= 0.97 * lifted_kg,
                        "{}: sand hops, none is lost",
                        s.name
                    );
                    assert!(landed_kg > 0.5 * lifted_kg, "{}: sand lands", s.name);
                    assert!(down_wind_kg > 0.0, "{}: sand crosses the edge", s.name);
                    assert!(top_m < 2.0, "{}: sand stays low ({top_m} m)", s.name);
                }
                _ => {
                    assert!(top_m > 5.0, "{}: dust is suspended ({top_m} m)", s.name);
                    assert!(airborne_kg > landed_kg, "{}: dust hangs in the air", s.name);
                }
            }
            s.check_clean("grains");
            landed.push((s.name.clone(), landed_kg, airborne_kg));
        }
        let (reference, landed_ref, air_ref) = landed[0].clone();
        for (name, l, a) in &landed[1..] {
            assert!(
                (l - landed_ref).abs() <= 0.02 * landed_ref.max(*l) + 1e-9
                    && (a - air_ref).abs() <= 0.02 * air_ref.max(*a) + 1e-9,
                "{kind:?}: {name} landed {l} and holds {a} kg, {reference} {landed_ref} and {air_ref}"
            );
        }
    }
}

#[test]
fn snow_drifts_behind_a_wall_alike_on_every_backend() {
    let mut covers = Vec::new();
    for mut s in all_subjects("drift") {
        s.backend.configure(&snow_over_a_wall()).expect("configure");
        for _ in 0..30 {
            s.backend.step(0.1).expect("step");
        }
        let cover = s.backend.read_cover().expect("cover");
        let totals = cover.totals();
        let depth = |x: f32| cover.texel_at(x, 0.5).expect("on the grid").depth_mm;
        let (lee, windward, open) = (depth(-4.5), depth(-6.5), depth(-15.5));
        println!(
            "{}: lee foot {lee:.0} mm, windward foot {windward:.0} mm, open {open:.0} mm; fallen {:.1} kg, drifted over the edges {:.1} kg, inside {:.2e} kg; steepest {:.1}°; imbalance {:.2e} kg",
            s.name,
            totals.deposited_kg,
            totals.edge_drifted_kg,
            totals.drifted_kg - totals.edge_drifted_kg,
            cover.steepest_snow_slope_deg(),
            totals.imbalance_kg()
        );
        assert!(lee > windward && lee > open, "{}: a lee drift", s.name);
        assert!(totals.blowing_area_m2 > 0.0, "{}: snow is blowing", s.name);
        assert!(
            (totals.drifted_kg - totals.edge_drifted_kg).abs() < 1e-3 * totals.deposited_kg,
            "{}: drift inside the grid makes or loses no snow: {totals:?}",
            s.name
        );
        assert!(
            totals.imbalance_kg().abs() < 1e-4 * totals.deposited_kg,
            "{}: books: {totals:?}",
            s.name
        );
        assert!(
            cover.steepest_snow_slope_deg() <= 38.5,
            "{}: no snow steeper than its repose",
            s.name
        );
        s.check_clean("drift");
        covers.push((s.name.clone(), cover));
    }
    // The same snow where the CPU reference has it, up to float rounding (which the
    // threshold and the shelter can amplify in a texel or two: hence the totals
    // tightly and texels loosely).
    let (reference_name, reference) = &covers[0];
    for (name, cover) in &covers[1..] {
        let (a, b) = (reference.totals(), cover.totals());
        for (what, x, y) in [
            ("snow", a.swe_kg, b.swe_kg),
            (
                "drifted over the edges",
                a.edge_drifted_kg,
                b.edge_drifted_kg,
            ),
            ("snow volume", a.snow_volume_m3, b.snow_volume_m3),
        ] {
            assert!(
                (x - y).abs() <= 0.01 * x.abs().max(y.abs()) + 1e-3,
                "{name} vs {reference_name}: {what} {y} vs {x}"
            );
        }
        let off = reference
            .texels
            .iter()
            .zip(&cover.texels)
            .filter(|(a, b)| {
                (a.depth_mm - b.depth_mm).abs() > 0.05 * a.depth_mm.max(b.depth_mm) + 5.0
            })
            .count();
        assert!(
            off * 100 <= reference.texels.len(),
            "{name} vs {reference_name}: {off} texels' depths differ"
        );
    }
}

/// Asserts that the drift inside the grid made or lost no snow and the cover's
/// books close (`what` names the subject).
fn assert_drift_conserves(what: &str, t: &precip_model::cover::CoverTotals) {
    assert!(
        (t.drifted_kg - t.edge_drifted_kg).abs() < 1e-4 * t.deposited_kg,
        "{what}: snow a texel sent its neighbour was lost or made: {t:?}"
    );
    assert!(
        t.imbalance_kg().abs() < 1e-4 * t.deposited_kg,
        "{what}: books: {t:?}"
    );
}

/// Heavy dry snow in still air at −12 °C over level grass of 1 m texels, with a
/// 3 m high flat roof 8 m square that fills one tile of the drift
/// (`precip_gpu::recipe::COVER_TILE_SIDE`: x and z from −4 to 4 m), at four hours a
/// second of cover time, fed at the weather's rate.
fn snow_on_a_roof_in_still_air() -> Setup {
    let mut s = snow_over_a_wall();
    let frame = s.ground.frame;
    let roof = |i: usize| {
        let c = frame.texel_centre(i);
        c.x.abs() < 4.0 && c.y.abs() < 4.0
    };
    let n = frame.texel_count();
    s.ground.height_m = (0..n).map(|i| if roof(i) { 3.0 } else { 0.0 }).collect();
    s.ground.eligibility = vec![1.0; n];
    s.cover.time_scale = 4.0 * 3_600.0;
    s.weather.intensity_mm_per_h = 10.0;
    s.weather.wind = precip_model::wind::WindField::calm();
    s
}

#[test]
fn snow_slides_off_a_roof_in_still_air_alike_on_every_backend() {
    // First a gale blows the snow over every texel; then the air stills, and the
    // drift runs only over the tiles where snow would move: the roof's and those
    // around it, where what slides off its edges lands. The tiles the gale worked
    // on last write their outflows back to zero once, or the roof's neighbours
    // would go on taking the gale's last outflows from them.
    let mut covers = Vec::new();
    for mut s in all_subjects("roof") {
        let still = snow_on_a_roof_in_still_air();
        let mut gale = still.clone();
        gale.weather.wind.mean_wind_mps = Vec3::new(14.0, 0.0, 0.0);
        s.backend.configure(&gale).expect("configure");
        for _ in 0..3 {
            s.backend.step(0.1).expect("step");
        }
        s.backend
            .set_weather(&still.weather)
            .expect("the air stills");
        for _ in 0..25 {
            s.backend.step(0.1).expect("step");
        }
        let cover = s.backend.read_cover().expect("cover");
        let totals = cover.totals();
        let depth = |x: f32, z: f32| cover.texel_at(x, z).expect("on the grid").depth_mm;
        let (centre, edge, foot, open) = (
            depth(0.5, 0.5),
            depth(-3.5, 0.5),
            depth(-4.5, 0.5),
            depth(-15.5, -15.5),
        );
        println!(
            "{}: roof centre {centre:.0} mm, roof edge {edge:.0} mm, its foot {foot:.0} mm, \
             open ground {open:.0} mm; fallen {:.0} kg, moved inside {:.2e} kg net, blowing area \
             {} m²; imbalance {:.2e} kg",
            s.name,
            totals.deposited_kg,
            totals.drifted_kg - totals.edge_drifted_kg,
            totals.blowing_area_m2,
            totals.imbalance_kg()
        );
        // A ledge holds snow up to the repose line from its edge: half a texel at
        // 38°, 0.39 m.
        let ledge_mm = 0.5 * 38f32.to_radians().tan() * 1000.0;
        assert!(
            centre > ledge_mm + 50.0,
            "{}: the roof's snow stands above its ledge limit ({centre} mm)",
            s.name
        );
        assert!(
            edge < ledge_mm + 10.0 && edge < centre - 50.0,
            "{}: snow slid off the roof's edge ({edge} mm, centre {centre} mm)",
            s.name
        );
        assert!(
            foot > open + 50.0,
            "{}: what slid off lies at the wall's foot, in the next tile ({foot} vs {open} mm)",
            s.name
        );
        assert!(
            totals.blowing_area_m2 <= 0.0,
            "{}: the air is still, yet snow blows over {} m²",
            s.name,
            totals.blowing_area_m2
        );
        assert_drift_conserves(&s.name, &totals);
        s.check_clean("roof");
        covers.push((s.name.clone(), cover));
    }
    let (reference_name, reference) = &covers[0];
    for (name, cover) in &covers[1..] {
        for (i, (a, b)) in reference.texels.iter().zip(&cover.texels).enumerate() {
            assert!(
                (a.depth_mm - b.depth_mm).abs() <= 0.01 * a.depth_mm.max(b.depth_mm) + 1.0
                    && (a.swe_mm - b.swe_mm).abs() <= 0.01 * a.swe_mm.max(b.swe_mm) + 0.1,
                "{name} vs {reference_name}, texel {i}: {} mm deep ({} SWE) vs {} ({})",
                b.depth_mm,
                b.swe_mm,
                a.depth_mm,
                a.swe_mm
            );
        }
    }
}

#[test]
fn a_lawn_holds_its_snow_against_the_wind_alike_on_every_backend() {
    // The wall's blizzard over a lawn: 3 s of cover time leave far less than the
    // 15 cm the grass holds, so nothing drifts on any backend
    // (precip_cover::Surface::snow_holding_depth_m), where bare soil's drifts.
    let mut covers = Vec::new();
    for mut s in all_subjects("lawn") {
        let mut lawn = snow_over_a_wall();
        let n = lawn.ground.surface.len();
        lawn.ground.surface = vec![precip_model::cover::Surface::Grass; n];
        s.backend.configure(&lawn).expect("configure");
        for _ in 0..30 {
            s.backend.step(0.1).expect("step");
        }
        let cover = s.backend.read_cover().expect("cover");
        let totals = cover.totals();
        let deepest = cover
            .texels
            .iter()
            .map(|t| t.depth_mm)
            .fold(0.0f32, f32::max);
        println!(
            "{}: fallen {:.1} kg, deepest {deepest:.0} mm, blowing over {:.1} m², drifted over the edges {:.2e} kg",
            s.name, totals.deposited_kg, totals.blowing_area_m2, totals.edge_drifted_kg
        );
        assert!(totals.deposited_kg > 0.0, "{}: snow fell", s.name);
        assert!(deepest < 150.0, "{}: below what the grass holds", s.name);
        assert!(totals.blowing_area_m2 <= 0.0, "{}: no snow blows", s.name);
        assert!(
            totals.edge_drifted_kg.abs() <= 0.0,
            "{}: none leaves",
            s.name
        );
        assert!(
            cover.texels.iter().all(|t| t.drifted_mm == 0.0),
            "{}: none moves",
            s.name
        );
        s.check_clean("lawn");
        covers.push((s.name.clone(), totals.swe_kg));
    }
    let (reference, swe) = covers[0].clone();
    for (name, other) in &covers[1..] {
        assert!(
            (other - swe).abs() <= 1e-3 * swe,
            "{name} holds {other} kg of snow, {reference} {swe}"
        );
    }
}

#[test]
fn snow_blown_across_heated_paving_loses_none_between_tiles() {
    // Snow lies only on the up-wind column of tiles (x < −12 m); the rest is heated
    // paving where none may lie. A 14 m/s wind lifts it off the soil and carries it
    // across the paving a texel a drift iteration, as fast as the drift lets snow
    // move between two lists of its tiles, and over the grid's down-wind edge.
    let mut totals_of = Vec::new();
    for mut s in all_subjects("heated paving") {
        let mut good = snow_over_a_wall();
        let frame = good.ground.frame;
        let n = frame.texel_count();
        let soil = |i: usize| frame.texel_centre(i).x < -12.0;
        good.ground.height_m = vec![0.0; n];
        good.ground.eligibility = (0..n).map(|i| if soil(i) { 1.0 } else { 0.0 }).collect();
        good.ground.surface = (0..n)
            .map(|i| {
                if soil(i) {
                    precip_model::cover::Surface::Soil
                } else {
                    precip_model::cover::Surface::Asphalt
                }
            })
            .collect();
        s.backend.configure(&good).expect("configure");
        for _ in 0..20 {
            s.backend.step(0.1).expect("step");
        }
        let cover = s.backend.read_cover().expect("cover");
        let t = cover.totals();
        println!(
            "{}: snow {:.1} kg, in at the edges {:.2} kg net, moved inside {:.2e} kg net; \
             fallen {:.0} kg, imbalance {:.2e} kg",
            s.name,
            t.swe_kg,
            t.edge_drifted_kg,
            t.drifted_kg - t.edge_drifted_kg,
            t.deposited_kg,
            t.imbalance_kg()
        );
        let down_wind = cover.texel_at(19.5, 0.5).expect("on the grid").swe_mm;
        assert!(
            down_wind > 0.0,
            "{}: snow crosses the paving to the down-wind edge",
            s.name
        );
        assert_drift_conserves(&s.name, &t);
        s.check_clean("heated paving");
        totals_of.push((s.name.clone(), t));
    }
    let (reference_name, a) = &totals_of[0];
    for (name, b) in &totals_of[1..] {
        for (what, x, y) in [
            ("snow", a.swe_kg, b.swe_kg),
            ("in at the edges", a.edge_drifted_kg, b.edge_drifted_kg),
        ] {
            assert!(
                (x - y).abs() <= 0.01 * x.abs().max(y.abs()) + 1e-3,
                "{name} vs {reference_name}: {what} {y} vs {x}"
            );
        }
    }
}

#[test]
fn raindrops_splash_alike_and_deterministically_on_every_backend() {
    let mut counts = Vec::new();
    for mut s in all_subjects("splashes") {
        let mut good = setup(12, 6_000);
        good.weather = Weather {
            kind: precip_model::PrecipitationKind::Rain,
            intensity_mm_per_h: 20.0,
            air_temperature_c: 12.0,
            ..Weather::default()
        };
        let mut runs = Vec::new();
        for _ in 0..2 {
            s.backend.configure(&good).expect("configure");
            for _ in 0..30 {
                s.backend.step(0.05).expect("step");
            }
            runs.push(s.backend.read_particles().expect("particles"));
        }
        assert!(
            bytes(&runs[0]) == bytes(&runs[1]),
            "{}: the same seed splashes the same",
            s.name
        );
        let splash = precip_model::particles::particle::flags::SPLASH;
        let flying: Vec<&Particle> = runs[0].iter().filter(|p| p.flags & splash != 0).collect();
        assert!(
            flying
                .iter()
                .all(|p| p.diameter_m < 1.6e-3 && p.kind() == precip_model::ParticleKind::Rain),
            "{}: droplets are a quarter of a drop",
            s.name
        );
        println!("{}: {} splash droplets in flight", s.name, flying.len());
        counts.push((s.name.clone(), flying.len()));
        s.check_clean("splashes");
    }
    // Drops land at ~1 000 a second here and most splash; a droplet flies ~0.1 s.
    let (reference_name, reference) = &counts[0];
    assert!(*reference > 20, "{reference_name}: {reference} droplets");
    for (name, n) in &counts[1..] {
        let ratio = *n as f64 / *reference as f64;
        assert!(
            (0.8..1.25).contains(&ratio),
            "{name}: {n} droplets vs {reference} on {reference_name}"
        );
    }
}
