//! The glTF JSON where the tool relies on it: typed, checked reads of buffers, bufferViews,
//! accessors and primitives, and the check of a whole document as it is read. The document itself
//! stays one `serde_json::Value`, edited in place, so that what the tool does not read (extensions,
//! extras, unknown keys, number formatting, key order) is written back as it was.

use serde_json::Value;

/// `target` of a bufferView holding vertex attributes.
pub const ARRAY_BUFFER: u64 = 34962;
/// `target` of a bufferView holding indices.
pub const ELEMENT_ARRAY_BUFFER: u64 = 34963;

/// A primitive's `mode`s by value; the tool processes triangles only.
pub const MODES: [&str; 7] = [
    "POINTS",
    "LINES",
    "LINE_LOOP",
    "LINE_STRIP",
    "TRIANGLES",
    "TRIANGLE_STRIP",
    "TRIANGLE_FAN",
];
/// The mode the tool processes, and a primitive's mode when it names none.
pub const TRIANGLES: u64 = 4;

/// An accessor's `componentType`: the value is the code glTF writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ComponentType {
    Byte = 5120,
    UnsignedByte = 5121,
    Short = 5122,
    UnsignedShort = 5123,
    UnsignedInt = 5125,
    Float = 5126,
}

impl ComponentType {
    const ALL: [ComponentType; 6] = [
        ComponentType::Byte,
        ComponentType::UnsignedByte,
        ComponentType::Short,
        ComponentType::UnsignedShort,
        ComponentType::UnsignedInt,
        ComponentType::Float,
    ];

    pub fn from_code(code: u64) -> Option<ComponentType> {
        ComponentType::ALL.into_iter().find(|t| u64::from(t.code()) == code)
    }

    pub fn code(self) -> u32 {
        self as u32
    }

    /// Bytes per component.
    pub fn size(self) -> usize {
        match self {
            ComponentType::Byte | ComponentType::UnsignedByte => 1,
            ComponentType::Short | ComponentType::UnsignedShort => 2,
            ComponentType::UnsignedInt | ComponentType::Float => 4,
        }
    }

    /// Whether indices may be of this type.
    pub fn is_index(self) -> bool {
        matches!(
            self,
            ComponentType::UnsignedByte | ComponentType::UnsignedShort | ComponentType::UnsignedInt
        )
    }

    /// The largest index of this index type: its largest value is primitive restart, never an index.
    pub fn max_index(self) -> u64 {
        (1u64 << (8 * self.size())) - 2
    }
}

/// An accessor's `type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ElementType {
    Scalar,
    Vec2,
    Vec3,
    Vec4,
    Mat2,
    Mat3,
    Mat4,
}

impl ElementType {
    fn from_name(name: &str) -> Option<ElementType> {
        Some(match name {
            "SCALAR" => ElementType::Scalar,
            "VEC2" => ElementType::Vec2,
            "VEC3" => ElementType::Vec3,
            "VEC4" => ElementType::Vec4,
            "MAT2" => ElementType::Mat2,
            "MAT3" => ElementType::Mat3,
            "MAT4" => ElementType::Mat4,
            _ => return None,
        })
    }

    /// Components per element; `None` for matrices (no vertex attribute or index is one).
    pub fn vector_components(self) -> Option<usize> {
        match self {
            ElementType::Scalar => Some(1),
            ElementType::Vec2 => Some(2),
            ElementType::Vec3 => Some(3),
            ElementType::Vec4 => Some(4),
            ElementType::Mat2 | ElementType::Mat3 | ElementType::Mat4 => None,
        }
    }
}

/// `buffers[index]`.
pub struct Buffer<'a> {
    pub byte_length: usize,
    pub uri: Option<&'a str>,
}

