//! Rendering: sprites where particles are, culling that changes nothing visible, snow
//! on the roof only, rain streaks along the velocity, fog by distance, surfaces of
//! another format, and bad input.

use glam::{Vec2, Vec3};
use precip_gpu_wgpu::WgpuBackend;
use precip_model::scene::builtin::{HousePlan, house_on_plane};
use precip_model::wind::WindField;
use precip_model::{
    Backend, BackendError, Camera, CameraVolume, CameraVolumeSetup, Material, Mesh,
    PrecipitationKind, Scene, SceneError, Setup, View, WorldEmitter,
};

use crate::common;
use crate::images::{keep, linear, luma, max_difference, mean_luma, pixel_of, project};

/// A dark sky so every particle shows.
/// A dark sky, on below the horizon (no land beyond the scene): the particles
/// stand out against it alone.
fn dark_sky(setup: &mut Setup) {
    setup.render.sky_colour = Vec3::new(0.02, 0.02, 0.03);
    setup.render.sizing.min_opacity = 0.6;
    setup.render.land_beyond = false;
}

fn view(camera: Camera, width_px: u32, height_px: u32) -> View {
    View {
        camera,
        width_px,
        height_px,
    }
}

/// A column of snow 3 m across over flat ground, seen from the side.
fn snow_column() -> (Setup, View) {
    let mut setup = Setup::over_flat_ground(40.0, 32, 12.0, 3_000);
    setup.world_emitter = setup.world_emitter.map(|mut e| {
        e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 12.0, 0.0), 3.0, 3.0, 12.0);
        e
    });
    dark_sky(&mut setup);
    let camera = Camera {
        position_m: Vec3::new(0.0, 6.0, 14.0),
        forward: Vec3::NEG_Z,
        ..Camera::default()
    };
    setup.camera = camera;
    (setup, view(camera, 96, 64))
}

#[test]
fn sprites_are_bright_where_particles_project_and_the_empty_sky_is_untouched() {
    let (setup, view) = snow_column();
    for (name, mut gpu) in common::gpu_backends("sprites_appear_where_particles_project") {
        common::run(&mut gpu, &setup, 4, 0.05);
        gpu.render(&view).expect("renders");
        let image = gpu.read_image().expect("an image");
        keep(&image, "snow_column");
        assert_eq!((image.width_px, image.height_px), (96, 64));
        let particles = gpu.read_particles().expect("particles");
        // The same frame with no snow in the air: the sky (brighter toward the
        // zenith) and the ground alone.
        let mut dry = setup.clone();
        dry.weather.intensity_mm_per_h = 0.0;
        common::run(&mut gpu, &dry, 1, 0.05);
        gpu.render(&view).expect("renders");
        let clear = gpu.read_image().expect("an image");
        let sky = |x, y| luma(&clear, x, y);
        let mut seen = 0;
        let mut projected = 0;
        let mut columns = [false; 96];
        for p in &particles {
            let Some(s) = project(&view, p.position_m) else {
                continue;
            };
            for dx in -3..=3 {
                let x = s.x as i32 + dx;
                if (0..96).contains(&x) {
                    columns[x as usize] = true;
                }
            }
            if s.x < 1.0 || s.y < 1.0 || s.x > 94.0 || s.y > 62.0 {
                continue;
            }
            projected += 1;
            let (x, y) = (s.x as u32, s.y as u32);
            let brightest = (x - 1..=x + 1)
                .flat_map(|x| (y - 1..=y + 1).map(move |y| (x, y)))
                .map(|(x, y)| luma(&image, x, y) - sky(x, y))
                .fold(f32::MIN, f32::max);
            if brightest > 10.0 {
                seen += 1;
            }
        }
        assert!(
            projected > 500,
            "{name}: only {projected} particles in view"
        );
        assert!(
            seen as f32 >= 0.95 * projected as f32,
            "{name}: {seen} of {projected} particles show a bright sprite"
        );
        // Columns no particle projects near stay exactly the clear frame.
        let mut empty = 0;
        for x in (0..96).filter(|&x| !columns[x as usize]) {
            empty += 1;
            for y in 0..64 {
                assert!(
                    (luma(&image, x, y) - sky(x, y)).abs() <= 1.0,
                    "{name}: pixel ({x}, {y}) lit with no particle near"
                );
            }
        }
        assert!(
            empty > 40,
            "{name}: the column should leave most of the sky empty"
        );
    }
}

#[test]
fn culling_on_and_off_give_the_same_image_and_culling_draws_fewer() {
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, 8_000).expect("valid");
    // Look at one corner of the house: most particles are outside the view.
    let camera = Camera {
        position_m: Vec3::new(8.0, 3.0, 9.0),
        forward: Vec3::new(-0.6, -0.1, -1.0),
        ..Camera::default()
    };
    setup.camera = camera;
    let view = view(camera, 80, 60);
    for (name, mut gpu) in common::gpu_backends("culling_on_and_off_give_the_same_image") {
        let mut images = Vec::new();
        let mut drawn = Vec::new();
        for culling in [true, false] {
            setup.render.view_cone_culling = culling;
            common::run(&mut gpu, &setup, 3, 0.05);
            gpu.render(&view).expect("renders");
            images.push(gpu.read_image().expect("an image"));
            drawn.push(gpu.drawn().expect("counts").expect("a drawing backend"));
        }
        keep(&images[0], "culling_on");
        let difference = max_difference(&images[0], &images[1]);
        assert!(difference <= 1, "{name}: images differ by {difference}/255");
        assert_eq!(drawn[1].total(), 8_000, "{name}: off draws every particle");
        assert!(
            drawn[0].total() < 4_000,
            "{name}: culling kept {:?} of 8000",
            drawn[0]
        );
        assert!(drawn[0].total() > 0, "{name}: some particles are in view");
    }
}

#[test]
fn snow_quads_kept_or_made_by_each_corner_draw_the_same_image() {
    // Heavy snow in a wind around a camera by the house: camera-volume flakes drawn
    // as several copies, sprites near and streaks, world flakes beyond, some
    // splatted; at the frame's resolution and at half of it.
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, 4_000).expect("valid");
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume::default(),
        particle_count: 4_000,
    });
    setup.weather.kind = PrecipitationKind::WetSnow;
    setup.weather.air_temperature_c = -2.0;
    setup.weather.intensity_mm_per_h = 12.0;
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(7.0, 0.0, -2.0),
        ..WindField::calm()
    };
    dark_sky(&mut setup);
    // Flakes large enough to be sprites, not splats, in a small image; the wind
    // sweeps the nearer ones into streaks.
    setup.render.sizing.snow_scale = 40.0;
    let camera = Camera {
        position_m: Vec3::new(4.0, 2.0, 10.0),
        forward: Vec3::new(-0.3, -0.1, -1.0),
        ..Camera::default()
    };
    setup.camera = camera;
    let view = view(camera, 320, 192);
    for (name, mut gpu) in common::gpu_backends("snow_quads_kept_or_made_by_each_corner") {
        for resolution in [
            precip_model::ParticleResolution::Full,
            precip_model::ParticleResolution::Half,
        ] {
            setup.render.particle_resolution = resolution;
            let mut images = Vec::new();
            let mut drawn = Vec::new();
            for quads in [true, false] {
                setup.render.snow_quads = quads;
                common::run(&mut gpu, &setup, 3, 0.05);
                gpu.render(&view).expect("renders");
                images.push(gpu.read_image().expect("an image"));
                drawn.push(gpu.drawn().expect("counts").expect("a drawing backend"));
            }
            eprintln!("{name} {resolution:?}: drawn {:?}", drawn[0]);
            keep(&images[0], "snow_quads");
            keep(&images[1], "snow_quads_off");
            let difference = max_difference(&images[0], &images[1]);
            assert!(
                difference <= 1,
                "{name} {resolution:?}: images differ by {difference}/255"
            );
            assert_eq!(drawn[0], drawn[1], "{name}");
            assert!(
                drawn[0].sprites > 30,
                "{name}: sprites drawn {:?}",
                drawn[0]
            );
        }
    }
}

/// The house under a day of snow per simulated second, fed by the weather's rate.
fn snowed_house() -> (Setup, HousePlan) {
    let plan = HousePlan::default();
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 128, 6.0, 1).expect("valid");
    setup.world_emitter = None;
    setup.camera_volume = Some(CameraVolumeSetup {
        volume: CameraVolume::default(),
        particle_count: 1_000,
    });
    setup.weather.intensity_mm_per_h = 5.0;
    setup.weather.air_temperature_c = -6.0;
    setup.cover.time_scale = 86_400.0;
    (setup, plan)
}

#[test]
fn after_snowing_the_roof_is_white_and_the_walls_and_the_ground_under_the_eaves_are_not() {
    let (setup, plan) = snowed_house();
    // From the south-east, a little above the eaves.
    let camera = Camera {
        position_m: Vec3::new(6.0, 9.0, 14.0),
        forward: Vec3::new(-6.0, -8.0, -11.0),
        ..Camera::default()
    };
    let view = view(camera, 240, 180);
    let z_wall = plan.depth_m / 2.0;
    let points = [
        (
            "roof",
            Vec3::new(0.0, plan.wall_height_m + 0.6, z_wall * 0.5),
        ),
        ("wall", Vec3::new(-1.0, 1.2, z_wall)),
        ("open ground", Vec3::new(-2.0, 0.0, z_wall + 5.0)),
        // Under the eaves of the south side, just outside the wall.
        ("sheltered ground", Vec3::new(-1.0, 0.0, z_wall + 0.35)),
    ];
    for (name, mut gpu) in common::gpu_backends("after_snowing_the_roof_is_white") {
        let mut lumas = Vec::new();
        for steps in [0, 4] {
            common::run(&mut gpu, &setup, steps, 0.05);
            gpu.render(&view).expect("renders");
            let image = gpu.read_image().expect("an image");
            keep(&image, &format!("house_after_{steps}_steps"));
            lumas.push(
                points
                    .iter()
                    .map(|(what, p)| {
                        let px = pixel_of(&view, *p).unwrap_or_else(|| panic!("{what} in view"));
                        (*what, mean_luma(&image, px, 1))
                    })
                    .collect::<Vec<_>>(),
            );
        }
        let cover = gpu.read_cover().expect("cover");
        let depth = |p: Vec3| {
            let i = cover
                .frame
                .texel_index(Vec2::new(p.x, p.z))
                .expect("on the grid");
            cover.texels[i].depth_mm
        };
        assert!(
            depth(points[0].1) > 100.0,
            "{name}: the roof holds {} mm",
            depth(points[0].1)
        );
        let (before, after) = (&lumas[0], &lumas[1]);
        let at = |set: &Vec<(&str, f32)>, what: &str| {
            set.iter()
                .find(|(w, _)| *w == what)
                .map(|(_, l)| *l)
                .expect(what)
        };
        let summary = format!("{name}: before {before:?}, after {after:?}");
        assert!(at(after, "roof") > 200.0, "roof not white: {summary}");
        assert!(
            at(after, "open ground") > 180.0,
            "open ground not white: {summary}"
        );
        for bare in ["wall", "sheltered ground"] {
            assert!(
                (at(after, bare) - at(before, bare)).abs() < 10.0 && at(after, bare) < 200.0,
                "{bare} changed under snow: {summary}"
            );
        }
    }
}

