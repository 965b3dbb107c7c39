//! Giving the heap's free pages back after a move of the cover grid.
//!
//! A cover grid that follows the camera (`--grid-side`) makes and frees vectors
//! of several MiB at every move (the cover read back, the moved texels, the
//! ground map and its strips, the words written to the device). glibc serves
//! them from its heap once its dynamic mmap threshold has risen to their size,
//! and the small, long-lived allocations made between them keep the freed space
//! from being returned at the heap's top: flown for 1 500 frames the viewer's
//! resident memory grew 7.5 KiB a frame (wgpu; vk 4.9 over 3 000), where with
//! the threshold pinned (`MALLOC_MMAP_THRESHOLD_=131072`) wgpu stayed at 0.1 —
//! the memory was free, not leaked (vk's, in smaller blocks, stayed at 5.6).
//! Pinning the threshold for the whole run would map and fault in every
//! frame's read-back and PNG buffers instead (measured here: ~10 ms a frame for
//! 7.7 MB of buffers, against 0.4 ms from the heap), so the viewer leaves glibc's
//! heuristic alone and, after a frame whose step moved the grid, asks glibc to
//! return its free pages (`malloc_trim(0)`, which also releases whole free pages
//! inside the heap) — a walk of the heap's free lists once a move (the frame's
//! read-back and PNG buffers, freed the frame before, are then faulted in anew:
//! a few ms on a frame that already waited for the move), nothing on other
//! frames. Flown as above with the trim: −0.3 KiB a frame on wgpu, 0.1 on vk
//! (3 000 frames). A program that embeds precip with a following grid can do
//! the same after a step that moved it (`Backend::cover_window`'s move count).

/// Watches the cover grid's moves and returns the heap's free pages after each.
#[derive(Debug, Default)]
pub struct TrimAfterMoves {
    moves: u32,
}

impl TrimAfterMoves {
    /// After a step: if the grid moved since the last call (`moves`, the grid's
    /// count of moves; `None` for a grid that stays), returns the heap's free
    /// pages to the system. Whether the grid moved (off glibc nothing is
    /// returned).
    pub fn after_step(&mut self, moves: Option<u32>) -> bool {
        let Some(moves) = moves else {
            return false;
        };
        if moves == self.moves {
            return false;
        }
        self.moves = moves;
        return_free_pages();
        true
    }
}

#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[expect(
    unsafe_code,
    reason = "malloc_trim is glibc's C interface for returning free heap pages"
)]
fn return_free_pages() {
    // SAFETY: malloc_trim takes a size and walks glibc's own heaps under their
    // locks, releasing free pages; it touches no memory precip owns and is safe
    // to call at any time from any thread.
    unsafe {
        libc::malloc_trim(0);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn return_free_pages() {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_move_trims() {
        let mut trim = TrimAfterMoves::default();
        assert!(!trim.after_step(None), "a grid that stays");
        assert!(!trim.after_step(Some(0)), "not moved yet");
        assert!(trim.after_step(Some(1)), "moved");
        assert!(!trim.after_step(Some(1)), "not since");
        assert!(trim.after_step(Some(3)), "moved twice more");
    }
}