impl<'a> Buffer<'a> {
    pub fn read(json: &'a Value, index: usize) -> Result<Buffer<'a>, String> {
        let buffer = item(json, "buffers", index)?;
        let read = || {
            let uri = match field(buffer, "uri") {
                None => None,
                Some(uri) => Some(uri.as_str().ok_or_else(|| format!("uri is {uri}, not a string"))?),
            };
            Ok(Buffer {
                // Missing: 0, as the gltf crate read it (the specification requires it).
                byte_length: size(buffer, "byteLength")?.unwrap_or(0),
                uri,
            })
        };
        read().map_err(|e: String| format!("buffer {index}: {e}"))
    }
}

/// `bufferViews[index]`.
pub struct BufferView {
    pub buffer: usize,
    pub byte_offset: usize,
    pub byte_length: usize,
    pub byte_stride: Option<usize>,
}

impl BufferView {
    pub fn read(json: &Value, index: usize) -> Result<BufferView, String> {
        let view = item(json, "bufferViews", index)?;
        let read = || {
            let byte_stride = size(view, "byteStride")?;
            if let Some(stride) = byte_stride.filter(|s| !(4..=252).contains(s)) {
                return Err(format!("byteStride {stride} is outside 4..=252"));
            }
            if let Some(target) = field(view, "target") {
                if ![ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER].contains(&target.as_u64().unwrap_or(0)) {
                    return Err(format!(
                        "target {target} is neither ARRAY_BUFFER nor ELEMENT_ARRAY_BUFFER"
                    ));
                }
            }
            Ok(BufferView {
                buffer: required(reference(json, view, "buffer", "buffers")?, "buffer")?,
                byte_offset: size(view, "byteOffset")?.unwrap_or(0),
                byte_length: required(size(view, "byteLength")?, "byteLength")?,
                byte_stride,
            })
        };
        read().map_err(|e: String| format!("bufferView {index}: {e}"))
    }
}

/// `accessors[index]`.
pub struct Accessor {
    /// `None`: every element is zero, unless `sparse` says otherwise.
    pub buffer_view: Option<usize>,
    pub byte_offset: usize,
    pub count: usize,
    pub component_type: ComponentType,
    pub element_type: ElementType,
    pub normalized: bool,
    pub sparse: Option<Sparse>,
}

/// The substitutions of a sparse accessor.
pub struct Sparse {
    pub count: usize,
    pub indices_view: usize,
    pub indices_offset: usize,
    pub index_type: ComponentType,
    pub values_view: usize,
    pub values_offset: usize,
}

impl Accessor {
    pub fn read(json: &Value, index: usize) -> Result<Accessor, String> {
        let accessor = item(json, "accessors", index)?;
        let read = || {
            let component_type = component_type(accessor)?;
            let element_type = required(field(accessor, "type"), "type")?;
            let element_type = element_type
                .as_str()
                .and_then(ElementType::from_name)
                .ok_or_else(|| format!("type {element_type} is not an accessor type"))?;
            let normalized = match field(accessor, "normalized") {
                None => false,
                Some(flag) => flag
                    .as_bool()
                    .ok_or_else(|| format!("normalized is {flag}, not a boolean"))?,
            };
            let sparse = match field(accessor, "sparse") {
                None => None,
                Some(sparse) => Some(Sparse::read(json, sparse).map_err(|e| format!("sparse {e}"))?),
            };
            let buffer_view = reference(json, accessor, "bufferView", "bufferViews")?;
            if buffer_view.is_none() && sparse.is_none() {
                return Err("bufferView is missing (and it is not sparse)".into());
            }
            Ok(Accessor {
                buffer_view,
                byte_offset: size(accessor, "byteOffset")?.unwrap_or(0),
                count: required(size(accessor, "count")?, "count")?,
                component_type,
                element_type,
                normalized,
                sparse,
            })
        };
        read().map_err(|e: String| format!("accessor {index}: {e}"))
    }
}

impl Sparse {
    fn read(json: &Value, sparse: &Value) -> Result<Sparse, String> {
        let part = |name: &str| {
            field(sparse, name)
                .filter(|part| part.is_object())
                .ok_or_else(|| format!("{name} is missing"))
        };
        let (indices, values) = (part("indices")?, part("values")?);
        let view = |part: &Value, name: &str| {
            reference(json, part, "bufferView", "bufferViews")
                .and_then(|view| required(view, "bufferView"))
                .map_err(|e| format!("{name} {e}"))
        };
        let index_type = component_type(indices).map_err(|e| format!("indices {e}"))?;
        if !index_type.is_index() {
            return Err(format!("indices componentType {} is no index type", index_type.code()));
        }
        Ok(Sparse {
            count: required(size(sparse, "count")?, "count")?,
            indices_view: view(indices, "indices")?,
            indices_offset: size(indices, "byteOffset")?.unwrap_or(0),
            index_type,
            values_view: view(values, "values")?,
            values_offset: size(values, "byteOffset")?.unwrap_or(0),
        })
    }
}

/// `meshes[mesh].primitives[primitive]`: the accessors it reads, by name, in the document's order.
pub struct Primitive {
    pub mode: u64,
    pub attributes: Vec<(String, usize)>,
    pub indices: Option<usize>,
    pub material: Option<usize>,
    pub targets: Vec<Vec<(String, usize)>>,
    pub draco_compressed: bool,
}

impl Primitive {
    pub fn read(json: &Value, mesh: usize, primitive: usize) -> Result<Primitive, String> {
        let object = &json["meshes"][mesh]["primitives"][primitive];
        let read = || {
            if !object.is_object() {
                return Err("does not exist".to_string());
            }
            let attributes = required(field(object, "attributes"), "attributes")?;
            let attributes = named_accessors(json, attributes).map_err(|e| format!("attribute {e}"))?;
            if let Some((name, _)) = attributes.iter().find(|(name, _)| !is_semantic(name)) {
                return Err(format!("attribute {name} is not a glTF attribute name"));
            }
            let &(_, position) = attributes
                .iter()
                .find(|(name, _)| name == "POSITION")
                .ok_or("POSITION is missing")?;
            // Required by the specification, as the gltf crate checked.
            for bound in ["min", "max"] {
                let value = &json["accessors"][position][bound];
                let numbers = value
                    .as_array()
                    .filter(|v| v.len() == 3 && v.iter().all(Value::is_number));
                if numbers.is_none() {
                    return Err(format!("POSITION accessor {position}: {bound} is not 3 numbers"));
                }
            }
            let mode = match field(object, "mode") {
                None => TRIANGLES,
                Some(mode) => mode
                    .as_u64()
                    .filter(|&m| m < MODES.len() as u64)
                    .ok_or_else(|| format!("mode {mode} is not a primitive mode"))?,
            };
            let targets = match field(object, "targets") {
                None => Vec::new(),
                Some(targets) => targets
                    .as_array()
                    .ok_or("targets is not an array")?
                    .iter()
                    .enumerate()
                    .map(|(k, target)| named_accessors(json, target).map_err(|e| format!("target {k} {e}")))
                    .collect::<Result<_, _>>()?,
            };
            Ok(Primitive {
                mode,
                attributes,
                indices: reference(json, object, "indices", "accessors")?,
                material: reference(json, object, "material", "materials")?,
                targets,
                draco_compressed: object["extensions"].get("KHR_draco_mesh_compression").is_some(),
            })
        };
        read().map_err(|e: String| format!("mesh {mesh} primitive {primitive}: {e}"))
    }
}

/// The TEXCOORD set material `index`'s normal texture reads: its `texCoord`, which
/// KHR_texture_transform may override; 0 without a normal texture.
pub fn normal_texcoord_set(json: &Value, material: usize) -> Result<u64, String> {
    let Some(texture) = field(item(json, "materials", material)?, "normalTexture") else {
        return Ok(0);
    };
    let read = || {
        required(field(texture, "index"), "index")?;
        let own = size(texture, "texCoord")?.unwrap_or(0);
        let own = u32::try_from(own).map_err(|_| format!("texCoord {own} is too large"))?;
        Ok(texture["extensions"]["KHR_texture_transform"]["texCoord"]
            .as_u64()
            .unwrap_or(u64::from(own)))
    };
    read().map_err(|e: String| format!("material {material}: normalTexture {e}"))
}

/// How many items top-level array `list` has.
pub fn count(json: &Value, list: &str) -> usize {
    json[list].as_array().map_or(0, Vec::len)
}

/// How many primitives mesh `mesh` has.
pub fn primitive_count(json: &Value, mesh: usize) -> usize {
    json["meshes"][mesh]["primitives"].as_array().map_or(0, Vec::len)
}

/// Top-level arrays of objects, as the gltf crate read them.
const LISTS: [&str; 13] = [
    "accessors",
    "animations",
    "buffers",
    "bufferViews",
    "cameras",
    "images",
    "materials",
    "meshes",
    "nodes",
    "samplers",
    "scenes",
    "skins",
    "textures",
];

/// References in the parts of a document the tool does not read, checked as the gltf crate checked
/// them: (where, the list it refers to). In a path, `*` stands for every item of an array (or
/// value of an object) and `*Texture` for every field whose name ends in `Texture`.
const REFERENCES: [(&str, &str); 19] = [
    ("scene", "scenes"),
    ("scenes/*/nodes/*", "nodes"),
    ("nodes/*/camera", "cameras"),
    ("nodes/*/children/*", "nodes"),
    ("nodes/*/mesh", "meshes"),
    ("nodes/*/skin", "skins"),
    ("skins/*/inverseBindMatrices", "accessors"),
    ("skins/*/joints/*", "nodes"),
    ("skins/*/skeleton", "nodes"),
    ("animations/*/channels/*/target/node", "nodes"),
    ("animations/*/samplers/*/input", "accessors"),
    ("animations/*/samplers/*/output", "accessors"),
    ("textures/*/sampler", "samplers"),
    ("textures/*/source", "images"),
    ("images/*/bufferView", "bufferViews"),
    ("materials/*/normalTexture/index", "textures"),
    ("materials/*/occlusionTexture/index", "textures"),
    ("materials/*/emissiveTexture/index", "textures"),
    ("materials/*/pbrMetallicRoughness/*Texture/index", "textures"),
];

/// Checks a whole document: its shape, every object the tool reads, and every reference.
pub fn check(json: &Value) -> Result<(), String> {
    if !json["asset"]["version"].is_string() {
        return Err("not a glTF 2.0 document: it has no asset.version".into());
    }
    let mut errors = Vec::new();
    for list in LISTS {
        let Some(value) = json.get(list) else { continue };
        match value.as_array() {
            Some(items) if items.iter().all(Value::is_object) => {}
            _ => errors.push(format!("{list} is not an array of objects")),
        }
    }
    for list in ["extensionsUsed", "extensionsRequired"] {
        let names = field(json, list).map(|names| names.as_array().filter(|a| a.iter().all(Value::is_string)));
        if names == Some(None) {
            errors.push(format!("{list} is not an array of names"));
        }
    }
    if !errors.is_empty() {
        return Err(invalid(errors));
    }
    let mut note = |result: Result<(), String>| errors.extend(result.err());
    for index in 0..count(json, "buffers") {
        note(Buffer::read(json, index).map(drop));
    }
    for index in 0..count(json, "bufferViews") {
        note(BufferView::read(json, index).map(drop));
    }
    for index in 0..count(json, "accessors") {
        note(Accessor::read(json, index).map(drop));
    }
    for mesh in 0..count(json, "meshes") {
        if !json["meshes"][mesh]["primitives"].is_array() {
            note(Err(format!("mesh {mesh}: primitives is not an array")));
        }
        for primitive in 0..primitive_count(json, mesh) {
            note(Primitive::read(json, mesh, primitive).map(drop));
        }
    }
    for material in 0..count(json, "materials") {
        note(normal_texcoord_set(json, material).map(drop));
    }
    for (path, list) in REFERENCES {
        let pattern: Vec<&str> = path.split('/').collect();
        visit(json, &pattern, Default::default(), &mut |at, _, value| {
            note(
                to_reference(json, value, list)
                    .map(drop)
                    .map_err(|e| format!("{at} {e}")),
            );
        });
    }
    for (a, animation) in json["animations"].as_array().into_iter().flatten().enumerate() {
        let samplers = animation["samplers"].as_array().map_or(0, Vec::len);
        for (c, channel) in animation["channels"].as_array().into_iter().flatten().enumerate() {
            if channel["sampler"].as_u64().is_none_or(|s| s >= samplers as u64) {
                let sampler = &channel["sampler"];
                note(Err(format!(
                    "animations[{a}].channels[{c}].sampler refers to sampler {sampler} of {samplers}"
                )));
            }
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(invalid(errors))
    }
}

/// `invalid glTF: ` and the first three errors.
fn invalid(mut errors: Vec<String>) -> String {
    let more = errors.len().saturating_sub(3);
    errors.truncate(3);
    let tail = if more > 0 {
        format!(" (and {more} more)")
    } else {
        String::new()
    };
    format!("invalid glTF: {}{tail}", errors.join("; "))
}

/// Calls `found` with every value at `pattern` below `value`, where it is (`nodes[2].mesh`) and
/// its JSON pointer (`/nodes/2/mesh`). A pattern piece `*` stands for every item of an array or
/// value of an object; `*Texture`, for every field whose name ends in `Texture`.
fn visit<'a>(
    value: &'a Value,
    pattern: &[&str],
    (at, pointer): (String, String),
    found: &mut impl FnMut(&str, &str, &'a Value),
) {
    let Some((piece, rest)) = pattern.split_first() else {
        found(&at, &pointer, value);
        return;
    };
    let dot = if at.is_empty() { "" } else { "." };
    // RFC 6901: `~` and `/` in a name are escaped.
    let named = |name: &str| {
        let escaped = name.replace('~', "~0").replace('/', "~1");
        (format!("{at}{dot}{name}"), format!("{pointer}/{escaped}"))
    };
    if *piece == "*" {
        for (i, item) in value.as_array().into_iter().flatten().enumerate() {
            visit(item, rest, (format!("{at}[{i}]"), format!("{pointer}/{i}")), found);
        }
        for (name, item) in value.as_object().into_iter().flatten() {
            visit(item, rest, named(name), found);
        }
    } else if let Some(suffix) = piece.strip_prefix('*') {
        for (name, item) in value.as_object().into_iter().flatten() {
            if name.ends_with(suffix) {
                visit(item, rest, named(name), found);
            }
        }
    } else if let Some(item) = field(value, piece) {
        visit(item, rest, named(piece), found);
    }
}

/// The JSON pointers of every value at `path`: pieces split by `/`, where `*` stands for every
/// item of an array or value of an object (`meshes/*/primitives/*/attributes/*`).
pub fn pointers(json: &Value, path: &str) -> Vec<String> {
    let pattern: Vec<&str> = path.split('/').collect();
    let mut out = Vec::new();
    visit(json, &pattern, Default::default(), &mut |_, pointer, _| {
        out.push(pointer.to_string())
    });
    out
}

/// `json[list][index]`, an object.
fn item<'a>(json: &'a Value, list: &str, index: usize) -> Result<&'a Value, String> {
    json[list]
        .get(index)
        .filter(|item| item.is_object())
        .ok_or_else(|| format!("{} {index} does not exist", singular(list)))
}

