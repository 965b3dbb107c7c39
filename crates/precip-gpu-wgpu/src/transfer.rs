//! Copying a GPU buffer back to the host (tests and tools, never the frame loop).

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
