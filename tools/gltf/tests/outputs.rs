//! What the tool must not destroy: its input, a file it did not write, an output half written.

mod common;

use std::path::Path;

use common::document::Doc;
use common::fixture::Fixture;
use common::tool;

/// Runs the tool; checks that it failed with exit status 1 and said `message`.
fn fails(args: &[&Path], message: &str) {
    let result = tool::run(args);
    assert_eq!(result.status.code(), Some(1), "exit status of {args:?}");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains(message), "the message says {message:?}: {stderr}");
}

#[cfg(unix)]
#[test]
fn an_output_that_is_the_input_is_refused() {
    let dir = tool::fresh_dir("output-is-input");
    let input = Fixture::mirrored_quad().write_glb(&dir, "quad");
    let bytes = std::fs::read(&input).unwrap();
    std::os::unix::fs::symlink(&input, dir.join("symbolic.glb")).unwrap();
    std::fs::hard_link(&input, dir.join("hard.glb")).unwrap();
    let o = Path::new("-o");
    fails(&[&input, o, &input], "is this file; write it elsewhere");
    fails(&[&input, Path::new("--out-dir"), &dir], "is this file");
    fails(&[&input, o, &dir.join("symbolic.glb")], "is this file");
    fails(&[&input, o, &dir.join("hard.glb")], "is this file");
    assert_eq!(std::fs::read(&input).unwrap(), bytes, "the input is as it was");
    assert_eq!(tool::listing(&dir), ["hard.glb", "quad.glb", "symbolic.glb"]);
}

#[test]
fn a_side_buffer_the_run_did_not_write_is_kept_unless_forced() {
    let dir = tool::fresh_dir("side-buffer-exists");
    let input = Fixture::mirrored_quad().write_gltf(&dir, "quad");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let side = out.join("quad.tangents.bin");
    std::fs::write(&side, b"another file's data").unwrap();
    let output = out.join("quad.gltf");
    fails(
        &[&input, Path::new("-o"), &output],
        "quad.tangents.bin exists and this run did not write it; remove it, or pass --force",
    );
    assert_eq!(std::fs::read(&side).unwrap(), b"another file's data");
    assert_eq!(tool::listing(&out), ["quad.tangents.bin"], "nothing else written");

    let result = tool::run([&input, Path::new("--force"), Path::new("-o"), &output]);
    assert!(result.status.success());
    assert_eq!(tool::listing(&out), ["quad.gltf", "quad.tangents.bin"]);
    assert_eq!(Doc::open(&output).corners(0, 0, 0).positions.len(), 6);
}

#[test]
fn a_failed_rename_of_the_main_file_leaves_no_side_buffer() {
    let dir = tool::fresh_dir("main-rename-fails");
    let input = Fixture::mirrored_quad().write_gltf(&dir, "quad");
    let out = dir.join("out");
    // A folder where the main file goes: its rename fails after the side buffer's succeeded.
    let output = out.join("quad.gltf");
    std::fs::create_dir_all(output.join("occupied")).unwrap();
    fails(&[&input, Path::new("-o"), &output], "cannot rename into");
    assert_eq!(tool::listing(&out), ["quad.gltf"], "no side buffer, no temporary file");
}
