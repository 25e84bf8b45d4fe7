//! The robust per-vertex methods (ANGLE, AREA, UNIFORM, and LENGYEL under SKIP, INHERIT and
//! REJECT): per-triangle tangents summed per vertex, then resolved into a finite unit frame
//! whatever the input.
//!
//! 1. [`accumulate`] solves each triangle's tangent and adds it to its vertices' sums, by
//!    handedness, with the kernel's shape test deciding which triangles count;
//! 2. REJECT refuses the mesh if any triangle was degenerate;
//! 3. [`resolve`] Gram-Schmidts each vertex sum against its normal, the mirror-fold rule picking
//!    the side ([`crate::kernel::fold`]);
//! 4. [`inherit`] gives vertices without a tangent one from their neighbours (policy INHERIT).
//!
//! [`corners`] writes the same frames per corner, each corner at a mirror fold its own side's.
#![forbid(unsafe_code)]

pub(crate) mod accumulate;
pub(crate) mod corners;
pub(crate) mod inherit;
pub(crate) mod resolve;

use crate::kernel::error::Error;
use crate::kernel::index_bounds::index_bounds;
use crate::kernel::memory::{self, Arena, Place};
use crate::kernel::mesh::{Mesh, Output, OutputPart, Target};
use crate::kernel::options::{DegeneratePolicy, Method, Options};
use crate::kernel::report::Report;
use crate::kernel::sums::{self, count_flags, Scratch};
use crate::kernel::{frame, parallel, simd};

/// Bytes of working memory a call needs in memory from `place`: the per-vertex sums and flags,
/// and policy INHERIT's adjacency (`vertex_count * 29 + 3`, and for INHERIT in the caller's
/// scratch `(2 * vertex_count + corner_count) * 4` more, or `* 8` beyond 32-bit counts; on the
/// heap the adjacency is reserved apart). `None` on overflow.
pub(crate) fn memory_bytes(
    policy: DegeneratePolicy,
    vertex_count: usize,
    corner_count: usize,
    place: Place,
) -> Option<usize> {
    let links = sums::link_bytes(policy, vertex_count, corner_count)?;
    memory::vertex_arrays_bytes(vertex_count, links, place)
}

/// The per-vertex arrays laid out in `memory` (at least [`memory_bytes`] long), policy INHERIT's
/// adjacency in heap memory reserved in `heap_links`.
fn scratch_in<'a>(
    mesh: &Mesh,
    (policy, threads): (DegeneratePolicy, u32),
    memory: &'a mut [u8],
    place: Place,
    heap_links: &'a mut Vec<u8>,
) -> Result<Scratch<'a>, Error> {
    let links = sums::link_bytes(policy, mesh.vertex_count(), mesh.corner_count()).ok_or(Error::SizeOverflow)?;
    let workers = parallel::workers_for(threads, mesh.corner_count() / 3);
    memory::vertex_arrays(
        &mut Arena::Carve(memory),
        mesh.vertex_count(),
        links,
        (place, workers),
        heap_links,
    )
}

/// Writes every vertex's frame into `target`, or every corner's ([`corners`]).
pub(crate) fn generate(
    mesh: &Mesh,
    options: &Options,
    memory: &mut [u8],
    place: Place,
    target: Target,
    report: &mut Report,
) -> Result<(), Error> {
    let mut heap_links = Vec::new();
    let mut scratch = scratch_in(
        mesh,
        (options.degenerate_policy, options.threads),
        memory,
        place,
        &mut heap_links,
    )?;
    match target {
        Target::Vertices(output) => resolve_vertices(mesh, options, &mut scratch, Some(output), report),
        Target::Corners(tangents) => {
            resolve_vertices(mesh, options, &mut scratch, None, report)?;
            corners::write(mesh, options, &scratch, tangents)
        }
    }
}

/// Policy REJECT's test for a pipeline that has none of its own (MIKKTSPACE): fails with
/// [`Error::DegenerateUv`], carrying the report every method's REJECT gives, when a triangle is
/// degenerate by the test every method's REJECT applies (UV or position quality below the
/// threshold, or non-finite input). Uses `memory` ([`memory_bytes`] of policy REJECT) and leaves
/// any bits there.
pub(crate) fn refuse_degenerate(mesh: &Mesh, options: &Options, memory: &mut [u8]) -> Result<(), Error> {
    // REJECT has no adjacency: nothing is reserved apart.
    let mut no_links = Vec::new();
    let mut scratch = scratch_in(
        mesh,
        (DegeneratePolicy::Reject, options.threads),
        memory,
        Place::Caller,
        &mut no_links,
    )?;
    let measured = Options {
        method: Method::Angle,
        ..*options
    };
    let mut found = accumulate::accumulate(mesh, &measured, &mut scratch, None)?;
    refuse_if_degenerate(mesh, &scratch, &mut found)
}

