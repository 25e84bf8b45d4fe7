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
//! * [`Options::mikktspace`] gives mikktspace.c's tangents bit for bit, per vertex or per corner
//!   ([`generate_corners`]), and [`split_corners`] turns per-corner tangents into an indexed mesh.
//!
//! This crate is plain Rust (glam is its only dependency). The C library `libtbasis` is a thin
//! boundary over it, with the same functions as `tbasis_*`.
//!
//! A whole program: tangents for a quad, then mikktspace.c's per corner, then in place in an
//! interleaved vertex buffer.
//!
//! ```
//! use tbasis::{generate, generate_corners, generate_interleaved, Mesh, Options, Output, StridedMut, VertexLayout};
//!
//! fn main() -> Result<(), tbasis::Error> {
//!     // One quad in the z = 0 plane, u along +x and v along +y.
//!     let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//!     let normals = [[0.0, 0.0, 1.0]; 4];
//!     let texcoords = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
//!     let indices = [0u32, 1, 2, 0, 2, 3];
//!     let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords).with_indices(&indices);
//!
//!     // Per vertex: x, y, z and the handedness w, with bitangent = w * cross(normal, tangent).
//!     let mut tangents = [[0.0f32; 4]; 4];
//!     let report = generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
//!     assert_eq!(tangents[2], [1.0, 0.0, 0.0, 1.0]);
//!     println!("{report:?}");
//!
//!     // Per corner, bit for bit what mikktspace.c gives (with_flip_v(true) for glTF's V).
//!     let mut corners = [[0.0f32; 4]; 6];
//!     generate_corners(&mesh, &Options::mikktspace(), &mut StridedMut::from_slice(&mut corners))?;
//!     assert_eq!(corners[5], [1.0, 0.0, 0.0, 1.0]);
//!
//!     // In place: position, normal, uv and tangent interleaved, 48 bytes per vertex.
//!     let mut vertices = Vec::new();
//!     for k in 0..4 {
//!         let floats = [positions[k].as_slice(), &normals[k], &texcoords[k], &[0.0; 4]].concat();
//!         vertices.extend(floats.iter().flat_map(|f: &f32| f.to_le_bytes()));
//!     }
//!     let layout = VertexLayout::new(48, 0, 12, 32).with_texcoord(24);
//!     generate_interleaved(&mut vertices, &layout, &indices, &Options::default())?;
//!     assert_eq!(vertices[32..36], 1.0f32.to_le_bytes());
//!     Ok(())
//! }
//! ```
#![deny(unsafe_code)]
#![warn(missing_docs)]

mod entry;
mod kernel;
mod pipelines;

pub use entry::generate::{
    generate, generate_corners, generate_corners_with_scratch, generate_with_scratch, scratch_size, scratch_size_for,
    scratch_size_for_counts,
};
pub use entry::interleaved::generate_interleaved;
pub use entry::reusable::ScratchBuffer;
pub use entry::seam_split::{copy_split_vertices, split_corners, SeamSplit};
pub use entry::transform::{from_tangent_space, to_tangent_space};
pub use entry::validate::check_written;
pub use kernel::error::{Buffer, Error, ErrorKind};
pub use kernel::frame::fallback_frame;
pub use kernel::mesh::{Indices, Mesh, Output};
pub use kernel::options::{DegeneratePolicy, Method, Options, DEFAULT_DEGENERATE_THRESHOLD};
pub use kernel::report::Report;
pub use kernel::views::interleaved::VertexLayout;
pub use kernel::views::strided::{span_bytes, Element, Footprint, Strided, StridedMut};

/// A drop-in for mikktspace.c's callback interface: the `mikktspace` crate's [`Geometry`] trait
/// and [`generate_tangents`], with mikktspace.c's bits (quads and angular thresholds included).
/// Moving from that crate, or from bevy_mikktspace's older API, takes one changed `use` line.
///
/// [`Geometry`]: mikktspace::Geometry
/// [`generate_tangents`]: mikktspace::generate_tangents
pub mod mikktspace {
    pub use crate::entry::geometry::{generate_tangents, generate_tangents_with, Geometry, Settings};
}

/// This crate's version, `major * 1000000 + minor * 1000 + patch`: the C library's
/// `tbasis_version()` and the Python package's `library_version`.
///
/// ```
/// assert_eq!(tbasis::VERSION / 1_000_000, env!("CARGO_PKG_VERSION_MAJOR").parse().unwrap());
/// ```
pub const VERSION: u32 = {
    const fn parse(digits: &str) -> u32 {
        let bytes = digits.as_bytes();
        let (mut value, mut i) = (0, 0);
        while i < bytes.len() {
            value = value * 10 + (bytes[i] - b'0') as u32;
            i += 1;
        }
        value
    }
    parse(env!("CARGO_PKG_VERSION_MAJOR")) * 1_000_000
        + parse(env!("CARGO_PKG_VERSION_MINOR")) * 1_000
        + parse(env!("CARGO_PKG_VERSION_PATCH"))
};
