//! One primitive: tangents per corner, the seam split that gives each corner its own tangent, and
//! the new accessors that hold the result.

use std::collections::HashMap;

use serde_json::{json, Map, Value};
use tbasis::{copy_split_vertices, split_corners, Indices, Mesh, Options, Report, ScratchBuffer, SeamSplit};
use tbasis::{Strided, StridedMut};

use crate::accessor::{self, Buffers, Layout};
use crate::buffers::Segment;
use crate::document::{ComponentType, ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER};
use crate::memory;
use crate::select::Source;

/// Tangents for a primitive's vertices after the split.
pub struct Computed {
    /// Vertices before the split.
    pub vertex_count: usize,
    /// One per vertex after the split: the original ones, then the appended copies.
    pub tangents: Vec<[f32; 4]>,
    /// The new index of every corner, and the vertex each appended one copies.
    pub split: SeamSplit,
    /// The index accessor's component type, `None` unindexed.
    pub index_type: Option<ComponentType>,
    pub report: Report,
}

/// What replaces the primitive's accessors: indices of accessors in its [`Segment`].
pub struct Edit {
    /// New accessors for attributes (empty when no vertex was split: the old ones still fit).
    pub attributes: Vec<(String, usize)>,
    pub tangent: usize,
    pub indices: Option<usize>,
    pub targets: Vec<Vec<(String, usize)>>,
    pub vertices_added: usize,
}

/// Memory a thread reuses from primitive to primitive: after the first (the largest, when they
/// come largest first), its pages are already mapped.
#[derive(Default)]
pub struct Workspace {
    /// The library's working memory.
    scratch: ScratchBuffer,
    /// Tangents per corner.
    corners: Vec<[f32; 4]>,
}

/// Computes the primitive's tangents per corner and splits its seams.
pub fn compute(
    source: &Source,
    json: &Value,
    buffers: &Buffers,
    options: &Options,
    workspace: &mut Workspace,
) -> Result<Computed, String> {
    let read = |name: &str, index: usize| -> Result<Layout, String> {
        accessor::layout(json, index).map_err(|e| format!("{name}: {e}"))
    };
    let vertex_count = read("POSITION", source.position)?.count;
    if vertex_count == 0 {
        return Err("POSITION has no elements".into());
    }
    let all = source.attributes.iter().chain(source.targets.iter().flatten());
    for (name, index) in all {
        let count = read(name, *index)?.count;
        if count != vertex_count {
            return Err(format!("{name} has {count} elements, POSITION {vertex_count}"));
        }
    }
    let (mut positions, mut normals, mut texcoords, mut indices) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let positions =
        accessor::floats::<3>(json, buffers, source.position, &mut positions).map_err(|e| format!("POSITION: {e}"))?;
    let normals =
        accessor::floats::<3>(json, buffers, source.normal, &mut normals).map_err(|e| format!("NORMAL: {e}"))?;
    let texcoords = accessor::floats::<2>(json, buffers, source.texcoord, &mut texcoords)
        .map_err(|e| format!("texture coordinates: {e}"))?;
    let (indices, index_type) = match source.indices {
        Some(index) => {
            let layout = read("indices", index)?;
            let indices = accessor::indices(json, buffers, index, &mut indices).map_err(|e| format!("indices: {e}"))?;
            (indices, Some(layout.component))
        }
        None => (Indices::None, None),
    };
    let mesh = Mesh {
        positions,
        normals,
        texcoords: Some(texcoords),
        indices,
    };
    let corners = &mut workspace.corners;
    // Every corner is written: what an earlier primitive left is overwritten.
    memory::resize(corners, mesh.corner_count(), [0.0; 4], "tangents per corner")?;
    let report = workspace
        .scratch
        .generate_corners(&mesh, options, &mut StridedMut::from_slice(corners))
        .map_err(|e| format!("tangents: {e}"))?;
    let split = split_corners(&mesh, &Strided::from_slice(corners)).map_err(|e| format!("seam split: {e}"))?;

    // Each corner's tangent goes to its vertex. A vertex no triangle uses (its `w` is still 0:
    // a written one is +1 or -1) still needs a valid TANGENT: a frame built from its normal.
    let mut tangents = memory::filled(vertex_count + split.sources.len(), [0.0f32; 4], "tangents")?;
    for (&vertex, corner) in split.indices.iter().zip(corners.iter()) {
        tangents[vertex as usize] = *corner;
    }
    for (v, tangent) in tangents.iter_mut().enumerate().filter(|(_, t)| t[3] == 0.0) {
        let source = split
            .sources
            .get(v.wrapping_sub(vertex_count))
            .map_or(v, |&s| s as usize);
        *tangent = tbasis::fallback_frame(normals.get(source));
    }
    Ok(Computed {
        vertex_count,
        tangents,
        split,
        index_type,
        report,
    })
}

