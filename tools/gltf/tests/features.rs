//! What the tool does to small files built here: seams split with every attribute following,
//! shared accessors left alone, existing tangents kept, other folders, the normal texture's set.

mod common;

use base64::Engine;
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
    // The stored tangents are replaced by those of the same quad without them, corner by corner.
    let fresh_input = Fixture::mirrored_quad().write_gltf(&dir, "fresh");
    let fresh = dir.join("fresh-out.gltf");
    assert!(tool::run([fresh_input.as_os_str(), "-o".as_ref(), fresh.as_os_str()])
        .status
        .success());
    let per_corner = |file: &std::path::Path| {
        let corners = Doc::open(file).corners(0, 0, 0);
        let tangents = corners.tangents.expect("TANGENT");
        corners
            .indices
            .iter()
            .map(|&v| tangents[v as usize])
            .collect::<Vec<_>>()
    };
    let replaced_tangents = per_corner(&replaced);
    assert_eq!(replaced_tangents, per_corner(&fresh));
    assert!(
        replaced_tangents.iter().any(|t| *t != [0.0, 1.0, 0.0, 1.0]),
        "{replaced_tangents:?}"
    );
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

    // KHR_texture_transform's texCoord overrides the texture's: set 1 again, though it says 0.
    f.json["materials"][0]["normalTexture"] = json!({
        "index": 0, "texCoord": 0, "extensions": { "KHR_texture_transform": { "texCoord": 1 } }
    });
    f.json["extensionsUsed"] = json!(["KHR_texture_transform"]);
    let input = f.write_glb(&dir, "transformed");
    let result = tool::run([
        input.as_os_str(),
        "-o".as_ref(),
        dir.join("transformed-out.glb").as_os_str(),
    ]);
    assert!(String::from_utf8_lossy(&result.stdout).contains("1 primitive done, 0 vertices added"));
}

