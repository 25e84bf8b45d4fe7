//! Method MIKKTSPACE: mikktspace.c's `genTangSpaceDefault`, float for float, in linear time.
#![forbid(unsafe_code)]

use crate::mesh::{Mesh, Output};
use crate::options::Options;
use crate::report::Report;
use crate::status::Error;
use crate::strided::StridedMut;

/// 32-bit words of working memory a call needs; `None` on overflow.
pub(crate) fn scratch_words(vertex_count: usize, corner_count: usize) -> Option<usize> {
    let _ = (vertex_count, corner_count);
    Some(0)
}

/// Writes mikktspace.c's frame for every corner.
pub(crate) fn generate_corners(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    words: &mut [u32],
    report: &mut Report,
) -> Result<(), Error> {
    let _ = (mesh, options, tangents, words, report);
    Err(Error::Internal)
}

/// Writes each vertex its first corner's frame.
pub(crate) fn generate_vertices(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    words: &mut [u32],
    report: &mut Report,
) -> Result<(), Error> {
    let _ = (mesh, options, output, words, report);
    Err(Error::Internal)
}
