//! `libtbasis_mikktspace`, the drop-in for mikktspace.c (`crates/mikktspace-c`,
//! `include/tbasis_mikktspace.h`), from C.
//!
//! One driver (`c_tests/mikktspace/driver.c`), compiled against mikktspace.h as vendored by the
//! crate mikktspace-sys, is linked to mikktspace.c and to the drop-in (`.a`, `.so`, and the `.so`
//! through this repository's header with 2 threads), and run on the same meshes: the generated
//! ones of `tbasis_test_support::face_meshes` and every corpus mesh. Every line it prints, the
//! return value, the number of set calls and a digest of every argument of every set call, must
//! be the same. The drop-in's driver also runs under AddressSanitizer + UBSan and under valgrind.
//! Beside it: the library's exports, its header's ABI, the contract the header states
//! (`c_tests/mikktspace/contract.c`), the worker threads each call starts
//! (`c_tests/mikktspace/workers.c`), every allocation of a call failing in turn
//! (`c_tests/mikktspace/out_of_memory.c`), a panic inside the boundary, and the sample program of the
//! README (`examples/mikktspace`) built with mikktspace.c and relinked.
//!
//! A test that needs a missing tool says it is skipped, with the tool named, except under CI, where
//! it fails (`tbasis_test_support::needs`).
#![cfg(target_os = "linux")]

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::{Mutex, OnceLock};

use common::artifacts::{library_dir, profile_dir};
use common::c_build::{self, compiler, C_FLAGS, SANITIZE_FLAGS, STATIC_LIBS};
use common::tools::{run, run_ok};
use tbasis_test_support::face_meshes::{self, FaceMesh};
use tbasis_test_support::face_scenes;
use tbasis_test_support::{load, needs};

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");
const SUITE: &str = "mikktspace_dropin";
/// Meshes above this many vertices are left to the plain and sanitized runs, and so are all but
/// these configurations (both entry points, each set callback, and both): valgrind runs the
/// library's debug build about 50 times slower.
const VALGRIND_MAX_VERTICES: u64 = 20_000;
const VALGRIND_CONFIGS: [&str; 3] = ["default both", "90 full", "30 basic"];

fn c_tests(file: &str) -> PathBuf {
    Path::new(CRATE_DIR).join("c_tests/mikktspace").join(file)
}

/// mikktspace-sys's `c_code/` (mikktspace.c and mikktspace.h); the test calling it has checked
/// `needs::MIKKTSPACE_C`.
fn mikktspace_c_dir() -> PathBuf {
    needs::mikktspace_c_dir().expect("needs::MIKKTSPACE_C was checked")
}

