//! Reading accessors: their elements as packed bytes (sparse substitutions applied), as floats,
//! or as indices.

use gltf::json::accessor::{ComponentType, Type};
use gltf::json::validation::Checked;
use gltf::json::Root;

/// Buffers as loaded (see [`crate::buffers::load`]).
pub type Buffers = [Option<Vec<u8>>];

/// What one element of an accessor is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    pub component: ComponentType,
    pub components: usize,
    pub normalized: bool,
    pub count: usize,
}

impl Layout {
    pub fn element_size(&self) -> usize {
        self.component.size() * self.components
    }
}

/// The layout of accessor `index`; matrices are refused (no vertex attribute or index is one).
pub fn layout(root: &Root, index: usize) -> Result<Layout, String> {
    let accessor = root
        .accessors
        .get(index)
        .ok_or_else(|| format!("accessor {index} does not exist"))?;
    let (Checked::Valid(component), Checked::Valid(kind)) = (&accessor.component_type, &accessor.type_) else {
        return Err(format!("accessor {index}: invalid componentType or type"));
    };
    let components = match kind {
        Type::Scalar => 1,
        Type::Vec2 => 2,
        Type::Vec3 => 3,
        Type::Vec4 => 4,
        _ => return Err(format!("accessor {index}: a matrix where vertex data was expected")),
    };
    Ok(Layout {
        component: component.0,
        components,
        normalized: accessor.normalized,
        count: accessor.count.0 as usize,
    })
}

/// The elements of accessor `index`, packed (no stride), with sparse substitutions applied.
pub fn packed(root: &Root, buffers: &Buffers, index: usize) -> Result<(Layout, Vec<u8>), String> {
    let layout = layout(root, index)?;
    let accessor = &root.accessors[index];
    let size = layout.element_size();
    let total = layout
        .count
        .checked_mul(size)
        .ok_or_else(|| format!("accessor {index}: too large"))?;
    let mut out = match accessor.buffer_view {
        // No bufferView: zeros, unless sparse says otherwise.
        None => vec![0u8; total],
        Some(view) => {
            let view_index = view.value();
            let view = &root.buffer_views[view_index];
            let stride = view.byte_stride.map_or(size, |s| s.0);
            let start = accessor.byte_offset.map_or(0, |o| o.0 as usize);
            let bytes = view_bytes(root, buffers, view_index)?;
            let needed = match layout.count {
                0 => Some(0),
                n => (n - 1).checked_mul(stride).and_then(|x| x.checked_add(start + size)),
            }
            .ok_or_else(|| format!("accessor {index}: too large"))?;
            if needed > bytes.len() {
                return Err(format!(
                    "accessor {index}: needs {needed} bytes of bufferView {view_index}, which has {}",
                    bytes.len()
                ));
            }
            if stride == size {
                bytes[start..start + total].to_vec()
            } else {
                let mut out = Vec::with_capacity(total);
                for i in 0..layout.count {
                    let at = start + i * stride;
                    out.extend_from_slice(&bytes[at..at + size]);
                }
                out
            }
        }
    };
    if let Some(sparse) = &accessor.sparse {
        apply_sparse(root, buffers, index, sparse, size, layout.count, &mut out)?;
    }
    Ok((layout, out))
}

fn apply_sparse(
    root: &Root,
    buffers: &Buffers,
    index: usize,
    sparse: &gltf::json::accessor::sparse::Sparse,
    size: usize,
    count: usize,
    out: &mut [u8],
) -> Result<(), String> {
    let n = sparse.count.0 as usize;
    let Checked::Valid(index_type) = &sparse.indices.component_type else {
        return Err(format!("sparse accessor {index}: invalid index componentType"));
    };
    let index_size = index_type.0.size();
    let indices = view_bytes(root, buffers, sparse.indices.buffer_view.value())?;
    let values = view_bytes(root, buffers, sparse.values.buffer_view.value())?;
    let (index_start, value_start) = (
        sparse.indices.byte_offset.0 as usize,
        sparse.values.byte_offset.0 as usize,
    );
    let end = |start: usize, size: usize| n.checked_mul(size).and_then(|x| x.checked_add(start));
    let fits = |end: Option<usize>, len: usize| end.is_some_and(|end| end <= len);
    if !fits(end(index_start, index_size), indices.len()) || !fits(end(value_start, size), values.len()) {
        return Err(format!(
            "sparse accessor {index}: its {n} indices or values run past their bufferViews"
        ));
    }
    for k in 0..n {
        let at = index_start + k * index_size;
        let target = read_index(&indices[at..at + index_size]) as usize;
        if target >= count {
            return Err(format!(
                "sparse accessor {index}: substitutes element {target} of {count}"
            ));
        }
        let from = value_start + k * size;
        out[target * size..(target + 1) * size].copy_from_slice(&values[from..from + size]);
    }
    Ok(())
}

