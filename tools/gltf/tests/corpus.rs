//! The tool on every glTF and GLB file of the mesh corpus (`../shared/meshes/`, README: "Test
//! corpus"), run once with `--overwrite` so that every eligible primitive is recomputed:
//! tangents equal mikktspace.c's per corner except where the summary counts a repair, everything
//! else is preserved, a second run on the output changes nothing, and the Khronos glTF Validator
//! finds no error or warning the input did not have.

mod common;

use std::collections::{BTreeSet, HashSet};
use std::path::PathBuf;
use std::sync::OnceLock;

use common::document::{normal_texcoord_set, Doc};
use common::{load, mikktspace_reference, needs, tool, validator};
use serde_json::Value;

/// The tool's run over the corpus, shared by the tests of this file.
struct Converted {
    /// (input, output) per file.
    files: Vec<(PathBuf, PathBuf)>,
    stdout: String,
}

/// Every glTF and GLB of the manifest. The 849k-vertex FlightHelmet.cc1.glb only in release
/// builds: in a debug build the tool alone takes about 16 s on it, and the reference, the reads
/// and the validator several times that.
fn corpus_files() -> Vec<PathBuf> {
    let dir = needs::corpus_dir();
    let rows = load::read_manifest(&dir).expect("MANIFEST.tsv");
    rows.iter()
        .filter(|row| row.format == "gltf" || row.format == "glb")
        .filter(|row| !cfg!(debug_assertions) || row.vertices < 500_000)
        .map(|row| dir.join(&row.path))
        .collect()
}

fn converted() -> &'static Converted {
    static CONVERTED: OnceLock<Converted> = OnceLock::new();
    CONVERTED.get_or_init(|| {
        let inputs = corpus_files();
        let out_dir = tool::fresh_dir("corpus");
        let output = tool::run(
            ["--overwrite".as_ref(), "--out-dir".as_ref(), out_dir.as_os_str()]
                .into_iter()
                .chain(inputs.iter().map(|p| p.as_os_str())),
        );
        assert!(output.status.success(), "the tool failed on the corpus");
        let files = inputs
            .iter()
            .map(|input| (input.clone(), out_dir.join(input.file_name().expect("a file name"))))
            .collect();
        Converted {
            files,
            stdout: String::from_utf8(output.stdout).expect("UTF-8"),
        }
    })
}

/// Whether the tool gave primitive `(m, p)` a new TANGENT: the summary does not list it as left
/// alone (the accessor's number may be the old one's: a new item takes a removed one's place).
fn processed(input: &Doc, output: &Doc, m: usize, p: usize) -> bool {
    output.attribute(m, p, "TANGENT").is_some()
        && !tool::left_primitives(&converted().stdout, &input.path).contains(&(m, p))
}

/// Primitives drawing the same accessors with the same texture coordinates are computed once.
fn geometry_key(json: &Value, primitive: &Value) -> String {
    let mut attributes = primitive["attributes"].clone();
    if let Some(map) = attributes.as_object_mut() {
        map.remove("TANGENT");
    }
    format!(
        "{attributes} {} {} {}",
        primitive["indices"],
        primitive["targets"],
        normal_texcoord_set(json, primitive)
    )
}

#[test]
fn tangents_equal_mikktspace_c_per_corner_except_repaired_ones() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let converted = converted();
    let mut checked_corners = 0;
    for (input_path, output_path) in &converted.files {
        let (input, output) = (Doc::open(input_path), Doc::open(output_path));
        let mut differing = 0;
        let mut seen = HashSet::new();
        for (m, mesh) in input.json["meshes"].as_array().into_iter().flatten().enumerate() {
            for (p, primitive) in mesh["primitives"].as_array().into_iter().flatten().enumerate() {
                if !processed(&input, &output, m, p) || !seen.insert(geometry_key(&input.json, primitive)) {
                    continue;
                }
                let set = normal_texcoord_set(&input.json, primitive);
                let (before, after) = (input.corners(m, p, set), output.corners(m, p, set));
                let reference = mikktspace_reference::reference_corners(
                    &before.positions,
                    &before.normals,
                    &before.texcoords,
                    Some(&before.indices),
                    true,
                )
                .unwrap_or_else(|| {
                    panic!(
                        "{}: mikktspace.c failed on mesh {m} primitive {p}",
                        input_path.display()
                    )
                });
                let tangents = after.tangents.expect("TANGENT");
                assert_eq!(
                    after.indices.len(),
                    before.indices.len(),
                    "{}: corner count",
                    output_path.display()
                );
                for (c, &vertex) in after.indices.iter().enumerate() {
                    let t = tangents[vertex as usize];
                    let length = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                    assert!(
                        (length - 1.0).abs() < 1e-4 && (t[3] == 1.0 || t[3] == -1.0),
                        "{}: mesh {m} primitive {p} corner {c}: {t:?} is no valid tangent",
                        output_path.display()
                    );
                    if t.map(f32::to_bits) != reference[c].map(f32::to_bits) {
                        differing += 1;
                    }
                }
                checked_corners += after.indices.len();
            }
        }
        assert_eq!(
            differing,
            tool::repaired_corners(&converted.stdout, input_path),
            "{}: corners that differ from mikktspace.c against corners the summary says were repaired",
            input_path.display()
        );
    }
    assert!(checked_corners > 100_000, "only {checked_corners} corners checked");
}

