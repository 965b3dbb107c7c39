//! LiDAR beams ([`precip_model::sensors::lidar`]): the `query_beams` kernel over the
//! configuration's particles and ground map, its hits read back. The Vulkan backend's
//! `beams.rs` does the same with its own objects.

use precip_gpu::recipe::{beam_bindings, dispatch_size};
use precip_model::BackendError;
use precip_model::sensors::lidar::{Beam, BeamHit, BeamParams, BeamQuery};
use wgpu::util::DeviceExt;

use crate::device::GpuDevice;
use crate::programs::Programs;
use crate::readback::read_buffer;
use crate::resources::Resources;

/// Casts `beams` (validated) with `params`; one hit per beam.
pub fn query_beams(
    gpu: &GpuDevice,
    programs: &Programs,
    resources: &Resources,
    params: &BeamParams,
    beams: &[Beam],
) -> Result<Vec<BeamHit>, BackendError> {
    let device = &gpu.device;
    let params_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("precip beam params"),
        contents: bytemuck::bytes_of(params),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let beams_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("precip beams"),
        contents: bytemuck::cast_slice(beams),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let hits_bytes = (beams.len() * size_of::<BeamHit>()) as u64;
    // Filled with UNWRITTEN: a hit the kernel never wrote is found, not read as one.
    let hits = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("precip beam hits"),
        contents: bytemuck::cast_slice(&BeamQuery::unwritten_hits(beams.len())),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("precip query_beams"),
        layout: &programs.beams_layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: beam_bindings::PARAMS,
                resource: params_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: beam_bindings::FRAMES,
                resource: resources.frames.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: beam_bindings::GROUND_HEIGHT,
                resource: resources.ground.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: beam_bindings::PARTICLES,
                resource: resources.particles.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: beam_bindings::BEAMS,
                resource: beams_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: beam_bindings::HITS,
                resource: hits.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("precip query_beams"),
    });
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("query_beams"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&programs.query_beams);
        pass.set_bind_group(0, &bind_group, &[]);
        let (x, y) = dispatch_size(params.beam_count);
        pass.dispatch_workgroups(x, y, 1);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = read_buffer(gpu, &hits, hits_bytes)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
