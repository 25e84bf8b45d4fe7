//! Installs the libraries with `scripts/install.sh` into fresh prefixes and consumes them the ways
//! a C or C++ project would: the installed layout and sonames, CMake's `find_package` (shared,
//! static, version check, moved prefix), pkg-config (shared and static), the C++ example, and the
//! mikktspace.c drop-in relinking `examples/mikktspace` through CMake and pkg-config.
//!
//! One test per set of tools, so that a missing tool makes only the tests that need it skip
//! (under CI, where tools must be installed, fail: `tbasis_test_support::needs`).
#![cfg(target_os = "linux")]

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::artifacts::{build_library, profile_dir, release, soname};
use common::tools::run_ok;
use tbasis_test_support::needs;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");
const MAJOR: &str = env!("CARGO_PKG_VERSION_MAJOR");
const MINOR: &str = env!("CARGO_PKG_VERSION_MINOR");
const PATCH: &str = env!("CARGO_PKG_VERSION_PATCH");
const WARNINGS: [&str; 4] = ["-Wall", "-Wextra", "-Werror", "-pedantic"];

/// The installed file of the shared library `lib{name}.so`.
fn real_name(name: &str) -> String {
    format!("lib{name}.so.{MAJOR}.{MINOR}.{PATCH}")
}

/// The line `examples/c/consumer.c` prints on success.
fn consumer_line() -> String {
    format!("consumer: tbasis {MAJOR}.{MINOR}.{PATCH}, 4 tangents ok")
}

/// A directory unique to this run, removed when the test passes and kept for inspection when it
/// fails.
struct Scratch(PathBuf);

impl Scratch {
    /// Named after the test, which runs beside the others in this process.
    fn new(test: &str) -> Scratch {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .expect("clock after 1970")
            .as_nanos();
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("install-{test}-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the scratch directory");
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("left {} for inspection", self.0.display());
        } else if let Err(e) = std::fs::remove_dir_all(&self.0) {
            eprintln!("could not remove {}: {e}", self.0.display());
        }
    }
}