/// Direction of streaks in `image` (degrees, 0 = image x axis, y down, mod 180) from
/// the structure tensor of its gradients (the uniform sky adds nothing).
fn streak_angle_deg(image: &precip_model::Image) -> f32 {
    let (mut jxx, mut jyy, mut jxy) = (0.0f64, 0.0f64, 0.0f64);
    for y in 1..image.height_px - 1 {
        for x in 1..image.width_px - 1 {
            let gx = f64::from(luma(image, x + 1, y) - luma(image, x - 1, y));
            let gy = f64::from(luma(image, x, y + 1) - luma(image, x, y - 1));
            jxx += gx * gx;
            jyy += gy * gy;
            jxy += gx * gy;
        }
    }
    // The gradients' dominant direction is across the streaks.
    let across = 0.5 * (2.0 * jxy).atan2(jxx - jyy);
    ((across.to_degrees() + 90.0) as f32).rem_euclid(180.0)
}

#[test]
fn rain_frames_show_streaks_along_the_velocity() {
    let camera = Camera {
        position_m: Vec3::new(0.0, 20.0, 0.0),
        forward: Vec3::NEG_Z,
        // A short exposure: streaks of 20 cm, each drop's ink on fewer pixels.
        lens: precip_model::Lens {
            exposure_s: 0.02,
            ..precip_model::Lens::default()
        },
        ..Camera::default()
    };
    let view = view(camera, 256, 192);
    for (name, mut gpu) in common::gpu_backends("rain_frames_show_streaks_along_the_velocity") {
        // At a reduced resolution the drops are splatted along their streaks at the
        // frame's (precip_model::ParticleResolution): the same directions.
        for resolution in [
            precip_model::ParticleResolution::Full,
            precip_model::ParticleResolution::Half,
            precip_model::ParticleResolution::Quarter,
        ] {
            let mut angles = Vec::new();
            for wind_x in [0.0, 9.0] {
                let mut setup = Setup::over_flat_ground(60.0, 16, 40.0, 1);
                setup.world_emitter = None;
                setup.camera_volume = Some(CameraVolumeSetup {
                    volume: CameraVolume {
                        half_extent_m: Vec3::splat(6.0),
                        ..CameraVolume::default()
                    },
                    particle_count: 3_000,
                });
                setup.camera = camera;
                setup.weather.kind = PrecipitationKind::Rain;
                setup.weather.air_temperature_c = 10.0;
                setup.weather.intensity_mm_per_h = 10.0;
                setup.weather.wind = WindField {
                    mean_wind_mps: Vec3::new(wind_x, 0.0, 0.0),
                    ..WindField::calm()
                };
                dark_sky(&mut setup);
                setup.render.particle_resolution = resolution;
                // Let the drops reach the wind's speed.
                common::run(&mut gpu, &setup, 30, 0.1);
                gpu.render(&view).expect("renders");
                let image = gpu.read_image().expect("an image");
                keep(&image, &format!("rain_wind_{wind_x}_{resolution:?}"));
                let particles = gpu.read_particles().expect("particles");
                // Weighted by each drop's ink, its projected area: big drops (falling
                // fastest, so steepest in the wind) show most.
                let (sum, weight) = particles.iter().fold((Vec3::ZERO, 0.0), |(a, w), p| {
                    let ink = p.diameter_m * p.diameter_m;
                    (a + p.velocity_mps * ink, w + ink)
                });
                let mean_velocity = sum / weight;
                // The velocity's direction on screen at the image centre.
                let ahead = camera.position_m + camera.forward * 5.0;
                let a = project(&view, ahead).expect("in front");
                let b = project(&view, ahead + mean_velocity * 0.1).expect("in front");
                let d = b - a;
                let expected = d.y.atan2(d.x).to_degrees().rem_euclid(180.0);
                let got = streak_angle_deg(&image);
                let error = (got - expected).abs();
                let error = error.min(180.0 - error);
                assert!(
                    error < 12.0,
                    "{name}, {resolution:?}: wind {wind_x} m/s: streaks at {got:.1}°, velocity at {expected:.1}° on screen"
                );
                angles.push(got);
            }
            let apart = (angles[0] - angles[1]).abs();
            assert!(
                apart.min(180.0 - apart) > 20.0,
                "{name}, {resolution:?}: wind should tilt the streaks: {angles:?}"
            );
        }
    }
}

#[test]
fn the_flakes_the_budget_leaves_undrawn_grain_the_view_as_the_model_says() {
    use precip_model::drawing::unresolved_streaks::UnresolvedStreaks;
    // A blizzard with one simulated particle (far behind the camera): the air's
    // flakes are all unresolved. A black wall 12 m off shows the haze's colour
    // times (1 − T) and, over it, the grain of the flakes between: each pixel moved
    // toward the haze by σ(z)·g, g new each exposure (docs/model.md (5.15b)). Two
    // frames three exposures apart: their difference's variance over the wall is
    // 2·σ²·(sky·T)².
    let camera = Camera {
        position_m: Vec3::new(-4.0, 3.0, 0.0),
        forward: Vec3::NEG_Z,
        vertical_fov_rad: 30f32.to_radians(),
        ..Camera::default()
    };
    let view = view(camera, 128, 96);
    let (mut setup, _) = Setup::over_scene(black_walls(&[12.0]), 32, 5.0, 1).expect("valid");
    setup.world_emitter = setup.world_emitter.map(|mut e| {
        e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 10.0, 500.0), 1.0, 1.0, 10.0);
        e
    });
    setup.weather.intensity_mm_per_h = 6.0;
    setup.weather.wind = WindField {
        mean_wind_mps: Vec3::new(14.0, 0.0, 0.0),
        ..WindField::calm()
    };
    setup.camera = camera;
    // The grain the frame's block carries.
    let pools = setup.pool_drawing(&setup.weather, camera.position_m);
    let params = setup.render_params(
        &view,
        &setup.weather,
        (Vec3::splat(-1.0), Vec3::ONE),
        0.05,
        1,
        setup.frames().waves,
        pools,
    );
    let g = params.unresolved_streaks;
    assert!(g.x > 0.0, "a blizzard's unresolved flakes grain the view");
    let grain = UnresolvedStreaks {
        scale: g.x,
        reach_m: g.y,
        near_m: g.z,
        length_px: g.w,
        velocity_mps: Vec3::ZERO,
    };
    let sky = precip_model::drawing::render::haze_colour(&setup.render, &setup.weather).x;
    let extinction = setup.render.clear_air_extinction_per_m + setup.weather.extinction_per_m();
    for (name, mut gpu) in common::gpu_backends("the_flakes_the_budget_leaves_undrawn") {
        common::run(&mut gpu, &setup, 1, 0.05);
        gpu.set_camera(&camera).expect("valid camera");
        gpu.render(&view).expect("renders");
        let first = gpu.read_image().expect("an image");
        gpu.step(0.05).expect("steps");
        gpu.render(&view).expect("renders");
        let second = gpu.read_image().expect("an image");
        keep(&first, "unresolved_grain");
        let (mut sum, mut sum2, mut expected, mut n) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for y in 0..96u32 {
            for x in 0..128u32 {
                // The wall's pixels: its plane z = −12 within its 6 × 6 m.
                let ndc = Vec2::new((x as f32 + 0.5) / 64.0 - 1.0, 1.0 - (y as f32 + 0.5) / 48.0);
                let half_h = (15f32.to_radians()).tan();
                let ray = Vec3::new(ndc.x * half_h * 128.0 / 96.0, ndc.y * half_h, -1.0);
                let hit = camera.position_m + ray * 12.0;
                if (hit.x + 4.0).abs() > 2.8 || hit.y < 0.2 || hit.y > 5.8 {
                    continue;
                }
                let z = (hit - camera.position_m).length();
                let t = precip_model::drawing::fog_transmittance(z, extinction);
                let a = linear(crate::images::rgb(&first, x, y)[0]);
                let b = linear(crate::images::rgb(&second, x, y)[0]);
                let d = f64::from(a - b);
                sum += d;
                sum2 += d * d;
                expected += f64::from(2.0 * grain.variance(z) * (sky * t).powi(2));
                n += 1.0;
            }
        }
        let measured = sum2 / n - (sum / n).powi(2);
        let want = expected / n;
        println!("{name}: {n} wall pixels, difference variance {measured:.3e}, model {want:.3e}");
        assert!(n > 2_000.0, "{name}: the wall fills the view ({n} pixels)");
        assert!(
            (measured / want - 1.0).abs() < 0.15,
            "{name}: the grain's variance {measured:.3e} against the model's {want:.3e}"
        );
    }
}

/// Black walls facing the camera at `distances_m` along −Z, 6 m wide and tall.
fn black_walls(distances_m: &[f32]) -> Scene {
    Scene {
        meshes: distances_m
            .iter()
            .enumerate()
            .map(|(i, &d)| {
                let x = 8.0 * i as f32 - 4.0;
                Mesh {
                    name: format!("wall at {d} m"),
                    positions_m: vec![
                        Vec3::new(x - 3.0, 0.0, -d),
                        Vec3::new(x + 3.0, 0.0, -d),
                        Vec3::new(x + 3.0, 6.0, -d),
                        Vec3::new(x - 3.0, 6.0, -d),
                    ],
                    indices: vec![0, 1, 2, 0, 2, 3],
                    material: Material {
                        base_colour: [0.0, 0.0, 0.0, 1.0],
                        base_colour_texture: None,
                    },
                    ..Mesh::default()
                }
            })
            .collect(),
    }
}

