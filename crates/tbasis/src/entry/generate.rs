//! The entry point: one call from the caller's buffers to written tangents.
#![forbid(unsafe_code)]

use crate::entry::validate;
use crate::kernel::error::Error;
use crate::kernel::memory::{with_memory, Fresh, Place};
use crate::kernel::mesh::{Mesh, Output, Target};
use crate::kernel::options::{DegeneratePolicy, Method, Options};
use crate::kernel::parallel;
use crate::kernel::report::Report;
use crate::kernel::views::strided::{Footprint, StridedMut};
use crate::pipelines::{listing, mikktspace, per_vertex};

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
/// `threads` 0 or 1 the call then allocates nothing (method MIKKTSPACE: but for a welded vertex
/// with more than 32 corners, or, on a mesh where a triangle takes its orientation from a group,
/// a group whose tangents may be exactly opposite or are not all of unit length).
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

/// The pipeline a validated call runs.
#[derive(Clone, Copy, PartialEq)]
enum Pipeline {
    /// Policy LEGACY with method LENGYEL: the original listing.
    Listing,
    /// Methods ANGLE, AREA, UNIFORM and LENGYEL under SKIP, INHERIT and REJECT.
    PerVertex,
    /// Method MIKKTSPACE, under every policy.
    Mikktspace,
}

impl Pipeline {
    /// The pipeline for `options` (validation refused policy LEGACY with any other method).
    fn of(options: &Options) -> Pipeline {
        match (options.method, options.degenerate_policy) {
            (Method::Mikktspace, _) => Pipeline::Mikktspace,
            (_, DegeneratePolicy::Legacy) => Pipeline::Listing,
            _ => Pipeline::PerVertex,
        }
    }

    /// Bytes of working memory the pipeline lays out for a call on `vertex_count` vertices and
    /// `corner_count` corners in memory from `place`; `None` on overflow. MIKKTSPACE under REJECT
    /// first runs the per-vertex test for degenerate triangles in the same memory.
    fn memory_bytes(
        self,
        policy: DegeneratePolicy,
        vertex_count: usize,
        corner_count: usize,
        place: Place,
    ) -> Option<usize> {
        match self {
            Pipeline::Listing => listing::memory_bytes(vertex_count),
            Pipeline::PerVertex => per_vertex::memory_bytes(policy, vertex_count, corner_count, place),
            Pipeline::Mikktspace => {
                let own = mikktspace::scratch_bytes(vertex_count, corner_count)?;
                if policy != DegeneratePolicy::Reject {
                    return Some(own);
                }
                Some(own.max(per_vertex::memory_bytes(policy, vertex_count, corner_count, place)?))
            }
        }
    }

    /// [`Pipeline::memory_bytes`] for a call on `mesh`.
    fn memory_for(self, mesh: &Mesh, options: &Options) -> impl Fn(Place) -> Option<usize> {
        let (policy, vertex_count, corner_count) =
            (options.degenerate_policy, mesh.vertex_count(), mesh.corner_count());
        move |place| self.memory_bytes(policy, vertex_count, corner_count, place)
    }
}

/// [`generate`] with optional caller scratch, the report filled in place.
pub(crate) fn generate_into(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    // 1. Nothing is written unless every check passes: options, counts, overlaps.
    validate::validate(mesh, options, output, footprint(&scratch))?;
    run(mesh, options, Target::Vertices(output), scratch, report)
}

/// Step 2 of both calls, after validation: working memory (the caller's scratch or a fresh zeroed
/// allocation, laid out by the pipeline), then the pipeline computes and writes.
fn run(
    mesh: &Mesh,
    options: &Options,
    target: Target,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let pipeline = Pipeline::of(options);
    // The per-vertex sums are added to from the start; MIKKTSPACE writes before it reads.
    let fresh = match pipeline {
        Pipeline::Mikktspace => Fresh::Untouched,
        Pipeline::Listing | Pipeline::PerVertex => Fresh::Written {
            workers: parallel::workers_for(options.threads, mesh.corner_count() / 3),
        },
    };
    with_memory(
        scratch,
        pipeline.memory_for(mesh, options),
        fresh,
        |memory, place| match pipeline {
            Pipeline::Listing => listing::generate(mesh, options, memory, place, target, report),
            Pipeline::PerVertex => per_vertex::generate(mesh, options, memory, place, target, report),
            Pipeline::Mikktspace => {
                refuse_degenerate(mesh, options, memory)?;
                mikktspace::generate(mesh, options, memory, target, report)?;
                if options.degenerate_policy == DegeneratePolicy::Reject {
                    // REJECT's test found no degenerate triangle, and its report says so: a
                    // triangle mikktspace.c cannot use (derivatives that underflow) passes it.
                    (report.degenerate_triangles, report.first_degenerate_triangle) = (0, None);
                }
                Ok(())
            }
        },
    )
}

/// Policy REJECT's refusal for MIKKTSPACE, whose pipeline has no degenerate test of its own: the
/// per-vertex methods' test, so every method refuses the same meshes with the same report.
fn refuse_degenerate(mesh: &Mesh, options: &Options, memory: &mut [u8]) -> Result<(), Error> {
    match options.degenerate_policy {
        DegeneratePolicy::Reject => per_vertex::refuse_degenerate(mesh, options, memory),
        _ => Ok(()),
    }
}

/// Where the caller's scratch lies, for the overlap checks.
fn footprint(scratch: &Option<&mut [u8]>) -> Option<Footprint> {
    scratch
        .as_deref()
        .map(|bytes| Footprint::contiguous(bytes.as_ptr() as usize, bytes.len()))
}

/// Computes a unit tangent and handedness for every triangle corner: `tangents[3t + k]` for corner
/// `k` of triangle `t` (`mesh.corner_count()` elements).
///
/// Method [`Method::Mikktspace`] gives exactly mikktspace.c's frame per corner. The per-vertex
/// methods give each corner exactly the bits [`generate`] writes for its vertex, except at a
/// mirror fold (a vertex used by non-degenerate triangles of both UV orientations): there a corner
/// of a non-degenerate triangle on the side the vertex's frame does not come from gets that side's
/// own frame and `w` (README, "Degenerate-UV policies"). Same scratch ([`scratch_size_for`]) and
/// report as [`generate`]; `threads` changes no bit. On error nothing in `tangents` has been
/// written.
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
    validate::validate_corners(mesh, options, tangents, footprint(&scratch))?;
    run(mesh, options, Target::Corners(tangents), scratch, report)
}

/// Bytes of caller scratch a [`generate_with_scratch`] or [`generate_corners_with_scratch`] call on `mesh` with
/// `options` needs (any alignment), 0 when the mesh has no vertices: for method MIKKTSPACE
/// `4 * mikktspace words(vertex_count, corner_count) + 3` (with policy REJECT at least
/// [`scratch_size`], in which the degenerate test runs first); for the other methods with policy
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
    Pipeline::of(options).memory_bytes(options.degenerate_policy, vertex_count, corner_count, Place::Caller)
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
    crate::kernel::memory::vertex_arrays_bytes(vertex_count, 0, Place::Caller)
}
