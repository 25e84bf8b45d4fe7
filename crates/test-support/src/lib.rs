//! Test support shared by the workspace's tests: the Rust crate's (`crates/tbasis/tests/`) and the
//! C library's (`tests/` at the repository root, whose C harness runs the same stability cases).
//! Each test file uses what it needs.

pub mod alloc_count;
pub mod cases;
pub mod face_meshes;
pub mod face_scenes;
pub mod invariants;
pub mod load;
pub mod mikktspace_reference;
pub mod mikktspace_scenes;
pub mod needs;
#[cfg(test)]
mod needs_tests;
pub mod proptest_config;
pub mod run;
pub mod scenes;
pub mod shapes;

/// mikktspace.c's own callback interface (the crate mikktspace-sys), for tests that call it
/// directly: `crates/tbasis/tests/geometry.rs` holds the `Geometry` trait to it.
pub use mikktspace_sys;
