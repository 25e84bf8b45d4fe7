//! The library's errors as one Python exception that the package translates.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tbasis::{Error, Report};

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
    let first = report.first_degenerate_triangle;
    (
        report.degenerate_triangles,
        (first != usize::MAX).then_some(first),
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

/// [`LibraryError`] for `error`.
pub fn library_error(py: Python<'_>, error: Error, details: Details) -> PyErr {
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
        Ok(()) => LibraryError::new_err((error.code(), error.message(), dict.unbind())),
        Err(failure) => failure,
    }
}
