//! GPU timestamp queries around each kernel of a step.
//!
//! Where the device has `TIMESTAMP_QUERY_INSIDE_PASSES`, a timestamp is written
//! before the first kernel and after every kernel of every sub-step; `timings()`
//! resolves and reads them (on demand only); the executor sums the time per
//! kernel, named by its entry point.

use precip_gpu::recipe::SUBSTEP_KERNELS;
use precip_model::BackendError;
use precip_model::backend::MAX_SUBSTEPS;

use crate::device::GpuDevice;
use crate::transfer::read_buffer;

/// Kernels of one sub-step.
const KERNELS: usize = SUBSTEP_KERNELS;

/// Queries: one at the start, one after each kernel of each sub-step.
pub const QUERY_COUNT: u32 = 1 + KERNELS as u32 * MAX_SUBSTEPS;

/// The query set and its resolve buffer.
#[derive(Debug)]
pub struct Timestamps {
    /// The queries.
    pub set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    /// Queries written by the last step (0: none yet).
    pub written: u32,
    period_ns: f32,
}

impl Timestamps {
    /// Creates the queries, or `None` when the device cannot time inside passes.
    #[must_use]
    pub fn new(gpu: &GpuDevice) -> Option<Self> {
        if !gpu.has_timestamps() {
            return None;
        }
        let set = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("precip timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: QUERY_COUNT,
        });
        let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("precip timestamps resolve"),
            size: u64::from(QUERY_COUNT) * 8,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(Self {
            set,
            resolve,
            written: 0,
            period_ns: gpu.queue.get_timestamp_period(),
        })
    }

    /// The buffer queries are resolved into.
    #[must_use]
    pub fn resolve_buffer(&self) -> &wgpu::Buffer {
        &self.resolve
    }

    /// The most timestamps one submission writes.
    #[must_use]
    pub fn capacity(&self) -> u32 {
        QUERY_COUNT
    }

    /// The milliseconds between consecutive timestamps of the last timed
    /// submission: one per dispatch, in order (empty before one).
    pub fn elapsed_ms(&self, gpu: &GpuDevice) -> Result<Vec<f64>, BackendError> {
        if self.written < 2 {
            return Ok(Vec::new());
        }
        let bytes = read_buffer(gpu, &self.resolve, u64::from(self.written) * 8)?;
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect();
        let period_ns = f64::from(self.period_ns);
        Ok(ticks
            .windows(2)
            .map(|pair| pair[1].saturating_sub(pair[0]) as f64 * period_ns * 1.0e-6)
            .collect())
    }
}
