//! Test support shared by the integration tests (each test file uses what it needs).
#![allow(dead_code)]

pub mod cases;
