//! The mirror-fold rule, stated once: which side's sum gives a mirror-fold vertex its frame.
//!
//! A vertex is a mirror fold when non-degenerate triangles of both UV orientations use it
//! ([`is_mirror_fold`]): its right-handed corners sum into one side (`primary`, w = +1), its
//! left-handed ones into the other (`secondary`, w = -1). The vertex takes the side of its first
//! non-degenerate corner in triangle order, as mikktspace.c gives a vertex its first corner's
//! frame, unless the other side's sum is more than [`MAJORITY`] times as long: then most of the
//! weighted tangent around the vertex lies there, and one stray triangle flipped in UV (a sliver,
//! often first in the order) does not decide the vertex's frame. If the chosen side leaves no
//! usable tangent, the other side is tried. Per corner, a corner on the side the vertex did not
//! take gets that side's own frame when its sum passes the same test (`generate_corners`).
#![forbid(unsafe_code)]

pub(crate) use crate::kernel::sums::is_mirror_fold;
use crate::kernel::sums::{flag, VertexSums};

use glam::Vec3;

/// How many times longer than the first corner's side the other side's sum must be to be kept
/// instead ([`first_side`]).
const MAJORITY: f32 = 2.0;

/// The side the rule above gives a vertex: `((its sum, its w), the other side's sum)`.
#[inline(always)]
pub fn first_side(sums: &VertexSums, flags: u8) -> (([f32; 3], f32), [f32; 3]) {
    let (right, left) = (Vec3::from_array(sums.primary), Vec3::from_array(sums.secondary));
    let squared = MAJORITY * MAJORITY;
    let left_first = if flags & flag::FIRST_LEFT != 0 {
        left.length_squared() * squared >= right.length_squared()
    } else {
        left.length_squared() > squared * right.length_squared()
    };
    if left_first {
        ((sums.secondary, -1.0), sums.primary)
    } else {
        ((sums.primary, 1.0), sums.secondary)
    }
}
