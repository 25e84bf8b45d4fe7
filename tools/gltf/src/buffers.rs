//! The document's buffers as bytes, and the new binary data: bufferViews and accessors appended
//! after the existing ones, whose data goes into one buffer (existing ones are never renumbered).

use std::path::Path;

use serde_json::{json, Value};

use crate::document::{self, Buffer};
use crate::memory;
use crate::uri;

/// Every buffer's bytes, from the GLB's binary chunk, a data URI or a file beside the document.
pub fn load(json: &Value, mut glb_bin: Option<Vec<u8>>, dir: &Path) -> Result<Vec<Option<Vec<u8>>>, String> {
    let count = document::count(json, "buffers");
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let buffer = Buffer::read(json, i)?;
        let length = buffer.byte_length;
        let bytes = match buffer.uri {
            None if i == 0 && glb_bin.is_some() => {
                let bin = glb_bin.take().unwrap_or_default();
                if bin.len() < length {
                    return Err(format!(
                        "buffer 0: the GLB binary chunk has {} bytes, fewer than its byteLength {length}",
                        bin.len()
                    ));
                }
                bin
            }
            None if is_fallback(&json["buffers"][i]) => {
                out.push(None);
                continue;
            }
            None => {
                return Err(format!(
                    "missing buffer {i}: it has no uri and no GLB binary chunk holds it"
                ))
            }
            Some(text) => match uri::data(text) {
                Some(decoded) => decoded.map_err(|e| format!("buffer {i}: {e}"))?,
                None if uri::readable(text) => {
                    let path = uri::resolve(dir, text);
                    crate::io::read_file(&path)
                        .map_err(|e| format!("missing buffer {i}: cannot read {}: {e}", path.display()))?
                }
                None => return Err(format!("buffer {i}: cannot load {text}: only files and data URIs")),
            },
        };
        if bytes.len() < length {
            return Err(format!(
                "buffer {i}: {} bytes, fewer than its byteLength {length}",
                bytes.len()
            ));
        }
        out.push(Some(bytes));
    }
    Ok(out)
}

/// A buffer that only stands in for data a compression extension holds.
fn is_fallback(buffer: &Value) -> bool {
    let extensions = &buffer["extensions"];
    ["EXT_meshopt_compression", "KHR_meshopt_compression"]
        .iter()
        .any(|name| extensions[name]["fallback"].as_bool() == Some(true))
}

/// One primitive's new data, and the bufferViews and accessors that describe it, numbered from 0
/// within it: primitives fill theirs on separate threads, then [`append_segments`] puts them one after the
/// other in the document.
#[derive(Default)]
pub struct Segment {
    bytes: Vec<u8>,
    views: Vec<View>,
    /// Each one's `bufferView` is an index into `views`.
    accessors: Vec<Value>,
}

struct View {
    offset: usize,
    length: usize,
    stride: Option<usize>,
    target: u64,
}

impl Segment {
    /// Appends a bufferView of `length` zero bytes (4-byte aligned, as vertex attributes need)
    /// and returns its index and the bytes to fill in place; `stride` is written for vertex data
    /// whose elements are padded.
    pub fn view_mut(
        &mut self,
        length: usize,
        stride: Option<usize>,
        target: u64,
    ) -> Result<(usize, &mut [u8]), String> {
        let offset = self.bytes.len();
        let padded_end = offset
            .checked_add(length)
            .and_then(|end| end.checked_next_multiple_of(4))
            .ok_or_else(|| too_long(length))?;
        memory::resize(&mut self.bytes, padded_end, 0, "new buffer data")?;
        self.views.push(View {
            offset,
            length,
            stride,
            target,
        });
        Ok((self.views.len() - 1, &mut self.bytes[offset..offset + length]))
    }

    /// Appends an accessor and returns its index.
    pub fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }
}

fn too_long(length: usize) -> String {
    format!("{length} more bytes do not fit in a buffer")
}

/// The segments placed: their bytes, one after the other, and where each one's accessors begin.
pub struct Placed {
    pub pieces: Vec<Vec<u8>>,
    /// The buffer's byteLength with the new data.
    pub end: usize,
    /// The document's index of each segment's first accessor.
    pub first_accessors: Vec<usize>,
}

/// Places `segments` one after the other from byte `base` (a multiple of 4) of buffer `buffer`,
/// and appends their bufferViews and accessors to the document's, after those it has (which are
/// never renumbered).
pub fn append_segments(json: &mut Value, segments: Vec<Segment>, buffer: usize, base: usize) -> Result<Placed, String> {
    debug_assert_eq!(base % 4, 0);
    let mut first_view = document::count(json, "bufferViews");
    let mut first_accessor = document::count(json, "accessors");
    let (mut views, mut accessors) = (Vec::new(), Vec::new());
    let mut placed = Placed {
        pieces: Vec::with_capacity(segments.len()),
        end: base,
        first_accessors: Vec::with_capacity(segments.len()),
    };
    for segment in segments {
        let segment_base = placed.end;
        // The buffer's new end must fit: the offsets below add up to it.
        placed.end = segment_base
            .checked_add(segment.bytes.len())
            .ok_or_else(|| too_long(segment.bytes.len()))?;
        for view in &segment.views {
            let mut json = json!({
                "buffer": buffer,
                "byteOffset": segment_base + view.offset,
                "byteLength": view.length,
            });
            if let Some(stride) = view.stride {
                json["byteStride"] = json!(stride);
            }
            json["target"] = json!(view.target);
            views.push(json);
        }
        placed.first_accessors.push(first_accessor);
        first_accessor += segment.accessors.len();
        for mut accessor in segment.accessors {
            let local = accessor["bufferView"]
                .as_u64()
                .expect("a segment's accessor names its view");
            accessor["bufferView"] = json!(first_view + local as usize);
            accessors.push(accessor);
        }
        first_view += segment.views.len();
        placed.pieces.push(segment.bytes);
    }
    for (key, items) in [("bufferViews", views), ("accessors", accessors)] {
        let list = json
            .as_object_mut()
            .expect("the document is an object")
            .entry(key)
            .or_insert_with(|| Value::Array(Vec::new()));
        if let Value::Array(list) = list {
            list.extend(items);
        }
    }
    Ok(placed)
}
