//! What the tool does to small files built here: seams split with every attribute following,
//! shared accessors left alone, existing tangents kept, other folders, the normal texture's set.

mod common;

use common::document::Doc;
use common::fixture::Fixture;
use common::tool;
use serde_json::json;

/// The mirrored quad with a skin, colours (3 bytes: padded), a morph target and a LINES
/// primitive that shares its POSITION accessor.
fn rich_quad() -> Fixture {
    let mut f = Fixture::mirrored_quad();
    let joints = f.accessor(
        &[0, 1, 0, 0, 1, 0, 0, 0, 2, 1, 0, 0, 3, 0, 0, 0],
        5121,
        "VEC4",
        4,
        json!({}),
    );
    let weights = f.floats(
        &[
            [1.0f32, 0.0, 0.0, 0.0],
            [0.5, 0.5, 0.0, 0.0],
            [0.25, 0.75, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
        ],
        "VEC4",
        false,
    );
    let colours = f.accessor(
        &[255, 0, 0, 0, 255, 0, 0, 0, 255, 9, 9, 9],
        5121,
        "VEC3",
        4,
        json!({ "normalized": true }),
    );
    let morph = f.floats(
        &[[0.0f32, 0.0, 1.0], [0.0, 0.0, 2.0], [0.0, 0.0, 3.0], [0.0, 0.0, 4.0]],
        "VEC3",
        true,
    );
    let attributes = &mut f.primitive(0)["attributes"];
    attributes["JOINTS_0"] = json!(joints);
    attributes["WEIGHTS_0"] = json!(weights);
    attributes["COLOR_0"] = json!(colours);
    f.primitive(0)["targets"] = json!([{ "POSITION": morph }]);
    let position = f.primitive(0)["attributes"]["POSITION"].clone();
    let lines = f.u16_indices(&[0, 1, 1, 2]);
    f.json["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "attributes": { "POSITION": position }, "indices": lines, "mode": 1 }));
    f
}

#[test]
fn a_mirror_seam_is_split_and_every_attribute_follows() {
    let dir = tool::fresh_dir("seam");
    let input = rich_quad().write_glb(&dir, "quad");
    let output = dir.join("out.glb");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    assert!(result.status.success());
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(stdout.contains("1 primitive done, 2 vertices added"), "{stdout}");
    assert!(
        stdout.contains("mesh 0 primitive 1: mode LINES, not TRIANGLES"),
        "{stdout}"
    );

    let (before, after) = (Doc::open(&input), Doc::open(&output));
    // The lines primitive and every accessor it reads are as they were.
    assert_eq!(before.primitive_json(0, 1), after.primitive_json(0, 1));
    let lines = before.primitive_json(0, 1);
    for accessor in [&lines["attributes"]["POSITION"], &lines["indices"]] {
        let a = accessor.as_u64().unwrap() as usize;
        assert_eq!(before.json["accessors"][a], after.json["accessors"][a]);
        assert_eq!(before.elements(a), after.elements(a));
    }
    // The accessors the split replaced are gone: every one left is read by a primitive.
    let mut read = std::collections::BTreeSet::new();
    for primitive in after.json["meshes"][0]["primitives"].as_array().unwrap() {
        let maps = [&primitive["attributes"], &primitive["targets"][0]];
        let values = maps
            .into_iter()
            .flat_map(|map| map.as_object().into_iter().flat_map(|m| m.values()));
        read.extend(values.chain([&primitive["indices"]]).filter_map(|a| a.as_u64()));
    }
    let count = after.json["accessors"].as_array().unwrap().len() as u64;
    assert_eq!(read, (0..count).collect(), "the accessors read");

    // Six vertices now, every attribute and the target copied; indices still 16-bit.
    let (old_corners, new_corners) = (before.corners(0, 0, 0), after.corners(0, 0, 0));
    assert_eq!(new_corners.positions.len(), 6);
    for name in ["POSITION", "NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0", "COLOR_0"] {
        let (old, new) = (
            before.elements(before.attribute(0, 0, name).unwrap()),
            after.elements(after.attribute(0, 0, name).unwrap()),
        );
        assert_eq!(new.len(), 6, "{name}");
        for (&i, &j) in old_corners.indices.iter().zip(&new_corners.indices) {
            assert_eq!(old[i as usize], new[j as usize], "{name}");
        }
    }
    let morph = |doc: &Doc| doc.elements(doc.primitive_json(0, 0)["targets"][0]["POSITION"].as_u64().unwrap() as usize);
    let (old, new) = (morph(&before), morph(&after));
    for (&i, &j) in old_corners.indices.iter().zip(&new_corners.indices) {
        assert_eq!(old[i as usize], new[j as usize], "morph target");
    }
    let indices = after.primitive_json(0, 0)["indices"].as_u64().unwrap() as usize;
    assert_eq!(after.json["accessors"][indices]["componentType"], 5123);

    // Each corner carries its own triangle's handedness. glTF's V points down, so the first
    // triangle (V growing along +y as stored) is left-handed and the mirrored one right-handed.
    let tangents = new_corners.tangents.unwrap();
    for (c, &v) in new_corners.indices.iter().enumerate() {
        let w = if c < 3 { -1.0 } else { 1.0 };
        assert_eq!(tangents[v as usize][3], w, "corner {c}");
    }
    // Padded colours: a 3-byte element on a 4-byte stride.
    let colours = after.attribute(0, 0, "COLOR_0").unwrap();
    let view = after.json["accessors"][colours]["bufferView"].as_u64().unwrap() as usize;
    assert_eq!(after.json["bufferViews"][view]["byteStride"], 4);
    assert_eq!(after.json["extras"], json!({ "kept": [1, 2.5, "three"] }));
}

#[test]
fn existing_tangents_are_kept_unless_overwrite_and_incomplete_primitives_are_listed() {
    let dir = tool::fresh_dir("kept");
    let mut f = Fixture::mirrored_quad();
    let tangent = f.floats(&[[0.0f32, 1.0, 0.0, 1.0]; 4], "VEC4", false);
    f.primitive(0)["attributes"]["TANGENT"] = json!(tangent);
    let position = f.primitive(0)["attributes"]["POSITION"].clone();
    let texcoord = f.primitive(0)["attributes"]["TEXCOORD_0"].clone();
    let indices = f.primitive(0)["indices"].clone();
    f.json["meshes"][0]["primitives"].as_array_mut().unwrap().push(json!({
        "attributes": { "POSITION": position, "TEXCOORD_0": texcoord }, "indices": indices
    }));
    let input = f.write_gltf(&dir, "quad");

    let kept = dir.join("kept.gltf");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), kept.as_os_str()]);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success());
    assert!(stdout.contains("0 primitives done, 0 vertices added"), "{stdout}");
    assert!(
        stdout.contains("mesh 0 primitive 0: has TANGENT, kept (--overwrite replaces it)"),
        "{stdout}"
    );
    assert!(stdout.contains("mesh 0 primitive 1: no NORMAL"), "{stdout}");
    assert_eq!(Doc::open(&kept).json["meshes"], Doc::open(&input).json["meshes"]);

    let replaced = dir.join("replaced.gltf");
    let result = tool::run([
        input.as_os_str(),
        "--overwrite".as_ref(),
        "-o".as_ref(),
        replaced.as_os_str(),
    ]);
    assert!(String::from_utf8_lossy(&result.stdout).contains("1 primitive done, 2 vertices added"));
    let after = Doc::open(&replaced);
    assert_ne!(after.attribute(0, 0, "TANGENT"), Some(tangent));
    assert!(dir.join("replaced.tangents.bin").is_file());
}

