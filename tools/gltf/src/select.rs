//! Which primitives get tangents, which accessors each reads, and why the others are left alone.

use serde_json::Value;

use crate::document::{normal_texcoord_set, Primitive, MODES, TRIANGLES};

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

/// What makes two primitives' results equal: indices, attributes, targets, texture set. Owned: a
/// map keeps it while its source moves on.
#[derive(Debug, PartialEq, Eq, Hash)]
pub struct Key {
    indices: Option<usize>,
    attributes: Vec<(String, usize)>,
    targets: Vec<Vec<(String, usize)>>,
    texcoord: usize,
}

impl Source {
    /// Identical keys read identical data and get identical results, so primitives that draw the
    /// same geometry with different materials share their new accessors.
    pub fn key(&self) -> Key {
        Key {
            indices: self.indices,
            attributes: self.attributes.clone(),
            targets: self.targets.clone(),
            texcoord: self.texcoord,
        }
    }
}

/// What happens to one primitive.
pub enum Plan {
    Process(Source),
    /// Left as it was, with the reason (listed in the file's summary).
    Leave(String),
}

/// The plan for primitive `p` of mesh `m`.
pub fn plan(json: &Value, m: usize, p: usize, overwrite: bool) -> Result<Plan, String> {
    let primitive = Primitive::read(json, m, p)?;
    if primitive.mode != TRIANGLES {
        let name = MODES.get(primitive.mode as usize).copied().unwrap_or("unknown");
        return Ok(Plan::Leave(format!("mode {name}, not TRIANGLES")));
    }
    if primitive.draco_compressed {
        return Ok(Plan::Leave("Draco-compressed".into()));
    }
    let attributes = primitive.attributes;
    let find = |name: &str| attributes.iter().find(|(n, _)| n == name).map(|&(_, a)| a);
    if find("TANGENT").is_some() && !overwrite {
        return Ok(Plan::Leave("has TANGENT, kept (--overwrite replaces it)".into()));
    }
    let set = match primitive.material {
        Some(material) => normal_texcoord_set(json, material)?,
        None => 0,
    };
    let texcoord_name = format!("TEXCOORD_{set}");
    let (Some(position), Some(normal), Some(texcoord)) = (find("POSITION"), find("NORMAL"), find(&texcoord_name))
    else {
        let missing: Vec<&str> = ["POSITION", "NORMAL", texcoord_name.as_str()]
            .into_iter()
            .filter(|name| find(name).is_none())
            .collect();
        return Ok(Plan::Leave(format!("no {}", missing.join(" or "))));
    };
    Ok(Plan::Process(Source {
        mesh: m,
        primitive: p,
        position,
        normal,
        texcoord,
        indices: primitive.indices,
        attributes: attributes.into_iter().filter(|(name, _)| name != "TANGENT").collect(),
        targets: primitive.targets,
    }))
}
