//! The original listing (Lengyel 2001, `CalculateTangentArray`), operation for operation.
//!
//! Kept apart from the other kernels on purpose: every float operation here runs in the listing's
//! order, so policy LEGACY reproduces its bits, including the inf/NaN it writes when a triangle's
//! UV determinant is zero. Rust never fuses a multiply and an add, so no FMA changes a result.
//! Both loops run on x, y and z at once or on several vertices at once, compiled for each SIMD
//! path ([`crate::kernel::simd`]); the same operations per component give the same bits. One
//! thing IEEE arithmetic leaves to operand order, which the compiler may choose per path, is
//! which of two NaNs an operation passes on; so every NaN here is the CPU's default NaN (a
//! caller's NaN included), where the listing passes on whichever its compiler picks.
#![forbid(unsafe_code)]

use core::ops::Range;

use glam::{Vec2, Vec3, Vec3A};

use crate::kernel::error::Error;
use crate::kernel::index_bounds::{index_bounds, runs, IndexBounds};
use crate::kernel::lanes::{lane3, lanes_in_use, set_lane3, LANES, PREFETCH_TRIANGLES};
use crate::kernel::memory::{self, Arena, Place};
use crate::kernel::mesh::{Mesh, Output, OutputPart, PerIndexType, Target};
use crate::kernel::options::Options;
use crate::kernel::parallel;
use crate::kernel::report::Report;
use crate::kernel::simd;
use crate::kernel::sums::{self, count_flags, flag, slot_in, Scratch, VertexSums};
use crate::kernel::views::strided::Strided;

/// Bytes of working memory a call needs: the per-vertex sums (`tan1`, `tan2`) and flags,
/// `vertex_count * 29 + 3`. `None` on overflow.
pub(crate) fn memory_bytes(vertex_count: usize) -> Option<usize> {
    memory::vertex_arrays_bytes(vertex_count, 0, Place::Caller)
}

/// Writes every vertex's frame, or every corner its vertex's, into `target`.
pub(crate) fn generate(
    mesh: &Mesh,
    options: &Options,
    memory: &mut [u8],
    place: Place,
    target: Target,
    report: &mut Report,
) -> Result<(), Error> {
    // The listing has no adjacency: nothing is reserved apart.
    let mut no_links = Vec::new();
    let workers = parallel::workers_for(options.threads, mesh.corner_count() / 3);
    let mut scratch = memory::vertex_arrays(
        &mut Arena::Carve(memory),
        mesh.vertex_count(),
        0,
        (place, workers),
        &mut no_links,
    )?;
    match target {
        Target::Vertices(output) => run(mesh, options, &mut scratch, Some(output), report),
        Target::Corners(tangents) => {
            run(mesh, options, &mut scratch, None, report)?;
            sums::write_corner_frames(mesh, options.threads, scratch.sums, tangents, |_, _| Ok(()))
        }
    }
}

/// Both loops of the listing, each vertex's frame written into `output` or, without one, kept in
/// its sums. With several workers, each resolves a consecutive range of vertices. The first loop:
/// where the triangle order follows the vertex order, each worker reads the triangles that touch
/// its range, in triangle order; elsewhere they solve ranges of triangles apart
/// ([`solve_apart`]), and each adds the terms kept to its range before resolving it.
fn run(
    mesh: &Mesh,
    options: &Options,
    scratch: &mut Scratch,
    output: Option<&mut Output>,
    report: &mut Report,
) -> Result<(), Error> {
    let Some(texcoords) = mesh.texcoords else {
        // Validation refuses policy LEGACY without texture coordinates.
        return Err(Error::MissingTexcoords {
            method: options.method,
            policy: options.degenerate_policy,
        });
    };
    let listing = Listing::new(mesh, texcoords, options.flip_v)?;
    let workers = parallel::workers_for(options.threads, listing.triangle_count);
    // Made only where the workers solve apart: small meshes call often.
    let mut lists: [Vec<Solved>; parallel::MAX_RANGES];
    let (mut found, kept) = if workers == 1 || parallel::worker_count(options.threads, mesh) == workers {
        // Several workers skip the blocks of triangles with no corner in their range.
        let bounds = match workers {
            1 => None,
            _ => index_bounds(mesh, listing.triangle_count, workers)?,
        };
        let first_loop = |part: &mut Scratch, _: Option<&mut OutputPart>| {
            add_solved(&listing, 0..listing.triangle_count, part, bounds.as_ref())
        };
        let found = sums::for_each_range(scratch, None, workers, first_loop, parallel::merge_results)?;
        (found, None)
    } else {
        lists = [const { Vec::new() }; parallel::MAX_RANGES];
        let (found, first_kept) = solve_apart(&listing, scratch, &mut lists[..workers - 1])?;
        (found, Some((first_kept, &lists[..workers - 1])))
    };
    let second_loop = |part: &mut Scratch, out: Option<&mut OutputPart>| {
        if let Some((first, kept)) = kept {
            add_kept(mesh, first, kept, part);
        }
        // Forced inline, here and below: a closure left out of line is compiled for the baseline
        // only.
        simd::run(
            #[inline(always)]
            || resolve(mesh, part, out),
        );
    };
    sums::for_each_range(scratch, output, workers, second_loop, |(), ()| ());
    count_flags(scratch.flags, &mut found);
    *report = found;
    Ok(())
}

