//! Welding corners: mikktspace.c treats corners whose position, normal and texture coordinate
//! compare equal with `==` as one vertex (`GenerateSharedVerticesIndexList`).
//!
//! mikktspace.c finds equal corners by sorting them into a grid along the widest axis of their
//! bounding box and splitting each cell at the midpoint of its widest extent until a part holds one
//! value (`MergeVertsFast`); each corner then takes the index of the first equal corner in the order
//! that splitting leaves. That order is visible downstream: the representative's bits are read
//! (a `-0.0` against a `+0.0`), a cell whose midpoint is not finite is left unwelded, and the
//! representative's index decides which edges end mikktspace.c's edge sort (see `neighbors`). So
//! the splitting is replayed step by step, its recursion on a stack, and its final quadratic search
//! compares vertex numbers first: corners of one vertex are equal unless a float is `NaN`; corners
//! of different vertices at the same position (seams, unwelded exports) compare per-vertex hashes,
//! and read their attributes only when those agree. Cells are independent, so ranges of them run on separate threads.
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::NONE;
use crate::kernel::error::Error;
use crate::kernel::memory::Arena;
use crate::kernel::parallel::{self, Ranges};
use crate::kernel::vector::{self, Packed, Vec3};

/// mikktspace.c's grid: cells along the widest axis of the bounding box.
const GRID_CELLS: usize = 2048;

/// Marks a vertex with a `NaN` among its attributes in [`WeldScratch::cells`]: it equals nothing.
const UNEQUAL: u32 = 1 << 31;

/// Working memory, all of it reused by the phases after the weld.
pub(crate) struct WeldScratch<'a> {
    /// Per vertex: its grid cell, or'd with [`UNEQUAL`], and a hash of its attributes; per cell,
    /// where its corners start, and the next free place.
    cells: &'a mut [u32],
    hashes: &'a mut [u32],
    starts: &'a mut [u32],
    cursors: &'a mut [u32],
    /// Per corner, in cell order: its position, and (corner, vertex or [`NONE`] when the vertex is
    /// [`UNEQUAL`], representative corner).
    positions: &'a mut [Vec3],
    entries: &'a mut [[u32; 3]],
    /// Per corner: its representative, then per representative its welded number; in a replay of
    /// selected cells, the list of their corners.
    representative: &'a mut [u32],
    number: &'a mut [u32],
    /// Pending parts of a cell, as (first, last) entry: last, as little of it is used (the
    /// phases after the weld find the pages before it already touched).
    stack: &'a mut [[u32; 2]],
}

impl<'a> WeldScratch<'a> {
    /// The cells, and apart from them what [`weld_cells`] works in; `listed`: with room for a list
    /// of the selected corners.
    fn cells_apart(&mut self, listed: bool) -> (&mut [u32], CellMemory<'_>) {
        let memory = CellMemory {
            hashes: self.hashes,
            starts: self.starts,
            cursors: self.cursors,
            positions: self.positions,
            entries: self.entries,
            stack: self.stack,
            listed: listed.then_some(&mut *self.representative),
        };
        (self.cells, memory)
    }

    /// Takes the scratch for `vertex_count` vertices and `corner_count` corners.
    pub fn take(arena: &mut Arena<'a>, vertex_count: usize, corner_count: usize) -> Result<Self, Error> {
        Ok(WeldScratch {
            cells: arena.take(vertex_count)?,
            hashes: arena.take(vertex_count)?,
            starts: arena.take(GRID_CELLS + 1)?,
            cursors: arena.take(GRID_CELLS)?,
            positions: arena.take(corner_count)?,
            entries: arena.take(corner_count)?,
            representative: arena.take(corner_count)?,
            number: arena.take(corner_count)?,
            stack: arena.take(corner_count)?,
        })
    }
}

