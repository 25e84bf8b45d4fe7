//! Runs the Python binding's tests (`bindings/python/tests/`, pytest) against the shared library
//! cargo builds for this profile.
//!
//! Without python3, numpy or pytest the test is skipped with a message, except when `CI` is set:
//! CI installs them, so there a missing tool fails the test.

mod common;

use std::path::Path;
use std::process::Command;

use common::artifacts::library_dir;
use common::tools::{missing, run};

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");
const PYTHON: &str = "python3";

/// Whether `python3 -c <code>` runs and succeeds.
fn python_succeeds(code: &str) -> bool {
    Command::new(PYTHON)
        .args(["-c", code])
        .output()
        .is_ok_and(|output| output.status.success())
}

/// The tools the binding's tests need that are not installed, in the order to install them.
fn missing_tools() -> Vec<&'static str> {
    if !python_succeeds("import sys") {
        return vec![PYTHON];
    }
    [("numpy", "import numpy"), ("pytest", "import pytest")]
        .into_iter()
        .filter(|(_, code)| !python_succeeds(code))
        .map(|(name, _)| name)
        .collect()
}

#[test]
fn python_binding_tests_pass() {
    let absent = missing_tools();
    if !absent.is_empty() {
        let how = if absent == [PYTHON] {
            "Debian: apt-get install python3 python3-pip, then python3 -m pip install numpy pytest"
        } else {
            "python3 -m pip install numpy pytest"
        };
        return missing(&format!("{} ({how})", absent.join(", ")), "the Python binding's tests");
    }

    let library = library_dir().join(format!(
        "{}tbasis{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    ));
    assert!(library.is_file(), "{} was not built", library.display());

    // No bytecode or pytest cache written into the source tree.
    let mut pytest = Command::new(PYTHON);
    pytest
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider", "bindings/python"])
        .current_dir(Path::new(CRATE_DIR))
        .env("TBASIS_LIBRARY", &library)
        .env("PYTHONDONTWRITEBYTECODE", "1");
    let output = run(pytest, "python3 -m pytest");
    assert!(
        output.status.success(),
        "pytest bindings/python failed ({}) with TBASIS_LIBRARY={}",
        output.status,
        library.display()
    );
}