fn stdout_of(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// Runs a built consumer with no LD_LIBRARY_PATH (cargo sets one for tests) unless `library_path`
/// names one, and requires `expected` as its whole output.
fn run_consumer(exe: &Path, library_path: Option<&Path>, expected: &str) {
    let mut command = Command::new(exe);
    command.env_remove("LD_LIBRARY_PATH");
    if let Some(dir) = library_path {
        command.env("LD_LIBRARY_PATH", dir);
    }
    let output = run_ok(command, &format!("running {}", exe.display()));
    assert_eq!(stdout_of(&output).trim_end(), expected, "output of {}", exe.display());
}

/// `readelf -d` of `file`: its dynamic section.
fn dynamic_section(file: &Path) -> String {
    let mut command = Command::new("readelf");
    command.arg("-d").arg(file);
    stdout_of(&run_ok(command, "readelf -d"))
}

/// The names in `[...]` of the dynamic entries of kind `tag` (NEEDED, SONAME, RUNPATH, RPATH).
fn dynamic_entries(file: &Path, tag: &str) -> Vec<String> {
    let marker = format!("({tag})");
    dynamic_section(file)
        .lines()
        .filter(|line| line.contains(&marker))
        .filter_map(|line| Some(line.split_once('[')?.1.split_once(']')?.0.to_string()))
        .collect()
}

/// Requires that `exe` loads the shared library `lib{name}.so` by its soname, or, `statically`, no
/// library of this repository at all.
fn check_needed(exe: &Path, name: &str, statically: bool) {
    let needed = dynamic_entries(exe, "NEEDED");
    if statically {
        assert!(
            !needed.iter().any(|name| name.starts_with("libtbasis")),
            "{} should contain the static archive but loads {needed:?}",
            exe.display()
        );
    } else {
        assert!(
            needed.contains(&soname(name)),
            "{} should load {} but loads {needed:?}",
            exe.display(),
            soname(name)
        );
    }
}

/// Installs with the profile of this test, so that the nested cargo build reuses what `cargo test`
/// and the C harness already built instead of building the library a second time.
fn install(prefix: &Path) {
    install_staged(prefix, None);
}

/// [`install`], with `DESTDIR` set to `stage` when given.
fn install_staged(prefix: &Path, stage: Option<&Path>) {
    let profile = if release() { "release" } else { "debug" };
    let target_dir = profile_dir().parent().expect("target/<profile>").to_path_buf();
    let mut command = Command::new("bash");
    command.arg(Path::new(CRATE_DIR).join("scripts/install.sh"));
    command.arg(prefix).args(["--profile", profile]);
    command.env("CARGO", env!("CARGO")).env("CARGO_TARGET_DIR", &target_dir);
    command.env_remove("DESTDIR");
    if let Some(stage) = stage {
        command.env("DESTDIR", stage);
    }
    let output = run_ok(command, "scripts/install.sh");
    for name in LIBRARIES {
        let expected = format!(
            "installed {name} {} ({profile}, soname {})",
            env!("CARGO_PKG_VERSION"),
            soname(name)
        );
        assert!(
            stdout_of(&output).contains(&expected),
            "scripts/install.sh did not report `{expected}`:\n{}",
            stdout_of(&output)
        );
    }
    // Where the files are not staged, the script ends by saying how programs find the library.
    let hint = format!(
        "elsewhere link with -Wl,-rpath,{}/lib or set LD_LIBRARY_PATH",
        prefix.display()
    );
    assert_eq!(
        stdout_of(&output).contains(&hint),
        stage.is_none(),
        "scripts/install.sh, DESTDIR {stage:?}: the loader's hint `{hint}`:\n{}",
        stdout_of(&output)
    );
}

/// The C libraries: `lib{name}.so`, `lib{name}.a`, `include/{name}.h`, `{name}.pc`.
const LIBRARIES: [&str; 2] = ["tbasis", "tbasis_mikktspace"];

/// (a) The files, the symlink chains and the sonames of both libraries.
fn check_layout(prefix: &Path) {
    let lib = prefix.join("lib");
    for name in LIBRARIES {
        check_library_layout(prefix, name);
    }
    for file in ["tbasisConfig.cmake", "tbasisConfigVersion.cmake"] {
        let text = std::fs::read_to_string(lib.join("cmake/tbasis").join(file)).expect(file);
        assert!(!text.contains(&*prefix.to_string_lossy()), "{file} names the prefix");
        assert!(!text.contains('@'), "{file} has a template key left:\n{text}");
    }
}

/// The installed files of `lib{name}`: the shared library, its links, its soname, the archive,
/// the header and the `.pc` file.
fn check_library_layout(prefix: &Path, name: &str) {
    let lib = prefix.join("lib");
    let real = lib.join(real_name(name));
    let meta = std::fs::symlink_metadata(&real).unwrap_or_else(|e| panic!("{}: {e}", real.display()));
    assert!(meta.file_type().is_file(), "{} must be a regular file", real.display());
    // Relative links, so that the prefix can move.
    for (link, target) in [(soname(name), real_name(name)), (format!("lib{name}.so"), soname(name))] {
        let path = lib.join(&link);
        let found = std::fs::read_link(&path).unwrap_or_else(|e| panic!("{} is not a symlink: {e}", path.display()));
        assert_eq!(found, Path::new(&target), "{} points elsewhere", path.display());
    }
    let archive = std::fs::read(lib.join(format!("lib{name}.a"))).expect("the archive");
    assert!(
        archive.starts_with(b"!<arch>\n"),
        "lib/lib{name}.a is not an ar archive"
    );
    let header = std::fs::read(prefix.join(format!("include/{name}.h"))).expect("the installed header");
    let committed =
        std::fs::read(Path::new(CRATE_DIR).join(format!("include/{name}.h"))).expect("the committed header");
    assert!(
        header == committed,
        "the installed header differs from include/{name}.h"
    );

    let pc = std::fs::read_to_string(lib.join(format!("pkgconfig/{name}.pc"))).expect("the .pc file");
    for line in [
        format!("prefix={}", prefix.display()),
        format!("Name: {name}"),
        format!("Version: {}", env!("CARGO_PKG_VERSION")),
        format!("Libs: -L${{libdir}} -l{name}"),
        "Cflags: -I${includedir}".to_string(),
    ] {
        assert!(pc.lines().any(|l| l == line), "{name}.pc lacks `{line}`:\n{pc}");
    }
    assert!(!pc.contains('@'), "{name}.pc has a template key left:\n{pc}");

    assert_eq!(
        dynamic_entries(&real, "SONAME"),
        [soname(name)],
        "soname of {}",
        real.display()
    );
}

/// Configures and builds `examples/c` against `prefix`, with `-DTBASIS_VERSION_REQUIRED=<version>`
/// when given. A failed configure returns its output; a failed build panics.
fn cmake_build(prefix: &Path, build: &Path, version: Option<&str>) -> Result<(), String> {
    let mut configure = Command::new("cmake");
    configure.arg("-S").arg(Path::new(CRATE_DIR).join("examples/c"));
    configure.arg("-B").arg(build);
    configure.arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()));
    configure.arg(format!("-DCMAKE_C_FLAGS={}", WARNINGS.join(" ")));
    if let Some(version) = version {
        configure.arg(format!("-DTBASIS_VERSION_REQUIRED={version}"));
    }
    let output = configure.output().expect("run cmake");
    if !output.status.success() {
        return Err(format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let cache = std::fs::read_to_string(build.join("CMakeCache.txt")).expect("CMakeCache.txt");
    let config_dir = format!("tbasis_DIR:PATH={}", prefix.join("lib/cmake/tbasis").display());
    assert!(
        cache.lines().any(|line| line == config_dir),
        "CMake did not use {config_dir}"
    );
    let mut compile = Command::new("cmake");
    compile.arg("--build").arg(build);
    run_ok(compile, "cmake --build examples/c");
    Ok(())
}

/// (b) `find_package(tbasis)` from examples/c: both targets, and the version check.
fn check_cmake(prefix: &Path, work: &Path) {
    let build = work.join("cmake");
    cmake_build(prefix, &build, Some(&format!("{MAJOR}.{MINOR}"))).unwrap_or_else(|log| panic!("cmake:\n{log}"));
    // No LD_LIBRARY_PATH: the shared library is found through the RUNPATH CMake gives executables
    // linked to imported targets in the build tree.
    run_consumer(&build.join("consumer"), None, &consumer_line());
    check_needed(&build.join("consumer"), "tbasis", false);
    run_consumer(&build.join("consumer_static"), None, &consumer_line());
    check_needed(&build.join("consumer_static"), "tbasis", true);

    // A version of another ABI series, and a newer one of this series, must be refused.
    let next_series = if MAJOR == "0" {
        format!("0.{}", MINOR.parse::<u64>().expect("minor") + 1)
    } else {
        format!("{}", MAJOR.parse::<u64>().expect("major") + 1)
    };
    let newer_patch = format!("{MAJOR}.{MINOR}.{}", PATCH.parse::<u64>().expect("patch") + 1);
    for version in [next_series, newer_patch] {
        match cmake_build(prefix, &work.join(format!("cmake-{version}")), Some(&version)) {
            Ok(()) => panic!(
                "find_package(tbasis {version}) accepted version {}",
                env!("CARGO_PKG_VERSION")
            ),
            // CMake wraps its message; compare with single spaces.
            Err(log) => assert!(
                log.split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" ")
                    .contains(&format!("compatible with requested version \"{version}\"")),
                "find_package(tbasis {version}) failed for another reason:\n{log}"
            ),
        }
    }
}