/// What the driver links.
enum Link {
    /// mikktspace.c's object file.
    MikktspaceC,
    /// A static archive, and the system libraries a Rust one needs.
    Static(PathBuf),
    /// `-l<name>` from a folder, found at run time through an rpath.
    Shared(PathBuf, &'static str),
}

/// The drop-in's static archive.
fn dropin_static() -> Link {
    Link::Static(library_dir().join("libtbasis_mikktspace.a"))
}

/// The drop-in's shared library.
fn dropin_shared() -> Link {
    Link::Shared(library_dir(), "tbasis_mikktspace")
}

/// mikktspace.c compiled once per test process, position-independent (for the reference's own
/// shared library), into `mikktspace.o`.
fn mikktspace_object() -> PathBuf {
    static OBJECT: OnceLock<PathBuf> = OnceLock::new();
    OBJECT
        .get_or_init(|| {
            let dir = c_build::work_dir(SUITE, "mikktspace.c");
            let object = dir.join("mikktspace.o");
            let mut command = compiler(false, &dir);
            // Its own code, compiled as its users compile it: warnings are not ours to fix.
            command.args(["-std=c99", "-ffp-contract=off", "-fPIC", "-w", "-c"]);
            command
                .arg(mikktspace_c_dir().join("mikktspace.c"))
                .arg("-o")
                .arg(&object);
            run_ok(command, "compiling mikktspace.c");
            object
        })
        .clone()
}

/// Compiles the driver into `dir/driver`: against mikktspace.h, or this repository's header
/// (`tbasis_header`), optionally sanitized, linked to `link`.
fn build_driver(dir: &Path, link: &Link, tbasis_header: bool, sanitized: bool) -> PathBuf {
    let exe = dir.join("driver");
    let mut command = compiler(false, dir);
    command.arg(c_tests("driver.c")).args(C_FLAGS);
    if tbasis_header {
        command
            .arg("-DDRIVER_TBASIS_HEADER")
            .arg("-I")
            .arg(Path::new(CRATE_DIR).join("include"));
    } else {
        command.arg("-I").arg(mikktspace_c_dir());
    }
    if sanitized {
        command.args(SANITIZE_FLAGS);
    }
    match link {
        Link::MikktspaceC => {
            command.arg(mikktspace_object()).arg("-lm");
        }
        Link::Static(archive) => {
            command.arg(archive).args(STATIC_LIBS);
        }
        Link::Shared(lib, name) => {
            command.arg("-L").arg(lib).arg(format!("-l{name}"));
            command.arg(format!("-Wl,-rpath,{}", lib.display()));
        }
    }
    command.arg("-o").arg(&exe);
    run_ok(command, "compiling the mikktspace driver");
    exe
}

/// The generated meshes, written once per test process.
fn generated_file() -> PathBuf {
    static FILE: OnceLock<PathBuf> = OnceLock::new();
    FILE.get_or_init(|| {
        let path = c_build::work_dir(SUITE, "generated").join("meshes.bin");
        face_meshes::write_file(&path, &face_scenes::generated()).expect("write the generated meshes");
        path
    })
    .clone()
}

/// Every corpus mesh with texture coordinates (those above `load::DEBUG_MAX_VERTICES` in
/// optimized builds only), written once.
fn corpus_file() -> PathBuf {
    let dir = load::corpus_dir().expect("the corpus");
    let mut meshes: Vec<FaceMesh> = Vec::new();
    for row in load::read_manifest(&dir).expect("MANIFEST.tsv") {
        if load::left_to_optimized_builds(&row) {
            continue;
        }
        let file = load::load(&dir, &row).unwrap_or_else(|e| panic!("{}: {e}", row.path));
        meshes.extend(
            file.primitives
                .iter()
                .filter_map(|primitive| face_scenes::from_primitive(&row.path, primitive, false)),
        );
    }
    assert!(meshes.len() >= 50, "only {} corpus meshes", meshes.len());
    let path = c_build::work_dir(SUITE, "corpus").join("meshes.bin");
    face_meshes::write_file(&path, &meshes).expect("write the corpus meshes");
    path
}

/// One line of the driver's output: mesh, configuration, return value, set calls, digest.
#[derive(Clone, Debug, PartialEq)]
struct Line {
    mesh: String,
    config: String,
    result: String,
    calls: String,
    digest: String,
}

/// How to run a driver: under valgrind or sanitizers, strict (a get callback for a face or vertex
/// that does not exist fails the run: the drop-in's runs; mikktspace.c makes one, see driver.c),
/// and with which arguments beyond the file.
#[derive(Clone, Default)]
struct RunAs {
    valgrind: bool,
    sanitized: bool,
    strict: bool,
    args: Vec<String>,
}

impl RunAs {
    /// How the drop-in's drivers run: strict.
    fn dropin() -> RunAs {
        RunAs {
            strict: true,
            ..RunAs::default()
        }
    }

    /// With `args` after the others.
    fn with(mut self, args: &[&str]) -> RunAs {
        self.args.extend(args.iter().map(|arg| arg.to_string()));
        self
    }

