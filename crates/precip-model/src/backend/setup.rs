//! [`Setup`]: everything `configure` needs, validated once at the boundary, and the
//! derived values every backend computes the same way (cover grid, step uniforms).

use std::sync::Arc;

use glam::{UVec2, Vec2, Vec3};
use precip_cover::{
    CoverAir, CoverFeed, CoverGrid, CoverParams, CoverStepParams, DepositBuffer, GridFrame,
    generate_threshold_masks,
};
use precip_wind::WindVolumeSpec;
use rayon::prelude::*;

use crate::backend::camera::Camera;
use crate::backend::error::BackendError;
use crate::drawing::render::RenderSettings;
use crate::particles::emitter::{CameraVolume, WorldEmitter};
use crate::particles::ground::GroundMap;
use crate::particles::kind::SpeciesParams;
use crate::particles::step::StepParams;
use crate::physics::drifting_snow::{DRIFTING_SNOW_LAYER_TOP_M, DRIFTING_SNOW_SHARE};
use crate::physics::grain::{Grain, lifted_flux_kg_per_m2_s, sand_friction_velocity_mps};
use crate::scene::{PreparedScene, Scene, SceneReport};
use crate::weather::Weather;

/// Seconds per day.
pub const SECONDS_PER_DAY: f32 = 86_400.0;

/// The world emitter and its share of the particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmitterSetup {
    /// The rectangle.
    pub emitter: WorldEmitter,
    /// Particles it owns.
    pub particle_count: u32,
}

/// The camera volume and its share of the particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraVolumeSetup {
    /// The box.
    pub volume: CameraVolume,
    /// Particles it owns.
    pub particle_count: u32,
}

/// The snow cover's grid and model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoverSetup {
    /// Where the cover grid lies (usually the ground map's frame).
    pub frame: GridFrame,
    /// The model's constants.
    pub params: CoverParams,
    /// Seed of the threshold masks.
    pub mask_seed: u32,
    /// Size of the masks' patches, m.
    pub mask_patch_scale_m: f32,
    /// Cover seconds per simulated second, `[0, 10⁷]`: 1 is real time, 86400 a day
    /// per second. Landed water is scaled by it too, so accumulation and melt keep
    /// their proportions.
    pub time_scale: f32,
    /// Over a terrain, the grid follows the camera (by whole tiles, when the
    /// camera is past a quarter of its side from its centre), the cover that
    /// leaves it kept beyond it per place ([`crate::host::CoverWindow`]); else it
    /// stays where it is. Meant for a grid wide against the camera's view of the
    /// ground (a flight's, a drive's): a grid round a small scene, seen from
    /// outside it, would leave the scene.
    pub follows_camera: bool,
}

impl CoverSetup {
    /// A real-time cover over `frame` with default constants.
    #[must_use]
    pub fn real_time(frame: GridFrame) -> Self {
        Self {
            frame,
            params: CoverParams::default(),
            mask_seed: 0,
            mask_patch_scale_m: 8.0,
            time_scale: 1.0,
            follows_camera: false,
        }
    }
}

/// Everything a backend needs to start.
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    /// Seed of every random draw.
    pub seed: u32,
    /// The initial weather.
    pub weather: Weather,
    /// Particles that fall on the scene and feed the cover.
    pub world_emitter: Option<EmitterSetup>,
    /// Particles that follow the camera.
    pub camera_volume: Option<CameraVolumeSetup>,
    /// The scene from above.
    pub ground: GroundMap,
    /// The snow cover.
    pub cover: CoverSetup,
    /// Size of the wind volume.
    pub wind_volume: WindVolumeSpec,
    /// The initial camera.
    pub camera: Camera,
    /// The scene drawn under the precipitation, prepared ([`Scene::prepare`]); `None`
    /// draws the precipitation alone. Its top-down view should be `ground`
    /// ([`Setup::over_scene`] does both).
    pub scene: Option<Arc<PreparedScene>>,
    /// How frames look.
    pub render: RenderSettings,
}

