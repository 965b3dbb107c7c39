//! Render pipelines from the frame's recipe (`precip_gpu::frame::Draw`): entry
//! points, topology, depth test, bias and blending as the recipe says (Vulkan twin:
//! `precip_gpu_vk::pipelines`).

use precip_gpu::frame::{Blend, Draw, Topology};
use precip_gpu::recipe::SceneVertex;

use crate::gpu::DEPTH_FORMAT;

const SCENE_ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
    0 => Float32x3,
    1 => Float32x3,
    2 => Float32x2,
    3 => Float32,
];

/// The render pipeline of `d` (its pipeline state as the recipe says).
pub fn draw_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    layout: &wgpu::PipelineLayout,
    d: &Draw,
    format: Option<wgpu::TextureFormat>,
) -> wgpu::RenderPipeline {
    let (vs, fs) = d.entry_points;
    let blend = match d.blend {
        Blend::Alpha => Some(wgpu::BlendState::ALPHA_BLENDING),
        Blend::Premultiplied => Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
        Blend::Opaque | Blend::None => None,
    };
    let targets =
        [format
            .filter(|_| d.blend != Blend::None)
            .map(|format| wgpu::ColorTargetState {
                format,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            })];
    let scene_vertices = [Some(wgpu::VertexBufferLayout {
        array_stride: size_of::<SceneVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &SCENE_ATTRIBUTES,
    })];
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
        layout: Some(layout),
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
