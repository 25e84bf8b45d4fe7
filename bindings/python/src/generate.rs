//! `generate` and `generate_corners`: tangents per vertex and per corner, written in place.

use pyo3::prelude::*;
use tbasis::{DegeneratePolicy, Error, Method, Options, Output, Report, DEFAULT_DEGENERATE_THRESHOLD};

use crate::errors::{library_error, report_tuple, Details, ReportTuple};
use crate::views::{first_out_of_range, rows, MeshPlaces};

/// Tangents (and bitangents) per vertex into `tangents` (`bitangents`), both `(n, 4)` and `(n, 3)`
/// float32 arrays; returns the report. `method` and `policy` are the C values (0: the default,
/// for the policy the method's default); `threshold` None is the default.
#[pyfunction]
#[pyo3(signature = (positions, normals, texcoords, indices, method, policy, threshold, flip_v, threads, tangents, bitangents))]
#[allow(clippy::too_many_arguments)]
pub fn generate(
    py: Python<'_>,
    positions: &Bound<'_, PyAny>,
    normals: &Bound<'_, PyAny>,
    texcoords: Option<&Bound<'_, PyAny>>,
    indices: Option<&Bound<'_, PyAny>>,
    method: u32,
    policy: u32,
    threshold: Option<f32>,
    flip_v: bool,
    threads: u32,
    tangents: &Bound<'_, PyAny>,
    bitangents: Option<&Bound<'_, PyAny>>,
) -> PyResult<ReportTuple> {
    let mesh = MeshPlaces::new(positions, normals, texcoords, indices)?;
    let tangents = rows::<4>("tangents", tangents, true)?;
    let bitangents = bitangents.map(|b| rows::<3>("bitangents", b, true)).transpose()?;
    let options = options(method, policy, threshold, flip_v, threads).map_err(|e| plain_error(py, e))?;
    let mut report = Report::default();
    let result = py.detach(|| {
        // SAFETY: the arrays are arguments of this call, so they outlive it; the library checks
        // that no output byte is an input byte before it writes. A Python thread that writes the
        // same arrays while the GIL is released races with the library, as it would with numpy.
        let (mesh, mut output) = unsafe {
            (
                mesh.mesh(),
                Output {
                    tangents: tangents.write(),
                    bitangents: bitangents.map(|b| b.write()),
                },
            )
        };
        tbasis::generate_into(&mesh, &options, &mut output, None, &mut report)
    });
    finish(py, result, mesh, &report)
}

/// A tangent per triangle corner into `tangents`, a `(corners, 4)` float32 array; returns the
/// report. Arguments as for [`generate`].
#[pyfunction]
#[pyo3(signature = (positions, normals, texcoords, indices, method, policy, threshold, flip_v, threads, tangents))]
#[allow(clippy::too_many_arguments)]
pub fn generate_corners(
    py: Python<'_>,
    positions: &Bound<'_, PyAny>,
    normals: &Bound<'_, PyAny>,
    texcoords: Option<&Bound<'_, PyAny>>,
    indices: Option<&Bound<'_, PyAny>>,
    method: u32,
    policy: u32,
    threshold: Option<f32>,
    flip_v: bool,
    threads: u32,
    tangents: &Bound<'_, PyAny>,
) -> PyResult<ReportTuple> {
    let mesh = MeshPlaces::new(positions, normals, texcoords, indices)?;
    let tangents = rows::<4>("tangents", tangents, true)?;
    let options = options(method, policy, threshold, flip_v, threads).map_err(|e| plain_error(py, e))?;
    let mut report = Report::default();
    let result = py.detach(|| {
        // SAFETY: as in `generate`.
        let (mesh, mut tangents) = unsafe { (mesh.mesh(), tangents.write()) };
        tbasis::generate_corners_into(&mesh, &options, &mut tangents, None, &mut report)
    });
    finish(py, result, mesh, &report)
}

/// The options from the C values, checked.
fn options(method: u32, policy: u32, threshold: Option<f32>, flip_v: bool, threads: u32) -> Result<Options, Error> {
    let method = Method::from_code(method)?;
    let options = Options {
        method,
        degenerate_policy: DegeneratePolicy::from_code(policy, method)?,
        flip_v,
        // Unlike the C ABI's 0, an explicit 0.0 is a threshold: only non-finite input is degenerate.
        degenerate_threshold: threshold.unwrap_or(DEFAULT_DEGENERATE_THRESHOLD),
        threads,
    };
    options.validate()?;
    Ok(options)
}

fn plain_error(py: Python<'_>, error: Error) -> PyErr {
    library_error(py, error, Details::default())
}

/// The report, or the error with what names its culprit.
fn finish(py: Python<'_>, result: Result<(), Error>, mesh: MeshPlaces, report: &Report) -> PyResult<ReportTuple> {
    let error = match result {
        Ok(()) => return Ok(report_tuple(report)),
        Err(error) => error,
    };
    let mut details = Details::default();
    match error {
        Error::DegenerateUv => details.report = Some(report_tuple(report)),
        // SAFETY: the arrays are still this call's arguments, and nothing writes them now.
        Error::IndexOutOfRange => details.index = first_out_of_range(&unsafe { mesh.mesh() }),
        _ => {}
    }
    Err(library_error(py, error, details))
}
