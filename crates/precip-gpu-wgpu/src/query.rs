//! Timestamp queries on wgpu (Vulkan twin: `precip_gpu_vk::query`): one set for a
//! step's kernels (one before the first and one after each, needs timestamps inside
//! passes) and one for a frame's passes (two a pass, at its start and its end).

use precip_gpu::frame::FRAME_PASSES;
use precip_gpu::recipe::SUBSTEP_KERNELS;
use precip_model::BackendError;
use precip_model::backend::MAX_SUBSTEPS;

use crate::device::GpuDevice;
use crate::transfer::read_buffer;

/// Queries of a step: one before the first kernel and one after each.
pub const QUERY_COUNT: u32 = 1 + SUBSTEP_KERNELS as u32 * MAX_SUBSTEPS;

/// Queries of a frame: two a pass.
pub const FRAME_QUERY_COUNT: u32 = 2 * FRAME_PASSES.len() as u32;

/// A query set, its resolve buffer and how many of its queries the last submission
/// wrote.
#[derive(Debug)]
pub struct Timestamps {
    /// The set.
    pub set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    /// Queries written by the last submission that wrote any.
    pub written: u32,
    count: u32,
    period_ns: f32,
}

impl Timestamps {
    /// `count` queries, or `None` when the device lacks `needs`.
    #[must_use]
    pub fn new(
        gpu: &GpuDevice,
        label: &'static str,
        count: u32,
        needs: wgpu::Features,
    ) -> Option<Self> {
        if !gpu.device.features().contains(needs) {
            return None;
        }
        Some(Self {
            set: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some(label),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: u64::from(count) * 8,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            written: 0,
            count,
            period_ns: gpu.queue.get_timestamp_period(),
        })
    }

    /// The step's set (timestamps between dispatches of one pass).
    #[must_use]
    pub fn for_steps(gpu: &GpuDevice) -> Option<Self> {
        Self::new(
            gpu,
            "precip timestamps",
            QUERY_COUNT,
            wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_PASSES,
        )
    }

    /// The frame's set (timestamps at passes' starts and ends).
    #[must_use]
    pub fn for_frames(gpu: &GpuDevice) -> Option<Self> {
        Self::new(
            gpu,
            "precip frame timestamps",
            FRAME_QUERY_COUNT,
            wgpu::Features::TIMESTAMP_QUERY,
        )
    }

    /// The buffer the set is resolved into.
    #[must_use]
    pub fn resolve_buffer(&self) -> &wgpu::Buffer {
        &self.resolve
    }

    /// How many queries the set holds.
    #[must_use]
    pub fn capacity(&self) -> u32 {
        self.count
    }

    fn ticks(&self, gpu: &GpuDevice) -> Result<Vec<u64>, BackendError> {
        let bytes = read_buffer(gpu, &self.resolve, u64::from(self.written) * 8)?;
        Ok(bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect())
    }

    fn ms(&self, from: u64, to: u64) -> f64 {
        to.saturating_sub(from) as f64 * f64::from(self.period_ns) * 1.0e-6
    }

    /// The milliseconds between consecutive timestamps (waits for the GPU).
    pub fn elapsed_ms(&self, gpu: &GpuDevice) -> Result<Vec<f64>, BackendError> {
        if self.written < 2 {
            return Ok(Vec::new());
        }
        let ticks = self.ticks(gpu)?;
        Ok(ticks.windows(2).map(|p| self.ms(p[0], p[1])).collect())
    }

    /// The milliseconds between the two timestamps of each pair (waits).
    pub fn pairs_ms(&self, gpu: &GpuDevice) -> Result<Vec<f64>, BackendError> {
        if self.written < 2 {
            return Ok(Vec::new());
        }
        let ticks = self.ticks(gpu)?;
        Ok(ticks.chunks_exact(2).map(|p| self.ms(p[0], p[1])).collect())
    }
}