/// Replaces the vertex of every corner in `corners` (indices already checked) by the number of its
/// welded vertex, numbered in order of first use; writes, per welded vertex, the vertex it reads its
/// attributes from to `source` and mikktspace.c's index for it (`4 * face + corner` of the corner
/// that represents it) to `values`. Returns the number of welded vertices.
pub(crate) fn weld(
    attributes: &Attributes,
    threads: u32,
    corners: &mut [u32],
    source: &mut [u32],
    values: &mut [u32],
    mut scratch: WeldScratch,
) -> usize {
    let corner_count = corners.len();
    let vertices = &*corners;
    let filled = split_cells(attributes, threads, corner_count, &|c| vertices[c], &mut scratch);
    debug_assert_eq!(filled, corner_count);
    let WeldScratch {
        hashes,
        entries,
        representative,
        number,
        ..
    } = scratch;

    // 4. Number the welded vertices in order of first use.
    for &[corner, _, first] in entries.iter() {
        representative[corner as usize] = first;
    }
    if attributes.corner_values.is_some() {
        // A face vertex that two triangles share (on a quad's diagonal) is one index in
        // mikktspace.c, welded or not (a `NaN`, a cell left unwelded): every representative
        // stands for its vertex's first corner.
        let first_of_vertex = &mut hashes[..];
        first_of_vertex.fill(NONE);
        for (c, &v) in corners.iter().enumerate() {
            if first_of_vertex[v as usize] == NONE {
                first_of_vertex[v as usize] = c as u32;
            }
        }
        for r in representative.iter_mut() {
            *r = first_of_vertex[corners[*r as usize] as usize];
        }
    }
    number.fill(NONE);
    let mut count = 0u32;
    for c in 0..corner_count {
        let first = representative[c] as usize;
        if number[first] == NONE {
            number[first] = count;
            // `first` has not been renumbered yet: either it is `c`, or it lies ahead.
            source[count as usize] = corners[first];
            values[count as usize] = attributes.value_of(first);
            count += 1;
        }
        corners[c] = number[first];
    }
    count as usize
}

/// Cells of the grid holding a wanted welded vertex, and the most corners they may hold together.
pub(crate) struct Wanted<'w> {
    pub welded: &'w (dyn Fn(usize) -> bool + Sync),
    pub corner_limit: usize,
}

/// mikktspace.c's representative corner of each corner in the grid cells holding a welded vertex
/// `wanted` names, by replaying `MergeVertsFast` on those cells alone: cells are welded
/// independently. `welded` is every corner's welded vertex from the weld by value
/// ([`super::value_weld`]), `source` a vertex of each and `packed` its attributes (read in
/// order, rather than the mesh's through `source`). Returns `[corner, vertex,
/// representative]` for each such corner, the vertex being its welded vertex's source; `None` when
/// those cells hold more than `wanted.corner_limit` corners (nothing replayed).
///
/// The weld by value found no `NaN` and a welded vertex's corners have identical bits, so the box
/// and the cells come from the welded vertices rather than from every corner. A cell is a
/// function of the position. The box's strict comparisons keep, of equal values, the first one
/// met. The welded vertices are numbered in order of first use, so the first of them with a
/// given coordinate is the welded vertex of the first corner with it, and has that corner's bits.
/// The C's box starts at index 0's position and takes the corners from the second on: when index
/// 0 is corner 0, the welded vertices give that box; when it is an ignored face's vertex
/// (`index_zero`), corner 0 is left out, so the box comes from the corners.
pub(crate) fn representatives<'s>(
    attributes: &Attributes,
    threads: u32,
    (welded, source, packed): (&[u32], &[u32], &[Packed]),
    wanted: Wanted,
    scratch: &'s mut WeldScratch,
) -> Option<&'s [[u32; 3]]> {
    let position = |w: usize| vector::position(&packed[w]);
    let (min, max) = match attributes.index_zero {
        Some(seed) => bounding_box(threads, welded.len(), seed, &|c| position(welded[c] as usize)),
        None => {
            let seed = position(welded[0] as usize);
            let (mut min, mut max) = (seed, seed);
            packed
                .iter()
                .for_each(|p| extend_box(&mut min, &mut max, vector::position(p)));
            (min, max)
        }
    };
    let axis = widest_axis([max[0] - min[0], max[1] - min[1], max[2] - min[2]]);
    let (cells, memory) = scratch.cells_apart(true);
    let cells = &mut cells[..packed.len()];
    let mut selected = [false; GRID_CELLS];
    for (w, (cell, p)) in cells.iter_mut().zip(packed).enumerate() {
        let k = grid_cell(min[axis], max[axis], p[axis]);
        *cell = k as u32;
        selected[k] |= (wanted.welded)(w);
    }
    // Only the selected cells' vertices are compared.
    for ((&cell, &v), key) in cells.iter().zip(source).zip(packed) {
        if selected[cell as usize] {
            memory.hashes[v as usize] = hash_of(&key.map(canonical_bits));
        }
    }
    let cells = &*cells;
    let locate = |c: usize| {
        let w = welded[c] as usize;
        (cells[w], source[w])
    };
    let selection = (&selected, wanted.corner_limit);
    weld_cells(attributes, threads, welded.len(), &locate, selection, memory)
}

