//! Welding corners: mikktspace.c treats corners whose position, normal and texture coordinate
//! compare equal with `==` as one vertex (`GenerateSharedVerticesIndexList`).
//!
//! mikktspace.c finds equal corners by sorting them into a grid along the widest axis of their
//! bounding box and splitting each cell at the midpoint of its widest extent until a part holds one
//! value (`MergeVertsFast`); each corner then takes the index of the first equal corner in the order
//! that splitting leaves. That order is visible downstream: the representative's bits are read
//! (a `-0.0` against a `+0.0`), a cell whose midpoint is not finite is left unwelded, and the
//! representative's index decides which edges end mikktspace.c's edge sort (see `neighbors`). So
//! the splitting is replayed step by step, its recursion on a stack and its final quadratic
//! search replaced by a sort.
#![forbid(unsafe_code)]

use super::attributes::Attributes;
use super::vector::Vec3;
use super::NONE;

/// mikktspace.c's grid: cells along the widest axis of the bounding box.
const GRID_CELLS: usize = 2048;

/// Replaces the vertex of every corner in `corners` (indices already checked) by the number of its
/// welded vertex, numbered in order of first use; writes, per welded vertex, the vertex it reads its
/// attributes from to `source` and mikktspace.c's index for it (`4 * face + corner` of the corner
/// that represents it) to `values`. Returns the number of welded vertices.
pub(crate) fn weld(attributes: &Attributes, corners: &mut [u32], source: &mut [u32], values: &mut [u32]) -> usize {
    weld_exactly(attributes, corners, source, values)
}

/// The bits of `x`, with -0 as +0 so that values equal under `==` have equal bits.
#[inline(always)]
fn canonical_bits(x: f32) -> u32 {
    if x == 0.0 {
        0
    } else {
        x.to_bits()
    }
}

/// A corner in a grid cell, as `STmpVert`: its position and its number.
#[derive(Clone, Copy)]
struct CellEntry {
    position: Vec3,
    corner: u32,
}

/// mikktspace.c's weld replayed step by step: the grid along the bounding box's widest axis,
/// each cell split at midpoints until a part's widest extent is one value, then each corner of
/// such a part welded to the first equal corner before it. Allocates its own memory (it runs only
/// for the inputs the module comment names). Returns the number of welded vertices.
fn weld_exactly(attributes: &Attributes, corners: &mut [u32], source: &mut [u32], values: &mut [u32]) -> usize {
    let corner_count = corners.len();
    let position = |c: usize| attributes.position(corners[c]);
    let mut representative: Vec<u32> = (0..corner_count as u32).collect();

    // The bounding box, with the C's `if ... else if` updates (a NaN never moves it).
    let mut min = position(0);
    let mut max = min;
    for c in 1..corner_count {
        let p = position(c);
        for axis in 0..3 {
            if min[axis] > p[axis] {
                min[axis] = p[axis];
            } else if max[axis] < p[axis] {
                max[axis] = p[axis];
            }
        }
    }
    let axis = widest_axis([max[0] - min[0], max[1] - min[1], max[2] - min[2]]);

    // Corners by grid cell, in corner order within a cell.
    let cells: Vec<usize> = (0..corner_count)
        .map(|c| grid_cell(min[axis], max[axis], position(c)[axis]))
        .collect();
    let mut starts = vec![0usize; GRID_CELLS + 1];
    for &cell in &cells {
        starts[cell + 1] += 1;
    }
    for k in 0..GRID_CELLS {
        starts[k + 1] += starts[k];
    }
    let mut filled = starts.clone();
    let mut by_cell = vec![0u32; corner_count];
    for (c, &cell) in cells.iter().enumerate() {
        by_cell[filled[cell]] = c as u32;
        filled[cell] += 1;
    }

    let mut entries = Vec::new();
    for k in 0..GRID_CELLS {
        let members = &by_cell[starts[k]..starts[k + 1]];
        if members.len() < 2 {
            continue;
        }
        entries.clear();
        entries.extend(members.iter().map(|&c| CellEntry {
            position: position(c as usize),
            corner: c,
        }));
        split_and_weld(attributes, corners, &mut entries, &mut representative);
    }

    // Number the welded vertices in order of first use.
    let mut number = vec![NONE; corner_count];
    let mut count = 0u32;
    for &first in representative.iter() {
        let first = first as usize;
        if number[first] == NONE {
            number[first] = count;
            source[count as usize] = corners[first];
            values[count as usize] = (4 * (first / 3) + first % 3) as u32;
            count += 1;
        }
    }
    for c in 0..corner_count {
        corners[c] = number[representative[c] as usize];
    }
    count as usize
}

