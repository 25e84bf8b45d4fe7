//! The working memory of one call: per-vertex sums and flags, and for policy INHERIT room for its
//! adjacency, from the caller or the heap.
#![forbid(unsafe_code)]

use core::mem::{align_of, size_of};

use glam::Vec3;

use crate::error::Error;
use crate::options::DegeneratePolicy;
use crate::views::strided::pod_prefix_mut;

/// `len` zero bytes from the heap, or [`Error::OutOfMemory`]. A fallible reservation first tells
/// whether the memory is there; the zeroed allocation that follows comes from the system already
/// cleared, so a large buffer costs only the pages a call then touches, not a pass over all of it.
pub(crate) fn zeroed_bytes(len: usize) -> Result<Vec<u8>, Error> {
    let mut probe: Vec<u8> = Vec::new();
    probe.try_reserve_exact(len).map_err(|_| Error::OutOfMemory)?;
    drop(probe);
    Ok(vec![0; len])
}

/// Per-vertex running sums.
///
/// Policy LEGACY: `primary` is the listing's `tan1` (sum of dP/du) and `secondary` its `tan2`
/// (sum of dP/dv). Other policies: `primary` sums the tangents of right-handed corners and
/// `secondary` those of left-handed corners, `weight` the total weight of both; once a vertex is
/// resolved, `primary` holds its unit tangent and `weight` its handedness ([`Self::keep_frame`]).
/// For the per-corner output every vertex keeps its frame that way, and a mirror-fold vertex
/// flagged [`flag::SIDE_FRAME`] keeps in `secondary` the unit tangent of its other side.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VertexSums {
    /// See the type's description.
    pub primary: [f32; 3],
    /// See the type's description.
    pub weight: f32,
    /// See the type's description.
    pub secondary: [f32; 3],
}

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
    /// twice as long (mikktspace.c gives a vertex its first corner's; see `robust::resolve`).
    pub(crate) const FIRST_LEFT: u8 = 128;
}

impl VertexSums {
    /// Keeps a resolved frame in place of the sums: `primary` = tangent, `weight` = `w`.
    #[inline(always)]
    pub fn keep_frame(&mut self, tangent: Vec3, w: f32) {
        self.primary = tangent.to_array();
        self.weight = w;
    }

    /// The frame [`Self::keep_frame`] kept, as written out: `x, y, z, w`.
    #[inline(always)]
    pub fn kept_frame(&self) -> [f32; 4] {
        let [x, y, z] = self.primary;
        [x, y, z, self.weight]
    }

    /// The other side's frame a [`flag::SIDE_FRAME`] vertex keeps, as written out.
    #[inline(always)]
    pub fn kept_side_frame(&self) -> [f32; 4] {
        let [x, y, z] = self.secondary;
        [x, y, z, -self.weight]
    }
}

/// Scratch bytes per vertex: one [`VertexSums`] and one flag byte.
pub(crate) const BYTES_PER_VERTEX: usize = size_of::<VertexSums>() + 1;

/// Bytes a call on `vertex_count` vertices needs under every policy but INHERIT:
/// `vertex_count * 29 + 3` (the 3 let the sums start at a 4-byte boundary wherever the caller's
/// bytes begin), 0 for an empty mesh. `None` on overflow.
pub fn scratch_size(vertex_count: usize) -> Option<usize> {
    scratch_size_with(vertex_count, 0)
}

/// [`scratch_size`] plus `link_bytes` (see [`link_bytes`]).
pub(crate) fn scratch_size_with(vertex_count: usize, link_bytes: usize) -> Option<usize> {
    if vertex_count == 0 {
        return Some(0);
    }
    vertex_count
        .checked_mul(BYTES_PER_VERTEX)?
        .checked_add(link_bytes)?
        .checked_add(align_of::<VertexSums>() - 1)
}

