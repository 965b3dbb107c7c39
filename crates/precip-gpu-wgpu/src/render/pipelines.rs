//! The render pipelines (per colour format, so the viewer's surface format and the
//! offscreen sRGB target both work) and the cull kernels' pipelines.

use precip_model::gpu::{COVER_TEXTURE_PASS, CULL_PASSES, SPLAT_PASS, SceneVertex, render_passes};
use precip_model::shaders::Program;

use super::layouts::RenderLayouts;
use crate::pipelines::shader_module;

/// The depth format of the shadow map and of the camera's depth buffer.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The draws of a frame for one colour format.
#[derive(Debug)]
pub struct DrawPipelines {
    /// Sun's depth.
    pub shadow: wgpu::RenderPipeline,
    /// The scene with its cover.
    pub scene: wgpu::RenderPipeline,
    /// Snow sprites.
    pub snow: wgpu::RenderPipeline,
    /// Rain tetrahedra.
    pub rain: wgpu::RenderPipeline,
    /// The splat sums blended over the frame.
    pub splat_resolve: wgpu::RenderPipeline,
}

/// The cull kernels, in the recipe's order, and the splat kernel.
#[derive(Debug)]
pub struct CullPipelines {
    /// `(kernel, pipeline)` of [`CULL_PASSES`].
    pub kernels: Vec<(precip_model::gpu::KernelPass, wgpu::ComputePipeline)>,
    /// [`SPLAT_PASS`].
    pub splat: wgpu::ComputePipeline,
    /// [`COVER_TEXTURE_PASS`].
    pub cover_texture: wgpu::ComputePipeline,
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

struct Draw<'a> {
    label: &'a str,
    layout: &'a wgpu::PipelineLayout,
    entry_points: (&'a str, Option<&'a str>),
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    topology: wgpu::PrimitiveTopology,
    depth_write: bool,
    bias: wgpu::DepthBiasState,
    colour: Option<wgpu::ColorTargetState>,
}

fn draw_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    d: &Draw<'_>,
) -> wgpu::RenderPipeline {
    let targets = [d.colour.clone()];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(d.label),
        layout: Some(d.layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(d.entry_points.0),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            buffers: d.buffers,
        },
        primitive: wgpu::PrimitiveState {
            topology: d.topology,
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(d.depth_write),
            depth_compare: Some(wgpu::CompareFunction::LessEqual),
            stencil: wgpu::StencilState::default(),
            bias: d.bias,
        }),
        multisample: wgpu::MultisampleState::default(),
        fragment: d.entry_points.1.map(|fs| wgpu::FragmentState {
            module,
            entry_point: Some(fs),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

fn pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    groups: &[&wgpu::BindGroupLayout],
) -> wgpu::PipelineLayout {
    let groups: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().map(|g| Some(*g)).collect();
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &groups,
        immediate_size: 0,
    })
}

impl DrawPipelines {
    /// The draws for colour targets of `format`.
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        layouts: &RenderLayouts,
        format: wgpu::TextureFormat,
    ) -> Self {
        let module = shader_module(device, Program::Render);
        let shadow_layout = pipeline_layout(device, "precip shadow", &[&layouts.frame]);
        let scene_layout = pipeline_layout(
            device,
            "precip scene",
            &[&layouts.frame, &layouts.light, &layouts.material],
        );
        let particle_layout = pipeline_layout(
            device,
            "precip particles",
            &[&layouts.frame, &layouts.light],
        );
        let resolve_layout = pipeline_layout(
            device,
            "precip splat resolve",
            &[&layouts.frame, &layouts.light, &layouts.splat_resolve],
        );
        let vertex = [Some(scene_vertex_layout())];
        let opaque = Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        });
        let blended = Some(wgpu::ColorTargetState {
            format,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            write_mask: wgpu::ColorWrites::ALL,
        });
        let no_bias = wgpu::DepthBiasState::default();
        Self {
            shadow: draw_pipeline(
                device,
                &module,
                &Draw {
                    label: "precip shadow",
                    layout: &shadow_layout,
                    entry_points: render_passes::SHADOW,
                    buffers: &vertex,
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    depth_write: true,
                    bias: wgpu::DepthBiasState {
                        constant: 2,
                        slope_scale: 2.0,
                        clamp: 0.0,
                    },
                    colour: None,
                },
            ),
            scene: draw_pipeline(
                device,
                &module,
                &Draw {
                    label: "precip scene",
                    layout: &scene_layout,
                    entry_points: render_passes::SCENE,
                    buffers: &vertex,
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    depth_write: true,
                    bias: no_bias,
                    colour: opaque,
                },
            ),
            snow: draw_pipeline(
                device,
                &module,
                &Draw {
                    label: "precip snow",
                    layout: &particle_layout,
                    entry_points: render_passes::SNOW,
                    buffers: &[],
                    topology: wgpu::PrimitiveTopology::TriangleStrip,
                    depth_write: false,
                    bias: no_bias,
                    colour: blended.clone(),
                },
            ),
            rain: draw_pipeline(
                device,
                &module,
                &Draw {
                    label: "precip rain",
                    layout: &particle_layout,
                    entry_points: render_passes::RAIN,
                    buffers: &[],
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    depth_write: false,
                    bias: no_bias,
                    colour: blended.clone(),
                },
            ),
            // At depth 0 it passes the less-equal test everywhere: no depth test.
            splat_resolve: draw_pipeline(
                device,
                &module,
                &Draw {
                    label: "precip splat resolve",
                    layout: &resolve_layout,
                    entry_points: render_passes::SPLAT_RESOLVE,
                    buffers: &[],
                    topology: wgpu::PrimitiveTopology::TriangleList,
                    depth_write: false,
                    bias: no_bias,
                    colour: blended,
                },
            ),
        }
    }
}

impl CullPipelines {
    /// The cull kernels.
    #[must_use]
    pub fn new(device: &wgpu::Device, layouts: &RenderLayouts) -> Self {
        let module = shader_module(device, Program::CullParticles);
        let layout = pipeline_layout(device, "precip cull", &[&layouts.cull]);
        let kernels = CULL_PASSES
            .iter()
            .map(|kernel| {
                (
                    *kernel,
                    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(kernel.entry_point),
                        layout: Some(&layout),
                        module: &module,
                        entry_point: Some(kernel.entry_point),
                        compilation_options: wgpu::PipelineCompilationOptions::default(),
                        cache: None,
                    }),
                )
            })
            .collect();
        let render = shader_module(device, Program::Render);
        let splat_layout = pipeline_layout(
            device,
            "precip splat",
            &[&layouts.frame, &layouts.light, &layouts.splat],
        );
        let splat = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(SPLAT_PASS.entry_point),
            layout: Some(&splat_layout),
            module: &render,
            entry_point: Some(SPLAT_PASS.entry_point),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        let cover_layout =
            pipeline_layout(device, "precip cover texture", &[&layouts.cover_texture]);
        let cover_texture = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(COVER_TEXTURE_PASS.entry_point),
            layout: Some(&cover_layout),
            module: &render,
            entry_point: Some(COVER_TEXTURE_PASS.entry_point),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        Self {
            kernels,
            splat,
            cover_texture,
        }
    }
}
