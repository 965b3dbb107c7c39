//! Shader modules, descriptor set layouts, pipeline layouts and the compute pipelines
//! of the frame recipe (`precip_gpu::recipe`), the same kernels and bindings the wgpu
//! backend uses.

use std::ffi::CString;

use ash::vk;
use precip_gpu::bind_groups;
use precip_gpu::recipe::{INIT_PASS, KernelPass, SUBSTEP_PASSES};
use precip_gpu::shaders::Program;
use precip_model::BackendError;

use crate::bind_groups::set_layout;
use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::spirv::words;

/// The compiled programs of one device.
#[derive(Debug)]
pub struct Programs {
    /// Set 0 of `step_particles`, `birth_particles`, `init_particles`.
    pub step_set_layout: vk::DescriptorSetLayout,
    /// Set 0 of `cover_update`.
    pub cover_set_layout: vk::DescriptorSetLayout,
    /// Their pipeline layouts.
    pub step_layout: vk::PipelineLayout,
    /// The cover kernel's.
    pub cover_layout: vk::PipelineLayout,
    modules: Vec<vk::ShaderModule>,
    /// `init_particles`.
    pub init: vk::Pipeline,
    /// The kernels of one sub-step, in the recipe's order.
    pub substep: Vec<(KernelPass, vk::Pipeline)>,
    /// Set 0 of `query_beams`.
    pub beams_set_layout: vk::DescriptorSetLayout,
    /// Its pipeline layout.
    pub beams_layout: vk::PipelineLayout,
    /// `query_beams`.
    pub query_beams: vk::Pipeline,
}

fn pipeline_layout(
    device: &Device,
    set: vk::DescriptorSetLayout,
) -> Result<vk::PipelineLayout, BackendError> {
    let sets = [set];
    let info = vk::PipelineLayoutCreateInfo::default().set_layouts(&sets);
    // SAFETY: a valid device; the set layout is live.
    unsafe { device.raw.create_pipeline_layout(&info, None) }
        .map_err(|e| map_vk("creating a pipeline layout", e))
}

/// A shader module of `program`'s SPIR-V.
pub fn module(device: &Device, program: Program) -> Result<vk::ShaderModule, BackendError> {
    let code = words(program).ok_or_else(|| BackendError::Device {
        backend: NAME,
        message: format!("{program:?} was not compiled to SPIR-V"),
    })?;
    let info = vk::ShaderModuleCreateInfo::default().code(&code);
    // SAFETY: naga wrote valid SPIR-V (validated in the build script).
    unsafe { device.raw.create_shader_module(&info, None) }
        .map_err(|e| map_vk("creating a shader module", e))
}

/// A compute pipeline of `entry` in `module`.
pub fn compute(
    device: &Device,
    layout: vk::PipelineLayout,
    module: vk::ShaderModule,
    entry: &str,
) -> Result<vk::Pipeline, BackendError> {
    let name = CString::new(entry).map_err(|_| BackendError::Device {
        backend: NAME,
        message: format!("entry point {entry} has a NUL"),
    })?;
    let stage = vk::PipelineShaderStageCreateInfo::default()
        .stage(vk::ShaderStageFlags::COMPUTE)
        .module(module)
        .name(&name);
    let info = vk::ComputePipelineCreateInfo::default()
        .stage(stage)
        .layout(layout);
    // SAFETY: the module and layout are live; the create info outlives the call.
    unsafe {
        device
            .raw
            .create_compute_pipelines(vk::PipelineCache::null(), &[info], None)
    }
    .map_err(|(_, e)| map_vk(&format!("creating the {entry} pipeline"), e))
    .map(|p| p[0])
}

impl Programs {
    /// Compiles every kernel of the recipe.
    pub fn new(device: &Device) -> Result<Self, BackendError> {
        let step_set_layout = set_layout(device, &bind_groups::STEP)?;
        let cover_set_layout = set_layout(device, &bind_groups::COVER_UPDATE)?;
        let step_layout = pipeline_layout(device, step_set_layout)?;
        let cover_layout = pipeline_layout(device, cover_set_layout)?;
        let step_module = module(device, Program::StepParticles)?;
        let cover_module = module(device, Program::CoverUpdate)?;
        let mut substep = Vec::new();
        for kernel in SUBSTEP_PASSES {
            let (layout, m) = match kernel.program {
                Program::CoverUpdate => (cover_layout, cover_module),
                _ => (step_layout, step_module),
            };
            substep.push((kernel, compute(device, layout, m, kernel.entry_point)?));
        }
        let beams_set_layout = set_layout(device, &bind_groups::BEAMS)?;
        let beams_layout = pipeline_layout(device, beams_set_layout)?;
        let beams_module = module(device, Program::QueryBeams)?;
        Ok(Self {
            query_beams: compute(device, beams_layout, beams_module, "query_beams")?,
            beams_set_layout,
            beams_layout,
            init: compute(device, step_layout, step_module, INIT_PASS.entry_point)?,
            substep,
            step_set_layout,
            cover_set_layout,
            step_layout,
            cover_layout,
            modules: vec![step_module, cover_module, beams_module],
        })
    }

    /// Destroys everything.
    ///
    /// # Safety
    /// - No pending work uses the pipelines, layouts or modules (the device is idle).
    /// - It is called once: the pipelines and layouts are not usable afterwards.
    pub unsafe fn destroy(&mut self, device: &Device) {
        // SAFETY: the caller guarantees the device is idle and this runs once; each
        // object is destroyed once (the lists are drained).
        unsafe {
            device.raw.destroy_pipeline(self.init, None);
            device.raw.destroy_pipeline(self.query_beams, None);
            for (_, p) in self.substep.drain(..) {
                device.raw.destroy_pipeline(p, None);
            }
            for m in self.modules.drain(..) {
                device.raw.destroy_shader_module(m, None);
            }
            device.raw.destroy_pipeline_layout(self.step_layout, None);
            device.raw.destroy_pipeline_layout(self.cover_layout, None);
            device.raw.destroy_pipeline_layout(self.beams_layout, None);
            device
                .raw
                .destroy_descriptor_set_layout(self.beams_set_layout, None);
            device
                .raw
                .destroy_descriptor_set_layout(self.step_set_layout, None);
            device
                .raw
                .destroy_descriptor_set_layout(self.cover_set_layout, None);
        }
    }
}
