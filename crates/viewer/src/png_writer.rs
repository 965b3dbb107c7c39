//! Headless frames' PNGs encoded beside the render loop.
//!
//! Encoding a frame's PNG costs about as much as drawing it on a GPU (about 20 ms
//! for 1920×1080 on one core, against a frame of 4–13 GPU ms on an H100:
//! docs/performance.md), so the loop hands each frame's pixels to worker threads and
//! goes on to the next frame. The queue holds as many frames as there are workers:
//! when they fall behind the loop waits (memory stays bounded: a few frames), and
//! that wait is what the frame time then shows. A write that fails stops the run at
//! the next frame handed over, or at [`PngWriter::finish`], with the file and why;
//! every PNG is on disk when `finish` returns.

use std::path::PathBuf;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

use precip_model::Image;

use crate::headless::HeadlessError;

/// At most this many encoding threads.
pub const MAX_PNG_THREADS: usize = 4;

/// A frame to write.
struct Job {
    file: PathBuf,
    image: Image,
}

/// The first write that failed: the file and why.
type Failure = Arc<Mutex<Option<(PathBuf, String)>>>;

/// Worker threads that encode and write the frames handed to them.
pub struct PngWriter {
    sender: Option<SyncSender<Job>>,
    workers: Vec<JoinHandle<()>>,
    failure: Failure,
}

impl PngWriter {
    /// Workers for this machine: one core is the render loop's, the others (at
    /// least one, at most [`MAX_PNG_THREADS`]) encode.
    #[must_use]
    pub fn for_this_machine() -> Self {
        let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
        Self::with_threads(cores.saturating_sub(1).clamp(1, MAX_PNG_THREADS))
    }

    /// `threads` workers (at least one; a thread the system refuses is left out,
    /// and with none the frames are written on the caller's thread).
    #[must_use]
    pub fn with_threads(threads: usize) -> Self {
        let threads = threads.max(1);
        let (sender, receiver) = sync_channel::<Job>(threads);
        let receiver = Arc::new(Mutex::new(receiver));
        let failure = Failure::default();
        let workers: Vec<JoinHandle<()>> = (0..threads)
            .filter_map(|k| {
                let receiver = Arc::clone(&receiver);
                let failure = Arc::clone(&failure);
                std::thread::Builder::new()
                    .name(format!("png-{k}"))
                    .spawn(move || work(&receiver, &failure))
                    .ok()
            })
            .collect();
        Self {
            sender: (!workers.is_empty()).then_some(sender),
            workers,
            failure,
        }
    }

    /// Hands `image` over to be written as `file`; waits while every worker is
    /// busy and the queue is full. An earlier write's failure is returned here, and
    /// from then on by every call (the frame handed over then is not written): a
    /// run stops at its first failed frame.
    pub fn write(&mut self, file: PathBuf, image: Image) -> Result<(), HeadlessError> {
        self.failed()?;
        match &self.sender {
            Some(sender) => match sender.send(Job { file, image }) {
                Ok(()) => Ok(()),
                // Every worker is gone: write it here.
                Err(std::sync::mpsc::SendError(job)) => {
                    self.sender = None;
                    save(&job).map_err(|detail| HeadlessError::Write {
                        file: job.file,
                        detail,
                    })
                }
            },
            None => {
                let job = Job { file, image };
                save(&job).map_err(|detail| HeadlessError::Write {
                    file: job.file,
                    detail,
                })
            }
        }
    }

    /// Waits for every frame handed over to be written; the first failure, if any.
    pub fn finish(mut self) -> Result<(), HeadlessError> {
        self.join();
        self.failed()
    }

    fn failed(&self) -> Result<(), HeadlessError> {
        let failure = self
            .failure
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone();
        match failure {
            Some((file, detail)) => Err(HeadlessError::Write { file, detail }),
            None => Ok(()),
        }
    }

    fn join(&mut self) {
        self.sender = None;
        for worker in self.workers.drain(..) {
            if worker.join().is_err() {
                let mut failure = self.failure.lock().unwrap_or_else(PoisonError::into_inner);
                failure.get_or_insert_with(|| {
                    (
                        PathBuf::from("(a PNG being written)"),
                        "the thread encoding it stopped".to_string(),
                    )
                });
            }
        }
    }
}

