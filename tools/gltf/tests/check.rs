//! `--check`: what the tool would change, per file, with nothing written; its exit status says
//! whether anything would change. And the message when no output is given.

mod common;

use std::path::Path;

use common::fixture::Fixture;
use common::tool;

/// Every file below `dir` with its bytes, to compare before and after a run.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    tool::listing(dir)
        .into_iter()
        .map(|name| {
            let bytes = std::fs::read(dir.join(&name)).unwrap();
            (name, bytes)
        })
        .collect()
}

#[test]
fn check_reports_what_would_change_writes_nothing_and_exits_with_1() {
    let dir = tool::fresh_dir("check-changes");
    let glb = Fixture::mirrored_quad().write_glb(&dir, "quad");
    let gltf = Fixture::mirrored_quad().write_gltf(&dir, "separate");
    let before = snapshot(&dir);

    let result = tool::run(["--check".as_ref(), glb.as_os_str(), gltf.as_os_str()]);
    assert_eq!(result.status.code(), Some(1), "something would change");
    let stdout = String::from_utf8_lossy(&result.stdout);
    for input in [&glb, &gltf] {
        let expected = format!(
            "{}: would change 1 primitive, 2 vertices added, 0 corners repaired",
            input.display()
        );
        assert!(stdout.lines().any(|line| line == expected), "{stdout}");
    }
    assert_eq!(snapshot(&dir), before, "--check wrote or changed a file");
}

#[test]
fn check_exits_with_0_when_nothing_would_change() {
    let dir = tool::fresh_dir("check-nothing");
    let input = Fixture::mirrored_quad().write_glb(&dir, "quad");
    let converted = dir.join("converted.glb");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), converted.as_os_str()]);
    assert!(result.status.success());

    let result = tool::run(["--check".as_ref(), converted.as_os_str()]);
    assert_eq!(result.status.code(), Some(0), "a converted file has nothing to change");
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(
        stdout.starts_with(&format!("{}: nothing to change", converted.display())),
        "{stdout}"
    );
    // With --overwrite its tangents would be computed again.
    let result = tool::run(["--check".as_ref(), "--overwrite".as_ref(), converted.as_os_str()]);
    assert_eq!(result.status.code(), Some(1));
}

#[test]
fn check_exits_with_2_on_a_file_it_cannot_read_and_takes_no_output() {
    let dir = tool::fresh_dir("check-errors");
    let good = Fixture::mirrored_quad().write_glb(&dir, "good");
    let bad = dir.join("bad.glb");
    std::fs::write(&bad, b"glTF but not really").unwrap();
    let before = snapshot(&dir);

    let result = tool::run(["--check".as_ref(), good.as_os_str(), bad.as_os_str()]);
    assert_eq!(result.status.code(), Some(2), "an error is neither 0 nor 1");
    assert!(String::from_utf8_lossy(&result.stderr).contains(&format!("{}: not a valid GLB file", bad.display())));
    assert_eq!(snapshot(&dir), before);

    let output = dir.join("out.glb");
    let result = tool::run(["--check".as_ref(), good.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    assert_eq!(result.status.code(), Some(2), "--check with -o");
    assert!(!output.exists());
}

#[test]
fn without_an_output_the_message_names_both_options() {
    let dir = tool::fresh_dir("no-output");
    let input = Fixture::mirrored_quad().write_glb(&dir, "quad");
    let result = tool::run([input.as_os_str()]);
    assert_eq!(result.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&result.stderr);
    for option in ["-o FILE", "--out-dir DIR", "--check"] {
        assert!(stderr.contains(option), "the message names {option}: {stderr}");
    }
}