/// Steps 1 to 3 of the weld on every cell: the grid, then each cell's corners gathered in corner
/// order and split and welded (`MergeVertsFast`). Leaves, in `scratch.entries`, (corner, vertex or
/// [`NONE`], representative corner) of every corner, and returns the corner count.
fn split_cells(
    attributes: &Attributes,
    threads: u32,
    corner_count: usize,
    vertex_of: &(impl Fn(usize) -> u32 + Sync),
    scratch: &mut WeldScratch,
) -> usize {
    let position = |v: u32| attributes.position(v);

    // 1. The bounding box.
    let seed = attributes.index_zero.unwrap_or_else(|| position(vertex_of(0)));
    let (min, max) = bounding_box(threads, corner_count, seed, &|c| position(vertex_of(c)));
    let axis = widest_axis([max[0] - min[0], max[1] - min[1], max[2] - min[2]]);

    // 2. Each vertex's grid cell and hash (ranges of vertices on separate threads).
    let (cells, memory) = scratch.cells_apart(false);
    let vertex_ranges = parallel::item_ranges(threads, cells.len(), 1);
    let ends = vertex_ranges.ends();
    let parts = parallel::split(cells, ends, 1).zip(parallel::split(memory.hashes, ends, 1));
    parallel::run_ranges(ends, parts, |first, (cells, hashes)| {
        for (v, (cell, hash)) in (first..).zip(cells.iter_mut().zip(hashes.iter_mut())) {
            let key = attributes.key(v as u32);
            let unequal = if key.iter().any(|x| x.is_nan()) { UNEQUAL } else { 0 };
            *cell = grid_cell(min[axis], max[axis], key[axis]) as u32 | unequal;
            *hash = hash_of(&key.map(canonical_bits));
        }
    });
    let cells = &*cells;
    let locate = |c: usize| {
        let v = vertex_of(c);
        (cells[v as usize], v)
    };
    let every_cell = (&[true; GRID_CELLS], usize::MAX);
    weld_cells(attributes, threads, corner_count, &locate, every_cell, memory).map_or(0, <[_]>::len)
}

/// What [`weld_cells`] works in: [`WeldScratch`] but the cells.
struct CellMemory<'m> {
    hashes: &'m mut [u32],
    starts: &'m mut [u32],
    cursors: &'m mut [u32],
    positions: &'m mut [Vec3],
    entries: &'m mut [[u32; 3]],
    stack: &'m mut [[u32; 2]],
    /// Room for the selected corners, one word per corner, when few cells are selected: the
    /// workers then gather from that list rather than from every corner.
    listed: Option<&'m mut [u32]>,
}

/// The vertex of a corner's entry: [`NONE`] where its attributes hold a `NaN` (the cell is marked
/// [`UNEQUAL`]), so that it equals nothing.
fn entry_vertex(cell: u32, vertex: u32) -> u32 {
    if cell & UNEQUAL != 0 {
        NONE
    } else {
        vertex
    }
}

/// Step 3 of the weld: each selected cell's corners gathered in corner order, then split and
/// welded (`MergeVertsFast`); on ranges of cells on separate threads where the corners are many.
/// `locate(c)` gives corner `c`'s cell (or'd with [`UNEQUAL`]) and vertex. Returns (corner, vertex
/// or [`NONE`], representative corner) of the corners those cells hold; `None` when they pass
/// `corner_limit` (nothing welded).
fn weld_cells<'m>(
    attributes: &Attributes,
    threads: u32,
    corner_count: usize,
    locate: &(dyn Fn(usize) -> (u32, u32) + Sync),
    selection: (&[bool; GRID_CELLS], usize),
    memory: CellMemory<'m>,
) -> Option<&'m [[u32; 3]]> {
    if corner_count < FEW_CORNERS && !count_always() {
        let CellMemory {
            hashes,
            positions,
            entries,
            stack,
            ..
        } = memory;
        let equal = Equality {
            attributes,
            hashes: &*hashes,
        };
        sort_into_cells(&equal, corner_count, locate, selection, (positions, entries, stack))
    } else {
        count_into_cells(attributes, threads, corner_count, locate, selection, memory)
    }
}

