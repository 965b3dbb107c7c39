//! [`DepositBuffer`]: landed water summed in fixed point, as the GPU's atomics do.
//!
//! ## Fixed point
//!
//! One unit is 2⁻²⁰ mm of water (≈ 0.95·10⁻⁶ mm). A `u32` per
//! texel and channel then holds up to 4096 mm per cover step, three orders of
//! magnitude above a cloudburst's water in one frame, and a single deposit is rounded
//! to the nearest unit, so rounding is unbiased and far below a flake's water.
//! Integer sums do not depend on the order of the additions: the CPU reference and
//! the GPU get the same bits however their threads interleave.
//!
//! Layout: [`DEPOSIT_CHANNELS`] `u32` per texel, interleaved `[snow, rain, grains]`
//! (WGSL twin: `deposits: array<atomic<u32>>`, `DEPOSIT_*` in `shaders/deposit.wgsl`).
//! The grains' channel holds sand and dust in kg/m² with the same scale (a mm of
//! water is a kg/m²).

use std::sync::atomic::{AtomicU32, Ordering};

use glam::Vec2;

use crate::frame::GridFrame;

/// Channels a texel: snow, rain, grains (sand and dust).
pub const DEPOSIT_CHANNELS: usize = 3;

/// Fixed-point units per mm of water.
pub const DEPOSIT_UNITS_PER_MM: f32 = 1_048_576.0;

/// The largest single deposit, in units (2048 mm): keeps a sum of two in range.
const MAX_DEPOSIT_UNITS: f32 = 2_147_483_648.0;

/// `water_mm` in fixed-point units, rounded to nearest (WGSL twin: `deposit_units`).
#[must_use]
pub fn deposit_units(water_mm: f32) -> u32 {
    (water_mm * DEPOSIT_UNITS_PER_MM + 0.5).clamp(0.0, MAX_DEPOSIT_UNITS) as u32
}

/// What landed on one texel during a step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Landed {
    /// Snow, mm of water.
    pub snow_mm: f32,
    /// Rain, mm.
    pub rain_mm: f32,
    /// Sand and dust, kg/m².
    pub grains_kg_m2: f32,
}

/// Water landed per texel during one step, fixed point, safe to add to from threads.
#[derive(Debug, Default)]
pub struct DepositBuffer {
    units: Vec<AtomicU32>,
}

impl DepositBuffer {
    /// Channel index of snow.
    pub const SNOW: usize = 0;
    /// Channel index of rain.
    pub const RAIN: usize = 1;
    /// Channel index of sand and dust (kg/m², the same scale as mm of water).
    pub const GRAINS: usize = 2;

    /// Bytes of the buffer for `texel_count` texels (the GPU's `deposits`).
    #[must_use]
    pub const fn bytes_for(texel_count: usize) -> usize {
        DEPOSIT_CHANNELS * 4 * texel_count
    }

    /// An empty buffer for `texel_count` texels.
    #[must_use]
    pub fn new(texel_count: usize) -> Self {
        Self {
            units: (0..DEPOSIT_CHANNELS * texel_count)
                .map(|_| AtomicU32::new(0))
                .collect(),
        }
    }

    /// Adds `water_mm` to `channel` of texel `index` (wrapping like `atomicAdd`).
    pub fn add(&self, index: usize, channel: usize, water_mm: f32) {
        let channel = channel.min(DEPOSIT_CHANNELS - 1);
        if let Some(slot) = self.units.get(DEPOSIT_CHANNELS * index + channel) {
            slot.fetch_add(deposit_units(water_mm), Ordering::Relaxed);
        }
    }

    /// Adds `water_mm` to `channel` of the texel of `frame` under world `(x, z)`;
    /// returns whether a texel was there (water landing off the grid is not kept).
    #[must_use = "water landing off the grid is dropped: say so where it is ignored"]
    pub fn add_at(&self, frame: &GridFrame, xz_m: Vec2, channel: usize, water_mm: f32) -> bool {
        match frame.texel_index(xz_m) {
            Some(index) => {
                self.add(index, channel, water_mm);
                true
            }
            None => false,
        }
    }