#[test]
fn a_vertex_no_triangle_uses_gets_a_tangent_from_its_normal() {
    let dir = tool::fresh_dir("unused-vertex");
    let mut f = Fixture::mirrored_quad();
    // A fifth vertex, used by no triangle, with a tilted normal.
    let position = f.floats(
        &[
            [0.0f32, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [5.0, 5.0, 5.0],
        ],
        "VEC3",
        true,
    );
    let normal = f.floats(
        &[
            [0.0f32, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.6, 0.8],
        ],
        "VEC3",
        false,
    );
    let texcoord = f.floats(
        &[[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 0.0], [0.0, 0.0]],
        "VEC2",
        false,
    );
    f.primitive(0)["attributes"] = json!({ "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord });
    let input = f.write_glb(&dir, "quad");
    let output = dir.join("out.glb");
    assert!(tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()])
        .status
        .success());
    let after = Doc::open(&output);
    let tangent = after.attribute(0, 0, "TANGENT").expect("TANGENT");
    let element = &after.elements(tangent)[4];
    let [x, y, z, w] = std::array::from_fn(|k| f32::from_le_bytes(element[4 * k..4 * k + 4].try_into().unwrap()));
    assert!(
        ((x * x + y * y + z * z).sqrt() - 1.0).abs() < 1e-5 && w.abs() == 1.0,
        "{x} {y} {z} {w}"
    );
    assert!(
        (0.6 * y + 0.8 * z).abs() < 1e-5,
        "orthogonal to the normal: {x} {y} {z}"
    );
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

/// A 6 x 6 grid, wavy in z, whose UVs mirror at its middle column: what each vertex holds, and
/// its triangles.
struct Grid {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    /// As 16-bit normalized integers; the float layouts store exactly what they decode to.
    texcoords: Vec<[u16; 2]>,
    triangles: Vec<u32>,
}

impl Grid {
    fn new() -> Grid {
        const SIDE: usize = 6;
        let (mut positions, mut normals, mut texcoords, mut triangles) = (vec![], vec![], vec![], vec![]);
        for y in 0..SIDE {
            for x in 0..SIDE {
                let (fx, fy) = (x as f32, y as f32);
                positions.push([fx, fy, (fx * 0.7).sin() * (fy * 0.5).cos()]);
                normals.push([-(fx * 0.3).cos() * 0.4, 0.2, 0.89]);
                let mirrored = x.min(2 * (SIDE / 2) - x);
                texcoords.push([(mirrored * 9000) as u16, (y * 11000 + x * 700) as u16]);
            }
        }
        for y in 0..SIDE - 1 {
            for x in 0..SIDE - 1 {
                let v = (y * SIDE + x) as u32;
                let s = SIDE as u32;
                triangles.extend([v, v + 1, v + s + 1, v, v + s + 1, v + s]);
            }
        }
        Grid {
            positions,
            normals,
            texcoords,
            triangles,
        }
    }

    fn texcoord_floats(&self) -> Vec<[f32; 2]> {
        let decode = |u: u16| f32::from(u) / 65535.0;
        self.texcoords.iter().map(|&[u, v]| [decode(u), decode(v)]).collect()
    }

    /// Every attribute packed in its own bufferView as floats, 16-bit indices.
    fn packed(&self) -> Fixture {
        let mut f = Fixture::empty_primitive();
        let position = f.floats(&self.positions, "VEC3", true);
        let normal = f.floats(&self.normals, "VEC3", false);
        let texcoord = f.floats(&self.texcoord_floats(), "VEC2", false);
        let indices: Vec<u16> = self.triangles.iter().map(|&i| i as u16).collect();
        let indices = f.u16_indices(&indices);
        *f.primitive(0) = json!({ "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord }, "indices": indices, "mode": 4 });
        f
    }

    /// The three attributes interleaved in one bufferView (a 32-byte stride), 32-bit indices.
    fn interleaved(&self) -> Fixture {
        let mut f = Fixture::empty_primitive();
        let texcoords = self.texcoord_floats();
        let mut bytes = Vec::new();
        for ((position, normal), texcoord) in self.positions.iter().zip(&self.normals).zip(&texcoords) {
            let floats = position.iter().chain(normal).chain(texcoord);
            bytes.extend(floats.flat_map(|f| f.to_le_bytes()));
        }
        let view = f.view(&bytes, Some(32));
        let count = self.positions.len();
        let mut accessor = |offset: usize, kind: &str| {
            let accessors = f.json["accessors"].as_array_mut().unwrap();
            accessors.push(json!({ "bufferView": view, "byteOffset": offset, "componentType": 5126, "count": count, "type": kind }));
            accessors.len() - 1
        };
        let (position, normal, texcoord) = (accessor(0, "VEC3"), accessor(12, "VEC3"), accessor(24, "VEC2"));
        let min_max = |k: usize, pick: fn(f32, f32) -> f32| self.positions.iter().map(|p| p[k]).reduce(pick).unwrap();
        f.json["accessors"][position]["min"] = json!([0, 1, 2].map(|k| min_max(k, f32::min)));
        f.json["accessors"][position]["max"] = json!([0, 1, 2].map(|k| min_max(k, f32::max)));
        let indices: Vec<u8> = self.triangles.iter().flat_map(|i| i.to_le_bytes()).collect();
        let indices = f.accessor(&indices, 5125, "SCALAR", self.triangles.len(), json!({}));
        *f.primitive(0) = json!({ "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord }, "indices": indices, "mode": 4 });
        f
    }

    /// What the tool converts: texture coordinates as normalized 16-bit integers, 8-bit indices,
    /// and positions whose vertex 7 is set by a sparse substitution.
    fn converted(&self) -> Fixture {
        let mut f = Fixture::empty_primitive();
        let mut wrong = self.positions.clone();
        wrong[7] = [50.0, -3.0, 8.0];
        let position = f.floats(&wrong, "VEC3", true);
        let values: Vec<u8> = self.positions[7].iter().flat_map(|f| f.to_le_bytes()).collect();
        let (indices_view, values_view) = (f.view(&[7], None), f.view(&values, None));
        f.json["accessors"][position]["sparse"] = json!({
            "count": 1,
            "indices": { "bufferView": indices_view, "componentType": 5121 },
            "values": { "bufferView": values_view },
        });
        let normal = f.floats(&self.normals, "VEC3", false);
        let texcoords: Vec<u8> = self.texcoords.iter().flatten().flat_map(|u| u.to_le_bytes()).collect();
        let texcoord = f.accessor(
            &texcoords,
            5123,
            "VEC2",
            self.texcoords.len(),
            json!({ "normalized": true }),
        );
        let indices: Vec<u8> = self.triangles.iter().map(|&i| i as u8).collect();
        let indices = f.accessor(&indices, 5121, "SCALAR", self.triangles.len(), json!({}));
        *f.primitive(0) = json!({ "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord }, "indices": indices, "mode": 4 });
        f
    }
}

/// Runs the tool on `fixture` written as `dir/name.glb`: each corner's tangent, as bits.
fn corner_tangents(dir: &std::path::Path, fixture: &Fixture, name: &str) -> Vec<[u32; 4]> {
    corner_tangents_with(dir, fixture, name, &[])
}

/// [`corner_tangents`] with the options `options` given to the tool too.
fn corner_tangents_with(dir: &std::path::Path, fixture: &Fixture, name: &str, options: &[&str]) -> Vec<[u32; 4]> {
    let input = fixture.write_glb(dir, name);
    let output = dir.join(format!("{name}.out.glb"));
    let mut args = vec![input.as_os_str(), "-o".as_ref(), output.as_os_str()];
    args.extend(options.iter().map(std::ffi::OsStr::new));
    let result = tool::run(args);
    assert!(
        result.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&result.stderr)
    );
    let corners = Doc::open(&output).corners(0, 0, 0);
    let tangents = corners.tangents.expect("TANGENT written");
    corners
        .indices
        .iter()
        .map(|&v| tangents[v as usize].map(f32::to_bits))
        .collect()
}

#[test]
fn every_accessor_layout_gives_the_same_tangents() {
    // The tool reads float attributes and 16- and 32-bit indices where they lie (packed or
    // strided) and converts the rest (normalized integers, 8-bit indices, sparse substitutions):
    // every way of storing the same mesh must give each corner the same tangent.
    let dir = tool::fresh_dir("layouts");
    let grid = Grid::new();
    let packed = corner_tangents(&dir, &grid.packed(), "packed");
    let mirrored = packed.iter().filter(|t| f32::from_bits(t[3]) < 0.0).count();
    assert!(0 < mirrored && mirrored < packed.len(), "the grid is mirrored in part");
    for (name, fixture) in [("interleaved", grid.interleaved()), ("converted", grid.converted())] {
        let tangents = corner_tangents(&dir, &fixture, name);
        let differ = packed.iter().zip(&tangents).filter(|(a, b)| a != b).count();
        assert_eq!(tangents.len(), packed.len(), "{name}: corners");
        assert_eq!(
            differ, 0,
            "{name}: corners whose tangent differs from the packed layout's"
        );
    }
}

/// `--method` and `--policy` reach the library: each corner's tangent is what
/// `tbasis::generate_corners` gives with those options and `flip_v` (glTF's V points down), on a
/// grid whose UVs collapse around one vertex, where the policies differ; REJECT refuses it.
#[test]
fn method_and_policy_give_the_librarys_corners() {
    use tbasis::{DegeneratePolicy as Policy, Method};
    let dir = tool::fresh_dir("methods");
    let mut grid = Grid::new();
    // Vertices (1..=3, 1..=3) share one UV: every triangle at vertex (2, 2) is degenerate.
    let collapsed = grid.texcoords[2 * 6 + 2];
    for (y, x) in (1..=3).flat_map(|y| (1..=3).map(move |x| (y, x))) {
        grid.texcoords[y * 6 + x] = collapsed;
    }
    let texcoords = grid.texcoord_floats();
    let mesh = tbasis::Mesh::new(&grid.positions[..], &grid.normals[..])
        .with_texcoords(&texcoords[..])
        .with_indices(&grid.triangles[..]);
    let library = |method, policy| {
        let options = tbasis::Options::default()
            .with_method(method)
            .with_policy(policy)
            .with_flip_v(true);
        let mut corners = vec![[0.0f32; 4]; grid.triangles.len()];
        let result = tbasis::generate_corners(&mesh, &options, &mut tbasis::StridedMut::from_slice(&mut corners));
        result.map(|_| corners.iter().map(|t| t.map(f32::to_bits)).collect::<Vec<_>>())
    };
    let choices = [
        ("mikktspace", Method::Mikktspace, "legacy", Policy::Legacy),
        ("mikktspace", Method::Mikktspace, "inherit", Policy::Inherit),
        ("lengyel", Method::Lengyel, "legacy", Policy::Legacy),
        ("angle", Method::Angle, "skip", Policy::Skip),
        ("angle", Method::Angle, "inherit", Policy::Inherit),
        ("area", Method::Area, "inherit", Policy::Inherit),
        ("uniform", Method::Uniform, "skip", Policy::Skip),
    ];
    let mut results = Vec::new();
    for (method_name, method, policy_name, policy) in choices {
        let name = format!("{method_name}-{policy_name}");
        let args = ["--method", method_name, "--policy", policy_name];
        let got = corner_tangents_with(&dir, &grid.packed(), &name, &args);
        assert_eq!(Ok(&got), library(method, policy).as_ref(), "{name}");
        results.push(got);
    }
    // The policy decides what the collapsed corners get.
    assert_ne!(results[0], results[1], "mikktspace: legacy and inherit");
    assert_ne!(results[3], results[4], "angle: skip and inherit");
    // REJECT: the library refuses the mesh, and the tool the file.
    assert!(library(Method::Uniform, Policy::Reject).is_err());
    let input = grid.packed().write_glb(&dir, "reject");
    let output = dir.join("reject.out.glb");
    let args = [input.as_os_str(), "-o".as_ref(), output.as_os_str()];
    let result = tool::run(
        args.into_iter()
            .chain(["--method", "uniform", "--policy", "reject"].map(std::ffi::OsStr::new)),
    );
    assert_eq!(result.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&result.stderr).contains("degenerate"));
    assert!(!output.exists());
}

#[test]
fn elements_that_overlap_are_read_as_they_lie() {
    // A byteStride shorter than the element: texture coordinate i is floats i and i + 1 of one
    // list. The tool reads them as a packed copy of the same pairs would be read.
    let dir = tool::fresh_dir("overlap");
    let floats = [0.0f32, 1.0, 0.0, 2.0, 1.0];
    let pairs: Vec<[f32; 2]> = floats.windows(2).map(|w| [w[0], w[1]]).collect();
    let mut packed = Fixture::mirrored_quad();
    let texcoord = packed.floats(&pairs, "VEC2", false);
    packed.primitive(0)["attributes"]["TEXCOORD_0"] = json!(texcoord);
    let mut overlapping = Fixture::mirrored_quad();
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let view = overlapping.view(&bytes, Some(4));
    let accessors = overlapping.json["accessors"].as_array_mut().unwrap();
    accessors.push(json!({ "bufferView": view, "componentType": 5126, "count": 4, "type": "VEC2" }));
    let texcoord = accessors.len() - 1;
    overlapping.primitive(0)["attributes"]["TEXCOORD_0"] = json!(texcoord);
    assert_eq!(
        corner_tangents(&dir, &overlapping, "overlapping"),
        corner_tangents(&dir, &packed, "packed")
    );
}

/// The JSON and binary chunk of a `.glb`, read without checking the document (the `gltf` crate's
/// checks refuse application-specific attribute names).
fn glb_parts(path: &std::path::Path) -> (serde_json::Value, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    let glb = gltf::Glb::from_slice(&bytes).expect("a GLB");
    let json = serde_json::from_slice(&glb.json).expect("JSON");
    (json, glb.bin.map(|b| b.into_owned()).unwrap_or_default())
}

/// Accessor `index` of a `.glb` as float vectors, from its binary chunk (tightly packed or not).
fn float_elements<const N: usize>(json: &serde_json::Value, bin: &[u8], index: usize) -> Vec<[f32; N]> {
    let accessor = &json["accessors"][index];
    let view = &json["bufferViews"][accessor["bufferView"].as_u64().unwrap() as usize];
    assert_eq!(view["buffer"], 0, "in the binary chunk");
    let start = (view["byteOffset"].as_u64().unwrap_or(0) + accessor["byteOffset"].as_u64().unwrap_or(0)) as usize;
    let stride = view["byteStride"].as_u64().map_or(4 * N, |s| s as usize);
    (0..accessor["count"].as_u64().unwrap() as usize)
        .map(|i| {
            std::array::from_fn(|k| {
                let at = start + i * stride + 4 * k;
                f32::from_le_bytes(bin[at..at + 4].try_into().unwrap())
            })
        })
        .collect()
}

#[test]
fn application_specific_attributes_are_copied_where_vertices_split() {
    let dir = tool::fresh_dir("custom-attribute");
    let mut fixture = Fixture::mirrored_quad();
    let values = [[1.0f32, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0], [10.0, 11.0, 12.0]];
    let custom = fixture.floats(&values, "VEC3", false);
    fixture.primitive(0)["attributes"]["_FOO"] = json!(custom);
    let input = fixture.write_glb(&dir, "custom");
    let output = dir.join("out.glb");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    assert!(result.status.success());
    assert!(String::from_utf8_lossy(&result.stdout).contains("1 primitive done, 2 vertices added"));

    let (json, bin) = glb_parts(&output);
    let attributes = &json["meshes"][0]["primitives"][0]["attributes"];
    let positions: Vec<[f32; 3]> = float_elements(&json, &bin, attributes["POSITION"].as_u64().unwrap() as usize);
    let copied: Vec<[f32; 3]> = float_elements(&json, &bin, attributes["_FOO"].as_u64().unwrap() as usize);
    assert_eq!((positions.len(), copied.len()), (6, 6));
    // The quad's four positions differ: each vertex's position names the vertex it copies.
    let quad = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    for (position, value) in positions.iter().zip(&copied) {
        let source = quad.iter().position(|p| p == position).expect("a position of the quad");
        assert_eq!(*value, values[source]);
    }
}

/// The mirrored quad as a `.glb` without a binary chunk: its data in a data URI, after the
/// buffers `first` (a meshopt fallback buffer, or nothing).
fn glb_without_binary_chunk(dir: &std::path::Path, name: &str, first: Option<serde_json::Value>) -> std::path::PathBuf {
    let fixture = Fixture::mirrored_quad();
    let mut json = fixture.json.clone();
    let data = base64::engine::general_purpose::STANDARD.encode(&fixture.bin);
    let data_buffer =
        json!({ "byteLength": fixture.bin.len(), "uri": format!("data:application/octet-stream;base64,{data}") });
    let shift = u64::from(first.is_some());
    json["buffers"] = json!(first.into_iter().chain([data_buffer]).collect::<Vec<_>>());
    for view in json["bufferViews"].as_array_mut().unwrap() {
        view["buffer"] = json!(shift);
    }
    if shift == 1 {
        json["extensionsUsed"] = json!(["EXT_meshopt_compression"]);
    }
    let path = dir.join(format!("{name}.glb"));
    common::fixture::write_glb_file(&path, &json, None);
    path
}

#[test]
fn a_glb_without_binary_chunk_gets_its_new_data_where_a_gltf_would() {
    let dir = tool::fresh_dir("glb-without-bin");
    // Every buffer a data URI: the output stays one file, its new data embedded too.
    let input = glb_without_binary_chunk(&dir, "embedded", None);
    let output = dir.join("out").join("embedded.glb");
    assert!(tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()])
        .status
        .success());
    assert_eq!(tool::listing(&dir.join("out")), ["embedded.glb"]);
    let after = Doc::open(&output);
    let tangents = after.corners(0, 0, 0).tangents.expect("TANGENT");
    assert_eq!(tangents.len(), 6);
    assert!(tangents.iter().all(|t| t[3].abs() == 1.0));

    // A first buffer that is a meshopt fallback holds no data and no binary chunk holds it: the
    // new data goes beside the output, and the output still holds it.
    let fallback = json!({ "byteLength": 64, "extensions": { "EXT_meshopt_compression": { "fallback": true } } });
    let input = glb_without_binary_chunk(&dir, "fallback", Some(fallback));
    let output = dir.join("out2").join("fallback.glb");
    assert!(tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()])
        .status
        .success());
    assert_eq!(
        tool::listing(&dir.join("out2")),
        ["fallback.glb", "fallback.tangents.bin"]
    );
    let (json, _) = glb_parts(&output);
    let tangent = &json["accessors"][json["meshes"][0]["primitives"][0]["attributes"]["TANGENT"]
        .as_u64()
        .unwrap() as usize];
    let view = &json["bufferViews"][tangent["bufferView"].as_u64().unwrap() as usize];
    let buffer = &json["buffers"][view["buffer"].as_u64().unwrap() as usize];
    assert_eq!(buffer["uri"], "fallback.tangents.bin");
    let side = std::fs::read(dir.join("out2").join("fallback.tangents.bin")).unwrap();
    assert!(side.len() as u64 >= buffer["byteLength"].as_u64().unwrap());
    let start = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    for k in 0..tangent["count"].as_u64().unwrap() as usize {
        let at = start + 16 * k + 12;
        let w = f32::from_le_bytes(side[at..at + 4].try_into().unwrap());
        assert_eq!(w.abs(), 1.0, "tangent {k}");
    }
}

#[test]
fn the_side_buffer_takes_a_numbered_name_when_the_document_uses_the_plain_one() {
    let dir = tool::fresh_dir("numbered-side-buffer");
    let input = Fixture::mirrored_quad().write_gltf(&dir, "quad");
    // The input's own buffer is named as the output's side buffer would be.
    std::fs::rename(dir.join("quad.bin"), dir.join("out.tangents.bin")).unwrap();
    let mut json: serde_json::Value = serde_json::from_slice(&std::fs::read(&input).unwrap()).unwrap();
    json["buffers"][0]["uri"] = json!("out.tangents.bin");
    std::fs::write(&input, serde_json::to_vec(&json).unwrap()).unwrap();
    let buffer = std::fs::read(dir.join("out.tangents.bin")).unwrap();

    let output = dir.join("out.gltf");
    assert!(tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()])
        .status
        .success());
    assert_eq!(
        std::fs::read(dir.join("out.tangents.bin")).unwrap(),
        buffer,
        "the input's buffer is as it was"
    );
    let after = Doc::open(&output);
    let uris: Vec<&str> = after.json["buffers"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|b| b["uri"].as_str())
        .collect();
    assert!(uris.contains(&"out.tangents.1.bin"), "{uris:?}");
    assert_eq!(after.corners(0, 0, 0).tangents.expect("TANGENT").len(), 6);
}

