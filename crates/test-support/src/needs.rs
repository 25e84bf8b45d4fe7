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
//! Where it is missing, the test prints `skipped: needs valgrind (Debian: valgrind)`, naming only
//! what is missing now and how to get it, and passes; under CI (`CI` set) it fails instead
//! ([`Need::found_or_skip`]). Everything is looked for when the test runs, never when it is
//! compiled, so that what is added after a build counts at the next `cargo test`.
//!
//! `tools/gltf` includes this file by path (through `tests/common/needs.rs`): so it uses only the
//! standard library.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Something tests need that a fresh clone may lack.
pub struct Need {
    probe: Probe,
}

enum Probe {
    /// Every file the repository's corpus manifests list, in `../shared/meshes` beside the clone.
    Corpus,
    /// Every program is on `PATH`: (program, the Debian package that has it).
    Programs(&'static [(&'static str, &'static str)]),
    /// `cc` compiles, links and runs a program with `-fsanitize=address,undefined`.
    Sanitizers,
    /// python3 3.11 or later (what the Python test's pinned packages need; the package itself
    /// runs on 3.9), with its venv and pip modules.
    PythonVenv,
    /// node, and the glTF Validator's package at [`GLTF_VALIDATOR_MODULE`] in its pinned version.
    GltfValidator,
    /// mikktspace.c and mikktspace.h as the crate mikktspace-sys vendors them ([`mikktspace_c_dir`]).
    MikktspaceC,
    /// A Linux kernel with transparent huge pages, which `madvise(MADV_HUGEPAGE)` needs.
    TransparentHugePages,
    /// util-linux's `script`, able to run a command on a pseudo-terminal.
    Terminal,
}

pub const CORPUS: Need = Need { probe: Probe::Corpus };
pub const BINUTILS: Need = Need {
    probe: Probe::Programs(&[("nm", "binutils"), ("readelf", "binutils"), ("ar", "binutils")]),
};
pub const CXX: Need = Need {
    probe: Probe::Programs(&[("c++", "g++")]),
};
pub const VALGRIND: Need = Need {
    probe: Probe::Programs(&[("valgrind", "valgrind")]),
};
pub const SANITIZERS: Need = Need {
    probe: Probe::Sanitizers,
};
pub const CMAKE: Need = Need {
    probe: Probe::Programs(&[("cmake", "cmake"), ("make", "make")]),
};
pub const GIT: Need = Need {
    probe: Probe::Programs(&[("git", "git")]),
};
pub const PKG_CONFIG: Need = Need {
    probe: Probe::Programs(&[("pkg-config", "pkg-config")]),
};
pub const PYTHON_VENV: Need = Need {
    probe: Probe::PythonVenv,
};
pub const GLTF_VALIDATOR: Need = Need {
    probe: Probe::GltfValidator,
};

pub const MIKKTSPACE_C: Need = Need {
    probe: Probe::MikktspaceC,
};
pub const TRANSPARENT_HUGE_PAGES: Need = Need {
    probe: Probe::TransparentHugePages,
};
pub const TERMINAL: Need = Need { probe: Probe::Terminal };

/// Where `.ci/run` installs the glTF Validator, below the repository root.
pub const GLTF_VALIDATOR_MODULE: &str = "tools/gltf/node_modules_dir/node_modules/gltf-validator";
/// The glTF Validator's version the tests expect (`.ci/run` installs it).
pub const GLTF_VALIDATOR_VERSION: &str = "2.0.0-dev.3.10";

/// The repository's root, whichever crate of the workspace compiles this file: the nearest folder
/// at or above the crate's that holds this file.
pub fn repo_dir() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .find(|dir| dir.join("crates/test-support/src/needs.rs").is_file())
        .unwrap_or(manifest)
        .to_path_buf()
}

/// The corpus folder, `../shared/meshes` beside the repository.
pub fn corpus_dir() -> PathBuf {
    repo_dir().join("../shared/meshes")
}

/// The corpus manifest beside the repository, which the tests read.
pub fn corpus_manifest() -> PathBuf {
    corpus_dir().join("MANIFEST.tsv")
}

