//! [`ResolutionControl`]: holds a frame rate by the resolution rain and snow are
//! drawn at ([`ParticleResolution`]), never by drawing fewer of them. The viewer's
//! `--quality auto` runs it; any application can: feed it each frame's smoothed
//! time and pass what it returns to [`crate::Backend::set_particle_resolution`].
//!
//! After each frame the smoothed frame time is compared with the target: over it
//! by a tenth, the particles go to the next coarser resolution; under 60 % of it,
//! to the next finer one. After a change the smoothed time is given
//! [`ResolutionControl::SETTLE_FRAMES`] frames to follow before the next decision,
//! so the control does not swing on its own echo. Where even a quarter cannot hold
//! the target (a CPU rasteriser), it stays at a quarter: the scene is drawn at the
//! frame's resolution whatever the level.

use crate::drawing::render::ParticleResolution;

/// The frame-rate control over the particles' resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResolutionControl {
    target_ms: f64,
    resolution: ParticleResolution,
    frames_since_change: u32,
}

impl ResolutionControl {
    /// Frames a change is given before the next decision.
    pub const SETTLE_FRAMES: u32 = 20;

    /// Holding `target_fps` (> 0), starting at `start`.
    #[must_use]
    pub fn new(target_fps: f32, start: ParticleResolution) -> Self {
        Self {
            target_ms: 1e3 / f64::from(target_fps.max(1e-3)),
            resolution: start,
            frames_since_change: 0,
        }
    }

    /// The resolution drawn at now.
    #[must_use]
    pub const fn resolution(&self) -> ParticleResolution {
        self.resolution
    }

    /// After a frame whose smoothed time is `frame_ms`: the resolution to draw at
    /// from the next frame, when it changes.
    pub fn after_frame(&mut self, frame_ms: f64) -> Option<ParticleResolution> {
        use ParticleResolution::{Full, Half, Quarter};
        self.frames_since_change = self.frames_since_change.saturating_add(1);
        if self.frames_since_change < Self::SETTLE_FRAMES {
            return None;
        }
        let next = if frame_ms > 1.1 * self.target_ms {
            match self.resolution {
                Full => Half,
                Half | Quarter => Quarter,
            }
        } else if frame_ms < 0.6 * self.target_ms {
            match self.resolution {
                Quarter => Half,
                Half | Full => Full,
            }
        } else {
            self.resolution
        };
        (next != self.resolution).then(|| {
            self.resolution = next;
            self.frames_since_change = 0;
            next
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ParticleResolution::{Full, Half, Quarter};

    /// Frames of a device whose frame takes `cost(resolution)`, smoothed as the
    /// window smooths them; the resolutions drawn at.
    fn run(
        target_fps: f32,
        cost: impl Fn(ParticleResolution) -> f64,
        frames: u32,
    ) -> Vec<ParticleResolution> {
        let mut control = ResolutionControl::new(target_fps, Full);
        let mut smoothed = cost(Full);
        let mut drawn = Vec::new();
        for _ in 0..frames {
            smoothed = 0.9 * smoothed + 0.1 * cost(control.resolution());
            control.after_frame(smoothed);
            drawn.push(control.resolution());
        }
        drawn
    }

    #[test]
    fn a_slow_device_steps_down_to_what_holds_the_rate_and_stays() {
        // 30 fps wanted: 50 ms at full, 30 at half, 20 at a quarter.
        let cost = |r| match r {
            Full => 50.0,
            Half => 30.0,
            Quarter => 20.0,
        };
        let drawn = run(30.0, cost, 400);
        assert_eq!(drawn[0], Full);
        assert!(
            drawn[300..].iter().all(|r| *r == Half),
            "{:?}",
            &drawn[300..]
        );
    }

    #[test]
    fn a_fast_device_stays_at_full_and_a_hopeless_one_at_a_quarter() {
        assert!(run(30.0, |_| 10.0, 200).iter().all(|r| *r == Full));
        let drawn = run(30.0, |_| 250.0, 200);
        assert!(drawn[100..].iter().all(|r| *r == Quarter));
    }

    #[test]
    fn no_decision_comes_before_the_last_one_settled() {
        let mut control = ResolutionControl::new(30.0, Full);
        let changes: Vec<u32> = (0..100)
            .filter(|_| control.after_frame(500.0).is_some())
            .collect();
        assert_eq!(changes.len(), 2, "full → half → quarter, then nothing");
        let mut control = ResolutionControl::new(30.0, Full);
        for k in 1..ResolutionControl::SETTLE_FRAMES {
            assert_eq!(control.after_frame(500.0), None, "frame {k}");
        }
        assert_eq!(control.after_frame(500.0), Some(Half));
    }
}
