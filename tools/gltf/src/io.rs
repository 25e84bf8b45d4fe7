//! Reading a .gltf or .glb into its JSON and its buffers; writing one through a temporary file in
//! the destination folder, renamed into place.

use std::fs;
use std::io::Write;
use std::ops::Range;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::convert::Files;
use crate::{buffers, document, uri};

/// Required extensions whose data the tool cannot decode: compressed geometry.
const UNDECODABLE: [(&str, &str); 3] = [
    ("KHR_draco_mesh_compression", "Draco mesh compression"),
    ("EXT_meshopt_compression", "meshopt compression"),
    ("KHR_meshopt_compression", "meshopt compression"),
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Gltf,
    Glb,
}

/// A document as read.
pub struct Asset {
    pub kind: Kind,
    /// The whole document, checked ([`document::check`]): edited, then written back.
    pub json: Value,
    /// Each buffer's bytes; `None` for a fallback buffer that holds none (meshopt).
    pub buffers: Vec<Option<Vec<u8>>>,
    /// The folder relative URIs resolve against.
    pub dir: PathBuf,
}

/// Reads and checks `path`; the error says what is wrong (the caller names the file). Buffers
/// and images must stay in the file's folder unless `allow_outside_uris` ([`uri::outside`]).
pub fn read(path: &Path, allow_outside_uris: bool) -> Result<Asset, String> {
    let bytes = fs::read(path).map_err(|e| format!("cannot read it: {e}"))?;
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
        _ => PathBuf::from("."),
    };
    parse(bytes, dir, allow_outside_uris)
}

/// Reads and checks the bytes of a .gltf or .glb (told apart by GLB's magic) whose relative URIs
/// resolve against `dir`.
pub fn parse(mut bytes: Vec<u8>, dir: PathBuf, allow_outside_uris: bool) -> Result<Asset, String> {
    let (kind, json, bin) = if bytes.starts_with(b"glTF") {
        let (json_range, bin_range) = glb_chunks(&bytes).map_err(|e| format!("not a valid GLB file: {e}"))?;
        let json = parse_json(&bytes[json_range])?;
        // The binary chunk keeps the file's allocation, cut down to it: tens of MB not copied.
        let bin = bin_range.map(|range| {
            bytes.truncate(range.end);
            bytes.drain(..range.start);
            bytes
        });
        (Kind::Glb, json, bin)
    } else {
        (Kind::Gltf, parse_json(&bytes)?, None)
    };
    check_required_extensions(&json)?;
    document::check(&json)?;
    if !allow_outside_uris {
        check_uris_stay_inside(&json, &dir)?;
    }
    let buffers = buffers::load(&json, bin, &dir)?;
    Ok(Asset {
        kind,
        json,
        buffers,
        dir,
    })
}

/// Refuses a buffer or image URI that leads out of `dir`: a tool run on uploaded files must not
/// copy other files of its machine into its output, nor point the output at them.
fn check_uris_stay_inside(json: &Value, dir: &Path) -> Result<(), String> {
    for (list, index, text) in uri::document_uris(json) {
        if let Some(why) = uri::outside(dir, text) {
            return Err(format!(
                "{list} {index}: its uri {text:?} {why}, outside the file's folder; \
                 --allow-outside-uris reads it all the same"
            ));
        }
    }
    Ok(())
}

fn parse_json(bytes: &[u8]) -> Result<Value, String> {
    let json: Value = serde_json::from_slice(bytes).map_err(|e| format!("broken JSON: {e}"))?;
    if !json.is_object() {
        return Err("broken JSON: the document is not an object".into());
    }
    Ok(json)
}