/// First loop of the listing over `triangles`: per triangle, solve
/// `[T B] = [Q1 Q2] * inverse([s1 t1; s2 t2])` and add `sdir` (dP/du) to `tan1`, `tdir` (dP/dv)
/// to `tan2` of its three vertices, in triangle order, for the vertices `scratch` holds. Also
/// checks every index, and counts the zero-determinant or non-finite triangles whose first vertex
/// it holds. With `bounds`, reads only the blocks of triangles with a vertex it holds (every index
/// was checked when the bounds were found).
fn add_solved(
    listing: &Listing,
    triangles: Range<usize>,
    scratch: &mut Scratch,
    bounds: Option<&IndexBounds>,
) -> Result<Report, Error> {
    simd::run(
        #[inline(always)]
        || {
            let listing = listing.clone();
            listing.mesh.indices.with_corner_reader(FirstLoop {
                listing,
                triangles,
                scratch,
                bounds,
            })
        },
    )
}

/// How much smaller the first worker's range of triangles is than each other's in
/// [`solve_apart`], as (numerator, denominator): it adds its terms at once, the others add
/// theirs after, all workers sharing. On the benchmark asset, two workers took least time with
/// about this ratio (solving a triangle costs about twice what adding its terms does).
const FIRST_RANGE: (usize, usize) = (2, 3);

/// The first loop on `lists.len() + 1` workers whatever the vertex order: the first worker solves
/// the first range of triangles and adds their terms at once ([`add_solved`]); each of the others
/// solves a range of the triangles after it and keeps each one's terms in its list ([`keep_solved`],
/// 28 bytes a triangle, allocated here and untouched until the worker writes it). Returns what it
/// found and the first triangle kept. Each vertex then adds the kept terms after the first
/// range's, in triangle order ([`add_kept`]): the order one worker adds them in.
fn solve_apart(listing: &Listing, scratch: &mut Scratch, lists: &mut [Vec<Solved>]) -> Result<(Report, usize), Error> {
    let triangle_count = listing.triangle_count;
    let (part, whole) = FIRST_RANGE;
    let first_kept = part * triangle_count / (whole * lists.len() + part);
    let ends = parallel::range_ends(triangle_count - first_kept, lists.len());
    let starts = core::iter::once(0).chain(ends.ends().iter().copied());
    let ranges = starts
        .zip(ends.ends())
        .map(|(start, &end)| first_kept + start..first_kept + end);
    for (list, triangles) in lists.iter_mut().zip(ranges.clone()) {
        *list = memory::vec_with_capacity(triangles.len())?;
    }
    let kept = lists
        .iter_mut()
        .zip(ranges)
        .map(|(list, triangles)| Share::Kept(triangles, list));
    let shares = core::iter::once(Share::Added(scratch)).chain(kept);
    let solve = |share: Share| match share {
        Share::Added(scratch) => add_solved(listing, 0..first_kept, scratch, None),
        Share::Kept(triangles, kept) => simd::run(
            #[inline(always)]
            || keep_solved(listing, triangles, kept),
        ),
    };
    let found = parallel::run_folded(shares, solve, parallel::merge_results).unwrap_or(Ok(Report::default()))?;
    Ok((found, first_kept))
}

/// A worker's share of [`solve_apart`]'s triangles: added at once into the whole scratch, or
/// the given ones kept.
enum Share<'p, 'a> {
    Added(&'p mut Scratch<'a>),
    Kept(Range<usize>, &'p mut Vec<Solved>),
}

/// One triangle's terms of the first loop: what it adds to each of its vertices.
struct Solved {
    sdir: [f32; 3],
    tdir: [f32; 3],
    /// The orientation flag ([`Listing::solve`]).
    orientation: u8,
}

/// The inputs of the listing's first loop.
#[derive(Clone)]
struct Listing<'m> {
    mesh: &'m Mesh<'m>,
    texcoords: Strided<'m, [f32; 2]>,
    v_sign: f32,
    triangle_count: usize,
}

/// The first loop over `triangles` into one worker's scratch, by `bounds` where given.
struct FirstLoop<'m, 's, 'a> {
    listing: Listing<'m>,
    triangles: Range<usize>,
    scratch: &'s mut Scratch<'a>,
    bounds: Option<&'s IndexBounds>,
}

