//! [`CpuBackend`]: the reference implementation of [`Backend`].
//!
//! ## Design
//!
//! A readable mirror of the GPU's frame: per sub-step, every particle runs
//! [`step_particle`] (in parallel with rayon; each particle is independent and landed
//! water is summed in integer fixed point, so the result does not depend on thread
//! order), then every cover texel runs the cover kernel. It is the yardstick the GPU
//! backends are compared with, not a renderer: `render` and `read_image` return
//! [`BackendError::NotSupported`].

use std::time::Instant;

use glam::Vec3;
use precip_cover::{CoverGrid, DepositBuffer};
use precip_wind::WindVolume;
use rayon::prelude::*;

use crate::backend::{Backend, BackendInfo, PassTiming, TimingSource, Timings, substeps};
use crate::birth::initial_particle;
use crate::camera::{Camera, Image, View};
use crate::drag::MAX_SUBSTEP_S;
use crate::error::BackendError;
use crate::lidar::{BeamQuery, BeamReturn, UnresolvedAir, query_on_cpu};
use crate::particle::Particle;
use crate::setup::Setup;
use crate::step::{StepInputs, StepParams, step_particle};
use crate::weather::Weather;

/// The most particles the CPU backend holds (5.4 GB of particle state).
pub const CPU_MAX_PARTICLES: u64 = 1 << 26;

/// Name of this backend.
const NAME: &str = "cpu";

/// The state of a configured backend.
#[derive(Debug)]
struct State {
    setup: Setup,
    weather: Weather,
    wind: WindVolume,
    camera: Camera,
    particles: Vec<Particle>,
    cover: CoverGrid,
    deposits: DepositBuffer,
    /// Step uniforms of the current weather; sub-steps set camera, dt and time.
    step_template: StepParams,
    time_s: f64,
}

/// The CPU reference backend.
#[derive(Debug, Default)]
pub struct CpuBackend {
    state: Option<State>,
    timings: Vec<PassTiming>,
}

impl CpuBackend {
    /// An unconfigured backend.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    fn state_mut(&mut self, operation: &'static str) -> Result<&mut State, BackendError> {
        self.state
            .as_mut()
            .ok_or(BackendError::NotConfigured { operation })
    }

    /// Simulated time since configure, s.
    #[must_use]
    pub fn time_s(&self) -> f64 {
        self.state.as_ref().map_or(0.0, |s| s.time_s)
    }
}

fn elapsed_ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1.0e3
}

impl Backend for CpuBackend {
    fn info(&self) -> BackendInfo {
        BackendInfo {
            name: NAME,
            device: format!("host CPU, {} threads", rayon::current_num_threads()),
            max_particles: CPU_MAX_PARTICLES,
            renders: false,
        }
    }

    fn configure(&mut self, setup: &Setup) -> Result<(), BackendError> {
        setup.validate(CPU_MAX_PARTICLES, "CPU backend limit")?;
        let start = Instant::now();
        let wind = WindVolume::bake(&setup.weather.wind, &setup.wind_volume)?;
        let bake_ms = elapsed_ms(start);
        let cover = setup.initial_cover()?;
        let params = setup.step_params(&setup.weather, setup.camera.position_m, MAX_SUBSTEP_S, 0.0);
        let particles: Vec<Particle> = (0..params.particle_count)
            .into_par_iter()
            .map(|i| initial_particle(i, &params, &setup.ground))
            .collect();
        let deposits = DepositBuffer::new(cover.texels.len());
        self.state = Some(State {
            setup: setup.clone(),
            weather: setup.weather,
            wind,
            camera: setup.camera,
            particles,
            cover,
            deposits,
            step_template: params,
            time_s: 0.0,
        });
        self.timings = vec![PassTiming {
            pass: "wind_bake",
            milliseconds: bake_ms,
        }];
        Ok(())
    }

    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError> {
        weather.validate()?;
        let state = self.state_mut("set_weather")?;
        let mut timings = Vec::new();
        let start = Instant::now();
        let (wind, rebaked) = state.wind.for_field(&weather.wind)?;
        if rebaked {
            timings.push(PassTiming {
                pass: "wind_bake",
                milliseconds: elapsed_ms(start),
            });
        }
        state.wind = wind;
        state.step_template = state
            .setup
            .step_params(weather, Vec3::ZERO, MAX_SUBSTEP_S, 0.0);
        state.weather = *weather;
        self.timings = timings;
        Ok(())
    }

    fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        camera.validate()?;
        self.state_mut("set_camera")?.camera = *camera;
        Ok(())
    }

    fn step(&mut self, dt_s: f32) -> Result<(), BackendError> {
        let (count, h) = substeps(dt_s)?;
        let state = self.state_mut("step")?;
        let (mut particle_ms, mut cover_ms) = (0.0, 0.0);
        for _ in 0..count {
            let start = Instant::now();
            let params = state
                .step_template
                .at(state.camera.position_m, h, state.time_s as f32);
            let inputs = StepInputs {
                params: &params,
                wind: &state.wind,
                ground: &state.setup.ground,
                cover_frame: &state.cover.frame,
                cover_texels: &state.cover.texels,
                deposits: &state.deposits,
            };
            state
                .particles
                .par_iter_mut()
                .enumerate()
                .for_each(|(i, p)| {
                    *p = step_particle(i as u32, p, &inputs).0;
                });
            particle_ms += elapsed_ms(start);

            let start = Instant::now();
            let cover = state.setup.cover_step_params(&state.weather, h);
            state.cover.step(
                &mut state.deposits,
                cover.air(),
                cover.dt_days,
                &state.setup.cover.params,
            );
            cover_ms += elapsed_ms(start);
            state.time_s += f64::from(h);
        }
        self.timings = vec![
            PassTiming {
                pass: "step_particles",
                milliseconds: particle_ms,
            },
            PassTiming {
                pass: "cover_update",
                milliseconds: cover_ms,
            },
        ];
        Ok(())
    }

    fn render(&mut self, _view: &View) -> Result<(), BackendError> {
        Err(BackendError::NotSupported {
            backend: NAME,
            operation: "render",
        })
    }

    fn read_particles(&mut self) -> Result<Vec<Particle>, BackendError> {
        Ok(self.state_mut("read_particles")?.particles.clone())
    }

    fn weather(&self) -> Result<Weather, BackendError> {
        self.state
            .as_ref()
            .map(|s| s.weather)
            .ok_or(BackendError::NotConfigured {
                operation: "weather",
            })
    }

    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError> {
        let beams = query.validate()?;
        let state = self.state_mut("query_beams")?;
        let params = query.params(&beams, state.particles.len() as u32, &state.setup.ground);
        let hits = query_on_cpu(&beams, &params, &state.particles, &state.setup.ground);
        let air = UnresolvedAir::of_configuration(
            &state.setup,
            &state.weather,
            state.step_template,
            state.camera.position_m,
            state.time_s,
        );
        query.answer(NAME, &beams, &hits, &state.weather, &air)
    }

    fn read_cover(&mut self) -> Result<CoverGrid, BackendError> {
        Ok(self.state_mut("read_cover")?.cover.clone())
    }

    fn read_image(&mut self) -> Result<Image, BackendError> {
        Err(BackendError::NotSupported {
            backend: NAME,
            operation: "read_image",
        })
    }

    fn timings(&mut self) -> Result<Timings, BackendError> {
        Ok(Timings {
            source: TimingSource::HostClock,
            passes: self.timings.clone(),
        })
    }
}
