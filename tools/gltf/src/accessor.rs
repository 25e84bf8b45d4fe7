//! Reading accessors: their elements as packed bytes (sparse substitutions applied), as floats,
//! or as indices.

use serde_json::Value;
use tbasis::{Element, Indices, Strided};

use crate::document::{Accessor, BufferView, ComponentType, Sparse};
use crate::memory;

/// Buffers as loaded (see [`crate::buffers::load`]).
pub type Buffers = [Option<Vec<u8>>];

/// The most elements an accessor without a bufferView may hold. Its count is not bounded by the
/// file: a few bytes of JSON could otherwise ask for more memory than the machine has. Each
/// element, a corner's index most of all, costs tens of bytes further on (a tangent per corner,
/// the library's working memory), so the bound is on elements: 16,777,216 (16 Mi).
pub const MAX_ZEROS: usize = 1 << 24;

/// What one element of an accessor is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    pub component: ComponentType,
    pub components: usize,
    pub normalized: bool,
    pub count: usize,
}

impl Layout {
    /// At most 16 bytes: a matrix is no layout.
    pub fn element_size(&self) -> usize {
        self.component.size() * self.components
    }
}

/// The layout of accessor `index`; matrices are refused (no vertex attribute or index is one).
pub fn layout(json: &Value, index: usize) -> Result<Layout, String> {
    layout_of(&Accessor::read(json, index)?, index)
}

fn layout_of(accessor: &Accessor, index: usize) -> Result<Layout, String> {
    let components = accessor
        .element_type
        .vector_components()
        .ok_or_else(|| format!("accessor {index}: a matrix where vertex data was expected"))?;
    Ok(Layout {
        component: accessor.component_type,
        components,
        normalized: accessor.normalized,
        count: accessor.count,
    })
}

/// The elements of accessor `index`, packed (no stride), with sparse substitutions applied.
pub fn packed(json: &Value, buffers: &Buffers, index: usize) -> Result<(Layout, Vec<u8>), String> {
    let accessor = Accessor::read(json, index)?;
    let layout = layout_of(&accessor, index)?;
    // Checked before anything is allocated: the size, and where the elements lie.
    let place = located(json, buffers, index, &accessor, layout)?;
    let size = layout.element_size();
    let mut out = memory::filled(layout.count * size, 0u8, &format!("accessor {index}"))?;
    write_elements(json, buffers, index, (&accessor, layout, place), &mut out, size)?;
    Ok((layout, out))
}

/// Writes the elements of accessor `index` (sparse substitutions applied) into `out`, one every
/// `out_stride` bytes; `out` must hold them, and is left as it is around them.
pub fn copy_into(
    json: &Value,
    buffers: &Buffers,
    index: usize,
    out: &mut [u8],
    out_stride: usize,
) -> Result<(), String> {
    let accessor = Accessor::read(json, index)?;
    let layout = layout_of(&accessor, index)?;
    let place = located(json, buffers, index, &accessor, layout)?;
    write_elements(json, buffers, index, (&accessor, layout, place), out, out_stride)
}

/// Where an accessor's elements lie, as [`located`] returns it.
type Place<'a> = Option<(&'a [u8], usize)>;

fn write_elements(
    json: &Value,
    buffers: &Buffers,
    index: usize,
    (accessor, layout, place): (&Accessor, Layout, Place),
    out: &mut [u8],
    out_stride: usize,
) -> Result<(), String> {
    let size = layout.element_size();
    let slots = out.chunks_mut(out_stride).take(layout.count);
    match place {
        // A stride may be shorter than an element (elements that overlap): `bytes` ends with
        // the last element.
        Some((bytes, stride)) => {
            for (e, slot) in slots.enumerate() {
                slot[..size].copy_from_slice(&bytes[e * stride..e * stride + size]);
            }
        }
        None => slots.for_each(|slot| slot[..size].fill(0)),
    }
    if let Some(sparse) = &accessor.sparse {
        apply_sparse(json, buffers, index, sparse, (size, out_stride), layout.count, out)?;
    }
    Ok(())
}

