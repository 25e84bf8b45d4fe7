//! One file, start to end: read, plan, compute the primitives and fill their new data (in
//! parallel), place that data, point URIs at the right files, write.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use serde_json::{json, Value};
use tbasis::Options;

use crate::accessor;
use crate::args::Job;
use crate::buffers::{self, Segment};
use crate::document::{self, Buffer};
use crate::io::{self, Asset, Kind};
use crate::primitive::{self, Edit, Workspace};
use crate::prune;
use crate::select::{self, Key, Plan, Source};
use crate::uri;

/// How every file is processed.
pub struct Settings {
    pub options: Options,
    pub overwrite: bool,
    /// Read buffers and images outside the input's folder ([`crate::uri::outside`]).
    pub allow_outside_uris: bool,
    /// Replace an existing side buffer (`OUT.tangents.bin`) that this run did not write.
    pub replace_side_files: bool,
    /// Threads for the primitives of one file.
    pub threads: usize,
    /// The side buffers this run writes.
    pub side_files: SideFiles,
}

/// The side buffers a run has written or is writing, so that no two inputs of one run write the
/// same one (`a.gltf` and a `.glb` without a binary chunk, both named `a`, into one folder).
#[derive(Default)]
pub struct SideFiles(Mutex<HashSet<PathBuf>>);

impl SideFiles {
    /// Takes `path` for the file being written, or says which input of the run already has.
    fn claim(&self, path: &Path) -> Result<(), String> {
        let mut claimed = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        if claimed.insert(path.to_path_buf()) {
            return Ok(());
        }
        Err(format!(
            "{} is the side buffer of another input of this run; give the inputs different names",
            path.display()
        ))
    }
}

/// What was done to one file.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Primitives that got tangents.
    pub done: usize,
    pub vertices_added: usize,
    /// Corners whose tangent was repaired (policies SKIP and INHERIT with MIKKTSPACE).
    pub repaired_corners: usize,
    /// Primitives left as they were: `mesh m primitive p: why`.
    pub left: Vec<String>,
    pub elapsed: Duration,
}

impl Outcome {
    /// Whether the file would be written with other contents.
    pub fn changes(&self) -> bool {
        self.done > 0
    }
}

/// Converts `job.input` into `job.output`; on error nothing has been written. Without an output
/// (`--check`), computes everything, writes nothing and says what would change.
pub fn convert(job: &Job, settings: &Settings) -> Result<Outcome, String> {
    let start = Instant::now();
    if let Some(output) = &job.output {
        io::refuse_to_replace_input(&job.input, output)?;
    }
    let asset = io::read(&job.input, settings.allow_outside_uris)?;
    // The output is written as the input is, and takes its kind from its name as the input does.
    let named = crate::args::kind_of(&job.input)?;
    let holds = match asset.kind {
        Kind::Glb => "glb",
        Kind::Gltf => "gltf",
    };
    if named != holds {
        return Err(format!(
            "its name says .{named} but it holds a .{holds} file; rename it"
        ));
    }
    let mut outcome = convert_asset(asset, job.output.as_deref(), settings, |files| {
        for (side_file, _) in &files[..files.len().saturating_sub(1)] {
            settings.side_files.claim(side_file)?;
        }
        io::write_files(files, &job.input, settings.replace_side_files)
    })?;
    outcome.elapsed = start.elapsed();
    Ok(outcome)
}

/// The files of an output: each path with its bytes in pieces, written one after the other; the
/// main file last.
pub type Files<'a> = [(PathBuf, Vec<&'a [u8]>)];