/// The bytes of bufferView `index`, checked against its buffer.
fn view_bytes<'a>(root: &Root, buffers: &'a Buffers, index: usize) -> Result<&'a [u8], String> {
    let view = &root.buffer_views[index];
    let buffer = view.buffer.value();
    let bytes = buffers[buffer]
        .as_deref()
        .ok_or_else(|| format!("bufferView {index}: buffer {buffer} holds no data (a compression fallback)"))?;
    let start = view.byte_offset.map_or(0, |o| o.0 as usize);
    let end = start.saturating_add(view.byte_length.0 as usize);
    bytes
        .get(start..end)
        .ok_or_else(|| format!("bufferView {index}: bytes {start}..{end} are past the end of buffer {buffer}"))
}

/// One little-endian unsigned index of 1, 2 or 4 bytes.
fn read_index(bytes: &[u8]) -> u32 {
    match *bytes {
        [a] => u32::from(a),
        [a, b] => u32::from(u16::from_le_bytes([a, b])),
        [a, b, c, d] => u32::from_le_bytes([a, b, c, d]),
        _ => unreachable!("index sizes are 1, 2 or 4"),
    }
}

/// Accessor `index` as `N` floats per element: floats as they are, normalized integers mapped
/// to [0, 1] or [-1, 1], other integers (KHR_mesh_quantization) converted.
pub fn floats<const N: usize>(root: &Root, buffers: &Buffers, index: usize) -> Result<Vec<[f32; N]>, String> {
    let (layout, bytes) = packed(root, buffers, index)?;
    if layout.components != N {
        return Err(format!(
            "accessor {index}: {} components per element, {N} expected",
            layout.components
        ));
    }
    let size = layout.component.size();
    let convert = |c: &[u8]| -> f32 {
        match (layout.component, layout.normalized) {
            (ComponentType::F32, _) => f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
            (ComponentType::U8, true) => f32::from(c[0]) / 255.0,
            (ComponentType::I8, true) => (f32::from(c[0] as i8) / 127.0).max(-1.0),
            (ComponentType::U16, true) => f32::from(u16::from_le_bytes([c[0], c[1]])) / 65535.0,
            (ComponentType::I16, true) => (f32::from(i16::from_le_bytes([c[0], c[1]])) / 32767.0).max(-1.0),
            (ComponentType::U8, false) => f32::from(c[0]),
            (ComponentType::I8, false) => f32::from(c[0] as i8),
            (ComponentType::U16, false) => f32::from(u16::from_le_bytes([c[0], c[1]])),
            (ComponentType::I16, false) => f32::from(i16::from_le_bytes([c[0], c[1]])),
            (ComponentType::U32, _) => u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f32,
        }
    };
    Ok(bytes
        .chunks_exact(size * N)
        .map(|element| std::array::from_fn(|k| convert(&element[k * size..(k + 1) * size])))
        .collect())
}

/// Accessor `index` as indices (unsigned byte, short or int scalars).
pub fn indices(root: &Root, buffers: &Buffers, index: usize) -> Result<Vec<u32>, String> {
    let (layout, bytes) = packed(root, buffers, index)?;
    let size = layout.component.size();
    let unsigned = matches!(
        layout.component,
        ComponentType::U8 | ComponentType::U16 | ComponentType::U32
    );
    if layout.components != 1 || !unsigned {
        return Err(format!("accessor {index}: indices must be unsigned scalars"));
    }
    Ok(bytes.chunks_exact(size).map(read_index).collect())
}
