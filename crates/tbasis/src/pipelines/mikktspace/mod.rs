//! Method MIKKTSPACE: mikktspace.c's `genTangSpaceDefault`, float for float.
//!
//! The result is what mikktspace.c hands to `setTSpaceBasic` for corner `k` of face `t` when its
//! callbacks read the mesh's positions, normals and texture coordinates through the index buffer.
//! Every step below names the C function it reproduces; each keeps the C's operations and their
//! order wherever they decide bits, and replaces a search that is quadratic in the C (welding,
//! edge pairing, sub-groups, the degenerate epilogue) by one that finds the same answer in linear
//! time, but where the C's own cost remains (`docs/mikktspace-fast-path.md`: a pairwise sub-group
//! comparison, a leaf of equal hashes, the replayed order of the edge sort's last run).
#![forbid(unsafe_code)]

mod attributes;
mod components;
mod corner_terms;
mod faces;
pub(crate) mod faces_interface;
mod fans;
mod frames;
mod groups;
mod last_run;
mod neighbors;
#[cfg(test)]
mod path_tests;
mod repair;
mod tspace;
mod value_weld;
mod weld;
#[cfg(test)]
mod weld_tests;

use core::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3 as GlamVec3;

use self::attributes::Attributes;
use self::corner_terms::CornerTerms;
use self::faces::GROUP_WITH_ANY;
use self::frames::{Arrays, Frames};
use self::groups::Groups;
use self::neighbors::EdgeScratch;
use self::tspace::Directions;
use self::tspace::Inputs;
use self::weld::{Wanted, WeldScratch};
use crate::kernel::error::Error;
use crate::kernel::memory::{bytes_of, Arena};
use crate::kernel::mesh::{Mesh, Output, Target};
use crate::kernel::options::{DegeneratePolicy, Options};
use crate::kernel::report::Report;
use crate::kernel::vector::{Packed, Vec3};
use crate::kernel::views::pod::triples;
use crate::kernel::views::strided::StridedMut;
use crate::kernel::{frame, parallel};

/// "No index": no neighbour, no group, no corner yet.
pub(crate) const NONE: u32 = u32::MAX;

/// The routes a call took (the tests count which meshes take each).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Routes {
    pub weld: WeldPath,
    pub groups: GroupRoute,
}

/// How a call found mikktspace.c's groups and their tangents.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum GroupRoute {
    /// One welded vertex at a time ([`fans`]).
    Fans(components::Settled),
    /// As components over the whole mesh, by the search near `GROUP_WITH_ANY` triangles
    /// ([`components`]).
    Components(components::Settled),
    /// By the search everywhere: mikktspace.c's own interface, or no corner at all.
    Search,
}

/// How a call reproduced mikktspace.c's weld (the tests count which meshes take each way).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WeldPath {
    /// By value in linear time ([`value_weld`], [`last_run`]).
    ByValue,
    /// By replaying mikktspace.c's splitting ([`weld`]): an attribute is `NaN` or huge, or a
    /// welded vertex's attributes differ in bits.
    ReplayedForAttributes,
    /// By value, then replayed for every welded vertex's index, and the edge sort's last run with
    /// it: that run may hold more than one edge.
    ReplayedForLastRun,
}

/// What a corner no group reaches keeps: the tangent (1, 0, 0), orientation 0 (w = -1).
const UNREACHED: (Vec3, u8) = ([1.0, 0.0, 0.0], 0);

/// The largest corner or vertex count: indices stay clear of the sentinels.
const MAX_COUNT: usize = (u32::MAX / 4) as usize;

/// The arrays that live through the whole call.
struct Buffers<'a> {
    /// Per corner: its vertex, then its welded vertex.
    welded: &'a mut [u32],
    /// Per welded vertex: the vertex its attributes come from, and those attributes.
    source: &'a mut [u32],
    /// Per welded vertex: mikktspace.c's index for it (`4 * face + corner` of its representative).
    values: &'a mut [u32],
    attributes: &'a mut [Packed],
    /// Per vertex, reused by phase (weld classes, first corners, flags).
    slots: &'a mut [u32],
    /// Two words per vertex (at least one per corner), reused by phase.
    table: &'a mut [u32],
    /// Good triangles in triangle order, then the degenerate ones.
    order: &'a mut [u32],
    /// Per good triangle: its welded vertices, derivatives, flags, neighbours and groups.
    ids: &'a mut [[u32; 3]],
    tangent_s: &'a mut [Vec3],
    tangent_t: &'a mut [Vec3],
    flags: &'a mut [u8],
    neighbors: &'a mut [[u32; 3]],
    assigned: &'a mut [[u32; 3]],
    /// Per corner: the tangent and its orientation (1: preserving, w = +1).
    tangents: &'a mut [Vec3],
    orientation: &'a mut [u8],
    /// Memory for one phase at a time: welding, edge pairing, then groups.
    phase: &'a mut [u8],
}

impl<'a> Buffers<'a> {
    fn take(arena: &mut Arena<'a>, vertex_count: usize, corner_count: usize) -> Result<Self, Error> {
        let triangles = corner_count / 3;
        let phase_bytes = bytes_of(|a| edge_scratch(a, corner_count))?
            .max(bytes_of(|a| group_scratch(a, triangles))?)
            .max(bytes_of(|a| WeldScratch::take(a, vertex_count, corner_count))?);
        Ok(Buffers {
            welded: arena.take(corner_count)?,
            source: arena.take(corner_count)?,
            values: arena.take(corner_count)?,
            attributes: arena.take(corner_count)?,
            slots: arena.take(vertex_count)?,
            table: arena.take((2 * vertex_count + 2).max(corner_count))?,
            order: arena.take(triangles)?,
            ids: arena.take(triangles)?,
            tangent_s: arena.take(triangles)?,
            tangent_t: arena.take(triangles)?,
            flags: arena.take(triangles)?,
            neighbors: arena.take(triangles)?,
            assigned: arena.take(triangles)?,
            tangents: arena.take(corner_count)?,
            orientation: arena.take(corner_count)?,
            phase: arena.take(phase_bytes)?,
        })
    }
}

