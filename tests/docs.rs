//! Every document in docs/ that holds a table of figures names, in a code block, a command that
//! `scripts/regenerate-docs` runs: one command regenerates every figure.

use std::path::Path;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");

/// The lines of `markdown`'s fenced code blocks that run a command (`cargo ...`, `bash ...`, or a
/// shell line that ends in one).
fn commands(markdown: &str) -> Vec<&str> {
    let mut inside = false;
    let mut found = Vec::new();
    for line in markdown.lines() {
        if line.starts_with("```") {
            inside = !inside;
        } else if inside && (line.contains("cargo ") || line.starts_with("bash ")) {
            found.push(line.trim());
        }
    }
    found
}

#[test]
fn every_document_with_figures_names_a_command_regenerate_docs_runs() {
    let root = Path::new(CRATE_DIR);
    let script = std::fs::read_to_string(root.join("scripts/regenerate-docs")).expect("scripts/regenerate-docs");
    let runs: Vec<&str> = script.lines().map(str::trim).filter(|l| !l.starts_with('#')).collect();
    let mut checked = 0;
    let mut failures = Vec::new();
    let mut docs: Vec<_> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "md"))
        .collect();
    docs.sort();
    for doc in docs {
        let text = std::fs::read_to_string(&doc).unwrap_or_else(|e| panic!("{}: {e}", doc.display()));
        // A Markdown table's separator row: the document has figures.
        if !text.lines().any(|line| line.starts_with("|---")) {
            continue;
        }
        checked += 1;
        let named = commands(&text);
        if !named.iter().any(|command| runs.contains(command)) {
            failures.push(format!(
                "{}: none of the commands it names is in scripts/regenerate-docs: {named:?}",
                doc.display()
            ));
        }
    }
    assert!(checked > 0, "no document with figures in docs/");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
