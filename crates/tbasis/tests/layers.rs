//! The crate's layers, as the README states them: `kernel/` imports no pipeline and no entry
//! point, the pipelines (`pipelines/listing.rs`, `per_vertex/`, `mikktspace/`) import the kernel
//! only, never each other, and no module imports one that imports it back.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every module of the crate (`["kernel", "memory"]` for `src/kernel/memory.rs`) and its text.
fn modules() -> BTreeMap<Vec<String>, String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut found = BTreeMap::new();
    let mut dirs = vec![src.clone()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path: PathBuf = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(&src).unwrap().with_extension("");
                let mut name: Vec<String> = relative.iter().map(|p| p.to_string_lossy().into_owned()).collect();
                if matches!(name.last().map(String::as_str), Some("mod" | "lib")) {
                    name.pop();
                }
                found.insert(name, std::fs::read_to_string(&path).unwrap());
            }
        }
    }
    found
}

/// The modules `text` (module `name`) refers to by `crate::` or `super::` path, resolved to the
/// longest module that exists; comments left out.
fn references(name: &[String], text: &str, modules: &BTreeMap<Vec<String>, String>) -> BTreeSet<Vec<String>> {
    let code: String = text
        .lines()
        .map(|line| line.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut targets = BTreeSet::new();
    for (prefix, base) in [
        ("crate::", Vec::new()),
        ("super::", name[..name.len().saturating_sub(1)].to_vec()),
    ] {
        for (start, _) in code.match_indices(prefix) {
            let path: Vec<String> = code[start + prefix.len()..]
                .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .next()
                .unwrap_or("")
                .split("::")
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .collect();
            let full: Vec<String> = base.iter().cloned().chain(path).collect();
            let target = (1..=full.len())
                .rev()
                .map(|n| full[..n].to_vec())
                .find(|m| modules.contains_key(m));
            if let Some(target) = target.filter(|t| !name.starts_with(t) && !t.starts_with(name)) {
                targets.insert(target);
            }
        }
    }
    targets
}

#[test]
fn the_kernel_and_the_pipelines_import_only_what_lies_below_them() {
    let modules = modules();
    assert!(modules.contains_key(&vec!["kernel".to_string(), "memory".to_string()]));
    let mut broken = Vec::new();
    let mut graph = BTreeMap::new();
    for (name, text) in &modules {
        let targets = references(name, text, &modules);
        for target in &targets {
            let layer = |m: &[String]| m.first().cloned().unwrap_or_default();
            let allowed = match layer(name).as_str() {
                "kernel" => layer(target) == "kernel",
                // A pipeline: the kernel, and its own modules.
                "pipelines" => layer(target) == "kernel" || target.get(..2) == name.get(..2),
                _ => true,
            };
            if !allowed {
                broken.push(format!("{} imports {}", name.join("::"), target.join("::")));
            }
        }
        graph.insert(name.clone(), targets);
    }
    assert!(broken.is_empty(), "{broken:#?}");

    // No cycle: a depth-first search never meets a module still on its path.
    fn visit<'g>(
        module: &'g Vec<String>,
        graph: &'g BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        path: &mut Vec<&'g Vec<String>>,
        done: &mut BTreeSet<&'g Vec<String>>,
    ) {
        if let Some(start) = path.iter().position(|m| *m == module) {
            let cycle: Vec<String> = path[start..].iter().map(|m| m.join("::")).collect();
            panic!("import cycle: {}", cycle.join(" -> "));
        }
        if !done.insert(module) {
            return;
        }
        path.push(module);
        for next in &graph[module] {
            visit(next, graph, path, done);
        }
        path.pop();
    }
    let mut done = BTreeSet::new();
    for module in graph.keys() {
        visit(module, &graph, &mut Vec::new(), &mut done);
    }
}
