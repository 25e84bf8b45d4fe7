//! The lines the README gives Rust users to depend on the crate, as a path and as a git
//! dependency: a new crate with each line builds against this repository. The git dependency
//! reads the repository's last commit, as it would from a clone's URL.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::tools::run_ok;
use tbasis_test_support::needs;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");

// The README's lines ("Install"), PATH standing for the clone's folder and URL for its address.
const PATH_DEPENDENCY: &str = r#"
[dependencies]
tbasis = { path = "PATH/crates/tbasis" }
"#;
const GIT_DEPENDENCY: &str = r#"
[dependencies]
tbasis = { git = "URL" }
"#;

/// A program that calls the crate, so that building it proves the dependency is the library.
const MAIN: &str = "fn main() {\n    let _ = tbasis::Options::default();\n    println!(\"{}\", tbasis::VERSION);\n}\n";

/// Writes a new crate named `name` with `dependencies` under the target dir and runs `cargo
/// check` on it; the crates share one target dir.
fn check_crate_with(name: &str, dependencies: &str) {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rust-dependency");
    let dir = root.join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src")).expect("create the crate");
    let manifest =
        format!("[package]\nname = \"{name}\"\nversion = \"0.0.0\"\nedition = \"2021\"\n{dependencies}\n[workspace]\n");
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    std::fs::write(dir.join("src/main.rs"), MAIN).unwrap();
    let mut check = Command::new(env!("CARGO"));
    check
        .arg("check")
        .current_dir(&dir)
        .env("CARGO_TARGET_DIR", root.join("target"));
    run_ok(check, &format!("cargo check of a crate with {}", dependencies.trim()));
}

#[test]
fn the_path_dependency_line_builds() {
    let repo = Path::new(CRATE_DIR).to_str().expect("a UTF-8 path");
    check_crate_with("path-user", &PATH_DEPENDENCY.replace("PATH", repo));
}

#[test]
fn the_git_dependency_line_builds() {
    if !needs::GIT.found_or_skip() {
        return;
    }
    // A bare copy of the repository stands for the address a user clones from.
    let bare: PathBuf = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rust-dependency/tbasis.git");
    let _ = std::fs::remove_dir_all(&bare);
    let mut clone = Command::new("git");
    clone
        .args(["clone", "--quiet", "--bare", "--no-local"])
        .arg(CRATE_DIR)
        .arg(&bare);
    run_ok(clone, "git clone --bare of the repository");
    let url = format!("file://{}", bare.display());
    check_crate_with("git-user", &GIT_DEPENDENCY.replace("URL", &url));
}
