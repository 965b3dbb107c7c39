//! Copies between the host and the device: uploads (through a staging buffer),
//! read-backs, image fills and layout changes, each waited for.

use ash::vk;
use gpu_allocator::MemoryLocation;
use precip_model::BackendError;

use crate::buffer::Buffer;
use crate::commands::{SHADER_STAGES, compute_barrier, image_barriers, submit};
use crate::device::Device;
use crate::image::Image;

/// Steps recorded ahead of the GPU: each has its own ring of uniform blocks and
/// queries, so the host writes step n + 1's while step n runs.
pub const FRAMES_IN_FLIGHT: usize = 2;

// Each frame in flight has its own copy of the terrain's windows.
const _: () = assert!(
    FRAMES_IN_FLIGHT as u32 <= precip_model::scene::terrain::CLIPMAP_WINDOW_SLOTS,
    "a frame slot without terrain windows"
);

/// Copies `bytes` into `target` at `offset` through a staging buffer (waits).
pub fn upload_at(
    device: &Device,
    target: &Buffer,
    offset: u64,
    bytes: &[u8],
) -> Result<(), BackendError> {
    if bytes.is_empty() {
        return Ok(());
    }
    let mut staging = Buffer::new(
        device,
        "staging",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    staging.write(0, bytes)?;
    let result = submit(device, |cb| {
        let region = vk::BufferCopy {
            src_offset: 0,
            dst_offset: offset,
            size: bytes.len() as u64,
        };
        // SAFETY: both buffers are live and large enough; `cb` is recording.
        unsafe {
            device
                .raw
                .cmd_copy_buffer(cb, staging.raw, target.raw, &[region])
        };
        // SAFETY: `cb` is recording, outside a render pass (inside `submit`).
        unsafe { compute_barrier(device, cb) };
    })
    .and_then(|f| f.wait(device));
    staging.destroy(device);
    result
}

/// Copies the first `size` bytes of `source` back (waits).
pub fn download(device: &Device, source: &Buffer, size: u64) -> Result<Vec<u8>, BackendError> {
    if size == 0 {
        return Ok(Vec::new());
    }
    let staging = Buffer::new(
        device,
        "read-back",
        size,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    let result = submit(device, |cb| {
        let region = vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size,
        };
        // SAFETY: both buffers are live and large enough; `cb` is recording.
        unsafe {
            device
                .raw
                .cmd_copy_buffer(cb, source.raw, staging.raw, &[region])
        };
    })
    .and_then(|f| f.wait(device))
    .and_then(|()| staging.read(size as usize));
    staging.destroy(device);
    result
}

/// A barrier moving all of colour `image` from layout `old` (after accesses `src`)
/// to `new` (before accesses `dst`).
fn layout_barrier(
    image: &Image,
    from: (vk::ImageLayout, vk::AccessFlags),
    to: (vk::ImageLayout, vk::AccessFlags),
) -> vk::ImageMemoryBarrier<'static> {
    image_barrier(image.raw, image.range(), from, to)
}

/// A barrier moving the `range` of `image` from layout and access `from` to `to`.
pub fn image_barrier(
    image: vk::Image,
    range: vk::ImageSubresourceRange,
    (old, src): (vk::ImageLayout, vk::AccessFlags),
    (new, dst): (vk::ImageLayout, vk::AccessFlags),
) -> vk::ImageMemoryBarrier<'static> {
    vk::ImageMemoryBarrier::default()
        .old_layout(old)
        .new_layout(new)
        .src_access_mask(src)
        .dst_access_mask(dst)
        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .image(image)
        .subresource_range(range)
}

/// A copy of every texel of a colour image of `extent`, tightly packed in the buffer.
fn whole_image(extent: glam::UVec3) -> vk::BufferImageCopy {
    vk::BufferImageCopy::default()
        .image_subresource(vk::ImageSubresourceLayers {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            mip_level: 0,
            base_array_layer: 0,
            layer_count: 1,
        })
        .image_extent(vk::Extent3D {
            width: extent.x,
            height: extent.y,
            depth: extent.z,
        })
}

