//! Groups and their tangents one welded vertex at a time (`BuildNeighborsFast`,
//! `Build4RuleGroups`, `GenerateTSpaces`), where no triangle takes its orientation from a group.
//!
//! Everything that decides a group keeps to its welded vertex `v`:
//! - the pairing of the edges at `v`: those between `v` and `w` all lie in triangles around `v`,
//!   and in triangle order the k-th running from `v` to `w` pairs with the k-th running from `w`
//!   to `v` ([`super::neighbors`]). The last run keeps that rule when [`super::last_run`] finds it
//!   trivial; else its edges, all between the welded vertex of index `i0` and those of larger
//!   index, pair as mikktspace.c's walk over them paired them ([`LastRun`]);
//! - the groups: the connected components of the corners at `v` joined by those pairs between
//!   triangles of one orientation ([`super::components`]);
//! - the tangent: the normalized sum of the group's terms in ascending triangle order where its
//!   directions lie in one half-space, else mikktspace.c's pairwise comparison
//!   ([`super::tspace`]).
//!
//! So the corners of each welded vertex, listed in triangle order, give its groups and their
//! tangents without any table over the whole mesh, and ranges of welded vertices can go to
//! separate threads.
#![forbid(unsafe_code)]

use super::components::{self, find, union, Settled};
use super::faces::ORIENT_PRESERVING;
use super::frames::Frames;
use super::tspace::{self, Directions, Inputs, Space, Written};
use crate::kernel::error::Error;
use crate::kernel::parallel;
use crate::kernel::simd;
use crate::kernel::vector::{normal, project_normalized, Vec3};

/// Up to this many corners at a welded vertex, the fan's arrays are on the stack and each edge
/// finds its partner by scanning the fan; past it, they are on the heap and the fan's edges are
/// sorted. Fuzzing builds (`cfg(fuzzing)`) lower it, so that the fuzzer's small meshes take both
/// ways.
pub(crate) const SCAN_LIMIT: usize = if cfg!(fuzzing) { 2 } else { 32 };

#[cfg(test)]
std::thread_local! {
    /// Set by tests to sort the edges of every fan, whatever its size, on this thread.
    pub(super) static SORT_ALWAYS: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
}

/// Whether a fan of `n` corners is scanned rather than sorted.
fn scanned(n: usize) -> bool {
    #[cfg(test)]
    if SORT_ALWAYS.with(core::cell::Cell::get) {
        return false;
    }
    n <= SCAN_LIMIT
}

/// Where the last run of the edge sort can matter: each welded vertex's index `values`, the last
/// run's `i0` (`last`), and the good triangle across each of its edges (`neighbors`, from
/// [`super::neighbors::pair_last_run`]).
pub(crate) struct LastRun<'a> {
    pub values: &'a [u32],
    pub last: u32,
    pub neighbors: &'a [[u32; 3]],
}

impl LastRun<'_> {
    /// Whether the edges between welded vertices `v` and `w` are the last run's: the smaller of
    /// their indices is its `i0`.
    #[inline(always)]
    fn holds(&self, v: u32, w: u32) -> bool {
        self.values[v as usize].min(self.values[w as usize]) == self.last
    }

    /// The place in the fan `corners` (ascending) of the corner at the same welded vertex of the
    /// triangle across the edge leaving `corner`, if the walk paired that edge.
    fn across(&self, corners: &[u32], corner: u32) -> Option<usize> {
        let other = self.neighbors[corner as usize / 3][corner as usize % 3];
        let place = corners.partition_point(|&c| c / 3 < other);
        (other != super::NONE && corners.get(place).is_some_and(|&c| c / 3 == other)).then_some(place)
    }
}

/// Every good corner (`3 g + k`) under its welded vertex, in corner order: welded vertex `v`'s
/// corners are `corners[starts[v]..starts[v + 1]]`.
struct Lists<'a> {
    starts: &'a [u32],
    corners: &'a [u32],
}

