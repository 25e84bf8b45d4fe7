//! The library's C artifacts (`libtbasis.so`, `libtbasis.a`), which `cargo test` does not build.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// `target/<profile>/`, where cargo puts `libtbasis.so` and `libtbasis.a`; test binaries run from
/// `target/<profile>/deps/`.
///
/// `cargo test` builds the library only as an rlib for the Rust tests, so the first call builds
/// its C artifacts into the same directory with `cargo build --lib` (same profile).
pub fn library_dir() -> PathBuf {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    BUILT
        .get_or_init(|| {
            let exe = std::env::current_exe().expect("path of the test executable");
            let dir = exe
                .parent()
                .and_then(Path::parent)
                .expect("the test executable lives in target/<profile>/deps/")
                .to_path_buf();
            let target_dir = dir.parent().expect("target/<profile>");
            let mut build = Command::new(env!("CARGO"));
            build.args([
                "build",
                "--lib",
                "--manifest-path",
                concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"),
            ]);
            build.arg("--target-dir").arg(target_dir);
            if dir.file_name().is_some_and(|name| name == "release") {
                build.arg("--release");
            }
            let status = build.status().expect("run cargo build");
            assert!(status.success(), "cargo build --lib failed: {status}");
            link_soname(&dir);
            dir
        })
        .clone()
}

/// Executables linked with `-ltbasis` load the soname build.rs gives the shared library
/// (`libtbasis.so.0.MINOR`, or `.MAJOR` from 1.0 on), which cargo does not create: link it to
/// `libtbasis.so` so that programs built against `target/<profile>/` run from there.
fn link_soname(dir: &Path) {
    let soname = soname();
    match std::os::unix::fs::symlink("libtbasis.so", dir.join(&soname)) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
        Err(e) => panic!("symlink {soname}: {e}"),
    }
}

/// The ABI name build.rs gives the shared library.
pub fn soname() -> String {
    let (major, minor) = (env!("CARGO_PKG_VERSION_MAJOR"), env!("CARGO_PKG_VERSION_MINOR"));
    if major == "0" {
        format!("libtbasis.so.0.{minor}")
    } else {
        format!("libtbasis.so.{major}")
    }
}