/// Where the elements of `accessor` (number `index`) lie: the bytes from its first element on
/// and the stride, checked to hold every element; `None` without a bufferView (zeros, at most
/// [`MAX_ZEROS`] elements of them).
fn located<'a>(
    json: &Value,
    buffers: &'a Buffers,
    index: usize,
    accessor: &Accessor,
    layout: Layout,
) -> Result<Place<'a>, String> {
    let size = layout.element_size();
    let what = format!("accessor {index}");
    let Some(view_index) = accessor.buffer_view else {
        if layout.count > MAX_ZEROS {
            return Err(format!(
                "{what}: {} elements without a bufferView (at most {MAX_ZEROS} are read)",
                layout.count
            ));
        }
        return Ok(None);
    };
    let view = BufferView::read(json, view_index)?;
    let stride = view.byte_stride.unwrap_or(size);
    let start = accessor.byte_offset;
    let bytes = view_bytes(&view, view_index, buffers)?;
    // The end of the last element.
    let end = match layout.count.checked_sub(1) {
        None => Some(start),
        Some(last) => last
            .checked_mul(stride)
            .and_then(|x| x.checked_add(start))
            .and_then(|x| x.checked_add(size)),
    }
    .ok_or_else(|| format!("{what}: too large"))?;
    if end > bytes.len() {
        return Err(format!(
            "{what}: needs {end} bytes of bufferView {view_index}, which has {}",
            bytes.len()
        ));
    }
    Ok(Some((&bytes[start..end], stride)))
}

/// The elements of accessor `index` where they lie in its buffer, when the library reads them
/// as stored: a bufferView, no sparse substitution, components of type `component`, and a
/// little-endian machine (glTF's byte order).
fn in_place<'a, T: Element>(
    json: &Value,
    buffers: &'a Buffers,
    index: usize,
    component: ComponentType,
) -> Result<Option<Strided<'a, T>>, String> {
    let accessor = Accessor::read(json, index)?;
    let layout = layout_of(&accessor, index)?;
    let stored_as_read = cfg!(target_endian = "little")
        && accessor.sparse.is_none()
        && layout.component == component
        && !layout.normalized
        && layout.element_size() == size_of::<T>();
    if !stored_as_read {
        return Ok(None);
    }
    // Elements that overlap (a stride shorter than an element) are copied apart instead.
    Ok(match located(json, buffers, index, &accessor, layout)? {
        Some((bytes, stride)) if stride >= size_of::<T>() => {
            Some(Strided::from_bytes(bytes, stride, layout.count).map_err(|e| format!("accessor {index}: {e}"))?)
        }
        _ => None,
    })
}

/// Writes the substituted elements into `out`, `count` elements of `size` bytes.
fn apply_sparse(
    json: &Value,
    buffers: &Buffers,
    index: usize,
    sparse: &Sparse,
    (size, out_stride): (usize, usize),
    count: usize,
    out: &mut [u8],
) -> Result<(), String> {
    let n = sparse.count;
    let index_size = sparse.index_type.size();
    let part_bytes = |view: usize| BufferView::read(json, view).and_then(|v| view_bytes(&v, view, buffers));
    let indices = part_bytes(sparse.indices_view)?;
    let values = part_bytes(sparse.values_view)?;
    let end = |start: usize, size: usize| n.checked_mul(size).and_then(|x| x.checked_add(start));
    let fits = |end: Option<usize>, len: usize| end.is_some_and(|end| end <= len);
    if !fits(end(sparse.indices_offset, index_size), indices.len())
        || !fits(end(sparse.values_offset, size), values.len())
    {
        return Err(format!(
            "sparse accessor {index}: its {n} indices or values run past their bufferViews"
        ));
    }
    // Within the lengths checked above, and `target` within `count`.
    for k in 0..n {
        let at = sparse.indices_offset + k * index_size;
        let target = read_index(&indices[at..at + index_size]) as usize;
        if target >= count {
            return Err(format!(
                "sparse accessor {index}: substitutes element {target} of {count}"
            ));
        }
        let from = sparse.values_offset + k * size;
        let to = target * out_stride;
        out[to..to + size].copy_from_slice(&values[from..from + size]);
    }
    Ok(())
}