/// Bytes a per-vertex call with `policy` needs besides the sums and flags: policy INHERIT's
/// adjacency ([`adjacency_bytes`]), nothing for the other policies or an empty mesh.
pub(crate) fn link_bytes(policy: DegeneratePolicy, vertex_count: usize, corner_count: usize) -> Option<usize> {
    if policy != DegeneratePolicy::Inherit || vertex_count == 0 {
        return Some(0);
    }
    adjacency_bytes(vertex_count, corner_count)
}

/// Bytes policy INHERIT's adjacency (`robust::inherit::propagate`) needs for a mesh of `vertex_count` vertices and `corner_count` corners:
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

/// Memory for policy INHERIT's adjacency, which only a call that defers some vertex fills.
pub enum Links<'s> {
    /// None: another policy, or one worker's range.
    None,
    /// Caller bytes past the sums (4-byte aligned), any contents.
    Caller(&'s mut [u8]),
    /// Heap bytes reserved (`.1` of them) before the call writes anything, so that using them
    /// cannot fail halfway; not written while no vertex needs them.
    Heap(&'s mut Vec<u8>, usize),
}

impl Links<'_> {
    /// The bytes (any contents), at least as many as were asked for: the heap's filled up to
    /// their reserved length without reallocating.
    pub fn bytes(&mut self) -> &mut [u8] {
        match self {
            Links::None => &mut [],
            Links::Caller(bytes) => bytes,
            Links::Heap(vec, len) => {
                vec.resize(*len, 0);
                vec
            }
        }
    }
}

impl<'s> Scratch<'s> {
    /// Where vertex `v` sits in this range's arrays, if the range holds it.
    #[inline(always)]
    pub fn slot(&self, v: usize) -> Option<usize> {
        slot_in(v, self.first, self.flags.len())
    }

    /// The same arrays cut at the vertices in `ends` (exclusive ends, increasing, the last the
    /// vertex count), one part per worker.
    pub fn split(&mut self, ends: &[usize]) -> Vec<Scratch<'_>> {
        let (mut sums, mut flags): (&mut [VertexSums], &mut [u8]) = (&mut *self.sums, &mut *self.flags);
        let mut first = self.first;
        let mut parts = Vec::with_capacity(ends.len());
        for &end in ends {
            let (part_sums, rest_sums) = core::mem::take(&mut sums).split_at_mut(end - first);
            let (part_flags, rest_flags) = core::mem::take(&mut flags).split_at_mut(end - first);
            parts.push(Scratch {
                sums: part_sums,
                flags: part_flags,
                first,
                links: Links::None,
            });
            (sums, flags, first) = (rest_sums, rest_flags, end);
        }
        parts
    }
}

/// Heap storage for a call that brings no scratch.
#[derive(Default)]
pub struct OwnedScratch {
    sums: Vec<VertexSums>,
    flags: Vec<u8>,
    links: Vec<u8>,
    links_len: usize,
}

impl OwnedScratch {
    /// Allocates zeroed arrays for `vertex_count` vertices and reserves `link_bytes` for the
    /// adjacency (3 more, to align it), failing with `OutOfMemory` rather than aborting.
    pub fn allocate(vertex_count: usize, link_bytes: usize) -> Result<Self, Error> {
        let mut owned = OwnedScratch::default();
        owned
            .sums
            .try_reserve_exact(vertex_count)
            .map_err(|_| Error::OutOfMemory)?;
        owned
            .flags
            .try_reserve_exact(vertex_count)
            .map_err(|_| Error::OutOfMemory)?;
        if link_bytes > 0 {
            owned.links_len = link_bytes.checked_add(3).ok_or(Error::OutOfMemory)?;
            owned
                .links
                .try_reserve_exact(owned.links_len)
                .map_err(|_| Error::OutOfMemory)?;
        }
        owned.sums.resize(vertex_count, VertexSums::default());
        owned.flags.resize(vertex_count, 0);
        Ok(owned)
    }

    /// The arrays, borrowed for one call.
    pub fn scratch(&mut self) -> Scratch<'_> {
        Scratch {
            sums: &mut self.sums,
            flags: &mut self.flags,
            first: 0,
            links: match self.links_len {
                0 => Links::None,
                len => Links::Heap(&mut self.links, len),
            },
        }
    }
}