/// Fills `starts` (one more word than there are welded vertices) and `corners` (one word per good
/// corner) from the good triangles' welded vertices `ids`, a counting sort on `workers` ranges of
/// welded vertices: each worker reads every corner and keeps those of its range, so each list is
/// in corner order on any number of workers. The weld numbers welded vertices in order of first
/// use, so in `ids` they mostly rise and each worker's test of its range is predictable.
fn list<'a>(ids: &[[u32; 3]], workers: usize, starts: &'a mut [u32], corners: &'a mut [u32]) -> Lists<'a> {
    let welded_count = starts.len() - 1;
    let vertex_ranges = parallel::range_ends(welded_count, workers);
    let vertex_ends = vertex_ranges.ends();
    let firsts = || core::iter::once(0).chain(vertex_ends.iter().copied());
    // 1. Each welded vertex's corners counted into `starts[v + 1]`, summed within its range:
    //    `starts[v + 1]` becomes the corners of the range's vertices up to `v`.
    let mut totals = [0u32; parallel::MAX_RANGES];
    let counts = firsts().zip(parallel::split(&mut starts[1..], vertex_ends, 1));
    let mut range = 0;
    let count = |(first, counts): (usize, &mut [u32])| {
        counts.fill(0);
        for &id in ids.iter().flatten() {
            if let Some(count) = counts.get_mut((id as usize).wrapping_sub(first)) {
                *count += 1;
            }
        }
        let mut total = 0;
        for count in counts.iter_mut() {
            total += *count;
            *count = total;
        }
        total
    };
    parallel::run(counts, count, |total| {
        totals[range] = total;
        range += 1;
    });
    // 2. Each range's offset: the corners of the ranges before it.
    let mut offset = 0;
    let offsets = totals.map(|total| {
        offset += total;
        offset - total
    });
    let corner_ranges = parallel::Ranges::from_ends(
        offsets[1..vertex_ends.len()]
            .iter()
            .map(|&o| o as usize)
            .chain([offset as usize]),
    );
    // 3. Each vertex's list filled from its start, which then holds its end: the next one's start.
    let parts = firsts()
        .zip(parallel::split(&mut starts[..welded_count], vertex_ends, 1))
        .zip(parallel::split(corners, corner_ranges.ends(), 1))
        .zip(offsets);
    parallel::run(
        parts,
        |(((first, cursors), corners), offset)| {
            let Some(last) = cursors.len().checked_sub(1) else {
                return;
            };
            // Until now `cursors[i]` held the range's corners up to vertex `first + i - 1`.
            cursors[0] = 0;
            for (c, &id) in ids.iter().flatten().enumerate() {
                if let Some(cursor) = cursors.get_mut((id as usize).wrapping_sub(first)) {
                    corners[*cursor as usize] = c as u32;
                    *cursor += 1;
                }
            }
            cursors.copy_within(..last, 1);
            cursors[0] = 0;
            cursors.iter_mut().for_each(|cursor| *cursor += offset);
        },
        |()| {},
    );
    starts[welded_count] = offset;
    Lists { starts, corners }
}

/// Writes every good corner's tangent and orientation into `frames` (per corner of every
/// triangle), on the ranges of good triangles `ends`: each worker takes a range of welded vertices
/// with about as many corners as the others, writes the corners in its range of good triangles and
/// spills the others. `lists` is the memory for [`list`]. Everything it allocates, it allocates
/// before the first corner is written: nothing fails after that.
pub(crate) fn evaluate_on_ranges<F: Frames<Vec3>>(
    inputs: &Inputs,
    ids: &[[u32; 3]],
    last_run: Option<&LastRun>,
    ends: &[usize],
    (starts, corners): (&mut [u32], &mut [u32]),
    frames: &mut F,
) -> Result<Settled, Error> {
    let lists = list(ids, ends.len(), starts, corners);
    let welded_count = lists.starts.len() - 1;
    let corner_total = lists.starts[welded_count] as usize;
    let vertex_ranges = parallel::Ranges::from_ends(
        parallel::ends(corner_total, ends.len())
            .map(|end| lists.starts.partition_point(|&s| (s as usize) < end).min(welded_count)),
    );
    let vertex_ends = vertex_ranges.ends();
    let first_vertices = core::iter::once(0).chain(vertex_ends.iter().copied());
    // Each worker's heap arrays, for its largest fan past the scan limit, and room to spill
    // every corner of its fans.
    let mut fans: [Fan; parallel::MAX_RANGES] = [const { Fan::EMPTY }; parallel::MAX_RANGES];
    let mut room = [0; parallel::MAX_RANGES];
    for (((first, &end), fan), room) in first_vertices.clone().zip(vertex_ends).zip(&mut fans).zip(&mut room) {
        let starts = &lists.starts[first..=end];
        let largest = starts.windows(2).map(|w| (w[1] - w[0]) as usize).max().unwrap_or(0);
        if !scanned(largest) {
            fan.reserve(largest)?;
        }
        *room = (starts[starts.len() - 1] - starts[0]) as usize;
    }
    let mut counts = [Settled::default(); parallel::MAX_RANGES];
    let parts = first_vertices.zip(vertex_ends).zip(counts.iter_mut().zip(&mut fans));
    let triangles = super::triangle_ranges(ends, inputs.order, frames.corners() / 3);
    let cuts = (ends, triangles.ends());
    let frames = frames.split(triangles.ends());
    super::write_in_ranges(cuts, frames, &room, parts, |out, ((first, &end), (counts, fan))| {
        *counts = evaluate(inputs, (ids, last_run), &lists, first..end, fan, out)?;
        Ok(())
    })?;
    let mut settled = Settled::default();
    counts.into_iter().for_each(|counts| settled += counts);
    Ok(settled)
}

