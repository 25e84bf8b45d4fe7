//! Running the tools tests need (`needs.rs` says what a test does when one is not installed).

use std::process::{Command, Output};

/// Runs `command` and prints what it printed (the test harness shows it when the test fails);
/// panics with `what` when it cannot start.
pub fn run(mut command: Command, what: &str) -> Output {
    let output = command
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run {command:?}: {e}"));
    print!("{}", String::from_utf8_lossy(&output.stdout));
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    output
}

/// [`run`], which must exit with 0.
pub fn run_ok(command: Command, what: &str) -> Output {
    let output = run(command, what);
    assert!(output.status.success(), "{what} failed: {}", output.status);
    output
}
