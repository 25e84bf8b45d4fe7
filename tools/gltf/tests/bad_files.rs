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

/// A quad in `in/` whose buffer `quad.bin` lies in the folder `secret/` beside it, named by the
/// URI `uri` gives for that file's path.
#[cfg(unix)]
fn reaching_out(test: &str, uri: impl Fn(&Path) -> String) -> (PathBuf, PathBuf) {
    let (input, output) = folders(test);
    let secret = input.parent().unwrap().join("secret");
    std::fs::create_dir_all(&secret).unwrap();
    let file = Fixture::mirrored_quad().write_gltf(&input, "quad");
    let buffer = secret.join("quad.bin");
    std::fs::rename(input.join("quad.bin"), &buffer).unwrap();
    let mut json: serde_json::Value = serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
    json["buffers"][0]["uri"] = json!(uri(&buffer));
    std::fs::write(&file, serde_json::to_vec(&json).unwrap()).unwrap();
    (file, output)
}

/// A way out of the input's folder: the URI that takes it to the buffer (making the link it goes
/// through), and whether `--allow-outside-uris` makes it readable.
#[cfg(unix)]
struct WayOut {
    name: &'static str,
    uri: fn(&Path) -> String,
    readable: bool,
}

#[cfg(unix)]
const WAYS_OUT: [WayOut; 4] = [
    WayOut {
        name: "dotdot",
        uri: |_| "../secret/quad.bin".to_string(),
        readable: true,
    },
    WayOut {
        name: "absolute",
        uri: |buffer| buffer.display().to_string(),
        readable: true,
    },
    WayOut {
        name: "file-scheme",
        uri: |buffer| format!("file://{}", buffer.display()),
        readable: false,
    },
    WayOut {
        name: "symlink",
        uri: |buffer| {
            let link = buffer.parent().unwrap().parent().unwrap().join("in/link.bin");
            std::os::unix::fs::symlink(buffer, link).unwrap();
            "link.bin".to_string()
        },
        readable: true,
    },
];

#[cfg(unix)]
#[test]
fn buffers_outside_the_folder_are_refused() {
    for way in WAYS_OUT {
        let (input, output) = reaching_out(&format!("outside-{}", way.name), way.uri);
        if way.readable {
            refused(&input, &output, "buffer 0: its uri");
            refused(
                &input,
                &output,
                "outside the file's folder; --allow-outside-uris accepts it",
            );
        } else {
            // The flag would not make it readable: the message does not offer it.
            refused(&input, &output, "buffer 0: cannot load file://");
            refused(&input, &output, "only files and data URIs");
            let out = output.join("quad.gltf");
            let stderr = tool::run([input.as_os_str(), "-o".as_ref(), out.as_os_str()]).stderr;
            assert!(!String::from_utf8_lossy(&stderr).contains("--allow-outside-uris"));
        }
    }
}

#[cfg(unix)]
#[test]
fn allow_outside_uris_reads_them() {
    for way in WAYS_OUT {
        let (input, output) = reaching_out(&format!("allowed-{}", way.name), way.uri);
        let out = output.join("quad.gltf");
        let result = tool::run([
            input.as_os_str(),
            "--allow-outside-uris".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ]);
        assert_eq!(result.status.success(), way.readable, "{}", way.name);
        if !way.readable {
            // No scheme but data: is ever read.
            assert!(String::from_utf8_lossy(&result.stderr).contains("only files and data URIs"));
        }
    }
}

#[cfg(unix)]
#[test]
fn a_link_to_a_folder_that_leads_out_is_refused() {
    let (input, output) = reaching_out("outside-linked-folder", |buffer| {
        let link = buffer.parent().unwrap().parent().unwrap().join("in/shared");
        std::os::unix::fs::symlink(buffer.parent().unwrap(), link).unwrap();
        "shared/quad.bin".to_string()
    });
    refused(&input, &output, "goes through a link, outside the file's folder");
}

#[test]
fn an_image_outside_the_folder_is_refused() {
    let (input, output) = folders("outside-image");
    let mut fixture = Fixture::mirrored_quad();
    fixture.json["images"] = json!([{ "uri": "textures/../../n.png" }]);
    let file = fixture.write_gltf(&input, "image");
    refused(
        &file,
        &output,
        "image 0: its uri \"textures/../../n.png\" climbs out with ..",
    );
}