#[test]
fn fog_lowers_contrast_with_distance_and_with_the_precipitation() {
    let distances = [10.0f32, 60.0];
    let camera = Camera {
        position_m: Vec3::new(0.0, 3.0, 0.0),
        forward: Vec3::NEG_Z,
        vertical_fov_rad: 50f32.to_radians(),
        ..Camera::default()
    };
    let view = view(camera, 96, 64);
    for (name, mut gpu) in common::gpu_backends("fog_lowers_contrast_with_distance") {
        let mut contrasts = Vec::new();
        for intensity in [1.0f32, 8.0] {
            let (mut setup, _) =
                Setup::over_scene(black_walls(&distances), 32, 5.0, 1).expect("valid");
            // The one particle falls far behind the camera.
            setup.world_emitter = setup.world_emitter.map(|mut e| {
                e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 10.0, 500.0), 1.0, 1.0, 10.0);
                e
            });
            setup.weather.intensity_mm_per_h = intensity;
            setup.camera = camera;
            common::run(&mut gpu, &setup, 1, 0.05);
            gpu.render(&view).expect("renders");
            let image = gpu.read_image().expect("an image");
            keep(&image, &format!("fog_{intensity}"));
            // The haze's colour, the sky's at the horizon (above it the overcast sky
            // brightens).
            let sky = precip_model::drawing::render::haze_colour(&setup.render, &setup.weather).x;
            let extinction =
                setup.render.clear_air_extinction_per_m + setup.weather.extinction_per_m();
            for (i, &d) in distances.iter().enumerate() {
                let x = 8.0 * i as f32 - 4.0;
                let centre = Vec3::new(x, 3.0, -d);
                let (px, py) = pixel_of(&view, centre).expect("wall in view");
                // The mean over 5 × 5 of the wall's pixels: the grain of the flakes
                // not drawn one by one scatters each about it (docs/model.md (5.15b)).
                let wall = (0..25)
                    .map(|k| linear(crate::images::rgb(&image, px + k % 5 - 2, py + k / 5 - 2)[0]))
                    .sum::<f32>()
                    / 25.0;
                // A black wall shows the sky's colour times (1 − T): contrast is T.
                let contrast = 1.0 - wall / sky;
                let along_ray = (centre - camera.position_m).length();
                let expected = precip_model::drawing::fog_transmittance(along_ray, extinction);
                assert!(
                    (contrast - expected).abs() < 0.03,
                    "{name}: {intensity} mm/h at {d} m: contrast {contrast:.3}, Beer–Lambert {expected:.3}"
                );
                contrasts.push(contrast);
            }
        }
        assert!(
            contrasts[1] < contrasts[0],
            "{name}: far walls fade: {contrasts:?}"
        );
        assert!(
            contrasts[3] < contrasts[1],
            "{name}: heavier snow, thicker fog: {contrasts:?}"
        );
    }
}

#[test]
fn a_fog_layer_dims_below_its_top_and_scatters_the_sun() {
    use precip_model::drawing::fog_layer::{FOG_LAYER_BOTTOM_M, FogLayer, air_path};
    let distances = [25.0f32, 60.0];
    let fog = FogLayer::new(8.0, 50.0);
    let to_sun = Vec3::new(0.0, 0.5, -1.0);
    // In the fog, and above its top looking down into it.
    for (height, pitch) in [(3.0f32, 0.0f32), (14.0, -0.25)] {
        let camera = Camera {
            position_m: Vec3::new(0.0, height, 0.0),
            forward: Vec3::new(0.0, pitch, -1.0),
            vertical_fov_rad: 50f32.to_radians(),
            ..Camera::default()
        };
        let view = view(camera, 96, 64);
        for (name, mut gpu) in common::gpu_backends("a_fog_layer_dims_below_its_top") {
            let (mut setup, _) =
                Setup::over_scene(black_walls(&distances), 32, 5.0, 1).expect("valid");
            setup.world_emitter = setup.world_emitter.map(|mut e| {
                e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 10.0, 500.0), 1.0, 1.0, 10.0);
                e
            });
            setup.weather.intensity_mm_per_h = 0.0;
            setup.render.fog_layer = Some(fog);
            setup.render.to_sun = to_sun;
            setup.camera = camera;
            common::run(&mut gpu, &setup, 1, 0.05);
            gpu.render(&view).expect("renders");
            let image = gpu.read_image().expect("an image");
            keep(&image, &format!("fog_layer_{height}"));
            let sky = precip_model::drawing::render::haze_colour(&setup.render, &setup.weather).x;
            let extinction =
                setup.render.clear_air_extinction_per_m + setup.weather.extinction_per_m();
            for (i, &d) in distances.iter().enumerate() {
                let x = 8.0 * i as f32 - 4.0;
                let centre = Vec3::new(x, 2.0, -d);
                let (px, py) = pixel_of(&view, centre).expect("wall in view");
                let wall = linear(crate::images::rgb(&image, px, py)[0]);
                let offset = centre - camera.position_m;
                let air = air_path(
                    camera.position_m,
                    offset.normalize(),
                    offset.length(),
                    extinction,
                    fog.extinction_per_m(),
                    FOG_LAYER_BOTTOM_M,
                    fog.top_m,
                    to_sun.normalize(),
                );
                // A black wall shows the sky's light scattered in and the sun's.
                let expected =
                    sky * (1.0 - air.transmittance) + setup.render.lighting.diffuse * air.sun;
                assert!(
                    (wall - expected).abs() < 0.03,
                    "{name}: from {height} m, the wall at {d} m: {wall:.3}, the model {expected:.3} ({air:?})"
                );
                assert!(air.sun > 0.01, "the sun's share shows: {air:?}");
            }
        }
    }
}

#[test]
fn seen_from_above_a_cloud_layer_hides_its_coverage_of_the_ground() {
    use precip_model::drawing::clouds::{CloudKind, CloudLayer, CloudLayers};
    // 20 km up looking straight down over 24 km of a cumulus layer (two periods of
    // the coverage map): the share of pixels whose clouds are at least 0.4 opaque
    // (an optical depth of 0.5, as the model's test counts a column clouded) is the
    // layer's coverage. Opacity: the pixel's light over a full cover's there.
    let camera = Camera {
        position_m: Vec3::new(0.0, 20_000.0, 0.0),
        forward: Vec3::new(0.0, -1.0, 0.001),
        vertical_fov_rad: 62f32.to_radians(),
        ..Camera::default()
    };
    let view = view(camera, 96, 96);
    for (name, mut gpu) in common::gpu_backends("seen_from_above_a_cloud_layer") {
        let frame = |gpu: &mut WgpuBackend, layers: &[CloudLayer]| {
            let (mut setup, _) =
                Setup::over_scene(black_walls(&[10.0]), 16, 5.0, 1).expect("valid");
            setup.weather.intensity_mm_per_h = 0.0;
            // No haze, a black sky and no land: only the sun's light on the
            // clouds shows.
            setup.render.clear_air_extinction_per_m = 0.0;
            setup.render.sky_colour = Vec3::ZERO;
            setup.render.land_beyond = false;
            setup.render.cloud_layers = CloudLayers::new(layers).expect("valid layers");
            setup.camera = camera;
            common::run(gpu, &setup, 1, 0.05);
            gpu.render(&view).expect("renders");
            gpu.read_image().expect("an image")
        };
        let cumulus = |coverage| CloudLayer::typical(CloudKind::Cumulus, coverage);
        let full = frame(&mut gpu, &[cumulus(1.0)]);
        // Two layers of 0.3 each read the map apart (docs/model.md (6.15)): their
        // clouds stand independently, clouding 1 − 0.7² = 0.51 of the view (0.3
        // if they stood one above the other).
        let upper = CloudLayer {
            base_m: 3_000.0,
            ..cumulus(0.3)
        };
        for (coverage, layers) in [
            (0.3f32, vec![cumulus(0.3)]),
            (0.7, vec![cumulus(0.7)]),
            (0.51, vec![cumulus(0.3), upper]),
        ] {
            let clouded = frame(&mut gpu, &layers);
            keep(&clouded, &format!("clouds_from_above_{coverage}"));
            let changed = full
                .rgba8
                .chunks(4)
                .zip(clouded.rgba8.chunks(4))
                .filter(|(a, b)| linear(b[1]) > 0.4 * linear(a[1]))
                .count();
            let share = changed as f32 / (view.width_px * view.height_px) as f32;
            assert!(
                (share - coverage).abs() < 0.1,
                "{name}: {share} of the view clouded at a coverage of {coverage}"
            );
        }
    }
}

/// Under a cumulus layer, 17 frames from `camera_at(0)` to `camera_at(16)` on each
/// GPU backend, against the last view marched whole (a backend with no image
/// before): per backend its name, the mean difference (/255), the share of values
/// off by more than 12, and the clouds' passes the 17 frames ran.
fn clouds_reused_against_whole(
    test: &str,
    camera_at: impl Fn(f32) -> Camera,
    size: (u32, u32),
) -> Vec<(String, f32, f32, Vec<&'static str>)> {
    use precip_model::drawing::clouds::{CloudKind, CloudLayer, CloudLayers};
    let (mut setup, _) = Setup::over_scene(black_walls(&[10.0]), 16, 5.0, 1).expect("valid");
    setup.weather.intensity_mm_per_h = 0.0;
    setup.render.cloud_layers = CloudLayers::one(CloudLayer::typical(CloudKind::Cumulus, 0.5));
    let mut out = Vec::new();
    for (name, mut gpu) in common::gpu_backends(test) {
        common::run(&mut gpu, &setup, 1, 0.05);
        let mut ran = Vec::new();
        for k in 0..=16 {
            let view = view(camera_at(k as f32), size.0, size.1);
            gpu.set_camera(&view.camera).expect("valid camera");
            gpu.render(&view).expect("renders");
            let timings = gpu.timings().expect("timings");
            ran.extend(
                timings
                    .passes
                    .iter()
                    .map(|p| p.pass)
                    .filter(|p| p.starts_with("clouds")),
            );
        }
        let reused = gpu.read_image().expect("an image");
        common::run(&mut gpu, &setup, 1, 0.05);
        let view = view(camera_at(16.0), size.0, size.1);
        gpu.set_camera(&view.camera).expect("valid camera");
        gpu.render(&view).expect("renders");
        let whole = gpu.read_image().expect("an image");
        keep(&reused, &format!("{test}_reused"));
        keep(&whole, &format!("{test}_whole"));
        let differences: Vec<i32> = reused
            .rgba8
            .iter()
            .zip(&whole.rgba8)
            .map(|(a, b)| (i32::from(*a) - i32::from(*b)).abs())
            .collect();
        let mean = differences.iter().sum::<i32>() as f32 / differences.len() as f32;
        let far_off =
            differences.iter().filter(|&&d| d > 12).count() as f32 / differences.len() as f32;
        println!("{name}: {test} against whole: mean {mean}/255, {far_off} off by > 12");
        out.push((name, mean, far_off, ran));
    }
    out
}