/// Field `name` of `object`; a `null` counts as missing, as it did for the gltf crate.
fn field<'a>(object: &'a Value, name: &str) -> Option<&'a Value> {
    object.get(name).filter(|value| !value.is_null())
}

fn required<T>(value: Option<T>, name: &str) -> Result<T, String> {
    value.ok_or_else(|| format!("{name} is missing"))
}

/// Field `name`, a byte offset, length or count: a non-negative integer.
fn size(object: &Value, name: &str) -> Result<Option<usize>, String> {
    let Some(value) = field(object, name) else {
        return Ok(None);
    };
    value
        .as_u64()
        .and_then(|n| usize::try_from(n).ok())
        .map(Some)
        .ok_or_else(|| format!("{name} is {value}, not a size"))
}

fn component_type(object: &Value) -> Result<ComponentType, String> {
    let code = required(field(object, "componentType"), "componentType")?;
    code.as_u64()
        .and_then(ComponentType::from_code)
        .ok_or_else(|| format!("componentType {code} is not a component type"))
}

/// Field `name`, a reference to an item of top-level array `list`.
fn reference(json: &Value, object: &Value, name: &str, list: &str) -> Result<Option<usize>, String> {
    field(object, name)
        .map(|value| to_reference(json, value, list).map_err(|e| format!("{name} {e}")))
        .transpose()
}

