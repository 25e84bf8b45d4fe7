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
//! the grid cells that hold them.
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::weld::{self, Wanted, WeldScratch};
use super::NONE;

/// The share of corners the replayed cells may hold (1 in this many) before the full weld is the
/// cheaper way to every index; up to [`REPLAY_FLOOR`] corners the replay costs little anyway.
const REPLAY_SHARE: usize = 8;
const REPLAY_FLOOR: usize = 4096;

/// Working memory: one word per welded vertex in each of `lo` and `hi`, and the weld's.
pub(crate) struct Memory<'a> {
    pub lo: &'a mut [u32],
    pub hi: &'a mut [u32],
    pub weld: WeldScratch<'a>,
}

/// True when the last run of mikktspace.c's edge sort holds at most the two sides of one edge.
/// `welded` are the corners' welded vertices, `class` each vertex's, `source` a vertex of each
/// welded vertex, `ids` the
/// welded vertices of each good triangle (those mikktspace.c pairs the edges of). False when it
/// does not, or when finding out would cost a large part of the full weld.
pub(crate) fn is_trivial(
    attributes: &Attributes,
    threads: u32,
    welded: &[u32],
    class: &[u32],
    source: &[u32],
    ids: &[[u32; 3]],
    memory: Memory,
) -> bool {
    let Memory { lo, hi, weld: scratch } = memory;
    lo.fill(NONE);
    hi.fill(0);
    for (c, &id) in welded.iter().enumerate() {
        let (id, v) = (id as usize, attributes.value_of(c));
        lo[id] = lo[id].min(v);
        hi[id] = hi[id].max(v);
    }
    let edges = || {
        ids.iter()
            .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
            .map(|(a, b)| (a as usize, b as usize))
    };
    let Some(lowest) = edges().map(|(a, b)| lo[a].min(lo[b])).max() else {
        return true;
    };
    let candidate = |id: usize| hi[id] >= lowest;
    // Their cells hold at least as many corners as they are: past the limit, stop before the grid.
    let candidates = hi.iter().filter(|&&h| h >= lowest).count();
    if candidates > (welded.len() / REPLAY_SHARE).max(REPLAY_FLOOR) {
        return false;
    }

    // The exact index of every candidate, in `lo`.
    let vertex_of = |c: usize| source[welded[c] as usize];
    let wanted = Wanted {
        vertex: &|v: u32| class[v as usize] != NONE && candidate(class[v as usize] as usize),
        corner_limit: (welded.len() / REPLAY_SHARE).max(REPLAY_FLOOR),
    };
    let replayed = weld::representatives(
        attributes,
        threads,
        welded.len(),
        &vertex_of,
        wanted,
        scratch,
        |c, first| {
            let id = welded[c as usize] as usize;
            if candidate(id) {
                lo[id] = attributes.value_of(first as usize);
            }
        },
    );
    if replayed.is_none() {
        return false;
    }
    let index = &*lo;
    let both = |&(a, b): &(usize, usize)| candidate(a) && candidate(b);
    let last = edges()
        .filter(both)
        .map(|(a, b)| index[a].min(index[b]))
        .max()
        .unwrap_or(0);
    let mut run = edges()
        .filter(|e| both(e) && index[e.0].min(index[e.1]) == last)
        .map(|(a, b)| index[a].max(index[b]));
    let first = run.next();
    let second = run.next();
    run.next().is_none() && (second.is_none() || second == first)
}