impl Drop for PngWriter {
    fn drop(&mut self) {
        self.join();
    }
}

/// A worker: takes jobs until the queue closes; keeps the first failure.
fn work(receiver: &Mutex<Receiver<Job>>, failure: &Mutex<Option<(PathBuf, String)>>) {
    loop {
        let job = {
            let receiver = receiver.lock().unwrap_or_else(PoisonError::into_inner);
            receiver.recv()
        };
        let Ok(job) = job else {
            return;
        };
        // A panic inside the encoder is this frame's failure, not a lost thread.
        let saved = std::panic::catch_unwind(|| save(&job))
            .unwrap_or_else(|_| Err("the PNG encoder stopped on this frame".to_string()));
        if let Err(detail) = saved {
            failure
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .get_or_insert((job.file, detail));
        }
    }
}

/// Encodes and writes one frame (an image whose bytes are not its 4 × width ×
/// height is refused, not handed to the encoder, which would panic).
fn save(job: &Job) -> Result<(), String> {
    let expected = 4 * u64::from(job.image.width_px) * u64::from(job.image.height_px);
    if job.image.rgba8.len() as u64 != expected {
        return Err(format!(
            "a {}×{} image needs {expected} bytes of RGBA, it has {}",
            job.image.width_px,
            job.image.height_px,
            job.image.rgba8.len()
        ));
    }
    image::save_buffer(
        &job.file,
        &job.image.rgba8,
        job.image.width_px,
        job.image.height_px,
        image::ExtendedColorType::Rgba8,
    )
    .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(shade: u8) -> Image {
        Image {
            width_px: 3,
            height_px: 2,
            rgba8: vec![shade; 3 * 2 * 4],
        }
    }

    #[test]
    fn every_frame_handed_over_is_on_disk_when_finish_returns() {
        let dir = std::env::temp_dir().join(format!("precip-png-writer-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        for threads in [1, 3] {
            let mut writer = PngWriter::with_threads(threads);
            for k in 0..10u8 {
                writer
                    .write(dir.join(format!("f{threads}_{k}.png")), image(k * 20))
                    .expect("written");
            }
            writer.finish().expect("all written");
            for k in 0..10u8 {
                let back = image::open(dir.join(format!("f{threads}_{k}.png")))
                    .expect("readable")
                    .to_rgba8();
                assert_eq!(back.dimensions(), (3, 2));
                assert!(back.pixels().all(|p| p.0 == [k * 20; 4]), "frame {k}");
            }
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn an_image_whose_bytes_are_not_its_size_is_refused_with_its_file() {
        let dir =
            std::env::temp_dir().join(format!("precip-png-writer-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        let file = dir.join("frame_0000.png");
        let mut writer = PngWriter::with_threads(1);
        let short = Image {
            width_px: 3,
            height_px: 2,
            rgba8: vec![0; 5],
        };
        let outcome = writer
            .write(file.clone(), short)
            .and_then(|()| writer.finish());
        match outcome {
            Err(HeadlessError::Write { file: f, detail }) => {
                assert_eq!(f, file);
                assert!(detail.contains("needs 24 bytes"), "{detail}");
            }
            other => panic!("expected a write error, got {other:?}"),
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_write_that_fails_is_reported_with_its_file() {
        let missing = std::env::temp_dir()
            .join(format!("precip-png-writer-missing-{}", std::process::id()))
            .join("no-such-folder");
        let mut writer = PngWriter::with_threads(2);
        let file = missing.join("frame_0000.png");
        // The failure shows at the next hand-over or at finish, whichever comes first.
        let first = writer.write(file.clone(), image(1));
        let outcome = first.and_then(|()| writer.finish());
        match outcome {
            Err(HeadlessError::Write { file: f, detail }) => {
                assert_eq!(f, file);
                assert!(!detail.is_empty());
            }
            other => panic!("expected a write error, got {other:?}"),
        }
    }
}