/// Edge pairing's arrays (welded vertices number at most the corners).
fn edge_scratch<'a>(arena: &mut Arena<'a>, corner_count: usize) -> Result<EdgeScratch<'a>, Error> {
    Ok(EdgeScratch {
        starts: arena.take(corner_count + 1)?,
        entries: arena.take(corner_count)?,
        next: arena.take(corner_count)?,
        head: arena.take(corner_count)?,
        tail: arena.take(corner_count)?,
        stamp: arena.take(corner_count)?,
    })
}

/// Grouping's and evaluation's memory: each corner's terms (projected dP/ds and dP/dt, angle),
/// the groups, and grouping's search stack (the terms are computed while the groups are built).
type GroupScratch<'a> = (([&'a mut [Vec3]; 2], &'a mut [f32]), Groups<'a>, &'a mut [u32]);

/// Takes [`GroupScratch`] for `triangles` good triangles, laid out so that the pages it uses are
/// ones the weld has already touched (the terms and the groups' members entirely, the rest of the
/// groups' arrays as far as there are groups, the stack as deep as a search goes): first use of
/// memory costs a page fault, a large part of a call's time.
fn group_scratch<'a>(arena: &mut Arena<'a>, triangles: usize) -> Result<GroupScratch<'a>, Error> {
    let terms = (
        [arena.take(3 * triangles)?, arena.take(3 * triangles)?],
        arena.take(3 * triangles)?,
    );
    let groups = Groups {
        corners: arena.take(3 * triangles)?,
        starts: arena.take(3 * triangles + 1)?,
        orientation: arena.take(3 * triangles)?,
    };
    Ok((terms, groups, arena.take(groups::stack_words(triangles))?))
}

/// Bytes of working memory a call needs; `None` on overflow. The layout's sum, which the header
/// states as `97 C + 65 T + 12 V + 4 max(2 V + 2, C) + 16454` (checked by a test): the weld's
/// phase, `40 C + 8 V + 16415`, is the largest: edge pairing's and grouping's (`119 T + 30`) fit
/// in it.
pub(crate) fn scratch_bytes(vertex_count: usize, corner_count: usize) -> Option<usize> {
    if vertex_count == 0 {
        // Every index is out of range, or there are none: nothing to work on.
        return Some(0);
    }
    if vertex_count > MAX_COUNT || corner_count > MAX_COUNT {
        return None;
    }
    bytes_of(|a| Buffers::take(a, vertex_count, corner_count).map(|_| ())).ok()
}

/// Writes mikktspace.c's frame for every corner, or each vertex its first corner's, into `target`.
pub(crate) fn generate(
    mesh: &Mesh,
    options: &Options,
    bytes: &mut [u8],
    target: Target,
    report: &mut Report,
) -> Result<(), Error> {
    match target {
        Target::Vertices(output) => generate_vertices(mesh, options, output, bytes, report),
        Target::Corners(tangents) => generate_corners(mesh, options, tangents, bytes, report),
    }
}

/// Writes mikktspace.c's frame for every corner.
fn generate_corners(
    mesh: &Mesh,
    options: &Options,
    output: &mut StridedMut<[f32; 4]>,
    bytes: &mut [u8],
    report: &mut Report,
) -> Result<(), Error> {
    let (buffers, _, in_place) = compute(mesh, options, bytes, Some(&mut *output), report)?;
    if in_place {
        return Ok(());
    }
    let write = |first: usize, mut part: StridedMut<[f32; 4]>| {
        for i in 0..part.len() {
            part.set(i, frame(&buffers, first + i));
        }
    };
    let ranges = parallel::item_ranges(options.threads, mesh.corner_count(), 3);
    match ranges.ends() {
        [_] => write(0, output.reborrow()),
        ends => parallel::run_ranges(ends, output.split(ends, 1).into_iter(), write),
    }
    Ok(())
}

/// Writes each vertex the frame of its first corner; a vertex no triangle uses gets the fallback
/// frame built from its normal.
fn generate_vertices(
    mesh: &Mesh,
    options: &Options,
    output: &mut Output,
    bytes: &mut [u8],
    report: &mut Report,
) -> Result<(), Error> {
    let (buffers, _, _) = compute(mesh, options, bytes, None, report)?;
    let mut out = output.whole();
    for (v, &first) in buffers.slots[..mesh.vertex_count()].iter().enumerate() {
        let normal = GlamVec3::from_array(mesh.normals.get(v));
        let unit = frame::VertexNormal::new(normal.to_array()).unit;
        let (tangent, w) = if first == NONE {
            report.fallback_vertices += 1;
            frame::fallback(unit)
        } else {
            let [x, y, z, w] = frame(&buffers, first as usize);
            (GlamVec3::new(x, y, z), w)
        };
        // LEGACY keeps the caller's normal as given; the other policies promise a unit bitangent,
        // so they use the normalized normal (or, without one, a direction across the tangent).
        let across = match options.degenerate_policy {
            DegeneratePolicy::Legacy => normal,
            _ => unit.unwrap_or_else(|| frame::fallback_tangent(tangent)),
        };
        out.write(v, tangent, w, across);
    }
    Ok(())
}

