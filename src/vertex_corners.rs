//! Per-corner output for the per-vertex methods: each corner gets its vertex's frame.
#![forbid(unsafe_code)]

use crate::generate::generate_into;
use crate::mesh::{Mesh, Output};
use crate::options::Options;
use crate::report::Report;
use crate::status::Error;
use crate::strided::StridedMut;

/// Writes every corner's frame into `tangents` (validated by the caller: one per corner).
pub(crate) fn generate_corners(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let mut frames = Vec::new();
    frames
        .try_reserve_exact(mesh.vertex_count())
        .map_err(|_| Error::OutOfMemory)?;
    frames.resize(mesh.vertex_count(), [0.0f32; 4]);
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut frames),
        bitangents: None,
    };
    generate_into(mesh, options, &mut output, scratch, report)?;
    for c in 0..mesh.corner_count() {
        tangents.set(c, frames[mesh.indices.corner(c)]);
    }
    Ok(())
}

/// Bytes of caller scratch [`generate_corners`] needs.
pub(crate) fn scratch_size(vertex_count: usize, _corner_count: usize) -> Option<usize> {
    crate::scratch::scratch_size(vertex_count)
}
