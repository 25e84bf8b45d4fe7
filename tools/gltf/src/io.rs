//! Reading a .gltf or .glb into its JSON and its buffers; writing one through a temporary file in
//! the destination folder, renamed into place.

use std::fs::{self, File};
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
    let cannot_read = |e: std::io::Error| format!("cannot read it: {e}");
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file = File::open(path).map_err(cannot_read)?;
    // A GLB's binary chunk is read straight into its own buffer; everything else whole.
    let length = regular_file_length(&file).map_err(cannot_read)?;
    let head = match length {
        Some(length) => read_range(&file, 0..length.min(GLB_HEAD)).map_err(cannot_read)?,
        None => Vec::new(),
    };
    let (Some(length), true) = (length, head.starts_with(b"glTF") && head.len() == GLB_HEAD) else {
        return parse(read_whole(&file).map_err(cannot_read)?, dir, allow_outside_uris);
    };
    let json_length = u32::from_le_bytes([head[12], head[13], head[14], head[15]]) as usize;
    // Up to the binary chunk's header, included.
    let before_bin = (GLB_HEAD + json_length).saturating_add(8).min(length);
    let head = read_range(&file, 0..before_bin).map_err(cannot_read)?;
    let (json_range, bin_range) = glb_chunks(&head, length).map_err(|e| format!("not a valid GLB file: {e}"))?;
    let bin = bin_range
        .map(|range| read_range(&file, range))
        .transpose()
        .map_err(cannot_read)?;
    finish(Kind::Glb, parse_json(&head[json_range])?, bin, dir, allow_outside_uris)
}

/// The bytes of the file at `path`: a regular file as `read_range` reads, anything else to its
/// end.
pub fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    read_whole(&File::open(path)?)
}

/// All of `file`: a regular file as `read_range` reads; one whose length is not known before it
/// is read, to its end.
fn read_whole(mut file: &File) -> std::io::Result<Vec<u8>> {
    match regular_file_length(file)? {
        Some(length) => read_range(file, 0..length),
        None => {
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut file, &mut bytes)?;
            Ok(bytes)
        }
    }
}

/// The length of `file` when it is known before it is read: a regular file's, unless 0 (the
/// files of /proc and /sys say 0 and have bytes).
fn regular_file_length(file: &File) -> std::io::Result<Option<usize>> {
    let metadata = file.metadata()?;
    if !metadata.is_file() || metadata.len() == 0 {
        return Ok(None);
    }
    let length = usize::try_from(metadata.len()).map_err(|_| std::io::ErrorKind::OutOfMemory)?;
    Ok(Some(length))
}

/// Bytes of a GLB before its JSON: the header and the JSON chunk's header.
const GLB_HEAD: usize = 20;

/// The bytes `range` of `file`. A large range is read in two halves on two threads (on Unix), so
/// that the kernel's copy into fresh pages, and the mapping of those pages, run on both cores.
fn read_range(file: &File, range: Range<usize>) -> std::io::Result<Vec<u8>> {
    let two_threads_from = if cfg!(unix) { 8 << 20 } else { usize::MAX };
    let mut bytes = vec![0u8; range.len()];
    let half = if range.len() >= two_threads_from {
        range.len() / 2
    } else {
        range.len()
    };
    let (first, second) = bytes.split_at_mut(half);
    let second_start = (range.start + half) as u64;
    std::thread::scope(|scope| {
        let second = (!second.is_empty()).then(|| scope.spawn(|| read_at(file, second, second_start)));
        read_at(file, first, range.start as u64)?;
        second.map_or(Ok(()), |thread| {
            thread.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        })
    })?;
    Ok(bytes)
}

#[cfg(unix)]
fn read_at(file: &File, bytes: &mut [u8], at: u64) -> std::io::Result<()> {
    std::os::unix::fs::FileExt::read_exact_at(file, bytes, at)
}

/// One thread at a time only: the file's position moves.
#[cfg(not(unix))]
fn read_at(mut file: &File, bytes: &mut [u8], at: u64) -> std::io::Result<()> {
    use std::io::{Read, Seek, SeekFrom};
    file.seek(SeekFrom::Start(at))?;
    file.read_exact(bytes)
}

