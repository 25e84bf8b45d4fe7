//! Test support shared by the integration tests (each test file uses what it needs).
#![allow(dead_code)]

pub mod artifacts;
pub mod cases;
pub mod invariants;
pub mod load;
pub mod mikktspace_reference;
pub mod mikktspace_scenes;
pub mod needs;
pub mod proptest_config;
pub mod run;
pub mod scenes;
pub mod shapes;
pub mod tools;