/// Runs `job` on zeroed arrays for `vertex_count` vertices, with `link_bytes` of room for the
/// adjacency ([`link_bytes`]): laid out in the caller's `bytes`, or allocated when there are none.
pub fn with_scratch<R>(
    bytes: Option<&mut [u8]>,
    vertex_count: usize,
    link_bytes: usize,
    job: impl FnOnce(&mut Scratch) -> Result<R, Error>,
) -> Result<R, Error> {
    match bytes {
        Some(bytes) => job(&mut carve(bytes, vertex_count, link_bytes)?),
        None => job(&mut OwnedScratch::allocate(vertex_count, link_bytes)?.scratch()),
    }
}

/// Lays the arrays for `vertex_count` vertices and `link_bytes` of adjacency out in caller memory
/// and zeroes the arrays: the sums, the adjacency (right after them, so 4-byte aligned), the flags.
pub fn carve(bytes: &mut [u8], vertex_count: usize, link_bytes: usize) -> Result<Scratch<'_>, Error> {
    let too_small = Error::ScratchTooSmall {
        needed: scratch_size_with(vertex_count, link_bytes).unwrap_or(usize::MAX),
        len: bytes.len(),
    };
    let (sums, rest) = pod_prefix_mut::<VertexSums>(bytes, vertex_count).ok_or_else(|| too_small.clone())?;
    if rest.len() < link_bytes {
        return Err(too_small);
    }
    let (links, rest) = rest.split_at_mut(link_bytes);
    let flags = rest.get_mut(..vertex_count).ok_or(too_small)?;
    sums.fill(VertexSums::default());
    flags.fill(0);
    let links = if link_bytes == 0 {
        Links::None
    } else {
        Links::Caller(links)
    };
    Ok(Scratch {
        sums,
        flags,
        first: 0,
        links,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scratch_size_is_enough_at_every_alignment_and_one_byte_less_is_not() {
        for vertex_count in [1usize, 2, 7, 100] {
            for link_bytes in [0, 4 * (2 * vertex_count + 9)] {
                let size = scratch_size_with(vertex_count, link_bytes).unwrap();
                let mut buffer = vec![0u8; size + 8];
                for offset in 0..4 {
                    let scratch = carve(&mut buffer[offset..offset + size], vertex_count, link_bytes).unwrap();
                    let links = match scratch.links {
                        Links::None => 0,
                        Links::Caller(bytes) => {
                            assert_eq!(bytes.as_ptr() as usize % 4, 0, "adjacency not aligned");
                            bytes.len()
                        }
                        Links::Heap(..) => unreachable!(),
                    };
                    assert_eq!(links, link_bytes);
                }
                // With the worst alignment, one byte less must fail.
                let worst = (0..4).find(|o| (buffer[*o..].as_ptr() as usize) % 4 == 1).unwrap();
                assert!(carve(&mut buffer[worst..worst + size - 1], vertex_count, link_bytes).is_err());
            }
        }
        assert_eq!(scratch_size(0), Some(0));
        assert_eq!(scratch_size(usize::MAX), None);
    }

    #[test]
    fn inherit_needs_its_adjacency_and_the_other_policies_nothing_more() {
        for policy in [
            DegeneratePolicy::Legacy,
            DegeneratePolicy::Skip,
            DegeneratePolicy::Reject,
        ] {
            assert_eq!(link_bytes(policy, 10, 30), Some(0));
        }
        let inherit = DegeneratePolicy::Inherit;
        assert_eq!(link_bytes(inherit, 0, 30), Some(0));
        // 4 bytes per entry: a start and a queue slot per vertex, one entry per corner.
        assert_eq!(link_bytes(inherit, 10, 30), Some(4 * (2 * 10 + 30)));
        let size = scratch_size_with(10, link_bytes(inherit, 10, 30).unwrap());
        assert_eq!(size, Some(10 * 37 + 30 * 4 + 3));
        assert_eq!(link_bytes(inherit, usize::MAX / 2, 30), None);
    }
}
