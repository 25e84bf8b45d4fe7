//! The entry point: one call from the caller's buffers to written tangents.
#![forbid(unsafe_code)]

use crate::error::Error;
use crate::mesh::{Mesh, Output, OutputPart};
use crate::options::{DegeneratePolicy, Method, Options};
use crate::report::{count_flags, Report};
use crate::robust::{accumulate, resolve};
use crate::scratch::{self, Scratch};
use crate::views::strided::{Footprint, StridedMut};
use crate::{legacy, mikktspace, parallel, simd, validate, vertex_corners};

/// Computes a unit tangent and handedness for every vertex of `mesh` into `output`.
///
/// Returns what it found; on error nothing in `output` has been written. Allocates its scratch;
/// [`generate_with_scratch`] and [`ScratchBuffer`](crate::ScratchBuffer) reuse memory instead.
///
/// ```
/// use tbasis::{generate, Mesh, Options, Output};
///
/// // One quad in the z = 0 plane, u along +x and v along +y.
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 4];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let indices = [0u32, 1, 2, 0, 2, 3];
/// let mut tangents = [[0.0f32; 4]; 4];
///
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords).with_indices(&indices);
/// let report = generate(&mesh, &Options::default(), &mut Output::new(&mut tangents))?;
///
/// assert_eq!(tangents[0], [1.0, 0.0, 0.0, 1.0]);
/// assert_eq!(report.degenerate_triangles, 0);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate(mesh: &Mesh, options: &Options, output: &mut Output) -> Result<Report, Error> {
    with_report(|report| generate_into(mesh, options, output, None, report))
}

/// [`generate`] in the caller's scratch: at least [`scratch_size_for`] bytes, any alignment. With
/// `threads` 0 or 1 the call then allocates nothing.
///
/// ```
/// use tbasis::{generate_with_scratch, scratch_size_for, Mesh, Options, Output};
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 3];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// let mut tangents = [[0.0f32; 4]; 3];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
/// let options = Options::default();
///
/// let mut scratch = vec![0u8; scratch_size_for(&mesh, &options).unwrap()];
/// generate_with_scratch(&mesh, &options, &mut Output::new(&mut tangents), &mut scratch)?;
/// assert_eq!(tangents[2], [1.0, 0.0, 0.0, 1.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate_with_scratch(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    scratch: &mut [u8],
) -> Result<Report, Error> {
    with_report(|report| generate_into(mesh, options, output, Some(scratch), report))
}

/// Runs `call` with a report to fill, and returns it.
fn with_report(call: impl FnOnce(&mut Report) -> Result<(), Error>) -> Result<Report, Error> {
    let mut report = Report::default();
    call(&mut report)?;
    Ok(report)
}

/// [`generate`] with optional caller scratch, the report filled in place.
pub(crate) fn generate_into(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let vertex_count = mesh.vertex_count();
    // 1. Nothing is written unless every check passes: options, counts, overlaps.
    let scratch_footprint = scratch
        .as_deref()
        .map(|bytes| Footprint::contiguous(bytes.as_ptr() as usize, bytes.len()));
    validate::validate(mesh, options, output, scratch_footprint)?;
    if options.method == Method::Mikktspace {
        let bytes = mikktspace::scratch_bytes(vertex_count, mesh.corner_count()).ok_or(Error::SizeOverflow)?;
        return with_bytes(scratch, bytes, |bytes| {
            mikktspace::generate_vertices(mesh, options, output, bytes, report)
        });
    }

    // 2. Working memory: per-vertex sums and flags (and INHERIT's adjacency), in the caller's
    //    scratch or on the heap.
    let links =
        scratch::link_bytes(options.degenerate_policy, vertex_count, mesh.corner_count()).ok_or(Error::SizeOverflow)?;
    scratch::with_scratch(scratch, vertex_count, links, |scratch| {
        resolve_vertices(mesh, options, scratch, Some(output), report)
    })
}

