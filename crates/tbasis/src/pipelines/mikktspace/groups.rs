//! Groups of triangles around a welded vertex that share one tangent-space orientation
//! (`Build4RuleGroups` and `AssignRecur`).
//!
//! A group starts at each corner, in triangle order, of a usable triangle that is in no group yet,
//! and spreads across edges to the triangles around the same welded vertex, depth first (left
//! neighbour, then right), as long as their UV orientation matches. A triangle with no usable
//! derivative (`GROUP_WITH_ANY`) takes the orientation of the first group that reaches it: the
//! order of the search is part of the result, so the recursion is replayed exactly, on a stack.
#![forbid(unsafe_code)]

use super::faces::{GROUP_WITH_ANY, ORIENT_PRESERVING};
use super::NONE;

/// The groups: group `i` is the corners `corners[starts[i]..starts[i + 1]]` (corner `k` of good
/// triangle `g` as `3 g + k`), at one welded vertex and one per triangle, with orientation
/// `orientation[i]` (1: preserving).
pub(crate) struct Groups<'a> {
    pub starts: &'a mut [u32],
    pub corners: &'a mut [u32],
    pub orientation: &'a mut [u8],
}

/// Words of search stack for `triangles` good triangles: a group takes at most one corner of each
/// (the first of the triangle's corners at the group's welded vertex), and only a corner taken
/// pushes, its two neighbours.
pub(crate) fn stack_words(triangles: usize) -> usize {
    2 * triangles + 2
}

/// Builds the groups at the welded vertices `at` selects (a group keeps to one welded vertex, so
/// those at the others are left out without changing these) and writes `assigned[g][k]`, the
/// group of corner `k` of good triangle `g` ([`NONE`] when it has none). `stack` needs
/// [`stack_words`] of `ids.len()`. With `write_order`, also writes there each grouped corner's
/// place in `groups.corners` as built: the order in which `GenerateTSpaces` writes the corners,
/// group after group, each in `AssignRecur`'s order. Returns the group count.
pub(crate) fn build(
    ids: &[[u32; 3]],
    neighbors: &[[u32; 3]],
    flags: &mut [u8],
    assigned: &mut [[u32; 3]],
    (groups, stack): (&mut Groups, &mut [u32]),
    at: impl Fn(u32) -> bool,
    mut write_order: Option<&mut [u32]>,
) -> usize {
    assigned.fill([NONE; 3]);
    let mut count = 0usize;
    let mut filled = 0usize;
    for f in 0..ids.len() {
        for i in 0..3 {
            if flags[f] & GROUP_WITH_ANY != 0 || assigned[f][i] != NONE || !at(ids[f][i]) {
                continue;
            }
            let group = count as u32;
            let vertex = ids[f][i];
            let preserving = flags[f] & ORIENT_PRESERVING;
            groups.starts[count] = filled as u32;
            groups.orientation[count] = preserving;
            count += 1;
            assigned[f][i] = group;
            groups.corners[filled] = (3 * f + i) as u32;
            if let Some(order) = write_order.as_deref_mut() {
                order[3 * f + i] = filled as u32;
            }
            filled += 1;

            // AssignRecur on the left neighbour, then the right: pushed right first.
            let mut top = 0;
            for neighbour in [neighbors[f][(i + 2) % 3], neighbors[f][i]] {
                if neighbour != NONE {
                    stack[top] = neighbour;
                    top += 1;
                }
            }
            while top > 0 {
                top -= 1;
                let t = stack[top] as usize;
                let Some(k) = ids[t].iter().position(|&id| id == vertex) else {
                    continue;
                };
                if assigned[t][k] != NONE {
                    continue;
                }
                if flags[t] & GROUP_WITH_ANY != 0 && assigned[t] == [NONE; 3] {
                    // The first group to reach it decides its orientation.
                    flags[t] = (flags[t] & !ORIENT_PRESERVING) | preserving;
                }
                if flags[t] & ORIENT_PRESERVING != preserving {
                    continue;
                }
                groups.corners[filled] = (3 * t + k) as u32;
                if let Some(order) = write_order.as_deref_mut() {
                    order[3 * t + k] = filled as u32;
                }
                filled += 1;
                assigned[t][k] = group;
                for neighbour in [neighbors[t][(k + 2) % 3], neighbors[t][k]] {
                    if neighbour != NONE {
                        stack[top] = neighbour;
                        top += 1;
                    }
                }
            }
        }
    }
    groups.starts[count] = filled as u32;
    count
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed fan of `n` triangles around welded vertex 0, all of one orientation: one group of
    /// every triangle at the centre, found with no more stack than [`stack_words`].
    #[test]
    fn a_whole_fan_is_one_group_within_the_stack() {
        for n in [3usize, 4, 64, 1001] {
            let ring = |t: usize| 1 + (t % n) as u32;
            let ids: Vec<[u32; 3]> = (0..n).map(|t| [0, ring(t), ring(t + 1)]).collect();
            // Across edge k (corner k to corner k + 1): the previous triangle, none, the next.
            let neighbors: Vec<[u32; 3]> = (0..n)
                .map(|t| [((t + n - 1) % n) as u32, NONE, ((t + 1) % n) as u32])
                .collect();
            let mut flags = vec![ORIENT_PRESERVING; n];
            let mut assigned = vec![[NONE; 3]; n];
            let (mut starts, mut corners, mut orientation) = (vec![0; 3 * n + 1], vec![0; 3 * n], vec![0; 3 * n]);
            let mut groups = Groups {
                starts: &mut starts,
                corners: &mut corners,
                orientation: &mut orientation,
            };
            let mut stack = vec![0; stack_words(n)];
            let count = build(
                &ids,
                &neighbors,
                &mut flags,
                &mut assigned,
                (&mut groups, &mut stack),
                |_| true,
                None,
            );
            // The centre's group, then each ring vertex's two corners, in one group each.
            assert_eq!(count, 1 + n, "{n} triangles");
            let mut centre: Vec<u32> = corners[..n].to_vec();
            centre.sort_unstable();
            assert_eq!(centre, (0..n as u32).map(|t| 3 * t).collect::<Vec<_>>());
            assert!(assigned.iter().all(|corners| corners[0] == 0));
        }
    }
}
