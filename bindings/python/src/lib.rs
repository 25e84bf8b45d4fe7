//! `tbasis._native`: the compiled half of the `tbasis` Python package.
//!
//! The pure-Python package (`python/tbasis/`) checks and converts what users pass, and turns the
//! [`errors::LibraryError`] raised here into its own exception classes. This module takes numpy
//! arrays already shaped for the library and hands their memory to it in place, as strided views,
//! with the GIL released while the library runs. It still checks every array it is given, so that
//! a direct call cannot make it read or write outside an array.

// The C library's option values and statuses, which the package shares (src/ of the repository).
#[allow(dead_code)]
#[path = "../../../src/codes.rs"]
mod codes;
mod errors;
mod generate;
mod split;
#[allow(dead_code, non_camel_case_types)]
#[path = "../../../src/status.rs"]
mod status;
mod transform;
mod views;

use pyo3::pymodule;

/// The version of the `tbasis` crate linked in, `major * 1000000 + minor * 1000 + patch`.
///
/// The crate does not export its version: this is this package's, which is the crate's, since
/// Cargo.toml requires exactly this version of it (the two must be changed together).
const LIBRARY_VERSION: u32 = {
    const fn parse(text: &str) -> u32 {
        let bytes = text.as_bytes();
        let (mut parts, mut part, mut i) = ([0u32; 3], 0, 0);
        while i < bytes.len() {
            match bytes[i] {
                b'.' => part += 1,
                // A pre-release or build suffix ends the numbers.
                b'-' | b'+' => break,
                digit => parts[part] = parts[part] * 10 + (digit - b'0') as u32,
            }
            i += 1;
        }
        parts[0] * 1_000_000 + parts[1] * 1000 + parts[2]
    }
    parse(env!("CARGO_PKG_VERSION"))
};

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
        module.add("library_version", super::LIBRARY_VERSION)?;
        Ok(())
    }
}