/// Below this many corners, [`weld_cells`] sorts the corners by cell rather than counting them
/// into every one of the [`GRID_CELLS`] cells, whose passes would take most of a small mesh's
/// time. Fuzzing builds (`cfg(fuzzing)`) lower it, so that the fuzzer's small meshes take both
/// ways.
pub(super) const FEW_CORNERS: usize = if cfg!(fuzzing) { 24 } else { GRID_CELLS / 16 };

#[cfg(test)]
std::thread_local! {
    /// Set by tests to take [`count_into_cells`] on meshes of any size, on this thread.
    pub(super) static COUNT_ALWAYS: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
}

/// Whether a test asked for [`count_into_cells`] on every mesh.
fn count_always() -> bool {
    #[cfg(test)]
    return COUNT_ALWAYS.with(core::cell::Cell::get);
    #[cfg(not(test))]
    false
}

/// [`weld_cells`] by sorting (cell, corner) pairs, on one thread: the same entries, in the same
/// order (cells in order, corners in order within each).
fn sort_into_cells<'m>(
    equal: &Equality,
    corner_count: usize,
    locate: &(dyn Fn(usize) -> (u32, u32) + Sync),
    (selected, corner_limit): (&[bool; GRID_CELLS], usize),
    (positions, entries, stack): (&mut [Vec3], &'m mut [[u32; 3]], &mut [[u32; 2]]),
) -> Option<&'m [[u32; 3]]> {
    // Each selected corner's entry, its cell in the representative's place for the sort.
    let mut filled = 0;
    for c in 0..corner_count {
        let (cell, v) = locate(c);
        let k = cell & !UNEQUAL;
        if selected[k as usize] {
            entries[filled] = [c as u32, entry_vertex(cell, v), k];
            filled += 1;
        }
    }
    if filled > corner_limit {
        return None;
    }
    let entries = &mut entries[..filled];
    entries.sort_unstable_by_key(|&[corner, _, cell]| (cell, corner));
    let mut start = 0;
    while start < filled {
        let cell = entries[start][2];
        let end = start + entries[start..].iter().take_while(|e| e[2] == cell).count();
        for (position, entry) in positions[start..end].iter_mut().zip(&mut entries[start..end]) {
            *position = equal.attributes.position(locate(entry[0] as usize).1);
            entry[2] = entry[0];
        }
        split_and_weld(equal, &mut positions[start..end], &mut entries[start..end], stack);
        start = end;
    }
    Some(entries)
}

