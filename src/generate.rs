//! The entry point: one call from the caller's buffers to written tangents.
#![forbid(unsafe_code)]

use crate::mesh::{Mesh, Output, OutputPart};
use crate::options::{DegeneratePolicy, Method, Options};
use crate::report::{count_flags, Report};
use crate::scratch::{self, OwnedScratch, Scratch};
use crate::status::Error;
use crate::strided::{pod_prefix_mut, Footprint, StridedMut};
use crate::{accumulate, legacy, mikktspace, parallel, resolve, validate, vertex_corners};

/// Computes a unit tangent and handedness for every vertex of `mesh` into `output`.
///
/// Returns what it found; on error nothing in `output` has been written. See [`generate_into`]
/// for caller-provided scratch and for the report of a rejected mesh.
///
/// ```
/// use tbasis::{generate, Indices, Mesh, Options, Output, Strided, StridedMut};
///
/// // One quad in the z = 0 plane, u along +x and v along +y.
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 4];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let indices = [0u32, 1, 2, 0, 2, 3];
/// let mut tangents = [[0.0f32; 4]; 4];
///
/// let mesh = Mesh {
///     positions: Strided::from_slice(&positions),
///     normals: Strided::from_slice(&normals),
///     texcoords: Some(Strided::from_slice(&texcoords)),
///     indices: Indices::U32(Strided::from_slice(&indices)),
/// };
/// let mut output = Output { tangents: StridedMut::from_slice(&mut tangents), bitangents: None };
/// let report = generate(&mesh, &Options::default(), &mut output)?;
///
/// assert_eq!(tangents[0], [1.0, 0.0, 0.0, 1.0]);
/// assert_eq!(report.degenerate_triangles, 0);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate(mesh: &Mesh, options: &Options, output: &mut Output) -> Result<Report, Error> {
    let mut report = Report::default();
    generate_into(mesh, options, output, None, &mut report)?;
    Ok(report)
}

/// [`generate`] with optional caller scratch (at least [`scratch_size`] bytes, any alignment;
/// then the call allocates nothing) and the report written to `report`, also when the call fails
/// with [`Error::DegenerateUv`].
pub fn generate_into(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let vertex_count = mesh.vertex_count();
    // 1. Nothing is written unless every check passes: options, counts, overlaps.
    let scratch_footprint = scratch.as_deref().map(|bytes| Footprint {
        start: bytes.as_ptr() as usize,
        stride: 1,
        size: 1,
        count: bytes.len(),
    });
    validate::validate(mesh, options, output, scratch_footprint)?;
    if options.method == Method::Mikktspace {
        let words = mikktspace::scratch_words(vertex_count, mesh.corner_count()).ok_or(Error::SizeOverflow)?;
        return with_words(scratch, words, |words| {
            mikktspace::generate_vertices(mesh, options, output, words, report)
        });
    }

    // 2. Working memory: per-vertex sums and flags, in the caller's scratch or on the heap.
    let mut owned;
    let mut scratch = match scratch {
        Some(bytes) => scratch::carve(bytes, vertex_count)?,
        None => {
            owned = OwnedScratch::allocate(vertex_count)?;
            owned.scratch()
        }
    };

    // 3. Per triangle: check its indices, solve Q = sT + tB for T (and B), add to its corners;
    //    with several workers, each adds to its own range of vertices, in triangle order.
    let workers = parallel::worker_count(options.threads, mesh);
    let accumulate_range = |part: &mut Scratch| match (options.degenerate_policy, mesh.texcoords) {
        (DegeneratePolicy::Legacy, Some(uvs)) => legacy::accumulate(mesh, uvs, options.flip_v, part),
        _ => accumulate::accumulate(mesh, options, part),
    };
    let mut found = if workers == 1 {
        accumulate_range(&mut scratch)?
    } else {
        let ends = parallel::range_ends(vertex_count, workers);
        parallel::merge(parallel::run(scratch.split(&ends), |mut part| {
            accumulate_range(&mut part)
        }))?
    };
    count_flags(scratch.flags, &mut found);

    // 4. REJECT refuses the mesh before anything is written, naming the first bad triangle.
    if options.degenerate_policy == DegeneratePolicy::Reject && found.degenerate_triangles > 0 {
        found.abnormal_normals = resolve::count_abnormal_normals(mesh);
        *report = found;
        return Err(Error::DegenerateUv);
    }

    // 5. Per vertex: Gram-Schmidt against the normal, handedness in w, fallbacks; write.
    let policy = options.degenerate_policy;
    let write_range = |part: &mut Scratch, out: &mut OutputPart| {
        let mut written = Report::default();
        let deferred = match policy {
            DegeneratePolicy::Legacy => {
                legacy::resolve(mesh, part, out);
                0
            }
            _ => resolve::write_measured(mesh, policy, part, out, &mut written),
        };
        (written, deferred)
    };
    let (written, deferred) = if workers == 1 {
        write_range(&mut scratch, &mut output.whole())
    } else {
        let ends = parallel::range_ends(vertex_count, workers);
        let parts = scratch.split(&ends).into_iter().zip(output.split(&ends)).collect();
        parallel::run(parts, |(mut part, mut out)| write_range(&mut part, &mut out))
            .into_iter()
            .fold((Report::default(), 0), |(mut total, deferred), (written, more)| {
                total.merge(&written);
                (total, deferred + more)
            })
    };
    found.merge(&written);

    // 6. INHERIT: vertices left without a tangent take their neighbours', ring by ring.
    if deferred > 0 {
        resolve::write_inherited(mesh, &mut scratch, &mut output.whole(), &mut found);
    }
    *report = found;
    Ok(())
}

