//! `split_corners`: the index buffer that draws per-corner tangents, and the vertices it appends.

use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use tbasis::{Buffer, Error, Mesh, SeamSplit};

use crate::errors::{guarded, library_error, Details};
use crate::views::{indices, rows, IndexPlace, Place};

/// `(new_indices, sources)`.
type Split<'py> = (Bound<'py, PyArray1<u32>>, Bound<'py, PyArray1<u32>>);

/// Returns `(new_indices, sources)`, two uint32 arrays, for a mesh of `vertex_count` vertices
/// whose corners carry `corner_tangents` (a `(corners, 4)` float32 array).
#[pyfunction]
pub fn split_corners<'py>(
    py: Python<'py>,
    indices: Option<&Bound<'py, PyAny>>,
    vertex_count: usize,
    corner_tangents: &Bound<'py, PyAny>,
) -> PyResult<Split<'py>> {
    let index_place = self::indices(indices)?;
    let corners = rows::<4>("corner_tangents", corner_tangents, false)?;
    match guarded(py, || split(index_place, vertex_count, corners))? {
        Ok(split) => Ok((split.indices.into_pyarray(py), split.sources.into_pyarray(py))),
        Err(error) => {
            // SAFETY: the indices are still this call's argument.
            let details = Details::of(&error, unsafe { index_place.view() });
            Err(library_error(py, &error, details))
        }
    }
}

/// The library's split of a mesh given by its indices alone.
///
/// The library's mesh has positions and normals, which the split never reads: zeros stand in for
/// them, but only for the vertices the indices use, so that a mesh with many vertices and few
/// corners costs no more than its corners. The split is then that of a mesh of the used vertices,
/// whose appended vertices are renumbered to follow all `vertex_count` of them.
fn split(index_place: IndexPlace, vertex_count: usize, corners: Place) -> Result<SeamSplit, Error> {
    // SAFETY: the arrays are arguments of the call this runs in, so they outlive it; it only reads.
    let (indices, corner_tangents) = unsafe { (index_place.view(), corners.read::<[f32; 4]>()) };
    // The library's checks, in its order, made here since the mesh it sees has fewer vertices.
    indices.triangle_count(vertex_count)?;
    let corner_count = indices.corner_count(vertex_count);
    if corner_tangents.len() != corner_count {
        return Err(Error::LengthMismatch {
            buffer: Buffer::CornerTangents,
            len: corner_tangents.len(),
            expected: corner_count,
        });
    }
    let mut used = 0;
    for corner in 0..corner_count {
        let vertex = indices.corner(corner);
        if vertex >= vertex_count {
            return Err(Error::IndexOutOfRange {
                triangle: corner / 3,
                index: vertex,
                vertex_count,
            });
        }
        used = used.max(vertex + 1);
    }

    let mut stand_in: Vec<[f32; 3]> = Vec::new();
    stand_in.try_reserve_exact(used).map_err(|_| Error::OutOfMemory)?;
    stand_in.resize(used, [0.0; 3]);
    let mesh = Mesh::new(&stand_in[..], &stand_in[..]).with_indices(indices);
    let mut split = tbasis::split_corners(&mesh, &corner_tangents)?;
    if used < vertex_count {
        // Appended indices must fit 32 bits, as the library checks for the vertices it saw.
        let appended = split.sources.len() as u64;
        if appended > 0 && vertex_count as u64 + appended > u64::from(u32::MAX) + 1 {
            return Err(Error::TooManyVertices);
        }
        for index in &mut split.indices {
            if *index as usize >= used {
                *index = (*index as usize - used + vertex_count) as u32;
            }
        }
    }
    Ok(split)
}