impl Setup {
    /// Snowfall over flat eligible ground: a square of `extent_m` at height 0 with a
    /// cover grid of `texels` per side, a world emitter over all of it at
    /// `emitter_height_m` with `particle_count` particles, and no camera volume.
    #[must_use]
    pub fn over_flat_ground(
        extent_m: f32,
        texels: u32,
        emitter_height_m: f32,
        particle_count: u32,
    ) -> Self {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(extent_m), UVec2::splat(texels));
        Self {
            seed: 1,
            weather: Weather::default(),
            world_emitter: Some(EmitterSetup {
                emitter: WorldEmitter::horizontal(
                    Vec3::new(0.0, emitter_height_m, 0.0),
                    extent_m,
                    extent_m,
                    emitter_height_m,
                ),
                particle_count,
            }),
            camera_volume: None,
            ground: GroundMap::flat(frame, 0.0, 1.0),
            cover: CoverSetup::real_time(frame),
            wind_volume: WindVolumeSpec::default(),
            camera: Camera::default(),
            scene: None,
            render: RenderSettings::default(),
        }
    }

    /// Snowfall onto `scene`: the scene is prepared (validated, completed), the ground
    /// map is its top-down view on a square grid of `texels` a side around it (with a
    /// margin of a tenth of its size), the cover grid covers the same square at half
    /// that resolution (each cover texel gathers four ground texels' landings, so the
    /// pack is less grainy), and a world emitter
    /// of `particle_count` particles covers it from `emitter_clearance_m` above its
    /// highest point. The camera looks at the scene from the south-east.
    pub fn over_scene(
        scene: Scene,
        texels: u32,
        emitter_clearance_m: f32,
        particle_count: u32,
    ) -> Result<(Self, SceneReport), BackendError> {
        let (scene, report) = scene.prepare()?;
        let (lo, hi) = scene
            .land_bounds_m()
            .ok_or(crate::scene::SceneError::Empty)?;
        let centre = Vec2::new(0.5 * (lo.x + hi.x), 0.5 * (lo.z + hi.z));
        let side = (hi.x - lo.x).max(hi.z - lo.z).max(1.0) * 1.1;
        let frame = GridFrame::centred(centre, Vec2::splat(side), UVec2::splat(texels));
        frame.validate("ground.frame")?;
        let ground = GroundMap::from_scene(&scene, frame);
        let top = hi.y + emitter_clearance_m.max(1.0);
        let emitter =
            WorldEmitter::horizontal(Vec3::new(centre.x, top, centre.y), side, side, top - lo.y);
        let look_at = Vec3::new(centre.x, lo.y + 0.25 * (hi.y - lo.y), centre.y);
        let eye = look_at + Vec3::new(0.45, 0.3, 0.75) * side * 0.6;
        let setup = Self {
            seed: 1,
            weather: Weather::default(),
            world_emitter: Some(EmitterSetup {
                emitter,
                particle_count,
            }),
            camera_volume: None,
            ground,
            cover: CoverSetup::real_time(GridFrame::centred(
                centre,
                Vec2::splat(side),
                UVec2::splat((texels / 2).max(1)),
            )),
            wind_volume: WindVolumeSpec::default(),
            camera: Camera {
                position_m: eye,
                forward: look_at - eye,
                ..Camera::default()
            },
            scene: Some(Arc::new(scene)),
            render: RenderSettings::default(),
        };
        Ok((setup, report))
    }

    /// The box the shadow map and the renderer must enclose: the scene's bounds, or
    /// the ground map's area when there is no scene, m.
    #[must_use]
    pub fn scene_bounds_m(&self) -> (Vec3, Vec3) {
        if let Some((lo, hi)) = self.scene.as_ref().and_then(|s| s.land_bounds_m()) {
            return (lo, hi);
        }
        let f = self.ground.frame;
        let floor = self.ground.floor_m();
        let top = self.ground.height_m.iter().copied().fold(floor, f32::max);
        (
            Vec3::new(f.origin_m.x, floor, f.origin_m.y),
            Vec3::new(
                f.origin_m.x + f.size_m.x,
                top + 1.0,
                f.origin_m.y + f.size_m.y,
            ),
        )
    }

    /// World-emitter and camera-volume particle counts.
    #[must_use]
    pub fn particle_counts(&self) -> (u32, u32) {
        (
            self.world_emitter.map_or(0, |e| e.particle_count),
            self.camera_volume.map_or(0, |c| c.particle_count),
        )
    }

    /// Checks everything against a backend holding at most `max_particles`.
    pub fn validate(&self, max_particles: u64, limit: &str) -> Result<(), BackendError> {
        let (world, camera) = self.particle_counts();
        let total = u64::from(world) + u64::from(camera);
        if total == 0 {
            return Err(BackendError::ZeroCapacity);
        }
        if total > max_particles {
            return Err(BackendError::CapacityTooLarge {
                requested: total,
                max: max_particles,
                limit: limit.to_owned(),
            });
        }
        self.weather.validate()?;
        if let Some(e) = &self.world_emitter {
            e.emitter.validate()?;
        }
        if let Some(c) = &self.camera_volume {
            c.volume.validate()?;
        }
        self.ground.validate()?;
        self.cover.frame.validate("cover.frame")?;
        self.cover.params.validate()?;
        if !(self.cover.mask_patch_scale_m.is_finite()
            && (0.01..=1.0e5).contains(&self.cover.mask_patch_scale_m))
        {
            return Err(BackendError::Setup {
                field: "cover.mask_patch_scale_m",
                problem: format!(
                    "= {} must be in [0.01, 100000] m",
                    self.cover.mask_patch_scale_m
                ),
            });
        }
        if !(self.cover.time_scale.is_finite() && (0.0..=1.0e7).contains(&self.cover.time_scale)) {
            return Err(BackendError::Setup {
                field: "cover.time_scale",
                problem: format!(
                    "= {} must be in [0, 10000000] (1 = real time, 86400 = a day per second)",
                    self.cover.time_scale
                ),
            });
        }
        self.wind_volume.validate()?;
        self.camera.validate()?;
        self.render.validate()?;
        Ok(())
    }

    /// The bare cover grid: eligibility, height and surface from the ground map under
    /// each texel's centre, fed by particles where the world emitter's footprint
    /// covers it, else by the weather's rate.
    pub fn initial_cover(&self) -> Result<CoverGrid, BackendError> {
        self.bare_cover_over(self.cover.frame)
    }

    /// [`Setup::initial_cover`] over `frame` (a grid, or a strip of one that
    /// enters a moving grid: its masks ranked over it alone).
    pub fn bare_cover_over(&self, frame: GridFrame) -> Result<CoverGrid, BackendError> {
        let n = frame.texel_count();
        let centres: Vec<Vec2> = (0..n)
            .into_par_iter()
            .map(|i| frame.texel_centre(i))
            .collect();
        let eligibility: Vec<f32> = centres
            .par_iter()
            .map(|&c| self.ground.eligibility_at(c))
            .collect();
        let feed: Vec<CoverFeed> = centres.par_iter().map(|&c| self.feed_at(c)).collect();
        let masks =
            generate_threshold_masks(&frame, self.cover.mask_seed, self.cover.mask_patch_scale_m);
        let floor = self.ground.floor_m();
        let heights: Vec<f32> = centres
            .par_iter()
            .map(|&c| self.ground.height_at(c).unwrap_or(floor))
            .collect();
        let surfaces: Vec<_> = centres
            .par_iter()
            .map(|&c| self.ground.surface_at(c))
            .collect();
        Ok(CoverGrid::new(frame, &eligibility, &masks, &feed)?.with_ground(&heights, &surfaces)?)
    }

    /// Where a cover texel centred at (x, z) takes its snow from: the particles
    /// where the world emitter's footprint covers it, else the weather's rate.
    #[must_use]
    pub fn feed_at(&self, centre_m: Vec2) -> CoverFeed {
        match &self.world_emitter {
            Some(e) if e.particle_count > 0 && e.emitter.footprint_contains(centre_m) => {
                CoverFeed::Particles
            }
            _ => CoverFeed::WeatherRate,
        }
    }

    /// The cover kernel's block for a sub-step of `dt_s` seconds under `weather`: the
    /// weather's rates in mm/day, and the step in days of cover time.
    #[must_use]
    pub fn cover_step_params(&self, weather: &Weather, dt_s: f32) -> CoverStepParams {
        CoverStepParams::new(
            &self.cover.params,
            CoverAir {
                snow_rate_mm_per_day: weather.channel_rate_mm_per_h(DepositBuffer::SNOW) * 24.0,
                rain_rate_mm_per_day: weather.channel_rate_mm_per_h(DepositBuffer::RAIN) * 24.0,
                air_temperature_c: weather.air_temperature_c,
                relative_humidity: weather.relative_humidity,
                wind_speed_mps: weather.ground_wind_speed_mps(),
                wind_mps: [weather.wind.mean_wind_mps.x, weather.wind.mean_wind_mps.z],
            },
            dt_s * self.cover.time_scale / SECONDS_PER_DAY,
            &self.cover.frame,
        )
    }

    /// The grids the particle kernels read (the wave grid over the cover texels
    /// whose surface is water: computed here, once a configure).
    #[must_use]
    pub fn frames(&self) -> crate::host::Frames {
        let cover = self.cover.frame;
        let water = (0..cover.texel_count()).filter(|&i| {
            self.ground.surface_at(cover.texel_centre(i)) == precip_cover::Surface::Water
        });
        crate::host::Frames {
            ground: self.ground.frame,
            cover,
            waves: crate::physics::water_waves::wave_frame_over(&cover, water),
        }
    }

    /// The uniform block of a step of `dt_s` (it scans the ground map for its floor:
    /// compute it once per weather change and set the per-sub-step fields with
    /// [`StepParams::at`]) starting at `time_s` under `weather` with
    /// the camera volume centred at `camera_centre_m`.
    #[must_use]
    pub fn step_params(
        &self,
        weather: &Weather,
        camera_centre_m: Vec3,
        dt_s: f32,
        time_s: f32,
    ) -> StepParams {
        let (world_count, camera_count) = self.particle_counts();
        let emitter = self.world_emitter.map(|e| e.emitter);
        let lift = self.grain_lift(weather, world_count);
        let sky_count = lift.lift_from;
        let water_per_particle_kg_per_s = match emitter {
            Some(e) if sky_count > 0 => {
                weather.intensity_mm_per_h / 3600.0 * e.horizontal_area_m2() / sky_count as f32
            }
            _ => 0.0,
        };
        let volume = self.camera_volume.map(|c| c.volume).unwrap_or_default();
        let pools = self.pool_drawing(weather, camera_centre_m);
        let e = emitter.unwrap_or_else(|| WorldEmitter::horizontal(Vec3::ZERO, 1.0, 1.0, 1.0));
        StepParams {
            emitter_model: e.model,
            emitter_size_m: Vec2::new(e.width_m, e.height_m),
            emitter_life_time_s: e.life_time_s,
            emitter_velocity_spread_mps: e.velocity_spread_mps,
            emitter_velocity_mps: e.initial_velocity_mps,
            water_per_particle_kg_per_s,
            camera_centre_m,
            dt_s,
            camera_half_extent_m: volume.half_extent_m,
            time_s,
            mean_wind_mps: weather.wind.mean_wind_mps,
            air_temperature_c: weather.air_temperature_c,
            world_rotation: Vec2::new(e.rotation_amplitude_rad, e.rotation_speed_rad_per_s),
            camera_rotation: Vec2::new(
                volume.rotation_amplitude_rad,
                volume.rotation_speed_rad_per_s,
            ),
            seed: self.seed,
            world_count,
            particle_count: world_count.saturating_add(camera_count),
            snow_is_wet: u32::from(weather.snow_is_wet()),
            deposit_scale_mm_per_kg: self.cover.time_scale / self.cover.frame.texel_area_m2(),
            ground_floor_m: self.ground.floor_m(),
            lift_from: lift.lift_from,
            lift_per_particle_kg_per_s: lift.per_particle_kg_per_s,
            friction_velocity_mps: lift.friction_velocity_mps,
            lift_layer_top_m: lift.layer_top_m,
            grain_suspended: u32::from(lift.suspended),
            flow_ceiling_m: crate::physics::terrain_flow::flow_ceiling_m(&self.ground),
            lift_area_min_m: lift.area_min_m,
            lift_area_max_m: lift.area_max_m,
            wall_rebound_speed_mps: if weather.snow_is_wet() {
                precip_cover::blowing::WET_SNOW_THRESHOLD_WIND_MPS
            } else {
                precip_cover::blowing::dry_snow_threshold_wind_mps(weather.air_temperature_c)
            },
            // What rests (particles::step, "Resting particles"): the sky while it
            // carries and shows nothing, the camera volume's particles not drawn.
            step_first: if water_per_particle_kg_per_s == 0.0 && pools.world_multiplicity == 0.0 {
                lift.lift_from
            } else {
                0
            },
            step_end: pools.camera_drawn_end,
            reserved2: 0,
            species: SpeciesParams::of_weather(weather, lift.grain),
        }
    }

    /// How sand or dust weather shares the world particles between the grains
    /// settling from the sky (born on the emitter) and the grains the wind lifts
    /// from the erodible ground ([`crate::physics::grain`]), in proportion to their mass
    /// fluxes: the sky's `R·A` (R the weather's rate, A the emitter's ground area)
    /// and the ground's `F·A_e` (F the lifted flux at the wind's friction velocity
    /// over sand, `A_e` the map's erodible area). Each pool's particles gather their
    /// pool's flux over their count, so the grains landed and in the air add up to
    /// what the two sources gave. Snow weather in a wind that can lift the snow sets
    /// a share aside for drifting snow instead ([`crate::physics::drifting_snow`]).
    #[must_use]
    pub fn grain_lift(&self, weather: &Weather, world_count: u32) -> GrainLift {
        let none = GrainLift {
            grain: weather.grains(),
            lift_from: world_count,
            ..GrainLift::default()
        };
        let Some(e) = self.world_emitter else {
            return none;
        };
        let Some(grain) = weather.grains() else {
            return self.drifting_snow(weather, world_count).unwrap_or(none);
        };
        let friction_velocity_mps = sand_friction_velocity_mps(weather.ground_wind_speed_mps());
        let frame = self.ground.frame;
        let half = 0.5 * frame.size_m / frame.texels.as_vec2();
        let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        for i in 0..frame.texel_count() {
            let c = frame.texel_centre(i);
            if self.ground.erodibility_at(c) > 0.0 {
                lo = lo.min(c - half);
                hi = hi.max(c + half);
            }
        }
        let lifted_kg_s =
            lifted_flux_kg_per_m2_s(&grain, friction_velocity_mps) * self.ground.erodible_area_m2();
        let sky_kg_s = weather.grain_rate_kg_per_m2_h() / 3600.0 * e.emitter.horizontal_area_m2();
        if !(lifted_kg_s > 0.0 && lo.x <= hi.x) || world_count == 0 {
            return none;
        }
        let lift_count = if sky_kg_s > 0.0 && world_count >= 2 {
            let share = lifted_kg_s / (lifted_kg_s + sky_kg_s);
            ((world_count as f32 * share).round() as u32).clamp(1, world_count - 1)
        } else {
            world_count
        };
        let layer_top_m = (e.emitter.model.w_axis.y - self.ground.floor_m()).max(1.0);
        GrainLift {
            grain: Some(grain),
            lift_from: world_count - lift_count,
            per_particle_kg_per_s: lifted_kg_s / lift_count as f32,
            friction_velocity_mps,
            layer_top_m,
            suspended: grain.is_suspended_by(friction_velocity_mps),
            area_min_m: lo,
            area_max_m: hi,
            lifted_kg_per_s: lifted_kg_s,
        }
    }
}

