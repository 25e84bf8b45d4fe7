//! The mesh corpus for a fresh clone: `scripts/fetch-corpus` fetches every file that
//! `corpus/MANIFEST.tsv` and `corpus/companions.tsv` list and checks its hash. CI has no network
//! beyond the package registries, so the script runs here on a local mirror, built from the
//! corpus beside the clone in the layout of the public sources; and the repository's manifests
//! must describe that corpus exactly.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::tools::{run, run_ok};
use tbasis_test_support::needs;

const CRATE_DIR: &str = env!("CARGO_MANIFEST_DIR");

fn script() -> Command {
    Command::new(Path::new(CRATE_DIR).join("scripts/fetch-corpus"))
}

/// `(path, fetch)` for every file the repository's manifests list.
fn listed_files() -> Vec<(String, String)> {
    let mut files = Vec::new();
    for list in ["corpus/MANIFEST.tsv", "corpus/companions.tsv"] {
        let text = std::fs::read_to_string(Path::new(CRATE_DIR).join(list)).expect(list);
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().expect("a header").split('\t').collect();
        let column = |name: &str| header.iter().position(|h| *h == name).expect(name);
        let (path, fetch) = (column("path"), column("fetch"));
        for line in lines {
            let fields: Vec<&str> = line.split('\t').collect();
            files.push((fields[path].to_string(), fields[fetch].to_string()));
        }
    }
    files
}

/// Every file below `dir`, relative to it.
fn files_below(dir: &Path) -> BTreeSet<String> {
    fn walk(root: &Path, dir: &Path, found: &mut BTreeSet<String>) {
        for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                walk(root, &path, found);
            } else {
                let relative = path.strip_prefix(root).expect("below the root");
                found.insert(relative.to_string_lossy().into_owned());
            }
        }
    }
    let mut found = BTreeSet::new();
    walk(dir, dir, &mut found);
    found
}

fn fresh_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("corpus-fetch").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a temporary folder");
    dir
}

fn copy(from: &Path, to: &Path) {
    std::fs::create_dir_all(to.parent().expect("a parent")).expect("create a folder");
    std::fs::copy(from, to).unwrap_or_else(|e| panic!("copy {} to {}: {e}", from.display(), to.display()));
}

/// A mirror of the public sources holding the corpus's files: GitHub files under
/// `github/OWNER/REPO/COMMIT/PATH`, each PyPI source distribution as `pypi/NAME-VERSION.tar.gz`
/// (with a decoy of each file elsewhere in it, which the script must tell apart by its hash), and
/// the Blender-made files under `derived/`.
fn build_mirror(corpus: &Path, mirror: &Path) {
    let sdists = mirror.join("sdists");
    for (path, fetch) in listed_files() {
        let file = corpus.join(&path);
        let (kind, spec) = fetch.split_once(':').expect("KIND:SPEC");
        match kind {
            "github" => {
                let (repo, rest) = spec.split_once('@').expect("OWNER/REPO@COMMIT:PATH");
                let (commit, source) = rest.split_once(':').expect("COMMIT:PATH");
                copy(&file, &mirror.join("github").join(repo).join(commit).join(source));
            }
            "pypi" => {
                let (name, rest) = spec.split_once("==").expect("NAME==VERSION:PATH");
                let (version, source) = rest.split_once(':').expect("VERSION:PATH");
                let root = sdists.join(format!("{name}-{version}"));
                copy(&file, &root.join(source));
                let decoy = root.join("decoy").join(source);
                std::fs::create_dir_all(decoy.parent().unwrap()).unwrap();
                std::fs::write(decoy, b"not the recorded file\n").unwrap();
            }
            "blender" => copy(&file, &mirror.join(spec)),
            _ => panic!("{path}: unknown source {fetch}"),
        }
    }
    std::fs::create_dir_all(mirror.join("pypi")).unwrap();
    for entry in std::fs::read_dir(&sdists).expect("the source distributions") {
        let root = entry.unwrap().file_name().into_string().unwrap();
        let mut tar = Command::new("tar");
        tar.arg("-czf")
            .arg(mirror.join("pypi").join(format!("{root}.tar.gz")))
            .arg("-C")
            .arg(&sdists)
            .arg(&root);
        run_ok(tar, "tar of a source distribution");
    }
}

#[test]
fn the_repository_manifests_describe_the_corpus_beside_the_clone() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let corpus = needs::corpus_dir();
    // Every file has its recorded hash, and MANIFEST.tsv is the one the script writes.
    let mut check = script();
    check.arg("--check").arg("--dest").arg(&corpus);
    run_ok(check, "scripts/fetch-corpus --check");
    // And nothing is there that the manifests do not list (the corpus's own README aside).
    let mut listed: BTreeSet<String> = listed_files().into_iter().map(|(path, _)| path).collect();
    listed.extend(["MANIFEST.tsv".to_string(), "README.md".to_string()]);
    let unlisted: Vec<String> = files_below(&corpus).difference(&listed).cloned().collect();
    assert!(
        unlisted.is_empty(),
        "corpus files the manifests do not list: {unlisted:?}"
    );
}