impl PerIndexType for FirstLoop<'_, '_, '_> {
    type Output = Result<Report, Error>;

    /// A scratch holding every vertex (one worker, or the first of workers solving apart) skips the
    /// test of whether it holds a corner; one holding a range of them reads, where there are
    /// bounds, only the blocks of triangles with a corner in it.
    #[inline(always)]
    fn run(self, corners: impl Fn(usize) -> [usize; 3]) -> Result<Report, Error> {
        let FirstLoop {
            listing,
            triangles,
            scratch,
            bounds,
        } = self;
        let vertex_count = listing.mesh.vertex_count();
        let (first, len) = (scratch.first, scratch.sums.len());
        let sums = &mut *scratch.sums;
        if first == 0 && len == vertex_count {
            return listing.sweep(triangles, sums, corners, Some);
        }
        let mut report = Report::default();
        for run in runs(bounds, triangles, first..first + len) {
            report.merge(&listing.sweep(run, sums, &corners, |v| slot_in(v, first, len))?);
        }
        Ok(report)
    }
}

/// The first loop's solve over `triangles`, into `kept` (empty, with room for them). Here and in
/// [`add_kept`], the index type is matched per triangle, not compiled into a loop per type as in
/// [`FirstLoop`]: these run only on large indexed meshes, where the match costs nothing measurable,
/// and the library stays smaller.
#[inline(always)]
fn keep_solved(listing: &Listing, triangles: Range<usize>, kept: &mut Vec<Solved>) -> Result<Report, Error> {
    let mut report = Report::default();
    for a in triangles {
        listing.mesh.indices.prefetch_triangle(a + PREFETCH_TRIANGLES);
        let [i1, i2, i3] = listing.mesh.checked_triangle(a)?;
        let (sdir, tdir, orientation) = listing.solve(i1, i2, i3);
        if orientation == 0 {
            report.note_degenerate(a);
        }
        kept.push(Solved {
            sdir: sdir.to_array(),
            tdir: tdir.to_array(),
            orientation,
        });
    }
    Ok(report)
}

/// Adds the terms `kept` for the triangles from `first` on to the vertices `scratch` holds.
fn add_kept(mesh: &Mesh, first: usize, kept: &[Vec<Solved>], scratch: &mut Scratch) {
    for (a, solved) in (first..).zip(kept.iter().flatten()) {
        for v in mesh.indices.triangle(a) {
            if let Some(slot) = scratch.slot(v) {
                let terms = (
                    Vec3A::from_array(solved.sdir),
                    Vec3A::from_array(solved.tdir),
                    solved.orientation,
                );
                add_terms(&mut scratch.sums[slot], terms);
            }
        }
    }
}

/// Adds one triangle's terms (`sdir`, `tdir`, orientation flag) to one of its vertices: `sdir`
/// to `tan1` with the flags in the bits of the unused `weight` beside it, which [`resolve`] moves
/// to the vertex's flags.
#[inline(always)]
fn add_terms(vertex: &mut VertexSums, (sdir, tdir, orientation): (Vec3A, Vec3A, u8)) {
    simd::add_and_mark(vertex, sdir, flag::REFERENCED | orientation);
    for (sum, term) in vertex.secondary.iter_mut().zip(tdir.to_array()) {
        *sum += term;
    }
}

impl<'m> Listing<'m> {
    /// The listing's inputs from `mesh`, or the index count's error.
    fn new(mesh: &'m Mesh<'m>, texcoords: Strided<'m, [f32; 2]>, flip_v: bool) -> Result<Self, Error> {
        Ok(Listing {
            mesh,
            texcoords,
            v_sign: if flip_v { -1.0 } else { 1.0 },
            triangle_count: mesh.indices.triangle_count(mesh.vertex_count())?,
        })
    }

    /// `triangles` in order; `slot(v)` is where vertex `v` sits in `sums`, if there.
    #[inline(always)]
    fn sweep(
        &self,
        triangles: Range<usize>,
        sums: &mut [VertexSums],
        corners: impl Fn(usize) -> [usize; 3],
        slot: impl Fn(usize) -> Option<usize>,
    ) -> Result<Report, Error> {
        let mut report = Report::default();
        for a in triangles {
            let [i1, i2, i3] = self.mesh.checked(corners(a))?;
            if [i1, i2, i3].iter().all(|&v| slot(v).is_none()) {
                continue;
            }
            let terms @ (_, _, orientation) = self.solve(i1, i2, i3);
            if orientation == 0 && slot(i1).is_some() {
                report.note_degenerate(a);
            }
            for v in [i1, i2, i3] {
                if let Some(slot) = slot(v) {
                    add_terms(&mut sums[slot], terms);
                }
            }
        }
        Ok(report)
    }