#[test]
fn primitives_that_read_the_same_accessors_are_computed_once_and_share_the_result() {
    let dir = tool::fresh_dir("shared-primitives");
    let mut fixture = Fixture::mirrored_quad();
    let twin = fixture.primitive(0).clone();
    fixture.json["meshes"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "primitives": [twin] }));
    let input = fixture.write_glb(&dir, "twins");
    let output = dir.join("out.glb");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    assert!(String::from_utf8_lossy(&result.stdout).contains("2 primitives done, 2 vertices added"));
    let after = Doc::open(&output);
    assert_eq!(after.primitive_json(0, 0), after.primitive_json(1, 0));
    assert!(after.attribute(0, 0, "TANGENT").is_some());
}

#[test]
fn a_document_with_an_unknown_extension_is_not_pruned() {
    let dir = tool::fresh_dir("unknown-extension");
    let mut fixture = Fixture::mirrored_quad();
    let tangent = fixture.floats(&[[0.0f32, 1.0, 0.0, 1.0]; 4], "VEC4", false);
    fixture.primitive(0)["attributes"]["TANGENT"] = json!(tangent);
    let accessors_before = fixture.json["accessors"].as_array().unwrap().len();
    let count = |fixture: &Fixture, name: &str| {
        let input = fixture.write_glb(&dir, name);
        let output = dir.join(format!("{name}-out.glb"));
        let result = tool::run([
            input.as_os_str(),
            "--overwrite".as_ref(),
            "-o".as_ref(),
            output.as_os_str(),
        ]);
        assert!(result.status.success());
        Doc::open(&output).json["accessors"].as_array().unwrap().len()
    };
    // Known extensions only: the replaced accessors (old TANGENT, attributes, indices) go.
    assert_eq!(count(&fixture, "known"), accessors_before);
    // An extension whose references the tool cannot renumber: everything stays.
    fixture.json["extensionsUsed"] = json!(["EXT_example_unknown"]);
    fixture.json["extensions"] = json!({ "EXT_example_unknown": { "accessor": 2 } });
    assert!(count(&fixture, "unknown") > accessors_before);
}

