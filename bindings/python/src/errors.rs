//! The library's errors as one Python exception that the package translates.

use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tbasis::{Error, Indices, Report};

use crate::fault::inject_panic;
use crate::status::{status_of, TBASIS_ERROR_INTERNAL};

create_exception!(
    tbasis._native,
    LibraryError,
    PyException,
    "A call into the library failed: args are (status, message, details), status being the C \
     status value, message the library's description and details a dict naming what failed \
     (keys: report, position, value, row)."
);

/// The report as a tuple in the order of `tbasis_report`'s fields, `first_degenerate_triangle`
/// `None` when there is none.
pub type ReportTuple = (usize, Option<usize>, usize, usize, usize, usize, usize, usize, usize);

pub fn report_tuple(report: &Report) -> ReportTuple {
    (
        report.degenerate_triangles,
        report.first_degenerate_triangle,
        report.fallback_vertices,
        report.mirrored_vertices,
        report.unreferenced_vertices,
        report.inherited_vertices,
        report.abnormal_normals,
        report.repaired_corners,
        report.split_vertices,
    )
}

/// What the package needs to name the culprit of a failure.
#[derive(Default)]
pub struct Details {
    /// The report, for [`Error::DegenerateUv`].
    pub report: Option<ReportTuple>,
    /// The position in the index buffer of the first index out of range, and that index.
    pub index: Option<(usize, usize)>,
    /// The row of the first vector a transform refused.
    pub row: Option<usize>,
}

impl Details {
    /// What `error`, from a call on a mesh with `indices`, tells about its culprit.
    pub fn of(error: &Error, indices: Indices<'_>) -> Details {
        match *error {
            Error::DegenerateUv { ref report, .. } => Details {
                report: Some(report_tuple(report)),
                ..Details::default()
            },
            Error::IndexOutOfRange { triangle, index, .. } => Details {
                index: Some((index_position(indices, triangle, index), index)),
                ..Details::default()
            },
            _ => Details::default(),
        }
    }
}

/// Where in the index buffer `triangle`'s out-of-range `index` is. The library names the first
/// corner out of range, so the corners of its triangle before it are in range and the first
/// corner holding `index` is the one.
fn index_position(indices: Indices<'_>, triangle: usize, index: usize) -> usize {
    let first = 3 * triangle;
    (first..first + 3)
        .find(|&corner| indices.corner(corner) == index)
        .unwrap_or(first)
}

/// [`LibraryError`] for `error`.
pub fn library_error(py: Python<'_>, error: &Error, details: Details) -> PyErr {
    status_error(py, status_of(error.kind()), error.to_string(), details)
}

/// [`LibraryError`] with the C `status` for a failure the binding finds itself.
pub fn status_error(py: Python<'_>, status: u32, message: String, details: Details) -> PyErr {
    let dict = PyDict::new(py);
    let filled = (|| -> PyResult<()> {
        if let Some(report) = details.report {
            dict.set_item("report", report)?;
        }
        if let Some((position, value)) = details.index {
            dict.set_item("position", position)?;
            dict.set_item("value", value)?;
        }
        if let Some(row) = details.row {
            dict.set_item("row", row)?;
        }
        Ok(())
    })();
    match filled {
        Ok(()) => LibraryError::new_err((status, message, dict.unbind())),
        Err(failure) => failure,
    }
}

/// Runs `body` (a call into the library) with the GIL released, a panic, which would be a library
/// bug, becoming [`LibraryError`] with `TBASIS_ERROR_INTERNAL` (the package raises
/// `tbasis.InternalError`) rather than PyO3's `PanicException`, which is no `Exception`.
pub fn guarded<T: Send>(py: Python<'_>, body: impl Send + FnOnce() -> T) -> PyResult<T> {
    let outcome = py.detach(|| {
        catch_unwind(AssertUnwindSafe(|| {
            inject_panic();
            body()
        }))
    });
    outcome.map_err(|_| {
        let message = "the library panicked: a bug, please report it".to_string();
        status_error(py, TBASIS_ERROR_INTERNAL, message, Details::default())
    })
}