/// `MergeVertsFast` on one grid cell, its recursion on a stack (a cell can split hundreds deep).
fn split_and_weld(attributes: &Attributes, corners: &[u32], entries: &mut [CellEntry], representative: &mut [u32]) {
    let mut parts = vec![(0usize, entries.len() - 1)];
    while let Some((left, right)) = parts.pop() {
        let part = &mut entries[left..=right];
        let mut min = part[0].position;
        let mut max = min;
        for entry in &part[1..] {
            for axis in 0..3 {
                if min[axis] > entry.position[axis] {
                    min[axis] = entry.position[axis];
                }
                if max[axis] < entry.position[axis] {
                    max[axis] = entry.position[axis];
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
            weld_run(attributes, corners, part, representative);
            continue;
        }
        let (below_end, above_start) = partition(part, axis, separator);
        if below_end > 0 {
            parts.push((left, left + below_end));
        }
        if above_start < part.len() - 1 {
            parts.push((left + above_start, right));
        }
    }
}

/// The C's two-sided partition of `part` around `separator` on `axis`, swap for swap. Returns the
/// last position of the lower part (0 when it holds one entry or none, which need no welding) and
/// the first position of the upper part.
fn partition(part: &mut [CellEntry], axis: usize, separator: f32) -> (usize, usize) {
    let below = |e: &CellEntry| e.position[axis] < separator;
    let (mut l, mut r) = (0isize, part.len() as isize - 1);
    while l < r {
        let (mut ready_left, mut ready_right) = (false, false);
        while !ready_left && l < r {
            ready_left = !below(&part[l as usize]);
            if !ready_left {
                l += 1;
            }
        }
        while !ready_right && l < r {
            ready_right = below(&part[r as usize]);
            if !ready_right {
                r -= 1;
            }
        }
        if ready_left && ready_right {
            part.swap(l as usize, r as usize);
            l += 1;
            r -= 1;
        }
    }
    if l == r {
        if below(&part[r as usize]) {
            l += 1;
        } else {
            r -= 1;
        }
    }
    (r.max(0) as usize, l as usize)
}

/// The final step on a part whose widest extent is one value: each corner takes the welded vertex
/// of the first corner before it, in the part's order, that equals it in all eight floats. Sorting
/// by (canonical key, position) finds those first corners without the C's quadratic search.
fn weld_run(attributes: &Attributes, corners: &[u32], part: &[CellEntry], representative: &mut [u32]) {
    /// Up to this many corners (a vertex's few corners, the usual case) the C's own search is
    /// cheaper than sorting.
    const SEARCH_LIMIT: usize = 16;
    let key = |entry: &CellEntry| {
        let key = attributes.key(corners[entry.corner as usize]);
        (!key.iter().any(|x| x.is_nan())).then(|| key.map(canonical_bits))
    };
    if part.len() <= SEARCH_LIMIT {
        let mut keys = [None; SEARCH_LIMIT];
        for (at, entry) in part.iter().enumerate() {
            keys[at] = key(entry);
            if keys[at].is_some() {
                if let Some(first) = (0..at).find(|&before| keys[before] == keys[at]) {
                    representative[entry.corner as usize] = part[first].corner;
                }
            }
        }
        return;
    }
    let mut order: Vec<(usize, [u32; 8])> = part
        .iter()
        .enumerate()
        .filter_map(|(at, entry)| key(entry).map(|key| (at, key)))
        .collect();
    order.sort_unstable_by(|a, b| a.1.cmp(&b.1).then(a.0.cmp(&b.0)));
    for run in order.chunk_by(|a, b| a.1 == b.1) {
        let first = part[run[0].0].corner;
        for &(at, _) in &run[1..] {
            representative[part[at].corner as usize] = first;
        }
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
}
