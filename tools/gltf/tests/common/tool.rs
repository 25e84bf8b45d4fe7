//! Running `tbasis-gltf` and making folders for its output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary under test.
pub fn command() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tbasis-gltf"))
}

/// Runs the tool with `args`; prints what it printed (shown when the test fails).
pub fn run<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let output = command().args(args).output().expect("tbasis-gltf starts");
    print!("{}", String::from_utf8_lossy(&output.stdout));
    eprint!("{}", String::from_utf8_lossy(&output.stderr));
    output
}

/// A new, empty folder for one test.
pub fn fresh_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("tbasis-gltf-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the test folder");
    dir
}

/// Every file name in `dir`, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("read the folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The corners the summary line of `input` says were repaired (0 when it names none).
pub fn repaired_corners(stdout: &str, input: &Path) -> usize {
    let prefix = format!("{} -> ", input.display());
    let line = stdout
        .lines()
        .find(|line| line.starts_with(&prefix))
        .unwrap_or_else(|| panic!("no summary line for {}", input.display()));
    line.split(", ")
        .find_map(|part| {
            part.strip_suffix(" corners repaired")
                .or(part.strip_suffix(" corner repaired"))
        })
        .map_or(0, |n| n.parse().expect("a count"))
}

/// The primitives `(mesh, primitive)` the summary of `input` lists as left as they were: the
/// lines `  mesh M ("name") primitive P: why` after its summary line.
pub fn left_primitives(stdout: &str, input: &Path) -> Vec<(usize, usize)> {
    let prefix = format!("{} -> ", input.display());
    let number = |text: &str| -> usize {
        let digits: String = text.chars().take_while(char::is_ascii_digit).collect();
        digits.parse().expect("a number")
    };
    stdout
        .lines()
        .skip_while(|line| !line.starts_with(&prefix))
        .skip(1)
        .map_while(|line| line.strip_prefix("  mesh "))
        .map(|line| {
            let (head, _why) = line.split_once(": ").expect("mesh M primitive P: why");
            let primitive = &head[head.rfind(" primitive ").expect("primitive P") + " primitive ".len()..];
            (number(line), number(primitive))
        })
        .collect()
}
