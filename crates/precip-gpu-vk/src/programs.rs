//! Shader modules (SPIR-V compiled from `precip-gpu`'s programs at build time),
//! pipeline layouts and compute pipelines: the pieces [`crate::gpu::Hal`] and the
//! renderer make their pipelines from.

use std::ffi::CString;

use ash::vk;
use precip_gpu::shaders::Program;
use precip_model::BackendError;

use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::spirv::words;

/// A pipeline layout of one descriptor set.
pub fn pipeline_layout(
    device: &Device,
    sets: &[vk::DescriptorSetLayout],
) -> Result<vk::PipelineLayout, BackendError> {
    let info = vk::PipelineLayoutCreateInfo::default().set_layouts(sets);
    // SAFETY: a valid device; the set layouts are live.
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
