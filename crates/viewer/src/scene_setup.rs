//! From a loaded scene and the user's choices to a [`Setup`] (docs/architecture.md §2):
//! the ground map and cover grid fit the scene's bounds at a chosen resolution; the
//! camera volume always holds precipitation around the camera; a world emitter covers
//! the scene (aimed: its particles land on it in any wind) when the scene is small enough
//! for the particle budget, so the cover there is fed by landing particles, and by the
//! weather's rate elsewhere.
//!
//! The camera volume holds the weather's physical number of particles of the sizes
//! seen one by one (`Weather::simulated_number_density_per_m3`: about 79 flakes per m³
//! in 2 mm/h of snow at −5 °C) up to [`CAMERA_SHARE`] of the budget; the world
//! emitter takes the rest when that is dense enough to feed the cover, else the
//! camera volume takes the whole budget.

use glam::{UVec2, Vec2, Vec3};
use precip_model::cover::GridFrame;
use precip_model::{
    BackendError, Camera, CameraVolume, CameraVolumeSetup, CoverSetup, EmitterSetup, GroundMap,
    PreparedScene, Setup, Weather, WorldEmitter,
};

/// The fastest the cover's clock may run, simulated days per real second: faster,
/// a frame's step of the cover (melt, drift, flow) runs for hours and stops being
/// physical (at 15 frames a second this steps it over three hours a frame).
pub const MOST_COVER_DAYS_PER_SECOND: f32 = 2.0;

/// Fewest world-emitter particles per m² of scene for particles to feed the cover.
pub const MIN_WORLD_DENSITY_PER_M2: f32 = 2.0;
/// Most of the budget the camera volume takes when a world emitter runs.
pub const CAMERA_SHARE: f32 = 0.5;

/// Half size of the box of particles around the camera, m: where a flake's sprite is
/// more than a pixel or two at 720 lines (beyond it the world emitter's particles,
/// splatted, and the fog carry the distance).
pub const CAMERA_VOLUME_HALF_EXTENT_M: Vec3 = Vec3::new(8.0, 6.0, 8.0);

/// What the user chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneOptions {
    /// Particles in all.
    pub particle_budget: u32,
    /// Seed of every random draw.
    pub seed: u32,
    /// Ground/cover texel size, m (the grid side is capped at 1024 texels).
    pub texel_m: f32,
    /// The grids' side, m (`None`: the scene's size, the grid fixed on it). Set,
    /// the cover grid follows the camera over a terrain
    /// (`precip_model::host::CoverWindow`), the cover that leaves it kept beyond
    /// it per place.
    pub grid_side_m: Option<f32>,
    /// Simulated cover days per real second.
    pub cover_days_per_second: f32,
    /// The weather.
    pub weather: Weather,
    /// The camera, or `None` for a view of the whole scene.
    pub camera: Option<Camera>,
}

/// The setup for `scene` (prepared) under `options`.
pub fn scene_setup(scene: PreparedScene, options: &SceneOptions) -> Result<Setup, BackendError> {
    let (lo, hi) = scene
        .land_bounds_m()
        .ok_or(precip_model::SceneError::Empty)?;
    let centre = Vec2::new(0.5 * (lo.x + hi.x), 0.5 * (lo.z + hi.z));
    let side = match options.grid_side_m {
        Some(s) if s.is_finite() && s > 0.0 => s,
        _ => (hi.x - lo.x).max(hi.z - lo.z).max(1.0),
    };
    let texel = if options.texel_m.is_finite() && options.texel_m > 0.0 {
        options.texel_m
    } else {
        0.5
    };
    let texels = ((side / texel).ceil() as u32).clamp(8, 1024);
    let frame = GridFrame::centred(centre, Vec2::splat(side), UVec2::splat(texels));
    let cover_frame =
        GridFrame::centred(centre, Vec2::splat(side), UVec2::splat((texels / 2).max(4)));
    let ground = GroundMap::of_prepared(&scene, frame);
    // On a terrain the emitter starts above its highest point under the grid, and
    // the camera sees to the terrain's far side.
    let (ground_lo, ground_hi) = ground
        .height_m
        .iter()
        .fold((lo.y, hi.y), |(a, b), &h| (a.min(h), b.max(h)));
    let far_m = scene.terrain().map_or(0.0, |t| 1.5 * t.size_m().length());

    let budget = options.particle_budget.max(1);
    let area = side * side;
    // The camera volume first: the weather's physical density of flakes seen one by
    // one, up to its share; the world emitter the rest, when that feeds the cover.
    let box_m3 = 8.0 * CAMERA_VOLUME_HALF_EXTENT_M.element_product();
    let camera_share = (budget as f32 * CAMERA_SHARE) as u32;
    let (camera_physical, _) = options
        .weather
        .simulated_particle_count(box_m3, camera_share);
    let world_particles = budget - camera_physical;
    let world = (world_particles as f32 / area >= MIN_WORLD_DENSITY_PER_M2).then(|| {
        let clearance = 10.0;
        let top = ground_hi + clearance;
        // Over the scene: the emitter is aimed (each particle is born up-wind of
        // where it lands by its own fall's drift; precip_model::birth_on_emitter).
        EmitterSetup {
            emitter: WorldEmitter::horizontal(
                Vec3::new(centre.x, top, centre.y),
                side,
                side,
                top - ground_lo,
            ),
            particle_count: world_particles,
        }
    });
    // Without an emitter the camera volume keeps the whole budget: it is all there is
    // to draw.
    let camera_particles = budget - world.map_or(0, |w| w.particle_count);
    let mut camera = options.camera.unwrap_or_else(|| {
        let look_at = Vec3::new(centre.x, lo.y + 0.2 * (hi.y - lo.y), centre.y);
        let eye = look_at + Vec3::new(0.35, 0.28, 0.8) * side * 0.45;
        Camera {
            position_m: eye,
            forward: look_at - eye,
            far_m: (side * 4.0).max(100.0).max(far_m),
            ..Camera::default()
        }
    });
    camera.far_m = camera.far_m.max(far_m);
    let setup = Setup {
        seed: options.seed,
        weather: options.weather,
        world_emitter: world,
        camera_volume: (camera_particles > 0).then_some(CameraVolumeSetup {
            // Close around the camera, so the flakes that are seen one by one are dense;
            // the world emitter and the fog carry the distance.
            volume: CameraVolume {
                half_extent_m: CAMERA_VOLUME_HALF_EXTENT_M,
                ..CameraVolume::default()
            },
            particle_count: camera_particles,
        }),
        ground,
        cover: CoverSetup {
            time_scale: (options.cover_days_per_second * 86_400.0)
                .clamp(0.0, MOST_COVER_DAYS_PER_SECOND * 86_400.0),
            follows_camera: options.grid_side_m.is_some(),
            ..CoverSetup::real_time(cover_frame)
        },
        wind_volume: precip_model::wind::WindVolumeSpec::default(),
        camera,
        scene: Some(std::sync::Arc::new(scene)),
        render: precip_model::RenderSettings::default(),
    };
    setup.validate(u64::MAX, "the viewer's budget")?;
    Ok(setup)
}

