//! The solver's time loops do not allocate (1D, 2D, 3D: one module each), counted by the
//! counting global allocator below. This is a binary of its own: the counter is global, so it
//! would see the allocations of every other test running in parallel in `tests/it`; and the
//! three checks run one after the other from one test function, for the same reason.

mod solver1d;
mod solver2d;
mod solver3d;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// The system allocator, counting allocations and reallocations.
struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);
/// Live bytes, and their peak.
pub static LIVE: AtomicUsize = AtomicUsize::new(0);
pub static PEAK: AtomicUsize = AtomicUsize::new(0);

/// Sizes of the first allocations counted while [`RECORD`] is on (for the failure message).
pub static SIZES: [AtomicUsize; 8] = [const { AtomicUsize::new(0) }; 8];
pub static RECORD: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
pub static RECORDED: AtomicUsize = AtomicUsize::new(0);

fn grew(by: usize) {
    if RECORD.load(Ordering::Relaxed) {
        let k = RECORDED.fetch_add(1, Ordering::Relaxed);
        if k < SIZES.len() {
            SIZES[k].store(by, Ordering::Relaxed);
        }
    }
    let now = LIVE.fetch_add(by, Ordering::Relaxed) + by;
    PEAK.fetch_max(now, Ordering::Relaxed);
}

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        grew(layout.size());
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        grew(layout.size());
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // old and new block both live for the copy
        grew(new_size);
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

pub fn allocations() -> u64 {
    ALLOCATIONS.load(Ordering::SeqCst)
}

/// One test function: the counter is global and the tests of one binary run in parallel.
#[test]
fn time_loops_do_not_allocate() {
    solver1d::the_1d_time_loop_does_not_allocate();
    solver2d::time_loop_does_not_allocate();
    solver3d::time_loop_does_not_allocate_in_3d();
}