/// Corner `c`'s tangent and sign as `setTSpaceBasic` receives them.
fn frame(buffers: &Buffers, c: usize) -> [f32; 4] {
    let [x, y, z] = buffers.tangents[c];
    [x, y, z, if buffers.orientation[c] != 0 { 1.0 } else { -1.0 }]
}

/// Every corner's tangent and orientation, the report, and (in `slots`) every vertex's first
/// corner, and how the weld was done. The frames go to the caller's per-corner output `in_place`
/// where the route allows it (then the third value is true), else to the buffers laid out in
/// `bytes`. Fails before anything reaches the caller's output.
fn compute<'a>(
    mesh: &Mesh,
    options: &Options,
    bytes: &'a mut [u8],
    mut in_place: Option<&mut StridedMut<[f32; 4]>>,
    report: &mut Report,
) -> Result<(Buffers<'a>, Routes, bool), Error> {
    if mesh.vertex_count() == 0 {
        // No scratch was asked for: any index is out of range, or there is nothing to do.
        if mesh.corner_count() > 0 {
            return Err(mesh.index_error());
        }
        *report = Report::default();
        let routes = Routes {
            weld: WeldPath::ByValue,
            groups: GroupRoute::Search,
        };
        return Ok((Buffers::take(&mut Arena::Count(0), 0, 0)?, routes, false));
    }
    let mut buffers = Buffers::take(&mut Arena::Carve(bytes), mesh.vertex_count(), mesh.corner_count())?;
    let (vertex_count, corner_count) = (mesh.vertex_count(), mesh.corner_count());
    if vertex_count > MAX_COUNT || corner_count > MAX_COUNT {
        return Err(Error::SizeOverflow);
    }
    let attributes = Attributes {
        mesh,
        flip_v: options.flip_v,
        corner_values: None,
        index_zero: None,
    };
    *report = Report::default();

    // 1. Every corner's vertex, checked against the vertex count; ranges of corners on separate
    //    threads.
    let ranges = parallel::item_ranges(options.threads, corner_count, 3);
    let ends = ranges.ends();
    let in_range = AtomicBool::new(true);
    parallel::run_ranges(ends, parallel::split(&mut *buffers.welded, ends, 1), |first, welded| {
        for (c, slot) in (first..).zip(welded.iter_mut()) {
            let v = mesh.indices.corner(c);
            if v >= vertex_count {
                in_range.store(false, Ordering::Relaxed);
                return;
            }
            *slot = v as u32;
        }
    });
    if !in_range.into_inner() {
        return Err(mesh.index_error());
    }
    // 2. mikktspace.c proper, steps 3 to 9 (policy REJECT refused a degenerate mesh before).
    let tangents = core::mem::take(&mut buffers.tangents);
    let solved = if corner_count > 0 {
        let in_place = in_place.as_deref_mut();
        solve(
            &attributes,
            options.threads,
            &mut buffers,
            &mut *tangents,
            in_place,
            None,
            report,
        )?
    } else {
        let routes = Routes {
            weld: WeldPath::ByValue,
            groups: GroupRoute::Search,
        };
        Solved {
            routes,
            good: 0,
            welded_count: 0,
            in_place: false,
        }
    };
    let orientation = core::mem::take(&mut buffers.orientation);
    // 10 and 11, and the counts, where the frames are.
    match in_place.filter(|_| solved.in_place) {
        Some(output) => finish(mesh, options, &mut buffers, &solved, output, report),
        None => {
            let mut arrays = Arrays {
                spaces: &mut *tangents,
                orientation: &mut *orientation,
            };
            finish(mesh, options, &mut buffers, &solved, &mut arrays, report);
        }
    }
    (buffers.tangents, buffers.orientation) = (tangents, orientation);
    Ok((buffers, solved.routes, solved.in_place))
}

/// Steps 10 and 11 on the frames `solve` wrote, and the per-vertex counts.
fn finish<F: Frames<Vec3>>(
    mesh: &Mesh,
    options: &Options,
    buffers: &mut Buffers,
    solved: &Solved,
    frames: &mut F,
    report: &mut Report,
) {
    // 10. Degenerate triangles' corners (DegenEpilogue).
    copy_to_degenerate(buffers, solved, frames, |c: usize| c, |_| false, Some(UNREACHED));
    // 11. Policies other than LEGACY replace what no frame can be; then per-vertex counts.
    if options.degenerate_policy != DegeneratePolicy::Legacy {
        repair::repair(mesh, options.degenerate_policy, frames, buffers.slots, report);
        report.abnormal_normals = frame::count_abnormal_normals(mesh);
    }
    let frames = &*frames;
    count_vertices(mesh, options.threads, buffers, |c| frames.get(c), report);
}

/// What mikktspace.c's own interface adds to a triangle mesh ([`faces_interface`]).
pub(crate) struct FaceExtras<'a> {
    /// Per triangle: the face it splits from (a quad's two triangles are neighbours in the list).
    pub face_of: &'a [u32],
    /// Per good triangle: `fMagS` and `fMagT` (filled by step 5).
    pub magnitudes: &'a mut [[f32; 2]],
    /// The angular threshold's cosine ([`tspace::threshold_cosine`]).
    pub threshold: f32,
    /// Per good corner (`3 g + k`, filled by step 7): its place in the order in which
    /// `GenerateTSpaces` writes the corners (group after group, each in `AssignRecur`'s order),
    /// which decides the bits where a quad's two triangles meet ([`groups::build`]).
    pub write_order: &'a mut [u32],
}

/// How [`solve`] ended: the routes it took, the good triangles (the first of `order`), the
/// welded vertices, and whether the frames went to the caller's output in place.
struct Solved {
    routes: Routes,
    good: usize,
    welded_count: usize,
    in_place: bool,
}

