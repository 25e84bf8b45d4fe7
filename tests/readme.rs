//! The README's code blocks marked `<!-- snippet: PATH -->` are taken from PATH, a file that a
//! test builds or runs: each of their lines appears in that file, in the same order (indentation
//! aside), so the README cannot drift from code that is exercised.

use std::path::Path;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");
const MARKER: &str = "<!-- snippet: ";

/// `(source path, block lines)` for every marked block.
fn marked_blocks(readme: &str) -> Vec<(String, Vec<String>)> {
    let mut blocks = Vec::new();
    let mut lines = readme.lines();
    while let Some(line) = lines.next() {
        let Some(path) = line.strip_prefix(MARKER).and_then(|rest| rest.strip_suffix(" -->")) else {
            continue;
        };
        let fence = lines.next().unwrap_or_default();
        assert!(
            fence.starts_with("```"),
            "the marker for {path} is not followed by a code block"
        );
        let body = lines
            .by_ref()
            .take_while(|l| !l.starts_with("```"))
            .map(str::to_string)
            .collect();
        blocks.push((path.to_string(), body));
    }
    blocks
}

/// A line without its indentation and without the comment leader of a doc comment (`///`, `//!`:
/// where doctests live) or of a C block comment (`*`: where build commands are written down).
fn bare(line: &str) -> &str {
    let line = line.trim();
    ["///", "//!", "*"]
        .iter()
        .find_map(|leader| line.strip_prefix(leader))
        .unwrap_or(line)
        .trim()
}

/// The first line of `block` (non-empty, trimmed) missing from `source` in order, if any.
fn first_missing_line(block: &[String], source: &str) -> Option<String> {
    let mut source_lines = source.lines().map(bare);
    block
        .iter()
        .map(|line| line.trim())
        .filter(|line| !line.is_empty())
        .find(|line| !source_lines.any(|s| s == *line))
        .map(str::to_string)
}

#[test]
fn readme_snippets_come_from_tested_files() {
    let readme = std::fs::read_to_string(Path::new(CRATE_DIR).join("README.md")).expect("README.md");
    let blocks = marked_blocks(&readme);
    let sources: Vec<&str> = blocks.iter().map(|(path, _)| path.as_str()).collect();
    for expected in [
        "examples/c/CMakeLists.txt",
        "examples/c/consumer.c",
        "examples/cpp/interleaved.cpp",
        "bindings/python/examples/interleaved.py",
        "tests/gltf_convention.rs",
        "tests/transform.rs",
        "src/generate.rs",
    ] {
        assert!(sources.contains(&expected), "no README snippet from {expected}");
    }
    for (path, block) in &blocks {
        assert!(!block.is_empty(), "the README snippet from {path} is empty");
        let source = std::fs::read_to_string(Path::new(CRATE_DIR).join(path)).unwrap_or_else(|e| panic!("{path}: {e}"));
        if let Some(line) = first_missing_line(block, &source) {
            panic!("README snippet line not in {path} (in order): {line}");
        }
    }
}

#[test]
fn a_changed_line_is_caught() {
    let block = vec!["let a = 1;".to_string(), "let b = 2;".to_string()];
    assert_eq!(first_missing_line(&block, "  let a = 1;\n  let b = 2;\n"), None);
    assert_eq!(first_missing_line(&block, "/// let a = 1;\n/// let b = 2;\n"), None);
    assert_eq!(first_missing_line(&block, " *   let a = 1;\n *   let b = 2;\n"), None);
    assert_eq!(
        first_missing_line(&block, "let b = 2;\nlet a = 1;\n"),
        Some("let b = 2;".to_string())
    );
    assert_eq!(
        first_missing_line(&block, "let a = 1;\nlet b = 3;\n"),
        Some("let b = 2;".to_string())
    );
}
