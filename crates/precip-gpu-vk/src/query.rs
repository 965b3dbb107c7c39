//! Timestamp queries around each kernel of a step (as the wgpu backend names them).

use ash::vk;
use precip_gpu::recipe::SUBSTEP_KERNELS;
use precip_model::BackendError;
use precip_model::backend::MAX_SUBSTEPS;

use crate::device::Device;
use crate::error::map_vk;

/// Queries: one at the start, one after each kernel of each sub-step.
pub const QUERY_COUNT: u32 = 1 + SUBSTEP_KERNELS as u32 * MAX_SUBSTEPS;

/// The query pool: [`QUERY_COUNT`] queries per in-flight slot.
#[derive(Debug)]
pub struct Timestamps {
    /// The pool.
    pub pool: vk::QueryPool,
    /// Queries the last step wrote.
    pub written: u32,
    /// The in-flight slot of the last step.
    pub slot: usize,
}

impl Timestamps {
    /// A pool, or `None` when the queue cannot time.
    pub fn new(device: &Device) -> Result<Option<Self>, BackendError> {
        if !device.timestamps {
            return Ok(None);
        }
        let info = vk::QueryPoolCreateInfo::default()
            .query_type(vk::QueryType::TIMESTAMP)
            .query_count(QUERY_COUNT * crate::transfer::FRAMES_IN_FLIGHT as u32);
        // SAFETY: a valid device and create info.
        let pool = unsafe { device.raw.create_query_pool(&info, None) }
            .map_err(|e| map_vk("creating a query pool", e))?;
        Ok(Some(Self {
            pool,
            written: 0,
            slot: 0,
        }))
    }

    /// The milliseconds between consecutive timestamps of the last timed
    /// submission (finished): one per dispatch, in order.
    pub fn elapsed_ms(&self, device: &Device) -> Result<Vec<f64>, BackendError> {
        if self.written < 2 {
            return Ok(Vec::new());
        }
        let mut ticks = vec![0u64; self.written as usize];
        let first = self.slot as u32 * QUERY_COUNT;
        // SAFETY: the slot's queries 0..written were written by a finished submission.
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
        Ok(ticks
            .windows(2)
            .map(|pair| pair[1].saturating_sub(pair[0]) as f64 * period * 1e-6)
            .collect())
    }

    /// Destroys the pool (the device must be idle).
    pub fn destroy(self, device: &Device) {
        // SAFETY: the device is idle; destroyed once (by the backend's Drop).
        unsafe { device.raw.destroy_query_pool(self.pool, None) };
    }
}