/// Steps 3 to 9: mikktspace.c proper, every good triangle's corners into `spaces` and
/// `b.orientation` (those no group reaches left as they were), or, where the groups go fan by fan
/// and `in_place` is given, into that per-corner output.
fn solve<S: tspace::Space>(
    attributes: &Attributes,
    threads: u32,
    b: &mut Buffers,
    spaces: &mut [S],
    in_place: Option<&mut StridedMut<[f32; 4]>>,
    mut extras: Option<&mut FaceExtras>,
    report: &mut Report,
) -> Result<Solved, Error> {
    let corner_count = b.welded.len();
    let triangles = corner_count / 3;

    // 3. Weld corners equal in position, normal and texture coordinate
    //    (GenerateSharedVerticesIndexList): by value where that finds mikktspace.c's welded
    //    vertices and the order of its last edges cannot matter; else by replaying its splitting.
    let vertex_count = attributes.mesh.vertex_count();
    let by_value = weld_by_value(attributes, threads, b);
    let welded_count = match by_value {
        Some(count) => count,
        None => {
            let mut phase = Arena::Carve(&mut *b.phase);
            let weld_scratch = WeldScratch::take(&mut phase, vertex_count, corner_count)?;
            weld::weld(attributes, threads, b.welded, b.source, b.values, weld_scratch)
        }
    };
    let ranges = parallel::item_ranges(threads, welded_count, 1);
    let ends = ranges.ends();
    let parts = parallel::split(&mut b.attributes[..welded_count], ends, 1);
    parallel::run_ranges(ends, parts, |first, part| {
        for (packed, &vertex) in part.iter_mut().zip(&b.source[first..]) {
            *packed = attributes.key(vertex);
        }
    });
    let packed = &b.attributes[..welded_count];

    // 4. Degenerate triangles (two equal positions) last, the good ones in order (DegenPrologue).
    //    The marks go in `flags`, which step 5 overwrites.
    let ranges = parallel::ranges(threads, triangles);
    let ends = ranges.ends();
    parallel::run_ranges(
        ends,
        parallel::split(&mut b.flags[..triangles], ends, 1),
        |first, marks| {
            faces::mark_degenerate(packed, b.welded, first, marks);
        },
    );
    let good = faces::good_first(&b.flags[..triangles], b.order);
    // Each good triangle's welded vertices: where every triangle is good (the usual mesh), those
    // of the corners as they are.
    let ids = if good == triangles {
        triples(b.welded)
    } else {
        parallel::run_ranges(ends, parallel::split(b.ids, ends, 1), |first, ids| {
            for (id, &t) in ids.iter_mut().zip(&b.order[first..]) {
                let t = t as usize;
                *id = [b.welded[3 * t], b.welded[3 * t + 1], b.welded[3 * t + 2]];
            }
        });
        &b.ids[..good]
    };
    let packed = &b.attributes[..welded_count];
    let order = &b.order[..good];

    // The last-run check (after a weld by value: [`last_run_is_trivial`]), and
    // 5. each good triangle's unit dP/ds, dP/dt and orientation (InitTriInfo, eq. 18-19), and
    // 6. the good triangle across each edge (BuildNeighborsFast). The derivatives read nothing
    //    the other two write: with two threads or more, the check, or else the pairing, each
    //    mostly on one thread, goes beside the derivatives, which take the others.
    let ranges = parallel::ranges(threads, good);
    let triangle_interface = extras.is_none() && S::tangents(&mut *spaces).is_some();
    let (tangent_s, tangent_t, flags) = (&mut b.tangent_s[..good], &mut b.tangent_t[..good], &mut b.flags[..good]);
    let mut magnitudes = extras.as_deref_mut().map(|e| &mut e.magnitudes[..good]);
    let mut derivatives = |threads: u32| {
        let ranges = parallel::ranges(threads, good);
        let ends = ranges.ends();
        let mut magnitudes = magnitudes.as_deref_mut().map(|m| parallel::split(m, ends, 1));
        let parts = parallel::split(&mut *tangent_s, ends, 1)
            .zip(parallel::split(&mut *tangent_t, ends, 1))
            .zip(parallel::split(&mut *flags, ends, 1))
            .map(|part| (part, magnitudes.as_mut().and_then(Iterator::next)));
        parallel::run_ranges(ends, parts, |first, (((s, t), flags), magnitudes)| {
            let end = first + flags.len();
            faces::derivatives(packed, &ids[first..end], s, t, flags, magnitudes)
        });
    };
    let mut weld_buffers = WeldBuffers {
        welded: &*b.welded,
        source: &mut *b.source,
        values: &mut *b.values,
        table: &mut *b.table,
        phase: &mut *b.phase,
    };
    let mut check = |threads: u32| last_run_is_trivial(attributes, threads, &mut weld_buffers, packed, ids);
    let checked_beside = by_value.is_some() && ranges.ends().len() > 1;
    let trivial = match by_value {
        Some(_) if checked_beside => Some(beside_derivatives(threads, &mut derivatives, &mut || check(1))?),
        Some(_) => Some(check(threads)?),
        None => None,
    };
    let path = match trivial {
        Some(true) => WeldPath::ByValue,
        Some(false) => {
            replay_for_last_run(attributes, threads, &mut weld_buffers, packed)?;
            WeldPath::ReplayedForLastRun
        }
        None => WeldPath::ReplayedForAttributes,
    };
    let values = (path != WeldPath::ByValue).then_some(&b.values[..welded_count]);
    let (phase, neighbors) = (&mut *b.phase, &mut b.neighbors[..good]);
    // Every edge's pairing (`whole`), or the last run's alone after a replayed weld, whose `i0`
    // it returns.
    let mut pairing = move |whole: bool| -> Result<Option<u32>, Error> {
        let mut phase = Arena::Carve(phase);
        let mut edges = edge_scratch(&mut phase, corner_count)?;
        edges.starts = &mut edges.starts[..welded_count + 1];
        Ok(match values {
            Some(values) if !whole => Some(neighbors::pair_last_run(ids, values, neighbors, edges)),
            _ => {
                neighbors::pair_edges(ids, values, neighbors, edges);
                None
            }
        })
    };
    // Taken fan by fan ([`fans`]), the groups need no pairing of every edge first, unless a
    // GROUP_WITH_ANY triangle calls for the search: only the last run's, after a replayed weld.
    let paired_beside = !checked_beside && ranges.ends().len() > 1;
    let mut paired = None;
    if paired_beside {
        let whole = !triangle_interface;
        beside_derivatives(threads, &mut derivatives, &mut || {
            paired = Some((whole, pairing(whole)?));
            Ok(true)
        })?;
    } else if !checked_beside {
        derivatives(threads);
    }
    let by_fans = triangle_interface && b.flags[..good].iter().all(|&f| f & GROUP_WITH_ANY == 0);
    let last_i0 = match paired {
        Some((true, _)) => None,
        Some((false, last)) if by_fans => last,
        _ if by_fans && values.is_none() => None,
        _ => pairing(!by_fans)?,
    };
    if let Some(extras) = extras.as_deref() {
        faces::force_quad_orientation(packed, ids, order, extras.face_of, &mut b.flags[..good]);
    }
    // Fan by fan, no good triangle is GROUP_WITH_ANY: only the degenerate ones are noted.
    let first_noted = if by_fans { good } else { 0 };
    for t in first_noted..triangles {
        let unusable = t >= good || b.flags[t] & GROUP_WITH_ANY != 0;
        if unusable {
            report.note_degenerate(b.order[t] as usize);
        }
    }

    // 7. Orientation-preserving groups around each welded vertex (Build4RuleGroups), and
    // 8. what each corner weighs (EvalTspace's projections and corner angle), on ranges of good
    //     triangles. Neither reads what the other writes: with two threads or more the grouping,
    //     which runs on one, goes beside the terms, which take the others.
    let mut phase = Arena::Carve(&mut *b.phase);
    let (terms, mut groups, stack) = group_scratch(&mut phase, triangles)?;
    let ([s, t], angle) = terms;
    let (s, t, angle) = (&mut s[..3 * good], &mut t[..3 * good], &mut angle[..3 * good]);
    let derivatives = [&b.tangent_s[..good], &b.tangent_t[..good]];
    // The terms, with the directions when `stored` is given.
    let mut weigh = |threads: u32, stored: Option<[&mut [Vec3]; 2]>| {
        let ranges = parallel::ranges(threads, good);
        let ends = ranges.ends();
        let mut stored = stored.map(|[s, t]| parallel::split(s, ends, 3).zip(parallel::split(t, ends, 3)));
        let parts = parallel::split(&mut *angle, ends, 3)
            .map(|angle| (stored.as_mut().and_then(Iterator::next).map(|(s, t)| [s, t]), angle));
        parallel::run_ranges(ends, parts, |first, (directions, angle)| {
            let range = first..first + angle.len() / 3;
            let derivatives = derivatives.map(|d| &d[range.clone()]);
            corner_terms::compute(packed, &ids[range], derivatives, CornerTerms { directions, angle });
        });
    };
    if let (None, Some(tangents)) = (&extras, S::tangents(&mut *spaces)) {
        // 7 to 9 at once: fan by fan ([`fans`]) or over the mesh ([`components`]), mikktspace.c's
        // search only at the welded vertices of GROUP_WITH_ANY triangles. Fan by fan, each
        // corner's directions are read once, so they are projected then rather than stored.
        let directions = if by_fans {
            weigh(threads, None);
            Directions::Projected {
                attributes: packed,
                ids,
                derivatives,
            }
        } else {
            weigh(threads, Some([&mut *s, &mut *t]));
            Directions::Stored { s, t }
        };
        let near = if by_fans {
            None
        } else {
            mark_near(ids, &b.flags[..good], &mut b.table[..welded_count])
        };
        let (neighbors, assigned) = (&b.neighbors[..good], &mut b.assigned[..good]);
        let searched = match near {
            Some(near) => {
                let memory = (&mut groups, &mut *stack);
                let at_near = |id: u32| near[id as usize] != 0;
                groups::build(ids, neighbors, &mut b.flags[..good], assigned, memory, at_near, None)
            }
            None => 0,
        };
        let inputs = Inputs {
            flags: &b.flags[..good],
            order,
            directions,
            angle,
            magnitudes: &[],
            threshold: tspace::threshold_cosine(180.0),
            face_of: None,
        };
        let outputs = (tangents, &mut *b.orientation);
        let in_place = in_place.filter(|_| by_fans);
        let written_in_place = in_place.is_some();
        let groups = if by_fans {
            let lists = (&mut groups.starts[..welded_count + 1], &mut groups.corners[..3 * good]);
            let last_run = last_i0.map(|last| fans::LastRun {
                values: &b.values[..welded_count],
                last,
                neighbors,
            });
            let (last_run, ends) = (last_run.as_ref(), ranges.ends());
            let settled = match in_place {
                Some(output) => fans::evaluate_on_ranges(&inputs, ids, last_run, ends, lists, output)?,
                None => {
                    let (spaces, orientation) = outputs;
                    let arrays = &mut Arrays { spaces, orientation };
                    fans::evaluate_on_ranges(&inputs, ids, last_run, ends, lists, arrays)?
                }
            };
            GroupRoute::Fans(settled)
        } else {
            // Corners of GROUP_WITH_ANY triangles that no group reaches keep the default.
            outputs.0.fill(UNREACHED.0);
            outputs.1.fill(UNREACHED.1);
            let adjacency = components::Adjacency { ids, neighbors, near };
            let parent = assigned.as_flattened_mut();
            let search = (&mut groups, searched);
            GroupRoute::Components(components::evaluate(&inputs, adjacency, parent, outputs, search)?)
        };
        return Ok(Solved {
            routes: Routes { weld: path, groups },
            good,
            welded_count,
            in_place: written_in_place,
        });
    }
    let (neighbors, flags, assigned) = (&b.neighbors[..good], &mut b.flags[..good], &mut b.assigned[..good]);
    let write_order = extras.as_deref_mut().map(|e| &mut e.write_order[..3 * good]);
    let group = || {
        groups::build(
            ids,
            neighbors,
            flags,
            assigned,
            (&mut groups, &mut *stack),
            |_| true,
            write_order,
        )
    };
    let group_count = if ranges.ends().len() > 1 {
        parallel::join(|| weigh(threads - 1, Some([&mut *s, &mut *t])), group).1
    } else {
        weigh(threads, Some([&mut *s, &mut *t]));
        group()
    };

    // 9. Each group's sub-groups and their angle-weighted tangents (GenerateTSpaces, EvalTspace),
    //     on ranges of groups of about as many members each (a vertex's triangles can lie far
    //     apart in the triangle order): a worker sorts its groups' corners, evaluates the
    //     groups, and writes the corners in its range of good triangles, the others (spilled)
    //     once every worker is done.
    let ends = ranges.ends();
    let inputs = Inputs {
        flags: &b.flags[..good],
        order,
        directions: Directions::Stored { s, t },
        angle,
        magnitudes: extras.as_deref().map_or(&[], |e| &e.magnitudes[..good]),
        threshold: extras
            .as_deref()
            .map_or(tspace::threshold_cosine(180.0), |e| e.threshold),
        face_of: extras.as_deref().map(|e| e.face_of),
    };
    let starts = &groups.starts[..group_count + 1];
    let members = starts[group_count] as usize;
    let group_ranges = parallel::Ranges::from_ends(
        parallel::ends(members, ends.len()).map(|end| starts.partition_point(|&s| (s as usize) < end)),
    );
    let group_ends = group_ranges.ends();
    let member_ends = parallel::Ranges::from_ends(group_ends.iter().map(|&g| starts[g] as usize));
    let first_groups = core::iter::once(0).chain(group_ends.iter().copied());
    let parts = parallel::split(&mut *groups.corners, member_ends.ends(), 1).zip(first_groups.zip(group_ends.iter()));
    let orientations = &*groups.orientation;
    let frames = &mut Arrays {
        spaces: &mut *spaces,
        orientation: &mut *b.orientation,
    };
    // A worker spills at most its groups' members.
    let mut room = [0; parallel::MAX_RANGES];
    for ((room, &end), start) in room
        .iter_mut()
        .zip(member_ends.ends())
        .zip(core::iter::once(0).chain(member_ends.ends().iter().copied()))
    {
        *room = end - start;
    }
    let triangles = triangle_ranges(ends, order, frames.corners() / 3);
    write_in_ranges(
        (ends, triangles.ends()),
        frames.split(triangles.ends()),
        &room,
        parts,
        |out, (corners, (first_group, &end_group))| {
            let base = starts[first_group] as usize;
            for group in first_group..end_group {
                let members = &mut corners[starts[group] as usize - base..starts[group + 1] as usize - base];
                members.sort_unstable();
                tspace::evaluate_group(&inputs, members, orientations[group] != 0, out)?;
            }
            Ok(())
        },
    )?;
    Ok(Solved {
        routes: Routes {
            weld: path,
            groups: GroupRoute::Search,
        },
        good,
        welded_count,
        in_place: false,
    })
}

