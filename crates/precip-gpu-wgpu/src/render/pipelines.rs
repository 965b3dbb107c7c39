//! The frame's pipelines, made from the recipe (`precip_gpu::frame`): one
//! render pipeline per [`Draw`] (per colour format, so the viewer's surface format
//! and the offscreen sRGB target both work) and one compute pipeline per kernel,
//! each with the pipeline layout of its entry point's groups
//! (`precip_gpu::bind_groups::groups_of`). Vulkan twin: `precip_gpu_vk::render::pipelines`.

use precip_gpu::bind_groups::{GroupLayout, groups_of};
use precip_gpu::frame::{self, Blend, Draw, Topology};
use precip_gpu::recipe::SceneVertex;
use precip_gpu::shaders::Program;

use super::layouts::RenderLayouts;
use crate::gpu::shader_module;

/// The depth format of the shadow map and of the camera's depth buffer.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The draws of a frame for one colour format, by vertex entry point.
#[derive(Debug)]
pub struct DrawPipelines {
    by_vertex_entry: Vec<(&'static str, wgpu::RenderPipeline)>,
}

/// The frame's compute kernels, by entry point.
#[derive(Debug)]
pub struct KernelPipelines {
    by_entry: Vec<(&'static str, wgpu::ComputePipeline)>,
}

const SCENE_ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
    0 => Float32x3,
    1 => Float32x3,
    2 => Float32x2,
    3 => Float32,
];

fn scene_vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: size_of::<SceneVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &SCENE_ATTRIBUTES,
    }
}

/// The pipeline layout of `groups`.
fn pipeline_layout(
    device: &wgpu::Device,
    layouts: &RenderLayouts,
    label: &str,
    groups: &[GroupLayout],
) -> wgpu::PipelineLayout {
    let groups: Vec<Option<&wgpu::BindGroupLayout>> =
        groups.iter().map(|g| layouts.of(g)).collect();
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &groups,
        immediate_size: 0,
    })
}

fn draw_pipeline(
    device: &wgpu::Device,
    layouts: &RenderLayouts,
    module: &wgpu::ShaderModule,
    d: &Draw,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let (vs, fs) = d.entry_points;
    let layout = pipeline_layout(
        device,
        layouts,
        vs,
        groups_of(Program::Render, vs).unwrap_or(&[]),
    );
    let targets = [match d.blend {
        Blend::None => None,
        Blend::Opaque => Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        }),
        Blend::Alpha => Some(wgpu::ColorTargetState {
            format,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            write_mask: wgpu::ColorWrites::ALL,
        }),
    }];
    let scene_vertices = [Some(scene_vertex_layout())];
    let bias = d
        .depth_bias
        .map_or_else(wgpu::DepthBiasState::default, |(constant, slope)| {
            wgpu::DepthBiasState {
                constant,
                slope_scale: slope,
                clamp: 0.0,
            }
        });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(vs),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vs),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: if d.scene_vertices {
                &scene_vertices
            } else {
                &[]
            },
        },
        primitive: wgpu::PrimitiveState {
            topology: match d.topology {
                Topology::TriangleList => wgpu::PrimitiveTopology::TriangleList,
                Topology::TriangleStrip => wgpu::PrimitiveTopology::TriangleStrip,
            },
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(d.depth_write),
            depth_compare: Some(wgpu::CompareFunction::LessEqual),
            stencil: wgpu::StencilState::default(),
            bias,
        }),
        multisample: wgpu::MultisampleState::default(),
        fragment: fs.map(|fs| wgpu::FragmentState {
            module,
            entry_point: Some(fs),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

impl DrawPipelines {
    /// Every draw of the frame recipe, for colour targets of `format`.
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        layouts: &RenderLayouts,
        format: wgpu::TextureFormat,
    ) -> Self {
        let module = shader_module(device, Program::Render);
        Self {
            by_vertex_entry: frame::draws()
                .map(|(_, d)| {
                    (
                        d.entry_points.0,
                        draw_pipeline(device, layouts, &module, d, format),
                    )
                })
                .collect(),
        }
    }

    /// The pipeline of the draw whose vertex entry point is `vertex_entry`.
    #[must_use]
    pub fn get(&self, vertex_entry: &str) -> Option<&wgpu::RenderPipeline> {
        self.by_vertex_entry
            .iter()
            .find(|(e, _)| *e == vertex_entry)
            .map(|(_, p)| p)
    }
}

impl KernelPipelines {
    /// Every kernel of the frame recipe.
    #[must_use]
    pub fn new(device: &wgpu::Device, layouts: &RenderLayouts) -> Self {
        let mut modules: Vec<(Program, wgpu::ShaderModule)> = Vec::new();
        let mut by_entry = Vec::new();
        for kernel in frame::kernels() {
            if !modules.iter().any(|(p, _)| *p == kernel.program) {
                modules.push((kernel.program, shader_module(device, kernel.program)));
            }
            let Some((_, module)) = modules.iter().find(|(p, _)| *p == kernel.program) else {
                continue;
            };
            let layout = pipeline_layout(
                device,
                layouts,
                kernel.entry_point,
                groups_of(kernel.program, kernel.entry_point).unwrap_or(&[]),
            );
            by_entry.push((
                kernel.entry_point,
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(kernel.entry_point),
                    layout: Some(&layout),
                    module,
                    entry_point: Some(kernel.entry_point),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    cache: None,
                }),
            ));
        }
        Self { by_entry }
    }

    /// The pipeline of kernel `entry_point`.
    #[must_use]
    pub fn get(&self, entry_point: &str) -> Option<&wgpu::ComputePipeline> {
        self.by_entry
            .iter()
            .find(|(e, _)| *e == entry_point)
            .map(|(_, p)| p)
    }
}