    /// On the meshes of up to `max_vertices` vertices only.
    fn up_to(self, max_vertices: Option<u64>) -> RunAs {
        match max_vertices {
            Some(n) => self.with(&["--max-vertices", &n.to_string()]),
            None => self,
        }
    }
}

/// The driver's command as `how` runs it, on `meshes`.
fn driver_command(exe: &Path, meshes: &Path, how: &RunAs) -> Command {
    let mut command = if how.valgrind {
        c_build::valgrind(exe)
    } else {
        Command::new(exe)
    };
    if how.sanitized {
        c_build::sanitizer_environment(&mut command);
    }
    command.arg(meshes).args(&how.args);
    if how.strict {
        command.arg("--strict");
    }
    command
}

/// Runs a driver on `meshes` and parses what it prints; it must exit with 0 (no callback out of
/// range, no sanitizer or valgrind error).
fn run_driver(exe: &Path, meshes: &Path, how: &RunAs) -> Vec<Line> {
    // Its lines are compared, not printed; what it says on stderr is shown.
    let output = driver_command(exe, meshes, how)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", exe.display()));
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    if how.sanitized {
        c_build::assert_no_sanitizer_reports(&output);
    }
    assert!(
        output.status.success(),
        "{} exited with {}",
        exe.display(),
        output.status
    );
    let parse = |line: &str| {
        let fields: Vec<&str> = line.split('\t').collect();
        let [mesh, config, result, calls, digest] = fields[..] else {
            panic!("not a driver line: {line:?}");
        };
        let [mesh, config, result, calls, digest] = [mesh, config, result, calls, digest].map(str::to_string);
        Line {
            mesh,
            config,
            result,
            calls,
            digest,
        }
    };
    String::from_utf8_lossy(&output.stdout).lines().map(parse).collect()
}

/// The driver linked to mikktspace.c, built once.
fn reference_driver() -> PathBuf {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| build_driver(&c_build::work_dir(SUITE, "reference"), &Link::MikktspaceC, false, false))
        .clone()
}

/// mikktspace.c's lines on `meshes` (those up to `max_vertices` vertices), run once per test
/// process for each.
fn reference_lines(meshes: &Path, max_vertices: Option<u64>) -> Vec<Line> {
    type Runs = BTreeMap<(PathBuf, Option<u64>), Vec<Line>>;
    static RUNS: Mutex<Runs> = Mutex::new(BTreeMap::new());
    let mut runs = RUNS.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let lines = runs
        .entry((meshes.to_path_buf(), max_vertices))
        .or_insert_with(|| run_driver(&reference_driver(), meshes, &RunAs::default().up_to(max_vertices)));
    lines.clone()
}

/// The calls of one run, one line each, from `--dump`.
fn dump(exe: &Path, meshes: &Path, line: &Line, how: &RunAs) -> Vec<String> {
    let how = how.clone().with(&["--dump", &line.mesh, &line.config]);
    let mut command = driver_command(exe, meshes, &how);
    command.stderr(std::process::Stdio::null());
    let output = command.output().expect("run the driver with --dump");
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .map(str::to_string)
        .collect()
}

/// The runs on which a driver's lines differ from mikktspace.c's, as text: every run counted, the
/// first few named with what each side printed, and the first of them with the first call that
/// differs (from `--dump`). Empty when they agree on every line.
fn differences(reference: &[Line], (exe, found, how): (&Path, &[Line], &RunAs), meshes: &Path) -> String {
    if reference.len() != found.len() {
        let key = |l: &Line| format!("{} / {}", l.mesh, l.config);
        let missing = reference.iter().find(|e| !found.iter().any(|f| key(f) == key(e)));
        return format!(
            "{} runs expected, {} printed; the first missing: {:?}",
            reference.len(),
            found.len(),
            missing.map(key)
        );
    }
    let differing: Vec<(&Line, &Line)> = reference.iter().zip(found).filter(|(e, f)| e != f).collect();
    let Some(&(first, first_found)) = differing.first() else {
        return String::new();
    };
    assert_eq!(
        (&first.mesh, &first.config),
        (&first_found.mesh, &first_found.config),
        "the drivers ran in another order"
    );
    let mut report = format!("{} of {} runs differ\n", differing.len(), reference.len());
    for (e, f) in differing.iter().take(12) {
        report += &format!(
            "  {} / {}: mikktspace.c returned {} with {} set calls ({}), this one {} with {} ({})\n",
            e.mesh, e.config, e.result, e.calls, e.digest, f.result, f.calls, f.digest
        );
    }
    let want = dump(&reference_driver(), meshes, first, &RunAs::default());
    let got = dump(exe, meshes, first, how);
    let call = want
        .iter()
        .zip(&got)
        .position(|(w, g)| w != g)
        .unwrap_or(want.len().min(got.len()));
    report += &format!(
        "first difference in {} / {}, line {call} of the calls:\n  mikktspace.c: {}\n  this one:     {}\n",
        first.mesh,
        first.config,
        want.get(call).map_or("(no more calls)", String::as_str),
        got.get(call).map_or("(no more calls)", String::as_str),
    );
    report
}

