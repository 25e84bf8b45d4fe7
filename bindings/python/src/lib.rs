//! `tbasis._native`: the compiled half of the `tbasis` Python package.
//!
//! The pure-Python package (`python/tbasis/`) checks and converts what users pass, and turns the
//! [`errors::LibraryError`] raised here into its own exception classes. This module takes numpy
//! arrays already shaped for the library and hands their memory to it in place, as strided views,
//! with the GIL released while the library runs. It still checks every array it is given, so that
//! a direct call cannot make it read or write outside an array.

// The C library's option values, statuses and test-only fault hook, which the package shares:
// `src/c_abi/` holds links to the repository's `src/codes.rs`, `src/status.rs` and `src/fault.rs`,
// which the source distribution stores as files.
#[allow(dead_code)]
#[path = "c_abi/codes.rs"]
mod codes;
mod errors;
#[path = "c_abi/fault.rs"]
mod fault;
mod generate;
mod split;
#[allow(dead_code, non_camel_case_types)]
#[path = "c_abi/status.rs"]
mod status;
mod transform;
mod views;

use pyo3::pymodule;

#[pymodule]
mod _native {
    use pyo3::prelude::*;

    #[pymodule_export]
    use super::errors::LibraryError;
    #[pymodule_export]
    use super::generate::{generate, generate_corners};
    #[pymodule_export]
    use super::split::split_corners;
    #[pymodule_export]
    use super::transform::{from_tangent_space, to_tangent_space};

    #[pymodule_init]
    fn init(module: &Bound<'_, PyModule>) -> PyResult<()> {
        module.add("__version__", env!("CARGO_PKG_VERSION"))?;
        // The version of the library linked in, as `TBASIS_VERSION` of the C header gives it, so
        // that a test can check that the package's version follows the library's.
        module.add("library_version", tbasis::VERSION)?;
        Ok(())
    }
}
