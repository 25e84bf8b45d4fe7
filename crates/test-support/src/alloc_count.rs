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
//!
//! For calls on several threads, the allocations of every thread but those marked with
//! [`mark_calling_thread`] are counted together, process-wide ([`other_allocations`],
//! [`fail_other_allocation`]): meaningful in a test binary whose only threads are its own and the
//! library's workers (`harness = false`), where a call with two threads has at most one worker at
//! a time, so that count is as repeatable as the caller's. [`record_backtraces`] keeps where each
//! counted allocation was made, to tell the library's own from the standard library's.

use std::alloc::{GlobalAlloc, Layout, System};
use std::backtrace::Backtrace;
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

/// The counting allocator: the system allocator, counting each `alloc` and `realloc`.
pub struct Counting;

thread_local! {
    // A const-initialized Cell needs no allocation of its own, not even on first use.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
    // The number (as `allocations` counts) of the allocation that fails; `usize::MAX`: none.
    static FAILING: Cell<usize> = const { Cell::new(usize::MAX) };
    // The thread counts in `ALLOCATIONS` only, not in `OTHER_ALLOCATIONS`.
    static CALLING: Cell<bool> = const { Cell::new(false) };
    // The thread is recording a backtrace: its allocations pass uncounted.
    static IN_HOOK: Cell<bool> = const { Cell::new(false) };
}

/// Allocations of the threads not marked calling, process-wide.
static OTHER_ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);
/// The number (as `other_allocations` counts) of the one that fails; `usize::MAX`: none.
static OTHER_FAILING: AtomicUsize = AtomicUsize::new(usize::MAX);
/// Whether counted allocations record their backtrace.
static RECORDING: AtomicBool = AtomicBool::new(false);
/// What [`record_backtraces`] returns.
static RECORDED: Mutex<Vec<Recorded>> = Mutex::new(Vec::new());

/// Allocations the calling thread has made so far.
pub fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

/// Makes the calling thread's allocation number `number` (the value [`allocations`] has just
/// before it) fail, or none with `None`.
pub fn fail_allocation(number: Option<usize>) {
    FAILING.with(|failing| failing.set(number.unwrap_or(usize::MAX)));
}

/// Marks the calling thread as one whose allocations [`other_allocations`] leaves out.
pub fn mark_calling_thread() {
    CALLING.with(|calling| calling.set(true));
}

/// Allocations made so far by every thread not marked with [`mark_calling_thread`].
pub fn other_allocations() -> usize {
    OTHER_ALLOCATIONS.load(Ordering::SeqCst)
}

/// Makes allocation number `number` of the other threads (the value [`other_allocations`] has
/// just before it) fail, or none with `None`.
pub fn fail_other_allocation(number: Option<usize>) {
    OTHER_FAILING.store(number.unwrap_or(usize::MAX), Ordering::SeqCst);
}

/// One counted allocation seen while recording.
pub struct Recorded {
    /// Made by a thread marked calling (then `number` counts as [`allocations`] does on it), or
    /// by another (as [`other_allocations`] does).
    pub calling: bool,
    /// Its number.
    pub number: usize,
    /// Where it was made.
    pub backtrace: Backtrace,
}

impl Recorded {
    /// The function names of the backtrace, innermost first.
    pub fn functions(&self) -> Vec<String> {
        // `Backtrace::frames` is not stable: its display, one `N: function` line per frame
        // followed by `at file:line` lines.
        let text = self.backtrace.to_string();
        text.lines()
            .filter_map(|line| {
                let (number, function) = line.trim_start().split_once(": ")?;
                number.parse::<usize>().ok().map(|_| function.to_string())
            })
            .collect()
    }
}

/// Runs `call` with every counted allocation (on any thread) recording its backtrace, and returns
/// `call`'s result and those records, in the order they were made.
pub fn record_backtraces<R>(call: impl FnOnce() -> R) -> (R, Vec<Recorded>) {
    RECORDED.lock().unwrap_or_else(PoisonError::into_inner).clear();
    RECORDING.store(true, Ordering::SeqCst);
    let result = call();
    RECORDING.store(false, Ordering::SeqCst);
    let recorded = std::mem::take(&mut *RECORDED.lock().unwrap_or_else(PoisonError::into_inner));
    (result, recorded)
}

/// Counts an allocation; false when it is the one that must fail.
fn count_one() -> bool {
    // `try_with`: a thread being torn down may still free and allocate.
    if IN_HOOK.try_with(Cell::get).unwrap_or(true) {
        return true;
    }
    let calling = CALLING.try_with(Cell::get).unwrap_or(false);
    let (number, succeeds) = if calling {
        let number = next_own_number();
        (
            number,
            FAILING.try_with(|failing| failing.get() != number).unwrap_or(true),
        )
    } else {
        // Each thread's own count goes on too, as before: a test that reads `allocations` on an
        // unmarked thread sees its allocations.
        let own = next_own_number();
        let number = OTHER_ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        let own_fails = FAILING.try_with(|failing| failing.get() == own).unwrap_or(false);
        (number, !own_fails && OTHER_FAILING.load(Ordering::SeqCst) != number)
    };
    if RECORDING.load(Ordering::SeqCst) {
        record(calling, number);
    }
    succeeds
}

/// Keeps the backtrace of counted allocation `number`, its own allocations passing uncounted.
fn record(calling: bool, number: usize) {
    if IN_HOOK.try_with(|hook| hook.replace(true)).is_err() {
        return;
    }
    let backtrace = Backtrace::force_capture();
    RECORDED.lock().unwrap_or_else(PoisonError::into_inner).push(Recorded {
        calling,
        number,
        backtrace,
    });
    let _ = IN_HOOK.try_with(|hook| hook.set(false));
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

/// The calling thread's next allocation number (`usize::MAX - 1` while the thread is torn down).
fn next_own_number() -> usize {
    ALLOCATIONS
        .try_with(|count| {
            let number = count.get();
            count.set(number + 1);
            number
        })
        .unwrap_or(usize::MAX - 1)
}