#[test]
fn a_gltf_written_to_another_folder_still_finds_its_buffers_and_images() {
    let dir = tool::fresh_dir("folders");
    let source = dir.join("source");
    std::fs::create_dir_all(source.join("textures")).unwrap();
    // Its lines primitive keeps reading the input's buffer.
    let mut f = rich_quad();
    f.json["images"] = json!([{ "uri": "textures/normal%20map.png" }]);
    let input = f.write_gltf(&source, "quad");
    std::fs::write(source.join("textures/normal map.png"), b"not really a png").unwrap();

    let out_dir = dir.join("elsewhere/deeper");
    let result = tool::run([input.as_os_str(), "--out-dir".as_ref(), out_dir.as_os_str()]);
    assert!(result.status.success());
    assert_eq!(tool::listing(&out_dir), ["quad.gltf", "quad.tangents.bin"]);
    let after = Doc::open(&out_dir.join("quad.gltf"));
    assert_eq!(after.json["buffers"][0]["uri"], "../../source/quad.bin");
    assert_eq!(after.json["buffers"][1]["uri"], "quad.tangents.bin");
    assert_eq!(after.json["images"][0]["uri"], "../../source/textures/normal%20map.png");
    assert_eq!(after.corners(0, 0, 0).positions.len(), 6);
}

#[test]
fn the_normal_texture_chooses_the_texture_coordinates() {
    let dir = tool::fresh_dir("texcoord");
    let mut f = Fixture::mirrored_quad();
    // TEXCOORD_1 is not mirrored, so nothing is split when the normal texture reads it.
    let plain = f.floats(&[[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], "VEC2", false);
    f.primitive(0)["attributes"]["TEXCOORD_1"] = json!(plain);
    f.primitive(0)["material"] = json!(0);
    f.json["materials"] = json!([{ "normalTexture": { "index": 0, "texCoord": 1 } }]);
    f.json["textures"] = json!([{ "source": 0 }]);
    f.json["images"] = json!([{ "uri": "n.png" }]);
    let input = f.write_glb(&dir, "quad");
    let output = dir.join("out.glb");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    assert!(String::from_utf8_lossy(&result.stdout).contains("1 primitive done, 0 vertices added"));
    let after = Doc::open(&output);
    let tangents = after.corners(0, 0, 1).tangents.unwrap();
    assert!(tangents.iter().all(|t| *t == [1.0, 0.0, 0.0, -1.0]), "{tangents:?}");
}

#[test]
fn policy_legacy_needs_a_method_with_a_legacy_form() {
    let dir = tool::fresh_dir("legacy-form");
    let input = Fixture::mirrored_quad().write_gltf(&dir, "quad");
    let output = dir.join("out.gltf");
    let refused = tool::run([
        input.as_os_str(),
        "--method".as_ref(),
        "angle".as_ref(),
        "--policy".as_ref(),
        "legacy".as_ref(),
        "-o".as_ref(),
        output.as_os_str(),
    ]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{stderr}");
    assert!(stderr.contains("method Angle has no legacy form"), "{stderr}");
    assert!(!output.exists(), "written despite the refusal");
    let listing = tool::run([
        input.as_os_str(),
        "--method".as_ref(),
        "lengyel".as_ref(),
        "--policy".as_ref(),
        "legacy".as_ref(),
        "-o".as_ref(),
        output.as_os_str(),
    ]);
    assert!(listing.status.success(), "{}", String::from_utf8_lossy(&listing.stderr));
}