/// Steps 3 to 6 of [`generate_into`] on a validated mesh: each vertex's frame into `output`, or,
/// without one (the per-corner output), kept in `scratch` (see [`VertexSums`]).
///
/// [`VertexSums`]: crate::scratch::VertexSums
pub(crate) fn resolve_vertices(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    mut output: Option<&mut Output>,
    report: &mut Report,
) -> Result<(), Error> {
    let deferred = resolve_measured(mesh, options, scratch, output.as_deref_mut(), report)?;

    // 6. INHERIT: vertices left without a tangent take their neighbours', ring by ring.
    if deferred > 0 {
        let mut whole = output.map(Output::whole);
        resolve::write_inherited(mesh, scratch, whole.as_mut(), report);
    }
    Ok(())
}

/// Steps 3 to 5 of [`generate_into`]: every vertex whose own triangles give it a frame is
/// resolved (and written); returns how many wait for step 6 (policy INHERIT). `report` gets what
/// was found; when REJECT refuses the mesh, the error carries it.
pub(crate) fn resolve_measured(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    output: Option<&mut Output>,
    report: &mut Report,
) -> Result<usize, Error> {
    let vertex_count = mesh.vertex_count();
    // 3. Per triangle: check its indices, solve Q = sT + tB for T (and B), add to its corners;
    //    with several workers, each adds to its own range of vertices, in triangle order. Where
    //    the triangle order follows the vertex order, each worker reads the triangles touching
    //    its range; elsewhere the policies but LEGACY measure ranges of triangles apart, then add
    //    (LEGACY stays on one thread there).
    let legacy = options.degenerate_policy == DegeneratePolicy::Legacy && mesh.texcoords.is_some();
    let local_workers = parallel::worker_count(options.threads, mesh);
    let workers = if legacy {
        local_workers
    } else {
        parallel::workers_for(options.threads, vertex_count)
    };
    let accumulate_range = |part: &mut Scratch| match (legacy, mesh.texcoords) {
        (true, Some(uvs)) => legacy::accumulate(mesh, uvs, options.flip_v, part),
        _ => simd::run(|| accumulate::accumulate(mesh, options, part)),
    };
    let mut found = if workers == 1 {
        accumulate_range(scratch)?
    } else if local_workers == workers || vertex_count > u32::MAX as usize {
        let ends = parallel::range_ends(vertex_count, workers);
        parallel::merge(parallel::run(scratch.split(&ends), |mut part| {
            accumulate_range(&mut part)
        }))?
    } else {
        let ends = parallel::range_ends(vertex_count, workers);
        accumulate::accumulate_in_chunks(mesh, options, scratch.split(&ends), &ends)?
    };
    count_flags(scratch.flags, &mut found);

    // 4. REJECT refuses the mesh before anything is written, naming the first bad triangle.
    if options.degenerate_policy == DegeneratePolicy::Reject && found.degenerate_triangles > 0 {
        found.abnormal_normals = resolve::count_abnormal_normals(mesh);
        return Err(Error::DegenerateUv {
            triangle: found.first_degenerate_triangle,
            report: found,
        });
    }

    // 5. Per vertex: Gram-Schmidt against the normal, handedness in w, fallbacks; write.
    let policy = options.degenerate_policy;
    let write_range = |part: &mut Scratch, out: Option<&mut OutputPart>| {
        let mut written = Report::default();
        let deferred = match policy {
            DegeneratePolicy::Legacy => {
                legacy::resolve(mesh, part, out);
                0
            }
            _ => simd::run(|| resolve::write_measured(mesh, policy, part, out, &mut written)),
        };
        (written, deferred)
    };
    let (written, deferred) = if workers == 1 {
        write_range(scratch, output.map(Output::whole).as_mut())
    } else {
        let ends = parallel::range_ends(vertex_count, workers);
        let outputs: Vec<Option<OutputPart>> = match output {
            Some(output) => output.split(&ends).into_iter().map(Some).collect(),
            None => ends.iter().map(|_| None).collect(),
        };
        let parts = scratch.split(&ends).into_iter().zip(outputs).collect();
        parallel::run(parts, |(mut part, mut out)| write_range(&mut part, out.as_mut()))
            .into_iter()
            .fold((Report::default(), 0), |(mut total, deferred), (written, more)| {
                total.merge(&written);
                (total, deferred + more)
            })
    };
    found.merge(&written);
    *report = found;
    Ok(deferred)
}