/// [`Error::DegenerateUv`] when `found` counted a degenerate triangle, with the vertex counts.
fn refuse_if_degenerate(mesh: &Mesh, scratch: &Scratch, found: &mut Report) -> Result<(), Error> {
    let Some(triangle) = found.first_degenerate_triangle else {
        return Ok(());
    };
    count_flags(scratch.flags, found);
    found.abnormal_normals = frame::count_abnormal_normals(mesh);
    Err(Error::DegenerateUv {
        triangle,
        report: *found,
    })
}

/// Steps 1 to 4 on a validated mesh: each vertex's frame into `output`, or, without one (the
/// per-corner output), kept in `scratch` (see [`sums::VertexSums`]).
fn resolve_vertices(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    mut output: Option<&mut Output>,
    report: &mut Report,
) -> Result<(), Error> {
    let deferred = resolve_measured(mesh, options, scratch, output.as_deref_mut(), report)?;

    // 4. INHERIT: vertices left without a tangent take their neighbours', ring by ring.
    if deferred > 0 {
        let mut whole = output.map(Output::whole);
        resolve::write_inherited(mesh, scratch, whole.as_mut(), report);
    }
    Ok(())
}

/// Steps 1 to 3: every vertex whose own triangles give it a frame is resolved (and written);
/// returns how many wait for step 4 (policy INHERIT). `report` gets what was found; when REJECT
/// refuses the mesh, the error carries it.
pub(crate) fn resolve_measured(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    output: Option<&mut Output>,
    report: &mut Report,
) -> Result<usize, Error> {
    let vertex_count = mesh.vertex_count();
    // 1. Per triangle: check its indices, solve Q = sT + tB for T, add to its corners; with
    //    several workers, each adds to its own range of vertices, in triangle order. Where the
    //    triangle order follows the vertex order, each worker reads the triangles touching its
    //    range; elsewhere the workers measure ranges of triangles apart, then add.
    let local_workers = parallel::worker_count(options.threads, mesh);
    let workers = parallel::workers_for(options.threads, mesh.corner_count() / 3);
    let mut found = if local_workers == workers || vertex_count > u32::MAX as usize {
        // Several workers skip the blocks of triangles with no corner in their range.
        let bounds = match workers {
            1 => None,
            _ => index_bounds(mesh, mesh.indices.triangle_count(vertex_count)?, workers)?,
        };
        let accumulate_range = |part: &mut Scratch, _: Option<&mut OutputPart>| {
            simd::run(|| accumulate::accumulate(mesh, options, part, bounds.as_ref()))
        };
        sums::for_each_range(scratch, None, workers, accumulate_range, parallel::merge_results)?
    } else {
        let ranges = parallel::range_ends(vertex_count, workers);
        accumulate::accumulate_in_chunks(mesh, options, scratch, ranges.ends())?
    };

    // 2. REJECT refuses the mesh before anything is written, naming the first bad triangle.
    if options.degenerate_policy == DegeneratePolicy::Reject {
        refuse_if_degenerate(mesh, scratch, &mut found)?;
    }
    count_flags(scratch.flags, &mut found);

    // 3. Per vertex: Gram-Schmidt against the normal, handedness in w, fallbacks; write.
    let policy = options.degenerate_policy;
    let write_range = |part: &mut Scratch, out: Option<&mut OutputPart>| {
        let mut written = Report::default();
        let deferred = simd::run(|| resolve::write_measured(mesh, policy, part, out, &mut written));
        (written, deferred)
    };
    let merge = |(mut total, deferred): (Report, usize), (written, more): (Report, usize)| {
        total.merge(&written);
        (total, deferred + more)
    };
    let (written, deferred) = sums::for_each_range(scratch, output, workers, write_range, merge);
    found.merge(&written);
    *report = found;
    Ok(deferred)
}
