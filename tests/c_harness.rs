//! Builds the C harness (`c_tests/`) against the library cargo just built and runs it: plain,
//! under AddressSanitizer + UndefinedBehaviorSanitizer, and under valgrind. Also compiles the
//! header as strict C99 and C++11 and checks what the shared library exports.
//!
//! A test that needs a missing tool says it is skipped, with the tool named, except under CI, where
//! it fails (`tbasis_test_support::needs`).
#![cfg(target_os = "linux")]

#[path = "common/mod.rs"]
mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::artifacts::library_dir;
use common::c_build::{self, compiler, C_FLAGS, SANITIZE_FLAGS, STATIC_LIBS};
use common::tools::{run, run_ok};
use tbasis_test_support::{cases, needs};

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");

/// An empty directory under the target dir for one test's build products.
fn work_dir(test: &str) -> PathBuf {
    c_build::work_dir("c_harness", test)
}

fn c_sources() -> Vec<PathBuf> {
    let dir = Path::new(CRATE_DIR).join("c_tests");
    let mut sources: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("c_tests/")
        .map(|entry| entry.expect("c_tests/ entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "c"))
        .collect();
    sources.sort();
    sources
}

/// Compiles the harness: linked to `libtbasis.so` (found through an rpath), or, sanitized, to
/// `libtbasis.a` so the sanitizer runtime is the first thing in the executable.
fn build_harness(dir: &Path, sanitized: bool) -> PathBuf {
    let exe = dir.join("harness");
    let lib = library_dir();
    let mut command = compiler(false, dir);
    command
        .args(c_sources())
        .arg("-I")
        .arg(Path::new(CRATE_DIR).join("include"));
    command.args(C_FLAGS);
    if sanitized {
        command.args(SANITIZE_FLAGS).arg(lib.join("libtbasis.a"));
        command.args(STATIC_LIBS);
    } else {
        command.arg("-L").arg(&lib).arg("-ltbasis").arg("-lm");
        command.arg(format!("-Wl,-rpath,{}", lib.display()));
    }
    command.arg("-o").arg(&exe);
    run_ok(command, "compiling the C harness");
    exe
}

/// The stability cases, written where the harness can read them.
fn case_file(dir: &Path) -> PathBuf {
    let path = dir.join("cases.bin");
    cases::write_case_file(&path, &cases::all_cases()).expect("write the case file");
    path
}

/// Runs the harness (possibly wrapped) on the case file and requires its own verdict to be clean.
/// `max_case_vertices` skips bigger stability cases (the harness's second argument).
fn run_harness(mut command: Command, dir: &Path, max_case_vertices: Option<u64>) -> Output {
    command.arg(case_file(dir));
    command.args(max_case_vertices.map(|limit| limit.to_string()));
    let output = run(command, "the C harness");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let summary = stdout.lines().rev().find_map(|line| {
        let (passed, failed) = line.strip_suffix(" failed")?.split_once(" passed, ")?;
        Some((passed.parse::<u64>().ok()?, failed.parse::<u64>().ok()?))
    });
    match summary {
        Some((passed, 0)) if passed > 0 => {}
        Some((_, failed)) => panic!("the C harness reports {failed} failed checks"),
        None => panic!("the C harness stopped before its summary ({})", output.status),
    }
    assert!(output.status.success(), "the C harness exited with {}", output.status);
    output
}

/// Builds the library with the test-only feature `fault-injection` into its own target dir (the
/// ordinary build of the other tests stays as it is), and links `c_tests/faults/internal.c` to it.
fn build_fault_program(dir: &Path) -> PathBuf {
    let target = common::artifacts::profile_dir()
        .parent()
        .unwrap()
        .join("fault-injection");
    let mut cargo = Command::new(env!("CARGO"));
    cargo.args(["build", "--lib", "--features", "fault-injection", "--manifest-path"]);
    cargo
        .arg(Path::new(CRATE_DIR).join("Cargo.toml"))
        .arg("--target-dir")
        .arg(&target);
    run_ok(cargo, "building the library with fault-injection");
    let lib = target.join("debug");
    let exe = dir.join("internal");
    let mut command = compiler(false, dir);
    command.arg(Path::new(CRATE_DIR).join("c_tests/faults/internal.c"));
    command
        .arg("-I")
        .arg(Path::new(CRATE_DIR).join("include"))
        .args(C_FLAGS);
    command
        .arg("-L")
        .arg(&lib)
        .arg("-ltbasis")
        .arg(format!("-Wl,-rpath,{}", lib.display()));
    command.arg("-o").arg(&exe);
    run_ok(command, "compiling c_tests/faults/internal.c");
    exe
}

/// `TBASIS_ERROR_INTERNAL`, the one status no input can cause, comes out of every entry point
/// when the library panics inside it, and nothing is written; the same calls succeed without the
/// injected panic. (The harness reaches and names every other status.)
#[test]
fn every_entry_point_turns_a_panic_into_internal() {
    let dir = work_dir("faults");
    let exe = build_fault_program(&dir);
    // Cargo's LD_LIBRARY_PATH would load the ordinary build before the program's rpath does.
    let mut clean = Command::new(&exe);
    clean.env_remove("LD_LIBRARY_PATH");
    let clean = run_ok(clean, "the calls without a fault");
    assert_eq!(String::from_utf8_lossy(&clean.stdout).trim(), "ok 8");
    let mut faulty = Command::new(&exe);
    faulty.env_remove("LD_LIBRARY_PATH");
    faulty.env("TBASIS_INJECT_PANIC", "1").env("RUST_BACKTRACE", "0");
    let output = run_ok(faulty, "the calls with an injected panic");
    assert_eq!(String::from_utf8_lossy(&output.stdout).trim(), "internal 8");
}

#[test]
fn c_harness_passes() {
    let dir = work_dir("plain");
    let exe = build_harness(&dir, false);
    run_harness(Command::new(exe), &dir, None);
}

#[test]
fn c_harness_passes_under_asan_and_ubsan() {
    if !needs::SANITIZERS.found_or_skip() {
        return;
    }
    let dir = work_dir("sanitized");
    let exe = build_harness(&dir, true);
    let mut command = Command::new(exe);
    // The out-of-memory check asks for ~4e18 bytes and needs malloc to return NULL, not to abort.
    c_build::sanitizer_environment(&mut command);
    let output = run_harness(command, &dir, None);
    c_build::assert_no_sanitizer_reports(&output);
}

#[test]
fn c_harness_passes_under_valgrind() {
    if !needs::VALGRIND.found_or_skip() {
        return;
    }
    let dir = work_dir("valgrind");
    let exe = build_harness(&dir, false);
    let command = c_build::valgrind(&exe);
    // Under valgrind the debug library runs ~50 times slower: leave the largest stability cases
    // to the plain and sanitized runs, which take every case.
    run_harness(command, &dir, Some(20_000));
}

/// Uses every function and each kind of declaration, so compiling and linking it checks the
/// header's declarations in both languages.
const HEADER_PROBE: &str = r#"#include "tbasis.h"
#include <string.h>

int main(void)
{
    struct tbasis_mesh mesh;
    tbasis_options options;
    tbasis_output output;
    tbasis_report report;
    memset(&mesh, 0, sizeof mesh);
    memset(&options, 0, sizeof options);
    memset(&output, 0, sizeof output);
    if (tbasis_version() != TBASIS_VERSION || tbasis_status_string(TBASIS_OK) == NULL)
        return 1;
    if (tbasis_scratch_size(&mesh, &options) != 0)
        return 2;
    if (tbasis_generate(&mesh, &options, NULL, &report) != TBASIS_ERROR_NULL_POINTER)
        return 3;
    if (tbasis_calculate_tangent_array(-1, NULL, NULL, NULL, 0, NULL, NULL) != TBASIS_ERROR_INVALID_COUNT)
        return 4;
    if (tbasis_generate_corners(NULL, &options, NULL, 16, &report) != TBASIS_ERROR_NULL_POINTER)
        return 6;
    (void)output;
    return TBASIS_INDEX_U16 + TBASIS_METHOD_LENGYEL + TBASIS_DEGENERATE_LEGACY + TBASIS_FLAG_FLIP_V == 4 ? 0 : 5;
}
"#;

#[test]
fn header_compiles_as_cpp() {
    if !needs::CXX.found_or_skip() {
        return;
    }
    let dir = work_dir("header");
    let lib = library_dir();
    for (cpp, file, standard) in [(true, "probe.cpp", "-std=c++11"), (false, "probe.c", "-std=c99")] {
        let source = dir.join(file);
        std::fs::write(&source, HEADER_PROBE).expect("write the probe");
        let exe = dir.join(format!("{file}.out"));
        let mut command = compiler(cpp, &dir);
        command.arg(standard).args(["-Wall", "-Wextra", "-Werror", "-pedantic"]);
        command.arg("-I").arg(Path::new(CRATE_DIR).join("include")).arg(&source);
        command.arg("-L").arg(&lib).arg("-ltbasis");
        command.arg(format!("-Wl,-rpath,{}", lib.display())).arg("-o").arg(&exe);
        run_ok(command, &format!("compiling the header as {standard}"));
        run_ok(Command::new(&exe), &format!("the {standard} header probe"));
    }
}

#[test]
fn shared_library_exports_exactly_the_header_functions() {
    if !needs::BINUTILS.found_or_skip() {
        return;
    }
    let header = Path::new(CRATE_DIR).join("include/tbasis.h");
    let exported =
        c_build::assert_exports_are_the_header_functions(&library_dir().join("libtbasis.so"), &header, "tbasis_", &[]);
    assert!(exported.len() >= 5, "found only {exported:?} in the header");
}