#[test]
fn quiet_prints_no_summary_and_a_draco_primitive_is_left_as_it_was() {
    let dir = tool::fresh_dir("quiet-draco");
    let mut fixture = Fixture::mirrored_quad();
    fixture.json["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    let mut draco = fixture.primitive(0).clone();
    draco["extensions"] = json!({ "KHR_draco_mesh_compression": { "bufferView": 0, "attributes": { "POSITION": 0 } } });
    fixture.json["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(draco);
    let input = fixture.write_glb(&dir, "draco");
    let output = dir.join("out.glb");
    let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(stdout.contains("mesh 0 primitive 1: Draco-compressed"), "{stdout}");
    let (before, after) = (Doc::open(&input), Doc::open(&output));
    assert_eq!(before.primitive_json(0, 1), after.primitive_json(0, 1));

    let quiet = dir.join("quiet.glb");
    let result = tool::run([input.as_os_str(), "--quiet".as_ref(), "-o".as_ref(), quiet.as_os_str()]);
    assert!(result.status.success() && result.stdout.is_empty());
    assert_eq!(std::fs::read(&quiet).unwrap(), std::fs::read(&output).unwrap());
}

#[test]
fn two_inputs_of_one_run_never_write_one_side_buffer() {
    let dir = tool::fresh_dir("side-buffer-twice");
    std::fs::create_dir_all(dir.join("a")).unwrap();
    std::fs::create_dir_all(dir.join("b")).unwrap();
    let gltf = Fixture::mirrored_quad().write_gltf(&dir.join("a"), "quad");
    // A .glb that needs a side buffer too: its first buffer a fallback, no binary chunk.
    let fallback = json!({ "byteLength": 64, "extensions": { "EXT_meshopt_compression": { "fallback": true } } });
    let glb = glb_without_binary_chunk(&dir.join("b"), "quad", Some(fallback));
    let out = dir.join("out");
    for force in [false, true] {
        let _ = std::fs::remove_dir_all(&out);
        let mut args = vec![gltf.as_os_str(), glb.as_os_str(), "--jobs".as_ref(), "1".as_ref()];
        args.extend(["--out-dir".as_ref(), out.as_os_str()]);
        if force {
            args.push("--force".as_ref());
        }
        let result = tool::run(args);
        assert_eq!(result.status.code(), Some(1), "force {force}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(
            stderr.contains("quad.tangents.bin is the side buffer of another input of this run"),
            "{stderr}"
        );
        // The first input's output is whole: its side buffer is its own.
        assert_eq!(tool::listing(&out), ["quad.gltf", "quad.tangents.bin"], "force {force}");
        assert_eq!(
            Doc::open(&out.join("quad.gltf"))
                .corners(0, 0, 0)
                .tangents
                .expect("TANGENT")
                .len(),
            6
        );
    }
}

#[test]
fn indices_stay_16_bit_up_to_65535_vertices() {
    let dir = tool::fresh_dir("index-width");
    // The mirrored quad (its split adds 2 vertices) among vertices no triangle uses.
    for (vertices, width) in [(65_533usize, 5123), (65_534, 5125)] {
        let mut f = Fixture::mirrored_quad();
        let corners = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let positions: Vec<[f32; 3]> = (0..vertices).map(|v| corners[v.min(3)]).collect();
        let normals = vec![[0.0f32, 0.0, 1.0]; vertices];
        let uvs = [[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 0.0]];
        let texcoords: Vec<[f32; 2]> = (0..vertices).map(|v| uvs[v.min(3)]).collect();
        let attributes = json!({
            "POSITION": f.floats(&positions, "VEC3", true),
            "NORMAL": f.floats(&normals, "VEC3", false),
            "TEXCOORD_0": f.floats(&texcoords, "VEC2", false),
        });
        f.primitive(0)["attributes"] = attributes;
        let input = f.write_glb(&dir, &format!("v{vertices}"));
        let output = dir.join(format!("v{vertices}-out.glb"));
        let result = tool::run([input.as_os_str(), "-o".as_ref(), output.as_os_str()]);
        assert!(String::from_utf8_lossy(&result.stdout).contains("2 vertices added"));
        let after = Doc::open(&output);
        let indices = after.primitive_json(0, 0)["indices"].as_u64().unwrap() as usize;
        assert_eq!(
            after.json["accessors"][indices]["componentType"],
            width,
            "{} vertices",
            vertices + 2
        );
    }
}
