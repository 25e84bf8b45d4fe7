//! A global allocator that counts the allocations of each thread, so that other tests running at
//! the same time (and the test harness's own threads) neither add to a count nor hide one.
//!
//! A test file installs it with
//!
//! ```ignore
//! #[global_allocator]
//! static GLOBAL: Counting = Counting;
//! ```
//!
//! and reads [`allocations`] before and after the call it measures.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The counting allocator: the system allocator, counting each `alloc` and `realloc`.
pub struct Counting;

thread_local! {
    // A const-initialized Cell needs no allocation of its own, not even on first use.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Allocations the calling thread has made so far.
pub fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

fn count_one() {
    // `try_with`: a thread being torn down may still free and allocate.
    let _ = ALLOCATIONS.try_with(|count| count.set(count.get() + 1));
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_one();
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_one();
        System.realloc(ptr, layout, new_size)
    }
}
