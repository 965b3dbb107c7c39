//! A scene standing on a terrain (issue 29's elevation data), alike on every GPU
//! backend: the clipmap puts the terrain's ridge where its heights say, both
//! backends draw the same picture, the Vulkan one without a validation message, its
//! land cover colours it by class, the cover beyond the grid is kept per place with
//! the air at each place's height (a ridge holds the snow a sleet leaves in the
//! valley as rain), and the ground map lands snow on the terrain where it rises
//! above the meshes.

use std::sync::Arc;

use glam::{UVec2, Vec2, Vec3};
use precip_conformance::gpu_subjects;
use precip_model::scene::LandCover;
use precip_model::scene::builtin::house_on_plane;
use precip_model::scene::terrain::Terrain;
use precip_model::{Camera, GroundMap, Image, Setup, View, Weather};

/// A valley 4 km square: flat around the house, a ridge 200 m high 1 km north
/// (−z) of it.
fn valley() -> Terrain {
    terrain_of(801, 5.0, |x, z| {
        -0.5 + 200.0 * (-((z + 1000.0) / 150.0).powi(2)).exp() + 2.0 * (x / 90.0).sin()
    })
}

/// `n × n` samples `spacing_m` apart centred on the origin, of heights
/// `height_m(x, z)`.
fn terrain_of(n: u32, spacing_m: f32, height_m: impl Fn(f32, f32) -> f32) -> Terrain {
    let half = 0.5 * (n - 1) as f32 * spacing_m;
    let mut h = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            h.push(height_m(
                i as f32 * spacing_m - half,
                j as f32 * spacing_m - half,
            ));
        }
    }
    Terrain::new(UVec2::splat(n), spacing_m, Vec2::ZERO, h).expect("a valid terrain")
}

/// The house's setup, on the valley or not, in clear calm air, looking north from
/// 2 m up.
fn setup(on_terrain: bool) -> Setup {
    setup_on(on_terrain.then(valley))
}

/// The house's setup on `terrain` if any, in clear calm air, looking north from
/// 2 m up.
fn setup_on(terrain: Option<Terrain>) -> Setup {
    scene_on(house_on_plane(), terrain)
}

/// `scene`'s setup on `terrain` if any, in clear calm air, looking north from 2 m
/// up.
fn scene_on(scene: precip_model::Scene, terrain: Option<Terrain>) -> Setup {
    let (mut setup, _) = Setup::over_scene(scene, 64, 6.0, 2_000).expect("valid");
    if let Some(terrain) = terrain {
        let scene = setup.scene.take().expect("a scene");
        let scene = Arc::unwrap_or_clone(scene).on_terrain(Arc::new(terrain));
        setup.ground = GroundMap::of_prepared(&scene, setup.ground.frame);
        setup.scene = Some(Arc::new(scene));
    }
    setup.weather = Weather {
        intensity_mm_per_h: 0.0,
        ..Weather::default()
    };
    setup.camera = Camera {
        position_m: Vec3::new(0.0, 2.0, 30.0),
        forward: Vec3::NEG_Z,
        far_m: 6000.0,
        ..Camera::default()
    };
    setup
}

const WIDTH: u32 = 320;
const HEIGHT: u32 = 240;

fn render(subject: &mut precip_conformance::Subject, setup: &Setup) -> Image {
    let backend = &mut subject.backend;
    backend.configure(setup).expect("configures");
    backend.step(0.05).expect("steps");
    frame(subject, setup)
}

/// The frame of `setup`'s camera now.
fn frame(subject: &mut precip_conformance::Subject, setup: &Setup) -> Image {
    let backend = &mut subject.backend;
    backend
        .render(&View {
            camera: setup.camera,
            width_px: WIDTH,
            height_px: HEIGHT,
        })
        .expect("renders");
    backend.read_image().expect("an image")
}

/// The share of the pixels of rows `rows` (top = 0), but the middle two fifths
/// where the house stands, that differ by more than 6/255 in a channel between `a`
/// and `b`.
fn differing(a: &Image, b: &Image, rows: std::ops::Range<u32>) -> f32 {
    let mut n = 0;
    let mut total = 0;
    for y in rows {
        for x in (0..WIDTH).filter(|x| *x < 3 * WIDTH / 10 || *x >= 7 * WIDTH / 10) {
            let i = 4 * (y * WIDTH + x) as usize;
            total += 1;
            if (0..3).any(|c| a.rgba8[i + c].abs_diff(b.rgba8[i + c]) > 6) {
                n += 1;
            }
        }
    }
    n as f32 / total as f32
}