/// (f) The CMake package still works after the prefix moves: its paths are relative to itself.
fn check_cmake_moved(prefix: &Path, work: &Path) {
    let moved = work.join("moved");
    std::fs::rename(prefix, &moved).expect("move the prefix");
    let build = work.join("cmake-moved");
    let result = cmake_build(&moved, &build, None);
    std::fs::rename(&moved, prefix).expect("move the prefix back");
    result.unwrap_or_else(|log| panic!("cmake with the moved prefix:\n{log}"));
    let runpath = [
        dynamic_entries(&build.join("consumer"), "RUNPATH"),
        dynamic_entries(&build.join("consumer"), "RPATH"),
    ]
    .concat();
    let moved_lib = moved.join("lib").display().to_string();
    assert!(
        runpath.iter().any(|p| p.split(':').any(|dir| dir == moved_lib)),
        "the consumer built against the moved prefix has runpath {runpath:?}"
    );
}

/// `pkg-config ARGS tbasis` against the installed .pc file.
fn pkg_config(prefix: &Path, args: &[&str]) -> Vec<String> {
    pkg_config_of("tbasis", prefix, args)
}

/// `pkg-config ARGS PACKAGE` against the installed .pc files.
fn pkg_config_of(package: &str, prefix: &Path, args: &[&str]) -> Vec<String> {
    let mut command = Command::new("pkg-config");
    command.env("PKG_CONFIG_PATH", prefix.join("lib/pkgconfig"));
    command.args(args).arg(package);
    let output = run_ok(command, &format!("pkg-config {args:?} {package}"));
    stdout_of(&output).split_whitespace().map(str::to_string).collect()
}

fn compile_consumer(flags: &[String], exe: &Path) {
    let mut command = Command::new("cc");
    command.arg("-std=c99").args(WARNINGS);
    command.arg(Path::new(CRATE_DIR).join("examples/c/consumer.c"));
    command.args(flags).arg("-o").arg(exe);
    run_ok(command, "compiling examples/c/consumer.c");
}

