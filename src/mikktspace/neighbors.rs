//! Which good triangle lies across each edge (`BuildNeighborsFast`), in linear time.
//!
//! mikktspace.c sorts every edge by (smaller welded vertex, larger welded vertex, triangle) and
//! walks the sorted list: each edge not yet paired takes the first later edge of the same two
//! vertices that runs the other way and is not yet paired. Within one pair of vertices that is the
//! k-th edge running one way paired with the k-th running the other way, in triangle order (an
//! edge left unpaired when it is walked meets no opposite edge after it, so every opposite edge
//! before a later one is already taken). Here the edges are bucketed by their smaller vertex in
//! triangle order, and a queue per larger vertex pairs them as they come.
#![forbid(unsafe_code)]

use super::NONE;

/// Working memory: one word per edge for `entries` and `next`, per welded vertex for the others
/// (`starts` one more).
pub(crate) struct EdgeScratch<'a> {
    pub starts: &'a mut [u32],
    pub entries: &'a mut [u32],
    pub next: &'a mut [u32],
    pub head: &'a mut [u32],
    pub tail: &'a mut [u32],
    pub stamp: &'a mut [u32],
}

/// Writes `neighbors[g][k]`: the good triangle across edge `k` (from corner `k` to `k + 1`) of good
/// triangle `g`, or [`NONE`]. `ids[g]` are the welded vertices of good triangle `g`.
pub(crate) fn pair_edges(ids: &[[u32; 3]], neighbors: &mut [[u32; 3]], scratch: EdgeScratch) {
    let EdgeScratch {
        starts,
        entries,
        next,
        head,
        tail,
        stamp,
    } = scratch;
    let ends = |g: usize, k: usize| (ids[g][k], ids[g][(k + 1) % 3]);

    // Edges bucketed by their smaller welded vertex, in triangle order within a bucket.
    starts.fill(0);
    for g in 0..ids.len() {
        for k in 0..3 {
            let (a, b) = ends(g, k);
            starts[a.min(b) as usize + 1] += 1;
        }
    }
    for v in 1..starts.len() {
        starts[v] += starts[v - 1];
    }
    for g in 0..ids.len() {
        for k in 0..3 {
            let (a, b) = ends(g, k);
            let slot = &mut starts[a.min(b) as usize];
            entries[*slot as usize] = (3 * g + k) as u32;
            *slot += 1;
        }
    }
    // `starts[v]` now ends bucket v, so bucket v begins at `starts[v - 1]`.

    neighbors.fill([NONE; 3]);
    stamp.fill(NONE);
    let mut begin = 0usize;
    for (smaller, &end) in starts[..starts.len() - 1].iter().enumerate() {
        let end = end as usize;
        for &edge in &entries[begin..end] {
            let (g, k) = (edge as usize / 3, edge as usize % 3);
            let (a, b) = ends(g, k);
            let larger = a.max(b) as usize;
            let forward = a < b;
            if stamp[larger] != smaller as u32 {
                stamp[larger] = smaller as u32;
                head[larger] = NONE;
            }
            let waiting = head[larger];
            let waiting_forward = waiting != NONE && {
                let (wa, wb) = ends(waiting as usize / 3, waiting as usize % 3);
                wa < wb
            };
            if waiting != NONE && waiting_forward != forward {
                head[larger] = next[waiting as usize];
                let (h, hk) = (waiting as usize / 3, waiting as usize % 3);
                neighbors[h][hk] = g as u32;
                neighbors[g][k] = h as u32;
            } else {
                next[edge as usize] = NONE;
                if waiting == NONE {
                    head[larger] = edge;
                } else {
                    next[tail[larger] as usize] = edge;
                }
                tail[larger] = edge;
            }
        }
        begin = end;
    }
}
