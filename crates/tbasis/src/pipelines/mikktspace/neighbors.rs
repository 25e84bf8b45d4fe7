//! Which good triangle lies across each edge (`BuildNeighborsFast`).
//!
//! mikktspace.c sorts every edge by its smaller welded index `i0`, then each run of equal `i0` by
//! the larger `i1`, then each run of equal `(i0, i1)` by triangle, and walks the list: each edge
//! not yet paired takes the first later edge of the same run that runs the other way and is not
//! yet paired. In a sorted run that is the k-th edge running one way paired with the k-th running
//! the other way, in triangle order (an edge left unpaired when it is walked meets no opposite
//! edge after it, so every opposite edge before a later one is already taken); here a queue per
//! pair of welded vertices pairs them as they come, in linear time. But the C's loops sort a run
//! only when the next one begins, so the last run of `i0` is never sorted by `i1`, nor the last
//! run of `(i0, i1)` by triangle: the edges of the largest `i0` keep the order the first quicksort
//! left them in, and pair as they lie. Those are replayed exactly: the quicksort with its seed,
//! along the parts that hold them, and the walk over them.
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
/// triangle `g`, or [`NONE`]. `ids[g]` are the welded vertices of good triangle `g`, `values[id]`
/// mikktspace.c's index for welded vertex `id`; `None` when the last run is known to hold at most
/// the two sides of one edge ([`super::last_run`]), whose order changes nothing.
pub(crate) fn pair_edges(
    ids: &[[u32; 3]],
    values: Option<&[u32]>,
    neighbors: &mut [[u32; 3]],
    mut scratch: EdgeScratch,
) {
    let ends = |edge: u32| edge_ends(ids, edge);
    neighbors.fill([NONE; 3]);
    let edge_count = 3 * ids.len();
    if edge_count == 0 {
        return;
    }
    let last = values.map(|values| (values, replay_last_run(ids, values, neighbors, &mut scratch)));
    let EdgeScratch {
        starts,
        entries,
        next,
        head,
        tail,
        stamp,
    } = scratch;

    // Every other edge: bucketed by its smaller welded vertex, in triangle order within a bucket.
    let in_last_run = |edge: u32| {
        let (a, b) = ends(edge);
        last.is_some_and(|(values, last)| values[a as usize].min(values[b as usize]) == last)
    };
    starts.fill(0);
    for edge in 0..edge_count as u32 {
        let (a, b) = ends(edge);
        starts[a.min(b) as usize + 1] += u32::from(!in_last_run(edge));
    }
    for v in 1..starts.len() {
        starts[v] += starts[v - 1];
    }
    for edge in 0..edge_count as u32 {
        if in_last_run(edge) {
            continue;
        }
        let (a, b) = ends(edge);
        let slot = &mut starts[a.min(b) as usize];
        entries[*slot as usize] = edge;
        *slot += 1;
    }
    // `starts[v]` now ends bucket v, so bucket v begins at `starts[v - 1]`.

    stamp.fill(NONE);
    let mut begin = 0usize;
    for (smaller, &end) in starts[..starts.len() - 1].iter().enumerate() {
        let end = end as usize;
        for &edge in &entries[begin..end] {
            let (a, b) = ends(edge);
            let larger = a.max(b) as usize;
            let forward = a < b;
            if stamp[larger] != smaller as u32 {
                stamp[larger] = smaller as u32;
                head[larger] = NONE;
            }
            let waiting = head[larger];
            let waiting_forward = waiting != NONE && {
                let (wa, wb) = ends(waiting);
                wa < wb
            };
            if waiting != NONE && waiting_forward != forward {
                head[larger] = next[waiting as usize];
                pair(neighbors, waiting, edge);
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

/// The pairing of the last run alone, for a route that pairs every other edge by the sorted rule
/// itself ([`super::fans`]): writes `neighbors` as [`pair_edges`] does across the edges of the
/// largest `i0`, [`NONE`] across every other, and returns that `i0`.
pub(crate) fn pair_last_run(
    ids: &[[u32; 3]],
    values: &[u32],
    neighbors: &mut [[u32; 3]],
    mut scratch: EdgeScratch,
) -> u32 {
    neighbors.fill([NONE; 3]);
    if ids.is_empty() {
        return 0;
    }
    replay_last_run(ids, values, neighbors, &mut scratch)
}

/// The welded vertices of edge `edge` (corner `edge % 3` to the next of good triangle `edge / 3`).
#[inline(always)]
fn edge_ends(ids: &[[u32; 3]], edge: u32) -> (u32, u32) {
    let (g, k) = (edge as usize / 3, edge as usize % 3);
    (ids[g][k], ids[g][(k + 1) % 3])
}

/// Pairs the edges of the largest `i0` in the order mikktspace.c walks them, and returns that
/// `i0`.
fn replay_last_run(ids: &[[u32; 3]], values: &[u32], neighbors: &mut [[u32; 3]], scratch: &mut EdgeScratch) -> u32 {
    let EdgeScratch {
        entries,
        next,
        head,
        tail,
        stamp,
        ..
    } = scratch;
    let ends = |edge: u32| edge_ends(ids, edge);
    let smaller_value = |edge: u32| {
        let (a, b) = ends(edge);
        values[a as usize].min(values[b as usize])
    };
    let larger_value = |edge: u32| {
        let (a, b) = ends(edge);
        values[a as usize].max(values[b as usize])
    };
    let edge_count = 3 * ids.len();
    let last = (0..edge_count as u32).map(smaller_value).max().unwrap_or(0);
    let order = &mut entries[..edge_count];
    let keys = &mut next[..edge_count];
    for (edge, (slot, key)) in (0u32..).zip(order.iter_mut().zip(keys.iter_mut())) {
        *slot = edge;
        *key = smaller_value(edge);
    }
    // The quicksort's pending parts live in arrays the second step fills later.
    quicksort_toward(keys, order, last, [&mut **head, &mut **tail, &mut **stamp]);
    let first_of_last = keys.iter().rposition(|&key| key != last).map_or(0, |p| p + 1);
    let run = &mut order[first_of_last..];
    // The third pass sorts each run of equal i1 by triangle, all but the very last one.
    let mut start = 0;
    for i in 1..run.len() {
        if larger_value(run[i]) != larger_value(run[start]) {
            run[start..i].sort_unstable();
            start = i;
        }
    }
    walk(run, &ends, &larger_value, neighbors);

    last
}

/// Records the triangles of edges `a` and `b` as neighbours across them.
fn pair(neighbors: &mut [[u32; 3]], a: u32, b: u32) {
    let (ga, ka, gb, kb) = (a as usize / 3, a as usize % 3, b as usize / 3, b as usize % 3);
    neighbors[ga][ka] = gb as u32;
    neighbors[gb][kb] = ga as u32;
}

/// mikktspace.c's `QuickSortEdges` on `keys` (carrying `edges` along), seed and pivots as in the C,
/// but only into the parts that hold a key `last`: where those edges end up, and in what order,
/// depends on nothing else. Pending parts (disjoint, two keys or more) wait in `stack` as left
/// end, right end and seed, one array each.
fn quicksort_toward(keys: &mut [u32], edges: &mut [u32], last: u32, stack: [&mut [u32]; 3]) {
    const SEED: u32 = 39_871_946;
    let mut pending = Pending { stack, top: 0, last };
    pending.push(keys, 0, keys.len() - 1, SEED);
    while let Some((left, right, seed)) = pending.pop() {
        let count = right - left + 1;
        if count == 2 {
            if keys[left] > keys[right] {
                keys.swap(left, right);
                edges.swap(left, right);
            }
            continue;
        }
        let seed = seed.wrapping_add(seed.rotate_left(seed & 31)).wrapping_add(3);
        let pivot = keys[left + (seed as usize % count)];
        let (mut l, mut r) = (left as isize, right as isize);
        loop {
            while keys[l as usize] < pivot {
                l += 1;
            }
            while keys[r as usize] > pivot {
                r -= 1;
            }
            if l <= r {
                keys.swap(l as usize, r as usize);
                edges.swap(l as usize, r as usize);
                l += 1;
                r -= 1;
            }
            if l > r {
                break;
            }
        }
        if (left as isize) < r {
            pending.push(keys, left, r as usize, seed);
        }
        if (l as usize) < right {
            pending.push(keys, l as usize, right, seed);
        }
    }
}

/// The quicksort's pending parts that hold the key `last`: left ends, right ends and seeds.
struct Pending<'a> {
    stack: [&'a mut [u32]; 3],
    top: usize,
    last: u32,
}

impl Pending<'_> {
    fn push(&mut self, keys: &[u32], left: usize, right: usize, seed: u32) {
        if left < right && keys[left..=right].contains(&self.last) {
            let [lefts, rights, seeds] = &mut self.stack;
            (lefts[self.top], rights[self.top], seeds[self.top]) = (left as u32, right as u32, seed);
            self.top += 1;
        }
    }

    fn pop(&mut self) -> Option<(usize, usize, u32)> {
        self.top = self.top.checked_sub(1)?;
        let [lefts, rights, seeds] = &self.stack;
        Some((lefts[self.top] as usize, rights[self.top] as usize, seeds[self.top]))
    }
}

/// mikktspace.c's pairing walk over `run`, edges as they lie: each edge not yet paired takes the
/// first later edge, contiguous with it and of the same two welded vertices, that runs the other
/// way and is not yet paired.
fn walk(run: &[u32], ends: &dyn Fn(u32) -> (u32, u32), larger_value: &dyn Fn(u32) -> u32, neighbors: &mut [[u32; 3]]) {
    for (i, &edge) in run.iter().enumerate() {
        if neighbors[edge as usize / 3][edge as usize % 3] != NONE {
            continue;
        }
        let (start, end) = ends(edge);
        for &other in &run[i + 1..] {
            if larger_value(other) != larger_value(edge) {
                break;
            }
            if ends(other) == (end, start) && neighbors[other as usize / 3][other as usize % 3] == NONE {
                pair(neighbors, edge, other);
                break;
            }
        }
    }
}
