//! [`FrameRateControl`]: holds a frame rate by what a frame may skip or coarsen —
//! the resolution rain and snow are drawn at ([`ParticleResolution`]) and how long a
//! stale shadow map is kept (`RenderSettings::shadow_refresh_frames`) — never by
//! drawing fewer particles or thinning the weather. The viewer's `--quality auto`
//! runs it; any application can: feed it each frame's smoothed time and pass the
//! [`FrameLevel`] it returns to [`crate::Backend::set_particle_resolution`] and
//! [`crate::Backend::set_shadow_refresh_frames`].
//!
//! The levels are a ladder ([`FrameRateControl::LEVELS`]), cheapest last. After
//! each frame the smoothed frame time is compared with the target: over it by a
//! tenth, the next cheaper level; under 60 % of it, the next dearer one. After a
//! change the smoothed time is given [`FrameRateControl::SETTLE_FRAMES`] frames to
//! follow before the next decision, so the control does not swing on its own echo.
//! Where even the last level cannot hold the target (a CPU rasteriser), it stays
//! there: the scene is drawn at the frame's resolution whatever the level.

use crate::drawing::render::ParticleResolution;

/// What a frame draws at: one rung of [`FrameRateControl::LEVELS`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameLevel {
    /// The resolution rain and snow are drawn at.
    pub particle_resolution: ParticleResolution,
    /// The most frames a stale shadow map is kept
    /// (`RenderSettings::shadow_refresh_frames`).
    pub shadow_refresh_frames: u32,
}

/// The frame-rate control over the frame's levels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameRateControl {
    target_ms: f64,
    level: usize,
    frames_since_change: u32,
}

impl FrameRateControl {
    /// Frames a change is given before the next decision.
    pub const SETTLE_FRAMES: u32 = 20;

    /// The ladder, dearest first: the particles' resolution halves, then the shadow
    /// map (redrawn every frame while the camera moves) is kept 4 frames, then the
    /// particles go to a quarter, then the map is kept 8.
    pub const LEVELS: [FrameLevel; 5] = [
        level(ParticleResolution::Full, 1),
        level(ParticleResolution::Half, 1),
        level(ParticleResolution::Half, 4),
        level(ParticleResolution::Quarter, 4),
        level(ParticleResolution::Quarter, 8),
    ];

    /// Holding `target_fps` (> 0), starting at the first level that draws the
    /// particles at `start`.
    #[must_use]
    pub fn new(target_fps: f32, start: ParticleResolution) -> Self {
        Self {
            target_ms: 1e3 / f64::from(target_fps.max(1e-3)),
            level: Self::LEVELS
                .iter()
                .position(|l| l.particle_resolution == start)
                .unwrap_or(0),
            frames_since_change: 0,
        }
    }

    /// The level drawn at now.
    #[must_use]
    pub const fn level(&self) -> FrameLevel {
        Self::LEVELS[self.level]
    }

    /// After a frame whose smoothed time is `frame_ms`: the level to draw at from
    /// the next frame, when it changes.
    pub fn after_frame(&mut self, frame_ms: f64) -> Option<FrameLevel> {
        self.frames_since_change = self.frames_since_change.saturating_add(1);
        if self.frames_since_change < Self::SETTLE_FRAMES {
            return None;
        }
        let next = if frame_ms > 1.1 * self.target_ms {
            (self.level + 1).min(Self::LEVELS.len() - 1)
        } else if frame_ms < 0.6 * self.target_ms {
            self.level.saturating_sub(1)
        } else {
            self.level
        };
        (next != self.level).then(|| {
            self.level = next;
            self.frames_since_change = 0;
            Self::LEVELS[next]
        })
    }
}

const fn level(particle_resolution: ParticleResolution, shadow_refresh_frames: u32) -> FrameLevel {
    FrameLevel {
        particle_resolution,
        shadow_refresh_frames,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ParticleResolution::{Full, Half, Quarter};

    /// Frames of a device whose frame takes `cost(level)`, smoothed as the window
    /// smooths them; the levels drawn at.
    fn run(target_fps: f32, cost: impl Fn(FrameLevel) -> f64, frames: u32) -> Vec<FrameLevel> {
        let mut control = FrameRateControl::new(target_fps, Full);
        let mut smoothed = cost(control.level());
        let mut drawn = Vec::new();
        for _ in 0..frames {
            smoothed = 0.9 * smoothed + 0.1 * cost(control.level());
            control.after_frame(smoothed);
            drawn.push(control.level());
        }
        drawn
    }

    /// 30 fps wanted: particles 25 ms at full, 10 at half, 4 at a quarter; a
    /// shadow map of 20 ms redrawn every `n`th frame; the rest 10 ms.
    fn moving_camera(l: FrameLevel) -> f64 {
        let particles = match l.particle_resolution {
            Full => 25.0,
            Half => 10.0,
            Quarter => 4.0,
        };
        10.0 + particles + 20.0 / f64::from(l.shadow_refresh_frames)
    }

    #[test]
    fn a_slow_device_steps_down_to_what_holds_the_rate_and_stays() {
        let drawn = run(30.0, moving_camera, 400);
        assert_eq!(drawn[0], FrameRateControl::LEVELS[0]);
        // Half with the map every frame is 40 ms; kept 4 frames, 25: held.
        assert!(
            drawn[300..].iter().all(|l| *l == level(Half, 4)),
            "{:?}",
            &drawn[300..]
        );
    }

    #[test]
    fn a_fast_device_stays_at_the_top_and_a_hopeless_one_at_the_bottom() {
        assert!(
            run(30.0, |_| 10.0, 200)
                .iter()
                .all(|l| *l == FrameRateControl::LEVELS[0])
        );
        let drawn = run(30.0, |_| 250.0, 300);
        assert!(drawn[150..].iter().all(|l| *l == level(Quarter, 8)));
    }

    #[test]
    fn no_decision_comes_before_the_last_one_settled() {
        let mut control = FrameRateControl::new(30.0, Full);
        let changes: Vec<u32> = (0..200)
            .filter(|_| control.after_frame(500.0).is_some())
            .collect();
        assert_eq!(changes.len(), 4, "down the ladder, then nothing");
        let mut control = FrameRateControl::new(30.0, Full);
        for k in 1..FrameRateControl::SETTLE_FRAMES {
            assert_eq!(control.after_frame(500.0), None, "frame {k}");
        }
        assert_eq!(control.after_frame(500.0), Some(level(Half, 1)));
        // Starting at a quarter starts at its first rung.
        assert_eq!(
            FrameRateControl::new(30.0, Quarter).level(),
            level(Quarter, 4)
        );
    }
}