/// Computes a unit tangent and handedness for every triangle corner: `tangents[3t + k]` for corner
/// `k` of triangle `t` (`mesh.corner_count()` elements).
///
/// Method [`Method::Mikktspace`] gives exactly mikktspace.c's frame per corner. The per-vertex
/// methods give each corner its vertex's frame, except at a mirror fold, where each corner gets the
/// frame of its own side. Exactly: a corner gets the bits [`generate`] writes for its vertex, except
/// where that vertex is a mirror fold whose frame was measured (from one side's sum, see the
/// README's "Degenerate-UV policies"): there a corner of a non-degenerate triangle on the other
/// side gets the frame of that side's own sum, with its `w`, when the sum passes the test the
/// vertex's passed. Corners of
/// degenerate triangles, of fold vertices that inherited or fell back, and all corners under
/// policy LEGACY get their vertex's frame. Same scratch ([`scratch_size_for`]) and report as
/// [`generate`]; `threads` changes no bit. On error nothing in `tangents` has been written.
///
/// ```
/// use tbasis::{generate_corners, Mesh, Options, StridedMut};
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 4];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// let indices = [0u32, 1, 2, 0, 2, 3];
/// let mut corners = [[0.0f32; 4]; 6];
///
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords).with_indices(&indices);
/// let report = generate_corners(&mesh, &Options::mikktspace(), &mut StridedMut::from_slice(&mut corners))?;
///
/// assert!(corners.iter().all(|&t| t == [1.0, 0.0, 0.0, 1.0]));
/// assert_eq!(report.split_vertices, 0);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate_corners(mesh: &Mesh, options: &Options, tangents: &mut StridedMut<[f32; 4]>) -> Result<Report, Error> {
    with_report(|report| generate_corners_into(mesh, options, tangents, None, report))
}

/// [`generate_corners`] in the caller's scratch: at least [`scratch_size_for`] bytes, any
/// alignment, as for [`generate_with_scratch`].
///
/// ```
/// use tbasis::{generate_corners_with_scratch, scratch_size_for, Mesh, Options, StridedMut};
///
/// let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let normals = [[0.0, 0.0, 1.0f32]; 3];
/// let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
/// let mut corners = [[0.0f32; 4]; 3];
/// let mesh = Mesh::new(&positions, &normals).with_texcoords(&texcoords);
/// let options = Options::mikktspace();
///
/// let mut scratch = vec![0u8; scratch_size_for(&mesh, &options).unwrap()];
/// generate_corners_with_scratch(&mesh, &options, &mut StridedMut::from_slice(&mut corners), &mut scratch)?;
/// assert_eq!(corners[1], [1.0, 0.0, 0.0, 1.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate_corners_with_scratch(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    scratch: &mut [u8],
) -> Result<Report, Error> {
    with_report(|report| generate_corners_into(mesh, options, tangents, Some(scratch), report))
}

/// [`generate_corners`] with optional caller scratch, the report filled in place.
pub(crate) fn generate_corners_into(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let scratch_footprint = scratch
        .as_deref()
        .map(|bytes| Footprint::contiguous(bytes.as_ptr() as usize, bytes.len()));
    validate::validate_corners(mesh, options, tangents, scratch_footprint)?;
    if options.method == Method::Mikktspace {
        let bytes = mikktspace::scratch_bytes(mesh.vertex_count(), mesh.corner_count()).ok_or(Error::SizeOverflow)?;
        return with_bytes(scratch, bytes, |bytes| {
            mikktspace::generate_corners(mesh, options, tangents, bytes, report)
        });
    }
    vertex_corners::generate_corners(mesh, options, tangents, scratch, report)
}

