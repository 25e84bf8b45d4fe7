//! What the tool must not destroy: its input, a file it did not write, an output half written;
//! and what `--overwrite` must not leave behind.

mod common;

use std::path::Path;

use common::document::Doc;
use common::fixture::Fixture;
use common::{needs, tool, validator};
use serde_json::json;

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
    // A side buffer `--force` would replace is put back as it was.
    std::fs::write(out.join("quad.tangents.bin"), b"an earlier output").unwrap();
    fails(
        &[&input, Path::new("--force"), Path::new("-o"), &output],
        "cannot rename into",
    );
    assert_eq!(tool::listing(&out), ["quad.gltf", "quad.tangents.bin"]);
    assert_eq!(
        std::fs::read(out.join("quad.tangents.bin")).unwrap(),
        b"an earlier output"
    );
}

/// Runs the tool with `--overwrite` on `input` into `output`.
fn overwrite(input: &Path, output: &Path) {
    let result = tool::run([input, Path::new("--overwrite"), Path::new("-o"), output]);
    assert!(result.status.success(), "{}", input.display());
}

/// How many items of top-level list `key` a file has.
fn count(file: &Path, key: &str) -> usize {
    Doc::open(file).json[key].as_array().map_or(0, Vec::len)
}

/// The quad with a normal map (so that the validator sees its tangents and texture coordinates
/// used), run through `--overwrite` twice, as .gltf and .glb: (input, first output, second output).
fn overwritten_twice(test: &str) -> Vec<[std::path::PathBuf; 3]> {
    let dir = tool::fresh_dir(test);
    let mut fixture = Fixture::mirrored_quad();
    // A 1×1 PNG.
    let png = "data:image/png;base64,\
               iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGNoaPgPAAODAgAApfuJAAAAAElFTkSuQmCC";
    fixture.json["images"] = json!([{ "uri": png }]);
    fixture.json["textures"] = json!([{ "source": 0 }]);
    fixture.json["materials"] = json!([{ "normalTexture": { "index": 0 } }]);
    fixture.primitive(0)["material"] = json!(0);
    [fixture.write_gltf(&dir, "quad"), fixture.write_glb(&dir, "quad")]
        .into_iter()
        .map(|input| {
            let extension = input.extension().unwrap().to_str().unwrap().to_string();
            let (first, second) = (
                dir.join(format!("first.{extension}")),
                dir.join(format!("second.{extension}")),
            );
            overwrite(&input, &first);
            overwrite(&first, &second);
            [input, first, second]
        })
        .collect()
}

#[test]
fn overwrite_leaves_no_unused_accessor_or_buffer_view() {
    for [_, first, second] in overwritten_twice("overwrite-twice") {
        // POSITION, NORMAL, TEXCOORD_0 and the indices, copied with the split vertices, and TANGENT.
        for file in [&first, &second] {
            assert_eq!(count(file, "accessors"), 5, "{}", file.display());
            assert_eq!(count(file, "bufferViews"), 5, "{}", file.display());
        }
        let buffers = if first.extension().unwrap() == "gltf" { 2 } else { 1 };
        assert_eq!(count(&second, "buffers"), buffers, "{}", second.display());
        assert_eq!(Doc::open(&second).corners(0, 0, 0).positions.len(), 6);
    }
}

#[test]
fn overwrite_twice_passes_the_validator_with_no_unused_object() {
    if !needs::GLTF_VALIDATOR.found_or_skip() {
        return;
    }
    for [input, _, second] in overwritten_twice("overwrite-validated") {
        let (before, after) = (validator::report(&input), validator::report(&second));
        assert!(
            !before.iter().any(|issue| issue.code == "UNUSED_OBJECT"),
            "{}: {before:#?}",
            input.display()
        );
        let new = validator::new_issues(&before, &after);
        assert!(new.is_empty(), "{}: {new:#?}", second.display());
    }
}

#[test]
fn inputs_whose_side_buffers_would_share_a_name_are_refused() {
    let dir = tool::fresh_dir("stems");
    std::fs::create_dir_all(dir.join("a")).unwrap();
    std::fs::create_dir_all(dir.join("b")).unwrap();
    let first = Fixture::mirrored_quad().write_gltf(&dir.join("a"), "quad");
    let second = dir.join("b").join("quad.GLTF");
    std::fs::rename(Fixture::mirrored_quad().write_gltf(&dir.join("b"), "quad"), &second).unwrap();
    let out = dir.join("out");
    let result = tool::run([
        first.as_os_str(),
        second.as_os_str(),
        "--out-dir".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(result.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&result.stderr).contains("two inputs are named quad.gltf"));
    assert!(!out.exists(), "nothing written");
    // A .glb of the same stem keeps its new data in its binary chunk: no collision.
    let glb = Fixture::mirrored_quad().write_glb(&dir.join("b"), "quad");
    let result = tool::run([
        first.as_os_str(),
        glb.as_os_str(),
        "--out-dir".as_ref(),
        out.as_os_str(),
    ]);
    assert!(result.status.success());
    assert_eq!(tool::listing(&out), ["quad.glb", "quad.gltf", "quad.tangents.bin"]);
}