/// Adds tangents to `asset` and hands what `output` consists of to `write`; without an output,
/// only says what would change.
pub fn convert_asset(
    mut asset: Asset,
    output: Option<&Path>,
    settings: &Settings,
    write: impl FnOnce(&Files) -> Result<(), String>,
) -> Result<Outcome, String> {
    let mut outcome = Outcome::default();
    let used_before = prune::used(&asset.json);

    // Plan every primitive; identical ones are computed once and share the result.
    let mut sources: Vec<Source> = Vec::new();
    let mut users: Vec<Vec<(usize, usize)>> = Vec::new();
    let mut by_key: HashMap<Key, usize> = HashMap::new();
    for m in 0..document::count(&asset.json, "meshes") {
        for p in 0..document::primitive_count(&asset.json, m) {
            match select::plan(&asset.json, m, p, settings.overwrite)? {
                Plan::Leave(why) => outcome
                    .left
                    .push(format!("{}: {why}", primitive_name(&asset.json, m, p))),
                Plan::Process(source) => {
                    let slot = *by_key.entry(source.key()).or_insert_with(|| {
                        sources.push(source);
                        users.push(Vec::new());
                        sources.len() - 1
                    });
                    users[slot].push((m, p));
                }
            }
        }
    }

    let done = compute_all(&asset, &sources, settings)?;
    let original_buffers = document::count(&asset.json, "buffers");
    let any_done = !done.is_empty();
    let mut grown = None;
    if any_done {
        grown = append(&mut asset, &users, done, &mut outcome)?;
    }
    let Some(output) = output else {
        return Ok(outcome);
    };
    // Made only now, so that a file that fails before leaves no folder behind.
    if let Some(dir) = output.parent().filter(|dir| !dir.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let side_file = finish_buffers(&mut asset, original_buffers, output)?;
    rebase_uris(&mut asset, original_buffers, output)?;
    // After the buffers are placed: pruning keeps the new buffer last (`finish_buffers`).
    if let Some(used_before) = used_before.filter(|_| any_done) {
        prune::remove_unused(&mut asset.json, &mut asset.buffers, &used_before);
    }
    let mut files: Vec<(PathBuf, Vec<&[u8]>)> = Vec::new();
    if let Some(path) = side_file {
        let added = asset.buffers.last().and_then(Option::as_deref).unwrap_or_default();
        files.push((path, vec![added]));
    }
    let document;
    let main = match asset.kind {
        Kind::Glb => {
            let bin = glb_bin(&asset, grown.as_ref());
            let length = bin.as_ref().map(|pieces| pieces.iter().map(|p| p.len()).sum());
            document = io::glb_head(&asset.json, length)?;
            let mut pieces = vec![document.as_slice()];
            pieces.extend(bin.into_iter().flatten());
            pieces.extend(length.map(io::glb_padding));
            pieces
        }
        Kind::Gltf => {
            document = io::encode_gltf(&asset.json)?;
            vec![document.as_slice()]
        }
    };
    files.push((output.to_path_buf(), main));
    write(&files)?;
    Ok(outcome)
}

/// `mesh 2 primitive 0 ("Helmet")`: how messages name a primitive.
fn primitive_name(json: &Value, m: usize, p: usize) -> String {
    match json["meshes"][m]["name"].as_str() {
        Some(name) => format!("mesh {m} ({name:?}) primitive {p}"),
        None => format!("mesh {m} primitive {p}"),
    }
}

/// A primitive computed: its new data, and how it changes the document.
struct Done {
    edit: Edit,
    segment: Segment,
    repaired_corners: usize,
}

/// Every source's tangents, split and new data, on up to `settings.threads` threads; the first
/// error wins.
fn compute_all(asset: &Asset, sources: &[Source], settings: &Settings) -> Result<Vec<Done>, String> {
    let results: Vec<Mutex<Option<Result<Done, String>>>> = sources.iter().map(|_| Mutex::new(None)).collect();
    // Largest first: the threads finish together, and each thread's workspace is as large as it
    // will be at its first primitive, so that the later ones reuse its pages.
    let mut order: Vec<usize> = (0..sources.len()).collect();
    let size = |k: &usize| accessor::layout(&asset.json, sources[*k].position).map_or(0, |layout| layout.count);
    order.sort_by_key(|k| std::cmp::Reverse(size(k)));
    let next = AtomicUsize::new(0);
    // Threads the primitives leave idle (a file of one large primitive) go to each call; the bits
    // are the same on any thread count.
    let per_call = (settings.threads / sources.len().max(1)).max(1);
    let options = settings.options.with_threads(per_call as u32);
    let process = |source: &Source, workspace: &mut Workspace| -> Result<Done, String> {
        let computed = primitive::compute(source, &asset.json, &asset.buffers, &options, workspace)?;
        // In the worker, not after all primitives: a thread out of primitives to compute is
        // not idle while another fills its new data.
        let mut segment = Segment::default();
        let edit = primitive::edit(source, &computed, &asset.json, &asset.buffers, &mut segment)?;
        let repaired_corners = computed.report.repaired_corners;
        Ok(Done {
            edit,
            segment,
            repaired_corners,
        })
    };
    let work = || {
        let mut workspace = Workspace::default();
        while let Some(&k) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
            let source = &sources[k];
            let result = process(source, &mut workspace)
                .map_err(|e| format!("{}: {e}", primitive_name(&asset.json, source.mesh, source.primitive)));
            *results[k].lock().unwrap_or_else(|e| e.into_inner()) = Some(result);
        }
    };
    let threads = settings.threads.clamp(1, sources.len().max(1));
    std::thread::scope(|scope| {
        for _ in 1..threads {
            scope.spawn(work);
        }
        work();
    });
    results
        .into_iter()
        .map(|slot| {
            slot.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .expect("every source was computed")
        })
        .collect()
}

