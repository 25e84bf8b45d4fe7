//! The README's code blocks marked `<!-- snippet: PATH -->` are taken from PATH, a file that a
//! test builds or runs: each of their lines appears in that file, in the same order (indentation
//! aside), so the README cannot drift from code that is exercised.
//!
//! A block marked `<!-- example: FILE -->` is a whole program, FILE, followed by a `sh` block that
//! builds and runs it from the repository root and a `text` block with its output: the test runs
//! those commands as written and compares the output.

use std::path::Path;

#[cfg(target_os = "linux")]
#[path = "common/artifacts.rs"]
#[allow(dead_code)]
mod artifacts;
#[cfg(target_os = "linux")]
#[path = "common/tools.rs"]
#[allow(dead_code)]
mod tools;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");
const MARKER: &str = "<!-- snippet: ";
const EXAMPLE_MARKER: &str = "<!-- example: ";

/// The name in a marker line `<prefix>NAME -->`.
fn marker<'a>(line: &'a str, prefix: &str) -> Option<&'a str> {
    line.strip_prefix(prefix)?.strip_suffix(" -->")
}

/// The next fenced code block of `lines`: its language and its lines. With `adjacent`, the block
/// must start on the first line.
fn next_block<'a>(lines: &mut impl Iterator<Item = &'a str>, adjacent: bool, what: &str) -> (String, Vec<String>) {
    let fence = if adjacent {
        lines.next().filter(|l| l.starts_with("```"))
    } else {
        lines.find(|l| l.starts_with("```"))
    };
    let language = fence
        .unwrap_or_else(|| panic!("{what} is not followed by a code block"))
        .trim_start_matches('`')
        .to_string();
    let body = lines
        .by_ref()
        .take_while(|l| !l.starts_with("```"))
        .map(str::to_string)
        .collect();
    (language, body)
}

/// `(source path, block lines)` for every marked block.
fn marked_blocks(readme: &str) -> Vec<(String, Vec<String>)> {
    let mut blocks = Vec::new();
    let mut lines = readme.lines();
    while let Some(line) = lines.next() {
        let Some(path) = marker(line, MARKER) else {
            continue;
        };
        let (_, body) = next_block(&mut lines, true, &format!("the marker for {path}"));
        blocks.push((path.to_string(), body));
    }
    blocks
}

/// A whole program in the README, with the commands that build and run it and what it prints.
struct Example {
    file: String,
    source: Vec<String>,
    commands: Vec<String>,
    output: Vec<String>,
}