#[test]
fn fetch_corpus_fetches_every_file_from_a_mirror_and_refuses_a_corrupted_one() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let corpus = needs::corpus_dir();
    let mirror = fresh_dir("mirror");
    build_mirror(&corpus, &mirror);
    let dest = fresh_dir("dest");

    let mut fetch = script();
    fetch.arg("--mirror").arg(&mirror).arg("--dest").arg(&dest);
    let output = run_ok(fetch, "scripts/fetch-corpus --mirror");
    let files = listed_files();
    let expected = format!("{} files fetched, 0 already there", files.len());
    assert!(
        String::from_utf8_lossy(&output.stdout).contains(&expected),
        "not every file was fetched"
    );
    let mut check = script();
    check.arg("--check").arg("--dest").arg(&dest);
    run_ok(check, "scripts/fetch-corpus --check on what it fetched");
    for (path, _) in &files {
        let (fetched, original) = (
            std::fs::read(dest.join(path)).unwrap(),
            std::fs::read(corpus.join(path)).unwrap(),
        );
        assert!(fetched == original, "{path}: other bytes than the corpus's");
    }

    // A file whose source changed is refused and not put in place; the others stay.
    let (victim, fetch_spec) = files
        .iter()
        .find(|(_, fetch)| fetch.starts_with("github:"))
        .expect("a file from GitHub");
    let (repo, rest) = fetch_spec["github:".len()..].split_once('@').unwrap();
    let (commit, source) = rest.split_once(':').unwrap();
    let mirrored = mirror.join("github").join(repo).join(commit).join(source);
    let mut bytes = std::fs::read(&mirrored).unwrap();
    bytes[0] ^= 1;
    std::fs::write(&mirrored, bytes).unwrap();
    std::fs::remove_file(dest.join(victim)).unwrap();
    let mut again = script();
    again.arg("--mirror").arg(&mirror).arg("--dest").arg(&dest);
    let output = run(again, "scripts/fetch-corpus --mirror with a corrupted file");
    assert_eq!(output.status.code(), Some(1), "a corrupted file must fail the fetch");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(&format!("{victim}: refused")),
        "the refusal must name {victim}: {stderr}"
    );
    assert!(
        !dest.join(victim).exists(),
        "{victim} was put in place although corrupted"
    );
    assert!(
        String::from_utf8_lossy(&output.stdout)
            .contains(&format!("0 files fetched, {} already there", files.len() - 1)),
        "the files already fetched must be kept"
    );

    // --check names a file that changed in place.
    std::fs::write(dest.join(victim), b"changed\n").unwrap();
    let mut check = script();
    check.arg("--check").arg("--dest").arg(&dest);
    let output = run(check, "scripts/fetch-corpus --check on a changed file");
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains(victim.as_str()));

    // The Blender-made files, absent from the mirror: without `blender` on PATH the script says
    // how to make them; with one, it runs it (here a stand-in that copies the corpus's files).
    std::fs::write(dest.join(victim), std::fs::read(corpus.join(victim)).unwrap()).unwrap();
    let derived: Vec<&String> = files
        .iter()
        .filter(|(_, fetch)| fetch.starts_with("blender:"))
        .map(|(path, _)| path)
        .collect();
    assert!(!derived.is_empty(), "the manifests list no Blender-made file");
    for path in &derived {
        std::fs::remove_file(mirror.join(path)).unwrap();
        std::fs::remove_file(dest.join(path)).unwrap();
    }
    let search_path = std::env::var_os("PATH").unwrap_or_default();
    let fetch_with_path = |path: &std::ffi::OsStr| {
        let mut fetch = script();
        fetch
            .arg("--mirror")
            .arg(&mirror)
            .arg("--dest")
            .arg(&dest)
            .env("PATH", path);
        fetch
    };
    if std::env::split_paths(&search_path).any(|dir| dir.join("blender").exists()) {
        eprintln!("fetch-corpus without Blender: not checked, `blender` is on PATH");
    } else {
        let output = run(fetch_with_path(&search_path), "scripts/fetch-corpus without Blender");
        assert_eq!(
            output.status.code(),
            Some(1),
            "a missing Blender-made file must fail the fetch"
        );
        let stderr = String::from_utf8_lossy(&output.stderr);
        for path in &derived {
            let hint = format!("{path}: made with Blender 3.4.1, which is not on PATH");
            assert!(stderr.contains(&hint), "no `{hint}`: {stderr}");
            assert!(stderr.contains("corpus/derive.py"), "no way to make {path}: {stderr}");
        }
    }

    let tools = fresh_dir("blender-stand-in");
    let mut stand_in = String::from("#!/bin/sh\nif [ \"$1\" = --version ]; then echo 'Blender 3.4.1'; exit 0; fi\n");
    stand_in.push_str("for work in \"$@\"; do :; done\n");
    for path in &derived {
        let (from, to) = (corpus.join(path), Path::new("$work").join(path));
        stand_in.push_str(&format!("mkdir -p \"$(dirname \"{}\")\"\n", to.display()));
        stand_in.push_str(&format!("cp '{}' \"{}\"\n", from.display(), to.display()));
    }
    let blender = tools.join("blender");
    std::fs::write(&blender, stand_in).unwrap();
    let mut permissions = std::fs::metadata(&blender).unwrap().permissions();
    std::os::unix::fs::PermissionsExt::set_mode(&mut permissions, 0o755);
    std::fs::set_permissions(&blender, permissions).unwrap();
    // Ahead of any other `blender` on PATH.
    let with_stand_in =
        std::env::join_paths(std::iter::once(tools.clone()).chain(std::env::split_paths(&search_path))).unwrap();
    let output = run_ok(
        fetch_with_path(&with_stand_in),
        "scripts/fetch-corpus with a Blender on PATH",
    );
    let expected = format!(
        "{} files fetched, {} already there",
        derived.len(),
        files.len() - derived.len()
    );
    assert!(
        String::from_utf8_lossy(&output.stdout).contains(&expected),
        "Blender's files were not made: {}",
        String::from_utf8_lossy(&output.stdout)
    );
    for path in &derived {
        assert!(
            std::fs::read(dest.join(path)).unwrap() == std::fs::read(corpus.join(path)).unwrap(),
            "{path}"
        );
    }
}
