//! The executor over a recording `Gpu`: what a configuration makes comes from the
//! resources table, every object goes back to the device on every path (a failure
//! injected at each call in turn leaves nothing alive), a step dispatches every
//! sub-step's kernels at its own block, and a refused step or weather changes
//! nothing; and the frame over the same device: every pass of the plan recorded in
//! order, each draw after its pipeline and groups, and nothing left alive after a
//! backend drawn at two sizes is dropped, wherever a call fails.

use std::cell::Cell;
use std::rc::Rc;

use precip_gpu::GpuBackend;
use precip_gpu::bind_groups::GroupLayout;
use precip_gpu::frame::{Draw, FRAME_PASSES, PassWork, RenderPassRecipe};
use precip_gpu::frame_resources::{Sampler, TexelFormat};
use precip_gpu::gpu::{
    BindingResource, Command, Dispatch, FrameWork, Gpu, PassKind, Target, TextureDesc,
};
use precip_gpu::recipe::SUBSTEP_PASSES;
use precip_gpu::resources::{BufferUsage, SimBuffer};
use precip_gpu::shaders::Program;
use precip_gpu::{Kernels, Simulation};
use precip_model::backend::MAX_STEP_S;
use precip_model::{
    Backend, BackendError, Camera, DeviceLimits, DeviceMemory, Setup, View, Weather,
};