/// Marks in `near` (one word per welded vertex) the welded vertices of `GROUP_WITH_ANY`
/// triangles; `None` when there are none.
fn mark_near<'n>(ids: &[[u32; 3]], flags: &[u8], near: &'n mut [u32]) -> Option<&'n [u32]> {
    near.fill(0);
    let mut any = false;
    for (corners, &flags) in ids.iter().zip(flags) {
        if flags & GROUP_WITH_ANY != 0 {
            corners.iter().for_each(|&id| near[id as usize] = 1);
            any = true;
        }
    }
    any.then_some(&*near)
}

/// Where each range of good triangles `ends` begins and ends in the triangles (good triangle `g`
/// is triangle `order[g]`; there are `triangles` in all): the cuts of [`write_in_ranges`]'s
/// frames.
fn triangle_ranges(ends: &[usize], order: &[u32], triangles: usize) -> parallel::Ranges {
    parallel::Ranges::from_ends(ends.iter().map(|&end| {
        if end == order.len() {
            triangles
        } else {
            order[end] as usize
        }
    }))
}

/// Runs `work(out, part)` for each range of good triangles `ends`, beside the others: `out` writes
/// the corners of the range's good triangles in place in its part of `frames` (the per-corner
/// frames of the triangles of [`triangle_ranges`], in order), and holds the others until every
/// worker is done, with room for `room[i]` of them in range `i`'s, made before any worker starts.
fn write_in_ranges<S: tspace::Space, G: Frames<S>, P: Send>(
    (ends, triangle_ends): (&[usize], &[usize]),
    frames: impl Iterator<Item = G>,
    room: &[usize],
    parts: impl Iterator<Item = P>,
    work: impl Fn(&mut tspace::Written<S, G>, P) -> Result<(), Error> + Sync,
) -> Result<(), Error> {
    let first_triangles = core::iter::once(0).chain(triangle_ends.iter().copied());
    // One range spills nothing and allocates nothing.
    let mut spilled: [Vec<tspace::Spilled<S>>; parallel::MAX_RANGES] = [const { Vec::new() }; parallel::MAX_RANGES];
    if ends.len() > 1 {
        for (spilled, &room) in spilled.iter_mut().zip(room) {
            spilled.try_reserve_exact(room).map_err(|_| Error::OutOfMemory)?;
        }
    }
    let mut slots: [Option<G>; parallel::MAX_RANGES] = [const { None }; parallel::MAX_RANGES];
    for (slot, frames) in slots.iter_mut().zip(frames) {
        *slot = Some(frames);
    }
    let mut frames = slots;
    let mut outcomes: [Result<(), Error>; parallel::MAX_RANGES] = [const { Ok(()) }; parallel::MAX_RANGES];
    let ranges = frames
        .iter_mut()
        .zip(first_triangles.clone().zip(ends.iter()))
        .zip(spilled.iter_mut().zip(outcomes.iter_mut()))
        .zip(parts);
    parallel::run_ranges(ends, ranges, |first, ranges| {
        let (((slot, (first_triangle, &end)), (spilled, outcome)), part) = ranges;
        let Some(frames) = slot.take() else {
            return;
        };
        let mut out = tspace::Written {
            frames,
            goods: first as u32..end as u32,
            first_triangle,
            spilled,
        };
        *outcome = work(&mut out, part);
        *slot = Some(out.frames);
    });
    outcomes.into_iter().collect::<Result<(), Error>>()?;
    for &(corner, space, preserving) in spilled.iter().flatten() {
        let triangle = corner as usize / 3;
        let range = triangle_ends.partition_point(|&end| end <= triangle);
        let first_triangle = first_triangles.clone().nth(range).unwrap_or(0);
        if let Some(frames) = &mut frames[range] {
            frames.set(corner as usize - 3 * first_triangle, space, preserving);
        }
    }
    Ok(())
}

