//! Reading a glTF file (input or output) for checks, with the `gltf` crate: an implementation
//! independent of the tool's own reader.

use std::path::{Path, PathBuf};

use serde_json::Value;

/// A file's JSON, its validated document and its buffers.
pub struct Doc {
    pub path: PathBuf,
    pub json: Value,
    pub document: gltf::Document,
    pub buffers: Vec<gltf::buffer::Data>,
}

/// One triangle primitive's corners: what each reads, vertex by vertex.
pub struct Corners {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub texcoords: Vec<[f32; 2]>,
    pub tangents: Option<Vec<[f32; 4]>>,
    /// Three per triangle (unindexed: 0, 1, 2, ...).
    pub indices: Vec<u32>,
}

impl Doc {
    pub fn open(path: &Path) -> Doc {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let (json_bytes, blob) = if bytes.starts_with(b"glTF") {
            let glb = gltf::Glb::from_slice(&bytes).expect("a GLB");
            (glb.json.into_owned(), glb.bin.map(|b| b.into_owned()))
        } else {
            (bytes, None)
        };
        let json: Value = serde_json::from_slice(&json_bytes).expect("JSON");
        let mut root: gltf::json::Root = serde_json::from_value(json.clone()).expect("glTF");
        // The `gltf` crate refuses required extensions it was not built with; none changes meshes.
        root.extensions_required.clear();
        let document = gltf::Document::from_json(root).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let buffers = gltf::import_buffers(&document, path.parent(), blob)
            .unwrap_or_else(|e| panic!("{}: buffers: {e}", path.display()));
        Doc {
            path: path.to_path_buf(),
            json,
            document,
            buffers,
        }
    }

    pub fn primitive(&self, m: usize, p: usize) -> gltf::Primitive<'_> {
        self.document
            .meshes()
            .nth(m)
            .expect("mesh")
            .primitives()
            .nth(p)
            .expect("primitive")
    }

    /// Primitive `(m, p)` with the texture coordinates of set `set`.
    pub fn corners(&self, m: usize, p: usize, set: u32) -> Corners {
        let primitive = self.primitive(m, p);
        let reader = primitive.reader(|b| Some(&self.buffers[b.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().expect("POSITION").collect();
        let indices = match reader.read_indices() {
            Some(indices) => indices.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        Corners {
            normals: reader.read_normals().expect("NORMAL").collect(),
            texcoords: reader.read_tex_coords(set).expect("TEXCOORD").into_f32().collect(),
            tangents: reader.read_tangents().map(Iterator::collect),
            positions,
            indices,
        }
    }

    /// The bytes of every element of accessor `index` (packed; sparse accessors are not read).
    pub fn elements(&self, index: usize) -> Vec<Vec<u8>> {
        let accessor = self.document.accessors().nth(index).expect("accessor");
        assert!(accessor.sparse().is_none(), "sparse accessors are not read here");
        let size = accessor.size();
        let Some(view) = accessor.view() else {
            return vec![vec![0; size]; accessor.count()];
        };
        let data = &self.buffers[view.buffer().index()];
        let stride = view.stride().unwrap_or(size);
        let start = view.offset() + accessor.offset();
        (0..accessor.count())
            .map(|i| data[start + i * stride..start + i * stride + size].to_vec())
            .collect()
    }

    /// The accessor `(m, p)` reads for `name` (an attribute), if any.
    pub fn attribute(&self, m: usize, p: usize, name: &str) -> Option<usize> {
        self.primitive_json(m, p)["attributes"][name]
            .as_u64()
            .map(|i| i as usize)
    }

    pub fn primitive_json(&self, m: usize, p: usize) -> &Value {
        &self.json["meshes"][m]["primitives"][p]
    }

    /// The count of accessor `index`.
    pub fn count(&self, index: usize) -> u64 {
        self.json["accessors"][index]["count"].as_u64().expect("count")
    }

    /// The file a relative URI of this document names (lexically: it may not exist).
    pub fn resolve(&self, uri: &str) -> PathBuf {
        let dir = std::fs::canonicalize(self.path.parent().expect("a folder")).expect("the folder exists");
        let mut out = PathBuf::new();
        for part in dir.join(uri.replace("%20", " ")).components() {
            match part {
                std::path::Component::ParentDir => {
                    out.pop();
                }
                std::path::Component::CurDir => {}
                other => out.push(other),
            }
        }
        out
    }
}

/// The TEXCOORD set the normal texture of `primitive`'s material reads (0 without one).
pub fn normal_texcoord_set(json: &Value, primitive: &Value) -> u32 {
    let Some(material) = primitive["material"].as_u64() else {
        return 0;
    };
    let texture = &json["materials"][material as usize]["normalTexture"];
    texture["extensions"]["KHR_texture_transform"]["texCoord"]
        .as_u64()
        .or_else(|| texture["texCoord"].as_u64())
        .unwrap_or(0) as u32
}