/// (c) and (d): `cc consumer.c $(pkg-config --cflags --libs [--static] tbasis)`.
fn check_pkg_config(prefix: &Path, work: &Path) {
    assert_eq!(pkg_config(prefix, &["--modversion"]), [env!("CARGO_PKG_VERSION")]);

    let exe = work.join("consumer-pkg-config");
    compile_consumer(&pkg_config(prefix, &["--cflags", "--libs"]), &exe);
    // Nothing records the prefix in the executable, so the loader finds the library through
    // LD_LIBRARY_PATH, as it would for any library in a non-system prefix.
    run_consumer(&exe, Some(&prefix.join("lib")), &consumer_line());
    check_needed(&exe, "tbasis", false);

    // The same flags from a copy of the prefix without the shared library: `-ltbasis` can then
    // only mean libtbasis.a, and the link needs Libs.private.
    let static_prefix = work.join("static-prefix");
    for file in ["include/tbasis.h", "lib/libtbasis.a", "lib/pkgconfig/tbasis.pc"] {
        let to = static_prefix.join(file);
        std::fs::create_dir_all(to.parent().expect("a directory")).expect("create the static prefix");
        std::fs::copy(prefix.join(file), &to).unwrap_or_else(|e| panic!("copy {file}: {e}"));
    }
    let define = format!("--define-variable=prefix={}", static_prefix.display());
    let flags = pkg_config(&static_prefix, &[&define, "--static", "--cflags", "--libs"]);
    assert!(flags.iter().any(|f| f == "-lpthread"), "no Libs.private in {flags:?}");
    let exe = work.join("consumer-pkg-config-static");
    compile_consumer(&flags, &exe);
    run_consumer(&exe, None, &consumer_line());
    check_needed(&exe, "tbasis", true);
}

/// (e) The C++ example against the installed header and shared library.
fn check_cpp(prefix: &Path, work: &Path) {
    let lib = prefix.join("lib");
    for standard in ["-std=c++11", "-std=c++14", "-std=c++17", "-std=c++20", "-std=c++23"] {
        let exe = work.join(format!("interleaved{standard}"));
        let mut command = Command::new("c++");
        command.arg(standard).args(WARNINGS);
        command.arg("-I").arg(prefix.join("include"));
        command.arg(Path::new(CRATE_DIR).join("examples/cpp/interleaved.cpp"));
        command.arg("-L").arg(&lib).arg("-ltbasis");
        command.arg(format!("-Wl,-rpath,{}", lib.display())).arg("-o").arg(&exe);
        run_ok(
            command,
            &format!("compiling examples/cpp/interleaved.cpp with {standard}"),
        );
        run_consumer(&exe, None, "interleaved: 24 vertices, 24 tangents written in place, ok");
    }
}

/// Configures and builds `examples/mikktspace` against `prefix`, its `mikktspace.h` (and, with
/// `with_mikktspace_c`, `mikktspace.c` compiled in) from mikktspace-sys.
fn cmake_build_sample(prefix: &Path, build: &Path, with_mikktspace_c: bool) {
    let mut configure = Command::new("cmake");
    configure
        .arg("-S")
        .arg(Path::new(CRATE_DIR).join("examples/mikktspace"));
    configure.arg("-B").arg(build);
    configure.arg(format!("-DCMAKE_PREFIX_PATH={}", prefix.display()));
    let mikktspace_dir = needs::mikktspace_c_dir().expect("needs::MIKKTSPACE_C was checked");
    configure.arg(format!("-DMIKKTSPACE_DIR={}", mikktspace_dir.display()));
    if with_mikktspace_c {
        // mikktspace.c's own warnings are not ours.
        configure.arg("-DUSE_MIKKTSPACE_C=ON");
    } else {
        configure.arg(format!("-DCMAKE_C_FLAGS={}", WARNINGS.join(" ")));
    }
    run_ok(configure, "cmake -S examples/mikktspace");
    let mut compile = Command::new("cmake");
    compile.arg("--build").arg(build);
    run_ok(compile, "cmake --build examples/mikktspace");
}