/// 10. Degenerate triangles copy the first good corner of the same welded vertex
///     (DegenEpilogue): `frames` hold what corner `c` gets at `slot_of(c)`;
///     triangles `skip` names copy nothing; a corner with nothing to copy gets `unreached`, if
///     given (else it keeps what it holds).
fn copy_to_degenerate<S: Copy>(
    b: &mut Buffers,
    solved: &Solved,
    frames: &mut impl Frames<S>,
    slot_of: impl Fn(usize) -> usize,
    skip: impl Fn(usize) -> bool,
    unreached: Option<(S, u8)>,
) {
    let triangles = b.welded.len() / 3;
    if solved.good == triangles {
        return;
    }
    let (good, degenerate) = b.order[..triangles].split_at(solved.good);
    let first_good = &mut b.table[..solved.welded_count];
    first_good.fill(NONE);
    for &t in good {
        for corner in 3 * t as usize..3 * t as usize + 3 {
            let id = b.welded[corner] as usize;
            if first_good[id] == NONE {
                first_good[id] = corner as u32;
            }
        }
    }
    for &t in degenerate.iter().filter(|&&t| !skip(t as usize)) {
        for corner in 3 * t as usize..3 * t as usize + 3 {
            let from = first_good[b.welded[corner] as usize];
            let to = slot_of(corner);
            if from != NONE {
                let (space, preserving) = frames.get(slot_of(from as usize));
                frames.set(to, space, preserving);
            } else if let Some((space, preserving)) = unreached {
                frames.set(to, space, preserving);
            }
        }
    }
}