    /// Snow and rain landed on texel `index`, mm, without clearing.
    #[must_use]
    pub fn peek_mm(&self, index: usize) -> (f32, f32) {
        (self.peek(index, Self::SNOW), self.peek(index, Self::RAIN))
    }

    /// `channel` of texel `index` (mm, or kg/m² of grains), without clearing.
    #[must_use]
    pub fn peek(&self, index: usize, channel: usize) -> f32 {
        self.units
            .get(DEPOSIT_CHANNELS * index + channel)
            .map_or(0.0, |u| {
                u.load(Ordering::Relaxed) as f32 / DEPOSIT_UNITS_PER_MM
            })
    }

    /// Reads and clears texel `index`: snow and rain in mm, grains in kg/m².
    pub fn take_mm(&mut self, index: usize) -> Landed {
        let mut take = |c: usize| {
            self.units
                .get_mut(DEPOSIT_CHANNELS * index + c)
                .map_or(0.0, |u| {
                    std::mem::take(u.get_mut()) as f32 / DEPOSIT_UNITS_PER_MM
                })
        };
        Landed {
            snow_mm: take(Self::SNOW),
            rain_mm: take(Self::RAIN),
            grains_kg_m2: take(Self::GRAINS),
        }
    }

    /// The raw units, `[snow, rain, grains]` per texel (for comparison with a GPU
    /// buffer).
    #[must_use]
    pub fn raw_units(&self) -> Vec<u32> {
        self.units
            .iter()
            .map(|u| u.load(Ordering::Relaxed))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_point_round_trips_and_sums_in_any_order() {
        assert_eq!(deposit_units(1.0), 1 << 20);
        assert_eq!(deposit_units(-3.0), 0);
        assert_eq!(deposit_units(f32::NAN), 0);
        let amounts: Vec<f32> = (0..1000).map(|i| 0.001 + (i as f32) * 1.3e-5).collect();
        let forward = DepositBuffer::new(1);
        let backward = DepositBuffer::new(1);
        for a in &amounts {
            forward.add(0, DepositBuffer::SNOW, *a);
        }
        for a in amounts.iter().rev() {
            backward.add(0, DepositBuffer::SNOW, *a);
        }
        assert_eq!(forward.raw_units(), backward.raw_units());
        let exact: f64 = amounts.iter().map(|&a| f64::from(a)).sum();
        let mut f = forward;
        let landed = f.take_mm(0);
        assert!((f64::from(landed.snow_mm) - exact).abs() < 1e-3 * exact);
        assert!(landed.rain_mm.abs() < f32::MIN_POSITIVE);
        assert_eq!(f.raw_units(), vec![0, 0, 0], "take clears");
    }

    #[test]
    fn deposits_at_a_world_position_find_their_texel() {
        let frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(4.0), glam::UVec2::splat(2));
        let buffer = DepositBuffer::new(4);
        assert!(buffer.add_at(&frame, Vec2::new(1.0, -1.0), DepositBuffer::RAIN, 2.0));
        assert!(!buffer.add_at(&frame, Vec2::new(3.0, 0.0), DepositBuffer::RAIN, 2.0));
        assert!((buffer.peek_mm(1).1 - 2.0).abs() < 1e-6);
        assert!(buffer.add_at(&frame, Vec2::new(-1.0, 1.0), DepositBuffer::GRAINS, 0.5));
        assert!((buffer.peek(2, DepositBuffer::GRAINS) - 0.5).abs() < 1e-6);
        assert_eq!(buffer.raw_units().iter().filter(|&&u| u > 0).count(), 2);
        assert_eq!(DepositBuffer::bytes_for(4), 4 * 4 * DEPOSIT_CHANNELS);
    }
}
