//! The per-vertex working arrays of the listing and the per-vertex methods: running sums and
//! flags per vertex, and for policy INHERIT room for its adjacency (laid out by
//! [`crate::kernel::memory::vertex_arrays`]).
#![forbid(unsafe_code)]

use core::ops::Range;

use crate::kernel::error::Error;
use crate::kernel::mesh::{Mesh, Output, OutputPart};
use crate::kernel::options::DegeneratePolicy;
use crate::kernel::parallel;
use crate::kernel::report::Report;
pub use crate::kernel::vertex_sums::VertexSums;
use crate::kernel::views::strided::StridedMut;

/// Per-vertex flag bits.
pub mod flag {
    /// Some triangle uses the vertex.
    pub(crate) const REFERENCED: u8 = 1;
    /// A non-degenerate triangle with positive UV determinant uses the vertex.
    pub(crate) const POSITIVE_UV: u8 = 2;
    /// A non-degenerate triangle with negative UV determinant uses the vertex.
    pub(crate) const NEGATIVE_UV: u8 = 4;
    /// The vertex has its final tangent in `primary` (policy INHERIT).
    pub(crate) const RESOLVED: u8 = 8;
    /// The vertex waits for its neighbours (policy INHERIT) and is written after them.
    pub(crate) const DEFERRED: u8 = 16;
    /// Per-corner output: `secondary` holds the frame of the mirror-fold side the vertex's own
    /// frame does not come from (its `w` is minus the vertex's).
    pub(crate) const SIDE_FRAME: u8 = 32;
    /// Policy INHERIT: the vertex is queued for the current ring (cleared when the ring ends).
    pub(crate) const CANDIDATE: u8 = 64;
    /// The first non-degenerate corner of the vertex, in triangle order, is left-handed: at a
    /// mirror fold the vertex takes that side's frame unless the other side's sum is more than
    /// twice as long ([`crate::kernel::fold`]).
    pub(crate) const FIRST_LEFT: u8 = 128;
}

/// Bytes a per-vertex call with `policy` needs besides the sums and flags: policy INHERIT's
/// adjacency ([`adjacency_bytes`]), nothing for the other policies or an empty mesh.
pub(crate) fn link_bytes(policy: DegeneratePolicy, vertex_count: usize, corner_count: usize) -> Option<usize> {
    if policy != DegeneratePolicy::Inherit || vertex_count == 0 {
        return Some(0);
    }
    adjacency_bytes(vertex_count, corner_count)
}

/// Bytes policy INHERIT's adjacency (`pipelines::per_vertex::inherit::propagate`) needs for a mesh
/// of `vertex_count` vertices and `corner_count` corners:
/// `2 * vertex_count + corner_count` entries (a range start and a queue slot per vertex, a
/// triangle per corner) of 4 bytes, or of 8 when a count does not fit in 32 bits.
fn adjacency_bytes(vertex_count: usize, corner_count: usize) -> Option<usize> {
    let width = if wide_links(vertex_count, corner_count) { 8 } else { 4 };
    vertex_count
        .checked_mul(2)?
        .checked_add(corner_count)?
        .checked_mul(width)
}

/// Whether the adjacency needs 8-byte entries: a vertex index, a triangle index or a count of
/// corners may not fit in 32 bits.
pub(crate) fn wide_links(vertex_count: usize, corner_count: usize) -> bool {
    vertex_count.max(corner_count) > u32::MAX as usize
}

/// Where vertex `v` sits in a range of `len` vertices starting at `first`, if the range holds it.
#[inline(always)]
pub(crate) fn slot_in(v: usize, first: usize, len: usize) -> Option<usize> {
    let slot = v.wrapping_sub(first);
    (slot < len).then_some(slot)
}

/// The per-vertex working arrays of one call, or of one worker's consecutive range of vertices.
pub struct Scratch<'s> {
    /// Running sums, one per vertex of the range.
    pub sums: &'s mut [VertexSums],
    /// Flag bits, one byte per vertex of the range.
    pub flags: &'s mut [u8],
    /// The first vertex of the range: vertex `v` is at `v - first`.
    pub first: usize,
    /// Room for policy INHERIT's adjacency (whole-mesh scratch only).
    pub links: Links<'s>,
}

