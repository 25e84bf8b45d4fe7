//! What a Rust user gets from `tbasis = "..."`: a plain library whose whole dependency tree has no
//! build script and no proc-macro (so it builds about as fast as glam alone, docs/build-time.md),
//! and `unsafe` only in the strided views and the SIMD dispatch.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// The packages a new crate depending on this one (`crates/tbasis`) by path builds (normal
/// dependencies, default features), from `cargo metadata` run in a scratch crate under the target
/// directory.
fn dependency_tree() -> Vec<Value> {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dependency-tree-check");
    std::fs::create_dir_all(scratch.join("src")).unwrap();
    let manifest = format!(
        "[package]\nname = \"user\"\nversion = \"0.0.0\"\nedition = \"2021\"\n\n[dependencies]\ntbasis = {{ path = {:?} }}\n\n[workspace]\n",
        crate_dir
    );
    std::fs::write(scratch.join("Cargo.toml"), manifest).unwrap();
    std::fs::write(scratch.join("src/main.rs"), "fn main() {}\n").unwrap();
    let output = Command::new(env!("CARGO"))
        .args(["metadata", "--format-version", "1", "--offline"])
        .current_dir(&scratch)
        .output()
        .unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let metadata: Value = serde_json::from_slice(&output.stdout).unwrap();

    // Walk the resolve graph from the scratch crate along normal dependencies only.
    let nodes = metadata["resolve"]["nodes"].as_array().unwrap();
    let node = |id: &str| nodes.iter().find(|n| n["id"] == id).unwrap();
    let root_id = metadata["resolve"]["root"].as_str().unwrap().to_string();
    let mut seen = vec![root_id.clone()];
    let mut queue = vec![root_id];
    while let Some(id) = queue.pop() {
        for dep in node(&id)["deps"].as_array().unwrap() {
            let normal = dep["dep_kinds"].as_array().unwrap().iter().any(|k| k["kind"].is_null());
            let dep_id = dep["pkg"].as_str().unwrap().to_string();
            if normal && !seen.contains(&dep_id) {
                seen.push(dep_id.clone());
                queue.push(dep_id);
            }
        }
    }
    let packages = metadata["packages"].as_array().unwrap();
    packages
        .iter()
        .filter(|p| seen.iter().any(|id| p["id"] == id.as_str()) && p["name"] != "user")
        .cloned()
        .collect()
}

#[test]
fn the_rust_crate_has_no_build_script_or_proc_macro_anywhere_in_its_tree() {
    let tree = dependency_tree();
    let mut names: Vec<&str> = tree.iter().map(|p| p["name"].as_str().unwrap()).collect();
    names.sort_unstable();
    // glam is the crate's only dependency (docs/build-time.md), and brings none of its own.
    assert_eq!(names, ["glam", "tbasis"]);
    for package in &tree {
        for target in package["targets"].as_array().unwrap() {
            let kinds: Vec<&str> = target["kind"]
                .as_array()
                .unwrap()
                .iter()
                .map(|k| k.as_str().unwrap())
                .collect();
            assert!(
                !kinds.contains(&"custom-build") && !kinds.contains(&"proc-macro"),
                "{} has a {kinds:?} target",
                package["name"]
            );
        }
    }
    let tbasis = tree.iter().find(|p| p["name"] == "tbasis").unwrap();
    let lib = tbasis["targets"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["name"] == "tbasis")
        .unwrap();
    assert_eq!(lib["crate_types"], serde_json::json!(["lib"]), "a plain rlib");
    let glam = tbasis["dependencies"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["name"] == "glam")
        .unwrap();
    assert!(
        glam["req"].as_str().unwrap().starts_with('^'),
        "a caret requirement on glam: {}",
        glam["req"]
    );
}

#[test]
fn unsafe_code_is_confined_to_the_views_and_the_simd_dispatch() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    let mut dirs = vec![src.clone()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    assert!(files.len() > 20, "found {} files", files.len());
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let relative = file.strip_prefix(&src).unwrap();
        let allowed = relative.starts_with("kernel/views") || relative == Path::new("kernel/simd.rs");
        // lib.rs denies it for the crate; the kernel allows it for the views and the SIMD dispatch
        // alone.
        if relative == Path::new("lib.rs") {
            assert!(text.contains("#![deny(unsafe_code)]"));
            assert_eq!(text.matches("unsafe_code").count(), 1, "lib.rs");
        } else if relative == Path::new("kernel/mod.rs") {
            assert_eq!(text.matches("#[allow(unsafe_code)]").count(), 2, "kernel/mod.rs");
            assert!(text.contains("#[allow(unsafe_code)]\npub(crate) mod views;"));
            assert!(text.contains("#[allow(unsafe_code)]\npub(crate) mod simd;"));
        } else if !allowed {
            assert!(
                text.contains("#![forbid(unsafe_code)]"),
                "{} does not forbid unsafe code",
                relative.display()
            );
        }
    }
}
