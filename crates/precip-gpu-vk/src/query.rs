//! Timestamp queries (wgpu twin: `precip_gpu_wgpu::query`): one pool around each
//! kernel of a step (a slot of [`QUERY_COUNT`] per submission in flight), one at the
//! start and end of each pass of a frame ([`FRAME_QUERY_COUNT`]).

use ash::vk;
use precip_gpu::recipe::SUBSTEP_KERNELS;
use precip_model::BackendError;
use precip_model::backend::MAX_SUBSTEPS;

use crate::device::Device;
use crate::error::map_vk;

/// Queries of a step: one at the start, one after each kernel of each sub-step.
pub const QUERY_COUNT: u32 = 1 + SUBSTEP_KERNELS as u32 * MAX_SUBSTEPS;

/// Queries of a frame: two a pass, at its start (`2·i`) and its end (`2·i + 1`),
/// as wgpu's pass timestamps.
pub const FRAME_QUERY_COUNT: u32 = 2 * precip_gpu::frame::FRAME_PASSES.len() as u32;

/// A pool of timestamp queries and which of them the last submission wrote.
#[derive(Debug)]
pub struct QueryPool {
    /// The pool.
    pub pool: vk::QueryPool,
    /// The first query and how many the last timed submission wrote.
    pub written: (u32, u32),
}

impl QueryPool {
    /// A pool of `count` queries, or `None` when the queue cannot time.
    pub fn new(device: &Device, name: &str, count: u32) -> Result<Option<Self>, BackendError> {
        if !device.timestamps {
            return Ok(None);
        }
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(count);
        // SAFETY: a valid device and create info.
        let pool = unsafe { device.raw.create_query_pool(&info, None) }
            .map_err(|e| map_vk("creating a query pool", e))?;
        device.name(pool, name);
        Ok(Some(Self {
            pool,
            written: (0, 0),
        }))
    }

    /// Records the reset of `count` queries from `first`.
    ///
    /// # Safety
    /// `cb` is a command buffer of `device` in the recording state, outside a render
    /// pass; the queries are in the pool.
    pub unsafe fn reset(&self, device: &Device, cb: vk::CommandBuffer, first: u32, count: u32) {
        // SAFETY: the caller's guarantees.
        unsafe { device.raw.cmd_reset_query_pool(cb, self.pool, first, count) };
    }

    /// Records timestamp `index` when earlier work reaches `stage`.
    ///
    /// # Safety
    /// `cb` is a command buffer of `device` in the recording state; `index` is in
    /// the pool and was reset earlier in `cb`.
    pub unsafe fn stamp(
        &self,
        device: &Device,
        cb: vk::CommandBuffer,
        index: u32,
        stage: vk::PipelineStageFlags,
    ) {
        // SAFETY: the caller's guarantees.
        unsafe { device.raw.cmd_write_timestamp(cb, stage, self.pool, index) };
    }

    /// The written queries, in milliseconds since an arbitrary origin (their
    /// submission must be finished).
    fn written_ms(&self, device: &Device) -> Result<Vec<f64>, BackendError> {
        let (first, count) = self.written;
        let mut ticks = vec![0u64; count as usize];
        // SAFETY: every query read was written by a finished submission.
        unsafe {
            device.raw.get_query_pool_results(
                self.pool,
                first,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .map_err(|e| map_vk("reading timestamps", e))?;
        let period = f64::from(device.properties.limits.timestamp_period);
        Ok(ticks.iter().map(|&t| t as f64 * period * 1e-6).collect())
    }

    /// The milliseconds between consecutive written timestamps (a step's kernels).
    pub fn elapsed_ms(&self, device: &Device) -> Result<Vec<f64>, BackendError> {
        if self.written.1 < 2 {
            return Ok(Vec::new());
        }
        let ms = self.written_ms(device)?;
        Ok(ms.windows(2).map(|p| (p[1] - p[0]).max(0.0)).collect())
    }

    /// The milliseconds between each pair's two timestamps (a frame's passes).
    pub fn pairs_ms(&self, device: &Device) -> Result<Vec<f64>, BackendError> {
        let ms = self.written_ms(device)?;
        Ok(ms.chunks_exact(2).map(|p| (p[1] - p[0]).max(0.0)).collect())
    }

    /// Destroys the pool (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once.
        unsafe { device.raw.destroy_query_pool(self.pool, None) };
    }
}