    /// One triangle of the listing: `sdir`, `tdir`, and the orientation flag of its UV winding
    /// (the sign of `det`, or 0 when `det` is zero or one of the ten edge components is not
    /// finite).
    ///
    /// Each line of the arithmetic runs on x, y and z at once (the same operations per component,
    /// so the same bits). Testing the ten edge components costs more than the solve, so the
    /// common case is settled from `det` and the numerator of `sdir`, `t2 Q1 - t1 Q2` (before the
    /// division, which it then does not wait for): when both are finite, so is every edge, hence
    /// every input. A non-finite `s` or `t` makes `det` non-finite (a product with ±inf or NaN is
    /// ±inf or NaN, and so is a difference with one); with finite `s` and `t`, a non-finite `x1`
    /// makes `t2 x1` non-finite (NaN when `t2` is zero), hence `t2 x1 - t1 x2` (likewise `x2`, y
    /// and z). A triangle with a zero `det` or a non-finite input ends in [`special_triangle`];
    /// the others hold no NaN but those their own arithmetic makes.
    #[inline(always)]
    fn solve(&self, i1: usize, i2: usize, i3: usize) -> (Vec3A, Vec3A, u8) {
        let positions = self.mesh.positions;
        let [p1, p2, p3] = positions.get_three([i1, i2, i3]);
        let [p1, p2, p3] = [Vec3A::from_array(p1), Vec3A::from_array(p2), Vec3A::from_array(p3)];
        let [w1, w2, w3] = self.texcoords.get_three([i1, i2, i3]);
        let [w1, w2, w3] = [Vec2::from_array(w1), Vec2::from_array(w2), Vec2::from_array(w3)];
        let (e1, e2) = (p2 - p1, p3 - p1);
        let (s1, s2) = (w2.x - w1.x, w3.x - w1.x);
        let (t1, t2) = ((w2.y - w1.y) * self.v_sign, (w3.y - w1.y) * self.v_sign);

        let det = s1 * t2 - s2 * t1;
        let r = 1.0f32 / det;
        let sdir_numerator = e1 * t2 - e2 * t1;
        let sdir = sdir_numerator * r;
        let tdir = (e2 * s1 - e1 * s2) * r;
        // x * 0 is zero exactly when x is finite.
        let finite = ((sdir_numerator + Vec3A::splat(det)) * 0.0).cmpeq(Vec3A::ZERO).all();
        if det != 0.0 && finite {
            (sdir, tdir, side(det))
        } else {
            special_triangle(det, sdir, tdir, [e1, e2], [s1, s2, t1, t2])
        }
    }
}

/// The end of [`Listing::solve`] for a triangle with a zero `det` or a non-finite input: the
/// orientation flag from its definition, and `sdir` and `tdir` with every NaN made the CPU's
/// default NaN. Where two different NaNs meet, which one an operation passes on depends on the
/// operand order, which the compiler may choose differently for each SIMD path. The common case's
/// inputs are finite, so its NaNs are the default one already; with these and the normals'
/// ([`canonical_nan`]) made the same, no path can differ from another in a bit. Inlined, but
/// marked rare: a call would return its vectors through memory, and the common case's terms
/// would then go through that memory too.
#[inline(always)]
fn special_triangle(
    det: f32,
    sdir: Vec3A,
    tdir: Vec3A,
    [e1, e2]: [Vec3A; 2],
    uv_edges: [f32; 4],
) -> (Vec3A, Vec3A, u8) {
    rare();
    let finite = e1.is_finite() && e2.is_finite() && uv_edges.iter().all(|x| x.is_finite());
    let orientation = if det == 0.0 || !finite { 0 } else { side(det) };
    let nan = default_nan();
    let [sdir, tdir] = [sdir, tdir].map(|v| Vec3A::from_array(canonical_nan(v.to_array(), nan)));
    (sdir, tdir, orientation)
}

/// Marks the path that calls it as rare, so that the compiler lays it out of the loop.
#[cold]
#[inline(never)]
fn rare() {}

/// The NaN this CPU's arithmetic produces (`0 / 0`), not a constant the compiler would pick.
fn default_nan() -> f32 {
    core::hint::black_box(0.0f32) / core::hint::black_box(0.0f32)
}

/// `v` with every NaN component made `nan` (see [`special_triangle`]).
#[inline(always)]
fn canonical_nan(v: [f32; 3], nan: f32) -> [f32; 3] {
    v.map(|x| if x.is_nan() { nan } else { x })
}

/// The flag of a non-zero determinant's sign.
#[inline(always)]
fn side(det: f32) -> u8 {
    if det > 0.0 {
        flag::POSITIVE_UV
    } else {
        flag::NEGATIVE_UV
    }
}