/// A fan's arrays, one element per corner: its two other welded vertices (the edge leaving the
/// vertex, the edge reaching it), its projected directions ([`Inputs::directions`]), its parent
/// in the union-find, its group's sum and whether the group's directions could part; the corners
/// set aside for the comparison, as (root, corner) by their places in the fan; a group's members.
struct Arrays<'a> {
    leaving: &'a mut [u32],
    reaching: &'a mut [u32],
    directions: &'a mut [[Vec3; 2]],
    parent: &'a mut [u32],
    sums: &'a mut [Vec3],
    may_part: &'a mut [bool],
    set_aside: &'a mut [u64],
    members: &'a mut [u32],
}

/// The arrays of a fan of up to [`SCAN_LIMIT`] corners, on the stack: the usual fan allocates
/// nothing.
struct Small {
    leaving: [u32; SCAN_LIMIT],
    reaching: [u32; SCAN_LIMIT],
    directions: [[Vec3; 2]; SCAN_LIMIT],
    parent: [u32; SCAN_LIMIT],
    sums: [Vec3; SCAN_LIMIT],
    may_part: [bool; SCAN_LIMIT],
    set_aside: [u64; SCAN_LIMIT],
    members: [u32; SCAN_LIMIT],
}

/// The arrays of larger fans, on the heap and kept from one to the next, with the fan's edges to
/// sort.
struct Fan {
    leaving: Vec<u32>,
    reaching: Vec<u32>,
    directions: Vec<[Vec3; 2]>,
    parent: Vec<u32>,
    sums: Vec<Vec3>,
    may_part: Vec<bool>,
    set_aside: Vec<u64>,
    members: Vec<u32>,
    edges: Vec<u64>,
}

/// Writes the tangent and orientation of every corner at the welded vertices `vertices` into
/// `out`; `fan` holds the arrays of fans past [`SCAN_LIMIT`] corners. Returns how many groups
/// there were, how many went to the pairwise comparison, and how many fans were large.
fn evaluate(
    inputs: &Inputs,
    (ids, last_run): (&[[u32; 3]], Option<&LastRun>),
    lists: &Lists,
    vertices: core::ops::Range<usize>,
    fan: &mut Fan,
    out: &mut Written<Vec3, impl Frames<Vec3>>,
) -> Result<Settled, Error> {
    let mut settled = Settled::default();
    let mut small = Small {
        leaving: [0; SCAN_LIMIT],
        reaching: [0; SCAN_LIMIT],
        directions: [[[0.0; 3]; 2]; SCAN_LIMIT],
        parent: [0; SCAN_LIMIT],
        sums: [[0.0; 3]; SCAN_LIMIT],
        may_part: [false; SCAN_LIMIT],
        set_aside: [0; SCAN_LIMIT],
        members: [0; SCAN_LIMIT],
    };
    for v in vertices {
        let corners = &lists.corners[lists.starts[v] as usize..lists.starts[v + 1] as usize];
        let n = corners.len();
        // Only fans with an index of at least the last run's `i0` hold any of its edges.
        let last_run = last_run.filter(|r| r.values[v] >= r.last).map(|r| (r, v as u32));
        let [groups, compared] = if scanned(n) {
            let arrays = Arrays {
                leaving: &mut small.leaving[..n],
                reaching: &mut small.reaching[..n],
                directions: &mut small.directions[..n],
                parent: &mut small.parent[..n],
                sums: &mut small.sums[..n],
                may_part: &mut small.may_part[..n],
                set_aside: &mut small.set_aside[..n],
                members: &mut small.members[..n],
            };
            evaluate_fan(inputs, (ids, last_run), corners, arrays, None, out)?
        } else {
            settled.large_fans += 1;
            fan.reserve(n)?;
            let arrays = Arrays {
                leaving: &mut fan.leaving[..n],
                reaching: &mut fan.reaching[..n],
                directions: &mut fan.directions[..n],
                parent: &mut fan.parent[..n],
                sums: &mut fan.sums[..n],
                may_part: &mut fan.may_part[..n],
                set_aside: &mut fan.set_aside[..n],
                members: &mut fan.members[..n],
            };
            evaluate_fan(inputs, (ids, last_run), corners, arrays, Some(&mut fan.edges), out)?
        };
        settled.components += groups;
        settled.compared += compared;
    }
    Ok(settled)
}