/// Every GPU backend draws the same picture (within 1/255 but a few pixels).
fn assert_backends_agree(images: &[(String, Image)]) {
    if let Some(((first_name, first), rest)) = images.split_first() {
        for (name, image) in rest {
            let off = first
                .rgba8
                .iter()
                .zip(&image.rgba8)
                .filter(|(a, b)| a.abs_diff(**b) > 1)
                .count();
            assert!(
                (off as f32) < 0.001 * first.rgba8.len() as f32,
                "{name} against {first_name}: {off} values differ"
            );
        }
    }
}

/// The image row at `elevation_deg` above the camera's level (its forward is
/// level).
fn row_at(camera: &Camera, elevation_deg: f32) -> u32 {
    let half = 0.5 * camera.vertical_fov_rad;
    let t = elevation_deg.to_radians().tan() / half.tan();
    ((0.5 - 0.5 * t) * HEIGHT as f32).round() as u32
}

#[test]
fn the_terrain_s_ridge_stands_where_its_heights_put_it_on_every_gpu_backend() {
    let bare = setup(false);
    let on = setup(true);
    let camera = on.camera;
    // The ridge's top: 200 m up, 1 030 m away, seen from 2 m up.
    let top_deg = (198.0f32 / 1030.0).atan().to_degrees();
    let mut images = Vec::new();
    for mut subject in gpu_subjects("the_terrain_s_ridge_stands_where_its_heights_put_it") {
        if !subject.renders() {
            continue;
        }
        let without = render(&mut subject, &bare);
        let with = render(&mut subject, &on);
        subject.check_clean("drawing a terrain");
        // Between the horizon and the ridge's top the terrain hides the sky; well
        // above the top the sky is as it was.
        let ridge = differing(
            &with,
            &without,
            row_at(&camera, top_deg - 2.0)..row_at(&camera, 1.5),
        );
        let sky = differing(&with, &without, 0..row_at(&camera, top_deg + 3.0));
        println!(
            "{}: the ridge's rows differ in {:.1} %, the sky above in {:.1} %",
            subject.name,
            100.0 * ridge,
            100.0 * sky
        );
        assert!(
            ridge > 0.95,
            "{}: the ridge is not drawn ({ridge})",
            subject.name
        );
        assert!(
            sky < 0.02,
            "{}: terrain above its heights ({sky})",
            subject.name
        );
        images.push((subject.name.clone(), with));
    }
    assert_backends_agree(&images);
}

/// The share of all the pixels that differ by more than 6/255 in a channel.
fn differing_anywhere(a: &Image, b: &Image) -> f32 {
    let off = a
        .rgba8
        .chunks(4)
        .zip(b.rgba8.chunks(4))
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 6))
        .count();
    off as f32 / (a.rgba8.len() / 4) as f32
}

/// The GPU holds only a window of each level round the camera, written again as
/// the camera moves (and one per frame in flight on vk): a camera flown 200 m a
/// frame over the valley, past a level-0 window (64 samples, 320 m) each frame,
/// draws at every stop the picture a camera placed there first draws. Windows
/// left where they were would draw the terrain from the samples of an earlier
/// stop.
#[test]
fn a_camera_flying_over_the_terrain_draws_it_from_the_samples_under_it_on_every_gpu_backend() {
    let on = setup(true);
    let at = |i: u32| Camera {
        position_m: Vec3::new(35.0, 150.0, 800.0 - 200.0 * i as f32),
        forward: Vec3::new(0.2, -0.35, -1.0),
        ..on.camera
    };
    let stops = [3, 6];
    for mut subject in
        gpu_subjects("a_camera_flying_over_the_terrain_draws_it_from_the_samples_under_it")
    {
        if !subject.renders() {
            continue;
        }
        let mut flown = Vec::new();
        subject.backend.configure(&on).expect("configures");
        subject.backend.step(0.05).expect("steps");
        for i in 0..=stops[stops.len() - 1] {
            let camera = at(i);
            subject.backend.set_camera(&camera).expect("a camera");
            let mut setup = on.clone();
            setup.camera = camera;
            let image = frame(&mut subject, &setup);
            if stops.contains(&i) {
                flown.push(image);
            }
        }
        subject.check_clean("flying over a terrain");
        for (&i, flown) in stops.iter().zip(&flown) {
            let mut placed = on.clone();
            placed.camera = at(i);
            let first = render(&mut subject, &placed);
            let off = differing_anywhere(flown, &first);
            println!(
                "{}: stop {i}, {:.2} % of the pixels differ from a camera placed there",
                subject.name,
                100.0 * off
            );
            assert!(
                off < 0.01,
                "{}: at stop {i} the flown camera's frame differs from the placed one's in {:.1} % of its pixels",
                subject.name,
                100.0 * off
            );
        }
    }
}

