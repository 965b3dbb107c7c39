//! [`HostState`]: what a configured backend knows on the host — the setup, the
//! weather, the baked wind volume, the camera and the clock — and every uniform
//! block computed from them, once, for the CPU reference and every GPU backend.

use std::sync::Arc;

use glam::{IVec2, Vec2, Vec3};
use precip_cover::{CoverGrid, CoverStepParams, GridFrame};
use precip_wind::{WindParams, WindVolume};

use crate::backend::camera::{Camera, View};
use crate::backend::error::BackendError;
use crate::backend::setup::Setup;
use crate::backend::substeps;
use crate::drawing::multiplicity::PoolDrawing;
use crate::drawing::render::{RenderParams, RenderSettings};
use crate::host::activity::Activity;
use crate::host::layout::Frames;
use crate::particles::step::StepParams;
use crate::physics::drag::MAX_SUBSTEP_S;
use crate::scene::terrain::{CLIPMAP_WINDOW_SLOTS, ClipmapRows, LandCoverRows, TerrainPyramid};
use crate::sensors::lidar::UnresolvedAir;
use crate::sensors::optics::Optics;
use crate::weather::Weather;
use precip_cover::{CoverInput, DepositBuffer};

use crate::drawing::clouds::cloud_drift_m;
use crate::host::cover_window::{CoverWindow, moved_cover};
use crate::host::far_cover::{FarCover, FarCoverRows};
use crate::host::far_water::{Shafts, WaterBeyond};

/// The host side of a configured simulation.
///
/// Every backend holds one: `configure` makes it ([`HostState::configure`]),
/// `set_weather` and `set_camera` change it, and `step` asks it for the sub-steps'
/// blocks ([`HostState::substeps`]) and then advances its clock
/// ([`HostState::advance`]). What a backend uploads is what this returns, so the
/// backends cannot disagree on a uniform.
#[derive(Debug, Clone)]
pub struct HostState {
    setup: Setup,
    weather: Weather,
    wind: WindVolume,
    camera: Camera,
    /// The step block of the current weather; each sub-step sets the camera, its
    /// length and its time ([`StepParams::at`]). Computing it scans the ground map,
    /// so it is made once per weather change.
    step_template: StepParams,
    /// How the pools are drawn under the current weather (their multiplicities); it
    /// scans the ground map too, so it is made once per weather change and each frame
    /// only moves the camera box to the camera.
    pools: PoolDrawing,
    /// Which of the cover's features may have work, from every weather since
    /// configure.
    activity: Activity,
    /// The terrain's pyramid for the GPU's clipmap, made once per configuration.
    terrain: Option<Arc<TerrainPyramid>>,
    /// The terrain's land cover for the GPU (pixels, classes), made once per
    /// configuration.
    land_cover: Option<Arc<(glam::UVec2, Vec<f32>)>>,
    /// The cover beyond the cover grid, per place ([`HostState::far_cover`]).
    far_cover: FarCover,
    /// Where the cover grid is, as it follows the camera over a terrain.
    window: CoverWindow,
    /// The water bodies' wave grid, made once at configure (the water bodies
    /// stay where the scene has them when the cover grid moves).
    waves: GridFrame,
    time_s: f64,
}

/// The uniform blocks of one sub-step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubStepBlocks {
    /// The particle kernels' block.
    pub step: StepParams,
    /// The cover kernels' block.
    pub cover: CoverStepParams,
}

/// A step split into sub-steps ([`substeps`]), each with its blocks, and the clock
/// after the last.
#[derive(Debug, Clone, PartialEq)]
pub struct SubSteps {
    /// Length of each sub-step, s.
    pub dt_s: f32,
    /// The blocks, in order.
    pub blocks: Vec<SubStepBlocks>,
    /// The simulated time after the last sub-step, s.
    end_time_s: f64,
}

/// What a weather change asks of a backend's device.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[must_use]
pub struct WeatherChange {
    /// The wind volume was baked again: upload its texels
    /// ([`HostState::wind`]`.as_bytes()`). Otherwise only the wind's block changed.
    pub wind_rebaked: bool,
}

