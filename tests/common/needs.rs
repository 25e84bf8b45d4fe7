//! `tbasis_test_support::needs` (`crates/test-support/src/needs.rs`), for `tools/gltf`, which
//! includes this file by path. The rest of the workspace uses the crate `tbasis-test-support`.

#[path = "../../crates/test-support/src/needs.rs"]
mod imp;
// Not every test of tools/gltf uses it.
#[allow(unused_imports)]
pub use imp::*;