/// A device that records calls, counts live objects and fails the `fail_at`-th
/// call that makes something.
#[derive(Debug, Default)]
struct Recording {
    made: usize,
    fail_at: Option<usize>,
    live: i64,
    /// Shared, to be read after a backend owning the device is dropped.
    alive: Rc<Cell<i64>>,
    /// Each frame's passes: name, whether it ran, its commands.
    frames: Vec<Vec<(&'static str, bool, usize)>>,
    /// Each kernel's entry point, by id.
    kernels: Vec<(u32, &'static str)>,
    buffers: Vec<(&'static str, u64)>,
    dispatches: Vec<(u32, Option<u32>)>,
    writes: Vec<(u64, usize)>,
}

impl Recording {
    fn make(&mut self) -> Result<u32, BackendError> {
        self.made += 1;
        if self.fail_at == Some(self.made) {
            return Err(BackendError::Device {
                backend: "recording",
                message: format!("call {} fails on purpose", self.made),
            });
        }
        self.live += 1;
        self.alive.set(self.live);
        Ok(self.made as u32)
    }

    fn free(&mut self) {
        self.live -= 1;
        self.alive.set(self.live);
    }
}

impl Gpu for Recording {
    type Buffer = (u32, u64);
    type Volume = u32;
    type GroupLayout = u32;
    type BindGroup = u32;
    type Kernel = u32;
    type Texture = (u32, (u32, u32));
    type Sampler = u32;
    type DrawPipeline = u32;
    type Surface = ();
    type ColourFormat = u8;

    fn name(&self) -> &'static str {
        "recording"
    }
    fn describe(&self) -> String {
        "a recording".into()
    }
    fn device_memory(&self) -> Option<DeviceMemory> {
        None
    }
    fn limits(&self) -> DeviceLimits {
        DeviceLimits {
            device: "recording".into(),
            max_storage_binding_bytes: 1 << 27,
            max_buffer_bytes: 1 << 30,
            max_texture_side_px: 8192,
        }
    }
    fn binding_limits(&self) -> precip_gpu::binding_limits::BindingLimits {
        precip_gpu::binding_limits::BindingLimits::WEBGPU_DEFAULT
    }
    fn uniform_alignment(&self) -> u64 {
        256
    }
    fn slots(&self) -> u32 {
        2
    }
    fn create_buffer(
        &mut self,
        label: &'static str,
        bytes: u64,
        _usage: BufferUsage,
        contents: Option<&[u8]>,
    ) -> Result<(u32, u64), BackendError> {
        if let Some(c) = contents {
            assert_eq!(
                c.len() as u64,
                bytes,
                "{label}: contents as long as the buffer"
            );
        }
        let id = self.make()?;
        self.buffers.push((label, bytes));
        Ok((id, bytes))
    }
    fn write_buffer(
        &mut self,
        buffer: &mut (u32, u64),
        offset: u64,
        bytes: &[u8],
    ) -> Result<(), BackendError> {
        assert!(
            offset + bytes.len() as u64 <= buffer.1,
            "a write past the end"
        );
        self.writes.push((offset, bytes.len()));
        Ok(())
    }
    fn read_buffer(&mut self, buffer: &(u32, u64), bytes: u64) -> Result<Vec<u8>, BackendError> {
        assert!(bytes <= buffer.1, "a read past the end");
        Ok(vec![0; bytes as usize])
    }
    fn create_volume(
        &mut self,
        _label: &'static str,
        size: [u32; 3],
        texels: &[u8],
    ) -> Result<u32, BackendError> {
        assert_eq!(texels.len(), 16 * size.iter().product::<u32>() as usize);
        self.make()
    }
    fn write_volume(&mut self, _volume: &u32, _texels: &[u8]) -> Result<(), BackendError> {
        Ok(())
    }
    fn group_layout(&mut self, _table: &GroupLayout) -> Result<u32, BackendError> {
        self.make()
    }
    fn kernel(
        &mut self,
        program: Program,
        entry_point: &'static str,
        layouts: &[&u32],
    ) -> Result<u32, BackendError> {
        assert!(
            program.entry_points().contains(&entry_point),
            "{entry_point}"
        );
        assert!(!layouts.is_empty());
        let id = self.make()?;
        self.kernels.push((id, entry_point));
        Ok(id)
    }
    fn create_texture(
        &mut self,
        desc: &TextureDesc<'_>,
    ) -> Result<(u32, (u32, u32)), BackendError> {
        if let Some(c) = desc.contents {
            let texels = desc.size.0 * desc.size.1;
            assert_eq!(
                c.len() as u32,
                texels * desc.format.texel_bytes(),
                "{}",
                desc.label
            );
        }
        Ok((self.make()?, desc.size))
    }
    fn read_texture(&mut self, texture: &(u32, (u32, u32))) -> Result<Vec<u8>, BackendError> {
        Ok(vec![0; (texture.1.0 * texture.1.1 * 4) as usize])
    }
    fn create_sampler(&mut self, _sampler: Sampler) -> Result<u32, BackendError> {
        self.make()
    }
    fn draw_pipeline(
        &mut self,
        draw: &Draw,
        pass: &RenderPassRecipe,
        layouts: &[&u32],
        colour: Option<u8>,
    ) -> Result<u32, BackendError> {
        assert_eq!(pass.colour.is_some(), colour.is_some(), "{draw:?}");
        assert!(!layouts.is_empty());
        self.make()
    }
    fn colour_format(&self, _target: Target<'_, Self>) -> u8 {
        1
    }
    fn rasterises_on_cpu(&self) -> bool {
        false
    }
    fn copy_format(&self, _target: Target<'_, Self>) -> Option<TexelFormat> {
        Some(TexelFormat::Rgba8UnormSrgb)
    }
    fn texture_size(&self, texture: &(u32, (u32, u32))) -> (u32, u32) {
        texture.1
    }
    fn submit_frame(
        &mut self,
        frame: &FrameWork<'_, Self>,
        _target: Target<'_, Self>,
    ) -> Result<(), BackendError> {
        let mut passes = Vec::new();
        for pass in &frame.passes {
            let mut bound = false;
            for c in &pass.commands {
                match (c, &pass.kind) {
                    (Command::Kernel(_), PassKind::Compute)
                    | (Command::Pipeline(_), PassKind::Render(_)) => bound = true,
                    (Command::Kernel(_) | Command::Dispatch(..), PassKind::Render(_))
                    | (Command::Pipeline(_) | Command::Draw(_), PassKind::Compute) => {
                        panic!("{}: {c:?} in the wrong kind of pass", pass.name)
                    }
                    (Command::Group { group, .. }, _) => assert!(**group > 0),
                    _ => assert!(bound, "{}: {c:?} before a pipeline", pass.name),
                }
            }
            passes.push((pass.name, pass.runs, pass.commands.len()));
        }
        self.frames.push(passes);
        Ok(())
    }
    fn frame_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError> {
        Ok(None)
    }
    fn forget_times(&mut self) {}
    fn has_timestamps(&self) -> bool {
        false
    }
    fn bind_group(
        &mut self,
        _layout: &u32,
        table: &GroupLayout,
        entries: &[(u32, BindingResource<'_, Self>)],
    ) -> Result<u32, BackendError> {
        assert_eq!(entries.len(), table.bindings.len(), "{}", table.name);
        self.make()
    }
    fn free_slot(&mut self, slot: u32) -> Result<(), BackendError> {
        assert!(slot < self.slots());
        Ok(())
    }
    fn settle(&mut self) -> Result<(), BackendError> {
        Ok(())
    }
    fn dispatch(
        &mut self,
        dispatches: &[Dispatch<'_, Self>],
        _timed: bool,
    ) -> Result<(), BackendError> {
        self.dispatches
            .extend(dispatches.iter().map(|d| (*d.kernel, d.offset)));
        Ok(())
    }
    fn kernel_times_ms(&mut self) -> Result<Option<Vec<f64>>, BackendError> {
        Ok(None)
    }
    fn destroy_buffer(&mut self, _buffer: (u32, u64)) {
        self.free();
    }
    fn destroy_volume(&mut self, _volume: u32) {
        self.free();
    }
    fn destroy_texture(&mut self, _texture: (u32, (u32, u32))) {
        self.free();
    }
    fn destroy_sampler(&mut self, _sampler: u32) {
        self.free();
    }
    fn destroy_bind_group(&mut self, _group: u32) {
        self.free();
    }
    fn destroy_kernel(&mut self, _kernel: u32) {
        self.free();
    }
    fn destroy_draw_pipeline(&mut self, _pipeline: u32) {
        self.free();
    }
    fn destroy_group_layout(&mut self, _layout: u32) {
        self.free();
    }
}

fn setup() -> Setup {
    Setup::over_flat_ground(20.0, 8, 10.0, 500)
}

#[test]
fn a_failure_at_any_call_leaves_nothing_alive() {
    let mut calls = 0;
    // Count the calls of a whole run, then fail each in turn.
    for fail_at in std::iter::once(None).chain((1..).map(Some)) {
        let mut gpu = Recording {
            fail_at,
            ..Recording::default()
        };
        let result = (|| -> Result<(), BackendError> {
            let kernels = Kernels::new(&mut gpu)?;
            let sim = Simulation::prepare(&gpu, &setup())
                .and_then(|p| Simulation::configure(&mut gpu, &kernels, p));
            let sim = match sim {
                Ok(s) => s,
                Err(e) => {
                    kernels.destroy(&mut gpu);
                    return Err(e);
                }
            };
            let queried = sim.optics(&mut gpu, &kernels).map(drop);
            sim.destroy(&mut gpu);
            kernels.destroy(&mut gpu);
            queried
        })();
        assert_eq!(gpu.live, 0, "fail at {fail_at:?}: {result:?}");
        match fail_at {
            None => {
                assert!(result.is_ok());
                calls = gpu.made;
            }
            Some(n) => {
                assert!(result.is_err(), "call {n} of {calls} was to fail");
                if n == calls {
                    break;
                }
            }
        }
    }
    assert!(
        calls > 30,
        "kernels, layouts, buffers, groups: {calls} calls"
    );
}

#[test]
fn the_table_makes_every_buffer_and_a_step_dispatches_every_sub_step() {
    let mut gpu = Recording::default();
    let kernels = Kernels::new(&mut gpu).expect("kernels");
    let prepared = Simulation::prepare(&gpu, &setup()).expect("a valid setup");
    let mut sim = Simulation::configure(&mut gpu, &kernels, prepared).expect("configure");
    for b in SimBuffer::ALL {
        assert!(
            gpu.buffers.iter().any(|(label, _)| *label == b.label()),
            "{b:?}"
        );
    }
    let particles = gpu
        .buffers
        .iter()
        .find(|(l, _)| *l == SimBuffer::Particles.label())
        .map(|(_, bytes)| *bytes);
    assert_eq!(particles, Some(500 * 64));
    // init_particles, once, at the first block.
    assert_eq!(gpu.dispatches.len(), 1);
    gpu.dispatches.clear();
    sim.step(&mut gpu, &kernels, 0.1).expect("a step");
    let substeps = gpu.dispatches.len() / SUBSTEP_PASSES.len();
    assert!(substeps >= 2 && gpu.dispatches.len() % SUBSTEP_PASSES.len() == 0);
    let mut offsets: Vec<u32> = gpu.dispatches.iter().filter_map(|d| d.1).collect();
    offsets.dedup();
    assert_eq!(offsets.len(), substeps, "one block per sub-step");
    assert!(offsets.iter().all(|o| o % 256 == 0));
    // The next step writes the other slot's ring.
    gpu.dispatches.clear();
    sim.step(&mut gpu, &kernels, 0.1).expect("a step");
    let second: Vec<u32> = gpu.dispatches.iter().filter_map(|d| d.1).collect();
    assert!(second.iter().all(|o| !offsets.contains(o)), "another slot");
    let time = sim.host().time_s();
    assert!(sim.step(&mut gpu, &kernels, MAX_STEP_S * 2.0).is_err());
    let bad = Weather {
        air_temperature_c: f32::NAN,
        ..*sim.host().weather()
    };
    assert!(sim.set_weather(&mut gpu, &bad).is_err());
    assert!((sim.host().time_s() - time).abs() < f64::EPSILON);
    assert!(sim.host().weather().air_temperature_c.is_finite());
    sim.destroy(&mut gpu);
    kernels.destroy(&mut gpu);
    assert_eq!(gpu.live, 0);
}

fn view(width_px: u32, height_px: u32) -> View {
    View {
        camera: Camera {
            aspect: width_px as f32 / height_px as f32,
            ..Camera::default()
        },
        width_px,
        height_px,
    }
}

/// Configure, step, draw at two sizes, read the image back and drop.
fn draw_twice(backend: &mut GpuBackend<Recording>) -> Result<(), BackendError> {
    backend.configure(&setup())?;
    backend.step(0.05)?;
    backend.render(&view(64, 48))?;
    backend.step(0.05)?;
    backend.render(&view(32, 16))?;
    let image = backend.read_image()?;
    assert_eq!((image.width_px, image.height_px), (32, 16));
    Ok(())
}

#[test]
fn a_frame_records_the_plan_and_a_failure_anywhere_leaves_nothing_alive() {
    let mut calls = 0;
    for fail_at in std::iter::once(None).chain((1..).map(Some)) {
        let alive = Rc::new(Cell::new(0));
        let gpu = Recording {
            fail_at,
            alive: alive.clone(),
            ..Recording::default()
        };
        let result = GpuBackend::new(gpu).and_then(|mut backend| {
            let drawn = draw_twice(&mut backend);
            if fail_at.is_none() {
                let frames = &backend.gpu().frames;
                assert_eq!(frames.len(), 2);
                for frame in frames {
                    let names: Vec<_> = frame.iter().map(|p| p.0).collect();
                    let plan: Vec<_> = FRAME_PASSES.iter().map(|p| p.name).collect();
                    assert_eq!(names, plan);
                    for ((name, runs, commands), pass) in frame.iter().zip(&FRAME_PASSES) {
                        // A copy is its pass kind alone.
                        let copy = pass.work == PassWork::CopyTarget;
                        assert!(
                            *commands > 0 || !*runs || copy,
                            "{name} runs with no commands"
                        );
                    }
                }
                calls = backend.gpu().made;
            }
            drawn
        });
        assert_eq!(alive.get(), 0, "fail at {fail_at:?}: {result:?}");
        match fail_at {
            None => assert!(result.is_ok(), "{result:?}"),
            Some(n) => {
                assert!(result.is_err(), "call {n} of {calls} was to fail");
                if n == calls {
                    break;
                }
            }
        }
    }
    assert!(calls > 60, "{calls} calls");
}

/// The entry points one step of `weather` dispatches.
fn kernels_of_a_step(weather: Weather) -> Vec<&'static str> {
    let mut gpu = Recording::default();
    let kernels = Kernels::new(&mut gpu).expect("kernels");
    let setup = Setup { weather, ..setup() };
    let prepared = Simulation::prepare(&gpu, &setup).expect("a valid setup");
    let mut sim = Simulation::configure(&mut gpu, &kernels, prepared).expect("configure");
    gpu.dispatches.clear();
    sim.step(&mut gpu, &kernels, 0.05).expect("a step");
    let names = gpu
        .dispatches
        .iter()
        .filter_map(|(id, _)| gpu.kernels.iter().find(|(k, _)| k == id).map(|(_, n)| *n))
        .collect();
    sim.destroy(&mut gpu);
    kernels.destroy(&mut gpu);
    names
}

#[test]
fn an_idle_feature_dispatches_nothing() {
    use precip_model::PrecipitationKind as Kind;
    let drift = ["snow_wind", "snow_outflow", "snow_inflow"];
    let flow = ["water_outflow", "water_inflow"];
    let weather = |kind, intensity_mm_per_h, air_temperature_c| Weather {
        kind,
        intensity_mm_per_h,
        air_temperature_c,
        ..setup().weather
    };
    let snow = kernels_of_a_step(weather(Kind::DrySnow, 1.0, -5.0));
    let rain = kernels_of_a_step(weather(Kind::Rain, 10.0, 12.0));
    let sand = kernels_of_a_step(weather(Kind::Sand, 1.0, 30.0));
    let clear = kernels_of_a_step(weather(Kind::Rain, 0.0, 12.0));
    for k in drift.iter().chain(&flow) {
        assert!(snow.contains(k), "snow runs {k}");
        assert!(!sand.contains(k) && !clear.contains(k), "{k} idle");
    }
    for k in drift {
        assert!(!rain.contains(&k), "rain leaves no snow to drift: {k}");
    }
    for k in flow {
        assert!(rain.contains(&k), "rain runs {k}");
    }
    assert!(sand.contains(&"step_particles") && sand.contains(&"cover_update"));
}
