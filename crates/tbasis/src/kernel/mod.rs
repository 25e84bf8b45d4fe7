//! The floor every pipeline stands on, imported by them and importing none of them.
//!
//! * The call's vocabulary: [`choices`], [`options`], [`report`], [`error`], and the caller's buffers, read and
//!   written in place ([`views`], [`mesh`]).
//! * Working memory, laid out by the code that uses it and sized by the same code ([`memory`],
//!   with the per-vertex sums in [`sums`]), and threads ([`parallel`]).
//! * Arithmetic shared by the pipelines: mikktspace.c's vector operations in its order
//!   ([`vector`]), SIMD lanes ([`lanes`]) and their dispatch ([`simd`]), the exact arc cosine
//!   ([`arc_cosine`]), the degenerate-shape test ([`degenerate`]), frames and the normal-only
//!   fallback ([`frame`]), and the side a mirror-fold vertex takes ([`fold`]).

pub(crate) mod arc_cosine;
pub(crate) mod choices;
pub(crate) mod degenerate;
pub(crate) mod error;
pub(crate) mod fold;
pub(crate) mod frame;
pub(crate) mod index_bounds;
pub(crate) mod lanes;
pub(crate) mod memory;
pub(crate) mod mesh;
pub(crate) mod options;
pub(crate) mod parallel;
pub(crate) mod report;
#[allow(unsafe_code)]
pub(crate) mod simd;
pub(crate) mod sums;
#[cfg(test)]
pub(crate) mod test_rng;
pub(crate) mod vector;
pub(crate) mod vertex_sums;
#[allow(unsafe_code)]
pub(crate) mod views;
