//! Writes the seeds of the fuzz target `gltf_tool` (`fuzz/fuzz_targets/gltf_tool.rs`) into the
//! folder named by its argument, built from the tests' mirrored quad:
//! - `quad.glb`, its buffer in the binary chunk;
//! - `quad-data-uri.gltf`, its buffer in a `data:` URI, with a normal texture;
//! - `quad-file-sparse.gltf`, which also reads the fuzz target's `a.bin` through a strided view,
//!   has sparse accessors, and a second primitive with a `TANGENT` already.
//!
//! `.ci/fuzz.sh` runs it before fuzzing: `cargo run -p tbasis-gltf --example fuzz_seeds -- DIR`.

#[allow(dead_code)]
#[path = "../tests/common/fixture.rs"]
mod fixture;

use std::path::Path;

use serde_json::json;
use tbasis_gltf::uri::encode_data;

use fixture::Fixture;

fn main() -> Result<(), String> {
    let dir = std::env::args().nth(1).ok_or("usage: fuzz_seeds DIR")?;
    let dir = Path::new(&dir);
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;

    Fixture::mirrored_quad().write_glb(dir, "quad");

    let mut textured = Fixture::mirrored_quad();
    textured.primitive(0)["material"] = json!(0);
    textured.json["materials"] = json!([{ "normalTexture": { "index": 0, "texCoord": 0 } }]);
    textured.json["textures"] = json!([{ "source": 0 }]);
    textured.json["images"] = json!([{ "uri": "n.png" }]);
    write_embedded(&textured, &[], dir, "quad-data-uri")?;

    // Accessors 0 to 3: POSITION, NORMAL, TEXCOORD_0, indices. The normals take one sparse
    // substitution; TEXCOORD_1 reads `a.bin`, 8 bytes apart; a TANGENT made of sparse values only.
    let mut sparse = textured;
    let views = sparse.json["bufferViews"].as_array_mut().ok_or("bufferViews")?;
    views.push(json!({ "buffer": 1, "byteOffset": 64, "byteLength": 32, "byteStride": 8 }));
    let strided_view = views.len() - 1;
    let accessors = sparse.json["accessors"].as_array_mut().ok_or("accessors")?;
    let substitution = |values: serde_json::Value| json!({ "count": 1, "indices": { "bufferView": 3, "componentType": 5123 }, "values": values });
    accessors[1]["sparse"] = substitution(json!({ "bufferView": 1, "byteOffset": 12 }));
    accessors.push(json!({ "bufferView": strided_view, "componentType": 5126, "count": 4, "type": "VEC2" }));
    accessors.push(json!({ "componentType": 5126, "count": 4, "type": "VEC4", "sparse": substitution(json!({ "bufferView": 0 })) }));
    sparse.primitive(0)["attributes"]["TEXCOORD_1"] = json!(4);
    let mut tangent = sparse.primitive(0).clone();
    tangent.as_object_mut().ok_or("primitive")?.remove("material");
    tangent["attributes"]
        .as_object_mut()
        .ok_or("attributes")?
        .remove("TEXCOORD_1");
    tangent["attributes"]["TANGENT"] = json!(5);
    sparse.json["meshes"][0]["primitives"]
        .as_array_mut()
        .ok_or("primitives")?
        .push(tangent);
    let a_bin = json!({ "byteLength": 4096, "uri": "a.bin" });
    write_embedded(&sparse, &[a_bin], dir, "quad-file-sparse")
}

/// Writes `dir/name.gltf` with the fixture's buffer in a `data:` URI, then `more` buffers.
fn write_embedded(fixture: &Fixture, more: &[serde_json::Value], dir: &Path, name: &str) -> Result<(), String> {
    let mut json = fixture.json.clone();
    let embedded = json!({ "byteLength": fixture.bin.len(), "uri": encode_data(&fixture.bin) });
    json["buffers"] = json!([embedded].into_iter().chain(more.iter().cloned()).collect::<Vec<_>>());
    let path = dir.join(format!("{name}.gltf"));
    let bytes = serde_json::to_vec(&json).map_err(|e| e.to_string())?;
    std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}
