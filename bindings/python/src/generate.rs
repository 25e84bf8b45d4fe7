//! `generate` and `generate_corners`: tangents per vertex and per corner, written in place.

use pyo3::prelude::*;
use tbasis::{Error, Options, Output, Report, DEFAULT_DEGENERATE_THRESHOLD};

use crate::codes::{method_of, policy_of};
use crate::errors::{guarded, library_error, report_tuple, status_error, Details, ReportTuple};
use crate::status::{TBASIS_ERROR_UNKNOWN_METHOD, TBASIS_ERROR_UNKNOWN_POLICY};
use crate::views::{rows, MeshPlaces};

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
    let options = options(py, method, policy, threshold, flip_v, threads)?;
    let result = guarded(py, || {
        // SAFETY: the arrays are arguments of this call, so they outlive it; the library checks
        // that no output byte is an input byte before it writes. A Python thread that writes the
        // same arrays while the GIL is released races with the library, as it would with numpy.
        let (mesh, mut output) = unsafe {
            let output = Output::new(tangents.write());
            let output = match bitangents {
                Some(bitangents) => output.with_bitangents(bitangents.write()),
                None => output,
            };
            (mesh.mesh(), output)
        };
        tbasis::generate(&mesh, &options, &mut output)
    })?;
    finish(py, result, mesh)
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
    let options = options(py, method, policy, threshold, flip_v, threads)?;
    let result = guarded(py, || {
        // SAFETY: as in `generate`.
        let (mesh, mut tangents) = unsafe { (mesh.mesh(), tangents.write()) };
        tbasis::generate_corners(&mesh, &options, &mut tangents)
    })?;
    finish(py, result, mesh)
}

/// The options from the C values, checked.
fn options(
    py: Python<'_>,
    method: u32,
    policy: u32,
    threshold: Option<f32>,
    flip_v: bool,
    threads: u32,
) -> PyResult<Options> {
    let plain = |status, message| status_error(py, status, message, Details::default());
    let chosen = method_of(method, policy)
        .ok_or_else(|| plain(TBASIS_ERROR_UNKNOWN_METHOD, format!("unknown method {method}")))?;
    let policy = policy_of(policy, chosen).ok_or_else(|| {
        plain(
            TBASIS_ERROR_UNKNOWN_POLICY,
            format!("unknown degenerate policy {policy}"),
        )
    })?;
    let options = Options::default()
        .with_method(chosen)
        .with_policy(policy)
        .with_flip_v(flip_v)
        // Unlike the C ABI's 0, an explicit 0.0 is a threshold: only non-finite input is degenerate.
        .with_degenerate_threshold(threshold.unwrap_or(DEFAULT_DEGENERATE_THRESHOLD))
        .with_threads(threads);
    options
        .validate()
        .map_err(|error| library_error(py, &error, Details::default()))?;
    Ok(options)
}

/// The report, or the error with what names its culprit.
fn finish(py: Python<'_>, result: Result<Report, Error>, mesh: MeshPlaces) -> PyResult<ReportTuple> {
    match result {
        Ok(report) => Ok(report_tuple(&report)),
        Err(error) => {
            // SAFETY: the arrays are still this call's arguments, and nothing writes them now.
            let details = Details::of(&error, unsafe { mesh.indices.view() });
            Err(library_error(py, &error, details))
        }
    }
}