/// Builds the driver `name` linked to `link` (through this repository's header with
/// `tbasis_header`; sanitized when `how` runs it so) and requires mikktspace.c's lines on the
/// meshes of `meshes` up to `max_vertices` vertices (in the configurations `how` chooses).
fn assert_same_calls(
    name: &str,
    link: &Link,
    tbasis_header: bool,
    meshes: &Path,
    max_vertices: Option<u64>,
    how: RunAs,
) {
    // The configurations `--config` chooses, if any.
    let chosen: Vec<&String> = how
        .args
        .windows(2)
        .filter(|w| w[0] == "--config")
        .map(|w| &w[1])
        .collect();
    let mut reference = reference_lines(meshes, max_vertices);
    reference.retain(|line| chosen.is_empty() || chosen.contains(&&line.config));
    let exe = build_driver(&c_build::work_dir(SUITE, name), link, tbasis_header, how.sanitized);
    let how = how.up_to(max_vertices);
    let found = run_driver(&exe, meshes, &how);
    let report = differences(&reference, (&exe, &found, &how), meshes);
    assert!(report.is_empty(), "{name}: not mikktspace.c's calls:\n{report}");
    assert!(found.iter().any(|line| line.result == "1"), "{name}: no run returned 1");
}

/// The generated meshes, through the static library, the shared library, and the shared library
/// through this repository's header with 2 worker threads: mikktspace.c's calls on every run.
#[test]
fn the_dropin_makes_mikktspace_c_calls_on_generated_meshes() {
    if !needs::MIKKTSPACE_C.found_or_skip() {
        return;
    }
    let meshes = generated_file();
    assert_same_calls("static", &dropin_static(), false, &meshes, None, RunAs::dropin());
    assert_same_calls("shared", &dropin_shared(), false, &meshes, None, RunAs::dropin());
    let two_threads = RunAs::dropin().with(&["--threads", "2"]);
    assert_same_calls("header-threads", &dropin_shared(), true, &meshes, None, two_threads);
}

/// Every corpus mesh, through the static and the shared library.
#[test]
fn the_dropin_makes_mikktspace_c_calls_on_every_corpus_mesh() {
    if !(needs::CORPUS.found_or_skip() && needs::MIKKTSPACE_C.found_or_skip()) {
        return;
    }
    let meshes = corpus_file();
    for (name, link) in [("corpus-static", dropin_static()), ("corpus-shared", dropin_shared())] {
        assert_same_calls(name, &link, false, &meshes, None, RunAs::dropin());
    }
}

/// The drop-in's driver on the generated meshes: its static build under AddressSanitizer +
/// UBSan, its shared build under valgrind (meshes up to `VALGRIND_MAX_VERTICES`).
#[test]
fn the_dropin_driver_passes_under_asan_ubsan_and_valgrind() {
    if !needs::MIKKTSPACE_C.found_or_skip() {
        return;
    }
    let meshes = generated_file();
    if needs::SANITIZERS.found_or_skip() {
        let sanitized = RunAs {
            sanitized: true,
            ..RunAs::dropin()
        };
        assert_same_calls("sanitized", &dropin_static(), false, &meshes, None, sanitized);
    }
    if needs::VALGRIND.found_or_skip() {
        let limit = Some(VALGRIND_MAX_VERTICES);
        let configs = VALGRIND_CONFIGS.map(|config| ["--config", config]).concat();
        let valgrind = RunAs {
            valgrind: true,
            ..RunAs::dropin()
        }
        .with(&configs);
        assert_same_calls("valgrind", &dropin_shared(), false, &meshes, limit, valgrind);
    }
}