impl Setup {
    /// The drifting-snow pool of snow weather ([`crate::physics::drifting_snow`]): a share of
    /// the world particles when the mean wind reaches 80 % of the snow's transport
    /// threshold (its gusts pass it), carrying no mass, born over the cover grid;
    /// `None` otherwise.
    fn drifting_snow(&self, weather: &Weather, world_count: u32) -> Option<GrainLift> {
        let snow_only = weather.snow_fraction() >= 1.0;
        let wind = weather.ground_wind_speed_mps();
        let threshold = if weather.snow_is_wet() {
            precip_cover::blowing::WET_SNOW_THRESHOLD_WIND_MPS
        } else {
            precip_cover::blowing::dry_snow_threshold_wind_mps(weather.air_temperature_c)
        };
        let count = (world_count as f32 * DRIFTING_SNOW_SHARE) as u32;
        if !(snow_only && wind >= 0.8 * threshold && count > 0 && count < world_count) {
            return None;
        }
        let frame = self.cover.frame;
        Some(GrainLift {
            grain: None,
            lift_from: world_count - count,
            per_particle_kg_per_s: 0.0,
            friction_velocity_mps: precip_cover::blowing::friction_velocity_mps(wind),
            layer_top_m: DRIFTING_SNOW_LAYER_TOP_M,
            suspended: true,
            area_min_m: frame.origin_m,
            area_max_m: frame.origin_m + frame.size_m,
            lifted_kg_per_s: 0.0,
        })
    }
}

/// Sand, dust or drifting snow lifted from the ground ([`Setup::grain_lift`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GrainLift {
    /// The weather's grains (`None`: snow and rain).
    pub grain: Option<Grain>,
    /// World particles from this index on are lifted (`world_count`: none).
    pub lift_from: u32,
    /// Grains each lifted particle gathers per second, kg/s.
    pub per_particle_kg_per_s: f32,
    /// The wind's friction velocity over sand, m/s.
    pub friction_velocity_mps: f32,
    /// Top of the suspended layer, m above the ground.
    pub layer_top_m: f32,
    /// Whether the lifted grains stay suspended (dust) or saltate (sand).
    pub suspended: bool,
    /// The erodible texels' bounds, min (x, z), m.
    pub area_min_m: Vec2,
    /// The erodible texels' bounds, max (x, z), m.
    pub area_max_m: Vec2,
    /// Grains the wind lifts from the map each second, kg/s.
    pub lifted_kg_per_s: f32,
}