/// [`weld_cells`] by counting the corners into the cells, ranges of cells on separate threads.
fn count_into_cells<'m>(
    attributes: &Attributes,
    threads: u32,
    corner_count: usize,
    locate: &(dyn Fn(usize) -> (u32, u32) + Sync),
    (selected, corner_limit): (&[bool; GRID_CELLS], usize),
    memory: CellMemory<'m>,
) -> Option<&'m [[u32; 3]]> {
    let CellMemory {
        hashes,
        starts,
        cursors,
        positions,
        entries,
        stack,
        listed,
    } = memory;
    starts.fill(0);
    let mut list = listed.map(|list| (list, 0));
    for c in 0..corner_count {
        let k = (locate(c).0 & !UNEQUAL) as usize;
        starts[k + 1] += u32::from(selected[k]);
        if let Some((list, count)) = list.as_mut().filter(|_| selected[k]) {
            list[*count] = c as u32;
            *count += 1;
        }
    }
    let list = list.map(|(list, count)| &list[..count]);
    // A running total in a register: each cell's start does not wait on the store of the last.
    // Each cell's cursor starts at its start, written here rather than copied after (8 KiB).
    let mut total = 0;
    for (start, cursor) in starts[1..].iter_mut().zip(cursors.iter_mut()) {
        *cursor = total;
        total += *start;
        *start = total;
    }
    let filled = starts[GRID_CELLS] as usize;
    if filled > corner_limit {
        return None;
    }

    // Each worker gathers its cells' corners (in corner order within a cell), then splits and
    // welds every cell.
    let cell_ranges = cell_ranges(threads, starts);
    let ends = cell_ranges.ends();
    let bounds = Ranges::from_ends(ends.iter().map(|&cell| starts[cell] as usize));
    let bounds = bounds.ends();
    let first_cells = core::iter::once(0).chain(ends.iter().copied());
    let starts = &*starts;
    let parts = parallel::split(&mut positions[..filled], bounds, 1)
        .zip(parallel::split(&mut entries[..filled], bounds, 1))
        .zip(parallel::split(&mut stack[..filled], bounds, 1))
        .zip(parallel::split(cursors, ends, 1))
        .zip(first_cells.zip(ends.iter().copied()));
    parallel::run_ranges(
        bounds,
        parts,
        |first, ((((positions, entries), stack), cursors), (first_cell, end_cell))| {
            let owned = first_cell..end_cell;
            let corners: &mut dyn Iterator<Item = usize> = match list {
                Some(list) => &mut list.iter().map(|&c| c as usize),
                None => &mut (0..corner_count),
            };
            for c in corners {
                let (cell, v) = locate(c);
                let k = (cell & !UNEQUAL) as usize;
                if !owned.contains(&k) || !selected[k] {
                    continue;
                }
                let cursor = &mut cursors[k - first_cell];
                let at = *cursor as usize - first;
                *cursor += 1;
                positions[at] = attributes.position(v);
                entries[at] = [c as u32, entry_vertex(cell, v), c as u32];
            }
            let equal = Equality {
                attributes,
                hashes: &*hashes,
            };
            for k in owned {
                let cell = starts[k] as usize - first..starts[k + 1] as usize - first;
                split_and_weld(&equal, &mut positions[cell.clone()], &mut entries[cell], stack);
            }
        },
    );
    Some(&entries[..filled])
}

/// The box mikktspace.c's `if ... else if` updates find, from `seed` (index 0's position) over
/// corners 1 onwards: a corner lowers the minimum or raises the maximum where it compares past
/// them, so a `NaN` moves nothing and a `NaN` in the seed stays; of equal values (a -0 and a +0)
/// the first stays. Ranges of corners on separate threads, each from its first value that is not
/// `NaN`, joined to the seed in order with the same strict comparisons: the same box.
/// `position(c)` is corner `c`'s position.
fn bounding_box(
    threads: u32,
    corner_count: usize,
    seed: Vec3,
    position: &(impl Fn(usize) -> Vec3 + Sync),
) -> (Vec3, Vec3) {
    let ranges = parallel::item_ranges(threads, corner_count, 3);
    let ends = ranges.ends();
    let mut boxes = [[[f32::NAN; 3]; 2]; parallel::MAX_RANGES];
    let starts = core::iter::once(1).chain(ends.iter().copied());
    let parts = starts.zip(ends).zip(boxes.iter_mut());
    parallel::run_ranges(ends, parts, |_, ((start, &end), [min, max])| {
        for c in start..end {
            let p = position(c);
            for axis in 0..3 {
                if min[axis].is_nan() {
                    (min[axis], max[axis]) = (p[axis], p[axis]);
                } else if min[axis] > p[axis] {
                    min[axis] = p[axis];
                } else if max[axis] < p[axis] {
                    max[axis] = p[axis];
                }
            }
        }
    });
    let (mut min, mut max) = (seed, seed);
    for [range_min, range_max] in &boxes[..ends.len()] {
        for axis in 0..3 {
            if min[axis] > range_min[axis] {
                min[axis] = range_min[axis];
            }
            if max[axis] < range_max[axis] {
                max[axis] = range_max[axis];
            }
        }
    }
    (min, max)
}

/// mikktspace.c's update of its bounding box by `p` (`if ... else if`): a coordinate lowers the
/// minimum or raises the maximum where it compares past them.
#[inline(always)]
fn extend_box(min: &mut Vec3, max: &mut Vec3, p: Vec3) {
    for axis in 0..3 {
        if min[axis] > p[axis] {
            min[axis] = p[axis];
        } else if max[axis] < p[axis] {
            max[axis] = p[axis];
        }
    }
}