/// Step 3 by value ([`value_weld`]): replaces each corner's vertex in `welded` by its welded
/// vertex, with each vertex's in `slots`, and fills `source`; or leaves `welded` as it was and
/// returns `None`. Uses `table` as scratch.
fn weld_by_value(attributes: &Attributes, threads: u32, b: &mut Buffers) -> Option<usize> {
    let vertex_count = attributes.mesh.vertex_count();
    let workers = parallel::workers_for(threads, b.welded.len() / 3);
    let class = &mut b.slots[..vertex_count];
    // Two slots per vertex keep the table at most half full; the rest stays untouched.
    let table = &mut b.table[..2 * vertex_count + 2];
    value_weld::weld(attributes, workers, b.welded, class, b.source, table)
}

/// Runs `derivatives` on `threads - 1` workers and `other` beside them on one; `other`'s outcome.
/// One function for both uses, so that the threads' code is compiled once.
fn beside_derivatives(
    threads: u32,
    derivatives: &mut (dyn FnMut(u32) + Send),
    other: &mut (dyn FnMut() -> Result<bool, Error> + Send),
) -> Result<bool, Error> {
    parallel::join(|| derivatives(threads - 1), other).1
}

/// After a weld by value: whether the last run of the edge sort can be left out ([`last_run`]),
/// from the good triangles' welded vertices `ids` and the welded vertices' attributes `packed`.
fn last_run_is_trivial(
    attributes: &Attributes,
    threads: u32,
    b: &mut WeldBuffers,
    packed: &[Packed],
    ids: &[[u32; 3]],
) -> Result<bool, Error> {
    let (vertex_count, corner_count, welded_count) = (attributes.mesh.vertex_count(), b.welded.len(), packed.len());
    let mut phase = Arena::Carve(&mut *b.phase);
    let memory = last_run::Memory {
        lo: &mut b.values[..welded_count],
        hi: &mut b.table[..welded_count],
        weld: WeldScratch::take(&mut phase, vertex_count, corner_count)?,
    };
    Ok(last_run::is_trivial(
        attributes,
        threads,
        b.welded,
        (b.source, packed),
        ids,
        memory,
    ))
}