fn examples(readme: &str) -> Vec<Example> {
    let mut examples = Vec::new();
    let mut lines = readme.lines();
    while let Some(line) = lines.next() {
        let Some(file) = marker(line, EXAMPLE_MARKER) else {
            continue;
        };
        let what = format!("the example {file}");
        let (_, source) = next_block(&mut lines, true, &what);
        let (language, commands) = next_block(&mut lines, false, &what);
        assert_eq!(
            language, "sh",
            "{what}: the block after the program must be its commands"
        );
        let (language, output) = next_block(&mut lines, false, &what);
        assert_eq!(
            language, "text",
            "{what}: the block after the commands must be its output"
        );
        examples.push(Example {
            file: file.to_string(),
            source,
            commands,
            output,
        });
    }
    examples
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
        "crates/tbasis/tests/gltf_convention.rs",
        "crates/tbasis/tests/transform.rs",
        "crates/tbasis/src/lib.rs",
        "crates/tbasis/src/entry/generate.rs",
        "c_tests/harness.c",
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

/// Languages whose blocks are code a user would paste; `sh` and `text` blocks are commands and
/// output, checked where an example runs them.
const CODE_LANGUAGES: [&str; 6] = ["rust", "c", "cpp", "python", "cmake", "toml"];

#[test]
fn every_code_block_is_a_tested_snippet_or_example() {
    let readme = std::fs::read_to_string(Path::new(CRATE_DIR).join("README.md")).expect("README.md");
    let lines: Vec<&str> = readme.lines().collect();
    let mut inside = false;
    for (k, line) in lines.iter().enumerate() {
        if !line.starts_with("```") {
            continue;
        }
        if inside {
            inside = false;
            continue;
        }
        inside = true;
        let language = line.trim_start_matches('`');
        let marked =
            k > 0 && (marker(lines[k - 1], MARKER).is_some() || marker(lines[k - 1], EXAMPLE_MARKER).is_some());
        assert!(
            !CODE_LANGUAGES.contains(&language) || marked,
            "README line {}: a {language} block without a snippet or example marker",
            k + 1
        );
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

/// Runs each README example's commands as written, in a directory standing for the repository
/// root (the example, `include` and `target` linked to the real ones), so that neither the source
/// tree nor a `CARGO_TARGET_DIR` elsewhere changes what they see. The commands start with `cargo
/// build --release`, which builds into the target dir of these tests.
#[cfg(target_os = "linux")]
#[test]
fn readme_examples_build_and_run_from_the_build_tree() {
    use std::os::unix::fs::symlink;
    use std::process::Command;

    let readme = std::fs::read_to_string(Path::new(CRATE_DIR).join("README.md")).expect("README.md");
    let examples = examples(&readme);
    assert!(examples.iter().any(|e| e.file == "quad.c"), "no README example quad.c");
    for example in &examples {
        let what = format!("the README example {}", example.file);
        let (build, commands) = example.commands.split_first().expect("commands");
        assert_eq!(
            build, "cargo build --release",
            "{what} must start by building the library"
        );
        let profile_dir = artifacts::build_library(true);

        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join("readme")
            .join(&example.file);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create the example directory");
        std::fs::write(dir.join(&example.file), example.source.join("\n") + "\n").expect("write the example");
        symlink(Path::new(CRATE_DIR).join("include"), dir.join("include")).expect("link include/");
        symlink(profile_dir.parent().expect("the target dir"), dir.join("target")).expect("link target/");

        // cargo sets LD_LIBRARY_PATH for tests; the program must find the library as written.
        let mut shell = Command::new("sh");
        shell.arg("-ec").arg(commands.join("\n"));
        shell.current_dir(&dir).env_remove("LD_LIBRARY_PATH");
        let output = tools::run_ok(shell, &what);
        assert_eq!(
            String::from_utf8_lossy(&output.stdout).lines().collect::<Vec<_>>(),
            example.output,
            "output of {what}"
        );

        // What the README shows compiles as strict C99.
        if example.file.ends_with(".c") {
            let mut strict = Command::new("cc");
            strict.args([
                "-std=c99",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-pedantic",
                "-fsyntax-only",
                "-Iinclude",
            ]);
            strict.arg(&example.file).current_dir(&dir);
            tools::run_ok(strict, &format!("{what} as strict C99"));
        }
    }
}

/// The README's `## NAME` sections, in order, with their text.
fn sections(readme: &str) -> Vec<(String, String)> {
    let mut sections: Vec<(String, String)> = Vec::new();
    let mut fenced = false;
    for line in readme.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        }
        match line.strip_prefix("## ") {
            Some(name) if !fenced => sections.push((name.to_string(), String::new())),
            _ => {
                if let Some((_, text)) = sections.last_mut() {
                    text.push_str(line);
                    text.push('\n');
                }
            }
        }
    }
    sections
}

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces as hyphens.
fn anchor(heading: &str) -> String {
    heading
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

#[test]
fn a_quick_start_for_each_audience_then_contents_within_80_lines() {
    let readme = std::fs::read_to_string(Path::new(CRATE_DIR).join("README.md")).expect("README.md");
    let sections = sections(&readme);
    let names: Vec<&str> = sections.iter().map(|(name, _)| name.as_str()).collect();
    assert_eq!(
        names[..2],
        ["Quick start", "Contents"],
        "the README opens with these sections"
    );
    let quick_start = &sections[0].1;
    for audience in ["**C**", "**C++**", "**Rust**", "**Python**", "**glTF files**"] {
        assert!(
            quick_start.contains(audience),
            "the quick start has no part for {audience}"
        );
    }
    let contents_line = readme.lines().position(|line| line == "## Contents").unwrap() + 1;
    assert!(contents_line <= 80, "the contents list starts on line {contents_line}");
    // Every link of the contents list leads to a heading.
    let headings: Vec<String> = readme
        .lines()
        .filter_map(|line| line.strip_prefix("## ").or_else(|| line.strip_prefix("### ")))
        .map(anchor)
        .collect();
    for link in sections[1].1.split("](#").skip(1) {
        let target = link.split(')').next().unwrap();
        assert!(
            headings.iter().any(|h| h == target),
            "the contents link #{target} leads nowhere"
        );
    }
}

/// The names of the tests, in `dir`'s files, that skip without the corpus: the functions whose
/// body checks `needs::CORPUS`.
fn corpus_tests(dir: &Path) -> Vec<String> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|ext| ext != "rs") {
            continue;
        }
        let source = std::fs::read_to_string(&path).unwrap();
        // Spelt in two pieces, so that this file does not name itself.
        for (at, _) in source.match_indices(concat!("needs::CORPUS", ".found_or_skip()")) {
            let before = &source[..at];
            let name = before.rsplit("fn ").next().unwrap().split('(').next().unwrap();
            names.push(name.trim().to_string());
        }
    }
    names
}

#[test]
fn the_readme_names_every_test_that_needs_the_corpus() {
    let readme = std::fs::read_to_string(Path::new(CRATE_DIR).join("README.md")).expect("README.md");
    let (_, corpus) = sections(&readme)
        .into_iter()
        .find(|(name, _)| name == "Test corpus")
        .expect("a Test corpus section");
    let mut tests = Vec::new();
    for dir in [
        "crates/tbasis/tests",
        "crates/tbasis/src/pipelines/mikktspace",
        "tests",
        "tools/gltf/tests",
    ] {
        tests.extend(corpus_tests(&Path::new(CRATE_DIR).join(dir)));
    }
    assert!(tests.len() >= 12, "only {} corpus tests found: {tests:?}", tests.len());
    for test in &tests {
        assert!(
            corpus.contains(&format!("`{test}`")),
            "the README's \"Test corpus\" does not name {test}, which needs the corpus"
        );
    }
}
