//! The C libraries' artifacts (`libtbasis.so`, `libtbasis.a`, and the mikktspace.c drop-in's
//! `libtbasis_mikktspace.so`, `libtbasis_mikktspace.a`), which `cargo test` does not build.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// `target/<profile>/` of the running test executable, which lives in `target/<profile>/deps/`.
pub fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("path of the test executable");
    exe.parent()
        .and_then(Path::parent)
        .expect("the test executable lives in target/<profile>/deps/")
        .to_path_buf()
}

/// Whether the running tests were built with `--release`.
pub fn release() -> bool {
    profile_dir().file_name().is_some_and(|name| name == "release")
}

/// Builds the C artifacts with `cargo build --lib [--release]` at the root, into the target dir of
/// the running tests, and returns the profile directory that holds them. That command builds the
/// workspace's default members, both C libraries, as `cargo build --release` does for a user.
/// Beside each `.so` (Linux), its build script links the soname to it, so that programs linked
/// against it run.
pub fn build_library(release: bool) -> PathBuf {
    let target_dir = profile_dir().parent().expect("target/<profile>").to_path_buf();
    let mut build = Command::new(env!("CARGO"));
    build.args([
        "build",
        "--lib",
        "--manifest-path",
        concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"),
    ]);
    build.arg("--target-dir").arg(&target_dir);
    if release {
        build.arg("--release");
    }
    let status = build.status().expect("run cargo build");
    assert!(status.success(), "cargo build --lib failed: {status}");
    target_dir.join(if release { "release" } else { "debug" })
}

/// `target/<profile>/` with the C artifacts of the tests' own profile: `cargo test` builds the
/// library only as an rlib, so the first call builds them (once per test process).
pub fn library_dir() -> PathBuf {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    BUILT.get_or_init(|| build_library(release())).clone()
}

/// The ABI name the build scripts (`packaging/soname.rs`) give the shared library `lib{name}.so`
/// (`tbasis`, `tbasis_mikktspace`), whose packages have this one's version.
pub fn soname(name: &str) -> String {
    let (major, minor) = (env!("CARGO_PKG_VERSION_MAJOR"), env!("CARGO_PKG_VERSION_MINOR"));
    if major == "0" {
        format!("lib{name}.so.0.{minor}")
    } else {
        format!("lib{name}.so.{major}")
    }
}
