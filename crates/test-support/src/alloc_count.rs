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
//! and reads [`allocations`] before and after the call it measures. [`fail_allocation`] makes one
//! of the calling thread's allocations fail (return null), to test that a call reports running out
//! of memory instead of aborting.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The counting allocator: the system allocator, counting each `alloc` and `realloc`.
pub struct Counting;

thread_local! {
    // A const-initialized Cell needs no allocation of its own, not even on first use.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
    // The number (as `allocations` counts) of the allocation that fails; `usize::MAX`: none.
    static FAILING: Cell<usize> = const { Cell::new(usize::MAX) };
}

/// Allocations the calling thread has made so far.
pub fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

/// Makes the calling thread's allocation number `number` (the value [`allocations`] has just
/// before it) fail, or none with `None`.
pub fn fail_allocation(number: Option<usize>) {
    FAILING.with(|failing| failing.set(number.unwrap_or(usize::MAX)));
}

/// Counts an allocation; false when it is the one that must fail.
fn count_one() -> bool {
    // `try_with`: a thread being torn down may still free and allocate.
    let number = ALLOCATIONS
        .try_with(|count| {
            let number = count.get();
            count.set(number + 1);
            number
        })
        .unwrap_or(usize::MAX - 1);
    FAILING.try_with(|failing| failing.get() != number).unwrap_or(true)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !count_one() {
            return std::ptr::null_mut();
        }
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if !count_one() {
            return std::ptr::null_mut();
        }
        System.realloc(ptr, layout, new_size)
    }
}
