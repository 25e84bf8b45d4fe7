//! Groups and their tangents in two passes over the corners, wherever no triangle takes its
//! orientation from a group (`Build4RuleGroups`, `GenerateTSpaces`).
//!
//! A group keeps to one welded vertex. At a vertex with no `GROUP_WITH_ANY` triangle, each
//! triangle keeps its own orientation, so `AssignRecur`'s search from a corner reaches exactly the
//! corners joined to it, at the same welded vertex, by paired edges between triangles of one
//! orientation: its connected component. No earlier group takes one of them (it would have taken
//! the whole component), so the groups are the components, whatever order the search visits them
//! in. Union-find finds them, each rooted at its first corner. One pass in corner order then adds
//! each corner's term to its root, which is the sum over the group's members in ascending
//! triangle order that `EvalTspace` forms, and checks the half-space condition of
//! [`super::tspace`] against the root's own directions; a second pass normalizes each root's sum
//! and copies it to the members. The few groups whose directions could part into sub-groups are
//! evaluated as [`super::tspace::evaluate_group`] evaluates any group, and so are the groups the
//! search found at the vertices of `GROUP_WITH_ANY` triangles, where the order of the search
//! decides orientations.
#![forbid(unsafe_code)]

use super::faces::ORIENT_PRESERVING;
use super::frames::Arrays;
use super::groups::Groups;
use super::tspace::{self, Inputs, Space, Spilled, Written};
use super::NONE;
use crate::kernel::error::Error;
use crate::kernel::vector::{dot, Vec3};

/// In a root's `orientation` until the second pass: its group's directions could part.
const MAY_PART: u8 = 2;

/// In `parent`: a corner at a welded vertex the search handles.
const SEARCHED: u32 = NONE;

/// How many groups each way settled: as components, of which the pairwise comparison took some,
/// and by the search; and how many fans were too large for the stack ([`super::fans`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Settled {
    pub components: usize,
    pub compared: usize,
    pub searched: usize,
    pub large_fans: usize,
}

impl core::ops::AddAssign for Settled {
    fn add_assign(&mut self, other: Settled) {
        self.components += other.components;
        self.compared += other.compared;
        self.searched += other.searched;
        self.large_fans += other.large_fans;
    }
}

/// How the good triangles meet.
pub(crate) struct Adjacency<'a> {
    /// Each good triangle's welded vertices.
    pub ids: &'a [[u32; 3]],
    /// The good triangle across each edge ([`super::neighbors`]).
    pub neighbors: &'a [[u32; 3]],
    /// Where there are `GROUP_WITH_ANY` triangles: not 0 at their welded vertices.
    pub near: Option<&'a [u32]>,
}