/// Second loop of the listing: `T' = normalize(t - n * dot(n, t))`,
/// `w = dot(cross(n, t), tan2) < 0 ? -1 : 1`. Without an `output` (the per-corner output) each
/// vertex keeps its frame in its sums instead. Also moves each vertex's flags from its sums
/// ([`add_terms`]) to its flags.
#[inline(always)]
pub fn resolve(mesh: &Mesh, scratch: &mut Scratch, mut output: Option<&mut OutputPart>) {
    let vertices = scratch.first..scratch.first + scratch.sums.len();
    let packed_normals = mesh.normals.packed().map(|normals| &normals[vertices.clone()]);
    let packed_tangents = output.as_deref_mut().and_then(OutputPart::packed_tangents);
    // Every NaN the sums hold is the default one: the normals' are made the same.
    let nan = default_nan();
    if let (Some(normals), Some(tangents)) = (packed_normals, packed_tangents) {
        return resolve_packed(normals, scratch.sums, scratch.flags, tangents, nan);
    }
    for ((a, sums), flags) in vertices.zip(scratch.sums.iter_mut()).zip(scratch.flags.iter_mut()) {
        *flags = simd::marks(sums);
        let n = Vec3::from_array(canonical_nan(mesh.normals.get(a), nan));
        let (tangent, w) = frame(n, Vec3::from_array(sums.primary), Vec3::from_array(sums.secondary));
        match output.as_deref_mut() {
            Some(output) => output.write(a, tangent, w, n),
            None => sums.keep_frame(tangent, w),
        }
    }
}

/// [`resolve`] from packed normals into packed tangents, [`LANES`] vertices at a time in SIMD
/// lanes (the same operations on every lane, so the same bits).
#[inline(always)]
fn resolve_packed(normals: &[[f32; 3]], sums: &[VertexSums], flags: &mut [u8], tangents: &mut [[f32; 4]], nan: f32) {
    debug_assert!(normals.len() == sums.len() && flags.len() == sums.len() && tangents.len() >= sums.len());
    let (mut n, mut tan1, mut tan2) = ([[0.0; LANES]; 3], [[0.0; LANES]; 3], [[0.0; LANES]; 3]);
    let mut frames = [[0.0; LANES]; 4];
    let batches = normals
        .chunks(LANES)
        .zip(sums.chunks(LANES))
        .zip(flags.chunks_mut(LANES));
    for (((normals, sums), flags), tangents) in batches.zip(tangents.chunks_mut(LANES)) {
        for (i, ((normal, sums), flags)) in normals.iter().zip(sums).zip(flags).enumerate() {
            *flags = simd::marks(sums);
            set_lane3(&mut n, i, *normal);
            set_lane3(&mut tan1, i, sums.primary);
            set_lane3(&mut tan2, i, sums.secondary);
        }
        for i in 0..lanes_in_use(normals.len()) {
            let normal = Vec3::from_array(canonical_nan(lane3(&n, i).to_array(), nan));
            let (t, w) = frame(normal, lane3(&tan1, i), lane3(&tan2, i));
            for (lanes, value) in frames.iter_mut().zip([t.x, t.y, t.z, w]) {
                lanes[i] = value;
            }
        }
        for (i, tangent) in tangents.iter_mut().enumerate() {
            *tangent = [frames[0][i], frames[1][i], frames[2][i], frames[3][i]];
        }
    }
}

/// One vertex of the listing's second loop: its unit tangent and `w`.
#[inline(always)]
fn frame(n: Vec3, t: Vec3, tan2: Vec3) -> (Vec3, f32) {
    let orthogonal = t - n * dot(n, t);
    let tangent = orthogonal * (1.0 / dot(orthogonal, orthogonal).sqrt());
    let w = if dot(cross(n, t), tan2) < 0.0 { -1.0 } else { 1.0 };
    (tangent, w)
}

