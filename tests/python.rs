//! The Python package (`bindings/python`, maturin + PyO3) as a user gets it: pip builds its wheel
//! from the source tree, the wheel goes into a fresh virtual environment with its `gltf` extra and
//! the test tools, and its tests run there from a directory outside the repository, so that they
//! import the installed package, never the source tree: pytest (`bindings/python/tests/`), then
//! `mypy --strict` on the tests, the examples and the package's own sources, and vermin on them
//! all for Python 3.9, the oldest the package supports. maturin also builds
//! the source distribution, which pip installs into another fresh virtual environment, where the
//! package's example runs. Last, pytest runs again in a third one, on the oldest numpy with wheels
//! for the running Python (numpy 1 up to Python 3.12).
//!
//! The tests compare the package with this crate's C library (a release build), whose path they
//! get in `TBASIS_REFERENCE_LIBRARY`. Everything the virtual environment holds comes from the
//! package index (PyPI), at the versions `bindings/python/test-constraints.txt` pins, in the build
//! environments too. Without python3 3.11 or later and its venv and pip modules the test is
//! skipped, except under CI, where it fails (`tbasis_test_support::needs`).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::artifacts::{build_library, profile_dir};
use common::tools::run_ok;
use tbasis_test_support::needs;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");

/// The tools the tests need besides the package, which brings numpy, and its `gltf` extra, which
/// brings what the glTF example needs (trimesh and Pillow).
const TEST_TOOLS: [&str; 3] = ["pytest", "mypy", "vermin"];

#[test]
fn python_package_builds_installs_and_passes_its_tests() {
    if !needs::PYTHON_VENV.found_or_skip() {
        return;
    }
    let package = Path::new(CRATE_DIR).join("bindings/python");
    let work = profile_dir().parent().expect("the target dir").join("python-package");
    let reference = build_library(true).join(format!(
        "{}tbasis{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    ));
    assert!(reference.is_file(), "{} was not built", reference.display());

    let pins = Constraints::of_the_package();
    let venv = fresh_venv(&work.join("venv"), &pins);
    let python = venv.python.clone();

    // The wheel, built as `pip install ./bindings/python` builds it, into the target dir rather
    // than the source tree, with the test-only feature `fault-injection` (maturin's PEP 517
    // backend takes cargo arguments from MATURIN_PEP517_ARGS): the tests make the library panic.
    let wheels = fresh_dir(&work.join("wheels"));
    let mut build = Command::new(&python);
    build
        .args(["-m", "pip", "wheel", "--quiet", "--no-deps", "--wheel-dir"])
        .arg(&wheels)
        .arg(&package)
        .env("CARGO_TARGET_DIR", work.join("target"))
        .env("MATURIN_PEP517_ARGS", "--features fault-injection");
    run_ok(clean(pins.applied(build)), "pip wheel bindings/python");
    let wheel = only_file(&wheels, ".whl");
    let name = wheel.file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.starts_with("tbasis-") && name.contains("-cp39-abi3-"),
        "{name}: not one abi3 wheel for CPython 3.9 and later"
    );
    let with_extra = format!("{}[gltf]", wheel.display());
    pip(&python, &pins, &["install", &with_extra]);
    let mut tools = vec!["install", "maturin"];
    tools.extend(TEST_TOOLS);
    pip(&python, &pins, &tools);
    pins.assert_every_package_pinned(&venv);

    // Outside the repository, so that `import tbasis` can only find the installed package.
    let outside = fresh_dir(&work.join("run"));
    pytest(&python, &package, &outside, &reference);

    let mut mypy = Command::new(&python);
    mypy.args(["-m", "mypy", "--strict", "--config-file"])
        .arg(package.join("pyproject.toml"))
        .arg("--cache-dir")
        .arg(outside.join("mypy-cache"))
        .arg(package.join("tests"))
        .arg(package.join("examples"))
        .current_dir(&outside);
    run_ok(clean(mypy), "mypy --strict on the tests and examples");
    let mut sources = Command::new(&python);
    sources
        .args(["-m", "mypy", "--strict", "--config-file"])
        .arg(package.join("pyproject.toml"))
        .arg("--cache-dir")
        .arg(outside.join("mypy-cache-sources"))
        .arg(package.join("python/tbasis"))
        .current_dir(&outside);
    run_ok(clean(sources), "mypy --strict on the package's sources");
    // One wheel for every CPython from 3.9 on, which mypy no longer targets: vermin finds the
    // oldest Python each file's syntax and standard library calls need. It has no `python -m`
    // entry point: its script, beside the interpreter.
    let script = if cfg!(windows) { "vermin.exe" } else { "vermin" };
    let mut vermin = Command::new(python.with_file_name(script));
    vermin
        .args(["--target=3.9-", "--violations", "--no-tips", "--eval-annotations"])
        .args(["python/tbasis", "tests", "examples"].map(|dir| package.join(dir)));
    run_ok(clean(vermin), "vermin: every Python file runs on Python 3.9");

    install_the_source_distribution(&python, &pins, &package, &work, &outside);

    // The package's tests on the oldest numpy this Python can install: numpy 1 up to Python 3.12.
    match oldest_numpy() {
        Some(oldest) => {
            let pins = pins.with("numpy", oldest, &work);
            let venv = fresh_venv(&work.join("oldest-numpy-venv"), &pins);
            pip(&venv.python, &pins, &["install", &with_extra, "pytest"]);
            pins.assert_every_package_pinned(&venv);
            pytest(&venv.python, &package, &outside, &reference);
        }
        // Under CI, as for a missing tool (`needs`), a check left out is a failure.
        None if std::env::var_os("CI").is_some() => panic!("the oldest numpy for this Python is not known"),
        None => eprintln!("skipped: the tests on the oldest numpy, not known for this Python"),
    }
}

/// The oldest numpy release with wheels for the Python `python3` runs (the package accepts numpy
/// 1.21 on; the test needs Python 3.11 on); `None` for a Python it does not name.
fn oldest_numpy() -> Option<&'static str> {
    let mut version = Command::new("python3");
    version.args(["-c", "import sys; print(sys.version_info[1])"]);
    let minor = String::from_utf8_lossy(&run_ok(clean(version), "python3 version").stdout)
        .trim()
        .to_string();
    match minor.as_str() {
        "11" => Some("1.23.2"),
        "12" => Some("1.26.0"),
        "13" => Some("2.1.0"),
        "14" => Some("2.3.2"),
        _ => None,
    }
}

