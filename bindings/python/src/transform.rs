//! `to_tangent_space` and `from_tangent_space` over arrays of vectors.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use tbasis::Error;

use crate::errors::{guarded, library_error, Details};
use crate::views::rows;

/// Each row of `directions` (object space) in the tangent space of the same row of `normals` and
/// `tangents`, into `out`; all `(m, 3)` float32 arrays but `tangents`, `(m, 4)`.
#[pyfunction]
pub fn to_tangent_space(
    py: Python<'_>,
    normals: &Bound<'_, PyAny>,
    tangents: &Bound<'_, PyAny>,
    directions: &Bound<'_, PyAny>,
    out: &Bound<'_, PyAny>,
) -> PyResult<()> {
    transform(py, normals, tangents, directions, out, tbasis::to_tangent_space)
}

/// Each row of `directions` (tangent space) in object space; arguments as for
/// [`to_tangent_space`].
#[pyfunction]
pub fn from_tangent_space(
    py: Python<'_>,
    normals: &Bound<'_, PyAny>,
    tangents: &Bound<'_, PyAny>,
    directions: &Bound<'_, PyAny>,
    out: &Bound<'_, PyAny>,
) -> PyResult<()> {
    transform(py, normals, tangents, directions, out, tbasis::from_tangent_space)
}

type Transform = fn([f32; 3], [f32; 4], [f32; 3]) -> Result<[f32; 3], Error>;

fn transform(
    py: Python<'_>,
    normals: &Bound<'_, PyAny>,
    tangents: &Bound<'_, PyAny>,
    directions: &Bound<'_, PyAny>,
    out: &Bound<'_, PyAny>,
    each: Transform,
) -> PyResult<()> {
    let normals = rows::<3>("normals", normals, false)?;
    let tangents = rows::<4>("tangents", tangents, false)?;
    let directions = rows::<3>("directions", directions, false)?;
    let out = rows::<3>("out", out, true)?;
    let count = out.len();
    if [normals.len(), tangents.len(), directions.len()] != [count; 3] {
        return Err(PyValueError::new_err(
            "normals, tangents, directions and out must have as many rows",
        ));
    }
    let result = guarded(py, || {
        // SAFETY: the arrays are arguments of this call, so they outlive it. Every result is
        // computed before `out` is written, so `out` may be an input (an in-place transform).
        let (normals, tangents, directions) = unsafe { (normals.read(), tangents.read(), directions.read()) };
        let mut results = Vec::new();
        results
            .try_reserve_exact(count)
            .map_err(|_| (None, Error::OutOfMemory))?;
        for row in 0..count {
            let result = each(normals.get(row), tangents.get(row), directions.get(row));
            results.push(result.map_err(|error| (Some(row), error))?);
        }
        // SAFETY: as above; the views that read are no longer used.
        let mut out = unsafe { out.write() };
        for (row, &result) in results.iter().enumerate() {
            out.set(row, result);
        }
        Ok(())
    })?;
    result.map_err(|(row, error)| {
        library_error(
            py,
            &error,
            Details {
                row,
                ..Details::default()
            },
        )
    })
}