/// Places the new data and accessors, in source order, and points the primitives at them;
/// returns what [`place`] returns.
fn append(
    asset: &mut Asset,
    users: &[Vec<(usize, usize)>],
    done: Vec<Done>,
    outcome: &mut Outcome,
) -> Result<Option<Grown>, String> {
    let (buffer, old_length) = data_buffer(asset)?;
    let mut edits = Vec::with_capacity(done.len());
    let mut segments = Vec::with_capacity(done.len());
    for done in done {
        outcome.repaired_corners += done.repaired_corners;
        outcome.vertices_added += done.edit.vertices_added;
        edits.push(done.edit);
        segments.push(done.segment);
    }
    let placed = buffers::append_segments(&mut asset.json, segments, buffer, old_length.next_multiple_of(4))?;
    for ((edit, users), &first_accessor) in edits.iter().zip(users).zip(&placed.first_accessors) {
        for &(m, p) in users {
            primitive::apply(&mut asset.json["meshes"][m]["primitives"][p], edit, first_accessor);
            outcome.done += 1;
        }
    }
    Ok(place(asset, buffer, old_length, placed.end, placed.pieces))
}

/// The buffer the new data goes into, and its length so far: the GLB's own buffer (its first,
/// without a URI, holding the binary chunk), or a new buffer (its URI is chosen when the file is
/// written). A first buffer without a URI that holds no data (a meshopt fallback in a GLB
/// without a binary chunk) is not the GLB's own.
fn data_buffer(asset: &Asset) -> Result<(usize, usize), String> {
    if asset.kind == Kind::Glb && asset.buffers.first().is_some_and(Option::is_some) {
        let first = Buffer::read(&asset.json, 0)?;
        if first.uri.is_none() {
            return Ok((0, first.byte_length));
        }
    }
    Ok((document::count(&asset.json, "buffers"), 0))
}

/// New data for the GLB's own buffer, written after its old bytes and their padding (not copied
/// onto them), in pieces.
struct Grown {
    old_length: usize,
    pieces: Vec<Vec<u8>>,
}

/// Stores the new data in the buffer `data_buffer` chose: a new buffer, or the GLB's own, whose
/// new data is returned.
fn place(asset: &mut Asset, buffer: usize, old_length: usize, length: usize, pieces: Vec<Vec<u8>>) -> Option<Grown> {
    if buffer < asset.buffers.len() {
        asset.json["buffers"][buffer]["byteLength"] = json!(length);
        Some(Grown { old_length, pieces })
    } else {
        let list = asset
            .json
            .as_object_mut()
            .expect("the document is an object")
            .entry("buffers")
            .or_insert_with(|| Value::Array(Vec::new()));
        if let Value::Array(list) = list {
            // Its URI (none for a GLB's own buffer) is set by `finish_buffers`.
            list.push(json!({ "byteLength": length }));
        }
        asset.buffers.push(Some(pieces.concat()));
        None
    }
}

