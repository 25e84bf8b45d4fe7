//! What the reference, mikktspace.c, would spend on a mesh in its three steps that are quadratic in
//! the worst case, so that the harness can leave it out where one input would run for seconds
//! (mikktspace.c is only the oracle; the library's port takes linear routes for all three but
//! where it must replay the C's weld within a run of equal hashes, or compare a group's corners
//! pairwise in `GenerateTSpaces`: docs/mikktspace-fast-path.md):
//!
//! - the weld (`GenerateSharedVerticesIndexList`): corners are hashed into 2048 cells along the
//!   widest axis of their positions, then each cell is split at the midpoint of its widest axis
//!   until a group cannot be split (`MergeVertsFast`); within such a group each corner is compared
//!   with every earlier one that differs from it (position, normal or texture coordinate): up to
//!   `n^2 / 2` comparisons of three callbacks each for a group of `n`;
//! - `GenerateTSpaces`: each group of faces around a welded vertex compares every face with every
//!   face, `k^2` for `k` faces; the corners welded into one vertex lie in one weld group, so this
//!   is at most the weld's `n^2`;
//! - `DegenEpilogue`: each corner of a degenerate triangle (two positions equal) searches the
//!   corners of the good triangles, `3 * 3` per pair of triangles.
//!
//! The groups come from a literal port of the partition (the same f32 operations, the same
//! swaps), which takes `n log n`.

/// mikktspace.c's `g_iCells`.
const CELLS: usize = 2048;

/// Pair comparisons (of a few callbacks each) mikktspace.c makes at most on a mesh whose corner
/// `c`, in triangle order, sits at `positions[c]`.
pub fn reference_cost(positions: &[[f32; 3]]) -> u64 {
    let mut cost = 0u64;
    for n in weld_groups(positions) {
        let n = n as u64;
        // The weld and GenerateTSpaces.
        cost = cost.saturating_add(2 * n * n);
    }
    let triangles = positions.len() / 3;
    let same = |a: [f32; 3], b: [f32; 3]| a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    let degenerate = positions
        .chunks_exact(3)
        .filter(|t| same(t[0], t[1]) || same(t[0], t[2]) || same(t[1], t[2]))
        .count() as u64;
    cost.saturating_add(9 * degenerate * (triangles as u64 - degenerate))
}

/// The sizes of the groups `MergeVertsFast` welds by comparing all pairs.
fn weld_groups(positions: &[[f32; 3]]) -> Vec<usize> {
    let mut groups = Vec::new();
    let Some(&first) = positions.first() else {
        return groups;
    };
    // The bounding box, with mikktspace.c's `else if`, from corner 0.
    let (mut min, mut max) = (first, first);
    for p in &positions[1..] {
        for c in 0..3 {
            if min[c] > p[c] {
                min[c] = p[c];
            } else if max[c] < p[c] {
                max[c] = p[c];
            }
        }
    }
    let channel = widest(min, max);
    let (low, high) = (min[channel], max[channel]);
    let mut cells: Vec<Vec<[f32; 3]>> = vec![Vec::new(); CELLS];
    for p in positions {
        // `FindGridCell`: C's `(int)` of NaN is INT_MIN, clamped to cell 0 as Rust's 0 is.
        let index = CELLS as f32 * ((p[channel] - low) / (high - low));
        let cell = (index as i32).clamp(0, CELLS as i32 - 1) as usize;
        cells[cell].push(*p);
    }
    for mut cell in cells.into_iter().filter(|cell| cell.len() >= 2) {
        let last = cell.len() - 1;
        merge_verts_fast(&mut cell, 0, last, &mut groups);
    }
    groups
}

/// mikktspace.c's choice of axis: y when strictly widest, else z when wider than x, else x.
fn widest(min: [f32; 3], max: [f32; 3]) -> usize {
    let d = [max[0] - min[0], max[1] - min[1], max[2] - min[2]];
    if d[1] > d[0] && d[1] > d[2] {
        1
    } else if d[2] > d[0] {
        2
    } else {
        0
    }
}

/// `MergeVertsFast` without the weld itself: splits `v[left..=right]` as mikktspace.c does (with a
/// stack for its recursion) and records the size of each group it would weld.
fn merge_verts_fast(v: &mut [[f32; 3]], left: usize, right: usize, groups: &mut Vec<usize>) {
    let mut pending = vec![(left, right)];
    while let Some((l_in, r_in)) = pending.pop() {
        let (mut min, mut max) = (v[l_in], v[l_in]);
        for p in &v[l_in + 1..=r_in] {
            for c in 0..3 {
                if min[c] > p[c] {
                    min[c] = p[c];
                }
                if max[c] < p[c] {
                    max[c] = p[c];
                }
            }
        }
        let channel = widest(min, max);
        let sep = 0.5f32 * (max[channel] + min[channel]);
        // All NaN (or an infinite bound): nothing is welded.
        if !sep.is_finite() {
            continue;
        }
        if sep >= max[channel] || sep <= min[channel] {
            groups.push(r_in - l_in + 1);
            continue;
        }
        let (mut l, mut r) = (l_in as isize, r_in as isize);
        let at = |v: &[[f32; 3]], i: isize| v[i as usize][channel];
        while l < r {
            let (mut left_ready, mut right_ready) = (false, false);
            while !left_ready && l < r {
                // Not `>=`: a NaN is ready on the left, as in C.
                #[allow(clippy::neg_cmp_op_on_partial_ord)]
                {
                    left_ready = !(at(v, l) < sep);
                }
                if !left_ready {
                    l += 1;
                }
            }
            while !right_ready && l < r {
                right_ready = at(v, r) < sep;
                if !right_ready {
                    r -= 1;
                }
            }
            if left_ready && right_ready {
                v.swap(l as usize, r as usize);
                l += 1;
                r -= 1;
            }
        }
        if l == r {
            if at(v, r) < sep {
                l += 1;
            } else {
                r -= 1;
            }
        }
        if (l_in as isize) < r {
            pending.push((l_in, r as usize));
        }
        if l < r_in as isize {
            pending.push((l as usize, r_in));
        }
    }
}
