//! Timestamps around the passes of a frame, named and ordered as the wgpu backend's
//! (`precip_gpu::recipe::TIMED_RENDER_PASSES`).

use ash::vk;
use precip_model::{BackendError, PassTiming};

use crate::device::Device;
use crate::error::map_vk;

/// The passes timed, in order.
pub const PASSES: [&str; precip_gpu::recipe::TIMED_RENDER_PASSES.len()] =
    precip_gpu::recipe::TIMED_RENDER_PASSES;

/// Queries: two a pass, at its start (`2·i`) and its end (`2·i + 1`), as wgpu's
/// pass timestamps.
pub const QUERIES: u32 = 2 * PASSES.len() as u32;

/// The query pool of a frame's timestamps.
#[derive(Debug)]
pub struct RenderStamps {
    /// The pool.
    pub pool: vk::QueryPool,
    /// Whether a submitted frame wrote them.
    pub written: bool,
    /// Whether the last frame drew the shadow map (else the pass is not reported).
    pub shadow_drawn: bool,
}

impl RenderStamps {
    /// A pool, or `None` when the queue cannot time.
    pub fn new(device: &Device) -> Result<Option<Self>, BackendError> {
        if !device.timestamps {
            return Ok(None);
        }
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(QUERIES);
        // SAFETY: a valid device and create info.
        let pool = unsafe { device.raw.create_query_pool(&info, None) }
            .map_err(|e| map_vk("creating a query pool", e))?;
        device.name(pool, "precip render timestamps");
        Ok(Some(Self {
            pool,
            written: false,
            shadow_drawn: true,
        }))
    }

    /// Records the reset of the queries.
    ///
    /// # Safety
    /// `cb` is a command buffer of `device` in the recording state, outside a render
    /// pass.
    pub unsafe fn reset(&self, device: &Device, cb: vk::CommandBuffer) {
        // SAFETY: the caller guarantees `cb` is recording outside a render pass.
        unsafe { device.raw.cmd_reset_query_pool(cb, self.pool, 0, QUERIES) };
    }

    /// Records timestamp `index` when earlier work reaches `stage` (`TOP_OF_PIPE` at
    /// a pass's start, `BOTTOM_OF_PIPE` at its end).
    ///
    /// # Safety
    /// - `cb` is a command buffer of `device` in the recording state.
    /// - `index` < [`QUERIES`], reset earlier in `cb` ([`RenderStamps::reset`]).
    pub unsafe fn stamp(
        &self,
        device: &Device,
        cb: vk::CommandBuffer,
        index: u32,
        stage: vk::PipelineStageFlags,
    ) {
        // SAFETY: the caller guarantees both.
        unsafe {
            device.raw.cmd_write_timestamp(cb, stage, self.pool, index);
        }
    }

    /// The last frame's time per pass (its submission must be finished).
    pub fn read(&self, device: &Device) -> Result<Vec<PassTiming>, BackendError> {
        if !self.written {
            return Ok(Vec::new());
        }
        let mut ticks = [0u64; QUERIES as usize];
        // SAFETY: every query was written by a finished submission.
        unsafe {
            device.raw.get_query_pool_results(
                self.pool,
                0,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .map_err(|e| map_vk("reading timestamps", e))?;
        let period = f64::from(device.properties.limits.timestamp_period);
        Ok(PASSES
            .iter()
            .zip(ticks.chunks_exact(2))
            .filter(|(pass, _)| self.shadow_drawn || **pass != "shadow")
            .map(|(pass, t)| PassTiming {
                pass,
                milliseconds: t[1].saturating_sub(t[0]) as f64 * period * 1e-6,
            })
            .collect())
    }

    /// Destroys the pool (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once.
        unsafe { device.raw.destroy_query_pool(self.pool, None) };
    }
}