/// (g) The drop-in: `examples/mikktspace` built with mikktspace.c compiled in, then relinked
/// through `tbasis::mikktspace` and `tbasis::mikktspace_static` and through
/// `pkg-config tbasis_mikktspace`: each prints what the build with mikktspace.c printed.
fn check_dropin(prefix: &Path, work: &Path) {
    let before = work.join("sample-before");
    cmake_build_sample(prefix, &before, true);
    let output = run_ok(
        Command::new(before.join("app")),
        "examples/mikktspace with mikktspace.c",
    );
    let expected = stdout_of(&output).trim_end().to_string();
    assert!(expected.ends_with("returned 1 after 7 tangents"), "{expected}");

    let after = work.join("sample-after");
    cmake_build_sample(prefix, &after, false);
    run_consumer(&after.join("app"), None, &expected);
    check_needed(&after.join("app"), "tbasis_mikktspace", false);
    run_consumer(&after.join("app_static"), None, &expected);
    check_needed(&after.join("app_static"), "tbasis_mikktspace", true);

    let exe = work.join("sample-pkg-config");
    let mut command = Command::new("cc");
    command.arg("-std=c99").args(WARNINGS);
    command.arg(Path::new(CRATE_DIR).join("examples/mikktspace/app.c"));
    command.arg("-I").arg(needs::mikktspace_c_dir().expect("checked"));
    command.args(pkg_config_of("tbasis_mikktspace", prefix, &["--cflags", "--libs"]));
    command.arg("-o").arg(&exe);
    run_ok(command, "compiling examples/mikktspace/app.c with pkg-config");
    run_consumer(&exe, Some(&prefix.join("lib")), &expected);
    check_needed(&exe, "tbasis_mikktspace", false);
}

/// A scratch directory named after `test` with the library installed in its `prefix/`.
fn installed(test: &str) -> (Scratch, PathBuf) {
    let scratch = Scratch::new(test);
    let prefix = scratch.0.join("prefix");
    install(&prefix);
    (scratch, prefix)
}

#[test]
fn installed_layout_and_soname() {
    if !needs::BINUTILS.found_or_skip() {
        return;
    }
    let (_scratch, prefix) = installed("layout");
    check_layout(&prefix);
}

/// `DESTDIR` stages the files for packaging: everything goes under it, and the files name the
/// prefix alone.
#[test]
fn destdir_stages_the_files() {
    let scratch = Scratch::new("destdir");
    let (stage, prefix) = (scratch.0.join("stage"), scratch.0.join("prefix"));
    install_staged(&prefix, Some(&stage));
    assert!(!prefix.exists(), "{} was written", prefix.display());
    let staged = stage.join(prefix.strip_prefix("/").expect("an absolute prefix"));
    for name in LIBRARIES {
        let lib = staged.join("lib");
        for file in [real_name(name), format!("lib{name}.a")] {
            assert!(lib.join(&file).is_file(), "{file} is not staged");
        }
        assert!(staged.join(format!("include/{name}.h")).is_file());
        let pc = std::fs::read_to_string(lib.join(format!("pkgconfig/{name}.pc"))).expect("the .pc file");
        let line = format!("prefix={}", prefix.display());
        assert!(pc.lines().any(|l| l == line), "{name}.pc lacks `{line}`:\n{pc}");
    }
    assert!(staged.join("lib/cmake/tbasis/tbasisConfig.cmake").is_file());
}

#[test]
fn installed_library_is_consumable_through_cmake() {
    if !(needs::CMAKE.found_or_skip() && needs::BINUTILS.found_or_skip()) {
        return;
    }
    let (scratch, prefix) = installed("cmake");
    check_cmake(&prefix, &scratch.0);
    check_cmake_moved(&prefix, &scratch.0);
}

#[test]
fn installed_library_is_consumable_through_pkg_config() {
    if !(needs::PKG_CONFIG.found_or_skip() && needs::BINUTILS.found_or_skip()) {
        return;
    }
    let (scratch, prefix) = installed("pkg-config");
    check_pkg_config(&prefix, &scratch.0);
}

#[test]
fn installed_dropin_relinks_a_mikktspace_program_through_cmake_and_pkg_config() {
    if !(needs::CMAKE.found_or_skip()
        && needs::PKG_CONFIG.found_or_skip()
        && needs::BINUTILS.found_or_skip()
        && needs::MIKKTSPACE_C.found_or_skip())
    {
        return;
    }
    let (scratch, prefix) = installed("dropin");
    check_dropin(&prefix, &scratch.0);
}

#[test]
fn installed_library_is_consumable_from_cpp() {
    if !needs::CXX.found_or_skip() {
        return;
    }
    let (scratch, prefix) = installed("cpp");
    check_cpp(&prefix, &scratch.0);
}

/// README "Size": the shared library `cargo build --release` makes stays under 1 MB
/// (docs/library-size.md: what each profile option saves).
#[test]
fn release_shared_library_is_under_one_megabyte() {
    const LIMIT: u64 = 1_000_000;
    let library = build_library(true).join("libtbasis.so");
    let bytes = std::fs::metadata(&library)
        .unwrap_or_else(|e| panic!("{}: {e}", library.display()))
        .len();
    assert!(bytes < LIMIT, "{}: {bytes} bytes, over {LIMIT}", library.display());
}
