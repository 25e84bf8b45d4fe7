//! Per-corner output for the per-vertex methods: each corner gets its vertex's frame, except at a
//! mirror fold, where it gets the frame of its own side.
//!
//! The per-vertex pass runs as for `generate` but keeps each vertex's frame in its sums instead of
//! writing it. Every corner then gets its vertex's frame, bit for bit what `generate` writes for
//! it, except a corner of a non-degenerate triangle at a measured mirror-fold vertex on the side
//! the vertex did not take ([`crate::kernel::fold`]): it gets the frame resolved from that side's
//! own sum, `w` = that side's handedness, when that sum passes the same test the vertex's did
//! (`resolve::resolve_other_side`). So corners of degenerate triangles (they added to neither
//! side) and all corners of a fold vertex that inherited its frame or fell back get their vertex's
//! frame.
#![forbid(unsafe_code)]

use crate::kernel::error::Error;
use crate::kernel::mesh::Mesh;
use crate::kernel::options::Options;
use crate::kernel::sums::{flag, write_corner_frames, Scratch};
use crate::kernel::views::strided::StridedMut;
use crate::pipelines::per_vertex::accumulate;

/// Writes every corner's frame into `tangents` (validated by the caller: one per corner) from the
/// frames the per-vertex pass kept in `scratch`.
pub(crate) fn write(
    mesh: &Mesh,
    options: &Options,
    scratch: &Scratch,
    tangents: &mut StridedMut<[f32; 4]>,
) -> Result<(), Error> {
    let (sums, flags) = (&*scratch.sums, &*scratch.flags);
    // Only when some vertex kept a side frame are the corners' sides worth recomputing.
    let any_side_frame = flags.iter().any(|&f| f & flag::SIDE_FRAME != 0);
    write_corner_frames(mesh, options.threads, sums, tangents, |triangles, part| {
        if !any_side_frame {
            return Ok(());
        }
        let first_corner = 3 * triangles.start;
        let has_side_frame = |v: usize| flags[v] & flag::SIDE_FRAME != 0;
        accumulate::visit_corner_sides(
            mesh,
            options,
            triangles,
            |corners| corners.iter().any(|&v| has_side_frame(v)),
            |t, k, v, right_handed| {
                let w = if right_handed { 1.0 } else { -1.0 };
                // The vertex's own frame is one side's: only the other side differs.
                if has_side_frame(v) && w != sums[v].weight {
                    part.set(3 * t + k - first_corner, sums[v].kept_side_frame());
                }
            },
        )
    })
}