#[test]
fn from_above_the_land_goes_on_beyond_the_scene() {
    // 300 m over a 40 m patch of flat ground, 1 km off it, looking 10° down: the
    // rays below the horizon meet the land beyond the scene (docs/model.md
    // (6.18)), bare fields seen through the air — darker and greener than the sky
    // above the horizon, and lighter toward the horizon as the air thickens.
    let mut setup = Setup::over_flat_ground(40.0, 32, 12.0, 1_000);
    setup.weather.intensity_mm_per_h = 0.0;
    let camera = Camera {
        position_m: Vec3::new(0.0, 300.0, 1_000.0),
        forward: Vec3::new(0.0, -10f32.to_radians().tan(), -1.0),
        ..Camera::default()
    };
    let view = view(camera, 96, 64);
    for (name, mut gpu) in common::gpu_backends("from_above_the_land_goes_on") {
        common::run(&mut gpu, &setup, 1, 0.05);
        gpu.set_camera(&view.camera).expect("valid camera");
        gpu.render(&view).expect("renders");
        let image = gpu.read_image().expect("an image");
        keep(&image, "far_ground");
        let sky = luma(&image, 10, 2);
        let near_land = crate::images::rgb(&image, 10, 60);
        let far_land = luma(&image, 10, 30);
        println!("{name}: sky {sky}, land far {far_land}, near {near_land:?}");
        assert!(
            luma(&image, 10, 60) < 0.7 * sky,
            "{name}: the land {near_land:?} against the sky {sky}"
        );
        assert!(
            near_land[1] > near_land[0] && near_land[1] > near_land[2],
            "{name}: fields are green: {near_land:?}"
        );
        assert!(
            far_land > luma(&image, 10, 60),
            "{name}: the air thickens toward the horizon"
        );
    }
}

#[test]
fn the_clouds_shadows_lie_on_the_land_where_the_model_puts_them() {
    use precip_model::drawing::clouds::{
        CloudKind, CloudLayer, CloudLayers, cloud_drift_m, cloud_noise,
    };
    // Looking down from 3 km on the land under broken cumulus 5 km up, the sun
    // high: each ground point's brightness follows the share of the sun's light
    // the model gives it through the layer (the clouds' shadow map,
    // docs/model.md (6.12)), not one share for the whole view.
    let mut setup = Setup::over_flat_ground(40.0, 32, 12.0, 1_000);
    setup.weather.intensity_mm_per_h = 0.0;
    setup.render.to_sun = Vec3::new(0.1, 1.0, 0.05);
    let layer = CloudLayer {
        base_m: 5_000.0,
        thickness_m: 1_500.0,
        ..CloudLayer::typical(CloudKind::Cumulus, 0.5)
    };
    setup.render.cloud_layers = CloudLayers::one(layer);
    let camera = Camera {
        position_m: Vec3::new(0.0, 3_000.0, 0.0),
        forward: Vec3::new(0.0, -1.0, -0.02),
        ..Camera::default()
    };
    let view = view(camera, 96, 64);
    for (name, mut gpu) in common::gpu_backends("the_clouds_shadows_lie_on_the_land") {
        common::run(&mut gpu, &setup, 1, 0.05);
        gpu.set_camera(&view.camera).expect("valid camera");
        gpu.render(&view).expect("renders");
        let image = gpu.read_image().expect("an image");
        keep(&image, "cloud_shadows");
        let drift = cloud_drift_m(setup.weather.wind.mean_wind_mps, 0.05);
        let to_sun = setup.render.to_sun.normalize();
        let (mut shares, mut lumas) = (Vec::new(), Vec::new());
        for gz in -12..=12 {
            for gx in -18..=18 {
                let ground = Vec3::new(gx as f32 * 80.0, 0.0, gz as f32 * 80.0);
                let Some(px) = project(&view, ground) else {
                    continue;
                };
                if px.x < 1.0 || px.y < 1.0 || px.x > 94.0 || px.y > 62.0 {
                    continue;
                }
                // The scene's own 40 m patch in the middle aside.
                if ground.x.abs() < 30.0 && ground.z.abs() < 30.0 {
                    continue;
                }
                shares.push(CloudLayers::one(layer).sun_transmittance(
                    cloud_noise(),
                    drift,
                    ground,
                    to_sun,
                ));
                lumas.push(luma(&image, px.x as u32, px.y as u32));
            }
        }
        let n = shares.len() as f32;
        let (ms, ml) = (
            shares.iter().sum::<f32>() / n,
            lumas.iter().sum::<f32>() / n,
        );
        let cov: f32 = shares
            .iter()
            .zip(&lumas)
            .map(|(s, l)| (s - ms) * (l - ml))
            .sum();
        let vs: f32 = shares.iter().map(|s| (s - ms) * (s - ms)).sum();
        let vl: f32 = lumas.iter().map(|l| (l - ml) * (l - ml)).sum();
        let r = cov / (vs * vl).sqrt();
        let shaded = shares.iter().filter(|&&s| s < 0.5).count();
        println!(
            "{name}: {} points, {shaded} shaded, correlation {r}",
            shares.len()
        );
        assert!(
            shaded > 20 && shaded + 20 < shares.len(),
            "{name}: {shaded} of {}",
            shares.len()
        );
        assert!(
            r > 0.8,
            "{name}: the land's brightness follows the shade by {r}"
        );
    }
}

#[test]
fn a_still_camera_s_clouds_lose_the_grain_of_the_march() {
    use precip_model::drawing::clouds::{CloudKind, CloudLayer, CloudLayers};
    // Looking at cumulonimbus bases near the horizon from 30 m, a march's steps
    // span kilometres and neighbouring pixels meet different clouds: grain. A
    // still camera averages each pixel's marches, each at other depths
    // (docs/model.md (6.14)): after five rounds of 16 frames the grain (the mean
    // difference of horizontal neighbours over the clouds) is well down.
    let (mut setup, _) = Setup::over_scene(black_walls(&[10.0]), 16, 5.0, 1).expect("valid");
    setup.weather.intensity_mm_per_h = 0.0;
    setup.render.cloud_layers = CloudLayers::one(CloudLayer::typical(CloudKind::Cumulonimbus, 0.3));
    let camera = Camera {
        position_m: Vec3::new(0.0, 30.0, 0.0),
        forward: Vec3::new(0.0, 0.07, -1.0),
        ..Camera::default()
    };
    let view = view(camera, 192, 108);
    let grain = |image: &precip_model::Image| {
        let w = image.width_px as usize;
        let rows = image.height_px as usize / 3;
        let mut sum = 0.0;
        for y in 0..rows {
            for x in 1..w {
                let at = |x: usize| {
                    let i = 4 * (y * w + x);
                    f32::from(image.rgba8[i])
                        + f32::from(image.rgba8[i + 1])
                        + f32::from(image.rgba8[i + 2])
                };
                sum += (at(x) - at(x - 1)).abs();
            }
        }
        sum / (rows * (w - 1)) as f32
    };
    for (name, mut gpu) in common::gpu_backends("a_still_camera_s_clouds_lose_the_grain") {
        common::run(&mut gpu, &setup, 1, 0.05);
        gpu.set_camera(&view.camera).expect("valid camera");
        gpu.render(&view).expect("renders");
        let first = gpu.read_image().expect("an image");
        for _ in 0..80 {
            gpu.render(&view).expect("renders");
        }
        let settled = gpu.read_image().expect("an image");
        keep(&first, "clouds_grain_first");
        keep(&settled, "clouds_grain_settled");
        let (before, after) = (grain(&first), grain(&settled));
        println!("{name}: grain {before} then {after}");
        // lavapipe: 5.8 then 3.0 (sums of three channels); each march taken
        // alone (no average): 5.8 then 5.8.
        assert!(
            after < 0.6 * before,
            "{name}: the grain went from {before} to {after}"
        );
    }
}

#[test]
fn flying_across_under_clouds_the_history_is_clamped_to_what_the_frame_marched() {
    // Flying 60 m a frame across the view under a cumulus layer at 1.5 km (a fast
    // jet, or a camera cut short of the 100 m that restarts the march): each
    // reused pixel's history mixes in columns its ray no longer crosses; clamped
    // to the pixels the frame marched around it (docs/model.md (6.14)), the last
    // frame stays near one that marched every pixel.
    let camera_at = |k: f32| Camera {
        position_m: Vec3::new(60.0 * k, 2.0, 0.0),
        forward: Vec3::new(0.0, 25f32.to_radians().sin(), -25f32.to_radians().cos()),
        ..Camera::default()
    };
    for (name, mean, far_off, _) in
        clouds_reused_against_whole("clouds_flown", camera_at, (256, 144))
    {
        // lavapipe: mean 2.5/255, 4.5 % off by more than 12 (the fresh pixels are
        // 16 of the frame's apart: what lies between them is softened); the
        // history unclamped: 3.0/255 and 6.8 %, a trail behind each cloud.
        assert!(
            mean < 2.7 && far_off < 0.058,
            "{name}: mean difference {mean}/255, {far_off} of the values off by more than 12"
        );
    }
}

#[test]
fn turning_under_clouds_reuses_the_frame_before_s_clouds_where_it_saw_them() {
    // Turning a degree a frame under a cumulus layer for 17 frames, a frame marches
    // one pixel in each 4 × 4 block of the clouds' image and takes the rest from
    // the frame before's image where its camera saw them (docs/model.md (6.14)):
    // the last frame looks as one that marched every pixel, and the two images
    // take turns.
    let camera_at = |yaw_deg: f32| {
        let (yaw, pitch) = (yaw_deg.to_radians(), 25f32.to_radians());
        Camera {
            position_m: Vec3::new(0.0, 2.0, 0.0),
            forward: Vec3::new(
                yaw.sin() * pitch.cos(),
                pitch.sin(),
                -yaw.cos() * pitch.cos(),
            ),
            ..Camera::default()
        }
    };
    for (name, mean, far_off, ran) in
        clouds_reused_against_whole("clouds_turned", camera_at, (128, 96))
    {
        if !ran.is_empty() {
            assert!(
                ran.contains(&"clouds")
                    && ran.contains(&"clouds_b")
                    && ran.contains(&"clouds_fresh"),
                "{name}: the images take turns: {ran:?}"
            );
        }
        // lavapipe: mean 1.6/255, 1.4 % off by more than 12 (the reused pixels are
        // the frame before's filtered again, the grain of the march's jitter
        // smoothed; a turning camera's history is not clamped); read at this
        // frame's camera instead of the frame before's: 3.0/255, 8.4 %; clamped as
        // if the camera had moved: 2.3/255, 4.7 %.
        assert!(
            mean < 2.2 && far_off < 0.04,
            "{name}: mean difference {mean}/255, {far_off} of the values off by more than 12"
        );
    }
}