/// Where a .glb's JSON chunk and binary chunk (if any) are. GLB 2.0: a 12-byte header (magic,
/// version, length), then chunks of an 8-byte header (length, type) and their bytes; the JSON
/// chunk first, a binary one next. Chunks after those two are ignored.
fn glb_chunks(bytes: &[u8]) -> Result<(Range<usize>, Option<Range<usize>>), String> {
    let word = |at: usize| -> Option<u32> {
        let word = bytes.get(at..at.checked_add(4)?)?;
        Some(u32::from_le_bytes(word.try_into().ok()?))
    };
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err("its header is cut short".into());
    };
    if version != 2 {
        return Err(format!("GLB version {version}, not 2"));
    }
    if !(12..=bytes.len()).contains(&(length as usize)) {
        return Err(format!("its header gives {length} bytes, the file has {}", bytes.len()));
    }
    // The range of the bytes of a chunk at `at` that must be of type `kind`.
    let chunk = |at: usize, kind: &[u8; 4], name: &str| -> Result<Range<usize>, String> {
        let start = at.checked_add(8).filter(|&start| start <= bytes.len());
        let (Some(start), Some(length)) = (start, word(at)) else {
            return Err(format!("its {name} chunk header is cut short"));
        };
        if &bytes[at + 4..start] != kind {
            return Err(format!("no {name} chunk where one belongs"));
        }
        start
            .checked_add(length as usize)
            .filter(|&end| end <= bytes.len())
            .map(|end| start..end)
            .ok_or_else(|| format!("its {name} chunk of {length} bytes runs past the end of the file"))
    };
    let json = chunk(12, b"JSON", "JSON")?;
    let bin = if json.end < bytes.len() {
        Some(chunk(json.end, b"BIN\0", "binary")?)
    } else {
        None
    };
    Ok((json, bin))
}

fn check_required_extensions(json: &Value) -> Result<(), String> {
    let required = json["extensionsRequired"]
        .as_array()
        .map(Vec::as_slice)
        .unwrap_or_default();
    for name in required.iter().filter_map(Value::as_str) {
        if let Some((_, what)) = UNDECODABLE.iter().find(|(ext, _)| *ext == name) {
            return Err(format!(
                "unsupported: it requires {name} ({what}), which tbasis-gltf cannot decode; decompress it first"
            ));
        }
    }
    Ok(())
}

/// The header and JSON chunk of a .glb holding `json`, up to the header of a binary chunk of
/// `bin_length` bytes (none when `None`); the caller writes those bytes after it, then
/// [`glb_padding`]. GLB 2.0: chunks are 4-byte aligned, JSON padded with spaces, binary with zeros.
pub fn glb_head(json: &Value, bin_length: Option<usize>) -> Result<Vec<u8>, String> {
    let mut json = serde_json::to_vec(json).map_err(|e| e.to_string())?;
    json.resize(json.len().next_multiple_of(4), b' ');
    let bin_chunk = bin_length.map_or(0, |length| 8 + length.next_multiple_of(4));
    let total = 12 + 8 + json.len() + bin_chunk;
    let field =
        |n: usize| u32::try_from(n).map_err(|_| format!("the GLB would be {total} bytes, over its 4 GiB limit"));
    let mut head = Vec::with_capacity(28 + json.len());
    head.extend_from_slice(b"glTF");
    head.extend_from_slice(&2u32.to_le_bytes());
    head.extend_from_slice(&field(total)?.to_le_bytes());
    head.extend_from_slice(&field(json.len())?.to_le_bytes());
    head.extend_from_slice(b"JSON");
    head.extend_from_slice(&json);
    if let Some(length) = bin_length {
        head.extend_from_slice(&field(length.next_multiple_of(4))?.to_le_bytes());
        head.extend_from_slice(b"BIN\0");
    }
    Ok(head)
}

/// The zeros that end a binary chunk of `bin_length` bytes on a 4-byte boundary.
pub fn glb_padding(bin_length: usize) -> &'static [u8] {
    &[0; 3][..bin_length.next_multiple_of(4) - bin_length]
}