/// The ranges of grid cells the workers take, about equal in corners.
fn cell_ranges(threads: u32, starts: &[u32]) -> Ranges {
    let corner_count = starts[GRID_CELLS] as usize;
    let targets = parallel::ranges(threads, corner_count / 3);
    let count = targets.ends().len();
    let mut previous = 0;
    Ranges::from_ends(targets.ends().iter().enumerate().filter_map(|(i, &t)| {
        // The last range ends the grid; an empty one is dropped.
        let end = if i + 1 == count {
            GRID_CELLS
        } else {
            starts.partition_point(|&s| (s as usize) < 3 * t).min(GRID_CELLS)
        };
        (end > previous).then(|| {
            previous = end;
            end
        })
    }))
}

/// A multiplicative hash of the eight canonical floats.
pub(crate) fn hash_of(bits: &[u32; 8]) -> u32 {
    let mut h = 0u64;
    for &b in bits {
        h = (h ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
    (h >> 32) as u32
}

/// The bits of `x`, with -0 as +0 so that values equal under `==` have equal bits.
#[inline(always)]
pub(crate) fn canonical_bits(x: f32) -> u32 {
    if x == 0.0 {
        0
    } else {
        x.to_bits()
    }
}

/// `MergeVertsFast` on one grid cell, its recursion on `stack` (a cell can split hundreds deep;
/// pending parts are disjoint and hold two entries or more, so with the partition's pairs the
/// stack needs as many slots as the cell has entries).
fn split_and_weld(equal: &Equality, positions: &mut [Vec3], entries: &mut [[u32; 3]], stack: &mut [[u32; 2]]) {
    if entries.len() < 2 {
        // Nothing to weld: a lone corner represents itself.
        return;
    }
    stack[0] = [0, entries.len() as u32 - 1];
    let mut top = 1;
    while top > 0 {
        top -= 1;
        let [left, right] = stack[top].map(|x| x as usize);
        let part = &mut positions[left..=right];
        let mut min = part[0];
        let mut max = min;
        for p in &part[1..] {
            for axis in 0..3 {
                if min[axis] > p[axis] {
                    min[axis] = p[axis];
                }
                if max[axis] < p[axis] {
                    max[axis] = p[axis];
                }
            }
        }
        let axis = widest_axis([max[0] - min[0], max[1] - min[1], max[2] - min[2]]);
        let separator = 0.5 * (max[axis] + min[axis]);
        if !separator.is_finite() {
            // mikktspace.c gives up on this part: none of its corners weld.
            continue;
        }
        if separator >= max[axis] || separator <= min[axis] {
            weld_run(equal, &mut entries[left..=right]);
            continue;
        }
        // Pending parts lie outside this one and hold two entries or more: the slots past them
        // have room for the pairs.
        let pairs = &mut stack[top..];
        let (below_end, above_start) = partition(part, &mut entries[left..=right], axis, separator, pairs);
        if below_end > 0 {
            stack[top] = [left as u32, (left + below_end) as u32];
            top += 1;
        }
        if above_start < part.len() - 1 {
            stack[top] = [(left + above_start) as u32, right as u32];
            top += 1;
        }
    }
}

/// The C's two-sided partition of `positions` (and `entries` alongside) around `separator` on
/// `axis`, swap for swap. Its scans swap the i-th entry at or above the separator, counted from the
/// left, with the i-th below it, counted from the right, until the two cross: exactly the entries
/// on the wrong side of the boundary `k` (the number below), paired in order. Finding those pairs
/// in straight passes avoids the scans' unpredictable branches. `pairs` needs half as many slots
/// as there are entries, plus one. Returns the last position of the lower part (0 when it holds one
/// entry or none, which need no welding) and the first position of the upper part.
fn partition(
    positions: &mut [Vec3],
    entries: &mut [[u32; 3]],
    axis: usize,
    separator: f32,
    pairs: &mut [[u32; 2]],
) -> (usize, usize) {
    let below = |p: &Vec3| p[axis] < separator;
    let k = positions.iter().filter(|p| below(p)).count();
    let mut swaps = 0;
    for (i, p) in positions[..k].iter().enumerate() {
        pairs[swaps][0] = i as u32;
        swaps += usize::from(!below(p));
    }
    let mut from_right = 0;
    for (i, p) in positions.iter().enumerate().skip(k).rev() {
        pairs[from_right][1] = i as u32;
        from_right += usize::from(below(p));
    }
    for &[l, r] in &pairs[..swaps] {
        positions.swap(l as usize, r as usize);
        entries.swap(l as usize, r as usize);
    }
    (k.saturating_sub(1), k)
}

/// Which vertices compare equal in all eight floats (neither has a `NaN`: those are
/// [`UNEQUAL`]): the same vertex, or equal hashes and equal attributes.
struct Equality<'a> {
    attributes: &'a Attributes<'a>,
    hashes: &'a [u32],
}

impl Equality<'_> {
    fn equal(&self, a: u32, b: u32) -> bool {
        let key = |v: u32| self.attributes.key(v).map(canonical_bits);
        a == b || (self.hashes[a as usize] == self.hashes[b as usize] && key(a) == key(b))
    }
}

