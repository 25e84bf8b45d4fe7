//! The panic rule of the C boundaries: a panic (a library bug) never reaches C. Shared by
//! `libtbasis` (`src/ffi.rs`) and `libtbasis_mikktspace` (`crates/mikktspace-c`, which includes
//! this file and `fault.rs` by path).
#![forbid(unsafe_code)]

use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::fault::inject_panic;

/// Runs `body` (after the test-only panic of the feature `fault-injection`), or gives `on_panic`
/// when it panics.
pub(crate) fn guard<T>(on_panic: T, body: impl FnOnce() -> T) -> T {
    let guarded = || {
        inject_panic();
        body()
    };
    catch_unwind(AssertUnwindSafe(guarded)).unwrap_or(on_panic)
}