#[test]
fn a_surface_format_renders_the_same_frame() {
    let (setup, view) = snow_column();
    for (name, mut gpu) in common::gpu_backends("a_surface_format_renders_the_same_frame") {
        common::run(&mut gpu, &setup, 2, 0.05);
        gpu.render(&view).expect("renders");
        let offscreen = gpu.read_image().expect("an image");
        let texture = gpu
            .device()
            .device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("surface stand-in"),
                size: wgpu::Extent3d {
                    width: view.width_px,
                    height: view.height_px,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Bgra8UnormSrgb,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
        let target = texture.create_view(&wgpu::TextureViewDescriptor::default());
        gpu.render_to(&view, &target)
            .expect("renders into a BGRA target");
        let smaller = View {
            width_px: view.width_px - 1,
            ..view
        };
        assert!(
            matches!(
                gpu.render_to(&smaller, &target),
                Err(BackendError::InvalidView(_))
            ),
            "{name}: a view of another size than the target"
        );
        // The same frame, channels swapped; read_image still returns the offscreen one.
        let mut bgra =
            precip_gpu_wgpu::transfer::read_image(gpu.device(), &texture).expect("read back");
        for px in bgra.rgba8.chunks_exact_mut(4) {
            px.swap(0, 2);
        }
        let difference = max_difference(&bgra, &offscreen);
        assert!(
            difference <= 1,
            "{name}: the BGRA frame differs by {difference}/255"
        );
        assert_eq!(gpu.read_image().expect("an image"), offscreen, "{name}");
    }
}

#[test]
fn bad_views_and_scenes_are_typed_errors() {
    for (name, mut gpu) in common::gpu_backends("bad_views_and_scenes_are_typed_errors") {
        let (setup, good) = snow_column();
        assert!(
            matches!(gpu.render(&good), Err(BackendError::NotConfigured { .. })),
            "{name}: render before configure"
        );
        gpu.configure(&setup).expect("valid");
        assert!(
            matches!(gpu.read_image(), Err(BackendError::NothingRendered)),
            "{name}"
        );
        for (w, h) in [(0, 64), (64, 0), (100_000, 64), (64, u32::MAX)] {
            let bad = View {
                width_px: w,
                height_px: h,
                ..good
            };
            assert!(
                matches!(gpu.render(&bad), Err(BackendError::InvalidView(_))),
                "{name}: {w}×{h}"
            );
        }
        let nan_camera = View {
            camera: Camera {
                forward: Vec3::NAN,
                ..good.camera
            },
            ..good
        };
        assert!(matches!(
            gpu.render(&nan_camera),
            Err(BackendError::InvalidCamera(_))
        ));
        // Still renders after the refusals.
        gpu.render(&good).expect("renders");

        // Scenes: empty, NaN vertex → typed errors at configure; degenerate triangles
        // are dropped and the rest renders.
        // A scene reaches a backend only prepared (the type says so): bad scenes are
        // refused by `prepare` and `over_scene`, before any backend sees them.
        assert!(matches!(Scene::default().prepare(), Err(SceneError::Empty)));
        let mut nan = black_walls(&[10.0]);
        nan.meshes[0].positions_m[2].y = f32::NAN;
        assert!(matches!(
            nan.clone().prepare(),
            Err(SceneError::NonFinite { .. })
        ));
        assert!(matches!(
            Setup::over_scene(nan, 16, 5.0, 10),
            Err(BackendError::Scene(SceneError::NonFinite { .. }))
        ));
        let mut degenerate = black_walls(&[10.0]);
        let m = &mut degenerate.meshes[0];
        m.positions_m.push(Vec3::new(1.0, 1.0, -10.0));
        m.indices.extend_from_slice(&[4, 4, 4, 0, 1, 0]);
        let (setup, report) =
            Setup::over_scene(degenerate, 16, 5.0, 10).expect("degenerate dropped");
        assert_eq!(report.degenerate_triangles, 2, "{name}");
        gpu.configure(&setup).expect("valid");
        gpu.render(&good).expect("renders");
        let image = gpu.read_image().expect("an image");
        assert_eq!(image.rgba8.len(), 4 * 96 * 64);
    }
}

#[test]
fn timings_name_every_pass_of_a_frame() {
    let (setup, view) = snow_column();
    for (name, mut gpu) in common::gpu_backends("timings_name_every_pass_of_a_frame") {
        for reduced in [false, true] {
            let mut setup = setup.clone();
            if reduced {
                setup.render.particle_resolution = precip_model::ParticleResolution::Half;
            }
            common::run(&mut gpu, &setup, 1, 0.05);
            gpu.render(&view).expect("renders");
            let timings = gpu.timings().expect("timings");
            if timings.source == precip_model::TimingSource::Unavailable {
                eprintln!("{name}: no timestamps on this adapter");
                continue;
            }
            // The particles are drawn one way or the other; no water to mirror, no
            // sea (nor its shore), no clouds.
            let cloudless: Vec<&str> = precip_gpu::recipe::cloud_passes().collect();
            let skipped: &[&str] = if reduced {
                &["particles", "water_mirror", "ocean", "shore"]
            } else {
                &[
                    "particles_reduced",
                    "particles_composite",
                    "water_mirror",
                    "ocean",
                    "shore",
                ]
            };
            for pass in precip_gpu::recipe::TIMED_RENDER_PASSES
                .into_iter()
                .filter(|p| !skipped.contains(p) && !cloudless.contains(p))
            {
                let t = timings
                    .passes
                    .iter()
                    .find(|p| p.pass == pass)
                    .unwrap_or_else(|| panic!("{name}: no timing for {pass}: {timings:?}"));
                assert!(t.milliseconds.is_finite() && t.milliseconds >= 0.0);
            }
            for pass in skipped {
                assert!(
                    timings.passes.iter().all(|p| p.pass != *pass),
                    "{name}: {pass} did not run"
                );
            }
        }
    }
}

/// The backend is usable as a `dyn Backend` that renders.
#[test]
fn the_wgpu_backend_says_it_renders() {
    for (name, gpu) in common::gpu_backends("the_wgpu_backend_says_it_renders") {
        let gpu: Box<dyn Backend> = Box::new(gpu);
        assert!(gpu.info().renders, "{name}");
    }
    let _: fn() -> Result<WgpuBackend, BackendError> = WgpuBackend::new;
}

#[test]
fn the_house_casts_a_shadow_away_from_the_sun() {
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, 1).expect("valid");
    setup.weather.intensity_mm_per_h = 0.0;
    setup.render.clear_air_extinction_per_m = 0.0;
    setup.render.to_sun = Vec3::new(0.4, 0.8, 0.3);
    // A clear day's hard shadow (the default, 0.6, is a snowy sky's soft one).
    setup.render.lighting.shadow_density = 1.0;
    let camera = Camera {
        position_m: Vec3::new(2.0, 30.0, 18.0),
        forward: Vec3::new(-5.0, -30.0, -20.0),
        ..Camera::default()
    };
    setup.camera = camera;
    let view = view(camera, 160, 120);
    // The roof's corner (−5, 2.4, −4) and the ridge's end (−5, 4.7, 0) fall on the
    // ground about (−6.2, −4.9) and (−7.4, −1.8): the point between is in shadow.
    let shaded = Vec3::new(-6.3, 0.0, -3.0);
    let sunlit = [Vec3::new(-6.3, 0.0, 6.0), Vec3::new(8.0, 0.0, -3.0)];
    for (name, mut gpu) in common::gpu_backends("the_house_casts_a_shadow_away_from_the_sun") {
        gpu.configure(&setup).expect("valid");
        gpu.render(&view).expect("renders");
        let image = gpu.read_image().expect("an image");
        keep(&image, "shadow");
        // Linear green: ambient 0.45 in the shadow against 0.45 + 0.55 in the sun.
        let at = |p: Vec3| {
            let (x, y) = pixel_of(&view, p).expect("in view");
            linear(crate::images::rgb(&image, x, y)[1])
        };
        for lit in sunlit {
            assert!(
                at(shaded) < 0.6 * at(lit),
                "{name}: shadow {} vs sunlit {} at {lit}",
                at(shaded),
                at(lit)
            );
        }
    }
}

/// Linear light of a pixel (mean of R, G, B), in 1/255.
fn light(image: &precip_model::Image, x: u32, y: u32) -> f32 {
    let [r, g, b] = crate::images::rgb(image, x, y);
    (linear(r) + linear(g) + linear(b)) / 3.0 * 255.0
}

/// Mean linear light of `image` over `block × block` tiles, row-major, in 1/255.
fn block_means(image: &precip_model::Image, block: u32) -> Vec<f32> {
    let (w, h) = (image.width_px / block, image.height_px / block);
    let mut out = Vec::with_capacity((w * h) as usize);
    for by in 0..h {
        for bx in 0..w {
            let mut sum = 0.0;
            for y in by * block..(by + 1) * block {
                for x in bx * block..(bx + 1) * block {
                    sum += light(image, x, y);
                }
            }
            out.push(sum / (block * block) as f32);
        }
    }
    out
}

/// Far snow, most of it below the sprite's minimum size, drawn by the splat and
/// drawn all as sprites: the splat takes the far particles (the counts say so) and
/// lays the same light on the image — the mean linear light above the sky agrees
/// within 10 %, and 16×16-pixel tiles within 2/255 of each other on average — while
/// near particles are sprites in both.
#[test]
fn splatted_far_snow_matches_the_all_sprite_frame() {
    let mut setup = Setup::over_flat_ground(400.0, 64, 40.0, 60_000);
    setup.world_emitter = setup.world_emitter.map(|mut e| {
        e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 40.0, 0.0), 160.0, 160.0, 40.0);
        e
    });
    dark_sky(&mut setup);
    setup.render.sizing.min_opacity = 0.0;
    // Large flakes, so the camera, inside the snow, has sprites near it.
    setup.render.sizing.snow_scale = 30.0;
    let camera = Camera {
        position_m: Vec3::new(0.0, 20.0, 60.0),
        forward: Vec3::new(0.0, -0.05, -1.0),
        ..Camera::default()
    };
    setup.camera = camera;
    let view = view(camera, 256, 160);
    for (name, mut gpu) in common::gpu_backends("splatted_far_snow_matches_the_all_sprite_frame") {
        let mut images = Vec::new();
        let mut drawn = Vec::new();
        for splat in [false, true] {
            setup.render.splat_sub_pixel = splat;
            common::run(&mut gpu, &setup, 3, 0.05);
            gpu.render(&view).expect("renders");
            images.push(gpu.read_image().expect("an image"));
            drawn.push(gpu.drawn().expect("counts").expect("a drawing backend"));
        }
        keep(&images[0], "far_snow_sprites");
        keep(&images[1], "far_snow_splatted");
        let (sprites, hybrid) = (drawn[0], drawn[1]);
        assert_eq!(sprites.splats, 0, "{name}: splat off splats nothing");
        assert_eq!(
            sprites.total(),
            hybrid.total(),
            "{name}: the same particles are drawn either way"
        );
        assert!(
            hybrid.splats > 4 * hybrid.sprites && hybrid.sprites > 0,
            "{name}: far snow is splatted, near snow is sprites: {hybrid:?}"
        );
        let sky = light(&images[0], 0, 0);
        let above_sky = |image| {
            let tiles = block_means(image, 16);
            tiles.iter().sum::<f32>() / tiles.len() as f32 - sky
        };
        let (a, b) = (above_sky(&images[0]), above_sky(&images[1]));
        eprintln!("{name}: light above the sky: sprites {a:.3}, hybrid {b:.3}; {hybrid:?}");
        assert!(a > 0.5, "{name}: the snow shows ({a})");
        assert!((b - a).abs() <= 0.1 * a, "{name}: sprites {a}, hybrid {b}");
        let (ta, tb) = (block_means(&images[0], 16), block_means(&images[1], 16));
        let tile_difference =
            ta.iter().zip(&tb).map(|(x, y)| (x - y).abs()).sum::<f32>() / ta.len() as f32;
        eprintln!("{name}: mean tile difference {tile_difference:.3}/255");
        assert!(
            tile_difference <= 2.0,
            "{name}: tiles differ by {tile_difference}/255 on average"
        );
    }
}