/// Reads and checks the bytes of a .gltf or .glb (told apart by GLB's magic) whose relative URIs
/// resolve against `dir`.
pub fn parse(mut bytes: Vec<u8>, dir: PathBuf, allow_outside_uris: bool) -> Result<Asset, String> {
    if !bytes.starts_with(b"glTF") {
        return finish(Kind::Gltf, parse_json(&bytes)?, None, dir, allow_outside_uris);
    }
    let (json_range, bin_range) = glb_chunks(&bytes, bytes.len()).map_err(|e| format!("not a valid GLB file: {e}"))?;
    let json = parse_json(&bytes[json_range])?;
    // The binary chunk keeps the allocation, cut down to it.
    let bin = bin_range.map(|range| {
        bytes.truncate(range.end);
        bytes.drain(..range.start);
        bytes
    });
    finish(Kind::Glb, json, bin, dir, allow_outside_uris)
}

/// Checks the document and loads its buffers.
fn finish(
    kind: Kind,
    json: Value,
    bin: Option<Vec<u8>>,
    dir: PathBuf,
    allow_outside_uris: bool,
) -> Result<Asset, String> {
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
/// copy other files of its machine into its output, nor point the output at them. A buffer URI
/// with a scheme other than `data:` is left to [`buffers::load`], which never reads one, flag or
/// not.
fn check_uris_stay_inside(json: &Value, dir: &Path) -> Result<(), String> {
    for (list, index, text) in uri::document_uris(json) {
        if list == "buffer" && !uri::readable(text) {
            continue;
        }
        if let Some(why) = uri::outside(dir, text) {
            return Err(format!(
                "{list} {index}: its uri {text:?} {why}, outside the file's folder; \
                 --allow-outside-uris accepts it all the same"
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
fn glb_chunks(bytes: &[u8], file_length: usize) -> Result<(Range<usize>, Option<Range<usize>>), String> {
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
    if !(12..=file_length).contains(&(length as usize)) {
        return Err(format!("its header gives {length} bytes, the file has {file_length}"));
    }
    // The range of the bytes of a chunk at `at` that must be of type `kind`.
    let chunk = |at: usize, kind: &[u8; 4], name: &str| -> Result<Range<usize>, String> {
        let start = at.checked_add(8).filter(|&start| start <= bytes.len().min(file_length));
        let (Some(start), Some(length)) = (start, word(at)) else {
            return Err(format!("its {name} chunk header is cut short"));
        };
        if &bytes[at + 4..start] != kind {
            return Err(format!("no {name} chunk where one belongs"));
        }
        start
            .checked_add(length as usize)
            .filter(|&end| end <= file_length)
            .map(|end| start..end)
            .ok_or_else(|| format!("its {name} chunk of {length} bytes runs past the end of the file"))
    };
    let json = chunk(12, b"JSON", "JSON")?;
    let bin = if json.end < file_length {
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
/// the main file, not it), and put back when the main file cannot be written. New files get
/// `like`'s permissions, and are writable by their owner (inputs are often read-only).
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
    // Side files that `replace_side_files` replaces, with a second name kept until the main file
    // is in place, under which they are put back if it is not: the output before stays whole.
    // The replacement itself is one rename, so an interrupted run leaves one or the other.
    let mut backups: Vec<(tempfile::TempPath, &Path)> = Vec::new();
    for (k, (file, path)) in staged.into_iter().enumerate() {
        let result = if k == main {
            file.persist(path).map(drop).map_err(|e| e.error)
        } else if replace_side_files {
            back_up(path).and_then(|backup| {
                backups.extend(backup.map(|backup| (backup, path.as_path())));
                file.persist(path).map(drop).map_err(|e| e.error)
            })
        } else {
            file.persist_noclobber(path).map(drop).map_err(|e| e.error)
        };
        if let Err(error) = result {
            for done in placed {
                let _ = fs::remove_file(done);
            }
            let mut message = if error.kind() == std::io::ErrorKind::AlreadyExists {
                format!(
                    "{} exists and this run did not write it; remove it, or pass --force to replace it",
                    path.display()
                )
            } else {
                format!("cannot rename into {}: {error}", path.display())
            };
            for (backup, path) in backups {
                if let Err(failed) = backup.persist(path) {
                    let kept = failed.path.keep().unwrap_or_default();
                    message += &format!(
                        "; the earlier {} could not be put back ({}): it is {}",
                        path.display(),
                        failed.error,
                        kept.display()
                    );
                }
            }
            return Err(message);
        }
        placed.push(path);
    }
    Ok(())
}

/// A second name beside the file at `path`, if there is one: a hard link, or a copy where the
/// file system has none. Removed when dropped.
fn back_up(path: &Path) -> std::io::Result<Option<tempfile::TempPath>> {
    if fs::symlink_metadata(path).is_err() {
        return Ok(None);
    }
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    let backup = tempfile::Builder::new()
        .prefix(".tbasis-gltf-old-")
        .tempfile_in(dir)?
        .into_temp_path();
    // The link needs the name free; the temporary file only reserved it.
    fs::remove_file(&backup)?;
    if fs::hard_link(path, &backup).is_err() {
        fs::copy(path, &backup)?;
    }
    Ok(Some(backup))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A GLB of a document with one buffer of `bin` bytes.
    fn glb(bin: &[u8]) -> Vec<u8> {
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}]}}"#,
            bin.len()
        );
        let json_length = json.len().next_multiple_of(4);
        let bin_length = bin.len().next_multiple_of(4);
        let mut bytes = b"glTF".to_vec();
        bytes.extend(2u32.to_le_bytes());
        bytes.extend(((28 + json_length + bin_length) as u32).to_le_bytes());
        bytes.extend((json_length as u32).to_le_bytes());
        bytes.extend(b"JSON");
        bytes.extend(json.as_bytes());
        bytes.resize(20 + json_length, b' ');
        bytes.extend((bin_length as u32).to_le_bytes());
        bytes.extend(b"BIN\0");
        bytes.extend(bin);
        bytes.resize(28 + json_length + bin_length, 0);
        bytes
    }

    #[test]
    fn reading_a_file_gives_what_parsing_its_bytes_gives() {
        // `read` takes a GLB's binary chunk straight from the file (in two halves from 8 MiB);
        // `parse` cuts it out of the bytes in memory. Whole, cut short anywhere, or lying about
        // its lengths, a file must give the same document, buffers or message either way.
        let dir = tempfile::tempdir().unwrap();
        let small = glb(&[7; 40]);
        let large = glb(&(0..9 << 20).map(|i: u32| (i % 251) as u8).collect::<Vec<_>>());
        let mut cases = vec![
            small.clone(),
            large.clone(),
            b"{\"asset\":{\"version\":\"2.0\"}}".to_vec(),
        ];
        cases.extend(
            [0, 4, 12, 19, 20, 21, 60, 79, 80, 84, 87, 88, 100, 127].map(|cut| small[..cut.min(small.len())].to_vec()),
        );
        cases.push(large[..large.len() - 1].to_vec());
        let mut extended = small.clone();
        extended.extend(b"more");
        cases.push(extended);
        for (offset, value) in [(8, u32::MAX), (12, 1 << 20), (12, 3), (12, u32::MAX)] {
            let mut lying = small.clone();
            lying[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
            cases.push(lying);
        }
        let summary = |asset: Result<Asset, String>| asset.map(|a| (a.kind, a.json, a.buffers));
        // The intact files load, with their binary chunk: a reader that refused every file
        // would otherwise pass the comparisons below.
        for (k, (bytes, bin_length)) in [(&small, 40), (&large, 9 << 20)].into_iter().enumerate() {
            let path = dir.path().join(format!("intact{k}.glb"));
            fs::write(&path, bytes).unwrap();
            let (kind, _, buffers) = summary(read(&path, false)).unwrap();
            assert_eq!((kind, buffers[0].as_ref().map(Vec::len)), (Kind::Glb, Some(bin_length)));
        }
        for (k, bytes) in cases.into_iter().enumerate() {
            let path = dir.path().join(format!("case{k}.glb"));
            fs::write(&path, &bytes).unwrap();
            let from_file = summary(read(&path, false));
            let from_bytes = summary(parse(bytes, dir.path().to_path_buf(), false));
            assert_eq!(from_file, from_bytes, "case {k}");
        }
        // A file whose length is not known before it is read (0 here, with bytes): read to its
        // end all the same.
        #[cfg(target_os = "linux")]
        {
            let status = Path::new("/proc/self/status");
            let bytes = fs::read(status).unwrap();
            assert!(!bytes.is_empty() && fs::metadata(status).unwrap().len() == 0);
            let from_proc = summary(read(status, false));
            assert_eq!(from_proc, summary(parse(bytes, PathBuf::from("/proc/self"), false)));
        }
    }
}