/// The new accessors for `computed`, in `segment`: TANGENT always; when vertices were appended, every vertex
/// attribute, morph target attribute and the indices too, as copies with the new vertices added.
pub fn edit(
    source: &Source,
    computed: &Computed,
    json: &Value,
    buffers: &Buffers,
    segment: &mut Segment,
) -> Result<Edit, String> {
    let total = computed.tangents.len();
    let (view, bytes) = segment.view_mut(byte_length(total, 16)?, None, ARRAY_BUFFER)?;
    write_le(bytes, computed.tangents.iter().flatten(), |f| f.to_le_bytes());
    let tangent = segment.accessor(json!({
        "bufferView": view,
        "componentType": ComponentType::Float.code(),
        "count": total,
        "type": "VEC4",
    }));
    let sources = &computed.split.sources;
    if sources.is_empty() {
        // Every corner kept its vertex: the indices and attributes stay as they are.
        return Ok(Edit {
            attributes: Vec::new(),
            tangent,
            indices: None,
            targets: Vec::new(),
            vertices_added: 0,
        });
    }
    // One copy per source accessor, even when several attributes read it.
    let mut copies = HashMap::new();
    let mut copy = |name: &str, index: usize| -> Result<usize, String> {
        if let Some(&done) = copies.get(&index) {
            return Ok(done);
        }
        let done = copy_attribute(json, buffers, index, computed.vertex_count, sources, segment)
            .map_err(|e| format!("{name}: {e}"))?;
        copies.insert(index, done);
        Ok(done)
    };
    let attributes = source
        .attributes
        .iter()
        .map(|(name, index)| Ok((name.clone(), copy(name, *index)?)))
        .collect::<Result<Vec<_>, String>>()?;
    let targets = source
        .targets
        .iter()
        .map(|target| {
            target
                .iter()
                .map(|(name, index)| Ok((name.clone(), copy(name, *index)?)))
                .collect::<Result<Vec<_>, String>>()
        })
        .collect::<Result<Vec<_>, String>>()?;
    let indices = Some(write_indices(computed, segment)?);
    Ok(Edit {
        attributes,
        tangent,
        indices,
        targets,
        vertices_added: sources.len(),
    })
}

/// Writes `edit` into the primitive's JSON, its segment's accessors numbered from
/// `first_accessor`.
pub fn apply(primitive: &mut Value, edit: &Edit, first_accessor: usize) {
    let accessor = |index: usize| json!(first_accessor + index);
    let attributes = object(&mut primitive["attributes"]);
    for (name, index) in &edit.attributes {
        attributes.insert(name.clone(), accessor(*index));
    }
    attributes.insert("TANGENT".into(), accessor(edit.tangent));
    if let Some(indices) = edit.indices {
        primitive["indices"] = accessor(indices);
    }
    for (k, target) in edit.targets.iter().enumerate() {
        let map = object(&mut primitive["targets"][k]);
        for (name, index) in target {
            map.insert(name.clone(), accessor(*index));
        }
    }
}

fn object(value: &mut Value) -> &mut Map<String, Value> {
    if !value.is_object() {
        *value = Value::Object(Map::new());
    }
    value.as_object_mut().expect("made an object above")
}

/// A copy of vertex accessor `index` with the appended vertices, as a new accessor.
fn copy_attribute(
    json: &Value,
    buffers: &Buffers,
    index: usize,
    vertex_count: usize,
    sources: &[u32],
    segment: &mut Segment,
) -> Result<usize, String> {
    let layout = accessor::layout(json, index)?;
    let size = layout.element_size();
    // Vertex attribute elements must start on 4-byte boundaries.
    let stride = size.next_multiple_of(4);
    let total = vertex_count.checked_add(sources.len()).ok_or("too many vertices")?;
    let (view, data) = segment.view_mut(
        byte_length(total, stride)?,
        (stride != size).then_some(stride),
        ARRAY_BUFFER,
    )?;
    accessor::copy_into(json, buffers, index, data, stride)?;
    copy_split_vertices(data, stride, size, vertex_count, sources).map_err(|e| format!("copying vertices: {e}"))?;
    let old = &json["accessors"][index];
    let mut accessor = json!({
        "bufferView": view,
        "componentType": layout.component.code(),
        "count": total,
        "type": old["type"],
    });
    if layout.normalized {
        accessor["normalized"] = json!(true);
    }
    // The same values, some repeated: the bounds still hold.
    for key in ["min", "max", "name"] {
        if let Some(value) = old.get(key) {
            accessor[key] = value.clone();
        }
    }
    Ok(segment.accessor(accessor))
}

/// The split indices as a new accessor, of the original type where every index fits it.
fn write_indices(computed: &Computed, segment: &mut Segment) -> Result<usize, String> {
    let largest_index = computed.tangents.len().saturating_sub(1) as u64;
    let original = computed.index_type.unwrap_or(ComponentType::UnsignedInt);
    let component = [ComponentType::UnsignedByte, ComponentType::UnsignedShort]
        .into_iter()
        .find(|kind| kind.size() >= original.size() && largest_index <= kind.max_index())
        .unwrap_or(ComponentType::UnsignedInt);
    let indices = &computed.split.indices;
    let length = byte_length(indices.len(), component.size())?;
    let (view, bytes) = segment.view_mut(length, None, ELEMENT_ARRAY_BUFFER)?;
    match component {
        ComponentType::UnsignedByte => write_le(bytes, indices, |&i| [i as u8]),
        ComponentType::UnsignedShort => write_le(bytes, indices, |&i| (i as u16).to_le_bytes()),
        _ => write_le(bytes, indices, |&i| i.to_le_bytes()),
    }
    Ok(segment.accessor(json!({
        "bufferView": view,
        "componentType": component.code(),
        "count": indices.len(),
        "type": "SCALAR",
    })))
}

/// The bytes of `count` elements of `size` bytes.
fn byte_length(count: usize, size: usize) -> Result<usize, String> {
    count
        .checked_mul(size)
        .ok_or_else(|| format!("{count} elements of {size} bytes are too many"))
}

/// Writes each value's `N` little-endian bytes one after the other.
fn write_le<T, const N: usize>(bytes: &mut [u8], values: impl IntoIterator<Item = T>, to_le: impl Fn(T) -> [u8; N]) {
    for (slot, value) in bytes.chunks_exact_mut(N).zip(values) {
        slot.copy_from_slice(&to_le(value));
    }
}