/// The comparison itself: mikktspace.c built as a static archive and as a shared library, linked
/// as the drop-in is, gives the reference's lines; one bit flipped in the first call of one mesh's
/// runs is noticed on exactly those runs, and `--dump` names the call.
#[test]
fn the_comparison_passes_mikktspace_c_and_notices_one_bit() {
    if !(needs::MIKKTSPACE_C.found_or_skip() && needs::BINUTILS.found_or_skip()) {
        return;
    }
    let dir = c_build::work_dir(SUITE, "self-check");
    let archive = dir.join("libmikktspace_reference.a");
    let mut ar = Command::new("ar");
    ar.arg("rcs").arg(&archive).arg(mikktspace_object());
    run_ok(ar, "archiving mikktspace.o");
    let mut shared = compiler(false, &dir);
    shared.arg("-shared").arg(mikktspace_object()).arg("-lm");
    shared.arg("-o").arg(dir.join("libmikktspace_reference.so"));
    run_ok(shared, "linking mikktspace.o into a shared library");
    let meshes = generated_file();
    let as_library = Link::Shared(dir.clone(), "mikktspace_reference");
    assert_same_calls(
        "self-check-static",
        &Link::Static(archive),
        false,
        &meshes,
        None,
        RunAs::default(),
    );
    assert_same_calls("self-check-shared", &as_library, false, &meshes, None, RunAs::default());

    let reference = reference_lines(&meshes, None);
    let perturbed_mesh = "quads: one degenerate triangle, shared";
    let how = RunAs::default().with(&["--perturb", perturbed_mesh]);
    let perturbed = run_driver(&reference_driver(), &meshes, &how);
    let report = differences(&reference, (&reference_driver(), &perturbed, &how), &meshes);
    // Every run of that mesh with a set call, and nothing else.
    let expected = reference
        .iter()
        .filter(|line| line.mesh == perturbed_mesh && line.calls != "0")
        .count();
    assert_eq!(expected, 12, "the perturbed mesh's runs with set calls");
    let counted = format!("{expected} of {} runs differ\n", reference.len());
    assert!(report.starts_with(&counted), "{report}");
    let named = format!("first difference in {perturbed_mesh} / default both, line 0");
    assert!(report.contains(&named), "{report}");
}

/// The shared library exports the two functions of mikktspace.h and its own `tbasis_` ones, which
/// its header declares, and nothing else; both libraries carry their soname.
#[test]
fn the_shared_library_exports_mikktspace_h_functions_and_tbasis_ones() {
    if !needs::BINUTILS.found_or_skip() {
        return;
    }
    let lib = library_dir().join("libtbasis_mikktspace.so");
    let mikktspace_names = ["genTangSpace", "genTangSpaceDefault"];
    let header = Path::new(CRATE_DIR).join("include/tbasis_mikktspace.h");
    let exported = c_build::assert_exports_are_the_header_functions(&lib, &header, "tbasis_", &mikktspace_names);
    let others: Vec<&String> = exported
        .iter()
        .filter(|name| !name.starts_with("tbasis_") && !mikktspace_names.contains(&name.as_str()))
        .collect();
    assert!(others.is_empty(), "exported without a tbasis_ prefix: {others:?}");
    for name in mikktspace_names {
        assert!(exported.contains(name), "{name} is not exported");
    }
    let soname = common::artifacts::soname("tbasis_mikktspace");
    let link = library_dir().join(&soname);
    assert_eq!(
        std::fs::read_link(&link).unwrap_or_else(|e| panic!("{}: {e}", link.display())),
        Path::new("libtbasis_mikktspace.so")
    );
    let mut readelf = Command::new("readelf");
    readelf.arg("-d").arg(&lib);
    let dynamic = String::from_utf8_lossy(&run_ok(readelf, "readelf -d").stdout).into_owned();
    assert!(dynamic.contains(&format!("Library soname: [{soname}]")), "{dynamic}");
}

/// Prints every size and offset of the ABI, compiled against a header.
const ABI_PROBE: &str = r#"#include <stddef.h>
#include <stdio.h>
#include HEADER

