//! Files the tool must refuse: a message naming the file and what is wrong, exit status 1, and
//! nothing written for that file.

mod common;

use std::path::{Path, PathBuf};

use common::fixture::Fixture;
use common::tool;
use serde_json::json;

/// Runs the tool on `input` into an empty folder; checks the failure, its message and that the
/// folder is still empty.
fn refused(input: &Path, out_dir: &Path, message: &str) {
    let output = out_dir.join(input.file_name().unwrap());
    let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    assert_eq!(result.status.code(), Some(1), "exit status");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains(&input.display().to_string()),
        "the message names the file: {stderr}"
    );
    assert!(stderr.contains(message), "the message says {message:?}: {stderr}");
    assert_eq!(tool::listing(out_dir), Vec::<String>::new(), "nothing written");
}

/// A folder with an input folder `in/` and an empty output folder `out/`.
fn folders(test: &str) -> (PathBuf, PathBuf) {
    let dir = tool::fresh_dir(test);
    let (input, output) = (dir.join("in"), dir.join("out"));
    std::fs::create_dir_all(&input).unwrap();
    std::fs::create_dir_all(&output).unwrap();
    (input, output)
}

#[test]
fn draco_compression_in_extensions_required() {
    let (input, output) = folders("draco");
    let mut fixture = Fixture::mirrored_quad();
    fixture.json["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    fixture.json["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let file = fixture.write_glb(&input, "draco");
    refused(
        &file,
        &output,
        "requires KHR_draco_mesh_compression (Draco mesh compression)",
    );
}

#[test]
fn meshopt_compression_in_extensions_required() {
    let (input, output) = folders("meshopt");
    let mut fixture = Fixture::mirrored_quad();
    fixture.json["extensionsUsed"] = json!(["EXT_meshopt_compression"]);
    fixture.json["extensionsRequired"] = json!(["EXT_meshopt_compression"]);
    let file = fixture.write_gltf(&input, "meshopt");
    refused(&file, &output, "requires EXT_meshopt_compression (meshopt compression)");
}

#[test]
fn sparse_accessor_substituting_a_missing_element() {
    let (input, output) = folders("sparse");
    let mut fixture = Fixture::mirrored_quad();
    // NORMAL gets a sparse substitution of element 9 of 4.
    let indices = fixture.u16_indices(&[9]);
    let view = |f: &Fixture, a: usize| f.json["accessors"][a]["bufferView"].clone();
    let index_view = view(&fixture, indices);
    let values = fixture.floats(&[[0.0f32, 1.0, 0.0]], "VEC3", false);
    let value_view = view(&fixture, values);
    let normal = fixture.primitive(0)["attributes"]["NORMAL"].as_u64().unwrap() as usize;
    fixture.json["accessors"][normal]["sparse"] = json!({
        "count": 1,
        "indices": { "bufferView": index_view, "componentType": 5123 },
        "values": { "bufferView": value_view },
    });
    let file = fixture.write_gltf(&input, "sparse");
    refused(&file, &output, "sparse accessor 1: substitutes element 9 of 4");
}

#[test]
fn broken_json() {
    let (input, output) = folders("broken-json");
    let file = input.join("broken.gltf");
    std::fs::write(&file, b"{\"asset\": {\"version\": \"2.0\"},\n \"meshes\": [").unwrap();
    refused(&file, &output, "broken JSON: EOF while parsing a list at line 2 column");
}

#[test]
fn missing_buffer() {
    let (input, output) = folders("missing-buffer");
    let file = Fixture::mirrored_quad().write_gltf(&input, "lost");
    std::fs::remove_file(input.join("lost.bin")).unwrap();
    refused(&file, &output, "missing buffer 0: cannot read");
}

#[test]
fn a_bad_file_fails_the_run_but_not_the_others() {
    let (input, output) = folders("batch");
    let good = Fixture::mirrored_quad().write_glb(&input, "good");
    let bad = input.join("bad.glb");
    std::fs::write(&bad, b"glTF but not really").unwrap();
    let result = tool::run([
        good.as_os_str(),
        bad.as_os_str(),
        "--out-dir".as_ref(),
        output.as_os_str(),
    ]);
    assert_eq!(result.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains(&format!("{}: not a valid GLB file", bad.display())),
        "{stderr}"
    );
    assert!(stderr.contains("1 of 2 files failed"), "{stderr}");
    assert_eq!(tool::listing(&output), ["good.glb"]);
}

#[test]
fn command_line_errors_exit_with_2() {
    let (input, output) = folders("usage");
    let file = Fixture::mirrored_quad().write_glb(&input, "quad");
    for args in [
        vec![
            file.as_os_str(),
            "-o".as_ref(),
            output.join("quad.gltf").into_os_string().leak(),
        ],
        vec![
            file.as_os_str(),
            file.as_os_str(),
            "-o".as_ref(),
            output.join("x.glb").into_os_string().leak(),
        ],
        vec![file.as_os_str()],
    ] {
        assert_eq!(tool::run(&args).status.code(), Some(2), "{args:?}");
    }
    assert_eq!(tool::listing(&output), Vec::<String>::new());
}