/// Gives a buffer the tool added a place: the GLB's binary chunk when it is the first buffer of a
/// .glb, a data URI in a document whose buffers are all embedded, else a file beside the output,
/// which is returned (its bytes are the last buffer's). The document had `original_buffers`.
fn finish_buffers(asset: &mut Asset, original_buffers: usize, output: &Path) -> Result<Option<PathBuf>, String> {
    // The index of the buffer the tool added, if it added one.
    let added = original_buffers;
    if asset.buffers.len() == added {
        return Ok(None);
    }
    if asset.kind == Kind::Glb && added == 0 {
        return Ok(None);
    }
    // A document whose buffers are all embedded stays one file.
    let embedded = (0..original_buffers)
        .all(|i| Buffer::read(&asset.json, i).is_ok_and(|b| b.uri.is_some_and(|u| u.starts_with("data:"))));
    if embedded {
        let bytes = asset.buffers[added].as_deref().unwrap_or_default();
        asset.json["buffers"][added]["uri"] = json!(uri::encode_data(bytes));
        return Ok(None);
    }
    let name = side_file_name(asset, output)?;
    asset.json["buffers"][added]["uri"] = json!(uri::encode_segment(&name));
    Ok(Some(output.with_file_name(&name)))
}

/// `<output stem>.tangents.bin`, or with a number, so that it names no file the document
/// already uses.
fn side_file_name(asset: &Asset, output: &Path) -> Result<String, String> {
    let stem = output
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| format!("{}: the output name is not valid UTF-8", output.display()))?;
    let out_dir = canonical_dir(output)?;
    let in_dir = std::fs::canonicalize(&asset.dir).map_err(|e| format!("{}: {e}", asset.dir.display()))?;
    let used: Vec<PathBuf> = uri::document_uris(&asset.json)
        .map(|(_, _, u)| u)
        .filter(|u| uri::is_relative_file(u))
        .map(|u| uri::resolve(&in_dir, u))
        .collect();
    (0..)
        .map(|k| match k {
            0 => format!("{stem}.tangents.bin"),
            k => format!("{stem}.tangents.{k}.bin"),
        })
        .find(|name| !used.contains(&out_dir.join(name)))
        .ok_or_else(|| "no free name for the new buffer".to_string())
}

/// A document written to another folder must still find its files: relative URIs are rewritten
/// to lead from the output's folder to the same files; buffers from `original_buffers` on are the
/// tool's, already beside the output.
fn rebase_uris(asset: &mut Asset, original_buffers: usize, output: &Path) -> Result<(), String> {
    let in_dir = std::fs::canonicalize(&asset.dir).map_err(|e| format!("{}: {e}", asset.dir.display()))?;
    let out_dir = canonical_dir(output)?;
    if in_dir == out_dir {
        return Ok(());
    }
    for key in ["buffers", "images"] {
        // `get_mut`: indexing would add the key with a null value.
        let Some(items) = asset.json.get_mut(key).and_then(Value::as_array_mut) else {
            continue;
        };
        let count = if key == "buffers" {
            original_buffers
        } else {
            items.len()
        };
        for item in items.iter_mut().take(count) {
            let Some(old) = item["uri"].as_str().filter(|u| uri::is_relative_file(u)) else {
                continue;
            };
            let new = uri::rebase(old, &in_dir, &out_dir)
                .ok_or_else(|| format!("cannot refer to {old} from {}", out_dir.display()))?;
            item["uri"] = json!(new);
        }
    }
    Ok(())
}

/// The output's folder, canonical (it must exist).
fn canonical_dir(output: &Path) -> Result<PathBuf, String> {
    let dir = match output.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    std::fs::canonicalize(dir).map_err(|e| format!("output folder {}: {e}", dir.display()))
}

/// The binary chunk of a .glb, in pieces: its first buffer when that one has no URI, followed by
/// the data [`place`] put after it.
fn glb_bin<'a>(asset: &'a Asset, grown: Option<&'a Grown>) -> Option<Vec<&'a [u8]>> {
    let first = asset.json["buffers"].get(0)?;
    if first.get("uri").is_some() {
        return None;
    }
    let data = asset.buffers.first()?.as_deref()?;
    Some(match grown {
        None => {
            let length = first["byteLength"].as_u64()? as usize;
            vec![&data[..length.min(data.len())]]
        }
        Some(Grown { old_length, pieces }) => [&data[..*old_length], io::glb_padding(*old_length)]
            .into_iter()
            .chain(pieces.iter().map(Vec::as_slice))
            .collect(),
    })
}