/// The final step on a part whose widest extent is one value: each corner takes as representative
/// the first corner before it, in the part's order, equal to it in all eight floats.
fn weld_run(equality: &Equality, part: &mut [[u32; 3]]) {
    /// Up to this many corners (a vertex's few corners, the usual case) the C's own search is
    /// cheaper than sorting.
    const SEARCH_LIMIT: usize = 16;
    let first_vertex = part.iter().map(|e| e[1]).find(|&v| v != NONE);
    if part.iter().all(|e| e[1] == NONE || Some(e[1]) == first_vertex) {
        // One vertex's corners (and unequal ones, which stay alone): all equal the first.
        if let Some(first) = part.iter().find(|e| e[1] != NONE).map(|e| e[0]) {
            for entry in part.iter_mut().filter(|e| e[1] != NONE) {
                entry[2] = first;
            }
        }
        return;
    }
    // Each corner takes the first equal one before it among `run`, in place order.
    let take_first_equal = |run: &mut [[u32; 3]]| {
        for at in 1..run.len() {
            let vertex = run[at][1];
            if vertex == NONE {
                continue;
            }
            if let Some(first) = run[..at].iter().find(|e| e[1] != NONE && equality.equal(e[1], vertex)) {
                run[at][2] = first[0];
            }
        }
    };
    if part.len() <= SEARCH_LIMIT {
        take_first_equal(part);
        return;
    }
    // The part's order is not needed after this: sort it by hash, then by place, so that equal
    // corners lie in one run of a hash (usually alone there), first to last in place order.
    for (at, entry) in part.iter_mut().enumerate() {
        entry[2] = at as u32;
    }
    let hash = |e: &[u32; 3]| (e[1] != NONE).then(|| equality.hashes[e[1] as usize]);
    part.sort_unstable_by_key(|e| (e[1] == NONE, hash(e), e[2]));
    for entry in part.iter_mut() {
        entry[2] = entry[0];
    }
    // Unequal corners each make a run of their own.
    for run in part.chunk_by_mut(|a, b| a[1] != NONE && hash(a) == hash(b)) {
        take_first_equal(run);
    }
}

/// The axis mikktspace.c splits along: y if strictly widest, else z if wider than x, else x.
fn widest_axis(extent: Vec3) -> usize {
    if extent[1] > extent[0] && extent[1] > extent[2] {
        1
    } else if extent[2] > extent[0] {
        2
    } else {
        0
    }
}