/// The files of the corpus, relative to its folder: `MANIFEST.tsv` and every path of the
/// repository's manifests (`corpus/MANIFEST.tsv`, `corpus/companions.tsv`), which
/// `scripts/fetch-corpus` fetches.
pub fn corpus_files() -> Vec<String> {
    let mut files = vec!["MANIFEST.tsv".to_string()];
    for list in ["corpus/MANIFEST.tsv", "corpus/companions.tsv"] {
        let path = repo_dir().join(list);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        files.extend(
            text.lines()
                .skip(1)
                .filter_map(|line| line.split('\t').next())
                .filter(|name| !name.is_empty())
                .map(str::to_string),
        );
    }
    files
}

impl Need {
    /// What is missing now and how to get it, or `None` when it is all there.
    pub fn missing(&self) -> Option<String> {
        match self.probe {
            Probe::Corpus => missing_corpus(),
            Probe::Programs(programs) => missing_programs(programs),
            Probe::Sanitizers => (!sanitizers_run())
                .then(|| "the AddressSanitizer and UBSan runtimes of cc (Debian: libasan8, libubsan1)".to_string()),
            Probe::PythonVenv => missing_python_venv(),
            Probe::GltfValidator => missing_gltf_validator(),
            Probe::TransparentHugePages => (!Path::new("/sys/kernel/mm/transparent_hugepage").exists())
                .then(|| "a kernel with transparent huge pages (/sys/kernel/mm/transparent_hugepage)".to_string()),
            Probe::Terminal => missing_terminal(),
            Probe::MikktspaceC => mikktspace_c_dir().is_none().then(|| {
                format!(
                    "mikktspace.c and mikktspace.h of the crate {MIKKTSPACE_SYS}, which `cargo metadata` \
                     finds once cargo has fetched it (`cargo fetch`)"
                )
            }),
        }
    }

    /// Whether it is there, for a test to return early when it is not: then, under CI (`CI` set),
    /// panics; elsewhere prints `skipped: needs <what is missing>` to the test's stderr and
    /// returns false. The message bypasses the test harness's capture, so that `cargo test` shows
    /// it although the test passes.
    pub fn found_or_skip(&self) -> bool {
        let Some(missing) = self.missing() else {
            return true;
        };
        if std::env::var_os("CI").is_some() {
            panic!("missing: {missing}; CI must provide it");
        }
        let thread = std::thread::current();
        let test = thread.name().unwrap_or("a test");
        // One write of the whole line, so that tests running at the same time do not interleave.
        let line = format!("{test}: skipped: needs {missing}\n");
        let _ = std::io::Write::write_all(&mut std::io::stderr(), line.as_bytes());
        false
    }
}

/// The corpus files absent from its folder, named, with the command that fetches them.
fn missing_corpus() -> Option<String> {
    missing_corpus_files(&corpus_dir(), &corpus_files())
}

/// Which of `files` are absent from `dir`, named (the first two), with the command that fetches
/// them; `None` when none is.
pub(crate) fn missing_corpus_files(dir: &Path, files: &[String]) -> Option<String> {
    let absent: Vec<&String> = files.iter().filter(|file| !dir.join(file).is_file()).collect();
    let shown = match absent.as_slice() {
        [] => return None,
        [one] => one.to_string(),
        [first, second] => format!("{first} and {second}"),
        [first, second, rest @ ..] => format!("{first}, {second} and {} more", rest.len()),
    };
    Some(format!(
        "the mesh corpus in {} ({shown} absent; scripts/fetch-corpus fetches it: README, \"Test corpus\")",
        dir.display()
    ))
}

/// The programs absent from `PATH` and their Debian packages.
pub(crate) fn missing_programs(programs: &[(&str, &str)]) -> Option<String> {
    let absent: Vec<&(&str, &str)> = programs.iter().filter(|(program, _)| !on_path(program)).collect();
    if absent.is_empty() {
        return None;
    }
    let names: Vec<&str> = absent.iter().map(|(program, _)| *program).collect();
    let mut packages: Vec<&str> = absent.iter().map(|(_, package)| *package).collect();
    packages.dedup();
    Some(format!("{} (Debian: {})", names.join(" and "), packages.join(", ")))
}