#[test]
fn everything_but_the_new_tangents_is_preserved() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    for (input_path, output_path) in &converted().files {
        let (input, output) = (Doc::open(input_path), Doc::open(output_path));
        let what = output_path.display();
        check_document(&input, &output);
        for (m, mesh) in input.json["meshes"].as_array().into_iter().flatten().enumerate() {
            for (p, before) in mesh["primitives"].as_array().into_iter().flatten().enumerate() {
                let after = output.primitive_json(m, p);
                if !processed(&input, &output, m, p) {
                    assert_eq!(before, after, "{what}: mesh {m} primitive {p} was left alone");
                    continue;
                }
                check_primitive(&input, &output, m, p);
            }
        }
    }
}

/// Everything outside the meshes, accessors, bufferViews, buffers and images is unchanged; those
/// only grow, and URIs still name the same files.
fn check_document(input: &Doc, output: &Doc) {
    let what = output.path.display();
    let changed = ["accessors", "bufferViews", "buffers", "meshes", "images"];
    let (before, after) = (input.json.as_object().unwrap(), output.json.as_object().unwrap());
    for (key, value) in before {
        if !changed.contains(&key.as_str()) {
            assert_eq!(Some(value), after.get(key), "{what}: {key}");
        }
    }
    for key in after.keys() {
        assert!(
            before.contains_key(key) || changed.contains(&key.as_str()),
            "{what}: new {key}"
        );
    }
    // An existing item stays in its place, unless only what the tool replaced used it: then it is
    // removed, and another (mostly a new one) may take its place.
    let replaced = replaced_items(input, output);
    for (k, key) in ["accessors", "bufferViews"].into_iter().enumerate() {
        let (old, new) = (before[key].as_array().unwrap(), after[key].as_array().unwrap());
        for (i, item) in old.iter().enumerate() {
            assert!(
                new.get(i) == Some(item) || replaced[k].contains(&i),
                "{what}: {key}[{i}] changed"
            );
        }
    }
    for key in ["buffers", "images"] {
        let Some(old) = before.get(key).and_then(Value::as_array) else {
            continue;
        };
        let new = after[key].as_array().unwrap();
        // Buffers keep their order when one is removed.
        let kept = old
            .iter()
            .enumerate()
            .filter(|(i, _)| key != "buffers" || !replaced[2].contains(i));
        for ((i, old), new) in kept.zip(new) {
            for (field, value) in old.as_object().unwrap() {
                match (field.as_str(), value.as_str()) {
                    ("uri", Some(uri)) if !uri.starts_with("data:") => assert_eq!(
                        input.resolve(uri),
                        output.resolve(new["uri"].as_str().unwrap()),
                        "{what}: {key}[{i}] names another file"
                    ),
                    ("byteLength", _) => assert!(new[field].as_u64() >= value.as_u64(), "{what}: {key}[{i}]"),
                    _ => assert_eq!(Some(value), new.get(field), "{what}: {key}[{i}].{field}"),
                }
            }
        }
    }
    let (old, new) = (
        before["meshes"].as_array().unwrap(),
        after["meshes"].as_array().unwrap(),
    );
    assert_eq!(old.len(), new.len(), "{what}: meshes");
    for (old, new) in old.iter().zip(new) {
        for (field, value) in old.as_object().unwrap() {
            if field != "primitives" {
                assert_eq!(Some(value), new.get(field), "{what}: mesh {field}");
            }
        }
        assert_eq!(
            old["primitives"].as_array().unwrap().len(),
            new["primitives"].as_array().unwrap().len()
        );
    }
}

