//! Helpers of the C library's tests alone: its C artifacts and the tools the tests run. What they
//! share with the crate's tests (`crates/tbasis/tests/`) is in `tbasis-test-support`.
#![allow(dead_code)]

pub mod artifacts;
pub mod tools;
