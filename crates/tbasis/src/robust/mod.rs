//! The robust per-vertex methods (ANGLE, AREA, UNIFORM, and LENGYEL under the robust policies):
//! per-triangle tangents summed per vertex, then resolved into a finite unit frame whatever the
//! input.
//!
//! 1. [`batch`] reads triangles in SIMD-width batches;
//! 2. [`accumulate`] solves each triangle's tangent and bitangent and adds them to its vertices,
//!    with [`degenerate`] deciding which triangles count;
//! 3. [`resolve`] Gram-Schmidts each vertex sum against its normal ([`frame`]), and
//!    [`inherit`] gives vertices without a tangent one from their neighbours (policy INHERIT).
#![forbid(unsafe_code)]

pub(crate) mod accumulate;
pub(crate) mod batch;
pub(crate) mod degenerate;
pub(crate) mod frame;
pub(crate) mod inherit;
pub(crate) mod resolve;