/// Far snow too small for a sprite, splatted, seen through a long exposure (1 s: a
/// flake 60 m away falling 1 m/s sweeps ~5 px down a 512×320 image): each flake's ink
/// is laid along the streak it draws during the exposure, so the image varies far
/// less down it than across it — the ratio of pixel-to-pixel differences along y to
/// those along x under 0.55 of what it is at a 1 ms exposure (0.45 measured on
/// lavapipe; 0.66 with every flake splatted at its centre).
#[test]
fn splatted_snow_streaks_over_the_exposure() {
    let mut setup = Setup::over_flat_ground(400.0, 64, 40.0, 60_000);
    setup.world_emitter = setup.world_emitter.map(|mut e| {
        e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 40.0, 0.0), 160.0, 160.0, 40.0);
        e
    });
    dark_sky(&mut setup);
    setup.weather.intensity_mm_per_h = 8.0;
    for (name, mut gpu) in common::gpu_backends("splatted_snow_streaks_over_the_exposure") {
        let mut ratios = Vec::new();
        for exposure_s in [0.001, 1.0] {
            let camera = Camera {
                position_m: Vec3::new(0.0, 20.0, 60.0),
                forward: Vec3::new(0.0, -0.05, -1.0),
                lens: precip_model::Lens {
                    exposure_s,
                    ..precip_model::Lens::default()
                },
                ..Camera::default()
            };
            setup.camera = camera;
            common::run(&mut gpu, &setup, 3, 0.05);
            gpu.render(&view(camera, 512, 320)).expect("renders");
            let image = gpu.read_image().expect("an image");
            keep(&image, &format!("splatted_snow_over_{exposure_s}_s"));
            let drawn = gpu.drawn().expect("counts").expect("a drawing backend");
            assert!(
                drawn.splats > 20 * drawn.sprites.max(1),
                "{name}: {drawn:?}"
            );
            let (mut down, mut across) = (0.0f64, 0.0f64);
            for y in 20..image.height_px - 21 {
                for x in 0..image.width_px - 1 {
                    across += f64::from((light(&image, x + 1, y) - light(&image, x, y)).abs());
                    down += f64::from((light(&image, x, y + 1) - light(&image, x, y)).abs());
                }
            }
            eprintln!("{name}: {exposure_s} s: differences down {down:.0}, across {across:.0}");
            ratios.push(down / across);
        }
        assert!(
            ratios[1] < 0.55 * ratios[0],
            "{name}: over the long exposure the splat streaks down: {ratios:?}"
        );
    }
}

/// The particles' resolution changed between frames (`set_particle_resolution`, what
/// `--quality auto` turns) draws the frame configuring it would: the same image
/// within 1/255 as a configuration at that resolution, through a full → half →
/// quarter → full sequence; not configured, it is refused.
#[test]
fn the_particles_resolution_changes_between_frames_as_configured() {
    use precip_model::ParticleResolution;
    let (mut setup, view) = snow_column();
    // Sprites, not only splats, at every resolution.
    setup.render.sizing.snow_scale = 100.0;
    let view = View {
        width_px: 256,
        height_px: 160,
        ..view
    };
    let name_of = "the_particles_resolution_changes_between_frames_as_configured";
    for (name, mut gpu) in common::gpu_backends(name_of) {
        let sequence = [
            ParticleResolution::Half,
            ParticleResolution::Quarter,
            ParticleResolution::Full,
            ParticleResolution::Half,
        ];
        let mut turned = Vec::new();
        common::run(&mut gpu, &setup, 2, 0.05);
        gpu.render(&view).expect("renders");
        for resolution in sequence {
            gpu.set_particle_resolution(resolution).expect("configured");
            gpu.render(&view).expect("renders");
            turned.push(gpu.read_image().expect("an image"));
        }
        for (resolution, image) in sequence.into_iter().zip(&turned) {
            let mut configured = setup.clone();
            configured.render.particle_resolution = resolution;
            common::run(&mut gpu, &configured, 2, 0.05);
            gpu.render(&view).expect("renders");
            let expected = gpu.read_image().expect("an image");
            let worst = max_difference(image, &expected);
            let drawn = gpu.drawn().expect("counts").expect("a drawing backend");
            eprintln!("{name}: {resolution:?}: worst {worst}/255, drawn {drawn:?}");
            assert!(drawn.sprites > 50, "{name}: {resolution:?}: {drawn:?}");
            assert!(worst <= 1, "{name}: {resolution:?}: {worst}/255");
        }
        let mut fresh = WgpuBackend::with_device(gpu.device().clone()).expect("a backend");
        assert!(matches!(
            fresh.set_particle_resolution(ParticleResolution::Half),
            Err(BackendError::NotConfigured { .. })
        ));
    }
}

/// Snow from near to far drawn at half and at a quarter of the frame's resolution
/// (`ParticleResolution`), seen from outside the snow and from inside it: the
/// particles' image, laid over the frame, brings the same light as drawing them at
/// the frame's — the mean light above the sky within 5 % (or half a level of 255),
/// 16×16-pixel tiles within 2/255 of each other on average — with fewer sprites
/// (what is under the sprites' minimum size in drawn pixels is splatted at the
/// frame's resolution, with the light the frame's sprite would have had).
#[test]
fn particles_drawn_at_a_reduced_resolution_bring_the_same_light() {
    use precip_model::ParticleResolution;
    let mut setup = Setup::over_flat_ground(400.0, 64, 40.0, 60_000);
    setup.world_emitter = setup.world_emitter.map(|mut e| {
        e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 40.0, 0.0), 160.0, 160.0, 40.0);
        e
    });
    dark_sky(&mut setup);
    setup.render.sizing.snow_scale = 30.0;
    let name_of = "particles_drawn_at_a_reduced_resolution_bring_the_same_light";
    for (name, mut gpu) in common::gpu_backends(name_of) {
        // Outside the snow, most of it far and splatted; inside it, among sprites.
        for (place, z_m) in [("outside", 60.0), ("inside", 0.0)] {
            let camera = Camera {
                position_m: Vec3::new(0.0, 20.0, z_m),
                forward: Vec3::new(0.0, -0.05, -1.0),
                ..Camera::default()
            };
            setup.camera = camera;
            let view = view(camera, 256, 160);
            let mut images = Vec::new();
            let mut drawn = Vec::new();
            for resolution in [
                ParticleResolution::Full,
                ParticleResolution::Half,
                ParticleResolution::Quarter,
            ] {
                setup.render.particle_resolution = resolution;
                common::run(&mut gpu, &setup, 3, 0.05);
                gpu.render(&view).expect("renders");
                images.push(gpu.read_image().expect("an image"));
                drawn.push(gpu.drawn().expect("counts").expect("a drawing backend"));
            }
            keep(&images[0], &format!("snow_{place}_at_full_resolution"));
            keep(&images[1], &format!("snow_{place}_at_half_resolution"));
            keep(&images[2], &format!("snow_{place}_at_a_quarter_resolution"));
            let sky = light(&images[0], 0, 0);
            let above_sky = |image| {
                let tiles = block_means(image, 16);
                tiles.iter().sum::<f32>() / tiles.len() as f32 - sky
            };
            let full = above_sky(&images[0]);
            assert!(full > 0.5, "{name}: the snow shows ({full})");
            for (reduced, (image, counts)) in ["half", "quarter"]
                .into_iter()
                .zip(images[1..].iter().zip(&drawn[1..]))
            {
                let light_there = above_sky(image);
                let (ta, tb) = (block_means(&images[0], 16), block_means(image, 16));
                let tiles =
                    ta.iter().zip(&tb).map(|(x, y)| (x - y).abs()).sum::<f32>() / ta.len() as f32;
                eprintln!(
                    "{name}, {place}: light above the sky: full {full:.3}, {reduced} \
                 {light_there:.3}; mean tile difference {tiles:.3}/255; drawn {:?} against {:?}",
                    counts, drawn[0]
                );
                // Inside, a hundred near sprites carry most of the light, each
                // rasterised on its own grid: within half a level of 255 there.
                assert!(
                    (light_there - full).abs() <= (0.05 * full).max(0.5),
                    "{name}, {place}: {reduced} {light_there}, full {full}"
                );
                assert!(
                    tiles <= 2.0,
                    "{name}: {reduced}: tiles differ by {tiles}/255"
                );
                assert_eq!(
                    counts.total(),
                    drawn[0].total(),
                    "{name}: the same particles"
                );
                assert!(
                    counts.sprites < drawn[0].sprites,
                    "{name}: {reduced}: fewer sprites ({counts:?} against {:?})",
                    drawn[0]
                );
            }
        }
    }
}

/// The surfaces read the cover from three RGBA16F textures the frame writes from the
/// cover texels: after a day of snow they hold every texel's depth, SWE, peak SWE,
/// wetness, masks, age, puddles and settled grains to half precision (relative
/// 2⁻¹⁰, plus 10⁻³ absolute).
#[test]
fn the_cover_textures_match_the_cover_texels() {
    let (setup, _) = snowed_house();
    let view = view(setup.camera, 64, 48);
    for (name, gpu) in common::gpu_backends("the_cover_textures_match_the_cover_texels") {
        let mut gpu = gpu;
        assert!(
            gpu.read_cover_textures().is_err(),
            "{name}: nothing before configure"
        );
        common::run(&mut gpu, &setup, 10, 0.1);
        assert_eq!(
            gpu.read_cover_textures().expect("reads"),
            None,
            "{name}: no frame yet"
        );
        gpu.render(&view).expect("renders");
        let textures = gpu
            .read_cover_textures()
            .expect("reads")
            .expect("a frame wrote them");
        let cover = gpu.read_cover().expect("the cover");
        assert_eq!(textures.len(), cover.texels.len(), "{name}");
        let mut snowy = 0;
        for (i, (t, c)) in textures.iter().zip(&cover.texels).enumerate() {
            let expected = [
                c.depth_mm,
                c.swe_mm,
                c.peak_swe_mm,
                c.wetness,
                c.accumulation_mask,
                c.melt_mask,
                c.age_days,
                c.puddle_ratio(),
                c.dust_kg_m2,
                precip_model::cover::Surface::from_raw(c.surface).snow_roughness_m(),
                0.0,
                0.0,
            ];
            for (k, (got, want)) in t.iter().zip(expected).enumerate() {
                assert!(
                    (got - want).abs() <= want.abs() / 1024.0 + 1.0e-3,
                    "{name}: texel {i} field {k}: texture {got}, cover {want}"
                );
            }
            snowy += usize::from(c.depth_mm > 1.0);
        }
        assert!(snowy > 100, "{name}: {snowy} texels have snow");
    }
}

