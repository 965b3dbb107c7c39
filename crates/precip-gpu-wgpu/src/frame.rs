//! A frame's commands into wgpu passes (Vulkan twin: `precip_gpu_vk::frame`): each
//! pass of the renderer's `FrameWork` that runs becomes a compute pass or a render
//! pass between its two timestamps; wgpu tracks the barriers and layouts itself.

use precip_gpu::frame::AttachmentLoad;
use precip_gpu::gpu::{Command, PassKind, RecordedPass};

use crate::gpu::Hal;
use crate::query::Timestamps;

fn load_op<V>(load: AttachmentLoad, clear: V) -> wgpu::LoadOp<V> {
    match load {
        AttachmentLoad::Clear => wgpu::LoadOp::Clear(clear),
        AttachmentLoad::Load => wgpu::LoadOp::Load,
    }
}

/// Records pass `index` of a frame (its commands between its two timestamps).
pub fn encode_pass(
    encoder: &mut wgpu::CommandEncoder,
    pass: &RecordedPass<'_, Hal>,
    index: u32,
    stamps: Option<&Timestamps>,
    colour: &wgpu::TextureView,
) {
    let (begin, end) = (Some(2 * index), Some(2 * index + 1));
    match &pass.kind {
        PassKind::CopyTarget {
            colour: copy,
            depth,
        } => {
            // Copies have no timestamps of their own in wgpu: an empty compute pass
            // writes each of the pass's two.
            let stamp = |encoder: &mut wgpu::CommandEncoder, at| {
                encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(pass.name),
                    timestamp_writes: stamps.map(|s| wgpu::ComputePassTimestampWrites {
                        query_set: &s.set,
                        beginning_of_pass_write_index: at,
                        end_of_pass_write_index: None,
                    }),
                });
            };
            stamp(encoder, begin);
            for (from, to) in [
                (colour.texture(), &copy.texture),
                (&depth.0.texture, &depth.1.texture),
            ] {
                encoder.copy_texture_to_texture(
                    from.as_image_copy(),
                    to.as_image_copy(),
                    from.size(),
                );
            }
            stamp(encoder, end);
        }
        PassKind::Compute => {
            let mut compute = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(pass.name),
                timestamp_writes: stamps.map(|s| wgpu::ComputePassTimestampWrites {
                    query_set: &s.set,
                    beginning_of_pass_write_index: begin,
                    end_of_pass_write_index: end,
                }),
            });
            for command in &pass.commands {
                match command {
                    Command::Kernel(k) => compute.set_pipeline(k),
                    Command::Group {
                        index,
                        group,
                        offsets,
                    } => compute.set_bind_group(*index, *group, offsets),
                    Command::Dispatch(x, y) => compute.dispatch_workgroups(*x, *y, 1),
                    _ => {}
                }
            }
        }
        PassKind::Render(attachments) => {
            let recipe = attachments.recipe;
            let [r, g, b, a] = attachments.clear_colour.map(f64::from);
            let view = attachments.colour.map_or(colour, |t| &t.view);
            let colour = recipe.colour.map(|load| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: load_op(load, wgpu::Color { r, g, b, a }),
                        store: wgpu::StoreOp::Store,
                    },
                })
            });
            let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(pass.name),
                color_attachments: match &colour {
                    Some(c) => std::slice::from_ref(c),
                    None => &[],
                },
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &attachments.depth.view,
                    depth_ops: Some(wgpu::Operations {
                        load: load_op(recipe.depth_load, 1.0),
                        store: if recipe.depth_stored {
                            wgpu::StoreOp::Store
                        } else {
                            wgpu::StoreOp::Discard
                        },
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: stamps.map(|s| wgpu::RenderPassTimestampWrites {
                    query_set: &s.set,
                    beginning_of_pass_write_index: begin,
                    end_of_pass_write_index: end,
                }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if let Some([x, y, width, height]) = attachments.scissor {
                render.set_scissor_rect(x, y, width, height);
            }
            for command in &pass.commands {
                match command {
                    Command::Pipeline(p) => render.set_pipeline(p),
                    Command::Group {
                        index,
                        group,
                        offsets,
                    } => render.set_bind_group(*index, *group, offsets),
                    Command::Meshes { vertices, indices } => {
                        render.set_vertex_buffer(0, vertices.slice(..));
                        render.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                    }
                    Command::Draw(n) => render.draw(0..*n, 0..1),
                    Command::DrawIndexed(range) => render.draw_indexed(range.clone(), 0, 0..1),
                    Command::DrawIndirect(buffer, offset) => render.draw_indirect(buffer, *offset),
                    Command::Kernel(_) | Command::Dispatch(..) => {}
                }
            }
        }
    }
}
