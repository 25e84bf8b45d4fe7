//! Whether the last run of mikktspace.c's edge sort can matter, from the few welded vertices that
//! can end it.
//!
//! `BuildNeighborsFast` sorts edges by the smaller index (`values` in [`super::weld`]) of their two
//! welded vertices, and leaves the run of the largest one unsorted (see [`super::neighbors`]). When
//! that run holds one edge, or the two sides of one edge, its order changes no pairing, and every
//! edge pairs as sorted runs pair, which needs no index at all. A welded vertex's index is that of
//! one of its corners, `4 * face + vert`, so it lies between the smallest and the largest of
//! them (`lo`, `hi`). The largest smaller index `i0*` is at least `L`, the largest smaller `lo`
//! over the edges, and both ends of an edge of that run have an index of at least `i0*`, so a `hi`
//! of at least `L`: only those vertices' indices are needed, and the splitting is replayed on just
//! the grid cells that hold them. When those are too many, a probe then replays the cells of the
//! last good triangles' vertices: the smaller index of any edge is at most `i0*` too, so the
//! largest one among their edges raises the bound, and with it the `hi` a vertex needs.
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::weld::{self, Wanted, WeldScratch};
use super::NONE;
use crate::kernel::vector::Packed;

/// The share of corners the replayed cells may hold (1 in this many) before the replay of every
/// cell is the cheaper way to every index; up to [`REPLAY_FLOOR`] corners the replay costs little anyway.
/// Fuzzing builds (`cfg(fuzzing)`, set by cargo-fuzz) lower the floor and the probe, so that the
/// fuzzer's small meshes take the probe and its narrowed replay too: every route must give the
/// same bits.
const REPLAY_SHARE: usize = 8;
const REPLAY_FLOOR: usize = if cfg!(fuzzing) { 24 } else { 4096 };

/// How many of the last good triangles the probe replays: each of their vertices has a corner near
/// the end of the list, so their edges' smaller indices tend to be the largest.
const PROBE_TRIANGLES: usize = if cfg!(fuzzing) { 2 } else { 64 };

/// In `lo`, once it has given `L`: a vertex of the probe whose index is not known yet.
const PROBED: u32 = NONE - 1;

/// Working memory: one word per welded vertex in each of `lo` and `hi`, and the weld's.
pub(crate) struct Memory<'a> {
    pub lo: &'a mut [u32],
    pub hi: &'a mut [u32],
    pub weld: WeldScratch<'a>,
}

/// True when the last run of mikktspace.c's edge sort holds at most the two sides of one edge.
/// `welded` are the corners' welded vertices, `source` a vertex of each welded vertex and `packed`
/// its attributes, `ids` the welded vertices of each good triangle (those mikktspace.c pairs the
/// edges of). False when it does not, or when finding out would cost a large part of the full
/// weld.
pub(crate) fn is_trivial(
    attributes: &Attributes,
    threads: u32,
    welded: &[u32],
    (source, packed): (&[u32], &[Packed]),
    ids: &[[u32; 3]],
    memory: Memory,
) -> bool {
    let Memory {
        lo,
        hi,
        weld: mut scratch,
    } = memory;
    lo.fill(NONE);
    hi.fill(0);
    for (c, &id) in welded.iter().enumerate() {
        let (id, v) = (id as usize, attributes.value_of(c));
        lo[id] = lo[id].min(v);
        hi[id] = hi[id].max(v);
    }
    let Some(lowest) = edges(ids).map(|(a, b)| lo[a].min(lo[b])).max() else {
        return true;
    };
    let search = Search {
        attributes,
        threads,
        welded,
        source,
        packed,
        ids,
        hi,
        corner_limit: (welded.len() / REPLAY_SHARE).max(REPLAY_FLOOR),
    };
    if !search.too_many(lowest) {
        if let Some(trivial) = search.settle(lowest, lo, &mut scratch) {
            return trivial;
        }
    }
    let Some(raised) = search.probe(lowest, lo, &mut scratch) else {
        return false;
    };
    // Unraised, the candidates are those that were too many already.
    raised > lowest && !search.too_many(raised) && search.settle(raised, lo, &mut scratch) == Some(true)
}

