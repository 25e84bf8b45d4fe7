//! Helpers of the C libraries' tests alone: their C artifacts, compiling C against them and the
//! tools the tests run. What they share with the crate's tests (`crates/tbasis/tests/`) is in `tbasis-test-support`.
#![allow(dead_code)]

pub mod artifacts;
pub mod c_build;
pub mod tools;