/// One welded vertex's `corners`, in ascending order; `edges` (room for two per corner) when
/// there are more than [`SCAN_LIMIT`]; with `last_run` the vertex, where it may hold the last
/// run's edges.
fn evaluate_fan(
    inputs: &Inputs,
    (ids, last_run): (&[[u32; 3]], Option<(&LastRun, u32)>),
    corners: &[u32],
    arrays: Arrays,
    edges: Option<&mut Vec<u64>>,
    out: &mut Written<Vec3, impl Frames<Vec3>>,
) -> Result<[usize; 2], Error> {
    let n = corners.len();
    let preserving = |i: usize| inputs.flags[corners[i] as usize / 3] & ORIENT_PRESERVING;
    let Arrays {
        leaving,
        reaching,
        directions,
        parent,
        sums,
        may_part,
        set_aside,
        members,
    } = arrays;
    for (i, &c) in corners.iter().enumerate() {
        let (g, k) = (c as usize / 3, c as usize % 3);
        leaving[i] = ids[g][(k + 1) % 3];
        reaching[i] = ids[g][(k + 2) % 3];
        parent[i] = i as u32;
    }
    // Compiled for the widest SIMD path.
    simd::run(
        #[inline(always)]
        || project(inputs, corners, directions),
    );

    // 1. Each pair of edges at the vertex joins its two corners when their triangles agree in
    //    orientation: the k-th edge leaving toward w with the k-th reaching from w, but in the
    //    last run, where an edge leaving toward w pairs with the edge the walk gave it.
    let join = |i: usize, j: usize, parent: &mut [u32]| {
        if preserving(i) == preserving(j) {
            union(parent, i, j);
        }
    };
    let in_last_run = |w: u32| last_run.is_some_and(|(r, v)| r.holds(v, w));
    let join_as_walked = |i: usize, parent: &mut [u32]| {
        if let Some(j) = last_run.and_then(|(r, _)| r.across(corners, corners[i])) {
            join(i, j, parent);
        }
    };
    match edges {
        None => {
            for i in 0..n {
                let w = leaving[i];
                if in_last_run(w) {
                    join_as_walked(i, parent);
                    continue;
                }
                let rank = leaving[..i].iter().filter(|&&x| x == w).count();
                if let Some(j) = (0..n).filter(|&j| reaching[j] == w).nth(rank) {
                    join(i, j, parent);
                }
            }
        }
        Some(edges) => {
            // (w, corner, leaving?) sorted: each w's edges in corner order.
            edges.clear();
            for i in 0..n {
                edges.push(u64::from(leaving[i]) << 32 | (i as u64) << 1 | 1);
                edges.push(u64::from(reaching[i]) << 32 | (i as u64) << 1);
            }
            edges.sort_unstable();
            for run in edges.chunk_by(|a, b| a >> 32 == b >> 32) {
                let corner = |e: u64| (e as u32 >> 1) as usize;
                let leaving = run.iter().filter(|&&e| e & 1 == 1);
                if in_last_run((run[0] >> 32) as u32) {
                    leaving.for_each(|&a| join_as_walked(corner(a), parent));
                    continue;
                }
                let reaching = run.iter().filter(|&&e| e & 1 == 0);
                for (&a, &b) in leaving.zip(reaching) {
                    join(corner(a), corner(b), parent);
                }
            }
        }
    }

    // 2. In ascending order, each corner's angle-weighted dP/ds added to its group's sum at the
    //    root (its first corner), and the half-space condition checked against the root's
    //    directions (EvalTspace).
    let mut groups = 0;
    for i in 0..n {
        let root = find(parent, i);
        if root == i {
            groups += 1;
            sums[i] = [0.0; 3];
            may_part[i] = components::may_part(directions[i], None);
        } else if components::may_part(directions[root], Some(directions[i])) {
            may_part[root] = true;
        }
        <Vec3 as Space>::add_with(&mut sums[root], inputs, corners[i] as usize, directions[i]);
    }

    // 3. Each corner's tangent: its group's sum normalized; where the directions could part,
    //    set aside as (root, corner), places in the fan.
    let mut aside = 0;
    for i in 0..n {
        let root = find(parent, i);
        if may_part[root] {
            set_aside[aside] = (root as u64) << 32 | i as u64;
            aside += 1;
            continue;
        }
        if root == i {
            sums[i] = Space::finish(sums[i]);
        }
        out.write(inputs.order, corners[i] as usize, sums[root], preserving(i) != 0)?;
    }

    // 4. mikktspace.c's comparison over each group set aside, members in ascending order.
    let set_aside = &mut set_aside[..aside];
    set_aside.sort_unstable();
    let mut compared = 0;
    for group in set_aside.chunk_by(|a, b| a >> 32 == b >> 32) {
        compared += 1;
        for (member, &e) in members.iter_mut().zip(group) {
            *member = corners[e as u32 as usize];
        }
        let root = (group[0] >> 32) as usize;
        tspace::evaluate_group(inputs, &members[..group.len()], preserving(root) != 0, out)?;
    }
    Ok([groups, compared])
}