/// The listing's `Dot`: `x*x' + y*y' + z*z'`, summed left to right.
#[inline(always)]
fn dot(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// The listing's `Cross`.
#[inline(always)]
fn cross(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::simd::tests::PINNED;
    use crate::kernel::simd::Path;
    use crate::kernel::test_rng::TestRng;
    use crate::kernel::views::strided::StridedMut;

    /// A triangle's edges as the listing names them: `[x1, x2, y1, y2, z1, z2]`, `[s1, s2, t1, t2]`.
    fn listing_edges(v: [[f32; 3]; 3], w: [[f32; 2]; 3]) -> ([f32; 6], [f32; 4]) {
        let pairs = |k: usize| [v[1][k] - v[0][k], v[2][k] - v[0][k]];
        let [[x1, x2], [y1, y2], [z1, z2]] = [0, 1, 2].map(pairs);
        let [[s1, s2], [t1, t2]] = [0, 1].map(|k| [w[1][k] - w[0][k], w[2][k] - w[0][k]]);
        ([x1, x2, y1, y2, z1, z2], [s1, s2, t1, t2])
    }

    /// The orientation flag by its definition: zero when the UV determinant is zero or any of the
    /// ten edge components is not finite, else the determinant's sign.
    fn defined_orientation(v: [[f32; 3]; 3], w: [[f32; 2]; 3]) -> u8 {
        let (edges, uv @ [s1, s2, t1, t2]) = listing_edges(v, w);
        let finite = edges.iter().chain(&uv).all(|x| x.is_finite());
        let det = s1 * t2 - s2 * t1;
        match (finite && det != 0.0, det > 0.0) {
            (false, _) => 0,
            (true, true) => flag::POSITIVE_UV,
            (true, false) => flag::NEGATIVE_UV,
        }
    }

    /// The listing's `sdir` and `tdir`, written out as it computes them, one component at a time.
    fn listing_directions(v: [[f32; 3]; 3], w: [[f32; 2]; 3]) -> [[f32; 3]; 2] {
        let ([x1, x2, y1, y2, z1, z2], [s1, s2, t1, t2]) = listing_edges(v, w);
        let r = 1.0f32 / (s1 * t2 - s2 * t1);
        [
            [
                (t2 * x1 - t1 * x2) * r,
                (t2 * y1 - t1 * y2) * r,
                (t2 * z1 - t1 * z2) * r,
            ],
            [
                (s1 * x2 - s2 * x1) * r,
                (s1 * y2 - s2 * y1) * r,
                (s1 * z2 - s2 * z1) * r,
            ],
        ]
    }

    /// Values that reach the listing's special cases: signed zeros, overflow, infinities, NaNs
    /// of both signs and with payloads (a signalling one too), a subnormal.
    const HOSTILE: [f32; 13] = [
        0.0,
        -0.0,
        1.0,
        -2.5,
        3e38,
        -3e38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        f32::from_bits(0xFFC0_1234),
        f32::from_bits(0x7F80_0001),
        1e-45,
    ];

    /// A value in [-2, 2) with `percent` chance, else one of [`HOSTILE`].
    fn hostile_or_ordinary(rng: &mut TestRng, percent: usize) -> f32 {
        if rng.chance(percent) {
            rng.unit() * 4.0 - 2.0
        } else {
            HOSTILE[rng.below(HOSTILE.len())]
        }
    }

    /// The SIMD paths this CPU has.
    fn paths() -> impl Iterator<Item = Path> {
        [Path::Baseline, Path::Avx2].into_iter().filter(|p| p.supported())
    }

    /// Every NaN in `values` is the CPU's default NaN.
    fn only_default_nans(values: &[f32]) -> bool {
        let nan = default_nan().to_bits();
        values.iter().all(|x| !x.is_nan() || x.to_bits() == nan)
    }

    /// The per-triangle solve on every SIMD path: the listing's `sdir` and `tdir` (any NaN for
    /// any NaN, and then the default one) and the orientation flag its definition gives.
    #[test]
    fn the_solve_gives_the_listing_and_the_orientation_flag_its_definition() {
        for path in paths() {
            let mut rng = TestRng(0x0B1E);
            let mut seen = [0usize; 3];
            for _ in 0..20_000 {
                let mut pick = || hostile_or_ordinary(&mut rng, 70);
                let v: [[f32; 3]; 3] = core::array::from_fn(|_| core::array::from_fn(|_| pick()));
                let w: [[f32; 2]; 3] = core::array::from_fn(|_| core::array::from_fn(|_| pick()));
                let normals = [[0.0, 0.0, 1.0]; 3];
                let mesh = Mesh::new(&v[..], &normals[..]).with_texcoords(&w[..]);
                let listing = Listing {
                    mesh: &mesh,
                    texcoords: mesh.texcoords.unwrap(),
                    v_sign: 1.0,
                    triangle_count: 1,
                };
                PINNED.with(|p| p.set(Some(path)));
                let (sdir, tdir, orientation) = simd::run(
                    #[inline(always)]
                    || listing.solve(0, 1, 2),
                );
                PINNED.with(|p| p.set(None));
                let what = format!("{path:?}: positions {v:?}, texture coordinates {w:?}");
                assert_eq!(orientation, defined_orientation(v, w), "{what}");
                let got = [sdir, tdir].map(|v| v.to_array());
                let same = |a: f32, b: f32| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
                let want = listing_directions(v, w);
                let agree = (0..2).all(|d| (0..3).all(|k| same(got[d][k], want[d][k])));
                assert!(agree, "{what}: {got:?}, the listing gives {want:?}");
                assert!(only_default_nans(got.as_flattened()), "{what}: {got:?}");
                seen[usize::from(orientation / 2)] += 1;
            }
            // Every outcome occurs, each many times.
            assert!(seen.iter().all(|&n| n > 1000), "{seen:?}");
        }
    }

    /// The first loop's adds, with the flags in `weight`'s bits: `tan1` and `tan2` get the
    /// listing's sums, and `weight` every flag.
    #[test]
    fn the_first_loop_keeps_the_sums_and_every_flag() {
        let terms = [
            ([1.5f32, -2.25, 3e-3], [0.5f32, 1e-3, -4.0], flag::POSITIVE_UV),
            ([0.1, 7.0, -3e-3], [-0.25, 2.0, 1e30], 0),
            ([-1.6, 1e30, 0.5], [3.0, -1e-3, 0.125], flag::NEGATIVE_UV),
        ];
        let listing_sum = |terms: [[f32; 3]; 3]| {
            terms.iter().fold([0.0f32; 3], |sum, term| {
                [sum[0] + term[0], sum[1] + term[1], sum[2] + term[2]]
            })
        };
        let (tan1, tan2) = (listing_sum(terms.map(|t| t.0)), listing_sum(terms.map(|t| t.1)));
        let mut sums = VertexSums::default();
        for (sdir, tdir, orientation) in core::hint::black_box(terms) {
            add_terms(
                &mut sums,
                (Vec3A::from_array(sdir), Vec3A::from_array(tdir), orientation),
            );
        }
        assert_eq!(sums.primary.map(f32::to_bits), tan1.map(f32::to_bits));
        assert_eq!(sums.secondary.map(f32::to_bits), tan2.map(f32::to_bits));
        assert_eq!(
            simd::marks(&sums),
            flag::REFERENCED | flag::POSITIVE_UV | flag::NEGATIVE_UV
        );
    }

    /// Every triangle with a corner in each third of the vertices: three workers solve ranges of
    /// triangles apart (two keep their terms), with the bits and report of one, per vertex and
    /// per corner, including an index out of range in a kept range.
    #[test]
    fn three_workers_solving_apart_give_the_bits_of_one() {
        let third = 300;
        let mut rng = TestRng(0x3A9F);
        let mut pick = || rng.unit() * 4.0 - 2.0;
        let positions: Vec<[f32; 3]> = (0..3 * third).map(|_| [pick(), pick(), pick()]).collect();
        let normals: Vec<[f32; 3]> = (0..3 * third).map(|_| [pick(), pick(), pick()]).collect();
        let texcoords: Vec<[f32; 2]> = (0..3 * third).map(|_| [pick(), pick()]).collect();
        let mut rng = TestRng(0x77C1);
        let mut indices: Vec<u32> = (0..600)
            .flat_map(|_| [0, 1, 2].map(|k| (k * third + rng.below(third)) as u32))
            .collect();
        let options = |threads| {
            Options::default()
                .with_method(crate::Method::Lengyel)
                .with_policy(crate::DegeneratePolicy::Legacy)
                .with_threads(threads)
        };
        for bad in [None, Some(indices.len() - 4)] {
            if let Some(corner) = bad {
                indices[corner] = 3 * third as u32;
            }
            let mesh = Mesh::new(&positions[..], &normals[..])
                .with_texcoords(&texcoords[..])
                .with_indices(&indices[..]);
            assert_eq!(parallel::workers_for(3, 600), 3);
            assert_eq!(parallel::worker_count(3, &mesh), 1, "the vertex ranges do not pay");
            let run = |threads: u32| {
                let mut frames = vec![[0.0f32; 4]; 3 * third];
                let mut corners = vec![[0.0f32; 4]; indices.len()];
                let result = crate::generate(&mesh, &options(threads), &mut Output::new(&mut frames[..]));
                let corner_result =
                    crate::generate_corners(&mesh, &options(threads), &mut StridedMut::from_slice(&mut corners[..]));
                let bits = |values: &[[f32; 4]]| values.iter().flatten().map(|x| x.to_bits()).collect::<Vec<u32>>();
                (result, corner_result, bits(&frames), bits(&corners))
            };
            let one = run(1);
            assert_eq!(one.0.is_err(), bad.is_some());
            for threads in [2, 3] {
                assert!(run(threads) == one, "threads={threads}, index out of range: {bad:?}");
            }
        }
    }

    /// A caller's stale scratch gives the bits of a zeroed one and of fresh memory, on one thread
    /// and several, per vertex and per corner, with vertices no triangle references (zero sums).
    #[test]
    fn stale_scratch_gives_the_bits_of_zeroed_memory() {
        let mut rng = TestRng(0x57A1);
        let vertex_count = 400;
        let mut pick = || rng.unit() * 4.0 - 2.0;
        let positions: Vec<[f32; 3]> = (0..vertex_count).map(|_| [pick(), pick(), pick()]).collect();
        let normals: Vec<[f32; 3]> = (0..vertex_count).map(|_| [pick(), pick(), pick()]).collect();
        let texcoords: Vec<[f32; 2]> = (0..vertex_count).map(|_| [pick(), pick()]).collect();
        // The last 100 vertices are referenced by no triangle.
        let mut rng = TestRng(0x1D7E);
        let indices: Vec<u32> = (0..3 * 500).map(|_| rng.below(vertex_count - 100) as u32).collect();
        let mesh = Mesh::new(&positions[..], &normals[..])
            .with_texcoords(&texcoords[..])
            .with_indices(&indices[..]);
        for threads in [1, 2, 8] {
            let options = Options::default()
                .with_method(crate::Method::Lengyel)
                .with_policy(crate::DegeneratePolicy::Legacy)
                .with_threads(threads);
            let size = crate::scratch_size_for(&mesh, &options).unwrap();
            let run = |scratch: Option<u8>| {
                let mut frames = vec![[0.0f32; 4]; vertex_count];
                let mut corners = vec![[0.0f32; 4]; indices.len()];
                let mut bytes = vec![scratch.unwrap_or(0); size];
                let mut output = Output::new(&mut frames[..]);
                let mut corner_output = StridedMut::from_slice(&mut corners[..]);
                match scratch {
                    Some(_) => {
                        crate::generate_with_scratch(&mesh, &options, &mut output, &mut bytes).unwrap();
                        crate::generate_corners_with_scratch(&mesh, &options, &mut corner_output, &mut bytes).unwrap();
                    }
                    None => {
                        crate::generate(&mesh, &options, &mut output).unwrap();
                        crate::generate_corners(&mesh, &options, &mut corner_output).unwrap();
                    }
                }
                let bits = |values: &[[f32; 4]]| values.iter().flatten().map(|x| x.to_bits()).collect::<Vec<u32>>();
                (bits(&frames), bits(&corners))
            };
            let fresh = run(None);
            for stale in [0x00, 0xA5, 0xFF] {
                assert!(run(Some(stale)) == fresh, "threads={threads}, scratch bytes {stale:#x}");
            }
            // An unreferenced vertex: zero sums give a NaN tangent (0 / 0) and w = 1.
            let unreferenced = &fresh.0[4 * (vertex_count - 1)..];
            assert!(f32::from_bits(unreferenced[0]).is_nan() && f32::from_bits(unreferenced[3]) == 1.0);
        }
    }

    /// The listing's loops read packed arrays as slices and other layouts through strided views,
    /// and run compiled for each SIMD path: all give the same bits, on values that reach every
    /// branch (zero and non-finite edges, overflowing `sdir`, NaNs of both signs and with payloads
    /// in every input), and every NaN written is the CPU's default one.
    #[test]
    fn packed_and_strided_arrays_give_the_same_bits_on_every_simd_path() {
        let mut rng = TestRng(0x9AC4);
        let vertex_count = 301;
        let mut pick = || hostile_or_ordinary(&mut rng, 92);
        let record: Vec<[f32; 9]> = (0..vertex_count).map(|_| core::array::from_fn(|_| pick())).collect();
        let positions: Vec<[f32; 3]> = record.iter().map(|r| [r[0], r[1], r[2]]).collect();
        let normals: Vec<[f32; 3]> = record.iter().map(|r| [r[3], r[4], r[5]]).collect();
        let texcoords: Vec<[f32; 2]> = record.iter().map(|r| [r[6], r[7]]).collect();
        let mut rng = TestRng(0x51DE);
        let indices: Vec<u32> = (0..3 * 1000).map(|_| rng.below(vertex_count) as u32).collect();
        let options = Options::default()
            .with_method(crate::Method::Lengyel)
            .with_policy(crate::DegeneratePolicy::Legacy);

        let packed = Mesh::new(&positions[..], &normals[..])
            .with_texcoords(&texcoords[..])
            .with_indices(&indices[..]);
        // The same vertices in 36-byte records, and tangents in 20-byte ones.
        let bytes: Vec<u8> = record.iter().flatten().flat_map(|x| x.to_ne_bytes()).collect();
        let view = |offset: usize| &bytes[offset..];
        let strided = Mesh::new(
            Strided::from_bytes(view(0), 36, vertex_count).unwrap(),
            Strided::from_bytes(view(12), 36, vertex_count).unwrap(),
        )
        .with_texcoords(Strided::from_bytes(view(24), 36, vertex_count).unwrap())
        .with_indices(&indices[..]);

        // Packed tangents, or the same in 20-byte records.
        let run = |path: Path, mesh: &Mesh, packed_output: bool| {
            let mut frames = vec![[0.0f32; 4]; vertex_count];
            let mut records = vec![0u8; 20 * vertex_count];
            PINNED.with(|p| p.set(Some(path)));
            let output = match packed_output {
                true => Output::new(&mut frames[..]),
                false => Output::new(StridedMut::from_bytes(&mut records, 20, vertex_count).unwrap()),
            };
            crate::generate(mesh, &options, &mut { output }).unwrap();
            PINNED.with(|p| p.set(None));
            if !packed_output {
                for (frame, record) in frames.iter_mut().zip(records.chunks(20)) {
                    *frame = core::array::from_fn(|k| f32::from_ne_bytes(record[4 * k..4 * k + 4].try_into().unwrap()));
                }
            }
            frames
        };
        let bits = |frames: &[[f32; 4]]| frames.iter().flatten().map(|x| x.to_bits()).collect::<Vec<u32>>();
        let packed_tangents = run(Path::Baseline, &packed, true);
        for path in paths() {
            for (mesh, packed_output, layout) in [(&packed, true, "packed"), (&strided, false, "strided")] {
                let tangents = run(path, mesh, packed_output);
                assert_eq!(bits(&tangents), bits(&packed_tangents), "{layout} on {path:?}");
            }
        }
        // The values reach every branch: finite frames, and frames a non-finite sum spoils.
        assert!(packed_tangents.iter().any(|t| t.iter().all(|x| x.is_finite())));
        assert!(packed_tangents.iter().any(|t| t[0].is_nan()));
        assert!(only_default_nans(packed_tangents.as_flattened()));
    }
}
