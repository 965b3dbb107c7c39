//! Shader modules, bind group layouts and compute pipelines of the frame recipe.

use precip_gpu::bind_groups;
use precip_gpu::recipe::{INIT_PASS, KernelPass, SUBSTEP_PASSES};
use precip_gpu::shaders::Program;

use crate::bind_groups::bind_group_layout;

/// The compiled programs of one device.
#[derive(Debug)]
pub struct Programs {
    /// Layout of [`Program::StepParticles`]'s group 0.
    pub step_layout: wgpu::BindGroupLayout,
    /// Layout of [`Program::CoverUpdate`]'s group 0.
    pub cover_layout: wgpu::BindGroupLayout,
    /// `init_particles`.
    pub init: wgpu::ComputePipeline,
    /// The kernels of one sub-step, in the recipe's order.
    pub substep: Vec<(KernelPass, wgpu::ComputePipeline)>,
    /// Layout of [`Program::QueryBeams`]'s group 0.
    pub beams_layout: wgpu::BindGroupLayout,
    /// `query_beams`.
    pub query_beams: wgpu::ComputePipeline,
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

impl Programs {
    /// Compiles every kernel of the recipe.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Self {
        let step_layout = bind_group_layout(device, &bind_groups::STEP);
        let cover_layout = bind_group_layout(device, &bind_groups::COVER_UPDATE);
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
        let beams_layout = bind_group_layout(device, &bind_groups::BEAMS);
        let beams_module = shader_module(device, Program::QueryBeams);
        Self {
            query_beams: pipeline(device, &beams_layout, &beams_module, "query_beams"),
            beams_layout,
            init: pipeline(device, &step_layout, &step_module, INIT_PASS.entry_point),
            substep,
            step_layout,
            cover_layout,
        }
    }
}