/// `pytest bindings/python/tests` with `python`, from `outside` (not the repository, so that
/// `import tbasis` finds the installed package alone), comparing with the C library `reference`.
fn pytest(python: &Path, package: &Path, outside: &Path, reference: &Path) {
    let mut pytest = Command::new(python);
    pytest
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
        .arg(package.join("tests"))
        .current_dir(outside)
        .env("TBASIS_REFERENCE_LIBRARY", reference)
        // No bytecode written into the source tree.
        .env("PYTHONDONTWRITEBYTECODE", "1");
    run_ok(clean(pytest), "pytest bindings/python/tests");
}

/// A virtual environment: its interpreter, and what `python3 -m venv` put in it (`name==version`,
/// from the interpreter rather than PyPI: pip, and setuptools on some Pythons).
struct Venv {
    python: PathBuf,
    bundled: Vec<String>,
}

/// A fresh virtual environment in `dir`, with pip at its pinned version.
fn fresh_venv(dir: &Path, pins: &Constraints) -> Venv {
    let venv = fresh_dir(dir);
    let mut create = Command::new("python3");
    create.args(["-m", "venv"]).arg(&venv);
    run_ok(clean(create), "python3 -m venv");
    let python = venv_python(&venv);
    let bundled = installed(&python);
    // An old pip builds a copy of the source tree elsewhere, where the path dependency on this
    // crate does not resolve; a current one builds in place.
    pip(&python, pins, &["install", "--upgrade", "pip"]);
    Venv { python, bundled }
}

/// The packages `python`'s environment holds, as `name==version`.
fn installed(python: &Path) -> Vec<String> {
    let mut list = Command::new(python);
    list.args(["-m", "pip", "list", "--format=freeze", "--disable-pip-version-check"]);
    let output = run_ok(clean(list), "pip list");
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .map(str::to_string)
        .collect()
}

/// Builds the source distribution with maturin (from `python`'s virtual environment), checks that
/// it holds regular files only, the licences among them, installs it with pip into a fresh virtual
/// environment, and runs the package's example there. Its build shares the wheel's target dir, so
/// that only the package's own crates are compiled again.
fn install_the_source_distribution(python: &Path, pins: &Constraints, package: &Path, work: &Path, outside: &Path) {
    let sdists = fresh_dir(&work.join("sdists"));
    let mut sdist = Command::new(python);
    sdist
        .args(["-m", "maturin", "sdist", "--out"])
        .arg(&sdists)
        .current_dir(package);
    run_ok(clean(sdist), "maturin sdist");
    let archive = only_file(&sdists, ".tar.gz");
    let mut contents = Command::new(python);
    contents.args(["-c", SDIST_CONTENTS]).arg(&archive);
    run_ok(clean(contents), "the source distribution's contents");

    let sdist_python = fresh_venv(&work.join("sdist-venv"), pins).python;
    let mut install = Command::new(&sdist_python);
    install
        .args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check"])
        .arg(&archive)
        .env("CARGO_TARGET_DIR", work.join("target"));
    run_ok(clean(pins.applied(install)), "pip install of the source distribution");
    let mut example = Command::new(&sdist_python);
    example
        .arg(package.join("examples/interleaved.py"))
        .current_dir(outside);
    let output = run_ok(clean(example), "the example, with the package built from its sdist");
    assert!(
        String::from_utf8_lossy(&output.stdout)
            .contains("index 5 (triangle 1, corner 2) is 4, not in range for 4 vertices"),
        "the example printed something else"
    );
}

