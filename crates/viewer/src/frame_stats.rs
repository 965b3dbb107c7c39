//! What a run reports: the mean frame time after a warm-up, the mean number of
//! particles drawn (sprites, streaks and splats, after culling) and the mean GPU time
//! of each kernel and pass (where the device has timestamps), read back from the
//! backend every few frames so the read-back's stall does not set the frame rate.

use precip_model::{Backend, BackendError};

/// Frames not timed at the start (pipelines are made and caches filled there).
pub const WARM_UP_FRAMES: u32 = 3;

/// Every how many frames the drawn counts are read back.
pub const DRAWN_EVERY: u32 = 8;

/// Frame times and drawn counts of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameStats {
    frames: u32,
    all_ms: f64,
    timed_ms: f64,
    timed: u32,
    drawn_sum: u64,
    drawn_samples: u32,
    /// Per pass: total GPU ms and the frames it ran in.
    passes: Vec<(&'static str, f64, u32)>,
    /// Frames whose timings were read (a pass that ran in fewer costs its share).
    timings_read: u32,
}

impl FrameStats {
    /// Records a frame that took `frame_ms`; on every [`DRAWN_EVERY`]-th frame (the
    /// first included) reads what `backend` drew.
    pub fn record(&mut self, frame_ms: f64, backend: &mut dyn Backend) -> Result<(), BackendError> {
        self.all_ms += frame_ms;
        if self.frames >= WARM_UP_FRAMES {
            self.timed_ms += frame_ms;
            self.timed += 1;
        }
        if self.frames.is_multiple_of(DRAWN_EVERY) {
            if let Some(drawn) = backend.drawn()? {
                self.drawn_sum += drawn.total();
                self.drawn_samples += 1;
            }
            if self.frames >= WARM_UP_FRAMES {
                let timings = backend.timings()?;
                self.add_passes(timings.passes.iter().map(|p| (p.pass, p.milliseconds)));
            }
        }
        self.frames += 1;
        Ok(())
    }

    /// Adds one sampled frame's GPU ms per pass (the passes that ran in it).
    fn add_passes(&mut self, passes: impl Iterator<Item = (&'static str, f64)>) {
        self.timings_read += 1;
        for (pass, ms) in passes {
            match self.passes.iter_mut().find(|(name, _, _)| *name == pass) {
                Some(entry) => {
                    entry.1 += ms;
                    entry.2 += 1;
                }
                None => self.passes.push((pass, ms, 1)),
            }
        }
    }

    /// Mean time of the frames after the warm-up (of all frames when there were no
    /// more), ms; `None` before any was timed.
    #[must_use]
    pub fn mean_frame_ms(&self) -> Option<f64> {
        if self.timed > 0 {
            Some(self.timed_ms / f64::from(self.timed))
        } else {
            (self.frames > 0).then(|| self.all_ms / f64::from(self.frames))
        }
    }

    /// Mean particles drawn over the sampled frames; `None` when none was sampled
    /// (or the backend does not draw).
    #[must_use]
    pub fn mean_drawn(&self) -> Option<f64> {
        (self.drawn_samples > 0).then(|| self.drawn_sum as f64 / f64::from(self.drawn_samples))
    }

    /// Mean GPU ms a frame of each kernel and pass over the sampled frames after
    /// the warm-up, in the order first seen (a pass that runs every third frame, the
    /// shadow's, counts a third of its time); empty without timestamps.
    #[must_use]
    pub fn mean_pass_ms(&self) -> Vec<(&'static str, f64)> {
        self.passes
            .iter()
            .map(|(name, ms, _)| (*name, ms / f64::from(self.timings_read.max(1))))
            .collect()
    }

    /// `mean frame time 12.3 ms, 104512 particles drawn` (what is known of it).
    #[must_use]
    pub fn describe(&self) -> String {
        let time = self.mean_frame_ms().map_or_else(
            || "no frame timed".to_string(),
            |ms| format!("mean frame time {ms:.1} ms"),
        );
        match self.mean_drawn() {
            Some(n) => format!("{time}, {n:.0} particles drawn"),
            None => time,
        }
    }

    /// `GPU ms: step_particles 27.1, scene 38.0, …`, or `None` without timestamps.
    #[must_use]
    pub fn describe_passes(&self) -> Option<String> {
        let passes = self.mean_pass_ms();
        (!passes.is_empty()).then(|| {
            let list: Vec<String> = passes
                .iter()
                .zip(&self.passes)
                .map(|((name, ms), (_, _, runs))| {
                    if *runs < self.timings_read {
                        format!("{name} {ms:.1} (ran in {runs} of {})", self.timings_read)
                    } else {
                        format!("{name} {ms:.1}")
                    }
                })
                .collect();
            format!(
                "GPU ms: {}; share of the GPU time: {}",
                list.join(", "),
                precip_gpu::recipe::feature_shares_text(&passes)
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use precip_model::CpuBackend;

    #[test]
    fn warm_up_frames_are_not_timed_and_a_non_drawing_backend_says_nothing() {
        let mut cpu = CpuBackend::new();
        let mut stats = FrameStats::default();
        assert_eq!(stats.mean_frame_ms(), None);
        stats.record(600.0, &mut cpu).expect("records");
        assert_eq!(
            stats.mean_frame_ms(),
            Some(600.0),
            "all frames when none is past the warm-up"
        );
        let mut stats = FrameStats::default();
        for ms in [500.0, 400.0, 300.0, 10.0, 20.0] {
            stats.record(ms, &mut cpu).expect("records");
        }
        assert_eq!(stats.mean_frame_ms(), Some(15.0));
        assert_eq!(stats.mean_drawn(), None);
        assert_eq!(stats.describe(), "mean frame time 15.0 ms");
    }

    #[test]
    fn pass_times_are_the_mean_of_the_sampled_frames_after_the_warm_up() {
        let mut cpu = CpuBackend::new();
        cpu.configure(&precip_model::Setup::over_flat_ground(16.0, 8, 10.0, 500))
            .expect("valid");
        let mut stats = FrameStats::default();
        assert_eq!(stats.describe_passes(), None);
        for _ in 0..=DRAWN_EVERY {
            cpu.step(0.02).expect("valid");
            stats.record(10.0, &mut cpu).expect("records");
        }
        // Frame 0 is in the warm-up; frame 8 is sampled.
        let passes = stats.mean_pass_ms();
        assert!(
            passes
                .iter()
                .any(|(name, ms)| *name == "step_particles" && *ms >= 0.0),
            "{passes:?}"
        );
        assert!(
            stats
                .describe_passes()
                .is_some_and(|d| d.starts_with("GPU ms: "))
        );
    }

    #[test]
    fn a_pass_that_ran_in_some_frames_costs_its_share_of_every_frame() {
        let mut stats = FrameStats::default();
        stats.add_passes([("scene", 100.0), ("shadow", 30.0)].into_iter());
        stats.add_passes([("scene", 100.0)].into_iter());
        stats.add_passes([("scene", 100.0)].into_iter());
        assert_eq!(
            stats.mean_pass_ms(),
            vec![("scene", 100.0), ("shadow", 10.0)]
        );
        let text = stats.describe_passes().expect("timed");
        assert!(
            text.starts_with("GPU ms: scene 100.0, shadow 10.0 (ran in 1 of 3)"),
            "{text}"
        );
    }
}