/// Writes the tangent and orientation of every corner of the good triangles, at the default
/// threshold: the groups at `near` vertices are the `searched` ones in `groups`
/// ([`super::groups::build`]), the others are found here. `parent` has one
/// word per corner of a good triangle; `spaces` and `orientation` are per corner of every
/// triangle, good triangle `g` being triangle `order[g]`.
pub(crate) fn evaluate(
    inputs: &Inputs,
    adjacency: Adjacency,
    parent: &mut [u32],
    (spaces, orientation): (&mut [Vec3], &mut [u8]),
    (groups, searched): (&mut Groups, usize),
) -> Result<Settled, Error> {
    let Adjacency { ids, neighbors, near } = adjacency;
    let slot = |c: usize| 3 * inputs.order[c / 3] as usize + c % 3;
    let preserving = |c: usize| inputs.flags[c / 3] & ORIENT_PRESERVING;

    // 1. The components: corners at one welded vertex joined across a paired edge of two
    //    triangles of one orientation; every root is its component's first corner.
    for (c, p) in parent.iter_mut().enumerate() {
        let searched = near.is_some_and(|near| near[ids[c / 3][c % 3] as usize] != 0);
        *p = if searched { SEARCHED } else { c as u32 };
    }
    for (g, (corners, across)) in ids.iter().zip(neighbors).enumerate() {
        for (k, &u) in across.iter().enumerate() {
            let u = u as usize;
            if u == NONE as usize || u <= g || preserving(3 * g) != preserving(3 * u) {
                continue;
            }
            for end in [k, (k + 1) % 3] {
                let Some(j) = ids[u].iter().position(|&id| id == corners[end]) else {
                    continue;
                };
                if parent[3 * g + end] != SEARCHED {
                    union(parent, 3 * g + end, 3 * u + j);
                }
            }
        }
    }

    // 2. In corner order: each corner's root (an earlier corner, already resolved), and its
    //    angle-weighted dP/ds added to the root's sum (EvalTspace), in ascending triangle order.
    let mut components = 0;
    for c in 0..parent.len() {
        let p = parent[c] as usize;
        if p == SEARCHED as usize {
            continue;
        }
        let root = if p == c { c } else { parent[p] as usize };
        parent[c] = root as u32;
        let directions = inputs.directions(c);
        if root == c {
            components += 1;
            spaces[slot(c)] = [0.0; 3];
            orientation[slot(c)] = if may_part(directions, None) { MAY_PART } else { 0 };
        } else if may_part(inputs.directions(root), Some(directions)) {
            orientation[slot(root)] = MAY_PART;
        }
        <Vec3 as Space>::add_with(&mut spaces[slot(root)], inputs, c, directions);
    }

    // 3. Each root's sum normalized, then copied to its members; those of a group whose
    //    directions could part are set aside.
    let mut set_aside = Vec::new();
    for c in 0..parent.len() {
        let root = parent[c] as usize;
        if root == SEARCHED as usize {
            continue;
        }
        if orientation[slot(root)] & MAY_PART != 0 {
            set_aside.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
            set_aside.push([root as u32, c as u32]);
            continue;
        }
        if root == c {
            spaces[slot(c)] = Space::finish(spaces[slot(c)]);
        }
        spaces[slot(c)] = spaces[slot(root)];
        orientation[slot(c)] = preserving(c);
    }

    // 4. The groups set aside and the searched ones, each as mikktspace.c evaluates a group:
    //    members in ascending order.
    //    Unstable, so in place (a stable sort allocates, and that allocation cannot fail softly);
    //    the same order, since the pairs differ and each root's corners were pushed in order.
    set_aside.sort_unstable();
    let mut spilled: Vec<Spilled<Vec3>> = Vec::new();
    let mut out = Written {
        frames: Arrays { spaces, orientation },
        goods: 0..ids.len() as u32,
        first_triangle: 0,
        spilled: &mut spilled,
    };
    let mut members = Vec::new();
    let mut compared = 0;
    for group in set_aside.chunk_by(|a, b| a[0] == b[0]) {
        members.clear();
        members.try_reserve(group.len()).map_err(|_| Error::OutOfMemory)?;
        members.extend(group.iter().map(|&[_, c]| c));
        let preserving = preserving(group[0][0] as usize) != 0;
        tspace::evaluate_group(inputs, &members, preserving, &mut out)?;
        compared += 1;
    }
    for group in 0..searched {
        let members = &mut groups.corners[groups.starts[group] as usize..groups.starts[group + 1] as usize];
        members.sort_unstable();
        tspace::evaluate_group(inputs, members, groups.orientation[group] != 0, &mut out)?;
    }
    Ok(Settled {
        components,
        compared,
        searched,
        large_fans: 0,
    })
}

/// Whether a corner could make its group part into sub-groups, from the projected directions
/// ([`Inputs::directions`]) of its group's root and, for a corner other than the root, its own:
/// the root's must be unit, to serve as the axes of [`within_half_space`], and every member's
/// must lie within it.
#[inline(always)]
pub(super) fn may_part([root_s, root_t]: [Vec3; 2], member: Option<[Vec3; 2]>) -> bool {
    let unit = |d: Vec3| d.iter().all(|x| x.is_finite()) && (dot(d, d) - 1.0).abs() <= 1e-4;
    match member {
        None => !unit(root_s) || !unit(root_t),
        Some([s, t]) => !within_half_space(root_s, s) || !within_half_space(root_t, t),
    }
}

/// Whether direction `d` keeps the half-space condition of [`super::tspace`] against the unit
/// direction `axis`: finite, and either short (squared length at most 1/4) or unit within 1e-4
/// and more than 0.01 along `axis`.
#[inline(always)]
fn within_half_space(axis: Vec3, d: Vec3) -> bool {
    let squared = dot(d, d);
    d.iter().all(|x| x.is_finite()) && (squared <= 0.25 || ((squared - 1.0).abs() <= 1e-4 && dot(axis, d) > 0.01))
}

/// Joins the components of `a` and `b`, the larger root under the smaller.
#[inline(always)]
pub(super) fn union(parent: &mut [u32], a: usize, b: usize) {
    let (a, b) = (find(parent, a), find(parent, b));
    if a != b {
        parent[a.max(b)] = a.min(b) as u32;
    }
}

/// The root of `x`'s component, halving the path on the way (every parent stays below its
/// child).
#[inline(always)]
pub(super) fn find(parent: &mut [u32], mut x: usize) -> usize {
    while parent[x] as usize != x {
        let grandparent = parent[parent[x] as usize];
        parent[x] = grandparent;
        x = grandparent as usize;
    }
    x
}