/// Python, given the path of a source distribution: fails unless every member is a directory or
/// a regular file (no link that would dangle once unpacked) and the licences are there.
const SDIST_CONTENTS: &str = "
import sys, tarfile
with tarfile.open(sys.argv[1]) as archive:
    members = archive.getmembers()
links = [m.name for m in members if not (m.isfile() or m.isdir())]
assert not links, f'links in the sdist: {links}'
names = {m.name.split('/', 1)[-1] for m in members}
for required in ('LICENSE-MIT', 'LICENSE-APACHE', 'bindings/python/src/c_abi/codes.rs'):
    assert required in names, f'{required} is not in the sdist'
";

/// `command` without what cargo's test environment would add to Python's search paths.
fn clean(mut command: Command) -> Command {
    command
        .env_remove("PYTHONPATH")
        .env_remove("PYTHONHOME")
        .env_remove("LD_LIBRARY_PATH");
    command
}

/// `python -m pip --quiet ARGS`, held to `pins`.
fn pip(python: &Path, pins: &Constraints, args: &[&str]) {
    let mut command = Command::new(python);
    command
        .args(["-m", "pip", "--quiet", "--disable-pip-version-check"])
        .args(args);
    run_ok(clean(pins.applied(command)), &format!("pip {}", args.join(" ")));
}

/// Exact versions for pip: `bindings/python/test-constraints.txt`, or that with one changed.
struct Constraints {
    /// The file pip reads.
    path: PathBuf,
    /// `(name, version)`, names normalized ([`normalized_name`]).
    pins: Vec<(String, String)>,
}

impl Constraints {
    fn of_the_package() -> Self {
        let path = Path::new(CRATE_DIR).join("bindings/python/test-constraints.txt");
        let text = std::fs::read_to_string(&path).expect("bindings/python/test-constraints.txt");
        let pins = text
            .lines()
            .filter(|line| !line.starts_with('#') && !line.trim().is_empty())
            .map(|line| {
                let (name, version) = line.split_once("==").expect("name==version");
                (normalized_name(name), version.trim().to_string())
            })
            .collect();
        Constraints { path, pins }
    }

    /// These with `name` at `version`, written into `dir`.
    fn with(&self, name: &str, version: &str, dir: &Path) -> Self {
        let mut pins = self.pins.clone();
        let pin = pins
            .iter_mut()
            .find(|(pinned, _)| *pinned == normalized_name(name))
            .expect("a pinned package");
        pin.1 = version.to_string();
        let text: String = pins
            .iter()
            .map(|(name, version)| format!("{name}=={version}\n"))
            .collect();
        let path = dir.join(format!("constraints-{name}-{version}.txt"));
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        Constraints { path, pins }
    }

    /// `command` (a pip command) held to these versions, and so are the isolated environments
    /// where it builds packages (pip 26.2 on reads those from `PIP_BUILD_CONSTRAINT` alone). Not
    /// for `python3 -m venv`: its pip comes from the interpreter, whatever its version.
    fn applied(&self, mut command: Command) -> Command {
        command
            .env("PIP_CONSTRAINT", &self.path)
            .env("PIP_BUILD_CONSTRAINT", &self.path);
        command
    }

    /// Every package `venv` holds from PyPI is at the version pinned here: a new
    /// dependency of a pinned one must be pinned too. The package itself and what `python3 -m
    /// venv` put there, as it put it, are not from PyPI.
    fn assert_every_package_pinned(&self, venv: &Venv) {
        let unpinned: Vec<String> = installed(&venv.python)
            .into_iter()
            .filter(|line| {
                let (name, version) = line.split_once("==").unwrap_or((line, ""));
                let name = normalized_name(name);
                name != "tbasis"
                    && !venv.bundled.contains(line)
                    && !self.pins.iter().any(|(pin, pinned)| *pin == name && pinned == version)
            })
            .collect();
        assert!(
            unpinned.is_empty(),
            "installed at a version {} does not pin: {unpinned:?}",
            self.path.display()
        );
    }
}

/// A package name as pip compares them: case, `-`, `_` and `.` aside.
fn normalized_name(name: &str) -> String {
    name.to_ascii_lowercase().replace(['-', '.'], "_")
}

/// The interpreter of a virtual environment.
fn venv_python(venv: &Path) -> PathBuf {
    if cfg!(windows) {
        venv.join("Scripts").join("python.exe")
    } else {
        venv.join("bin").join("python")
    }
}

/// `dir`, emptied.
fn fresh_dir(dir: &Path) -> PathBuf {
    if dir.exists() {
        std::fs::remove_dir_all(dir).unwrap_or_else(|e| panic!("remove {}: {e}", dir.display()));
    }
    std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("create {}: {e}", dir.display()));
    dir.to_path_buf()
}

/// The one file in `dir` whose name ends with `suffix`.
fn only_file(dir: &Path, suffix: &str) -> PathBuf {
    let files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("the output directory")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.to_string_lossy().ends_with(suffix))
        .collect();
    assert_eq!(files.len(), 1, "expected one {suffix} in {}: {files:?}", dir.display());
    files.into_iter().next().unwrap()
}