/// A drop refracts the ground over its lower field: the `drop_ground` kernel gives
/// every frame the cover's ground albedo around the camera, as
/// `precip_model::drawing::drop_ground_albedo` computes it from the cover read back
/// (bare ground 0.2 before the snow; brighter under a day of it), and the land's
/// beyond the scene, as `far_ground_albedo` does over the whole grid.
#[test]
fn the_drops_refract_the_cover_around_the_camera() {
    let (setup, _) = snowed_house();
    let view = view(setup.camera, 64, 48);
    for (name, mut gpu) in common::gpu_backends("the_drops_refract_the_cover_around_the_camera") {
        let mut albedos = Vec::new();
        for steps in [0, 10] {
            common::run(&mut gpu, &setup, steps, 0.1);
            assert_eq!(gpu.read_drop_ground_albedo().expect("reads"), None);
            gpu.render(&view).expect("renders");
            let [got, land] = gpu
                .read_drop_ground_albedo()
                .expect("reads")
                .expect("a frame wrote it");
            let cover = gpu.read_cover().expect("the cover");
            let want_land =
                precip_model::drawing::far_ground::far_ground_albedo(&cover, &setup.cover.params);
            assert!(
                (land - want_land).abs() < 1.0e-4,
                "{name} after {steps} steps: the land's, kernel {land}, model {want_land}"
            );
            let camera = view.camera.position_m;
            let want = precip_model::drawing::drop_ground_albedo(
                &cover,
                Vec2::new(camera.x, camera.z),
                &setup.cover.params,
            );
            assert!(
                (got - want).abs() < 1.0e-4,
                "{name} after {steps} steps: kernel {got}, model {want}"
            );
            albedos.push(got);
        }
        assert!(
            (albedos[0] - precip_model::drawing::BARE_GROUND_ALBEDO).abs() < 1.0e-6,
            "{name}: bare ground {}",
            albedos[0]
        );
        // The grid ends within the radius (bare beyond): 0.4 here.
        assert!(
            albedos[1] > albedos[0] + 0.15,
            "{name}: under a day of snow {}",
            albedos[1]
        );
    }
}

/// The shadow map is drawn on the first frame and again only when the sun, the
/// displacement or the snow moved enough (`ShadowCache`): frames in real time under
/// light snow, with the camera moving, reuse it and look the same as a frame that
/// redraws it; a heavy snowfall at a day per second redraws it every frame.
#[test]
fn the_shadow_map_is_not_redrawn_when_nothing_changed() {
    let (mut setup, _) = snowed_house();
    setup.cover.time_scale = 1.0;
    let view = view(setup.camera, 96, 72);
    let shadow_timed = |gpu: &mut WgpuBackend| {
        gpu.timings()
            .expect("timings")
            .passes
            .iter()
            .any(|p| p.pass == "shadow")
    };
    for (name, mut gpu) in
        common::gpu_backends("the_shadow_map_is_not_redrawn_when_nothing_changed")
    {
        common::run(&mut gpu, &setup, 2, 0.05);
        gpu.render(&view).expect("renders");
        if gpu.timings().expect("timings").source == precip_model::TimingSource::Unavailable {
            eprintln!("{name}: no timestamps: the cache is not observable here");
            continue;
        }
        assert!(shadow_timed(&mut gpu), "{name}: the first frame draws it");
        let mut moved = view;
        let mut cameras = Vec::new();
        for _ in 0..5 {
            moved.camera.position_m.x += 0.01;
            cameras.push(moved.camera);
            gpu.set_camera(&moved.camera).expect("valid");
            gpu.step(0.05).expect("valid");
            gpu.render(&moved).expect("renders");
            assert!(
                !shadow_timed(&mut gpu),
                "{name}: 5 cm/h moves nothing in 0.05 s"
            );
        }
        gpu.render(&moved).expect("renders");
        let reused = gpu.read_image().expect("an image");
        // The same state re-made (deterministic), its first frame drawing the map.
        common::run(&mut gpu, &setup, 2, 0.05);
        for camera in &cameras {
            gpu.set_camera(camera).expect("valid");
            gpu.step(0.05).expect("valid");
        }
        gpu.render(&moved).expect("renders");
        assert!(
            shadow_timed(&mut gpu),
            "{name}: a new configuration draws it"
        );
        let redrawn = gpu.read_image().expect("an image");
        let difference = max_difference(&reused, &redrawn);
        assert!(
            difference <= 1,
            "{name}: the reused map differs by {difference}/255"
        );
        // A day per second of heavy snow moves the surface every frame.
        setup.cover.time_scale = 86_400.0;
        setup.weather.intensity_mm_per_h = 20.0;
        gpu.configure(&setup).expect("valid");
        for frame in 0..3 {
            gpu.step(0.05).expect("valid");
            gpu.render(&view).expect("renders");
            assert!(shadow_timed(&mut gpu), "{name}: frame {frame} redraws it");
        }
        // Kept up to 4 frames (a frame-rate control's knob): redrawn every 4th.
        for bad in [0, 61] {
            assert!(
                gpu.set_shadow_refresh_frames(bad).is_err(),
                "{name}: {bad} frames"
            );
        }
        gpu.set_shadow_refresh_frames(4).expect("valid");
        let mut redrawn = Vec::new();
        for _ in 0..8 {
            gpu.step(0.05).expect("valid");
            gpu.render(&view).expect("renders");
            redrawn.push(shadow_timed(&mut gpu));
        }
        assert_eq!(
            redrawn,
            [false, false, false, true, false, false, false, true],
            "{name}: kept 3 frames after each draw"
        );
    }
}

/// A tiled display rig: two channels on separate machines (backends), each showing
/// its window of one image plane (lens shifted half a width left and right), stepped
/// and drawn alike from the same setup, draw the same pixels where their windows
/// overlap — and both match one wide view of the whole plane.
#[test]
fn adjacent_channels_of_a_rig_draw_the_same_pixels_where_they_overlap() {
    let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, 6_000).expect("valid");
    setup.cover.time_scale = 20_000.0;
    setup.camera = Camera {
        position_m: Vec3::new(9.0, 3.0, 10.0),
        forward: Vec3::new(-0.7, -0.15, -1.0),
        ..Camera::default()
    };
    let channel = |shift: f32, width_px: u32| {
        view(
            Camera {
                lens_shift: Vec2::new(shift, 0.0),
                ..setup.camera
            },
            width_px,
            48,
        )
    };
    // Each channel is 64 px wide: shifted by ±0.5 half-widths their windows overlap
    // by 32 px, and together they span a 96 px view of the same height.
    let views = [channel(-0.5, 64), channel(0.5, 64), channel(0.0, 96)];
    let mut images = Vec::new();
    let mut name = String::new();
    for (view, (n, mut gpu)) in views
        .iter()
        .zip((0..3).filter_map(|_| common::gpu_backends("adjacent_channels").into_iter().next()))
    {
        name = n;
        gpu.configure(&setup).expect("valid");
        for _ in 0..6 {
            gpu.step(0.05).expect("step");
            gpu.render(view).expect("render");
        }
        images.push(gpu.read_image().expect("an image"));
    }
    if images.len() < 3 {
        return;
    }
    keep(&images[0], "rig_left");
    keep(&images[1], "rig_right");
    keep(&images[2], "rig_whole");
    let pixel = |image: &precip_model::Image, x: u32, y: u32| {
        let i = 4 * (y * image.width_px + x) as usize;
        [image.rgba8[i], image.rgba8[i + 1], image.rgba8[i + 2]]
    };
    // (image, column offset) pairs that show the same rays: the overlap of the two
    // channels, each channel's overlap with the whole view, and the left channel's
    // outer part with the whole view's.
    let pairs = [
        ((0, 32), (1, 0), "left/right"),
        ((0, 32), (2, 32), "left/whole"),
        ((1, 0), (2, 32), "right/whole"),
        ((0, 0), (2, 0), "left edge/whole"),
    ];
    let mut compared = 0;
    let mut differing = Vec::new();
    for ((a, ax), (b, bx), what) in pairs {
        for y in 0..48 {
            for x in 0..32 {
                compared += 1;
                let (p, q) = (pixel(&images[a], x + ax, y), pixel(&images[b], x + bx, y));
                let d = p
                    .iter()
                    .zip(q)
                    .map(|(u, v)| u.abs_diff(v))
                    .max()
                    .unwrap_or(0);
                if d > 1 {
                    differing.push((x, y, what, d));
                }
            }
        }
    }
    println!(
        "{name}: {compared} pixel pairs compared, {} differ by more than 1/255: {:?}",
        differing.len(),
        &differing[..differing.len().min(12)]
    );
    // Rasterisation may round an edge pixel apart; nothing more.
    assert!(differing.len() * 200 <= compared, "{name}: {differing:?}");
    // The overlap is not empty sky: the house and the flakes are in it.
    let distinct: std::collections::HashSet<[u8; 3]> = (0..48)
        .flat_map(|y| (0..32).map(move |x| (x, y)))
        .map(|(x, y)| pixel(&images[1], x, y))
        .collect();
    assert!(distinct.len() > 50, "{name}: {} colours", distinct.len());
}