/// Fills a sampled image's texels (`bytes` tightly packed) and leaves it in
/// `SHADER_READ_ONLY_OPTIMAL` for every shader stage (waits).
pub fn upload_image(device: &Device, image: &Image, bytes: &[u8]) -> Result<(), BackendError> {
    let mut staging = Buffer::new(
        device,
        "image staging",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    staging.write(0, bytes)?;
    let e = image.extent;
    let result = submit(device, |cb| {
        let barrier = |old, new, src, dst| layout_barrier(image, (old, src), (new, dst));
        let to_transfer = barrier(
            vk::ImageLayout::UNDEFINED,
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            vk::AccessFlags::empty(),
            vk::AccessFlags::TRANSFER_WRITE,
        );
        let to_shader = barrier(
            vk::ImageLayout::TRANSFER_DST_OPTIMAL,
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            vk::AccessFlags::TRANSFER_WRITE,
            vk::AccessFlags::SHADER_READ,
        );
        let region = whole_image(e);
        // SAFETY: `cb` is recording; the image and staging buffer are live; the
        // barriers move the whole image through the layouts the copy and the shaders
        // need (the earlier contents are discarded: UNDEFINED), after any earlier
        // work that read it.
        unsafe {
            let stages = (
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::TRANSFER,
            );
            image_barriers(device, cb, stages, &[to_transfer]);
            device.raw.cmd_copy_buffer_to_image(
                cb,
                staging.raw,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
            );
            let stages = (vk::PipelineStageFlags::TRANSFER, SHADER_STAGES);
            image_barriers(device, cb, stages, &[to_shader]);
        }
    })
    .and_then(|f| f.wait(device));
    staging.destroy(device);
    result
}

/// Moves `images` (just made) to `layout` (`GENERAL`, where shaders both write
/// storage images and sample them; a depth buffer's read-only layout); waits.
pub fn to_layout(
    device: &Device,
    images: &[&Image],
    layout: vk::ImageLayout,
) -> Result<(), BackendError> {
    let barriers: Vec<vk::ImageMemoryBarrier<'_>> = images
        .iter()
        .map(|image| {
            layout_barrier(
                image,
                (vk::ImageLayout::UNDEFINED, vk::AccessFlags::empty()),
                (
                    layout,
                    vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
                ),
            )
        })
        .collect();
    submit(device, |cb| {
        // SAFETY: `cb` is recording; the images are live and unused (just made).
        unsafe {
            let stages = (vk::PipelineStageFlags::TOP_OF_PIPE, SHADER_STAGES);
            image_barriers(device, cb, stages, &barriers);
        }
    })
    .and_then(|f| f.wait(device))
}

/// Every texel of the 2D colour `image` (resting in `layout`, made with
/// `TRANSFER_SRC`), `texel_bytes` each, rows tightly packed (waits).
pub fn download_image(
    device: &Device,
    image: &Image,
    layout: vk::ImageLayout,
    texel_bytes: u32,
) -> Result<Vec<u8>, BackendError> {
    use vk::{ImageLayout as L, PipelineStageFlags as S};
    let (width, height) = image.size();
    let bytes = u64::from(width) * u64::from(height) * u64::from(texel_bytes);
    let staging = Buffer::new(
        device,
        "image read-back",
        bytes,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    let region = whole_image(image.extent);
    // An image resting in another layout (a storage image's GENERAL) is moved to
    // the one copies read best from, and back.
    let copy = (L::TRANSFER_SRC_OPTIMAL, vk::AccessFlags::TRANSFER_READ);
    let rest = (
        layout,
        vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE,
    );
    let (any, transfer) = (S::ALL_COMMANDS, S::TRANSFER);
    let result = submit(device, |cb| {
        // SAFETY: `cb` is recording, outside a render pass; the image rests in
        // `layout` and the barriers name it, there and back; the staging buffer is
        // live and large enough.
        unsafe {
            let unless_there = |stages, from, to| {
                if layout != copy.0 {
                    image_barriers(device, cb, stages, &[layout_barrier(image, from, to)]);
                }
            };
            unless_there((any, transfer), rest, copy);
            device
                .raw
                .cmd_copy_image_to_buffer(cb, image.raw, copy.0, staging.raw, &[region]);
            unless_there((transfer, any), copy, rest);
        }
    })
    .and_then(|f| f.wait(device))
    .and_then(|()| staging.read(bytes as usize));
    staging.destroy(device);
    result
}