impl HostState {
    /// The host state of `setup`: its wind baked, its blocks computed, the clock at 0.
    /// The caller has checked `setup` against its device's limits.
    pub fn configure(setup: &Setup) -> Result<Self, BackendError> {
        let wind = WindVolume::bake(&setup.weather.wind, &setup.wind_volume)?;
        Ok(Self {
            step_template: setup.step_params(&setup.weather, Vec3::ZERO, MAX_SUBSTEP_S, 0.0),
            pools: setup.pool_drawing(&setup.weather, Vec3::ZERO),
            activity: Activity::default().after(&setup.weather),
            terrain: setup
                .scene
                .as_ref()
                .and_then(|s| s.terrain())
                .map(|t| Arc::new(TerrainPyramid::of(t))),
            land_cover: setup
                .scene
                .as_ref()
                .and_then(|s| s.terrain())
                .and_then(|t| t.land_cover())
                .map(|l| Arc::new(l.gpu_samples())),
            far_cover: setup
                .scene
                .as_ref()
                .and_then(|s| s.terrain())
                .map_or_else(FarCover::everywhere, |t| {
                    FarCover::over(t, &setup.cover.frame)
                }),
            window: CoverWindow::of(setup),
            waves: setup.frames().waves,
            setup: setup.clone(),
            weather: setup.weather,
            wind,
            camera: setup.camera,
            time_s: 0.0,
        })
    }

    /// Where the cover grid should move to follow the camera, in cover texels from
    /// where it was configured ([`CoverWindow::shift_for`]); `None` while it stays.
    /// A backend that gets one moves its grid before the step
    /// ([`HostState::move_cover_grid`]).
    #[must_use]
    pub fn cover_grid_move(&self) -> Option<IVec2> {
        let at = self.camera.position_m;
        self.window.shift_for(Vec2::new(at.x, at.z))
    }

    /// Moves the cover grid to `shift` texels from where it was configured, its
    /// cover now `cover` (the backend's texels): the setup's ground map made
    /// anew under it, the world emitter with it, the texels that leave it taken
    /// into the far cover and those that enter it lent the far cover's
    /// ([`crate::host::cover_window`]). Returns the moved grid's texels for the
    /// backend to hold. Nothing changes on an error.
    pub fn move_cover_grid(
        &mut self,
        shift: IVec2,
        cover: &CoverGrid,
    ) -> Result<CoverGrid, BackendError> {
        let setup = self
            .window
            .setup_at(&self.setup, shift)
            .ok_or(BackendError::NotSupported {
                backend: "host",
                operation: "moving the cover grid without a scene",
            })?;
        let mut far = self.far_cover.clone();
        let moved = moved_cover(cover, &setup, &mut far)?;
        let centre = setup.cover.frame.origin_m + 0.5 * setup.cover.frame.size_m;
        if let Some(site) = setup
            .scene
            .as_ref()
            .and_then(|s| s.terrain())
            .and_then(|t| t.height_at(centre))
        {
            far.move_site(site);
        }
        self.far_cover = far;
        // What the texels brought in may hold (a colder cell's snow under rain
        // here, the land beyond's showers' water): the kernels that move them run.
        let holds = |f: fn(&precip_cover::CoverTexel) -> bool| moved.texels.iter().any(f);
        self.activity = Activity {
            snow_may_lie: self.activity.snow_may_lie || holds(|t| t.swe_mm > 0.0),
            water_may_stand: self.activity.water_may_stand
                || holds(|t| t.standing_mm > 0.0 || t.film_mm > 0.0 || t.liquid_mm > 0.0),
        };
        self.step_template = setup.step_params(&self.weather, Vec3::ZERO, MAX_SUBSTEP_S, 0.0);
        self.pools = setup.pool_drawing(&self.weather, Vec3::ZERO);
        self.setup = setup;
        self.window.moved_to(shift);
        Ok(moved)
    }

    /// Where the cover grid is ([`CoverWindow`]): its offset from where it was
    /// configured and how many times it moved.
    #[must_use]
    pub fn cover_window(&self) -> &CoverWindow {
        &self.window
    }