/// The bytes of a .gltf holding `json`.
pub fn encode_gltf(json: &Value) -> Result<Vec<u8>, String> {
    let mut bytes = serde_json::to_vec_pretty(json).map_err(|e| e.to_string())?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// Refuses an output that is the input itself, by its path or through a link: the run would
/// replace what it reads.
pub fn refuse_to_replace_input(input: &Path, output: &Path) -> Result<(), String> {
    // An output that does not exist yet is no file at all.
    if same_file::is_same_file(input, output).unwrap_or(false) {
        return Err(format!(
            "the output {} is this file; write it elsewhere",
            output.display()
        ));
    }
    Ok(())
}

/// Writes the files of an output ([`crate::convert::Files`]: side files first, the main file
/// last) through temporary files beside them, then renames them into place in that order, so that
/// an interrupted run leaves no half-written file and the main file never names a side file that
/// is missing. When a rename fails, the files already renamed are removed: all of the output or
/// none of it. A side file that exists is replaced only with `replace_side_files` (the user named
/// the main file, not it). New files get `like`'s permissions, and are writable by their owner
/// (inputs are often read-only).
pub fn write_files(files: &Files, like: &Path, replace_side_files: bool) -> Result<(), String> {
    let permissions = fs::metadata(like).map(|m| writable(m.permissions())).ok();
    let mut staged = Vec::new();
    for (path, pieces) in files {
        let dir = match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        };
        let mut file = tempfile::Builder::new()
            .prefix(".tbasis-gltf-")
            .suffix(".tmp")
            .tempfile_in(dir)
            .map_err(|e| format!("cannot create a temporary file in {}: {e}", dir.display()))?;
        preallocate(file.as_file(), pieces.iter().map(|p| p.len()).sum());
        // A rename after the write is what an interrupted run needs; no fsync (that is for power loss).
        for piece in pieces {
            file.write_all(piece)
                .map_err(|e| format!("cannot write {}: {e}", file.path().display()))?;
        }
        if let Some(permissions) = &permissions {
            // Not fatal: the temporary file's own mode is private but valid.
            let _ = file.as_file().set_permissions(permissions.clone());
        }
        staged.push((file, path));
    }
    let main = staged.len().saturating_sub(1);
    let mut placed: Vec<&Path> = Vec::new();
    for (k, (file, path)) in staged.into_iter().enumerate() {
        let result = if k == main || replace_side_files {
            file.persist(path).map(drop)
        } else {
            file.persist_noclobber(path).map(drop)
        };
        if let Err(e) = result {
            for done in placed {
                let _ = fs::remove_file(done);
            }
            return Err(if e.error.kind() == std::io::ErrorKind::AlreadyExists {
                format!(
                    "{} exists and this run did not write it; remove it, or pass --force to replace it",
                    path.display()
                )
            } else {
                format!("cannot rename into {}: {}", path.display(), e.error)
            });
        }
        placed.push(path);
    }
    Ok(())
}

/// Reserves the file's blocks before the write. On ext4 a file written without them has its
/// blocks allocated and its pages flushed when it is renamed over an existing file, which took
/// longer than the write itself (about 0.1 s for 134 MB). Not fatal where unsupported.
#[cfg(target_os = "linux")]
fn preallocate(file: &fs::File, length: usize) {
    let _ = rustix::fs::fallocate(file, rustix::fs::FallocateFlags::empty(), 0, length as u64);
}

#[cfg(not(target_os = "linux"))]
fn preallocate(_file: &fs::File, _length: usize) {}

#[cfg(unix)]
fn writable(permissions: fs::Permissions) -> fs::Permissions {
    use std::os::unix::fs::PermissionsExt;
    fs::Permissions::from_mode(permissions.mode() | 0o200)
}

#[cfg(not(unix))]
fn writable(mut permissions: fs::Permissions) -> fs::Permissions {
    #[allow(clippy::permissions_set_readonly_false)]
    permissions.set_readonly(false);
    permissions
}