/// Memory for policy INHERIT's adjacency (4-byte aligned, any contents), which only a call that
/// defers some vertex writes.
pub enum Links<'s> {
    /// Laid out in the caller's scratch (empty for a worker's range).
    Caller(&'s mut [u8]),
    /// Heap bytes reserved (`.1` of them) before the call writes anything, so that using them
    /// cannot fail halfway; neither written nor faulted in while no vertex needs them.
    Heap(&'s mut Vec<u8>, usize),
}

impl<'s> Links<'s> {
    /// `len` bytes reserved in `heap` (3 more, to align them), or [`Error::OutOfMemory`].
    pub fn reserve(heap: &'s mut Vec<u8>, len: usize) -> Result<Self, Error> {
        let with_alignment = if len == 0 {
            0
        } else {
            len.checked_add(3).ok_or(Error::OutOfMemory)?
        };
        heap.try_reserve_exact(with_alignment).map_err(|_| Error::OutOfMemory)?;
        Ok(Links::Heap(heap, with_alignment))
    }

    /// The bytes (any contents), at least as many as were asked for: the heap's filled up to
    /// their reserved length without reallocating.
    pub fn bytes(&mut self) -> &mut [u8] {
        match self {
            Links::Caller(bytes) => bytes,
            Links::Heap(heap, len) => {
                heap.resize(*len, 0);
                heap
            }
        }
    }
}

impl<'s> Scratch<'s> {
    /// The same arrays and links, borrowed for a while.
    pub fn reborrow(&mut self) -> Scratch<'_> {
        Scratch {
            sums: &mut *self.sums,
            flags: &mut *self.flags,
            first: self.first,
            links: match &mut self.links {
                Links::Caller(bytes) => Links::Caller(bytes),
                Links::Heap(heap, len) => Links::Heap(heap, *len),
            },
        }
    }

    /// Where vertex `v` sits in this range's arrays, if the range holds it.
    #[inline(always)]
    pub fn slot(&self, v: usize) -> Option<usize> {
        slot_in(v, self.first, self.flags.len())
    }

    /// The same arrays cut at the vertices in `ends` (exclusive ends, increasing, the last the
    /// vertex count), one part per worker, without allocating.
    pub fn split<'p>(&'p mut self, ends: &'p [usize]) -> impl Iterator<Item = Scratch<'p>> + 'p {
        let (mut sums, mut flags): (&mut [VertexSums], &mut [u8]) = (&mut *self.sums, &mut *self.flags);
        let mut first = self.first;
        ends.iter().map(move |&end| {
            let (part_sums, rest_sums) = core::mem::take(&mut sums).split_at_mut(end - first);
            let (part_flags, rest_flags) = core::mem::take(&mut flags).split_at_mut(end - first);
            let part = Scratch {
                sums: part_sums,
                flags: part_flags,
                first,
                links: Links::Caller(&mut []),
            };
            (sums, flags, first) = (rest_sums, rest_flags, end);
            part
        })
    }
}

/// Runs `job` on the arrays of `workers` consecutive ranges of vertices, each with its part of
/// `output` if there is one, the first range on the calling thread and the others on their own,
/// and folds the results in range order with `merge`. With one worker: on the whole arrays and
/// output, through the same compiled job as the workers' (one copy of it in the library).
/// Allocates nothing ([`parallel::run`]).
pub fn for_each_range<R: Send>(
    scratch: &mut Scratch,
    output: Option<&mut Output>,
    workers: usize,
    job: impl Fn(&mut Scratch, Option<&mut OutputPart>) -> R + Sync,
    merge: impl FnMut(R, R) -> R,
) -> R {
    // One closure, passed by reference to both paths: one compiled job.
    let job = &|(mut part, mut out): (Scratch, Option<OutputPart>)| job(&mut part, out.as_mut());
    if workers == 1 {
        return parallel::run_one(job, (scratch.reborrow(), output.map(Output::whole)));
    }
    let ranges = parallel::range_ends(scratch.flags.len(), workers);
    let ends = ranges.ends();
    let mut outputs = output.map(|output| output.split(ends));
    let outputs = core::iter::from_fn(|| Some(outputs.as_mut().and_then(Iterator::next)));
    let parts = scratch.split(ends).zip(outputs);
    parallel::run_folded(parts, job, merge).expect("at least one range")
}

/// The per-corner output of the per-vertex pipelines, from the frames their vertices kept
/// ([`VertexSums::keep_frame`]): each corner gets its vertex's, then `adjust(triangles, part)` may
/// rewrite corners of those triangles (`part`'s element 0 is the first one's corner 0). With
/// several workers, each writes a consecutive range of triangles.
pub fn write_corner_frames(
    mesh: &Mesh,
    threads: u32,
    sums: &[VertexSums],
    tangents: &mut StridedMut<[f32; 4]>,
    adjust: impl Fn(Range<usize>, &mut StridedMut<[f32; 4]>) -> Result<(), Error> + Sync,
) -> Result<(), Error> {
    let write = |triangles: Range<usize>, part: &mut StridedMut<[f32; 4]>| {
        let first_corner = 3 * triangles.start;
        for c in first_corner..3 * triangles.end {
            part.set(c - first_corner, sums[mesh.indices.corner(c)].kept_frame());
        }
        adjust(triangles, part)
    };
    let triangle_count = mesh.corner_count() / 3;
    let workers = parallel::worker_count(threads, mesh);
    if workers == 1 {
        return write(0..triangle_count, tangents);
    }
    let ranges = parallel::range_ends(triangle_count, workers);
    let ends = ranges.ends();
    let corner_ends = parallel::Ranges::from_ends(ends.iter().map(|&end| 3 * end));
    let starts = core::iter::once(0).chain(ends.iter().copied());
    let parts = tangents
        .split(corner_ends.ends(), 1)
        .into_iter()
        .zip(starts.zip(ends.iter().copied()));
    let first_error = |before: Result<(), Error>, next| before.and(next);
    parallel::run_folded(
        parts,
        |(mut part, (start, end))| write(start..end, &mut part),
        first_error,
    )
    .unwrap_or(Ok(()))
}

/// A vertex used by non-degenerate triangles of both UV orientations: a mirror fold.
#[inline(always)]
pub fn is_mirror_fold(flags: u8) -> bool {
    let both = flag::POSITIVE_UV | flag::NEGATIVE_UV;
    flags & both == both
}

/// Adds what the flags tell to `report`: vertices no triangle uses, and mirror folds.
pub(crate) fn count_flags(flags: &[u8], report: &mut Report) {
    for &f in flags {
        report.unreferenced_vertices += usize::from(f & flag::REFERENCED == 0);
        report.mirrored_vertices += usize::from(is_mirror_fold(f));
    }
}
