//! Tangent-space bases for triangle meshes: a unit tangent and a handedness sign per vertex.
//!
//! Per triangle, solve `Q1 = s1 T + t1 B`, `Q2 = s2 T + t2 B` for the texture-aligned tangent `T`
//! and bitangent `B`; per vertex, sum them, Gram-Schmidt the tangent against the normal and store
//! the handedness in `w`, so that `bitangent = w * cross(normal, tangent.xyz)` (Lengyel 2001).
//!
//! The library reads the caller's vertex buffers in place through strided views (any stride,
//! any alignment, interleaved or not), writes into a strided output (which may live in the same
//! interleaved array), and allocates only compact scratch (or none, with caller scratch).
//!
//! * [`Options::legacy`] reproduces the original listing bit for bit.
//! * The other [`DegeneratePolicy`] values keep every tangent finite, unit length and orthogonal
//!   to the normal, whatever the input: collapsed UVs, slivers, mirror folds, NaN.
//!
//! The same functions are exported to C as `tbasis_*` (see `include/tbasis.h`).
#![deny(unsafe_code)]
#![warn(missing_docs)]

mod accumulate;
mod batch;
mod degenerate;
#[allow(unsafe_code)]
pub mod ffi;
mod frame;
mod generate;
mod inherit;
mod legacy;
mod mesh;
mod mikktspace;
mod options;
mod parallel;
mod report;
mod resolve;
mod scratch;
mod seam_split;
mod status;
#[allow(unsafe_code)]
mod strided;
#[cfg(test)]
mod test_rng;
#[cfg(test)]
mod thread_count_tests;
mod transform;
mod validate;
mod vertex_corners;

pub use generate::{generate, generate_corners, generate_corners_into, generate_into, scratch_size, scratch_size_for};
pub use mesh::{Indices, Mesh, Output};
pub use options::{DegeneratePolicy, Method, Options, DEFAULT_DEGENERATE_THRESHOLD};
pub use report::Report;
pub use seam_split::{copy_split_vertices, split_corners, SeamSplit};
pub use status::Error;
pub use strided::{span_bytes, Element, Strided, StridedMut};
pub use transform::{from_tangent_space, to_tangent_space};
