//! Small glTF files built in the tests: a mirrored quad whose seam the tool must split, with
//! whatever attributes a test adds.

use std::path::Path;

use serde_json::{json, Value};

/// A document under construction: JSON and one binary buffer.
pub struct Fixture {
    pub json: Value,
    pub bin: Vec<u8>,
}

impl Fixture {
    /// One mesh, one primitive: a quad of two triangles whose second one is mirrored in UV
    /// (vertices 0 and 2 are shared across the mirror line, so they must be split), 16-bit
    /// indices, POSITION, NORMAL and TEXCOORD_0.
    pub fn mirrored_quad() -> Fixture {
        let mut fixture = Fixture {
            json: json!({
                "asset": { "version": "2.0", "generator": "tbasis-gltf tests" },
                "extras": { "kept": [1, 2.5, "three"] },
                "scene": 0,
                "scenes": [{ "nodes": [0] }],
                "nodes": [{ "mesh": 0, "name": "quad" }],
                "meshes": [{ "primitives": [{ "attributes": {}, "mode": 4 }] }],
                "accessors": [],
                "bufferViews": [],
                "buffers": [],
            }),
            bin: Vec::new(),
        };
        let positions = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let position = fixture.floats(&positions, "VEC3", true);
        let normal = fixture.floats(&[[0.0f32, 0.0, 1.0]; 4], "VEC3", false);
        let texcoord = fixture.floats(&[[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 0.0]], "VEC2", false);
        let indices = fixture.u16_indices(&[0, 1, 2, 0, 2, 3]);
        let primitive = &mut fixture.json["meshes"][0]["primitives"][0];
        primitive["attributes"] = json!({ "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord });
        primitive["indices"] = json!(indices);
        fixture
    }

    /// The document of [`Fixture::mirrored_quad`] without accessors, bufferViews or data: one
    /// triangle primitive for a test to fill.
    pub fn empty_primitive() -> Fixture {
        let mut f = Fixture::mirrored_quad();
        f.json["accessors"] = json!([]);
        f.json["bufferViews"] = json!([]);
        f.bin.clear();
        f
    }

    /// Adds a bufferView of raw `bytes` (with `byteStride` when given); returns it.
    pub fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let views = self.json["bufferViews"].as_array_mut().unwrap();
        views.push(json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() }));
        if let Some(stride) = stride {
            views.last_mut().unwrap()["byteStride"] = json!(stride);
        }
        self.bin.extend_from_slice(bytes);
        views.len() - 1
    }

    /// Adds a bufferView and accessor of raw `bytes`; returns the accessor.
    pub fn accessor(&mut self, bytes: &[u8], component_type: u32, kind: &str, count: usize, extra: Value) -> usize {
        let view = self.view(bytes, None);
        let mut accessor = json!({ "bufferView": view, "componentType": component_type, "count": count, "type": kind });
        if let (Some(accessor), Some(extra)) = (accessor.as_object_mut(), extra.as_object()) {
            accessor.extend(extra.clone());
        }
        let accessors = self.json["accessors"].as_array_mut().unwrap();
        accessors.push(accessor);
        accessors.len() - 1
    }

    /// Float vectors; `bounds` adds min and max (POSITION needs them).
    pub fn floats<const N: usize>(&mut self, values: &[[f32; N]], kind: &str, bounds: bool) -> usize {
        let bytes: Vec<u8> = values.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        let extra = if bounds {
            let min: Vec<f32> = (0..N)
                .map(|k| values.iter().map(|v| v[k]).fold(f32::INFINITY, f32::min))
                .collect();
            let max: Vec<f32> = (0..N)
                .map(|k| values.iter().map(|v| v[k]).fold(f32::NEG_INFINITY, f32::max))
                .collect();
            json!({ "min": min, "max": max })
        } else {
            json!({})
        };
        self.accessor(&bytes, 5126, kind, values.len(), extra)
    }

    pub fn u16_indices(&mut self, indices: &[u16]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        self.accessor(&bytes, 5123, "SCALAR", indices.len(), json!({}))
    }

    pub fn primitive(&mut self, p: usize) -> &mut Value {
        &mut self.json["meshes"][0]["primitives"][p]
    }

    /// Writes `dir/name.gltf` with its buffer in `dir/name.bin`.
    pub fn write_gltf(&self, dir: &Path, name: &str) -> std::path::PathBuf {
        let mut json = self.json.clone();
        json["buffers"] = json!([{ "uri": format!("{name}.bin"), "byteLength": self.bin.len() }]);
        std::fs::write(dir.join(format!("{name}.bin")), &self.bin).unwrap();
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec_pretty(&json).unwrap()).unwrap();
        path
    }

    /// Writes `dir/name.glb`.
    pub fn write_glb(&self, dir: &Path, name: &str) -> std::path::PathBuf {
        let mut json = self.json.clone();
        json["buffers"] = json!([{ "byteLength": self.bin.len() }]);
        let path = dir.join(format!("{name}.glb"));
        write_glb_file(&path, &json, Some(&self.bin));
        path
    }
}

/// Writes a GLB of `json` and, when given, the binary chunk `bin`.
pub fn write_glb_file(path: &Path, json: &Value, bin: Option<&[u8]>) {
    let glb = gltf::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: 0,
        },
        json: serde_json::to_vec(json).unwrap().into(),
        bin: bin.map(|bin| bin.to_vec().into()),
    };
    std::fs::write(path, glb.to_vec().unwrap()).unwrap();
}