/// Where the last run can matter: mikktspace.c's index for every welded vertex, into `values`.
/// The weld by value's classes are the C's, and both number them in order of first use, so only
/// the representatives are missing: the splitting is replayed on every cell from the welded
/// vertices' attributes ([`weld::representatives`]), which reads each vertex once rather than
/// every corner's.
fn replay_for_last_run(
    attributes: &Attributes,
    threads: u32,
    b: &mut WeldBuffers,
    packed: &[Packed],
) -> Result<(), Error> {
    let (vertex_count, corner_count) = (attributes.mesh.vertex_count(), b.welded.len());
    let mut phase = Arena::Carve(&mut *b.phase);
    let mut scratch = WeldScratch::take(&mut phase, vertex_count, corner_count)?;
    let every_cell = Wanted {
        welded: &|_| true,
        corner_limit: corner_count,
    };
    let welded_vertices = (b.welded, &b.source[..packed.len()], packed);
    // The cells hold every corner and no more, so the limit is never passed: `None` cannot come
    // back.
    let found = weld::representatives(attributes, threads, welded_vertices, every_cell, &mut scratch);
    for &[c, _, first] in found.unwrap_or_default() {
        b.values[b.welded[c as usize] as usize] = attributes.value_of(first as usize);
    }
    Ok(())
}

/// What the last-run check and the replay read (the corners' welded vertices of [`Buffers`]) and
/// rewrite: each welded vertex's source and index, its table and its phase memory.
struct WeldBuffers<'w> {
    welded: &'w [u32],
    source: &'w mut [u32],
    values: &'w mut [u32],
    table: &'w mut [u32],
    phase: &'w mut [u8],
}

/// Per vertex: its first corner (into `slots`), and the report's vertex counts: unreferenced,
/// mirrored (corners of both signs) and split (corners that differ in any bit). Ranges of vertices
/// on separate threads, each worker reading every corner's frame (`frame(c)`) and keeping those of
/// its vertices.
fn count_vertices(
    mesh: &Mesh,
    threads: u32,
    buffers: &mut Buffers,
    frame: impl Fn(usize) -> (Vec3, u8) + Sync,
    report: &mut Report,
) {
    const MIRRORED: u32 = 1;
    const SPLIT: u32 = 2;
    let vertex_count = mesh.vertex_count();
    let ranges = parallel::item_ranges(threads, vertex_count, 1);
    let ends = ranges.ends();
    // Per range: unreferenced, mirrored and split vertices.
    let mut counts = [[0usize; 3]; parallel::MAX_RANGES];
    let parts = parallel::split(&mut buffers.slots[..vertex_count], ends, 1)
        .zip(parallel::split(&mut buffers.table[..vertex_count], ends, 1))
        .zip(counts.iter_mut());
    parallel::run_ranges(ends, parts, |start, ((first, marks), counts)| {
        first.fill(NONE);
        marks.fill(0);
        for c in 0..mesh.corner_count() {
            let Some(v) = mesh.indices.corner(c).checked_sub(start).filter(|&v| v < first.len()) else {
                continue;
            };
            if first[v] == NONE {
                first[v] = c as u32;
                continue;
            }
            let ((first_tangent, first_orientation), (tangent, orientation)) = (frame(first[v] as usize), frame(c));
            if first_orientation != orientation {
                marks[v] |= MIRRORED;
            }
            let same = first_orientation == orientation && first_tangent.map(f32::to_bits) == tangent.map(f32::to_bits);
            if !same {
                marks[v] |= SPLIT;
            }
        }
        for (&f, &m) in first.iter().zip(marks.iter()) {
            counts[0] += usize::from(f == NONE);
            counts[1] += usize::from(m & MIRRORED != 0);
            counts[2] += usize::from(m & SPLIT != 0);
        }
    });
    for [unreferenced, mirrored, split] in &counts[..ends.len()] {
        report.unreferenced_vertices += unreferenced;
        report.mirrored_vertices += mirrored;
        report.split_vertices += split;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scratch_bytes_follow_the_documented_formula() {
        // The largest phase is the weld's, whatever the counts; a count that is not a multiple of
        // 3 leaves its partial triangle out of `T`.
        for (v, c) in [
            (1, 3),
            (3, 3),
            (4, 6),
            (100, 30),
            (10, 300),
            (1000, 5994),
            (7, 0),
            (2, 3279),
            (2, 3282),
            (2, 3284),
            (1000, 5995),
        ] {
            let t = c / 3;
            let formula = 97 * c + 65 * t + 12 * v + 4 * (2 * v + 2).max(c) + 16454;
            let grouping = bytes_of(|a| group_scratch(a, t).map(|_| ()));
            assert_eq!(grouping, Ok(119 * t + 30), "{t} triangles");
            let weld = bytes_of(|a| WeldScratch::take(a, v, c).map(|_| ()));
            assert_eq!(weld, Ok(40 * c + 8 * v + 16415), "{v} vertices, {c} corners");
            assert!(bytes_of(|a| edge_scratch(a, c).map(|_| ())).unwrap() <= 40 * c + 8 * v + 16415);
            assert_eq!(scratch_bytes(v, c), Some(formula), "{v} vertices, {c} corners");
        }
        assert_eq!(scratch_bytes(0, 0), Some(0));
        assert_eq!(scratch_bytes(0, 3), Some(0));
        assert_eq!(scratch_bytes(usize::MAX / 8, 3), None);
        assert_eq!(scratch_bytes(3, usize::MAX), None);
    }
}