#[cfg(test)]
mod tests {
    use precip_model::scene::builtin::house_on_plane;

    use super::*;

    fn options(budget: u32) -> SceneOptions {
        SceneOptions {
            particle_budget: budget,
            seed: 1,
            texel_m: 0.5,
            grid_side_m: None,
            cover_days_per_second: 0.0,
            weather: Weather::default(),
            camera: None,
        }
    }

    #[test]
    fn small_scenes_get_a_world_emitter_large_ones_only_the_camera_volume() {
        let scene = house_on_plane().prepare().expect("valid").0;
        let setup = scene_setup(scene.clone(), &options(100_000)).expect("valid");
        let (world, camera) = setup.particle_counts();
        assert_eq!(world + camera, 100_000);
        assert!(world > 0 && camera > 0);
        // 1 mm/h at the default −5 °C: ~38 flakes per m³ in 3 072 m³, more than the
        // camera volume's half of the budget.
        assert_eq!(camera, 50_000);
        let mut light = options(100_000);
        light.weather.intensity_mm_per_h = 0.05;
        let setup =
            scene_setup(house_on_plane().prepare().expect("valid").0, &light).expect("valid");
        let (world, camera) = setup.particle_counts();
        let expected = light.weather.simulated_number_density_per_m3() * 3_072.0;
        assert!(
            (camera as f32 - expected).abs() <= 1.0,
            "a light snow's physical {expected} flakes, not the budget: {camera}"
        );
        assert_eq!(world + camera, 100_000, "the rest feeds the cover");
        let setup = scene_setup(scene, &options(1_000)).expect("valid");
        assert_eq!(
            setup.particle_counts(),
            (0, 1_000),
            "40 m needs 3.2k particles: no emitter, the camera volume takes the budget"
        );
        assert_eq!(setup.ground.frame.texels.x, 80, "40 m at 0.5 m");
    }

    #[test]
    fn in_wind_the_emitter_stays_over_the_scene_and_is_aimed() {
        let scene = house_on_plane().prepare().expect("valid").0;
        let mut o = options(100_000);
        o.weather.wind.mean_wind_mps = Vec3::new(3.0, 0.0, 0.0);
        let setup = scene_setup(scene, &o).expect("valid");
        let e = setup.world_emitter.expect("an emitter").emitter;
        assert!(
            e.model.w_axis.x.abs() < 1e-3,
            "centre at x = {}",
            e.model.w_axis.x
        );
        // Its particles are born up-wind of where they land (precip_model::particles::birth):
        // the same draw in calm air lies down-wind by the fall's drift, ≥ 10 m
        // (3 m/s over a fall of ≥ 10 m at ≤ 3 m/s).
        let calm = Weather {
            wind: precip_model::wind::WindField::calm(),
            ..o.weather
        };
        let windy = setup.step_params(&o.weather, Vec3::ZERO, 0.05, 0.0);
        let still = setup.step_params(&calm, Vec3::ZERO, 0.05, 0.0);
        for index in 0..8 {
            let born =
                precip_model::particles::birth::birth_on_emitter(index, 0, &windy, &setup.ground);
            let aim =
                precip_model::particles::birth::birth_on_emitter(index, 0, &still, &setup.ground);
            assert!(
                born.position_m.x < aim.position_m.x - 10.0,
                "born at x = {}, aimed at {}",
                born.position_m.x,
                aim.position_m.x
            );
        }
    }
}
