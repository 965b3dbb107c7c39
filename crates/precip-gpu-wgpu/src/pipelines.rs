//! Shader modules, bind group layouts and compute pipelines of the frame recipe.

use std::num::NonZeroU64;

use precip_model::cover::CoverStepParams;
use precip_model::gpu::{INIT_PASS, KernelPass, SUBSTEP_PASSES, cover_bindings, step_bindings};
use precip_model::shaders::Program;
use precip_model::step::StepParams;

/// The compiled programs of one device.
#[derive(Debug)]
pub struct Pipelines {
    /// Layout of [`Program::StepParticles`]'s group 0.
    pub step_layout: wgpu::BindGroupLayout,
    /// Layout of [`Program::CoverUpdate`]'s group 0.
    pub cover_layout: wgpu::BindGroupLayout,
    /// `init_particles`.
    pub init: wgpu::ComputePipeline,
    /// The kernels of one sub-step, in the recipe's order.
    pub substep: Vec<(KernelPass, wgpu::ComputePipeline)>,
}

fn uniform(binding: u32, size: usize, dynamic: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: dynamic,
            min_binding_size: NonZeroU64::new(size as u64),
        },
        count: None,
    }
}

fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A WGSL program as a shader module.
#[must_use]
pub fn shader_module(device: &wgpu::Device, program: Program) -> wgpu::ShaderModule {
    device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(program.label()),
        source: wgpu::ShaderSource::Wgsl(program.source().into()),
    })
}

fn pipeline(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    entry_point: &str,
) -> wgpu::ComputePipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(entry_point),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry_point),
        layout: Some(&pipeline_layout),
        module,
        entry_point: Some(entry_point),
        compilation_options: wgpu::PipelineCompilationOptions::default(),
        cache: None,
    })
}

impl Pipelines {
    /// Compiles every kernel of the recipe.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Self {
        let step_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip step_particles"),
            entries: &[
                uniform(step_bindings::STEP_PARAMS, size_of::<StepParams>(), true),
                uniform(
                    step_bindings::FRAMES,
                    size_of::<precip_model::gpu::Frames>(),
                    false,
                ),
                uniform(
                    step_bindings::WIND,
                    size_of::<precip_model::wind::WindParams>(),
                    false,
                ),
                wgpu::BindGroupLayoutEntry {
                    binding: step_bindings::WIND_VOLUME,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D3,
                        multisampled: false,
                    },
                    count: None,
                },
                storage(step_bindings::GROUND_HEIGHT, true),
                storage(step_bindings::PARTICLES, false),
                storage(step_bindings::DEPOSITS, false),
            ],
        });
        let cover_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("precip cover_update"),
            entries: &[
                uniform(
                    cover_bindings::COVER_PARAMS,
                    size_of::<CoverStepParams>(),
                    true,
                ),
                storage(cover_bindings::COVER, false),
                storage(cover_bindings::DEPOSITS, false),
            ],
        });
        let step_module = shader_module(device, Program::StepParticles);
        let cover_module = shader_module(device, Program::CoverUpdate);
        let substep = SUBSTEP_PASSES
            .iter()
            .map(|kernel| {
                let (layout, module) = match kernel.program {
                    Program::CoverUpdate => (&cover_layout, &cover_module),
                    _ => (&step_layout, &step_module),
                };
                (
                    *kernel,
                    pipeline(device, layout, module, kernel.entry_point),
                )
            })
            .collect();
        Self {
            init: pipeline(device, &step_layout, &step_module, INIT_PASS.entry_point),
            substep,
            step_layout,
            cover_layout,
        }
    }
}
