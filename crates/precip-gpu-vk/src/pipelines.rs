//! Graphics pipelines from the frame's recipe (`precip_gpu::frame::Draw`): the same
//! entry points, topologies, depth tests, bias and blending as wgpu's, so the
//! images agree (wgpu twin: `precip_gpu_wgpu::pipelines`).

use std::ffi::CString;

use ash::vk;
use precip_gpu::frame::{Blend, Draw, Topology};
use precip_gpu::recipe::SceneVertex;
use precip_model::BackendError;

use crate::device::Device;
use crate::error::{NAME, map_vk};

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

/// The graphics pipeline of `d` (the recipe's entry points, topology, depth test,
/// bias and blending, as wgpu's) on `layout`, for passes compatible with `pass`.
pub fn draw_pipeline(
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
    // wgpu's BlendState::ALPHA_BLENDING: colour src·α + dst·(1 − α), alpha "over";
    // PREMULTIPLIED_ALPHA_BLENDING: colour src + dst·(1 − α), alpha "over".
    let over = |src_colour| {
        vec![
            vk::PipelineColorBlendAttachmentState::default()
                .blend_enable(true)
                .src_color_blend_factor(src_colour)
                .dst_color_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                .color_blend_op(vk::BlendOp::ADD)
                .src_alpha_blend_factor(vk::BlendFactor::ONE)
                .dst_alpha_blend_factor(vk::BlendFactor::ONE_MINUS_SRC_ALPHA)
                .alpha_blend_op(vk::BlendOp::ADD)
                .color_write_mask(vk::ColorComponentFlags::RGBA),
        ]
    };
    let attachment = match d.blend {
        Blend::Alpha => over(vk::BlendFactor::SRC_ALPHA),
        Blend::Premultiplied => over(vk::BlendFactor::ONE),
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
