//! Compiling and checking C programs against the libraries: the compiler, the flags and the
//! sanitizer and valgrind runs of the C harness (`tests/c_harness.rs`) and of the drop-in's driver
//! (`tests/mikktspace_dropin.rs`), and what a shared library exports.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The warnings every C file of the tests compiles without; no fused multiply-add, so that the
/// arithmetic is the source's.
pub const C_FLAGS: [&str; 5] = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-ffp-contract=off"];

/// AddressSanitizer and UndefinedBehaviorSanitizer, stopping at the first report.
pub const SANITIZE_FLAGS: [&str; 4] = [
    "-fsanitize=address,undefined",
    "-fno-sanitize-recover=all",
    "-g",
    "-fno-omit-frame-pointer",
];

/// What a static Rust library needs from the system when linked into a C program.
pub const STATIC_LIBS: [&str; 3] = ["-lpthread", "-ldl", "-lm"];

/// An empty directory `suite/test` under the target dir for one test's build products.
pub fn work_dir(suite: &str, test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(suite).join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the build directory");
    dir
}

/// Integration tests get no `TARGET` variable; the C tests only run on Linux, so build the triple.
fn target_triple() -> String {
    let env = if cfg!(target_env = "musl") { "musl" } else { "gnu" };
    format!("{}-unknown-linux-{env}", std::env::consts::ARCH)
}

/// The C (or C++) compiler `cc` chooses for this target, at -O2.
pub fn compiler(cpp: bool, out_dir: &Path) -> Command {
    let triple = target_triple();
    cc::Build::new()
        .cpp(cpp)
        .target(&triple)
        .host(&triple)
        .opt_level(2)
        .cargo_metadata(false)
        .out_dir(out_dir)
        .get_compiler()
        .to_command()
}

/// A sanitized program's environment: a refused allocation returns NULL instead of aborting, leaks
/// are reported, and UBSan prints a stack.
pub fn sanitizer_environment(command: &mut Command) {
    command.env("ASAN_OPTIONS", "allocator_may_return_null=1:detect_leaks=1");
    command.env("UBSAN_OPTIONS", "print_stacktrace=1:halt_on_error=1");
}

/// Panics with the sanitizer reports in a run's stderr, if any (not the warning a refused
/// allocation prints).
pub fn assert_no_sanitizer_reports(output: &Output) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    let reports: Vec<&str> = stderr
        .lines()
        .filter(|line| {
            line.contains("runtime error:")
                || line.contains("SUMMARY: ")
                || line.contains("ERROR: ") && line.contains("Sanitizer")
        })
        .collect();
    assert!(reports.is_empty(), "sanitizer reports:\n{}", reports.join("\n"));
}

/// `valgrind` running `exe`: memcheck, failing on any error and on definite leaks.
pub fn valgrind(exe: &Path) -> Command {
    let mut command = Command::new("valgrind");
    command.args([
        "--error-exitcode=99",
        "--leak-check=full",
        "--errors-for-leak-kinds=definite",
    ]);
    command.arg(exe);
    command
}

/// The dynamic symbols `library` defines (`nm -D --defined-only`), without version suffixes.
pub fn exported_symbols(library: &Path) -> BTreeSet<String> {
    let mut nm = Command::new("nm");
    nm.args(["-D", "--defined-only"]).arg(library);
    let listing = super::tools::run_ok(nm, &format!("nm -D {}", library.display())).stdout;
    let listing = String::from_utf8_lossy(&listing);
    // The name ends each line; a versioned symbol's is `name@VERSION` or `name@@VERSION`.
    let names = listing.lines().filter_map(|line| line.split_whitespace().last());
    names
        .map(|name| name.split('@').next().unwrap_or(name).to_string())
        .collect()
}

/// Requires that the shared library exports exactly the functions its header declares (those
/// starting with `prefix`, and `names`), and returns them.
pub fn assert_exports_are_the_header_functions(
    library: &Path,
    header: &Path,
    prefix: &str,
    names: &[&str],
) -> BTreeSet<String> {
    let declared = header_functions(header, prefix, names);
    assert!(!declared.is_empty(), "no function found in {}", header.display());
    let exported = exported_symbols(library);
    assert_eq!(
        exported,
        declared,
        "dynamic symbols of {} vs the functions of {}",
        library.display(),
        header.display()
    );
    exported
}

/// The functions a header declares: the identifiers directly followed by `(` outside comments
/// that start with `prefix` or are one of `names`.
pub fn header_functions(header: &Path, prefix: &str, names: &[&str]) -> BTreeSet<String> {
    let text = std::fs::read_to_string(header).unwrap_or_else(|e| panic!("{}: {e}", header.display()));
    let code = without_comments(&text);
    let is_word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut found = BTreeSet::new();
    for (start, _) in code.match_indices(|c: char| c.is_ascii_alphabetic() || c == '_') {
        if code[..start].ends_with(is_word) {
            continue;
        }
        let end = code[start..]
            .find(|c: char| !is_word(c))
            .map_or(code.len(), |n| start + n);
        let word = &code[start..end];
        if code[end..].starts_with('(') && (word.starts_with(prefix) || names.contains(&word)) {
            found.insert(word.to_string());
        }
    }
    found
}

/// C source without its `/* */` and `//` comments.
fn without_comments(text: &str) -> String {
    let mut code = String::new();
    let mut rest = text;
    loop {
        match (rest.find("/*"), rest.find("//")) {
            (Some(block), line) if line.is_none_or(|line| block < line) => {
                code.push_str(&rest[..block]);
                code.push(' ');
                rest = rest[block..].find("*/").map_or("", |end| &rest[block + end + 2..]);
            }
            (_, Some(line)) => {
                code.push_str(&rest[..line]);
                rest = rest[line..].find('\n').map_or("", |end| &rest[line + end..]);
            }
            (Some(_), None) => unreachable!("the first arm takes a block comment without a line comment"),
            (None, None) => {
                code.push_str(rest);
                return code;
            }
        }
    }
}
