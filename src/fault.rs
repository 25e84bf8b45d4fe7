//! The test-only panic of the C libraries and the Python binding (`crates/mikktspace-c` and
//! `bindings/python` include this file): with the feature `fault-injection`, every entry point
//! panics inside its guard when `TBASIS_INJECT_PANIC` is set, so that a test can see each one turn
//! a library bug into its error (`TBASIS_ERROR_INTERNAL`; 0 from `genTangSpace`).

/// Panics when the feature `fault-injection` is on and `TBASIS_INJECT_PANIC` is set.
#[cfg(feature = "fault-injection")]
pub fn inject_panic() {
    if std::env::var_os("TBASIS_INJECT_PANIC").is_some() {
        panic!("TBASIS_INJECT_PANIC is set");
    }
}

/// Does nothing: the feature `fault-injection` is off.
#[cfg(not(feature = "fault-injection"))]
#[inline(always)]
pub fn inject_panic() {}
