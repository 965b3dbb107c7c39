//! The draw pipelines (per colour format, like the wgpu backend's) and the cull
//! kernels, from `precip_model::gpu::{render_passes, CULL_PASSES}` — the same entry
//! points, topologies, depth tests, bias and blending as wgpu, so the images agree.

use std::ffi::CString;

use ash::vk;
use precip_model::BackendError;
use precip_model::gpu::{
    COVER_TEXTURE_PASS, CULL_PASSES, KernelPass, SPLAT_PASS, SceneVertex, render_passes,
};

use super::layouts::RenderLayouts;
use crate::device::Device;
use crate::error::{NAME, map_vk};
use crate::programs::compute;

/// The draws of a frame for one colour format (the shadow draw is shared).
#[derive(Debug)]
pub struct DrawPipelines {
    /// The scene with its cover.
    pub scene: vk::Pipeline,
    /// Snow sprites.
    pub snow: vk::Pipeline,
    /// Rain tetrahedra.
    pub rain: vk::Pipeline,
    /// The splat sums blended over the frame.
    pub splat_resolve: vk::Pipeline,
}

/// The cull kernels, in the recipe's order, and the splat kernel.
#[derive(Debug)]
pub struct CullPipelines {
    /// `(kernel, pipeline)` of [`CULL_PASSES`].
    pub kernels: Vec<(KernelPass, vk::Pipeline)>,
    /// [`SPLAT_PASS`].
    pub splat: vk::Pipeline,
    /// [`COVER_TEXTURE_PASS`].
    pub cover_texture: vk::Pipeline,
}

/// How a draw differs from the others.
struct Draw<'a> {
    name: &'a str,
    entry_points: (&'a str, Option<&'a str>),
    scene_vertices: bool,
    topology: vk::PrimitiveTopology,
    depth_write: bool,
    /// Constant and slope-scaled depth bias (the shadow draw's, as wgpu's 2 and 2.0).
    bias: Option<(f32, f32)>,
    blend: Option<bool>,
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
    d: &Draw<'_>,
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
    let assembly = vk::PipelineInputAssemblyStateCreateInfo::default().topology(d.topology);
    let viewport = vk::PipelineViewportStateCreateInfo::default()
        .viewport_count(1)
        .scissor_count(1);
    let (constant, slope) = d.bias.unwrap_or((0.0, 0.0));
    let raster = vk::PipelineRasterizationStateCreateInfo::default()
        .polygon_mode(vk::PolygonMode::FILL)
        .cull_mode(vk::CullModeFlags::NONE)
        .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
        .depth_bias_enable(d.bias.is_some())
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
        Some(true) => vec![
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
        Some(false) => vec![
            vk::PipelineColorBlendAttachmentState::default()
                .color_write_mask(vk::ColorComponentFlags::RGBA),
        ],
        None => Vec::new(),
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
    .map_err(|(_, e)| map_vk(&format!("creating the {} pipeline", d.name), e))?[0];
    device.name(pipeline, d.name);
    Ok(pipeline)
}

/// The shadow draw (depth only, biased like wgpu's: constant 2, slope 2.0).
pub fn shadow_pipeline(
    device: &Device,
    module: vk::ShaderModule,
    layouts: &RenderLayouts,
    shadow_pass: vk::RenderPass,
) -> Result<vk::Pipeline, BackendError> {
    draw_pipeline(
        device,
        module,
        layouts.draw_layout,
        shadow_pass,
        &Draw {
            name: "precip shadow",
            entry_points: render_passes::SHADOW,
            scene_vertices: true,
            topology: vk::PrimitiveTopology::TRIANGLE_LIST,
            depth_write: true,
            bias: Some((2.0, 2.0)),
            blend: None,
        },
    )
}

impl DrawPipelines {
    /// The draws for a camera pass `pass` (its colour format).
    pub fn new(
        device: &Device,
        module: vk::ShaderModule,
        layouts: &RenderLayouts,
        pass: vk::RenderPass,
    ) -> Result<Self, BackendError> {
        let layout = layouts.draw_layout;
        let scene = draw_pipeline(
            device,
            module,
            layout,
            pass,
            &Draw {
                name: "precip scene",
                entry_points: render_passes::SCENE,
                scene_vertices: true,
                topology: vk::PrimitiveTopology::TRIANGLE_LIST,
                depth_write: true,
                bias: None,
                blend: Some(false),
            },
        )?;
        let particles = |name, entry_points, topology| Draw {
            name,
            entry_points,
            scene_vertices: false,
            topology,
            depth_write: false,
            bias: None,
            blend: Some(true),
        };
        let snow = draw_pipeline(
            device,
            module,
            layout,
            pass,
            &particles(
                "precip snow",
                render_passes::SNOW,
                vk::PrimitiveTopology::TRIANGLE_STRIP,
            ),
        )?;
        let rain = draw_pipeline(
            device,
            module,
            layout,
            pass,
            &particles(
                "precip rain",
                render_passes::RAIN,
                vk::PrimitiveTopology::TRIANGLE_LIST,
            ),
        )?;
        // At depth 0 it passes the less-equal test everywhere: no depth test.
        let splat_resolve = draw_pipeline(
            device,
            module,
            layouts.resolve_layout,
            pass,
            &particles(
                "precip splat resolve",
                render_passes::SPLAT_RESOLVE,
                vk::PrimitiveTopology::TRIANGLE_LIST,
            ),
        )?;
        Ok(Self {
            scene,
            snow,
            rain,
            splat_resolve,
        })
    }

    /// Destroys the pipelines (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once (by the renderer's destroy).
        unsafe {
            for p in [self.scene, self.snow, self.rain, self.splat_resolve] {
                device.raw.destroy_pipeline(p, None);
            }
        }
    }
}

impl CullPipelines {
    /// The cull kernels of `module` (the `CullParticles` program) and the splat
    /// kernel of `render_module` (the `Render` program).
    pub fn new(
        device: &Device,
        module: vk::ShaderModule,
        render_module: vk::ShaderModule,
        layouts: &RenderLayouts,
    ) -> Result<Self, BackendError> {
        let mut kernels = Vec::with_capacity(CULL_PASSES.len());
        for kernel in CULL_PASSES {
            let pipeline = compute(device, layouts.cull_layout, module, kernel.entry_point)?;
            device.name(pipeline, kernel.entry_point);
            kernels.push((kernel, pipeline));
        }
        let mut made = Self {
            kernels,
            splat: vk::Pipeline::null(),
            cover_texture: vk::Pipeline::null(),
        };
        for (kernel, layout) in [
            (SPLAT_PASS, layouts.splat_layout),
            (COVER_TEXTURE_PASS, layouts.cover_texture_layout),
        ] {
            let pipeline = match compute(device, layout, render_module, kernel.entry_point) {
                Ok(p) => p,
                Err(e) => {
                    made.destroy(device);
                    return Err(e);
                }
            };
            device.name(pipeline, kernel.entry_point);
            if kernel == SPLAT_PASS {
                made.splat = pipeline;
            } else {
                made.cover_texture = pipeline;
            }
        }
        Ok(made)
    }

    /// Destroys the pipelines (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once.
        unsafe {
            for (_, p) in &self.kernels {
                device.raw.destroy_pipeline(*p, None);
            }
            device.raw.destroy_pipeline(self.splat, None);
            device.raw.destroy_pipeline(self.cover_texture, None);
        }
    }
}