/// The bytes of bufferView `view` (number `index`), checked against its buffer.
fn view_bytes<'a>(view: &BufferView, index: usize, buffers: &'a Buffers) -> Result<&'a [u8], String> {
    let buffer = view.buffer;
    let bytes = buffers
        .get(buffer)
        .ok_or_else(|| format!("bufferView {index}: buffer {buffer} does not exist"))?
        .as_deref()
        .ok_or_else(|| format!("bufferView {index}: buffer {buffer} holds no data (a compression fallback)"))?;
    let start = view.byte_offset;
    view.byte_length
        .checked_add(start)
        .and_then(|end| bytes.get(start..end))
        .ok_or_else(|| {
            format!(
                "bufferView {index}: {} bytes from byte {start} are past the end of buffer {buffer}",
                view.byte_length
            )
        })
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

/// Accessor `index` as `N` floats per element: floats where they lie in the buffer when they can
/// be read in place (`in_place`), else converted into `storage`: normalized integers mapped to
/// [0, 1] or [-1, 1], other integers (KHR_mesh_quantization) converted.
pub fn floats<'a, const N: usize>(
    json: &Value,
    buffers: &'a Buffers,
    index: usize,
    storage: &'a mut Vec<[f32; N]>,
) -> Result<Strided<'a, [f32; N]>, String>
where
    [f32; N]: Element,
{
    if let Some(view) = in_place(json, buffers, index, ComponentType::Float)? {
        return Ok(view);
    }
    let (layout, bytes) = packed(json, buffers, index)?;
    if layout.components != N {
        return Err(format!(
            "accessor {index}: {} components per element, {N} expected",
            layout.components
        ));
    }
    let size = layout.component.size();
    let convert = |c: &[u8]| -> f32 {
        match (layout.component, layout.normalized) {
            (ComponentType::Float, _) => f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
            (ComponentType::UnsignedByte, true) => f32::from(c[0]) / 255.0,
            (ComponentType::Byte, true) => (f32::from(c[0] as i8) / 127.0).max(-1.0),
            (ComponentType::UnsignedShort, true) => f32::from(u16::from_le_bytes([c[0], c[1]])) / 65535.0,
            (ComponentType::Short, true) => (f32::from(i16::from_le_bytes([c[0], c[1]])) / 32767.0).max(-1.0),
            (ComponentType::UnsignedByte, false) => f32::from(c[0]),
            (ComponentType::Byte, false) => f32::from(c[0] as i8),
            (ComponentType::UnsignedShort, false) => f32::from(u16::from_le_bytes([c[0], c[1]])),
            (ComponentType::Short, false) => f32::from(i16::from_le_bytes([c[0], c[1]])),
            (ComponentType::UnsignedInt, _) => u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f32,
        }
    };
    let elements = bytes
        .chunks_exact(size * N)
        .map(|element| std::array::from_fn(|k| convert(&element[k * size..(k + 1) * size])));
    *storage = memory::collect(layout.count, elements, &format!("accessor {index}"))?;
    Ok(Strided::from_slice(storage))
}

/// Accessor `index` as indices (unsigned byte, short or int scalars): 16- and 32-bit indices where
/// they lie in the buffer when they can be read in place (`in_place`), else converted into
/// `storage`.
pub fn indices<'a>(
    json: &Value,
    buffers: &'a Buffers,
    index: usize,
    storage: &'a mut Vec<u32>,
) -> Result<Indices<'a>, String> {
    let layout = layout(json, index)?;
    if layout.components != 1 || !layout.component.is_index() {
        return Err(format!("accessor {index}: indices must be unsigned scalars"));
    }
    let read_in_place = match layout.component {
        ComponentType::UnsignedShort => in_place(json, buffers, index, layout.component)?.map(Indices::U16),
        ComponentType::UnsignedInt => in_place(json, buffers, index, layout.component)?.map(Indices::U32),
        _ => None,
    };
    if let Some(indices) = read_in_place {
        return Ok(indices);
    }
    let (layout, bytes) = packed(json, buffers, index)?;
    let indices = bytes.chunks_exact(layout.component.size()).map(read_index);
    *storage = memory::collect(layout.count, indices, &format!("accessor {index}"))?;
    Ok(Indices::U32(Strided::from_slice(storage)))
}
