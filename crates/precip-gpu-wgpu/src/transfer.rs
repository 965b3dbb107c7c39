//! Copying a GPU buffer or texture back to the host (read-backs, tests and tools,
//! never the frame loop).

use precip_model::BackendError;

use crate::device::GpuDevice;
use crate::error::map_device_error;

/// Copies `size` bytes of `source` back, waiting for the GPU.
pub fn read_buffer(
    gpu: &GpuDevice,
    source: &wgpu::Buffer,
    size: u64,
) -> Result<Vec<u8>, BackendError> {
    if size == 0 {
        return Ok(Vec::new());
    }
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("precip readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("precip readback"),
        });
    encoder.copy_buffer_to_buffer(source, 0, &staging, 0, size);
    gpu.queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    staging
        .slice(..)
        .map_async(wgpu::MapMode::Read, move |result| {
            // The receiver waits below; a send error means it is gone, nothing to do.
            let _ = sender.send(result);
        });
    gpu.wait()?;
    receiver
        .recv()
        .map_err(|e| map_device_error("reading back", &e))?
        .map_err(|e| map_device_error("mapping the read-back buffer", &e))?;
    let bytes = staging
        .slice(..)
        .get_mapped_range()
        .map_err(|e| map_device_error("reading the mapped buffer", &e))?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}

/// Every texel of `texture` (a 2D texture made with `COPY_SRC`), rows tightly
/// packed, waiting for the GPU.
pub fn read_texture(gpu: &GpuDevice, texture: &wgpu::Texture) -> Result<Vec<u8>, BackendError> {
    let (width, height) = (texture.width(), texture.height());
    let row = width * texture.format().block_copy_size(None).unwrap_or(4);
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("precip image copy"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("precip image copy"),
        });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);
    let bytes = read_buffer(gpu, &buffer, u64::from(padded) * u64::from(height));
    buffer.destroy();
    let bytes = bytes?;
    let mut texels = Vec::with_capacity((row * height) as usize);
    for r in 0..height as usize {
        let start = r * padded as usize;
        texels.extend_from_slice(&bytes[start..start + row as usize]);
    }
    Ok(texels)
}

/// A colour texture of 4-byte texels as an [`precip_model::Image`] (tests and tools:
/// a window's image).
pub fn read_image(
    gpu: &GpuDevice,
    texture: &wgpu::Texture,
) -> Result<precip_model::Image, BackendError> {
    Ok(precip_model::Image {
        width_px: texture.width(),
        height_px: texture.height(),
        rgba8: read_texture(gpu, texture)?,
    })
}
