//! Deferred release: an object the GPU may still use (a target replaced on resize, an
//! old swapchain) is retired with the number of submissions made so far and freed
//! once all of them have finished, so resizing never waits for the device.

use crate::device::Device;

type Release = Box<dyn FnOnce(&Device)>;

/// Objects waiting for the submissions that may use them.
#[derive(Default)]
pub struct Retired {
    items: Vec<(u64, Release)>,
}

impl std::fmt::Debug for Retired {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Retired")
            .field("pending", &self.items.len())
            .finish()
    }
}

impl Retired {
    /// Frees `release` once `submitted` submissions have finished.
    pub fn retire(&mut self, submitted: u64, release: impl FnOnce(&Device) + 'static) {
        self.items.push((submitted, Box::new(release)));
    }

    /// Frees what no unfinished submission uses (`completed` have finished).
    pub fn release(&mut self, device: &Device, completed: u64) {
        let (ready, waiting): (Vec<_>, Vec<_>) =
            self.items.drain(..).partition(|(n, _)| *n <= completed);
        self.items = waiting;
        for (_, release) in ready {
            release(device);
        }
    }

    /// Frees everything (the device must be idle).
    pub fn release_all(&mut self, device: &Device) {
        self.release(device, u64::MAX);
    }
}