/// Computes a unit tangent and handedness for every triangle corner: `tangents[3t + k]` for corner
/// `k` of triangle `t` (`mesh.corner_count()` elements).
///
/// Method [`Method::Mikktspace`] gives exactly mikktspace.c's frame per corner. The per-vertex
/// methods give each corner its vertex's frame, except at a mirror fold, where each corner gets the
/// frame of its own side. On error nothing in `tangents` has been written.
///
/// ```
/// use tbasis::{generate_corners, Indices, Mesh, Options, Strided, StridedMut};
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 4];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let indices = [0u32, 1, 2, 0, 2, 3];
/// let mut corners = [[0.0f32; 4]; 6];
///
/// let mesh = Mesh {
///     positions: Strided::from_slice(&positions),
///     normals: Strided::from_slice(&normals),
///     texcoords: Some(Strided::from_slice(&texcoords)),
///     indices: Indices::U32(Strided::from_slice(&indices)),
/// };
/// let report = generate_corners(&mesh, &Options::mikktspace(), &mut StridedMut::from_slice(&mut corners))?;
///
/// assert!(corners.iter().all(|&t| t == [1.0, 0.0, 0.0, 1.0]));
/// assert_eq!(report.split_vertices, 0);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate_corners(mesh: &Mesh, options: &Options, tangents: &mut StridedMut<[f32; 4]>) -> Result<Report, Error> {
    let mut report = Report::default();
    generate_corners_into(mesh, options, tangents, None, &mut report)?;
    Ok(report)
}

/// [`generate_corners`] with optional caller scratch (at least [`scratch_size_for`] bytes, any
/// alignment) and the report written to `report`, also when the call fails with
/// [`Error::DegenerateUv`].
pub fn generate_corners_into(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let scratch_footprint = scratch.as_deref().map(|bytes| Footprint {
        start: bytes.as_ptr() as usize,
        stride: 1,
        size: 1,
        count: bytes.len(),
    });
    validate::validate_corners(mesh, options, tangents, scratch_footprint)?;
    if options.method == Method::Mikktspace {
        let words = mikktspace::scratch_words(mesh.vertex_count(), mesh.corner_count()).ok_or(Error::SizeOverflow)?;
        return with_words(scratch, words, |words| {
            mikktspace::generate_corners(mesh, options, tangents, words, report)
        });
    }
    vertex_corners::generate_corners(mesh, options, tangents, scratch, report)
}

/// Runs `job` on `words` zeroed 32-bit words of working memory: the caller's bytes (aligned inside
/// them) or a fresh allocation.
fn with_words<R>(
    scratch: Option<&mut [u8]>,
    words: usize,
    job: impl FnOnce(&mut [u32]) -> Result<R, Error>,
) -> Result<R, Error> {
    match scratch {
        Some(bytes) => {
            let (words, _) = pod_prefix_mut::<u32>(bytes, words).ok_or(Error::ScratchTooSmall)?;
            words.fill(0);
            job(words)
        }
        None => {
            let mut owned = Vec::new();
            owned.try_reserve_exact(words).map_err(|_| Error::OutOfMemory)?;
            owned.resize(words, 0u32);
            job(&mut owned)
        }
    }
}

/// Bytes of caller scratch a [`generate_into`] or [`generate_corners_into`] call on `mesh` with
/// `options` needs (any alignment): for method MIKKTSPACE
/// `4 * mikktspace words(vertex_count, corner_count) + 3`, otherwise [`scratch_size`] of the
/// vertex count. `None` when that overflows.
pub fn scratch_size_for(mesh: &Mesh, options: &Options) -> Option<usize> {
    scratch_bytes(options.method, mesh.vertex_count(), mesh.corner_count())
}

/// [`scratch_size_for`] from the counts alone.
pub(crate) fn scratch_bytes(method: Method, vertex_count: usize, corner_count: usize) -> Option<usize> {
    match method {
        Method::Mikktspace => {
            let words = mikktspace::scratch_words(vertex_count, corner_count)?;
            if words == 0 {
                return Some(0);
            }
            words.checked_mul(4)?.checked_add(3)
        }
        _ => vertex_corners::scratch_size(vertex_count, corner_count),
    }
}

/// Bytes of caller scratch a call on `vertex_count` vertices needs:
/// `vertex_count * 29 + 3` (0 when empty); `None` when that overflows.
pub fn scratch_size(vertex_count: usize) -> Option<usize> {
    scratch::scratch_size(vertex_count)
}