/// Runs `job` on `size` bytes of working memory: the caller's, or a fresh zeroed allocation.
fn with_bytes<R>(
    scratch: Option<&mut [u8]>,
    size: usize,
    job: impl FnOnce(&mut [u8]) -> Result<R, Error>,
) -> Result<R, Error> {
    match scratch {
        Some(bytes) => {
            let len = bytes.len();
            job(bytes
                .get_mut(..size)
                .ok_or(Error::ScratchTooSmall { needed: size, len })?)
        }
        None => {
            let mut owned = scratch::zeroed_bytes(size)?;
            job(&mut owned)
        }
    }
}

/// Bytes of caller scratch a [`generate_with_scratch`] or [`generate_corners_with_scratch`] call on `mesh` with
/// `options` needs (any alignment), 0 when the mesh has no vertices: for method MIKKTSPACE
/// `4 * mikktspace words(vertex_count, corner_count) + 3`; for the other methods with policy
/// INHERIT `vertex_count * 37 + corner_count * 4 + 3` ([`scratch_size`] plus the adjacency that
/// spreads tangents: per vertex a list start and a queue slot, per corner its triangle, 4 bytes
/// each, or 8 when the vertex or corner count exceeds `u32::MAX`); otherwise [`scratch_size`] of
/// the vertex count. `None` when that overflows.
///
/// ```
/// use tbasis::{generate_with_scratch, scratch_size, scratch_size_for, DegeneratePolicy, Error};
/// use tbasis::{Mesh, Options, Output};
///
/// let mesh = Mesh::new(&[[0.0f32; 3]; 3], &[[0.0, 0.0, 1.0f32]; 3]);
/// let inherit = Options::default();
/// let skip = Options::default().with_policy(DegeneratePolicy::Skip);
/// assert_eq!(scratch_size_for(&mesh, &inherit), Some(3 * 37 + 3 * 4 + 3));
/// assert_eq!(scratch_size_for(&mesh, &skip), scratch_size(3));
///
/// // scratch_size alone leaves no room for policy INHERIT's adjacency.
/// let mut scratch = vec![0u8; scratch_size(3).unwrap()];
/// let mut tangents = [[0.0f32; 4]; 3];
/// let error = generate_with_scratch(&mesh, &inherit, &mut Output::new(&mut tangents), &mut scratch);
/// assert!(matches!(error, Err(Error::ScratchTooSmall { .. })));
/// ```
pub fn scratch_size_for(mesh: &Mesh, options: &Options) -> Option<usize> {
    scratch_size_for_counts(options, mesh.vertex_count(), mesh.corner_count())
}

/// [`scratch_size_for`] from the counts alone: `corner_count` is the index count, or the vertex
/// count when unindexed.
///
/// ```
/// use tbasis::{scratch_size_for, scratch_size_for_counts, Mesh, Options};
///
/// let indices = [0u32, 1, 2, 0, 2, 3];
/// let mesh = Mesh::new(&[[0.0f32; 3]; 4], &[[0.0, 0.0, 1.0f32]; 4]).with_indices(&indices);
/// let options = Options::mikktspace();
/// assert_eq!(scratch_size_for_counts(&options, 4, 6), scratch_size_for(&mesh, &options));
/// assert_eq!(scratch_size_for_counts(&options, usize::MAX, 3), None);
/// ```
pub fn scratch_size_for_counts(options: &Options, vertex_count: usize, corner_count: usize) -> Option<usize> {
    match options.method {
        Method::Mikktspace => mikktspace::scratch_bytes(vertex_count, corner_count),
        _ => vertex_corners::scratch_size(options.degenerate_policy, vertex_count, corner_count),
    }
}

/// Bytes of caller scratch a call on `vertex_count` vertices needs under policies LEGACY, SKIP and
/// REJECT: `vertex_count * 29 + 3` (0 when empty); `None` when that overflows. Policy INHERIT and
/// method MIKKTSPACE need more: see [`scratch_size_for`].
///
/// ```
/// assert_eq!(tbasis::scratch_size(0), Some(0));
/// assert_eq!(tbasis::scratch_size(1000), Some(1000 * 29 + 3));
/// assert_eq!(tbasis::scratch_size(usize::MAX), None);
/// ```
pub fn scratch_size(vertex_count: usize) -> Option<usize> {
    scratch::scratch_size(vertex_count)
}