fn to_reference(json: &Value, value: &Value, list: &str) -> Result<usize, String> {
    let count = count(json, list);
    match value.as_u64().and_then(|index| usize::try_from(index).ok()) {
        Some(index) if index < count => Ok(index),
        Some(index) => Err(format!("refers to {} {index}, which does not exist", singular(list))),
        None => Err(format!("is {value}, not an index")),
    }
}

/// `{"NAME": accessor, ...}` as pairs, in the document's order.
fn named_accessors(json: &Value, map: &Value) -> Result<Vec<(String, usize)>, String> {
    let map = map.as_object().ok_or("map is not an object")?;
    map.iter()
        .map(|(name, value)| {
            let index = to_reference(json, value, "accessors").map_err(|e| format!("{name} {e}"))?;
            Ok((name.clone(), index))
        })
        .collect()
}

/// Whether `name` is a glTF attribute semantic: one of the specification's, or an
/// application-specific `_NAME` (copied like any other attribute where vertices are split).
fn is_semantic(name: &str) -> bool {
    if ["POSITION", "NORMAL", "TANGENT"].contains(&name) || (name.len() > 1 && name.starts_with('_')) {
        return true;
    }
    ["COLOR_", "TEXCOORD_", "JOINTS_", "WEIGHTS_"]
        .iter()
        .any(|prefix| name.strip_prefix(prefix).is_some_and(|set| set.parse::<u32>().is_ok()))
}

/// `accessor` for `accessors`: how messages name one item of a list.
fn singular(list: &str) -> &str {
    match list {
        "meshes" => "mesh",
        list => list.strip_suffix('s').unwrap_or(list),
    }
}
