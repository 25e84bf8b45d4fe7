//! The public entry points: each validates the call, then hands it to one pipeline.
#![forbid(unsafe_code)]

#[cfg(test)]
mod determinism_tests;
pub(crate) mod generate;
pub(crate) mod geometry;
pub(crate) mod interleaved;
pub(crate) mod reusable;
pub(crate) mod seam_split;
pub(crate) mod transform;
pub(crate) mod validate;
