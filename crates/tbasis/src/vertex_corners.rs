//! Per-corner output for the per-vertex methods: each corner gets its vertex's frame, except at a
//! mirror fold, where it gets the frame of its own side.
//!
//! The rule, exactly. The per-vertex pass runs as for [`generate`](crate::generate) but keeps each vertex's
//! frame in its sums instead of writing it (so the scratch is the per-vertex one). Then:
//!
//! * Every corner gets its vertex's frame, bit for bit what [`generate`](crate::generate) writes for it.
//! * Except a corner of a non-degenerate triangle at a mirror fold (a vertex that non-degenerate
//!   triangles of both UV orientations use) whose frame was measured from its sums: the vertex's
//!   frame comes from one side (see `resolve::resolve`), and a corner on the other side
//!   (right-handed corners sum into one side, left-handed into the other, as the sums were built)
//!   gets the frame resolved from that side's own sum, `w` = that side's handedness, when that sum
//!   passes the same test the vertex's did (see `resolve::resolve_other_side`).
//!
//! So degenerate triangles' corners get their vertex's frame (they added to neither side), and so
//! do all corners of a fold vertex that inherited its frame or fell back (neither side had a
//! usable tangent). Policy LEGACY has no sides: every corner gets its
//! vertex's frame.
//!
//! [`generate`](crate::generate): crate::generate_into
#![forbid(unsafe_code)]

use crate::error::Error;
use crate::generate::resolve_vertices;
use crate::mesh::Mesh;
use crate::options::{DegeneratePolicy, Options};
use crate::parallel;
use crate::report::Report;
use crate::robust::accumulate;
use crate::scratch::{self, flag, VertexSums};
use crate::views::strided::StridedMut;

/// Writes every corner's frame into `tangents` (validated by the caller: one per corner).
pub(crate) fn generate_corners(
    mesh: &Mesh,
    options: &Options,
    tangents: &mut StridedMut<[f32; 4]>,
    scratch: Option<&mut [u8]>,
    report: &mut Report,
) -> Result<(), Error> {
    let links = scratch::link_bytes(options.degenerate_policy, mesh.vertex_count(), mesh.corner_count())
        .ok_or(Error::SizeOverflow)?;
    scratch::with_scratch(scratch, mesh.vertex_count(), links, |scratch| {
        resolve_vertices(mesh, options, scratch, None, report)?;
        let frames = KeptFrames {
            sums: scratch.sums,
            flags: scratch.flags,
            any_side_frame: scratch.flags.iter().any(|&f| f & flag::SIDE_FRAME != 0),
        };
        frames.write(mesh, options, tangents)
    })
}

/// Bytes of caller scratch [`generate_corners`] needs: the per-vertex call's (29 bytes a vertex,
/// and policy INHERIT's adjacency), since each vertex's frames are kept in its own sums.
pub(crate) fn scratch_size(policy: DegeneratePolicy, vertex_count: usize, corner_count: usize) -> Option<usize> {
    scratch::scratch_size_with(vertex_count, scratch::link_bytes(policy, vertex_count, corner_count)?)
}

/// What the per-vertex pass kept: each vertex's frame, and at folds its other side's.
struct KeptFrames<'s> {
    sums: &'s [VertexSums],
    flags: &'s [u8],
    /// Some vertex kept a side frame: only then are the corners' sides worth recomputing.
    any_side_frame: bool,
}

impl KeptFrames<'_> {
    /// Writes every corner; with several workers, each writes a consecutive range of triangles.
    fn write(&self, mesh: &Mesh, options: &Options, tangents: &mut StridedMut<[f32; 4]>) -> Result<(), Error> {
        let triangle_count = mesh.corner_count() / 3;
        let workers = parallel::worker_count(options.threads, mesh);
        if workers == 1 {
            return self.write_triangles(mesh, options, 0..triangle_count, tangents);
        }
        let ends = parallel::range_ends(triangle_count, workers);
        let corner_ends: Vec<usize> = ends.iter().map(|&end| 3 * end).collect();
        let starts = core::iter::once(0).chain(ends.iter().copied());
        let parts: Vec<_> = tangents
            .split(&corner_ends)
            .into_iter()
            .zip(starts.zip(ends.iter().copied()))
            .collect();
        parallel::run(parts, |(mut part, (start, end))| {
            self.write_triangles(mesh, options, start..end, &mut part)
        })
        .into_iter()
        .collect()
    }

    /// Triangles `triangles` into `tangents`, whose element 0 is the range's first corner.
    ///
    /// Never fails: the per-vertex pass checked every index before anything was written.
    fn write_triangles(
        &self,
        mesh: &Mesh,
        options: &Options,
        triangles: core::ops::Range<usize>,
        tangents: &mut StridedMut<[f32; 4]>,
    ) -> Result<(), Error> {
        let first_corner = 3 * triangles.start;
        for c in first_corner..3 * triangles.end {
            tangents.set(c - first_corner, self.sums[mesh.indices.corner(c)].kept_frame());
        }
        if !self.any_side_frame {
            return Ok(());
        }
        let has_side_frame = |v: usize| self.flags[v] & flag::SIDE_FRAME != 0;
        accumulate::visit_corner_sides(
            mesh,
            options,
            triangles,
            |corners| corners.iter().any(|&v| has_side_frame(v)),
            |t, k, v, right_handed| {
                let w = if right_handed { 1.0 } else { -1.0 };
                // The vertex's own frame is one side's: only the other side differs.
                if has_side_frame(v) && w != self.sums[v].weight {
                    tangents.set(3 * t + k - first_corner, self.sums[v].kept_side_frame());
                }
            },
        )
    }
}