/// The edges of the good triangles, as pairs of welded vertices.
fn edges(ids: &[[u32; 3]]) -> impl Iterator<Item = (usize, usize)> + '_ {
    ids.iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(a, b)| (a as usize, b as usize))
}

/// What the search reads: the mesh, its weld by value, and each welded vertex's `hi`.
struct Search<'s> {
    attributes: &'s Attributes<'s>,
    threads: u32,
    welded: &'s [u32],
    source: &'s [u32],
    packed: &'s [Packed],
    ids: &'s [[u32; 3]],
    hi: &'s [u32],
    corner_limit: usize,
}

impl Search<'_> {
    /// Whether the candidates for a bound `lowest` are more than the replay may take: their cells
    /// hold at least as many corners as they are, so this stops before the grid.
    fn too_many(&self, lowest: u32) -> bool {
        self.hi.iter().filter(|&&h| h >= lowest).count() > self.corner_limit
    }

    /// `[corner, vertex, representative]` for every corner in the cells of the welded vertices
    /// `wanted` names, by mikktspace.c's weld (`None` past the corner limit).
    fn replay<'w>(
        &self,
        wanted: &(dyn Fn(usize) -> bool + Sync),
        scratch: &'w mut WeldScratch,
    ) -> Option<&'w [[u32; 3]]> {
        let wanted = Wanted {
            welded: wanted,
            corner_limit: self.corner_limit,
        };
        let welded_vertices = (self.welded, &self.source[..self.hi.len()], self.packed);
        weld::representatives(self.attributes, self.threads, welded_vertices, wanted, scratch)
    }

    /// The bound `lowest` raised by the exact indices of the last good triangles' vertices
    /// (written to `lo`); `None` past the corner limit.
    fn probe(&self, lowest: u32, lo: &mut [u32], scratch: &mut WeldScratch) -> Option<u32> {
        let last = &self.ids[self.ids.len().saturating_sub(PROBE_TRIANGLES)..];
        lo.fill(NONE);
        for &id in last.iter().flatten() {
            lo[id as usize] = PROBED;
        }
        let probed = &*lo;
        let found = self.replay(&|id| probed[id] != NONE, scratch)?;
        for &[c, _, first] in found {
            let id = self.welded[c as usize] as usize;
            if lo[id] != NONE {
                lo[id] = self.attributes.value_of(first as usize);
            }
        }
        let mut lowest = lowest;
        for (a, b) in edges(last) {
            lowest = lowest.max(lo[a].min(lo[b]));
        }
        Some(lowest)
    }

    /// Whether the last run is trivial, from the exact index of every welded vertex whose `hi` is
    /// at least `lowest` (a bound at most `i0*`), written to `lo`; `None` past the corner limit.
    fn settle(&self, lowest: u32, lo: &mut [u32], scratch: &mut WeldScratch) -> Option<bool> {
        let candidate = |id: usize| self.hi[id] >= lowest;
        for &[c, _, first] in self.replay(&candidate, scratch)? {
            let id = self.welded[c as usize] as usize;
            if candidate(id) {
                lo[id] = self.attributes.value_of(first as usize);
            }
        }
        // One pass: the largest smaller index so far, how many edges have it, and the larger
        // index of the first two.
        let index = &*lo;
        let (mut last, mut count, mut larger) = (0, 0usize, [0; 2]);
        for (a, b) in edges(self.ids).filter(|&(a, b)| candidate(a) && candidate(b)) {
            let (small, large) = (index[a].min(index[b]), index[a].max(index[b]));
            if count == 0 || small > last {
                (last, count, larger) = (small, 1, [large, 0]);
            } else if small == last {
                larger[1] = large;
                count += 1;
            }
        }
        Some(count < 2 || (count == 2 && larger[0] == larger[1]))
    }
}