    /// Takes a new weather: validated, the wind re-baked only if its gusts changed.
    pub fn set_weather(&mut self, weather: &Weather) -> Result<WeatherChange, BackendError> {
        weather.validate()?;
        let (wind, wind_rebaked) = self.wind.for_field(&weather.wind)?;
        self.wind = wind;
        self.step_template = self
            .setup
            .step_params(weather, Vec3::ZERO, MAX_SUBSTEP_S, 0.0);
        self.pools = self.setup.pool_drawing(weather, Vec3::ZERO);
        self.activity = self.activity.after(weather);
        self.weather = *weather;
        Ok(WeatherChange { wind_rebaked })
    }

    /// Which of the cover's features may have work ([`Activity`]).
    #[must_use]
    pub fn activity(&self) -> Activity {
        self.activity
    }

    /// Moves the camera (validated).
    pub fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        camera.validate()?;
        self.camera = *camera;
        Ok(())
    }

    /// Draws rain and snow at `resolution` from the next frame's block on.
    pub fn set_particle_resolution(&mut self, resolution: crate::ParticleResolution) {
        self.setup.render.particle_resolution = resolution;
    }

    /// Keeps a stale shadow map for up to `frames` frames from the next frame on
    /// (validated as `RenderSettings::shadow_refresh_frames`).
    pub fn set_shadow_refresh_frames(&mut self, frames: u32) -> Result<(), BackendError> {
        self.set_look(RenderSettings {
            shadow_refresh_frames: frames,
            ..self.setup.render
        })
    }

    /// Takes the sun's direction and the clear air's extinction (validated; `None`
    /// keeps the one in effect), from the next frame on.
    pub fn set_atmosphere(
        &mut self,
        to_sun: Option<Vec3>,
        clear_air_extinction_per_m: Option<f32>,
    ) -> Result<(), BackendError> {
        let render = self.setup.render;
        self.set_look(RenderSettings {
            to_sun: to_sun.unwrap_or(render.to_sun),
            clear_air_extinction_per_m: clear_air_extinction_per_m
                .unwrap_or(render.clear_air_extinction_per_m),
            ..render
        })
    }

    /// Takes cloud layers (validated; none: no clouds), from the next frame on.
    pub fn set_cloud_layers(
        &mut self,
        cloud_layers: crate::drawing::clouds::CloudLayers,
    ) -> Result<(), BackendError> {
        self.set_look(RenderSettings {
            cloud_layers,
            ..self.setup.render
        })
    }

    /// Takes a fog layer (validated) or none, from the next frame on.
    pub fn set_fog_layer(
        &mut self,
        fog_layer: Option<crate::drawing::fog_layer::FogLayer>,
    ) -> Result<(), BackendError> {
        self.set_look(RenderSettings {
            fog_layer,
            ..self.setup.render
        })
    }

    /// Takes `render` if it is valid (what may change between frames without
    /// configuring again: the callers above pick which fields).
    fn set_look(&mut self, render: RenderSettings) -> Result<(), BackendError> {
        render.validate()?;
        self.setup.render = render;
        Ok(())
    }

    /// The blocks of a step of `dt_s` (validated), from the clock now; the clock
    /// moves only with [`HostState::advance`], once the backend has the step under way.
    pub fn substeps(&self, dt_s: f32) -> Result<SubSteps, BackendError> {
        let (count, h) = substeps(dt_s)?;
        let cover = self.setup.cover_step_params(&self.weather, h);
        let mut time_s = self.time_s;
        let blocks = (0..count)
            .map(|_| {
                let step = self
                    .step_template
                    .at(self.camera.position_m, h, time_s as f32);
                time_s += f64::from(h);
                SubStepBlocks { step, cover }
            })
            .collect();
        Ok(SubSteps {
            dt_s: h,
            blocks,
            end_time_s: time_s,
        })
    }

    /// The clock after `steps`, and the far cover given their weather (it steps
    /// every [`crate::host::FAR_STEP_EVERY`] steps).
    pub fn advance(&mut self, steps: &SubSteps) {
        self.time_s = steps.end_time_s;
        let w = &self.weather;
        let dt_days =
            steps.dt_s * steps.blocks.len() as f32 * self.setup.cover.time_scale / 86_400.0;
        let input = CoverInput {
            snow_mm: w.channel_rate_mm_per_h(DepositBuffer::SNOW) * 24.0 * dt_days,
            rain_mm: w.channel_rate_mm_per_h(DepositBuffer::RAIN) * 24.0 * dt_days,
            air_temperature_c: w.air_temperature_c,
            relative_humidity: w.relative_humidity,
            wind_speed_mps: w.ground_wind_speed_mps(),
            dt_days,
        };
        // Beyond the camera's surroundings the land takes the rate set for it, under
        // the lowest layer's clouds alone (model (6.16), as the shafts are drawn).
        let render = &self.setup.render;
        let there = Weather {
            intensity_mm_per_h: render.rate_beyond_mm_per_h.unwrap_or(w.intensity_mm_per_h),
            ..*w
        };
        let beyond = WaterBeyond {
            camera_xz_m: Vec2::new(self.camera.position_m.x, self.camera.position_m.z),
            snow_mm: there.channel_rate_mm_per_h(DepositBuffer::SNOW) * 24.0 * dt_days,
            rain_mm: there.channel_rate_mm_per_h(DepositBuffer::RAIN) * 24.0 * dt_days,
            shafts: render.cloud_layers.lowest().map(|lowest| Shafts {
                coverage: lowest.coverage,
                drift_m: cloud_drift_m(w.wind.mean_wind_mps, self.time_s as f32),
            }),
        };
        self.far_cover
            .add_step(input, beyond, render.to_sun, &self.setup.cover.params);
    }

    /// The cover beyond the cover grid (a scene's far meshes, a terrain's
    /// kilometres), per place ([`FarCover`]): cells over the terrain, each with a
    /// texel of each of [`crate::host::FAR_COVER_SURFACES`] under the weather since configure at
    /// the cell's height, its snow fallen at the weather's rate and melted, settled
    /// and aged, its surface wetted and dried, by the grid's own texel physics —
    /// no particles, no drift or flow; each texel keeps the books of its surface's
    /// land in its cell off the grid ([`HostState::far_cover_totals`]). The
    /// renderer shades what lies off the grid with its place's texels of its
    /// surface ([`crate::host::far_cover_slot`]), each fragment's slope, land class and patch
    /// noise as on the grid.
    #[must_use]
    pub fn far_cover(&self) -> &FarCover {
        &self.far_cover
    }

    /// The books of the cover beyond the grid: each far texel for the terrain's
    /// land of its surface in its cell off the grid (`None` without a terrain).
    /// With the grid's books they are the whole terrain's.
    #[must_use]
    pub fn far_cover_totals(&self) -> Option<precip_cover::CoverTotals> {
        self.far_cover.totals()
    }

    /// The snow line beyond the grid ([`FarCover::snow_line_m`]), m.
    #[must_use]
    pub fn far_snow_line_m(&self) -> Option<f32> {
        self.far_cover.snow_line_m()
    }

    /// Words of the terrain's windows in the ground buffer (every frame slot's,
    /// [`CLIPMAP_WINDOW_SLOTS`]; 0 without a terrain), after the ground map.
    #[must_use]
    pub fn terrain_window_words(&self) -> u32 {
        self.terrain
            .as_ref()
            .map_or(0, |p| CLIPMAP_WINDOW_SLOTS * p.window_words())
    }

    /// The first word of the far cover's two regions in the ground buffer: after
    /// the ground map, the terrain's windows and its land cover.
    #[must_use]
    pub fn far_cover_first_word(&self) -> u32 {
        self.ground_words()
            + self.terrain_window_words()
            + self.land_cover.as_ref().map_or(0, |l| l.1.len() as u32)
    }

    /// The rows of the frame block that say where the GPU reads the far cover now.
    #[must_use]
    pub fn far_cover_rows(&self) -> FarCoverRows {
        self.far_cover.rows(self.far_cover_first_word())
    }

    /// After a far step, the far cover's rows the GPU lacks and the ground
    /// buffer's word they go to (`None` when it has them). A GPU backend uploads
    /// them after each step; the CPU reference has no use for them.
    pub fn take_far_cover_upload(&mut self) -> Option<(u32, Vec<f32>)> {
        let first = self.far_cover_first_word();
        self.far_cover.take_upload(first)
    }

    /// The rows of the frame block that place the terrain's land cover on the GPU
    /// (zeros without one: every fragment's class is no data).
    #[must_use]
    pub fn land_cover_rows(&self) -> LandCoverRows {
        match (&self.terrain, &self.land_cover, self.terrain_extent_m()) {
            (Some(_), Some(l), Some((corner, size))) => LandCoverRows {
                pixels: glam::UVec4::new(
                    l.0.x,
                    l.0.y,
                    self.ground_words() + self.terrain_window_words(),
                    1,
                ),
                extent_m: glam::Vec4::new(corner.x, corner.y, size.x, size.y),
            },
            _ => LandCoverRows::default(),
        }
    }

    /// The land cover's classes for the GPU, after the pyramid in the ground
    /// buffer, where the terrain has one.
    #[must_use]
    pub fn land_cover_samples(&self) -> Option<&[f32]> {
        self.land_cover.as_ref().map(|l| l.1.as_slice())
    }

    /// The terrain's corner (x, z) and size, m.
    fn terrain_extent_m(&self) -> Option<(Vec2, Vec2)> {
        let t = self.setup.scene.as_ref()?.terrain()?;
        Some((t.corner_m(), t.size_m()))
    }

    /// The block `init_particles` runs with at configure (the particles born warm
    /// around the configured camera).
    #[must_use]
    pub fn init_block(&self) -> StepParams {
        self.step_template
            .at(self.camera.position_m, MAX_SUBSTEP_S, 0.0)
    }

    /// The wind sampler's block.
    #[must_use]
    pub fn wind_params(&self) -> WindParams {
        self.wind.gpu_params()
    }

    /// The grids the particle kernels read.
    #[must_use]
    pub fn frames(&self) -> Frames {
        Frames {
            ground: self.setup.ground.frame,
            cover: self.setup.cover.frame,
            waves: self.waves,
        }
    }

    /// The frame's block for `view`, with the shadow map over `shadow_bounds_m`, for
    /// `particle_count` particles and the water bodies' wave grid `waves`.
    #[must_use]
    pub fn render_params(
        &self,
        view: &View,
        shadow_bounds_m: (Vec3, Vec3),
        particle_count: u32,
        waves: GridFrame,
    ) -> RenderParams {
        self.setup.render_params(
            view,
            &self.weather,
            shadow_bounds_m,
            self.time_s,
            particle_count,
            waves,
            PoolDrawing {
                camera_box_m: self
                    .pools
                    .camera_box_m
                    .map(|(_, half)| (self.camera.position_m, half)),
                ..self.pools
            },
        )
    }

    /// `optics` with the fog layer's and a cloud layer's droplets where the camera
    /// is in them ([`Optics::in_fog`], [`Optics::in_cloud`]).
    #[must_use]
    pub fn with_layers(&self, optics: Optics) -> Optics {
        let render = &self.setup.render;
        let at = self.camera.position_m;
        optics.in_fog(render.fog_layer, at).in_cloud(
            &render.cloud_layers,
            cloud_drift_m(self.weather.wind.mean_wind_mps, self.time_s as f32),
            at,
        )
    }

    /// The air beyond the simulated particles, for LiDAR beams now.
    #[must_use]
    pub fn unresolved_air(&self) -> UnresolvedAir {
        UnresolvedAir::of_configuration(
            &self.setup,
            &self.weather,
            self.step_template,
            self.camera.position_m,
            self.time_s,
        )
    }

    /// The terrain's pyramid the GPU draws it from, where the scene stands on one.
    #[must_use]
    pub fn terrain_pyramid(&self) -> Option<&Arc<TerrainPyramid>> {
        self.terrain.as_ref()
    }

    /// The words of the ground buffer before the terrain's windows
    /// ([`crate::GroundMap::gpu_words`]).
    #[must_use]
    pub fn ground_words(&self) -> u32 {
        2 * self.setup.ground.frame.texel_count() as u32
    }

    /// The clipmap's rows of the frame block for a view from `camera_m` (zeros
    /// without a terrain: nothing drawn), its windows in the first frame slot's
    /// words (a GPU backend moves them to its slot's: `TerrainPyramid::window_words`
    /// further each).
    #[must_use]
    pub fn clipmap_rows(&self, camera_m: Vec3) -> ClipmapRows {
        self.terrain
            .as_ref()
            .map_or_else(ClipmapRows::default, |p| {
                let at = camera_m;
                p.clipmap(
                    at,
                    p.height_under(Vec2::new(at.x, at.z)),
                    self.ground_words(),
                )
            })
    }

    /// The setup it was configured with.
    #[must_use]
    pub fn setup(&self) -> &Setup {
        &self.setup
    }

    /// The weather now.
    #[must_use]
    pub fn weather(&self) -> &Weather {
        &self.weather
    }

    /// The baked wind volume (its texels are the wind texture's).
    #[must_use]
    pub fn wind(&self) -> &WindVolume {
        &self.wind
    }

    /// The camera now.
    #[must_use]
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Simulated time since configure, s.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// The particles in the air under the current weather: the ones a step moves
    /// (the others rest unseen: [`crate::particles::step::stepped_particles`]);
    /// what the beams and the optics read.
    #[must_use]
    pub fn particles_in_the_air(&self) -> std::ops::Range<u32> {
        crate::particles::step::stepped_particles(&self.step_template)
    }

    /// The step block of the current weather, before a sub-step's camera, length and
    /// time are set.
    #[must_use]
    pub fn step_template(&self) -> StepParams {
        self.step_template
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::MAX_STEP_S;
    use crate::scene::terrain::Terrain;

    fn host() -> HostState {
        HostState::configure(&Setup::over_flat_ground(20.0, 8, 10.0, 256)).expect("a valid setup")
    }

    #[test]
    fn sub_steps_carry_the_clock_and_the_camera() {
        let mut host = host();
        let steps = host.substeps(0.05).expect("a valid step");
        let n = steps.blocks.len();
        assert!(n >= 1 && steps.dt_s <= MAX_SUBSTEP_S);
        for (k, b) in steps.blocks.iter().enumerate() {
            let expected = (k as f64 * f64::from(steps.dt_s)) as f32;
            assert!((b.step.time_s - expected).abs() < 1e-6, "{k}");
            assert_eq!(b.step.camera_centre_m, host.camera().position_m);
            assert!((b.step.dt_s - steps.dt_s).abs() < f32::EPSILON);
        }
        assert!(
            host.time_s().abs() < f64::EPSILON,
            "substeps alone moves no clock"
        );
        host.advance(&steps);
        assert!((host.time_s() - f64::from(steps.dt_s) * n as f64).abs() < 1e-9);
    }

    #[test]
    fn bad_steps_and_weather_leave_the_state_as_it_was() {
        let mut host = host();
        assert!(host.substeps(0.0).is_err());
        assert!(host.substeps(MAX_STEP_S * 2.0).is_err());
        let before = *host.weather();
        let mut bad = before;
        bad.air_temperature_c = f32::NAN;
        assert!(host.set_weather(&bad).is_err());
        assert_eq!(*host.weather(), before);
    }

    #[test]
    fn the_frame_weighs_the_pools_of_the_weather_now_around_the_camera_now() {
        let mut setup = Setup::over_flat_ground(20.0, 8, 10.0, 256);
        setup.camera_volume = Some(crate::CameraVolumeSetup {
            volume: crate::CameraVolume::default(),
            particle_count: 128,
        });
        let mut host = HostState::configure(&setup).expect("a valid setup");
        let view = |camera| View {
            camera,
            width_px: 16,
            height_px: 16,
        };
        let frame = |host: &HostState| {
            host.render_params(
                &view(*host.camera()),
                (Vec3::ZERO, Vec3::ONE),
                384,
                GridFrame::centred(Vec2::ZERO, Vec2::ONE, glam::UVec2::ONE),
            )
        };
        let first = frame(&host);
        assert!(first.camera_box_half_m.w > 0.0 && first.camera_box_centre_m.w > 0.0);
        assert_eq!(
            first.camera_box_centre_m.truncate(),
            host.camera().position_m
        );
        let moved = Camera {
            position_m: Vec3::new(3.0, 4.0, 5.0),
            ..*host.camera()
        };
        host.set_camera(&moved).expect("a valid camera");
        assert_eq!(
            frame(&host).camera_box_centre_m.truncate(),
            moved.position_m
        );
        let dry = Weather {
            intensity_mm_per_h: 0.0,
            ..*host.weather()
        };
        let change = host.set_weather(&dry).expect("a valid weather");
        assert!(!change.wind_rebaked, "the same wind");
        let after = frame(&host);
        assert_eq!(
            (after.camera_box_centre_m.w, after.camera_box_half_m.w),
            (0.0, 0.0)
        );
    }

    #[test]
    fn the_mean_wind_has_one_source() {
        let mut host = host();
        let mut weather = *host.weather();
        weather.wind.mean_wind_mps = Vec3::new(3.0, 0.0, -4.0);
        let change = host.set_weather(&weather).expect("a valid weather");
        assert!(!change.wind_rebaked, "a mean wind alone needs no bake");
        let steps = host.substeps(0.01).expect("a valid step");
        let blocks = steps.blocks[0];
        assert_eq!(blocks.step.mean_wind_mps, weather.wind.mean_wind_mps);
        assert_eq!(host.wind_params().mean_wind_mps, weather.wind.mean_wind_mps);
        let [x, z] = blocks.cover.air().wind_mps;
        assert!((x - 3.0).abs() < f32::EPSILON && (z + 4.0).abs() < f32::EPSILON);
    }

    /// 2 mm/h of dry snow at −5 °C for half a second (half a day of cover at a
    /// day a second).
    fn snow_for_half_a_second(host: &mut HostState) {
        dry_snow(host, 2.0, 10);
    }

    /// `rate_mm_per_h` of dry snow at −5 °C for `steps` steps of 0.05 s.
    fn dry_snow(host: &mut HostState, rate_mm_per_h: f32, steps: u32) {
        let snow = Weather {
            kind: crate::PrecipitationKind::DrySnow,
            intensity_mm_per_h: rate_mm_per_h,
            air_temperature_c: -5.0,
            ..*host.weather()
        };
        let _rebaked = host.set_weather(&snow).expect("a valid weather");
        for _ in 0..steps {
            let steps = host.substeps(0.05).expect("a valid step");
            host.advance(&steps);
        }
    }

    #[test]
    fn the_cover_beyond_the_grid_keeps_a_texel_of_each_surface() {
        use crate::host::{FAR_COVER_SURFACES, far_cover_slot};
        use precip_cover::Surface;
        let mut setup = Setup::over_flat_ground(20.0, 8, 10.0, 256);
        // A day a second, so a few seconds of steps lay a visible snowfall.
        setup.cover.time_scale = 86_400.0;
        let mut host = HostState::configure(&setup).expect("a valid setup");
        snow_for_half_a_second(&mut host);
        let far = host.far_cover().texels();
        for (texel, surface) in far.iter().zip(FAR_COVER_SURFACES) {
            assert_eq!(texel.surface, surface as u32);
            assert_eq!(
                far_cover_slot(surface),
                far_cover_slot(Surface::from_raw(texel.surface))
            );
        }
        let grass = far[far_cover_slot(Surface::Grass)];
        let paving = far[far_cover_slot(Surface::Asphalt)];
        let water = far[far_cover_slot(Surface::Water)];
        // Half a simulated day of 2 mm/h: grass and paving hold the snow, a lake
        // takes it in.
        assert!(grass.swe_mm > 5.0, "grass {}", grass.swe_mm);
        assert!(paving.swe_mm > 5.0, "paving {}", paving.swe_mm);
        assert!(water.swe_mm < 1e-3, "water {}", water.swe_mm);
        assert_eq!(
            far_cover_slot(Surface::Roof),
            far_cover_slot(Surface::Asphalt)
        );
        assert_eq!(far_cover_slot(Surface::Sand), far_cover_slot(Surface::Soil));
        // The GPU's rows: after the ground map, in the region the last step wrote.
        let rows = host.far_cover_rows();
        assert_eq!(rows.cells.x * rows.cells.y, 1);
        assert!(rows.cells.z >= host.far_cover_first_word());
    }

    /// The house's setup on 201² samples of flat terrain `spacing_m` apart at
    /// its ground's −0.5 m (made by `terrain` from the flat one), a day a second.
    fn house_on_flat_terrain(spacing_m: f32, terrain: impl Fn(Terrain) -> Terrain) -> Setup {
        use crate::scene::builtin::house_on_plane;
        let (mut setup, _) = Setup::over_scene(house_on_plane(), 32, 6.0, 256).expect("valid");
        let flat = Terrain::new(
            glam::UVec2::splat(201),
            spacing_m,
            Vec2::ZERO,
            vec![-0.5; 201 * 201],
        )
        .expect("valid");
        let scene = setup.scene.take().expect("a scene");
        setup.scene = Some(Arc::new(
            Arc::unwrap_or_clone(scene).on_terrain(Arc::new(terrain(flat))),
        ));
        setup.cover.time_scale = 86_400.0;
        setup
    }

    #[test]
    fn the_books_beyond_the_grid_cover_the_terrain_off_it_and_close() {
        use crate::scene::LandCover;
        // 2 km of flat terrain, its west half a lake, under the house's 40 m grid.
        let setup = house_on_flat_terrain(10.0, |t| {
            t.with_land_cover(
                LandCover::from_worldcover(glam::UVec2::new(2, 1), &[80, 30]).expect("valid"),
            )
        });
        let mut host = HostState::configure(&setup).expect("a valid setup");
        snow_for_half_a_second(&mut host);
        let far = host.far_cover_totals().expect("a terrain");
        // The terrain's 4 km² but the grid's square, half of it lake.
        let grid = f64::from(setup.cover.frame.size_m.element_product());
        assert!(
            (far.area_m2 - (4.0e6 - grid)).abs() < 0.01 * 4.0e6,
            "{}",
            far.area_m2
        );
        assert!(far.deposited_kg > 0.0);
        assert!(
            far.imbalance_kg().abs() < 1e-5 * far.deposited_kg,
            "{} of {}",
            far.imbalance_kg(),
            far.deposited_kg
        );
        // The lake took its half in (run off into a water body), the grass holds
        // its half as snow.
        assert!(
            (far.runoff_kg / far.deposited_kg - 0.5).abs() < 0.02,
            "{far:?}"
        );
        assert!(
            (far.swe_kg / far.deposited_kg - 0.5).abs() < 0.02,
            "{far:?}"
        );
        // Without a terrain there are no books beyond the grid.
        assert!(
            HostState::configure(&Setup::over_flat_ground(20.0, 8, 10.0, 256))
                .expect("valid")
                .far_cover_totals()
                .is_none()
        );
    }

    #[test]
    fn the_land_beyond_the_camera_s_three_km_takes_the_rate_beyond_under_the_clouds() {
        use crate::drawing::clouds::{CloudKind, CloudLayer, CloudLayers};
        // 10 km of flat terrain under the house's grid; no snow here, 2 mm/h around.
        let mut setup = house_on_flat_terrain(50.0, |t| t);
        setup.render.rate_beyond_mm_per_h = Some(2.0);
        let mut host = HostState::configure(&setup).expect("a valid setup");
        dry_snow(&mut host, 0.0, 8);
        let near = host
            .far_cover()
            .texel_at(Vec2::new(1000.0, 0.0), precip_cover::Surface::Grass);
        let far = host
            .far_cover()
            .texel_at(Vec2::new(4500.0, 4500.0), precip_cover::Surface::Grass);
        assert!(near.deposited_mm.abs() < 1e-12, "{}", near.deposited_mm);
        // 0.4 s at a day a second of 2 mm/h: 19.2 mm beyond.
        assert!(
            (far.deposited_mm - 19.2).abs() < 0.01,
            "{}",
            far.deposited_mm
        );
        // Under a cumulus layer the water beyond falls under its clouds alone, and
        // the books close.
        setup.render.cloud_layers = CloudLayers::one(CloudLayer::typical(CloudKind::Cumulus, 0.3));
        let mut host = HostState::configure(&setup).expect("a valid setup");
        dry_snow(&mut host, 0.0, 8);
        let beyond: Vec<f32> = host
            .far_cover()
            .texels()
            .iter()
            .filter(|t| t.surface == precip_cover::Surface::Grass as u32 && t.deposited_mm > 0.0)
            .map(|t| t.deposited_mm)
            .collect();
        let most = beyond.iter().copied().fold(0.0, f32::max);
        let full = 19.2 / crate::drawing::clouds::shaft_share(0.3);
        assert!((most - full).abs() < 0.01 * full, "{most} of {full}");
        assert!(beyond.len() < 9216 / 2, "{} cells wet", beyond.len());
        let books = host.far_cover_totals().expect("a terrain");
        assert!(books.imbalance_kg().abs() < 1e-5 * books.deposited_kg);
    }
}