/// What running a command on a pseudo-terminal with `script -qec COMMAND /dev/null` lacks here.
fn missing_terminal() -> Option<String> {
    if !on_path("script") {
        return Some("script (Debian: bsdutils)".to_string());
    }
    let mut probe = Command::new("script");
    probe.args(["-qec", "true", "/dev/null"]).env("SHELL", "/bin/sh");
    (!succeeds(&mut probe))
        .then(|| "a pseudo-terminal, which `script -qec true /dev/null` cannot open here".to_string())
}

fn missing_python_venv() -> Option<String> {
    if !on_path("python3") {
        return Some(
            "python3, 3.11 or later, with its venv and pip modules (Debian: python3, python3-venv, python3-pip)".into(),
        );
    }
    if !succeeds(Command::new("python3").args(["-c", "import sys; assert sys.version_info >= (3, 11)"])) {
        return Some("python3 3.11 or later (an older one is on PATH)".into());
    }
    let absent: Vec<&str> = ["venv", "ensurepip"]
        .into_iter()
        .filter(|module| !succeeds(Command::new("python3").args(["-c", &format!("import {module}")])))
        .collect();
    if absent.is_empty() {
        return None;
    }
    Some(format!(
        "the python3 module{} {} (Debian: python3-venv, python3-pip); the Python package's test then \
         fetches maturin, numpy, pytest, mypy, trimesh and Pillow from PyPI",
        if absent.len() == 1 { "" } else { "s" },
        absent.join(" and ")
    ))
}

fn missing_gltf_validator() -> Option<String> {
    let install = format!(
        "npm install --prefix tools/gltf/node_modules_dir --no-audit --no-fund gltf-validator@{GLTF_VALIDATOR_VERSION}"
    );
    if !on_path("node") {
        return Some(format!(
            "node (Debian: nodejs, npm), then the Khronos glTF Validator {GLTF_VALIDATOR_VERSION} ({install})"
        ));
    }
    let package = repo_dir().join(GLTF_VALIDATOR_MODULE).join("package.json");
    let pinned = format!("\"version\": \"{GLTF_VALIDATOR_VERSION}\"");
    match std::fs::read_to_string(&package) {
        Ok(text) if text.contains(&pinned) => None,
        Ok(_) => Some(format!(
            "the Khronos glTF Validator {GLTF_VALIDATOR_VERSION}, not the version in {} ({install})",
            package.display()
        )),
        Err(_) => Some(format!(
            "the Khronos glTF Validator {GLTF_VALIDATOR_VERSION} ({install})"
        )),
    }
}

/// The package that vendors mikktspace.c, a dependency of tbasis-test-support.
const MIKKTSPACE_SYS: &str = "mikktspace-sys 0.1.1";

/// The folder holding mikktspace.c and mikktspace.h as the crate mikktspace-sys vendors them (its
/// `c_code/`), found through `cargo metadata` (offline) of the workspace; `None` when cargo has
/// not fetched that package. Looked for once per process.
pub fn mikktspace_c_dir() -> Option<PathBuf> {
    static DIR: std::sync::OnceLock<Option<PathBuf>> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        let output = Command::new(cargo)
            .args([
                "metadata",
                "--format-version",
                "1",
                "--offline",
                "--locked",
                "--manifest-path",
            ])
            .arg(repo_dir().join("Cargo.toml"))
            .stdin(Stdio::null())
            .stderr(Stdio::null())
            .output()
            .ok()?;
        let json = String::from_utf8(output.stdout).ok()?;
        // The package's `"manifest_path":"<registry>/mikktspace-sys-0.1.1/Cargo.toml"`.
        let package = MIKKTSPACE_SYS.replace(' ', "-");
        let end = json.find(&format!("/{package}/Cargo.toml\""))?;
        let start = json[..end].rfind('"')? + 1;
        let dir = Path::new(&json[start..end]).join(&package).join("c_code");
        (dir.join("mikktspace.c").is_file() && dir.join("mikktspace.h").is_file()).then_some(dir)
    })
    .clone()
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
