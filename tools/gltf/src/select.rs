//! Which primitives get tangents, which accessors each reads, and why the others are left alone.

use serde_json::Value;

/// A primitive to process: the accessors it reads and the ones its new vertices copy.
#[derive(Clone, Debug)]
pub struct Source {
    pub mesh: usize,
    pub primitive: usize,
    pub position: usize,
    pub normal: usize,
    /// The texture coordinates of the material's normal texture (TEXCOORD_0 without one).
    pub texcoord: usize,
    pub indices: Option<usize>,
    /// Every vertex attribute but TANGENT, by name.
    pub attributes: Vec<(String, usize)>,
    /// Each morph target's attributes, by name.
    pub targets: Vec<Vec<(String, usize)>>,
}

/// What makes two primitives' results equal: indices, attributes, targets, texture set.
pub type Key<'a> = (Option<usize>, &'a [(String, usize)], &'a [Vec<(String, usize)>], usize);

impl Source {
    /// Identical keys read identical data and get identical results, so primitives that draw the
    /// same geometry with different materials share their new accessors.
    pub fn key(&self) -> Key<'_> {
        (self.indices, &self.attributes, &self.targets, self.texcoord)
    }
}

/// What happens to one primitive.
pub enum Plan {
    Process(Source),
    /// Left as it was, with the reason (listed in the file's summary).
    Leave(String),
}

/// The plan for primitive `p` of mesh `m`.
pub fn plan(json: &Value, m: usize, p: usize, overwrite: bool) -> Plan {
    let primitive = &json["meshes"][m]["primitives"][p];
    let mode = primitive["mode"].as_u64().unwrap_or(4);
    if mode != 4 {
        let name = [
            "POINTS",
            "LINES",
            "LINE_LOOP",
            "LINE_STRIP",
            "TRIANGLES",
            "TRIANGLE_STRIP",
            "TRIANGLE_FAN",
        ]
        .get(mode as usize)
        .copied()
        .unwrap_or("unknown");
        return Plan::Leave(format!("mode {name}, not TRIANGLES"));
    }
    if primitive["extensions"].get("KHR_draco_mesh_compression").is_some() {
        return Plan::Leave("Draco-compressed".into());
    }
    let attributes = named_accessors(&primitive["attributes"]);
    let find = |name: &str| attributes.iter().find(|(n, _)| n == name).map(|&(_, a)| a);
    if find("TANGENT").is_some() && !overwrite {
        return Plan::Leave("has TANGENT, kept (--overwrite replaces it)".into());
    }
    let set = normal_texcoord_set(json, primitive);
    let texcoord_name = format!("TEXCOORD_{set}");
    let (Some(position), Some(normal), Some(texcoord)) = (find("POSITION"), find("NORMAL"), find(&texcoord_name))
    else {
        let missing: Vec<&str> = ["POSITION", "NORMAL", texcoord_name.as_str()]
            .into_iter()
            .filter(|name| find(name).is_none())
            .collect();
        return Plan::Leave(format!("no {}", missing.join(" or ")));
    };
    let targets = primitive["targets"]
        .as_array()
        .map(|targets| targets.iter().map(named_accessors).collect())
        .unwrap_or_default();
    Plan::Process(Source {
        mesh: m,
        primitive: p,
        position,
        normal,
        texcoord,
        indices: primitive["indices"].as_u64().map(|i| i as usize),
        attributes: attributes.into_iter().filter(|(name, _)| name != "TANGENT").collect(),
        targets,
    })
}

/// `{"NAME": accessor, ...}` as pairs, in the document's order.
fn named_accessors(map: &Value) -> Vec<(String, usize)> {
    map.as_object()
        .map(|map| {
            map.iter()
                .filter_map(|(name, index)| Some((name.clone(), index.as_u64()? as usize)))
                .collect()
        })
        .unwrap_or_default()
}

/// The TEXCOORD set the primitive's normal texture reads: its `texCoord`, which
/// KHR_texture_transform may override; 0 without a normal texture.
fn normal_texcoord_set(json: &Value, primitive: &Value) -> u64 {
    let Some(material) = primitive["material"].as_u64() else {
        return 0;
    };
    let normal_texture = &json["materials"][material as usize]["normalTexture"];
    normal_texture["extensions"]["KHR_texture_transform"]["texCoord"]
        .as_u64()
        .or_else(|| normal_texture["texCoord"].as_u64())
        .unwrap_or(0)
}