/// An image URI with a scheme is never read (images are not), but the output would point at it:
/// refused, and with `--allow-outside-uris` kept as it was.
#[test]
fn an_image_with_a_scheme_is_refused_unless_allowed() {
    let uri = "https://example.com/n.png";
    let (input, output) = folders("image-scheme");
    let mut fixture = Fixture::mirrored_quad();
    fixture.json["images"] = json!([{ "uri": uri }]);
    let file = fixture.write_gltf(&input, "image");
    refused(
        &file,
        &output,
        "image 0: its uri \"https://example.com/n.png\" has a scheme",
    );
    let out = output.join("image.gltf");
    let result = tool::run([
        file.as_os_str(),
        "--allow-outside-uris".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let written: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(written["images"][0]["uri"], json!(uri));
}

#[test]
fn an_accessor_offset_that_wraps_around() {
    let (input, output) = folders("offset-wraps");
    let mut fixture = Fixture::mirrored_quad();
    // Offset + the last element's end passes 2^64: unchecked, it would wrap past the bounds check.
    fixture.json["accessors"][1]["byteOffset"] = json!(u64::MAX - 15);
    let file = fixture.write_glb(&input, "wraps");
    refused(&file, &output, "accessor 1: too large");
}

/// The mirrored quad whose indices are `count` zeros: an accessor without a bufferView (sparse,
/// with one substitution, so that it stays valid), a few bytes of JSON whatever `count` is.
fn quad_with_zero_indices(count: u64) -> Fixture {
    let mut fixture = Fixture::mirrored_quad();
    let indices = fixture.primitive(0)["indices"].as_u64().unwrap() as usize;
    let accessor = &mut fixture.json["accessors"][indices];
    let view = accessor.as_object_mut().unwrap().remove("bufferView").unwrap();
    accessor["count"] = json!(count);
    accessor["sparse"] = json!({
        "count": 1,
        "indices": { "bufferView": view, "componentType": 5123 },
        "values": { "bufferView": view },
    });
    fixture
}

#[test]
fn a_huge_accessor_without_data() {
    let (input, output) = folders("zeros");
    // One element past the limit of 16 Mi, and 2 TB of zeros.
    for count in [(1u64 << 24) + 1, 1 << 40] {
        let file = quad_with_zero_indices(count).write_gltf(&input, &format!("zeros-{count}"));
        refused(
            &file,
            &output,
            &format!("accessor 3: {count} elements without a bufferView"),
        );
    }
}

#[test]
fn contents_not_of_the_kind_the_name_says() {
    let (input, output) = folders("kind");
    let json = Fixture::mirrored_quad().write_gltf(&input, "json");
    let named_glb = input.join("json.glb");
    std::fs::rename(&json, &named_glb).unwrap();
    refused(&named_glb, &output, "its name says .glb but it holds a .gltf file");
    let glb = Fixture::mirrored_quad().write_glb(&input, "binary");
    let named_gltf = input.join("binary.gltf");
    std::fs::rename(&glb, &named_gltf).unwrap();
    refused(&named_gltf, &output, "its name says .gltf but it holds a .glb file");
}

#[test]
fn a_failed_file_leaves_no_output_folder() {
    let (input, output) = folders("no-folder");
    let missing = input.join("missing.glb");
    let nested = output.join("new").join("folder");
    let result = tool::run([missing.as_os_str(), "-o".as_ref(), nested.join("x.glb").as_os_str()]);
    assert_eq!(result.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&result.stderr).contains("cannot read it"));
    let result = tool::run([missing.as_os_str(), "--out-dir".as_ref(), nested.as_os_str()]);
    assert_eq!(result.status.code(), Some(1));
    assert_eq!(tool::listing(&output), Vec::<String>::new(), "no folder made");
}

/// A file whose counts need more memory than the process may have fails with a message, not an
/// abort: 16 Mi indices of zeros (the most read without a bufferView) from a few bytes of JSON,
/// about 1 GB of working memory, under a limit of 256 MiB of address space.
#[cfg(target_os = "linux")]
#[test]
fn a_file_that_needs_more_memory_than_the_system_gives() {
    let (input, output) = folders("memory");
    let file = quad_with_zero_indices((1 << 24) - 1).write_glb(&input, "memory");
    let result = std::process::Command::new("sh")
        .args(["-c", "ulimit -v 262144 && exec \"$0\" \"$@\""])
        .arg(env!("CARGO_BIN_EXE_tbasis-gltf"))
        .args(["--jobs".as_ref(), "1".as_ref(), file.as_os_str(), "-o".as_ref()])
        .arg(output.join("memory.glb"))
        .output()
        .expect("sh starts");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "exit status: {stderr}");
    assert!(
        stderr.contains("memory.glb") && stderr.contains("memory for"),
        "{stderr}"
    );
    assert_eq!(tool::listing(&output), Vec::<String>::new(), "nothing written");
}
