//! What some tests need beyond Rust: the mesh corpus beside the clone, and tools.
//!
//! A test that needs one checks it when it runs, first thing:
//!
//! ```ignore
//! #[test]
//! fn c_harness_passes_under_valgrind() {
//!     if !needs::VALGRIND.found_or_skip() {
//!         return;
//!     }
//!     // ...
//! }
//! ```
//!
//! Where it is missing, the test prints `skipped: needs valgrind (Debian: valgrind)` and passes;
//! under CI (`CI` set) it fails instead ([`Need::found_or_skip`]).
//!
//! `tools/gltf` includes this file by path (through `tests/common/needs.rs`) in its build script,
//! which compiles its tests that need something missing as ignored, with the cfg
//! `tbasis_missing_<name>`: so it uses only the standard library.

use std::path::Path;
use std::process::{Command, Stdio};

/// Something tests need that a fresh clone may lack.
pub struct Need {
    /// Its name; `tools/gltf` sets the cfg `tbasis_missing_<name>` when it is missing.
    pub name: &'static str,
    /// What it is and where to get it, for messages.
    pub what: &'static str,
    probe: Probe,
}

enum Probe {
    /// `../shared/meshes/MANIFEST.tsv` beside the crate.
    Corpus,
    /// Every program is on `PATH`.
    Programs(&'static [&'static str]),
    /// `cc` compiles, links and runs a program with `-fsanitize=address,undefined`.
    Sanitizers,
    /// `python3` imports every module.
    Python(&'static str),
    /// `node` loads the package installed at this path below the repository root.
    NodeModule(&'static str),
}

pub const CORPUS: Need = Need {
    name: "corpus",
    what: "the mesh corpus ../shared/meshes beside the clone (README: \"Test corpus\")",
    probe: Probe::Corpus,
};
pub const BINUTILS: Need = Need {
    name: "binutils",
    what: "nm and readelf (Debian: binutils)",
    probe: Probe::Programs(&["nm", "readelf"]),
};
pub const CXX: Need = Need {
    name: "cxx",
    what: "a C++ compiler, c++ (Debian: g++)",
    probe: Probe::Programs(&["c++"]),
};
pub const VALGRIND: Need = Need {
    name: "valgrind",
    what: "valgrind (Debian: valgrind)",
    probe: Probe::Programs(&["valgrind"]),
};
pub const SANITIZERS: Need = Need {
    name: "sanitizers",
    what: "the AddressSanitizer and UBSan runtimes of cc (Debian: libasan8, libubsan1)",
    probe: Probe::Sanitizers,
};
pub const CMAKE: Need = Need {
    name: "cmake",
    what: "cmake and make (Debian: cmake, make)",
    probe: Probe::Programs(&["cmake", "make"]),
};
pub const PKG_CONFIG: Need = Need {
    name: "pkg_config",
    what: "pkg-config (Debian: pkg-config)",
    probe: Probe::Programs(&["pkg-config"]),
};
pub const PYTHON_VENV: Need = Need {
    name: "python_venv",
    what: "python3 (3.9 or later) with its venv and pip modules (Debian: python3-venv, python3-pip); the \
           Python package's test then fetches maturin, numpy, pytest, mypy and trimesh from PyPI",
    probe: Probe::Python("import sys, venv, ensurepip; assert sys.version_info >= (3, 9)"),
};

pub const GLTF_VALIDATOR: Need = Need {
    name: "gltf_validator",
    what: "node with the Khronos glTF Validator in tools/gltf/node_modules_dir (Debian: nodejs, npm; then \
           npm install --prefix tools/gltf/node_modules_dir gltf-validator@2.0.0-dev.3.10)",
    probe: Probe::NodeModule(GLTF_VALIDATOR_MODULE),
};

/// Where `.ci/run` installs the glTF Validator, below the repository root.
pub const GLTF_VALIDATOR_MODULE: &str = "tools/gltf/node_modules_dir/node_modules/gltf-validator";

pub const ALL: [&Need; 9] = [
    &CORPUS,
    &BINUTILS,
    &CXX,
    &VALGRIND,
    &SANITIZERS,
    &CMAKE,
    &PKG_CONFIG,
    &GLTF_VALIDATOR,
    &PYTHON_VENV,
];

/// The repository's root, whichever crate of the workspace compiles this file: the nearest folder
/// at or above the crate's that holds this file.
pub fn repo_dir() -> std::path::PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .find(|dir| dir.join("crates/test-support/src/needs.rs").is_file())
        .unwrap_or(manifest)
        .to_path_buf()
}