/// The accessors, bufferViews and buffers of the input that only processed primitives used: the
/// tool replaced them by copies (or by a new TANGENT), so it may remove them.
fn replaced_items(input: &Doc, output: &Doc) -> [HashSet<usize>; 3] {
    let json = &input.json;
    let mut users: Vec<Vec<bool>> = vec![Vec::new(); json["accessors"].as_array().map_or(0, Vec::len)];
    for (m, mesh) in json["meshes"].as_array().into_iter().flatten().enumerate() {
        for (p, primitive) in mesh["primitives"].as_array().into_iter().flatten().enumerate() {
            let done = processed(input, output, m, p);
            let maps =
                std::iter::once(&primitive["attributes"]).chain(primitive["targets"].as_array().into_iter().flatten());
            let indices = maps.flat_map(|map| map.as_object().into_iter().flatten().map(|(_, a)| a));
            for accessor in indices.chain(primitive.get("indices")) {
                users[accessor.as_u64().unwrap() as usize].push(done);
            }
        }
    }
    let mut elsewhere = HashSet::new();
    for skin in json["skins"].as_array().into_iter().flatten() {
        elsewhere.extend(skin["inverseBindMatrices"].as_u64());
    }
    for animation in json["animations"].as_array().into_iter().flatten() {
        for sampler in animation["samplers"].as_array().into_iter().flatten() {
            elsewhere.extend(
                [&sampler["input"], &sampler["output"]]
                    .into_iter()
                    .filter_map(Value::as_u64),
            );
        }
    }
    let accessors: HashSet<usize> = (0..users.len())
        .filter(|&a| !users[a].is_empty() && users[a].iter().all(|&done| done) && !elsewhere.contains(&(a as u64)))
        .collect();
    let mut view_users: Vec<Vec<bool>> = vec![Vec::new(); json["bufferViews"].as_array().map_or(0, Vec::len)];
    for (a, accessor) in json["accessors"].as_array().into_iter().flatten().enumerate() {
        let sparse = &accessor["sparse"];
        for view in [
            &accessor["bufferView"],
            &sparse["indices"]["bufferView"],
            &sparse["values"]["bufferView"],
        ] {
            if let Some(view) = view.as_u64() {
                view_users[view as usize].push(accessors.contains(&a));
            }
        }
    }
    for image in json["images"].as_array().into_iter().flatten() {
        if let Some(view) = image["bufferView"].as_u64() {
            view_users[view as usize].push(false);
        }
    }
    let views: HashSet<usize> = (0..view_users.len())
        .filter(|&v| !view_users[v].is_empty() && view_users[v].iter().all(|&removable| removable))
        .collect();
    let mut buffer_users: Vec<Vec<bool>> = vec![Vec::new(); json["buffers"].as_array().map_or(0, Vec::len)];
    for (v, view) in json["bufferViews"].as_array().into_iter().flatten().enumerate() {
        buffer_users[view["buffer"].as_u64().unwrap() as usize].push(views.contains(&v));
    }
    let buffers = (0..buffer_users.len())
        .filter(|&b| !buffer_users[b].is_empty() && buffer_users[b].iter().all(|&removable| removable))
        .collect();
    [accessors, views, buffers]
}

