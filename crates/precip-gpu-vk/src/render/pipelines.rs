//! The frame's pipelines, made from the recipe (`precip_gpu::frame`): one
//! graphics pipeline per [`Draw`] (per colour format, like the wgpu backend's; a draw
//! of the depth-only shadow pass against the shadow pass) and one compute pipeline
//! per kernel, each with its entry point's pipeline layout
//! ([`RenderLayouts::pipeline_layout`]) — the same entry points, topologies, depth
//! tests, bias and blending as wgpu, so the images agree. wgpu twin:
//! `precip_gpu_wgpu::render::pipelines`.

use std::ffi::CString;

use ash::vk;
use precip_gpu::frame::{self, Blend, DepthTarget, Draw, PassWork, Topology};
use precip_gpu::recipe::SceneVertex;
use precip_gpu::shaders::Program;
use precip_model::BackendError;

use super::layouts::RenderLayouts;
use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::programs::compute;

/// The draws of a frame for one colour format, by vertex entry point.
#[derive(Debug)]
pub struct DrawPipelines {
    by_vertex_entry: Vec<(&'static str, vk::Pipeline)>,
}

/// The frame's compute kernels, by entry point.
#[derive(Debug)]
pub struct KernelPipelines {
    by_entry: Vec<(&'static str, vk::Pipeline)>,
}

fn entry(name: &str) -> Result<CString, BackendError> {
    CString::new(name).map_err(|_| BackendError::Device {
        backend: NAME,
        message: format!("entry point {name} has a NUL"),
    })
}

/// `SceneVertex`: position, normal, uv, eligibility (locations 0–3).
fn scene_attributes() -> [vk::VertexInputAttributeDescription; 4] {
    let attribute = |location, format, offset| vk::VertexInputAttributeDescription {
        location,
        binding: 0,
        format,
        offset,
    };
    [
        attribute(0, vk::Format::R32G32B32_SFLOAT, 0),
        attribute(1, vk::Format::R32G32B32_SFLOAT, 12),
        attribute(2, vk::Format::R32G32_SFLOAT, 24),
        attribute(3, vk::Format::R32_SFLOAT, 32),
    ]
}

fn draw_pipeline(
    device: &Device,
    module: vk::ShaderModule,
    layout: vk::PipelineLayout,
    pass: vk::RenderPass,
    d: &Draw,
) -> Result<vk::Pipeline, BackendError> {
    let vs = entry(d.entry_points.0)?;
    let fs = d.entry_points.1.map(entry).transpose()?;
    let mut stages = vec![
        vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::VERTEX)
            .module(module)
            .name(&vs),
    ];
    if let Some(fs) = &fs {
        stages.push(
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::FRAGMENT)
                .module(module)
                .name(fs),
        );
    }
    let bindings = [vk::VertexInputBindingDescription {
        binding: 0,
        stride: size_of::<SceneVertex>() as u32,
        input_rate: vk::VertexInputRate::VERTEX,
    }];
    let attributes = scene_attributes();
    let vertex_input = if d.scene_vertices {
        vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(&bindings)
            .vertex_attribute_descriptions(&attributes)
    } else {
        vk::PipelineVertexInputStateCreateInfo::default()
    };
    let assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(match d.topology {
        Topology::TriangleList => vk::PrimitiveTopology::TRIANGLE_LIST,
        Topology::TriangleStrip => vk::PrimitiveTopology::TRIANGLE_STRIP,
    });
    let viewport = vk::PipelineViewportStateCreateInfo::default()
        .viewport_count(1)
        .scissor_count(1);
    let (constant, slope) = d
        .depth_bias
        .map_or((0.0, 0.0), |(constant, slope)| (constant as f32, slope));
    let raster = vk::PipelineRasterizationStateCreateInfo::default()
        .polygon_mode(vk::PolygonMode::FILL)
        .cull_mode(vk::CullModeFlags::NONE)
        .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
        .depth_bias_enable(d.depth_bias.is_some())
        .depth_bias_constant_factor(constant)
        .depth_bias_slope_factor(slope)
        .line_width(1.0);
    let multisample = vk::PipelineMultisampleStateCreateInfo::default()
        .rasterization_samples(vk::SampleCountFlags::TYPE_1);
    let depth = vk::PipelineDepthStencilStateCreateInfo::default()
        .depth_test_enable(true)
        .depth_write_enable(d.depth_write)
        .depth_compare_op(vk::CompareOp::LESS_OR_EQUAL)
        .max_depth_bounds(1.0);
    // wgpu's BlendState::ALPHA_BLENDING: colour src·α + dst·(1 − α), alpha "over".
    let attachment = match d.blend {
        Blend::Alpha => vec![
            vk::PipelineColorBlendAttachmentState::default()
                .blend_enable(true)
                .src_color_blend_factor(vk::BlendFactor::SRC_ALPHA)
                .dst_color_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                .color_blend_op(vk::BlendOp::ADD)
                .src_alpha_blend_factor(vk::BlendFactor::ONE)
                .dst_alpha_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                .alpha_blend_op(vk::BlendOp::ADD)
                .color_write_mask(vk::ColorComponentFlags::RGBA),
        ],
        Blend::Opaque => vec![
            vk::PipelineColorBlendAttachmentState::default()
                .color_write_mask(vk::ColorComponentFlags::RGBA),
        ],
        Blend::None => Vec::new(),
    };
    let blend = vk::PipelineColorBlendStateCreateInfo::default().attachments(&attachment);
    let dynamic = [vk::DynamicState::VIEWPORT, vk::DynamicState::SCISSOR];
    let dynamic = vk::PipelineDynamicStateCreateInfo::default().dynamic_states(&dynamic);
    let info = vk::GraphicsPipelineCreateInfo::default()
        .stages(&stages)
        .vertex_input_state(&vertex_input)
        .input_assembly_state(&assembly)
        .viewport_state(&viewport)
        .rasterization_state(&raster)
        .multisample_state(&multisample)
        .depth_stencil_state(&depth)
        .color_blend_state(&blend)
        .dynamic_state(&dynamic)
        .layout(layout)
        .render_pass(pass)
        .subpass(0);
    // SAFETY: the module, layout and pass are live; everything the create info
    // points to outlives the call.
    let pipeline = unsafe {
        device
            .raw
            .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
    }
    .map_err(|(_, e)| map_vk(&format!("creating the {} pipeline", d.entry_points.0), e))?[0];
    device.name(pipeline, d.entry_points.0);
    Ok(pipeline)
}