/// Lanes of [`project`]: one AVX2 register.
const LANES: usize = 8;

/// Each corner's projected directions ([`Inputs::directions`]), [`LANES`] corners at a time in
/// loops that compile to SIMD under [`simd::run`]: the corners share the vertex's normal, and
/// every lane runs the same IEEE operations as the scalar projection, so the bits are the same.
#[inline(always)]
fn project(inputs: &Inputs, corners: &[u32], directions: &mut [[Vec3; 2]]) {
    let Directions::Projected {
        attributes,
        ids,
        derivatives,
    } = inputs.directions
    else {
        for (d, &c) in directions.iter_mut().zip(corners) {
            *d = inputs.directions(c as usize);
        }
        return;
    };
    let Some(&first) = corners.first() else {
        return;
    };
    let n = normal(&attributes[ids[first as usize / 3][first as usize % 3] as usize]);
    for (corners, directions) in corners.chunks(LANES).zip(directions.chunks_mut(LANES)) {
        // `[s or t][component][lane]`.
        let mut lanes = [[[0.0f32; LANES]; 3]; 2];
        for (i, &c) in corners.iter().enumerate() {
            for (lanes, derivatives) in lanes.iter_mut().zip(derivatives) {
                let d = derivatives[c as usize / 3];
                (lanes[0][i], lanes[1][i], lanes[2][i]) = (d[0], d[1], d[2]);
            }
        }
        for [xs, ys, zs] in &mut lanes {
            for ((x, y), z) in xs.iter_mut().zip(ys.iter_mut()).zip(zs.iter_mut()) {
                [*x, *y, *z] = project_normalized([*x, *y, *z], n);
            }
        }
        for (i, d) in directions.iter_mut().enumerate() {
            *d = lanes.map(|l| [l[0][i], l[1][i], l[2][i]]);
        }
    }
}

impl Fan {
    /// No room yet.
    const EMPTY: Fan = Fan {
        leaving: Vec::new(),
        reaching: Vec::new(),
        directions: Vec::new(),
        parent: Vec::new(),
        sums: Vec::new(),
        may_part: Vec::new(),
        set_aside: Vec::new(),
        members: Vec::new(),
        edges: Vec::new(),
    };

    /// Room for a fan of `n` corners.
    fn reserve(&mut self, n: usize) -> Result<(), Error> {
        fn grow<T: Clone + Default>(v: &mut Vec<T>, n: usize) -> Result<(), Error> {
            if v.len() < n {
                v.try_reserve(n - v.len()).map_err(|_| Error::OutOfMemory)?;
                v.resize(n, T::default());
            }
            Ok(())
        }
        grow(&mut self.leaving, n)?;
        grow(&mut self.reaching, n)?;
        grow(&mut self.directions, n)?;
        grow(&mut self.parent, n)?;
        grow(&mut self.sums, n)?;
        grow(&mut self.may_part, n)?;
        grow(&mut self.set_aside, n)?;
        grow(&mut self.members, n)?;
        // Emptied first, so that room reserved once for the largest fan serves every later one.
        self.edges.clear();
        self.edges.try_reserve(2 * n).map_err(|_| Error::OutOfMemory)
    }
}