/// The mean of the three channels over rows `rows` and columns `columns`.
fn mean_level(image: &Image, rows: std::ops::Range<u32>, columns: std::ops::Range<u32>) -> f32 {
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in rows {
        for x in columns.clone() {
            let i = 4 * (y * WIDTH + x) as usize;
            sum += (0..3).map(|c| f32::from(image.rgba8[i + c])).sum::<f32>() / 3.0;
            n += 1.0;
        }
    }
    sum / n
}

#[test]
fn the_land_cover_colours_the_terrain_by_class_on_every_gpu_backend() {
    // West of the house forest, east of it glacier ice (WorldCover 10 and 70).
    let cover = LandCover::from_worldcover(UVec2::new(2, 1), &[10, 70]).expect("valid codes");
    let plain = setup(true);
    let covered = setup_on(Some(valley().with_land_cover(cover)));
    let camera = plain.camera;
    let top_deg = (198.0f32 / 1030.0).atan().to_degrees();
    let rows = row_at(&camera, top_deg - 2.0)..row_at(&camera, 1.5);
    let (west, east) = (0..3 * WIDTH / 10, 7 * WIDTH / 10..WIDTH);
    let mut images = Vec::new();
    for mut subject in gpu_subjects("the_land_cover_colours_the_terrain_by_class") {
        if !subject.renders() {
            continue;
        }
        let without = render(&mut subject, &plain);
        let with = render(&mut subject, &covered);
        subject.check_clean("drawing a terrain's land cover");
        let level =
            |image: &Image, columns: std::ops::Range<u32>| mean_level(image, rows.clone(), columns);
        let (forest, grass_w) = (level(&with, west.clone()), level(&without, west.clone()));
        let (ice, grass_e) = (level(&with, east.clone()), level(&without, east.clone()));
        println!(
            "{}: the ridge west {grass_w:.1} → forest {forest:.1}, east {grass_e:.1} → ice {ice:.1}",
            subject.name
        );
        // Through 1 km of clear air the forest is darker than the grass, the ice
        // brighter.
        assert!(
            forest < grass_w - 3.0,
            "{}: forest {forest} against grass {grass_w}",
            subject.name
        );
        assert!(
            ice > grass_e + 10.0,
            "{}: ice {ice} against grass {grass_e}",
            subject.name
        );
        images.push((subject.name.clone(), with));
    }
    assert_backends_agree(&images);
}

#[test]
fn the_pond_mirrors_the_terrain_s_ridge_on_every_gpu_backend() {
    use precip_model::scene::builtin::house_with_pond;
    let bare = scene_on(house_with_pond(), None);
    let on = scene_on(house_with_pond(), Some(valley()));
    // The pond (z 4–14 m, x ±8 m) from 2 m up at z = 30: 4.4° to 7.1° below the
    // horizon; its mirror looks as far above it, at the ridge (0°–11° up), but for
    // the house's reflection in its middle (so its sides are read).
    let camera = on.camera;
    let rows = row_at(&camera, -4.8)..row_at(&camera, -6.8);
    let mut images = Vec::new();
    for mut subject in gpu_subjects("the_pond_mirrors_the_terrain_s_ridge") {
        if !subject.renders() {
            continue;
        }
        let without = render(&mut subject, &bare);
        let with = render(&mut subject, &on);
        subject.check_clean("mirroring a terrain");
        let mut n = 0;
        let mut total = 0;
        for y in rows.clone() {
            for x in (7 * WIDTH / 32..12 * WIDTH / 32).chain(20 * WIDTH / 32..25 * WIDTH / 32) {
                let i = 4 * (y * WIDTH + x) as usize;
                total += 1;
                if (0..3).any(|c| with.rgba8[i + c].abs_diff(without.rgba8[i + c]) > 6) {
                    n += 1;
                }
            }
        }
        let share = n as f32 / total as f32;
        println!(
            "{}: the pond's pixels differ in {:.1} % with the ridge behind",
            subject.name,
            100.0 * share
        );
        assert!(
            share > 0.5,
            "{}: the pond does not mirror the terrain ({share})",
            subject.name
        );
        images.push((subject.name.clone(), with));
    }
    assert_backends_agree(&images);
}

#[test]
fn snow_lands_on_the_terrain_where_it_rises_above_the_meshes() {
    let setup = setup(true);
    let ground = &setup.ground;
    let terrain = valley();
    // The house's plane is the top-most over its square, the terrain beyond it.
    let inside = ground
        .frame
        .texel_index(Vec2::new(0.0, 15.0))
        .expect("on the grid");
    assert!(ground.height_m[inside].abs() < 1e-3);
    let corner = ground.frame.texel_centre(0);
    let t = terrain.height_at(corner).expect("on the terrain");
    assert!(
        ground.height_m[0] >= t - 1e-4,
        "{} under the terrain's {t}",
        ground.height_m[0]
    );
}