impl DrawPipelines {
    /// Every draw of the frame recipe: those of the camera's passes against
    /// `camera_pass` (its colour format), the shadow pass's against `shadow_pass`.
    pub fn new(
        device: &Device,
        module: vk::ShaderModule,
        layouts: &RenderLayouts,
        camera_pass: vk::RenderPass,
        shadow_pass: vk::RenderPass,
    ) -> Result<Self, BackendError> {
        let mut made = Self {
            by_vertex_entry: Vec::new(),
        };
        for (pass, draw) in frame::draws() {
            let render_pass = match pass.work {
                PassWork::Render(r) if r.depth == DepthTarget::ShadowMap => shadow_pass,
                _ => camera_pass,
            };
            let vs = draw.entry_points.0;
            let made_one = layouts
                .pipeline_layout(vs)
                .ok_or_else(|| BackendError::Device {
                    backend: NAME,
                    message: format!(
                        "no pipeline layout for {vs} (a bug in precip: please report it)"
                    ),
                })
                .and_then(|layout| draw_pipeline(device, module, layout, render_pass, draw));
            match made_one {
                Ok(p) => made.by_vertex_entry.push((vs, p)),
                Err(e) => {
                    made.destroy(device);
                    return Err(e);
                }
            }
        }
        Ok(made)
    }

    /// The pipeline of the draw whose vertex entry point is `vertex_entry`.
    #[must_use]
    pub fn get(&self, vertex_entry: &str) -> Option<vk::Pipeline> {
        self.by_vertex_entry
            .iter()
            .find(|(e, _)| *e == vertex_entry)
            .map(|(_, p)| *p)
    }

    /// Destroys the pipelines (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once (by the renderer's destroy).
        unsafe {
            for (_, p) in self.by_vertex_entry {
                device.raw.destroy_pipeline(p, None);
            }
        }
    }
}

impl KernelPipelines {
    /// Every kernel of the frame recipe, from the module of its program
    /// (`module_of`).
    pub fn new(
        device: &Device,
        module_of: impl Fn(Program) -> Option<vk::ShaderModule>,
        layouts: &RenderLayouts,
    ) -> Result<Self, BackendError> {
        let mut made = Self {
            by_entry: Vec::new(),
        };
        for kernel in frame::kernels() {
            let entry = kernel.entry_point;
            let made_one = match (module_of(kernel.program), layouts.pipeline_layout(entry)) {
                (Some(module), Some(layout)) => compute(device, layout, module, entry),
                _ => Err(BackendError::Device {
                    backend: NAME,
                    message: format!(
                        "no module or layout for {entry} (a bug in precip: please report it)"
                    ),
                }),
            };
            match made_one {
                Ok(p) => {
                    device.name(p, entry);
                    made.by_entry.push((entry, p));
                }
                Err(e) => {
                    made.destroy(device);
                    return Err(e);
                }
            }
        }
        Ok(made)
    }

    /// The pipeline of kernel `entry_point`.
    #[must_use]
    pub fn get(&self, entry_point: &str) -> Option<vk::Pipeline> {
        self.by_entry
            .iter()
            .find(|(e, _)| *e == entry_point)
            .map(|(_, p)| *p)
    }

    /// Destroys the pipelines (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once.
        unsafe {
            for (_, p) in self.by_entry {
                device.raw.destroy_pipeline(p, None);
            }
        }
    }
}
