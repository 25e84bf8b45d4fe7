//! The document's buffers as bytes, and the new binary data: bufferViews and accessors appended
//! after the existing ones, whose data goes into one buffer (existing ones are never renumbered).

use std::path::Path;

use serde_json::{json, Value};

use crate::document::{self, Buffer};
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
                None if uri::is_relative_file(text) => {
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

/// The new data, and the JSON of the bufferViews and accessors that describe it.
pub struct Appender {
    /// The bytes, to be placed at `base` in buffer `buffer`.
    pub bytes: Vec<u8>,
    pub buffer: usize,
    base: usize,
    first_view: usize,
    views: Vec<Value>,
    first_accessor: usize,
    accessors: Vec<Value>,
}

impl Appender {
    /// Data placed at byte `base` (a multiple of 4) of buffer `buffer`, with bufferViews and
    /// accessors numbered from the documents' current counts.
    pub fn new(buffer: usize, base: usize, first_view: usize, first_accessor: usize) -> Self {
        debug_assert_eq!(base % 4, 0);
        Appender {
            bytes: Vec::new(),
            buffer,
            base,
            first_view,
            views: Vec::new(),
            first_accessor,
            accessors: Vec::new(),
        }
    }

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
        // The buffer's new end must fit too: `end` adds it up unchecked.
        let padded_end = offset
            .checked_add(length)
            .and_then(|end| end.checked_next_multiple_of(4))
            .filter(|&end| self.base.checked_add(end).is_some())
            .ok_or_else(|| format!("{length} more bytes do not fit in a buffer"))?;
        self.bytes.resize(padded_end, 0);
        let mut view = json!({
            "buffer": self.buffer,
            "byteOffset": self.base + offset,
            "byteLength": length,
        });
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        view["target"] = json!(target);
        self.views.push(view);
        Ok((
            self.first_view + self.views.len() - 1,
            &mut self.bytes[offset..offset + length],
        ))
    }

    /// Appends an accessor and returns its index.
    pub fn accessor(&mut self, accessor: Value) -> usize {
        self.accessors.push(accessor);
        self.first_accessor + self.accessors.len() - 1
    }

    /// The buffer's byteLength once the data is placed.
    pub fn end(&self) -> usize {
        self.base + self.bytes.len()
    }

    /// Adds the new bufferViews and accessors to the document.
    pub fn append_json(self, json: &mut Value) -> Vec<u8> {
        for (key, items) in [("bufferViews", self.views), ("accessors", self.accessors)] {
            let list = json
                .as_object_mut()
                .expect("the document is an object")
                .entry(key)
                .or_insert_with(|| Value::Array(Vec::new()));
            if let Value::Array(list) = list {
                list.extend(items);
            }
        }
        self.bytes
    }
}
