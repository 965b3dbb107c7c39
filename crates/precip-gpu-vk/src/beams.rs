//! LiDAR beams ([`precip_model::sensors::lidar`]): the `query_beams` kernel over the
//! configuration's particles and ground map, its hits read back. The wgpu backend's
//! `beams.rs` does the same with its own objects.
//!
//! Each query makes its beam, hit and parameter buffers and a one-set descriptor pool,
//! waits for the kernel, and frees them all on every path.

use ash::vk;
use gpu_allocator::MemoryLocation;
use precip_gpu::recipe::{Frames, beam_bindings, dispatch_size};
use precip_model::BackendError;
use precip_model::sensors::lidar::{Beam, BeamHit, BeamParams, BeamQuery};

use crate::buffer::Buffer;
use crate::commands::{record_dispatch, submit};
use crate::descriptors::{self, buffer_info, write};
use crate::device::Device;
use crate::programs::Programs;
use crate::resources::{Resources, download, upload};

/// What one query allocates; [`QueryObjects::destroy`] frees it all.
struct QueryObjects {
    buffers: Vec<Buffer>,
    pool: Option<vk::DescriptorPool>,
}

impl QueryObjects {
    fn destroy(self, device: &Device) {
        for b in self.buffers {
            b.destroy(device);
        }
        if let Some(pool) = self.pool {
            // SAFETY: the query waited for its submission; the pool's set is unused.
            unsafe { device.raw.destroy_descriptor_pool(pool, None) };
        }
    }
}

/// Casts `beams` (validated) with `params`; one hit per beam. The device must be done
/// with earlier steps (the caller settles first).
pub fn query_beams(
    device: &Device,
    programs: &Programs,
    resources: &Resources,
    params: &BeamParams,
    beams: &[Beam],
) -> Result<Vec<BeamHit>, BackendError> {
    let mut objects = QueryObjects {
        buffers: Vec::new(),
        pool: None,
    };
    let result = run(device, programs, resources, params, beams, &mut objects);
    objects.destroy(device);
    result
}

fn run(
    device: &Device,
    programs: &Programs,
    resources: &Resources,
    params: &BeamParams,
    beams: &[Beam],
    objects: &mut QueryObjects,
) -> Result<Vec<BeamHit>, BackendError> {
    use vk::BufferUsageFlags as U;
    let mut params_buffer = Buffer::new(
        device,
        "beam params",
        size_of::<BeamParams>() as u64,
        U::UNIFORM_BUFFER,
        MemoryLocation::CpuToGpu,
    )?;
    let written = params_buffer.write(0, bytemuck::bytes_of(params));
    objects.buffers.push(params_buffer);
    written?;
    let beam_bytes: &[u8] = bytemuck::cast_slice(beams);
    objects.buffers.push(Buffer::new(
        device,
        "beams",
        beam_bytes.len() as u64,
        U::STORAGE_BUFFER | U::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )?);
    let hits_bytes = (beams.len() * size_of::<BeamHit>()) as u64;
    objects.buffers.push(Buffer::new(
        device,
        "beam hits",
        hits_bytes,
        U::STORAGE_BUFFER | U::TRANSFER_SRC | U::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )?);
    let [params_buffer, beams_buffer, hits] = &objects.buffers[..] else {
        return Err(BackendError::Device {
            backend: crate::error::NAME,
            message: "the beam query lost a buffer (a bug in precip: please report it)".into(),
        });
    };
    upload(device, beams_buffer, beam_bytes)?;
    // Filled with UNWRITTEN: a hit the kernel never wrote is found, not read as one.
    upload(
        device,
        hits,
        bytemuck::cast_slice(&BeamQuery::unwritten_hits(beams.len())),
    )?;
    use vk::DescriptorType as T;
    let pool = descriptors::pool(
        device,
        "beams",
        &[(T::UNIFORM_BUFFER, 2), (T::STORAGE_BUFFER, 4)],
        1,
    )?;
    objects.pool = Some(pool);
    let set = descriptors::allocate(device, pool, &[programs.beams_set_layout])?[0];
    let whole = vk::WHOLE_SIZE;
    let params_info = buffer_info(params_buffer, size_of::<BeamParams>() as u64);
    let frames_info = buffer_info(&resources.frames, size_of::<Frames>() as u64);
    let ground_info = buffer_info(&resources.ground, whole);
    let particles_info = buffer_info(&resources.particles, whole);
    let beams_info = buffer_info(beams_buffer, whole);
    let hits_info = buffer_info(hits, whole);
    let writes = [
        write(set, beam_bindings::PARAMS, T::UNIFORM_BUFFER).buffer_info(&params_info),
        write(set, beam_bindings::FRAMES, T::UNIFORM_BUFFER).buffer_info(&frames_info),
        write(set, beam_bindings::GROUND_HEIGHT, T::STORAGE_BUFFER).buffer_info(&ground_info),
        write(set, beam_bindings::PARTICLES, T::STORAGE_BUFFER).buffer_info(&particles_info),
        write(set, beam_bindings::BEAMS, T::STORAGE_BUFFER).buffer_info(&beams_info),
        write(set, beam_bindings::HITS, T::STORAGE_BUFFER).buffer_info(&hits_info),
    ];
    // SAFETY: every write names a live buffer of the binding's type and usage.
    unsafe { device.raw.update_descriptor_sets(&writes, &[]) };
    submit(device, |cb| {
        // SAFETY: `cb` is recording outside a render pass (inside `submit`); the
        // pipeline was made with the beams layout, whose set has no dynamic binding.
        unsafe {
            record_dispatch(
                device,
                cb,
                (programs.query_beams, programs.beams_layout),
                set,
                &[],
                dispatch_size(params.beam_count),
            );
        }
    })?
    .wait(device)?;
    let bytes = download(device, hits, hits_bytes)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