/// What is drawn follows the air's density (docs/model.md (5.15)): a camera volume
/// holding more particles than the air at every intensity draws a share `m` of them
/// — the air's count over its own — so the drawn count is the physical count, in
/// proportion across intensities and kinds, and at 0 mm/h nothing.
#[test]
fn the_drawn_density_is_the_air_s_at_every_intensity() {
    let camera = Camera {
        position_m: Vec3::new(0.0, 20.0, 0.0),
        forward: Vec3::NEG_Z,
        ..Camera::default()
    };
    let view = view(camera, 32, 32);
    let count = 120_000u32;
    let box_m3 = 64.0;
    for (name, mut gpu) in common::gpu_backends("the_drawn_density_is_the_air_s_at_every_intensity")
    {
        for (kind, temperature_c) in [
            (PrecipitationKind::Rain, 10.0),
            (PrecipitationKind::DrySnow, -5.0),
        ] {
            for intensity in [0.0, 0.01, 0.1, 1.0, 10.0] {
                let mut setup = Setup::over_flat_ground(60.0, 16, 40.0, 1);
                setup.world_emitter = None;
                setup.camera_volume = Some(CameraVolumeSetup {
                    volume: CameraVolume {
                        half_extent_m: Vec3::splat(2.0),
                        ..CameraVolume::default()
                    },
                    particle_count: count,
                });
                setup.camera = camera;
                setup.render.view_cone_culling = false;
                setup.weather.kind = kind;
                setup.weather.air_temperature_c = temperature_c;
                setup.weather.intensity_mm_per_h = intensity;
                common::run(&mut gpu, &setup, 1, 0.02);
                gpu.render(&view).expect("renders");
                let drawn = gpu
                    .drawn()
                    .expect("counts")
                    .expect("a drawing backend")
                    .total() as f64;
                let physical = f64::from(setup.weather.simulated_number_density_per_m3()) * box_m3;
                assert!(
                    physical < f64::from(count),
                    "{kind:?} {intensity}: the pool holds the air"
                );
                // Binomial: 4.5 standard deviations, plus one.
                let share = physical / f64::from(count);
                let sd = (f64::from(count) * share * (1.0 - share)).sqrt();
                assert!(
                    (drawn - physical).abs() <= 4.5 * sd + 1.0,
                    "{name}: {kind:?} at {intensity} mm/h: {drawn} drawn, the air holds {physical:.0}"
                );
                if intensity == 0.0 {
                    assert!(drawn == 0.0, "{name}: {kind:?}: nothing in dry air");
                }
            }
        }
    }
}

/// A pond 30 m long with a red wall 6 m high beyond it, on flat ground.
fn pond_and_wall(wall: bool) -> Scene {
    let quad = |name: &str, corners: [Vec3; 4], colour: [f32; 4], surface| Mesh {
        name: name.to_owned(),
        positions_m: corners.to_vec(),
        indices: vec![0, 1, 2, 0, 2, 3],
        material: Material {
            base_colour: colour,
            base_colour_texture: None,
        },
        surface,
        ..Mesh::default()
    };
    let mut meshes = vec![
        quad(
            "ground",
            [
                Vec3::new(-20.0, -0.01, 5.0),
                Vec3::new(20.0, -0.01, 5.0),
                Vec3::new(20.0, -0.01, -45.0),
                Vec3::new(-20.0, -0.01, -45.0),
            ],
            [0.3, 0.3, 0.3, 1.0],
            None,
        ),
        quad(
            "pond",
            [
                Vec3::new(-10.0, 0.0, -2.0),
                Vec3::new(10.0, 0.0, -2.0),
                Vec3::new(10.0, 0.0, -32.0),
                Vec3::new(-10.0, 0.0, -32.0),
            ],
            [0.3, 0.3, 0.3, 1.0],
            Some(precip_model::cover::Surface::Water),
        ),
    ];
    if wall {
        meshes.push(quad(
            "red wall",
            [
                Vec3::new(-4.0, 0.0, -34.0),
                Vec3::new(4.0, 0.0, -34.0),
                Vec3::new(4.0, 6.0, -34.0),
                Vec3::new(-4.0, 6.0, -34.0),
            ],
            [0.9, 0.05, 0.05, 1.0],
            None,
        ));
    }
    Scene { meshes }
}

/// Eye height over the water, looking at the wall 34 m away.
fn low_over_the_water() -> (Camera, View) {
    let camera = Camera {
        position_m: Vec3::new(0.0, 1.5, 0.0),
        forward: Vec3::new(0.0, -0.12, -1.0).normalize(),
        vertical_fov_rad: 50f32.to_radians(),
        ..Camera::default()
    };
    (camera, view(camera, 128, 96))
}

/// The first two frames of the pond (with the wall or not) seen by `camera`.
fn pond_frames(
    gpu: &mut WgpuBackend,
    camera: Camera,
    view: &View,
    wall: bool,
) -> (precip_model::Image, precip_model::Image) {
    let (mut setup, _) = Setup::over_scene(pond_and_wall(wall), 32, 5.0, 1).expect("valid");
    setup.weather.intensity_mm_per_h = 0.0;
    setup.camera = camera;
    common::run(gpu, &setup, 1, 0.05);
    gpu.render(view).expect("renders");
    let first = gpu.read_image().expect("an image");
    gpu.render(view).expect("renders");
    (first, gpu.read_image().expect("an image"))
}

/// The water mirrors the scene beyond it, not only the sky: the red wall's mirror
/// image shows in the pond (the planar mirror, from the first frame on), where the
/// same pond without the wall reflects the sky.
#[test]
fn a_pond_mirrors_the_wall_beyond_it() {
    let (camera, view) = low_over_the_water();
    // The wall's point 2 m up, mirrored in the pond's level: where its image shows.
    let (mx, my) = pixel_of(&view, Vec3::new(0.0, -2.0, -34.0)).expect("image in view");
    let (wx, wy) = pixel_of(&view, Vec3::new(0.0, 2.0, -34.0)).expect("wall in view");
    // Beside the image, the sky's reflection only.
    let (sx, sy) = pixel_of(&view, Vec3::new(-8.5, -2.0, -34.0)).expect("pond in view");
    let redness = |image: &precip_model::Image, x, y| {
        let [r, g, _] = crate::images::rgb(image, x, y);
        linear(r) - linear(g)
    };
    for (name, mut gpu) in common::gpu_backends("a_pond_mirrors_the_wall_beyond_it") {
        let mut frames = Vec::new();
        for wall in [true, false] {
            let (first, second) = pond_frames(&mut gpu, camera, &view, wall);
            keep(&second, &format!("pond_wall_{wall}"));
            frames.push((first, second));
        }
        let (with_wall, without) = (&frames[0], &frames[1]);
        let wall_red = redness(&with_wall.1, wx, wy);
        assert!(wall_red > 0.2, "{name}: the wall is red: {wall_red}");
        // The pond's own colour (its depths are blue-green) is the baseline.
        let pond = redness(&without.1, mx, my);
        let image_red = redness(&with_wall.1, mx, my) - pond;
        assert!(
            image_red > 0.1 * wall_red,
            "{name}: the wall's image in the pond at ({mx}, {my}) is red: {image_red} more than the pond alone (the wall {wall_red})"
        );
        let first = redness(&with_wall.0, mx, my) - pond;
        assert!(
            (first - image_red).abs() < 0.02,
            "{name}: the first frame mirrors the wall as the second does: {first} against {image_red}"
        );
        let beside = redness(&with_wall.1, sx, sy) - redness(&without.1, sx, sy);
        assert!(
            beside.abs() < 0.02,
            "{name}: the pond beside the image reflects the sky as the pond alone does: red excess {beside}"
        );
    }
}

/// The planar mirror shows what the frame does not: looking down at the pond, the
/// red wall beyond it is above the frame's top edge (no screen-space ray can find
/// it), and its image still shows in the water; without the wall, the sky's.
#[test]
fn a_pond_mirrors_a_wall_above_the_frame() {
    let (camera, _) = low_over_the_water();
    let camera = Camera {
        forward: Vec3::new(0.0, -0.53, -1.0).normalize(),
        ..camera
    };
    let view = view(camera, 128, 96);
    assert_eq!(
        pixel_of(&view, Vec3::new(0.0, 0.0, -34.0)),
        None,
        "the wall's foot is out of view"
    );
    let (mx, my) = pixel_of(&view, Vec3::new(0.0, -4.0, -34.0)).expect("its image in view");
    for (name, mut gpu) in common::gpu_backends("a_pond_mirrors_a_wall_above_the_frame") {
        let mut reds = Vec::new();
        for wall in [true, false] {
            let (_, image) = pond_frames(&mut gpu, camera, &view, wall);
            keep(&image, &format!("pond_wall_above_{wall}"));
            let [r, g, _] = crate::images::rgb(&image, mx, my);
            reds.push(linear(r) - linear(g));
        }
        assert!(
            reds[0] > reds[1] + 0.05,
            "{name}: the wall's image in the pond is red ({}) against the pond alone ({})",
            reds[0],
            reds[1]
        );
    }
}

/// Rain standing on asphalt before a red wall mirrors the wall where the settings
/// let puddles mirror the scene (`Mirrors::AllWater`), and only the sky where they
/// do not (`Mirrors::WaterBodies`).
#[test]
fn puddles_mirror_the_wall_only_when_the_settings_say_so() {
    let (camera, view) = low_over_the_water();
    let (mx, my) = pixel_of(&view, Vec3::new(0.0, -2.0, -34.0)).expect("image in view");
    let redness = |image: &precip_model::Image| {
        let [r, g, _] = crate::images::rgb(image, mx, my);
        linear(r) - linear(g)
    };
    let mut scene = pond_and_wall(true);
    // No pond: the ground itself, asphalt, under a cloudburst.
    scene.meshes.retain(|m| m.name != "pond");
    scene.meshes[0].surface = Some(precip_model::cover::Surface::Asphalt);
    for (name, mut gpu) in common::gpu_backends("puddles_mirror_the_wall") {
        let mut reds = Vec::new();
        for mirrors in [
            precip_model::Mirrors::WaterBodies,
            precip_model::Mirrors::AllWater,
        ] {
            let (mut setup, _) = Setup::over_scene(scene.clone(), 32, 5.0, 1).expect("valid");
            // The one particle falls far behind the camera; the cover takes the rate.
            setup.world_emitter = setup.world_emitter.map(|mut e| {
                e.emitter = WorldEmitter::horizontal(Vec3::new(0.0, 10.0, 500.0), 1.0, 1.0, 10.0);
                e
            });
            setup.weather.kind = PrecipitationKind::Rain;
            setup.weather.air_temperature_c = 15.0;
            setup.weather.intensity_mm_per_h = 40.0;
            setup.cover.time_scale = 3_600.0;
            setup.render.mirrors = mirrors;
            setup.camera = camera;
            common::run(&mut gpu, &setup, 10, 0.1);
            let standing = gpu.read_cover().expect("cover").totals().standing_kg;
            assert!(standing > 0.0, "{name}: water stands on the asphalt");
            gpu.render(&view).expect("renders");
            gpu.render(&view).expect("renders");
            let image = gpu.read_image().expect("an image");
            keep(&image, &format!("puddle_wall_{mirrors:?}"));
            reds.push(redness(&image));
        }
        assert!(
            reds[1] > reds[0] + 0.02,
            "{name}: the puddles mirror the red wall with AllWater ({}) and not with WaterBodies ({})",
            reds[1],
            reds[0]
        );
    }
}