/// The corpus manifest beside the repository, whose presence stands for the corpus.
pub fn corpus_manifest() -> std::path::PathBuf {
    repo_dir().join("../shared/meshes/MANIFEST.tsv")
}

impl Need {
    /// Whether it is there now.
    pub fn found(&self) -> bool {
        match self.probe {
            Probe::Corpus => corpus_manifest().is_file(),
            Probe::Programs(programs) => programs.iter().all(|p| on_path(p)),
            Probe::Sanitizers => sanitizers_run(),
            Probe::Python(code) => succeeds(Command::new("python3").args(["-c", code])),
            Probe::NodeModule(path) => succeeds(
                Command::new("node")
                    .args(["-e", "require(process.argv[1])"])
                    .arg(repo_dir().join(path)),
            ),
        }
    }

    /// Whether it is there, for a test to return early when it is not: then, under CI (`CI` set),
    /// panics like [`Need::require`]; elsewhere prints `skipped: needs <what>` to the test's
    /// stderr and returns false. The message bypasses the test harness's capture, so that
    /// `cargo test` shows it although the test passes.
    pub fn found_or_skip(&self) -> bool {
        if self.found() {
            return true;
        }
        if std::env::var_os("CI").is_some() {
            self.missing_under_ci();
        }
        let thread = std::thread::current();
        let test = thread.name().unwrap_or("a test");
        // One write of the whole line, so that tests running at the same time do not interleave.
        let line = format!("{test}: skipped: needs {}\n", self.what);
        let _ = std::io::Write::write_all(&mut std::io::stderr(), line.as_bytes());
        false
    }

    /// Panics unless it is there: under CI, which must provide it, or (`tools/gltf`) in a test
    /// compiled to run, which means it was removed after `build.rs` looked.
    pub fn require(&self) {
        if self.found() {
            return;
        }
        if std::env::var_os("CI").is_some() {
            self.missing_under_ci();
        }
        panic!(
            "{} is missing but was there when build.rs looked; `touch build.rs` to compile the \
             tests that need it as ignored",
            self.what
        );
    }

    fn missing_under_ci(&self) -> ! {
        panic!("{} is missing; CI must provide it", self.what);
    }

    /// The need called `name`.
    pub fn named(name: &str) -> Option<&'static Need> {
        ALL.into_iter().find(|need| need.name == name)
    }
}

/// For `tools/gltf`: fails when a need that its `build.rs` found missing (`missing_at_build`, its
/// comma-separated `TBASIS_MISSING_NEEDS`) is found now: its tests stay compiled as ignored until
/// `build_rs` changes, so the failure says to touch it.
pub fn assert_none_appeared_since(missing_at_build: &str, build_rs: &str) {
    let appeared: Vec<&str> = missing_at_build
        .split(',')
        .filter(|name| !name.is_empty())
        .map(|name| Need::named(name).unwrap_or_else(|| panic!("build.rs names an unknown need {name}")))
        .filter(|need| need.found())
        .map(|need| need.what)
        .collect();
    assert!(
        appeared.is_empty(),
        "found now, but missing when build.rs ran, so the tests needing them are compiled as \
         ignored: {}; `touch {build_rs}` and run the tests again",
        appeared.join("; ")
    );
}

/// Whether an executable file `program` is in a directory of `PATH`.
fn on_path(program: &str) -> bool {
    let Some(path) = std::env::var_os("PATH") else {
        return false;
    };
    std::env::split_paths(&path).any(|dir| {
        let file = dir.join(program);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            file.metadata()
                .is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        }
        #[cfg(not(unix))]
        {
            file.with_extension("exe").is_file()
        }
    })
}

/// Whether `command` starts and exits with 0; its output is dropped.
fn succeeds(command: &mut Command) -> bool {
    command
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|status| status.success())
}

/// A sanitized program must compile, link and run: the runtimes come in packages of their own.
fn sanitizers_run() -> bool {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let dir = std::env::temp_dir().join(format!("tbasis-sanitizer-probe-{}-{nanos}", std::process::id()));
    if std::fs::create_dir_all(&dir).is_err() {
        return false;
    }
    let (source, exe) = (dir.join("probe.c"), dir.join("probe"));
    let ok = std::fs::write(&source, "int main(void) { return 0; }\n").is_ok()
        && succeeds(
            Command::new("cc")
                .arg("-fsanitize=address,undefined")
                .arg(&source)
                .arg("-o")
                .arg(&exe),
        )
        && succeeds(&mut Command::new(&exe));
    let _ = std::fs::remove_dir_all(&dir);
    ok
}