int main(void)
{
    tbool (*generate_default)(const SMikkTSpaceContext *) = genTangSpaceDefault;
    tbool (*generate)(const SMikkTSpaceContext *, const float) = genTangSpace;
    printf("tbool %u\n", (unsigned)sizeof(tbool));
    printf("interface %u\n", (unsigned)sizeof(SMikkTSpaceInterface));
    printf("m_getNumFaces %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_getNumFaces));
    printf("m_getNumVerticesOfFace %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_getNumVerticesOfFace));
    printf("m_getPosition %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_getPosition));
    printf("m_getNormal %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_getNormal));
    printf("m_getTexCoord %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_getTexCoord));
    printf("m_setTSpaceBasic %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_setTSpaceBasic));
    printf("m_setTSpace %u\n", (unsigned)offsetof(SMikkTSpaceInterface, m_setTSpace));
    printf("context %u\n", (unsigned)sizeof(SMikkTSpaceContext));
    printf("m_pInterface %u\n", (unsigned)offsetof(SMikkTSpaceContext, m_pInterface));
    printf("m_pUserData %u\n", (unsigned)offsetof(SMikkTSpaceContext, m_pUserData));
    return generate_default(NULL) == 0 && generate(NULL, 180.0f) == 0 ? 0 : 1;
}
"#;

/// include/tbasis_mikktspace.h declares mikktspace.h's ABI: the same sizes and offsets, the same
/// function types, in C99 and C++11 with every warning an error, and links to the library.
#[test]
fn the_header_declares_mikktspace_h_abi() {
    if !(needs::MIKKTSPACE_C.found_or_skip() && needs::CXX.found_or_skip()) {
        return;
    }
    let dir = c_build::work_dir(SUITE, "header");
    let lib = library_dir();
    let mut layouts = Vec::new();
    for (name, cpp, standard, header, include) in [
        (
            "mikktspace.h",
            false,
            "-std=c99",
            "\"mikktspace.h\"",
            mikktspace_c_dir(),
        ),
        (
            "ours-c",
            false,
            "-std=c99",
            "\"tbasis_mikktspace.h\"",
            Path::new(CRATE_DIR).join("include"),
        ),
        (
            "ours-cpp",
            true,
            "-std=c++11",
            "\"tbasis_mikktspace.h\"",
            Path::new(CRATE_DIR).join("include"),
        ),
    ] {
        let source = dir.join(if cpp { "probe.cpp" } else { "probe.c" });
        std::fs::write(&source, ABI_PROBE.replace("HEADER", header)).expect("write the probe");
        let exe = dir.join(name);
        let mut command = compiler(cpp, &dir);
        command.arg(standard).args(["-Wall", "-Wextra", "-Werror", "-pedantic"]);
        command.arg("-I").arg(include).arg(&source);
        command.arg("-L").arg(&lib).arg("-ltbasis_mikktspace");
        command.arg(format!("-Wl,-rpath,{}", lib.display())).arg("-o").arg(&exe);
        run_ok(command, &format!("compiling the ABI probe with {name}"));
        let output = run_ok(Command::new(&exe), &format!("the ABI probe with {name}"));
        layouts.push(String::from_utf8_lossy(&output.stdout).into_owned());
    }
    assert!(layouts[0].contains("m_pUserData"), "{}", layouts[0]);
    assert_eq!(
        layouts[1], layouts[0],
        "tbasis_mikktspace.h's layout vs mikktspace.h's (C)"
    );
    assert_eq!(
        layouts[2], layouts[0],
        "tbasis_mikktspace.h's layout vs mikktspace.h's (C++)"
    );
}

/// Compiles `c_tests/mikktspace/SOURCE` with the counted checks (`c_tests/counted.c`) into
/// `dir/name` with `flags`, linked to the drop-in in `lib`: its archive when `sanitized` (then
/// sanitized), else its shared library.
fn build_program(source: &str, dir: &Path, name: &str, lib: &Path, flags: &[&str], sanitized: bool) -> PathBuf {
    let exe = dir.join(name);
    let mut command = compiler(false, dir);
    command
        .arg(c_tests(source))
        .arg(Path::new(CRATE_DIR).join("c_tests/counted.c"))
        .args(C_FLAGS)
        .arg("-pthread")
        .args(flags);
    command.arg("-I").arg(Path::new(CRATE_DIR).join("include"));
    if sanitized {
        command
            .args(SANITIZE_FLAGS)
            .arg(lib.join("libtbasis_mikktspace.a"))
            .args(STATIC_LIBS);
    } else {
        command.arg("-L").arg(lib).arg("-ltbasis_mikktspace");
        command.arg(format!("-Wl,-rpath,{}", lib.display()));
    }
    command.arg("-o").arg(&exe);
    run_ok(command, &format!("compiling c_tests/mikktspace/{source} ({name})"));
    exe
}

/// Runs a program of counted checks (`c_tests/counted.c`): it must end well, its last line
/// `N passed, 0 failed`.
fn assert_checks_pass(command: Command, what: &str) -> Output {
    let output = run(command, what);
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let summary = stdout.lines().last().unwrap_or_default();
    assert!(
        output.status.success() && summary.ends_with(" passed, 0 failed"),
        "{what}: {}, {summary}",
        output.status
    );
    output
}

/// `c_tests/mikktspace/contract.c`: what the header promises beyond mikktspace.c's results
/// (NULL callbacks and contexts, negative counts, which callbacks are called in what order, all
/// on the calling thread with several workers), against the shared library, plain and under
/// valgrind, and against the static one under the sanitizers.
#[test]
fn the_dropin_keeps_the_contract_of_its_header() {
    let dir = c_build::work_dir(SUITE, "contract");
    let check = assert_checks_pass;
    let plain = build_program("contract.c", &dir, "contract", &library_dir(), &[], false);
    check(Command::new(&plain), "the contract checks");
    if needs::SANITIZERS.found_or_skip() {
        let mut command = Command::new(build_program(
            "contract.c",
            &dir,
            "sanitized",
            &library_dir(),
            &[],
            true,
        ));
        c_build::sanitizer_environment(&mut command);
        c_build::assert_no_sanitizer_reports(&check(command, "the contract checks, sanitized"));
    }
    if needs::VALGRIND.found_or_skip() {
        check(c_build::valgrind(&plain), "the contract checks under valgrind");
    }
}

/// `c_tests/mikktspace/workers.c`: the worker threads each call starts, counted by the program's
/// own `pthread_create` and `pthread_join`, which the shared library's calls reach first: a call
/// keeps the count it read when it started, whatever is set during it, and two calls at once each
/// start the workers they start alone, at most as many at once as the count, with the set calls
/// of one thread.
#[test]
fn each_call_reads_the_thread_count_when_it_starts_and_has_its_own_workers() {
    let dir = c_build::work_dir(SUITE, "workers");
    let exe = build_program("workers.c", &dir, "workers", &library_dir(), &["-ldl"], false);
    // Its calls wait for each other: a call that failed would leave the other waiting, so the run
    // is cut off (`timeout`, status 124) rather than left hanging.
    let mut command = Command::new("timeout");
    command.arg("600").arg(&exe);
    assert_checks_pass(command, "the worker counts");
}

/// `c_tests/mikktspace/out_of_memory.c`: with one thread, each allocation a call makes, failed in
/// turn by the program's own allocator (which the shared library's calls reach first), makes the
/// call return 0 with no set callback called, and leaves no block allocated; past the last, the
/// call succeeds with the same set calls.
#[test]
#[cfg(target_env = "gnu")] // The program hands allocations on to glibc's own (`__libc_malloc`).
fn every_failed_allocation_makes_a_dropin_call_return_0_and_call_nothing() {
    let dir = c_build::work_dir(SUITE, "out_of_memory");
    let exe = build_program("out_of_memory.c", &dir, "out_of_memory", &library_dir(), &[], false);
    assert_checks_pass(Command::new(&exe), "the out-of-memory checks");
}

/// With the test-only feature `fault-injection` and `TBASIS_INJECT_PANIC` set, both entry points
/// panic inside their boundary: each returns 0 and calls no callback; without the variable the
/// same calls succeed.
#[test]
fn a_panic_inside_the_dropin_returns_0_and_calls_nothing() {
    let target = profile_dir().parent().unwrap().join("fault-injection");
    let mut cargo = Command::new(env!("CARGO"));
    cargo.args([
        "build",
        "--lib",
        "-p",
        "tbasis-mikktspace",
        "--features",
        "fault-injection",
    ]);
    cargo
        .arg("--manifest-path")
        .arg(Path::new(CRATE_DIR).join("Cargo.toml"));
    cargo.arg("--target-dir").arg(&target);
    run_ok(cargo, "building the drop-in with fault-injection");
    let dir = c_build::work_dir(SUITE, "faults");
    let exe = build_program(
        "contract.c",
        &dir,
        "faults",
        &target.join("debug"),
        &["-DCONTRACT_FAULTS"],
        false,
    );
    for (inject, expected) in [(true, "internal 2"), (false, "ok 2")] {
        // Cargo's LD_LIBRARY_PATH would load the ordinary build before the program's rpath does.
        let mut command = Command::new(&exe);
        command.env_remove("LD_LIBRARY_PATH").env("RUST_BACKTRACE", "0");
        if inject {
            command.env("TBASIS_INJECT_PANIC", "1");
        }
        let output = run_ok(command, "the fault calls");
        assert_eq!(String::from_utf8_lossy(&output.stdout).trim(), expected);
    }
}

/// The build commands `examples/mikktspace/app.c` states (and the README shows), in order: the
/// lines of its opening comment that start with `cc`, `./app` or `LD_LIBRARY_PATH=`.
fn sample_commands() -> Vec<String> {
    let source = std::fs::read_to_string(Path::new(CRATE_DIR).join("examples/mikktspace/app.c")).expect("app.c");
    let comment = &source[..source.find("*/").expect("an opening comment")];
    comment
        .lines()
        .map(|line| line.trim_start().trim_start_matches('*').trim())
        .filter(|line| {
            ["cc ", "./app", "LD_LIBRARY_PATH="]
                .iter()
                .any(|start| line.starts_with(start))
        })
        .map(str::to_string)
        .collect()
}

/// The sample program of the README, built as its comment says: with mikktspace.c, then relinked
/// to the drop-in's shared library and to its archive, from a folder holding app.c, mikktspace.c,
/// mikktspace.h and `tbasis/target/release` (standing for the tests' own build of the libraries).
/// Each build prints the same lines.
#[test]
fn the_sample_program_prints_the_same_relinked_to_the_dropin() {
    if !needs::MIKKTSPACE_C.found_or_skip() {
        return;
    }
    let dir = c_build::work_dir(SUITE, "sample");
    std::fs::copy(
        Path::new(CRATE_DIR).join("examples/mikktspace/app.c"),
        dir.join("app.c"),
    )
    .expect("copy app.c");
    for file in ["mikktspace.c", "mikktspace.h"] {
        std::fs::copy(mikktspace_c_dir().join(file), dir.join(file)).expect("copy mikktspace.c and .h");
    }
    std::fs::create_dir_all(dir.join("tbasis/target")).expect("create tbasis/target");
    std::os::unix::fs::symlink(library_dir(), dir.join("tbasis/target/release")).expect("link the libraries");

    let commands = sample_commands();
    assert_eq!(commands.len(), 6, "app.c's commands: {commands:?}");
    let mut outputs = Vec::new();
    for pair in commands.chunks(2) {
        let (build, start) = (&pair[0], &pair[1]);
        assert!(build.starts_with("cc ") && start.ends_with("./app"), "{build}; {start}");
        let _ = std::fs::remove_file(dir.join("app"));
        let mut shell = Command::new("sh");
        // cargo sets LD_LIBRARY_PATH for tests; the program must find the library as written.
        shell
            .arg("-ec")
            .arg(format!("{build}\n{start}"))
            .current_dir(&dir)
            .env_remove("LD_LIBRARY_PATH");
        let output = run(shell, build);
        outputs.push((
            build.clone(),
            output.status.success(),
            String::from_utf8_lossy(&output.stdout).into_owned(),
        ));
    }
    let (before, ok, expected) = &outputs[0];
    assert!(
        *ok && expected.ends_with("genTangSpaceDefault returned 1 after 7 tangents\n"),
        "{before}:\n{expected}"
    );
    for (build, _, printed) in &outputs[1..] {
        assert_eq!(printed, expected, "{build} prints other lines than {before}");
    }
}
