//! GPU timestamps around the passes of a frame (pass-level writes: they need only
//! `TIMESTAMP_QUERY`).

use precip_model::{BackendError, PassTiming};

use crate::device::GpuDevice;
use crate::transfer::read_buffer;

/// The passes of a frame, in order; pass `i` writes queries `2i` and `2i + 1`.
pub const RENDER_PASSES: [&str; precip_gpu::recipe::TIMED_RENDER_PASSES.len()] =
    precip_gpu::recipe::TIMED_RENDER_PASSES;

/// The render query set and its resolve buffer.
#[derive(Debug)]
pub struct RenderStamps {
    /// The queries.
    pub set: wgpu::QuerySet,
    /// Where they are resolved.
    pub resolve: wgpu::Buffer,
    /// Whether a frame wrote them.
    pub written: bool,
    /// Whether the last frame drew the shadow map (else its queries are stale and
    /// the pass is not reported).
    pub shadow_drawn: bool,
    period_ns: f32,
}

impl RenderStamps {
    /// The queries, or `None` without timestamp support.
    #[must_use]
    pub fn new(gpu: &GpuDevice) -> Option<Self> {
        if !gpu
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            return None;
        }
        let count = 2 * RENDER_PASSES.len() as u32;
        Some(Self {
            set: gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("precip render timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("precip render timestamps"),
                size: u64::from(count) * 8,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            written: false,
            shadow_drawn: true,
            period_ns: gpu.queue.get_timestamp_period(),
        })
    }

    /// Resolves the queries at the end of a frame's encoder.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(
            &self.set,
            0..2 * RENDER_PASSES.len() as u32,
            &self.resolve,
            0,
        );
    }

    /// Time per pass of the last frame.
    pub fn read(&self, gpu: &GpuDevice) -> Result<Vec<PassTiming>, BackendError> {
        if !self.written {
            return Ok(Vec::new());
        }
        let bytes = read_buffer(gpu, &self.resolve, 2 * RENDER_PASSES.len() as u64 * 8)?;
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect();
        Ok(RENDER_PASSES
            .iter()
            .enumerate()
            .filter(|(_, pass)| self.shadow_drawn || **pass != "shadow")
            .map(|(i, pass)| PassTiming {
                pass,
                milliseconds: ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64
                    * f64::from(self.period_ns)
                    * 1.0e-6,
            })
            .collect())
    }
}