/// The house's flat at −0.5 m out to 300 m north (z = −300 m), a plateau 600 m up
/// from 700 m north on, a slope between (4 km square). Along z, so a fragment
/// that looked its cover up by its height instead of its z would read the flat's
/// cells on the plateau.
fn plateau() -> Terrain {
    terrain_of(401, 10.0, |_, z| {
        -0.5 + 600.0 * ((-z - 300.0) / 400.0).clamp(0.0, 1.0)
    })
}

/// Four days (a day a simulated second) of 2 mm/h falling at `air_c` at the site,
/// then clear air for the frame; the frame.
fn after_four_days(
    subject: &mut precip_conformance::Subject,
    setup: &Setup,
    kind: precip_model::PrecipitationKind,
    air_c: f32,
) -> Image {
    let backend = &mut subject.backend;
    backend.configure(setup).expect("configures");
    let falling = Weather {
        kind,
        intensity_mm_per_h: 2.0,
        air_temperature_c: air_c,
        ..setup.weather
    };
    backend.set_weather(&falling).expect("a valid weather");
    for _ in 0..40 {
        backend.step(0.1).expect("steps");
    }
    backend
        .set_weather(&Weather {
            intensity_mm_per_h: 0.0,
            ..falling
        })
        .expect("a valid weather");
    for _ in 0..4 {
        backend.step(0.01).expect("steps");
    }
    frame(subject, setup)
}

#[test]
fn the_cover_beyond_the_grid_is_kept_per_place_with_the_air_at_its_height_on_every_gpu_backend() {
    use precip_model::PrecipitationKind;
    let mut setup = setup_on(Some(plateau()));
    setup.cover.time_scale = 86_400.0;
    // Looking down from 1.9 km above the plateau's edge, east up: the plateau in
    // the image's north (left) quarter, the flat in its south quarter.
    setup.camera.position_m = Vec3::new(0.0, 2500.0, -500.0);
    setup.camera.forward = Vec3::NEG_Y;
    setup.camera.up = Vec3::X;
    let rows = HEIGHT / 4..3 * HEIGHT / 4;
    let (flat, high) = (3 * WIDTH / 4..WIDTH, 0..WIDTH / 4);
    let mut images = Vec::new();
    for mut subject in gpu_subjects("the_cover_beyond_the_grid_is_kept_per_place") {
        if !subject.renders() {
            continue;
        }
        // Rain at +0.2 °C at the site is three tenths snow on the plateau
        // (−3.7 °C), which lies there; at +12 °C it is rain there too.
        let cold = after_four_days(&mut subject, &setup, PrecipitationKind::Rain, 0.2);
        let books = subject
            .backend
            .far_cover_totals()
            .expect("a terrain's far cover");
        let warm = after_four_days(&mut subject, &setup, PrecipitationKind::Rain, 12.0);
        subject.check_clean("drawing the far cover per place");
        let level =
            |image: &Image, columns: std::ops::Range<u32>| mean_level(image, rows.clone(), columns);
        let (snowy, bare) = (level(&cold, high.clone()), level(&warm, high.clone()));
        let (cold_flat, warm_flat) = (level(&cold, flat.clone()), level(&warm, flat.clone()));
        println!(
            "{}: the plateau {bare:.1} after warm rain, {snowy:.1} after cold rain; the flat {warm_flat:.1} and {cold_flat:.1}; beyond the grid {:.0} kg landed, {:.0} kg snow, imbalance {:.2e} kg",
            subject.name,
            books.deposited_kg,
            books.swe_kg,
            books.imbalance_kg()
        );
        assert!(
            snowy > bare + 20.0,
            "{}: the plateau's snow does not show ({snowy} against {bare})",
            subject.name
        );
        assert!(
            (cold_flat - warm_flat).abs() < 0.25 * (snowy - bare),
            "{}: the flat below changed as the plateau did ({cold_flat} against {warm_flat})",
            subject.name
        );
        // The flat's cells took the rain as rain: the snow beyond the grid is the
        // plateau's and the slope's, a part of what landed, and the books close.
        assert!(books.swe_kg > 0.05 * books.deposited_kg, "{books:?}");
        assert!(books.swe_kg < 0.3 * books.deposited_kg, "{books:?}");
        assert!(
            books.imbalance_kg().abs() < 1e-4 * books.deposited_kg,
            "{books:?}"
        );
        images.push((subject.name.clone(), cold));
    }
    assert_backends_agree(&images);
}