/// `FindGridCell`: the cell of `value` along an axis spanning `min..max`, with the float-to-int
/// conversion of x86-64 (`cvttss2si`: `NaN` and out-of-range values become `INT_MIN`, cell 0).
fn grid_cell(min: f32, max: f32, value: f32) -> usize {
    let index = GRID_CELLS as f32 * ((value - min) / (max - min));
    if !(-2_147_483_648.0..2_147_483_648.0).contains(&index) {
        return 0;
    }
    let index = index as i32;
    if index >= GRID_CELLS as i32 {
        GRID_CELLS - 1
    } else if index < 0 {
        0
    } else {
        index as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_cells_stay_in_the_grid() {
        for (min, max, v) in [
            (0.0f32, 1.0, 1.0),
            (0.0, 1.0, 0.0),
            (0.0, 0.0, 0.0),
            (f32::NAN, 1.0, 0.5),
            (-1e30, 1e30, 1e30),
            (0.0, 1.0, 2.0),
            (0.0, 1.0, -2.0),
            (0.0, f32::INFINITY, 1.0),
            (0.0, 2.0, 2.0),
            (0.0, 2.0, 1.9999999),
        ] {
            let cell = grid_cell(min, max, v);
            assert!(cell < GRID_CELLS, "{min} {max} {v} -> {cell}");
        }
    }

    #[test]
    fn the_bounding_box_is_the_one_pass_box_on_any_thread_count() {
        // The C's loop, on one thread.
        let one_pass = |points: &[Vec3]| {
            let (mut min, mut max) = (points[0], points[0]);
            points[1..].iter().for_each(|&p| extend_box(&mut min, &mut max, p));
            (min, max)
        };
        let mut rng = crate::kernel::test_rng::TestRng(0x5EED);
        for case in 0..40 {
            // Few distinct values, so that ties (a -0 against a +0) and NaN meet every range.
            let all = [0.0f32, -0.0, 1.0, f32::NAN, -1.0, 2.5, -3.0, 0.5];
            // Half the cases with the extremes signed zeros (minimum) and 1 (maximum) only.
            let values = if case % 2 == 0 { &all[..4] } else { &all[..] };
            let points: Vec<Vec3> = (0..300)
                .map(|i| {
                    let pick = |rng: &mut crate::kernel::test_rng::TestRng| values[rng.below(values.len())];
                    let p = [pick(&mut rng), pick(&mut rng), pick(&mut rng)];
                    // Some cases start with a NaN, some have no NaN before the last range.
                    match (case % 4, i) {
                        (0, 0) => [f32::NAN, p[1], -0.0],
                        (1, _) if i < 200 => p.map(|x| if x.is_nan() { 0.0 } else { x }),
                        _ => p,
                    }
                })
                .collect();
            let corners: Vec<u32> = (0..points.len() as u32).rev().collect();
            let ordered: Vec<Vec3> = corners.iter().map(|&v| points[v as usize]).collect();
            let expected = one_pass(&ordered);
            let bits = |(min, max): (Vec3, Vec3)| (min.map(f32::to_bits), max.map(f32::to_bits));
            for threads in [1, 2, 8] {
                let seed = ordered[0];
                let found = bounding_box(threads, corners.len(), seed, &|c| points[corners[c] as usize]);
                assert_eq!(bits(found), bits(expected), "case {case}, threads={threads}");
            }
        }
    }

    #[test]
    fn a_run_welds_each_corner_to_the_first_equal_one() {
        // Vertices 0 and 1 are equal (+0 against -0), 2 differs, 3 is unequal (NONE in entries).
        let positions = [[0.0f32, 0.0, 0.0]; 4];
        let normals = [[0.0f32, 0.0, 1.0], [0.0, -0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]];
        let texcoords = [[0.5f32, 0.5], [0.5, 0.5], [0.25, 0.5], [0.5, f32::NAN]];
        let mesh = crate::Mesh::new(&positions[..], &normals[..]).with_texcoords(&texcoords[..]);
        let attributes = Attributes {
            mesh: &mesh,
            flip_v: false,
            corner_values: None,
            index_zero: None,
        };
        let hashes: Vec<u32> = (0..4)
            .map(|v| hash_of(&attributes.key(v).map(canonical_bits)))
            .collect();
        let equality = Equality {
            attributes: &attributes,
            hashes: &hashes,
        };
        let mut part = [
            [10, 1, 10],
            [11, NONE, 11],
            [12, 0, 12],
            [13, 2, 13],
            [14, 2, 14],
            [15, 1, 15],
        ];
        weld_run(&equality, &mut part);
        assert_eq!(part.map(|e| e[2]), [10, 11, 10, 13, 13, 10]);
        // One vertex's corners all take the first; the sorting path agrees with the search.
        let mut one = [[20, 2, 20], [21, NONE, 21], [22, 2, 22]];
        weld_run(&equality, &mut one);
        assert_eq!(one.map(|e| e[2]), [20, 21, 20]);
        let vertex_of = |c: u32| [1, NONE, 0, 2, 2][c as usize % 5];
        let mut long: Vec<[u32; 3]> = (0..40u32).rev().map(|c| [c, vertex_of(c), c]).collect();
        weld_run(&equality, &mut long);
        for &[c, vertex, first] in &long {
            let equal = |d: u32| match (vertex_of(d), vertex) {
                (NONE, _) | (_, NONE) => d == c,
                (a, b) => (a == 2) == (b == 2),
            };
            let expected = (0..40u32).rev().find(|&d| equal(d)).unwrap();
            assert_eq!(first, expected, "corner {c}");
        }
    }
}