/// A processed primitive: the same fields and attributes plus TANGENT, every attribute and
/// target of one count, and every corner reading exactly the bytes it read before.
fn check_primitive(input: &Doc, output: &Doc, m: usize, p: usize) {
    let what = format!("{}: mesh {m} primitive {p}", output.path.display());
    let (before, after) = (input.primitive_json(m, p), output.primitive_json(m, p));
    for (field, value) in before.as_object().unwrap() {
        if !["attributes", "indices", "targets"].contains(&field.as_str()) {
            assert_eq!(Some(value), after.get(field), "{what}: {field}");
        }
    }
    let names = |v: &Value| {
        v.as_object()
            .map(|o| o.keys().cloned().collect::<BTreeSet<_>>())
            .unwrap_or_default()
    };
    let mut expected = names(&before["attributes"]);
    expected.insert("TANGENT".into());
    assert_eq!(expected, names(&after["attributes"]), "{what}: attribute names");
    let targets = |v: &Value| v["targets"].as_array().map(|t| t.iter().map(names).collect::<Vec<_>>());
    assert_eq!(targets(before), targets(after), "{what}: morph targets");

    let vertex_count = output.count(output.attribute(m, p, "POSITION").unwrap());
    let all_after = after["attributes"].as_object().unwrap().values().chain(
        after["targets"]
            .as_array()
            .into_iter()
            .flatten()
            .flat_map(|t| t.as_object().unwrap().values()),
    );
    for accessor in all_after {
        assert_eq!(
            output.count(accessor.as_u64().unwrap() as usize),
            vertex_count,
            "{what}: counts"
        );
    }

    // Each corner reads what it read before, in every attribute and morph target.
    let set = normal_texcoord_set(&input.json, before);
    let (old_corners, new_corners) = (input.corners(m, p, set).indices, output.corners(m, p, set).indices);
    let pairs = before["attributes"]
        .as_object()
        .unwrap()
        .iter()
        .filter(|(name, _)| name.as_str() != "TANGENT")
        .map(|(name, old)| (name.clone(), old.clone(), after["attributes"][name].clone()))
        .chain(
            before["targets"]
                .as_array()
                .into_iter()
                .flatten()
                .enumerate()
                .flat_map(|(k, target)| {
                    target.as_object().unwrap().iter().map(move |(name, old)| {
                        (
                            format!("target {k} {name}"),
                            old.clone(),
                            after["targets"][k][name].clone(),
                        )
                    })
                }),
        );
    for (name, old, new) in pairs {
        let (old, new) = (
            input.elements(old.as_u64().unwrap() as usize),
            output.elements(new.as_u64().unwrap() as usize),
        );
        for (c, (&i, &j)) in old_corners.iter().zip(&new_corners).enumerate() {
            assert_eq!(old[i as usize], new[j as usize], "{what}: {name} at corner {c}");
        }
    }

    // Indices keep their 16-bit type where the vertices still fit it.
    if let (Some(old), Some(new)) = (before["indices"].as_u64(), after["indices"].as_u64()) {
        let kind = |doc: &Doc, i: u64| doc.json["accessors"][i as usize]["componentType"].as_u64().unwrap();
        if kind(input, old) == 5123 && vertex_count < 65535 {
            assert_eq!(kind(output, new), 5123, "{what}: index type");
        }
    }
}

#[test]
fn a_second_run_without_overwrite_writes_the_same_bytes() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    // `--check` on every output at once: nothing would change. A `.gltf` written to another folder
    // refers back to its buffers and images with `../`, which only that flag lets the tool read.
    let outputs = converted().files.iter().map(|(_, output)| output.as_os_str());
    let flags = ["--check".as_ref(), "--allow-outside-uris".as_ref()];
    let check = tool::run(flags.into_iter().chain(outputs));
    assert_eq!(
        check.status.code(),
        Some(0),
        "--check finds something to change in the outputs"
    );
    for (_, output) in &converted().files {
        let name = output.file_name().unwrap().to_string_lossy();
        // The same folder, so that relative URIs stay as they are.
        let again = output.with_file_name(format!("again.{name}"));
        // The output refers to the input's buffers, outside its own folder.
        let result = tool::run([
            output.as_os_str(),
            "--allow-outside-uris".as_ref(),
            "-o".as_ref(),
            again.as_os_str(),
        ]);
        assert!(result.status.success());
        assert!(
            String::from_utf8_lossy(&result.stdout).contains(": 0 primitives done, 0 vertices added"),
            "{}: the second run changed primitives",
            output.display()
        );
        let (first, second) = (std::fs::read(output).unwrap(), std::fs::read(&again).unwrap());
        assert!(
            first == second,
            "{}: the second run wrote other bytes",
            output.display()
        );
        let stem = again.file_stem().unwrap().to_string_lossy().into_owned();
        assert!(
            !again.with_file_name(format!("{stem}.tangents.bin")).exists(),
            "{}: the second run wrote a buffer",
            output.display()
        );
    }
}

#[test]
fn outputs_pass_the_validator_with_no_issue_the_input_lacked() {
    if !(needs::CORPUS.found_or_skip() && needs::GLTF_VALIDATOR.found_or_skip()) {
        return;
    }
    let mut failures = Vec::new();
    for (input, output) in &converted().files {
        let new = validator::new_issues(&validator::issues(input), &validator::issues(output));
        if !new.is_empty() {
            failures.push(format!("{}:\n  {}", output.display(), new.join("\n  ")));
        }
    }
    assert!(failures.is_empty(), "new validator issues:\n{}", failures.join("\n"));
}

#[test]
fn a_second_issue_of_a_code_the_input_had_is_new() {
    let issue = |code: &str, pointer: &str| validator::Issue {
        code: code.into(),
        severity: 0,
        pointer: pointer.into(),
        message: String::new(),
    };
    let before = [issue("IO_ERROR", "/buffers/0")];
    let after = [issue("IO_ERROR", "/buffers/0"), issue("IO_ERROR", "/buffers/1")];
    assert_eq!(validator::new_issues(&before, &before), Vec::<String>::new());
    assert_eq!(validator::new_issues(&before, &after).len(), 2);
    assert_eq!(validator::new_issues(&[], &before).len(), 1);
}
