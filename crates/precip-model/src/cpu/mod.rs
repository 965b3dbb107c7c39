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

use precip_cover::{CoverGrid, DepositBuffer};
use rayon::prelude::*;

use crate::backend::camera::{Camera, Image, View};
use crate::backend::error::BackendError;
use crate::backend::setup::Setup;
use crate::backend::{Backend, BackendInfo, PassTiming, TimingSource, Timings};
use crate::host::HostState;
use crate::particles::birth::initial_particle;
use crate::particles::particle::Particle;
use crate::particles::step::{StepInputs, step_particle, stepped_particles};
use crate::sensors::lidar::{BeamQuery, BeamReturn, query_on_cpu};
use crate::weather::Weather;

/// The most particles the CPU backend holds (5.4 GB of particle state).
pub const CPU_MAX_PARTICLES: u64 = 1 << 26;

/// Name of this backend.
const NAME: &str = "cpu";

/// The state of a configured backend: the host state every backend shares, and
/// what the CPU keeps where a GPU keeps buffers.
#[derive(Debug)]
struct State {
    host: HostState,
    particles: Vec<Particle>,
    cover: CoverGrid,
    deposits: DepositBuffer,
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
        self.state.as_ref().map_or(0.0, |s| s.host.time_s())
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
        let host = HostState::configure(setup)?;
        let bake_ms = elapsed_ms(start);
        let cover = setup.initial_cover()?;
        let params = host.init_block();
        let particles: Vec<Particle> = (0..params.particle_count)
            .into_par_iter()
            .map(|i| initial_particle(i, &params, &setup.ground))
            .collect();
        let deposits = DepositBuffer::new(cover.texels.len());
        self.state = Some(State {
            host,
            particles,
            cover,
            deposits,
        });
        self.timings = vec![PassTiming {
            pass: "wind_bake",
            milliseconds: bake_ms,
        }];
        Ok(())
    }

    fn set_weather(&mut self, weather: &Weather) -> Result<(), BackendError> {
        let state = self.state_mut("set_weather")?;
        let start = Instant::now();
        let change = state.host.set_weather(weather)?;
        self.timings = if change.wind_rebaked {
            vec![PassTiming {
                pass: "wind_bake",
                milliseconds: elapsed_ms(start),
            }]
        } else {
            Vec::new()
        };
        Ok(())
    }

    fn set_camera(&mut self, camera: &Camera) -> Result<(), BackendError> {
        self.state_mut("set_camera")?.host.set_camera(camera)
    }

    fn step(&mut self, dt_s: f32) -> Result<(), BackendError> {
        let state = self.state_mut("step")?;
        let mut steps = state.host.substeps(dt_s)?;
        // The cover grid follows the camera over a terrain (host::cover_window);
        // the step's blocks then from the moved setup (its emitter, its floor).
        if let Some(shift) = state.host.cover_grid_move() {
            state.cover = state.host.move_cover_grid(shift, &state.cover)?;
            steps = state.host.substeps(dt_s)?;
        }
        let (mut particle_ms, mut cover_ms) = (0.0, 0.0);
        for blocks in &steps.blocks {
            let start = Instant::now();
            let inputs = StepInputs {
                params: &blocks.step,
                wind: state.host.wind(),
                ground: &state.host.setup().ground,
                cover_frame: &state.cover.frame,
                cover_texels: &state.cover.texels,
                deposits: &state.deposits,
            };
            let stepped = stepped_particles(&blocks.step);
            state.particles[stepped.start as usize..stepped.end as usize]
                .par_iter_mut()
                .zip(stepped)
                .for_each(|(p, i)| {
                    *p = step_particle(i, p, &inputs).0;
                });
            particle_ms += elapsed_ms(start);

            let start = Instant::now();
            state.cover.step(
                &mut state.deposits,
                blocks.cover.air(),
                blocks.cover.dt_days,
                &state.host.setup().cover.params,
            );
            cover_ms += elapsed_ms(start);
        }
        state.host.advance(&steps);
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

    fn set_atmosphere(
        &mut self,
        to_sun: Option<glam::Vec3>,
        clear_air_extinction_per_m: Option<f32>,
    ) -> Result<(), BackendError> {
        self.state_mut("set_atmosphere")?
            .host
            .set_atmosphere(to_sun, clear_air_extinction_per_m)
    }

    fn set_cloud_layers(
        &mut self,
        cloud_layers: crate::drawing::clouds::CloudLayers,
    ) -> Result<(), BackendError> {
        self.state_mut("set_cloud_layers")?
            .host
            .set_cloud_layers(cloud_layers)
    }

    fn set_fog_layer(
        &mut self,
        fog_layer: Option<crate::drawing::fog_layer::FogLayer>,
    ) -> Result<(), BackendError> {
        self.state_mut("set_fog_layer")?
            .host
            .set_fog_layer(fog_layer)
    }

    fn optics(&mut self) -> Result<crate::sensors::optics::Optics, BackendError> {
        let state = self.state_mut("optics")?;
        let in_the_air = state.host.particles_in_the_air();
        Ok(state.host.with_layers(crate::sensors::optics::Optics::live(
            state.host.weather(),
            &state.particles[in_the_air.start as usize..in_the_air.end as usize],
        )))
    }

    fn read_particles(&mut self) -> Result<Vec<Particle>, BackendError> {
        Ok(self.state_mut("read_particles")?.particles.clone())
    }

    fn weather(&self) -> Result<Weather, BackendError> {
        self.state
            .as_ref()
            .map(|s| *s.host.weather())
            .ok_or(BackendError::NotConfigured {
                operation: "weather",
            })
    }

    fn query_beams(&mut self, query: &BeamQuery) -> Result<Vec<BeamReturn>, BackendError> {
        let beams = query.validate()?;
        let state = self.state_mut("query_beams")?;
        let ground = &state.host.setup().ground;
        let params = query.params(&beams, state.host.particles_in_the_air(), ground);
        let hits = query_on_cpu(&beams, &params, &state.particles, ground);
        let air = state.host.unresolved_air();
        let mut returns = query.answer(NAME, &beams, &hits, state.host.weather(), &air)?;
        crate::sensors::lidar::label_targets(&mut returns, &beams, ground);
        Ok(returns)
    }

    fn read_cover(&mut self) -> Result<CoverGrid, BackendError> {
        Ok(self.state_mut("read_cover")?.cover.clone())
    }

    fn far_cover_totals(&self) -> Option<precip_cover::CoverTotals> {
        self.state.as_ref()?.host.far_cover_totals()
    }

    fn far_snow_line_m(&self) -> Option<f32> {
        self.state.as_ref()?.host.far_snow_line_m()
    }

    fn cover_window(&self) -> Option<crate::host::CoverWindow> {
        Some(self.state.as_ref()?.host.cover_window().clone())
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
