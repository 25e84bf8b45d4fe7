//! Policy INHERIT: a vertex without a measured tangent takes one from its neighbours.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::kernel::frame::orthonormalize;
use crate::kernel::frame::VertexNormal;
use crate::kernel::mesh::{Mesh, PerIndexType};
use crate::kernel::sums::{flag, wide_links, Scratch, VertexSums};
use crate::kernel::views::pod::{pod_prefix_mut, Pod};

/// Spreads resolved tangents into unresolved vertices one ring at a time, until a ring resolves
/// nothing; returns how many vertices were resolved.
///
/// Expects resolved vertices to hold their unit tangent in `primary` and handedness in `weight`,
/// and unresolved ones zeroed `secondary` and `weight`; leaves the unresolved ones so.
///
/// In a ring, each unresolved vertex `v` sums, over the triangles using it in ascending order
/// (twice for a triangle that uses it twice), the tangents and handedness of that triangle's
/// corners, in corner order, that were resolved before the ring (Jacobi order); then every `v`
/// whose sum has a usable component in its tangent plane is resolved from it. The sums are
/// built in exactly that order, so the bits do not depend on how the rings are found.
///
/// A vertex's sum changes only when a vertex it shares a triangle with was resolved in the ring
/// before, so each ring visits only those vertices (breadth first), through a vertex-to-triangle
/// adjacency built once. A vertex that settles is summed once; one that fails is summed again
/// only in a ring after some neighbour resolved.
pub fn propagate(mesh: &Mesh, scratch: &mut Scratch) -> usize {
    let vertex_count = mesh.vertex_count();
    assert!(
        scratch.first == 0 && scratch.flags.len() == vertex_count,
        "needs the whole mesh's scratch"
    );
    let triangle_count = mesh.indices.triangle_count(vertex_count).unwrap_or(0);
    let corner_count = 3 * triangle_count;
    let entries = 2 * vertex_count + corner_count;
    let bytes = scratch.links.bytes();
    let (sums, flags) = (&mut *scratch.sums, &mut *scratch.flags);
    if wide_links(vertex_count, corner_count) {
        let links = pod_prefix_mut::<[u32; 2]>(bytes, entries)
            .expect("scratch holds the adjacency")
            .0;
        spread(mesh, triangle_count, sums, flags, links)
    } else {
        let links = pod_prefix_mut::<u32>(bytes, entries)
            .expect("scratch holds the adjacency")
            .0;
        spread(mesh, triangle_count, sums, flags, links)
    }
}

/// An entry of the adjacency: a vertex, a triangle or a position in the triangle list.
trait Link: Pod {
    fn new(value: usize) -> Self;
    fn get(self) -> usize;
}

impl Link for u32 {
    #[inline(always)]
    fn new(value: usize) -> Self {
        value as u32
    }
    #[inline(always)]
    fn get(self) -> usize {
        self as usize
    }
}

impl Link for [u32; 2] {
    #[inline(always)]
    fn new(value: usize) -> Self {
        let value = value as u64;
        [value as u32, (value >> 32) as u32]
    }
    #[inline(always)]
    fn get(self) -> usize {
        (u64::from(self[0]) | (u64::from(self[1]) << 32)) as usize
    }
}

/// [`propagate`] with `links` (`2 * vertex_count + 3 * triangle_count` entries, any contents) as
/// its working memory.
fn spread<L: Link>(
    mesh: &Mesh,
    triangle_count: usize,
    sums: &mut [VertexSums],
    flags: &mut [u8],
    links: &mut [L],
) -> usize {
    mesh.indices.with_corner_reader(Spread {
        mesh,
        triangle_count,
        sums,
        flags,
        links,
    })
}

/// The state of one [`spread`], run once per index type.
struct Spread<'a, 'm, L> {
    mesh: &'a Mesh<'m>,
    triangle_count: usize,
    sums: &'a mut [VertexSums],
    flags: &'a mut [u8],
    links: &'a mut [L],
}

impl<L: Link> PerIndexType for Spread<'_, '_, L> {
    type Output = usize;

    fn run(self, corners: impl Fn(usize) -> [usize; 3]) -> usize {
        let Spread {
            mesh,
            triangle_count,
            sums,
            flags,
            links,
        } = self;
        let vertex_count = flags.len();
        let (starts, rest) = links.split_at_mut(vertex_count);
        let (triangles, queue) = rest.split_at_mut(3 * triangle_count);
        let adjacency = Adjacency::build(&corners, triangle_count, flags, starts, triangles);
        // Neither resolved nor already queued for the next ring.
        let unqueued = |flags: &[u8], v: usize| flags[v] & (flag::RESOLVED | flag::CANDIDATE) == 0;

        // The first ring's candidates: the unresolved corners of triangles with a resolved corner.
        let mut queued = 0;
        for t in 0..triangle_count {
            let corners = corners(t);
            if corners.iter().any(|&u| flags[u] & flag::RESOLVED != 0) {
                for u in corners {
                    if unqueued(flags, u) {
                        flags[u] |= flag::CANDIDATE;
                        queue[queued] = L::new(u);
                        queued += 1;
                    }
                }
            }
        }

        // `queue[..frontier]`: the vertices the last ring resolved; `queue[frontier..queued]`: the
        // next ring's candidates. The two are disjoint, so they fit in one slot per vertex.
        let mut frontier = 0;
        let mut inherited = 0;
        while queued > frontier {
            let mut resolved = 0;
            for slot in frontier..queued {
                let v = queue[slot].get();
                flags[v] &= !flag::CANDIDATE;
                let (gathered, vote) = gather(&corners, &adjacency, sums, flags, v);
                // Candidates are settled as they are summed: only `RESOLVED` makes a vertex count
                // as a neighbour, and it is set once the ring is over.
                if let Some(tangent) = settle(mesh, v, gathered) {
                    sums[v].primary = tangent.to_array();
                    sums[v].weight = if vote < 0.0 { -1.0 } else { 1.0 };
                    // `resolved <= slot - frontier`: the slot it overwrites has been read.
                    queue[resolved] = L::new(v);
                    resolved += 1;
                }
            }
            for slot in &queue[..resolved] {
                flags[slot.get()] |= flag::RESOLVED;
            }
            inherited += resolved;

            frontier = resolved;
            queued = frontier;
            for slot in 0..frontier {
                for &t in adjacency.of(queue[slot].get()) {
                    for u in corners(t.get()) {
                        if unqueued(flags, u) {
                            flags[u] |= flag::CANDIDATE;
                            queue[queued] = L::new(u);
                            queued += 1;
                        }
                    }
                }
            }
        }
        inherited
    }
}

/// The triangles of every vertex not resolved at the start, in ascending order, once per corner
/// the vertex takes in them (the others never need theirs).
struct Adjacency<'a, L> {
    /// Where each vertex's triangles start in `triangles`; they end where the next vertex's start.
    starts: &'a [L],
    triangles: &'a [L],
    /// Entries in use in `triangles`.
    len: usize,
}

impl<'a, L: Link> Adjacency<'a, L> {
    /// A counting sort of the corners of unresolved vertices by vertex.
    fn build(
        corners: &impl Fn(usize) -> [usize; 3],
        triangle_count: usize,
        flags: &[u8],
        starts: &'a mut [L],
        triangles: &'a mut [L],
    ) -> Self {
        let wanted = |v: usize| flags[v] & flag::RESOLVED == 0;
        starts.fill(L::new(0));
        for t in 0..triangle_count {
            for v in corners(t) {
                if wanted(v) {
                    starts[v] = L::new(starts[v].get() + 1);
                }
            }
        }
        // Each start becomes its range's end; filling from the last triangle down moves it back
        // to the range's beginning and leaves each range ascending.
        let mut len = 0;
        for start in starts.iter_mut() {
            len += start.get();
            *start = L::new(len);
        }
        for t in (0..triangle_count).rev() {
            for v in corners(t) {
                if wanted(v) {
                    let at = starts[v].get() - 1;
                    starts[v] = L::new(at);
                    triangles[at] = L::new(t);
                }
            }
        }
        Adjacency { starts, triangles, len }
    }

    /// The triangles of vertex `v`, once per corner of `v` in them.
    #[inline(always)]
    fn of(&self, v: usize) -> &[L] {
        let end = self.starts.get(v + 1).map_or(self.len, |end| end.get());
        &self.triangles[self.starts[v].get()..end]
    }
}

/// Vertex `v`'s sum of the tangents and handedness of its neighbours resolved before this ring,
/// in the order [`propagate`] describes.
#[inline(always)]
fn gather<L: Link>(
    corners: &impl Fn(usize) -> [usize; 3],
    adjacency: &Adjacency<L>,
    sums: &[VertexSums],
    flags: &[u8],
    v: usize,
) -> (Vec3, f32) {
    // Unresolved vertices keep zeroed accumulators: start from them, as every ring does.
    let mut gathered = Vec3::from_array(sums[v].secondary);
    let mut vote = sums[v].weight;
    for &t in adjacency.of(v) {
        for u in corners(t.get()) {
            if flags[u] & flag::RESOLVED != 0 {
                gathered += Vec3::from_array(sums[u].primary);
                vote += sums[u].weight;
            }
        }
    }
    (gathered, vote)
}

/// The tangent vertex `v` takes from its gathered neighbour tangents (projected into its tangent
/// plane and normalized), if enough of them is left there.
#[inline(always)]
fn settle(mesh: &Mesh, v: usize, gathered: Vec3) -> Option<Vec3> {
    let normal = VertexNormal::new(mesh.normals.get(v)).unit;
    // Neighbours' tangents are unit vectors: a remainder below 1e-3 of one is cancellation.
    match orthonormalize(gathered, normal) {
        Some((in_plane, tangent)) if in_plane > 1e-3 => Some(tangent),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::memory::{self, Arena, Place};
    use crate::kernel::mesh::Indices;
    use crate::kernel::options::{DegeneratePolicy, Method, Options};
    use crate::kernel::parallel;
    use crate::kernel::report::Report;
    use crate::kernel::sums::{self, Links};
    use crate::kernel::views::strided::Strided;
    use crate::pipelines::per_vertex::resolve_measured;

    /// Per-vertex arrays of the tests' own, kept from one look to the next.
    struct OwnedScratch {
        sums: Vec<VertexSums>,
        flags: Vec<u8>,
        links: Vec<u8>,
    }

    impl OwnedScratch {
        fn allocate(vertex_count: usize, link_bytes: usize) -> Option<Self> {
            Some(OwnedScratch {
                sums: vec![VertexSums::default(); vertex_count],
                flags: vec![0; vertex_count],
                links: vec![0; link_bytes],
            })
        }

        fn scratch(&mut self) -> Scratch<'_> {
            Scratch {
                sums: &mut self.sums,
                flags: &mut self.flags,
                first: 0,
                links: Links::Caller(&mut self.links),
            }
        }
    }

    /// What the quadratic reference saw, to prove the meshes exercise what they should.
    #[derive(Default, Debug)]
    struct Seen {
        rings: usize,
        /// Gatherings that got some neighbour tangent and still did not settle.
        failed: usize,
    }

    /// The definition [`propagate`] must match bit for bit: every ring passes over every triangle;
    /// for each corner that is unresolved, every corner of its triangle resolved before the ring
    /// adds its tangent and handedness; then every unresolved vertex is settled (Jacobi order).
    fn reference_propagate(mesh: &Mesh, sums: &mut [VertexSums], flags: &mut [u8], seen: &mut Seen) -> usize {
        let triangle_count = mesh.indices.triangle_count(mesh.vertex_count()).unwrap_or(0);
        let mut touched_vertex = vec![false; mesh.vertex_count()];
        let mut inherited = 0;
        loop {
            let mut touched = false;
            for t in 0..triangle_count {
                let corners = mesh.indices.triangle(t);
                for &v in &corners {
                    if flags[v] & flag::RESOLVED != 0 {
                        continue;
                    }
                    for &u in &corners {
                        if flags[u] & flag::RESOLVED != 0 {
                            let from = sums[u];
                            let to = &mut sums[v];
                            to.secondary = (Vec3::from_array(to.secondary) + Vec3::from_array(from.primary)).to_array();
                            to.weight += from.weight;
                            touched = true;
                            touched_vertex[v] = true;
                        }
                    }
                }
            }
            if !touched {
                return inherited;
            }
            seen.rings += 1;
            let mut ring = 0;
            for v in 0..mesh.vertex_count() {
                if flags[v] & flag::RESOLVED != 0 {
                    continue;
                }
                let sums = &mut sums[v];
                let gathered = Vec3::from_array(sums.secondary);
                let vote = sums.weight;
                sums.secondary = [0.0; 3];
                sums.weight = 0.0;
                let normal = VertexNormal::new(mesh.normals.get(v)).unit;
                match orthonormalize(gathered, normal) {
                    Some((in_plane, tangent)) if in_plane > 1e-3 => {
                        sums.primary = tangent.to_array();
                        sums.weight = if vote < 0.0 { -1.0 } else { 1.0 };
                        flags[v] |= flag::RESOLVED;
                        ring += 1;
                    }
                    _ => seen.failed += usize::from(touched_vertex[v]),
                }
                touched_vertex[v] = false;
            }
            if ring == 0 {
                return inherited;
            }
            inherited += ring;
        }
    }

    use crate::kernel::test_rng::TestRng as Rng;

    #[derive(Clone, Copy, PartialEq)]
    enum Form {
        U16,
        U32,
        Unindexed,
    }

    struct TestMesh {
        positions: Vec<[f32; 3]>,
        normals: Vec<[f32; 3]>,
        texcoords: Vec<[f32; 2]>,
        indices: Vec<u32>,
        indices16: Vec<u16>,
        form: Form,
        /// Triangles that use a vertex more than once.
        repeated: usize,
    }

    impl TestMesh {
        fn new(vertex_count: usize) -> Self {
            TestMesh {
                positions: vec![[0.0; 3]; vertex_count],
                normals: vec![[0.0, 0.0, 1.0]; vertex_count],
                texcoords: vec![[0.0; 2]; vertex_count],
                indices: Vec::new(),
                indices16: Vec::new(),
                form: Form::U32,
                repeated: 0,
            }
        }

        fn mesh(&self) -> Mesh<'_> {
            Mesh {
                positions: Strided::from_slice(&self.positions),
                normals: Strided::from_slice(&self.normals),
                texcoords: Some(Strided::from_slice(&self.texcoords)),
                indices: match self.form {
                    Form::U16 => Indices::U16(Strided::from_slice(&self.indices16)),
                    Form::U32 => Indices::U32(Strided::from_slice(&self.indices)),
                    Form::Unindexed => Indices::None,
                },
            }
        }

        /// Adds a triangle, sometimes with a corner repeated.
        fn push(&mut self, rng: &mut Rng, mut corners: [usize; 3]) {
            if rng.chance(3) {
                let k = rng.below(3);
                corners[k] = corners[(k + 1 + rng.below(2)) % 3];
            } else if rng.below(1000) < 3 {
                corners = [corners[0]; 3];
            }
            self.repeated +=
                usize::from(corners[0] == corners[1] || corners[1] == corners[2] || corners[0] == corners[2]);
            self.indices.extend(corners.map(|v| v as u32));
        }

        /// Shuffles the triangles: the sums follow triangle order, not vertex order.
        fn shuffle(&mut self, rng: &mut Rng) {
            let count = self.indices.len() / 3;
            for t in (1..count).rev() {
                let other = rng.below(t + 1);
                for k in 0..3 {
                    self.indices.swap(3 * t + k, 3 * other + k);
                }
            }
        }

        fn finish(mut self, rng: &mut Rng) -> Self {
            self.shuffle(rng);
            if self.positions.len() <= usize::from(u16::MAX) && rng.chance(30) {
                self.form = Form::U16;
                self.indices16 = self.indices.iter().map(|&i| i as u16).collect();
            }
            self
        }
    }

    /// A normal: mostly near +z (exactly +z on a `clean` mesh), sometimes along the tangents (+x,
    /// so nothing is left in its plane and the vertex cannot settle), zero, not finite or not unit
    /// length.
    fn normal(rng: &mut Rng, clean: bool) -> [f32; 3] {
        match rng.below(100) {
            0..=3 => [1.0, 0.0, 0.0],
            4 => [0.0; 3],
            5 => [f32::NAN, 0.0, 1.0],
            6 => [0.3, -0.2, 3.0],
            _ if clean => [0.0, 0.0, 1.0],
            _ => [0.2 * rng.unit() - 0.1, 0.2 * rng.unit() - 0.1, 1.0],
        }
    }

    /// A `width` x `height` grid in the z = 0 plane (u along +x; exact positions when `clean`, so
    /// that opposite tangents cancel exactly), its vertices row by row with an unreferenced vertex
    /// after every `gap` of them, some cells left out; discs where the UVs collapse to a point (the
    /// vertices inside have no tangent of their own) or are mirrored (opposite tangents meet at
    /// their rims).
    fn grid(rng: &mut Rng, width: usize, height: usize, gap: usize, clean: bool) -> TestMesh {
        let id = |i: usize, j: usize| {
            let k = j * width + i;
            k + k / gap
        };
        let mut mesh = TestMesh::new(id(width - 1, height - 1) + 2);
        for v in 0..mesh.positions.len() {
            mesh.positions[v] = [rng.unit(), rng.unit(), rng.unit()];
            mesh.normals[v] = normal(rng, clean);
        }
        // 0: plain, 1: mirrored, 2: collapsed.
        let mut kind = vec![0u8; width * height];
        let discs = 1 + width * height / 120;
        for d in 0..discs + discs / 3 {
            let r = 1.0 + rng.unit() * 6.0;
            let (cx, cy) = (rng.unit() * width as f32, rng.unit() * height as f32);
            let rows = (cy - r).max(0.0) as usize..((cy + r) as usize + 1).min(height);
            for j in rows {
                for i in (cx - r).max(0.0) as usize..((cx + r) as usize + 1).min(width) {
                    let (dx, dy) = (i as f32 - cx, j as f32 - cy);
                    if dx * dx + dy * dy <= r * r {
                        kind[j * width + i] = kind[j * width + i].max(if d < discs { 2 } else { 1 });
                    }
                }
            }
        }
        let jitter = if clean { 0.0 } else { 0.2 };
        for j in 0..height {
            for i in 0..width {
                let (x, y) = (i as f32, j as f32);
                let v = id(i, j);
                mesh.positions[v] = [x + jitter * rng.unit(), y + jitter * rng.unit(), jitter * rng.unit()];
                mesh.texcoords[v] = match kind[j * width + i] {
                    0 => [0.0625 * x, 0.0625 * y],
                    1 => [-0.0625 * x, 0.0625 * y],
                    _ => [0.25, 0.75],
                };
            }
        }
        for j in 0..height - 1 {
            for i in 0..width - 1 {
                if rng.chance(2) {
                    continue;
                }
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if rng.chance(50) {
                    mesh.push(rng, [a, b, c]);
                    mesh.push(rng, [a, c, d]);
                } else {
                    mesh.push(rng, [a, b, d]);
                    mesh.push(rng, [b, c, d]);
                }
            }
        }
        mesh.finish(rng)
    }

    /// Triangles among nearby vertex numbers (a long, thin, tangled strip), random positions, and
    /// runs of vertices sharing one UV.
    fn strip(rng: &mut Rng) -> TestMesh {
        let vertex_count = 8 + rng.below(300);
        let mut mesh = TestMesh::new(vertex_count);
        let mut v = 0;
        while v < vertex_count {
            let run = 1 + rng.below(12);
            let collapsed = rng.chance(50);
            let point = [rng.unit(), rng.unit()];
            for w in v..(v + run).min(vertex_count) {
                mesh.positions[w] = [w as f32 * 0.3 + rng.unit(), rng.unit(), rng.unit()];
                mesh.normals[w] = normal(rng, false);
                mesh.texcoords[w] = if collapsed { point } else { [rng.unit(), rng.unit()] };
            }
            v += run;
        }
        let isolated: Vec<bool> = (0..vertex_count).map(|_| rng.chance(5)).collect();
        let near = |rng: &mut Rng, v: usize| {
            let w = (v + rng.below(7)).saturating_sub(3).min(vertex_count - 1);
            if isolated[w] {
                v
            } else {
                w
            }
        };
        for _ in 0..rng.below(3 * vertex_count) {
            let a = rng.below(vertex_count);
            if isolated[a] {
                continue;
            }
            let corners = [a, near(rng, a), near(rng, a)];
            mesh.push(rng, corners);
        }
        mesh.finish(rng)
    }

    /// A triangle soup: no vertex shared, so nothing to inherit.
    fn soup(rng: &mut Rng) -> TestMesh {
        let mut mesh = strip(rng);
        let count = mesh.positions.len() / 3 * 3;
        mesh.positions.truncate(count);
        mesh.normals.truncate(count);
        mesh.texcoords.truncate(count);
        mesh.form = Form::Unindexed;
        mesh
    }

    /// A copy of a scratch's sums and flags (without room for the adjacency).
    fn copy(owned: &mut OwnedScratch) -> OwnedScratch {
        let from = owned.scratch();
        let mut copy = OwnedScratch::allocate(from.flags.len(), 0).unwrap();
        let to = copy.scratch();
        to.sums.copy_from_slice(from.sums);
        to.flags.copy_from_slice(from.flags);
        copy
    }

    /// The scratch state after steps 3 to 5, the deferred count and the report.
    fn measured(mesh: &Mesh, options: &Options, owned: &mut OwnedScratch) -> (usize, Report) {
        let mut report = Report::default();
        let deferred = resolve_measured(mesh, options, &mut owned.scratch(), None, &mut report).unwrap();
        (deferred, report)
    }

    fn bits(sums: &[VertexSums]) -> Vec<[u32; 7]> {
        sums.iter()
            .map(|s| {
                let [a, b, c] = s.primary;
                let [d, e, f] = s.secondary;
                [a, b, c, s.weight, d, e, f].map(f32::to_bits)
            })
            .collect()
    }

    /// Per mesh, for 1, 2 and 8 threads: the state before propagation is the same, and
    /// [`propagate`] leaves exactly the reference's sums, flags and count; so it does with 8-byte
    /// entries and (`caller`) in caller bytes at an odd address. Returns how many vertices waited
    /// for their neighbours and how many of them inherited.
    fn check(
        test: &TestMesh,
        method: Method,
        flip_v: bool,
        caller: bool,
        what: &str,
        seen: &mut Seen,
    ) -> (usize, usize) {
        let mesh = test.mesh();
        let vertex_count = mesh.vertex_count();
        let links = sums::link_bytes(DegeneratePolicy::Inherit, vertex_count, mesh.corner_count()).unwrap();
        let options = |threads| Options {
            method,
            degenerate_policy: DegeneratePolicy::Inherit,
            flip_v,
            threads,
            ..Options::default()
        };
        let mut runs: Vec<_> = [1, 2, 8]
            .into_iter()
            .map(|threads| {
                let mut owned = OwnedScratch::allocate(vertex_count, links).unwrap();
                let (deferred, _) = measured(&mesh, &options(threads), &mut owned);
                (threads, deferred, owned)
            })
            .collect();
        let deferred = runs[0].1;
        let before = bits(runs[0].2.scratch().sums);
        let mut wide = copy(&mut runs[0].2);
        let mut expected = copy(&mut runs[0].2);
        let reference = expected.scratch();
        let inherited = reference_propagate(&mesh, reference.sums, reference.flags, seen);
        let (expected_sums, expected_flags) = (bits(reference.sums), reference.flags.to_vec());

        for (threads, again, owned) in &mut runs {
            let what = format!("{what}, {threads} threads");
            let mut scratch = owned.scratch();
            assert_eq!(*again, deferred, "{what}: deferred");
            assert!(bits(scratch.sums) == before, "{what}: state before");
            assert_eq!(propagate(&mesh, &mut scratch), inherited, "{what}: count");
            assert!(bits(scratch.sums) == expected_sums, "{what}: sums");
            assert!(scratch.flags == expected_flags.as_slice(), "{what}: flags");
        }

        let wide = wide.scratch();
        let triangle_count = mesh.corner_count() / 3;
        let mut entries = vec![[u32::MAX; 2]; 2 * vertex_count + 3 * triangle_count];
        let count = spread(&mesh, triangle_count, wide.sums, wide.flags, &mut entries);
        assert_eq!(count, inherited, "{what}, 8-byte entries: count");
        assert!(bits(wide.sums) == expected_sums, "{what}, 8-byte entries: sums");
        assert!(wide.flags == expected_flags.as_slice(), "{what}, 8-byte entries: flags");

        if caller {
            let size = memory::vertex_arrays_bytes(vertex_count, links, Place::Caller).unwrap();
            let (mut bytes, mut unused) = (vec![0xA5u8; size + 1], Vec::new());
            let mut scratch = memory::vertex_arrays(
                &mut Arena::Carve(&mut bytes[1..]),
                vertex_count,
                links,
                (Place::Caller, 1),
                &mut unused,
            )
            .unwrap();
            resolve_measured(&mesh, &options(1), &mut scratch, None, &mut Report::default()).unwrap();
            assert_eq!(
                propagate(&mesh, &mut scratch),
                inherited,
                "{what}, caller scratch: count"
            );
            assert!(bits(scratch.sums) == expected_sums, "{what}, caller scratch: sums");
            assert!(
                scratch.flags == expected_flags.as_slice(),
                "{what}, caller scratch: flags"
            );
        }
        (deferred, inherited)
    }

    const METHODS: [Method; 4] = [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform];

    #[test]
    fn propagate_matches_the_quadratic_definition_on_random_meshes() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut seen = Seen::default();
        let (mut inherited, mut repeated, mut fell_back, mut split) = (0, 0, 0, 0);
        for case in 0..240 {
            let test = match case % 8 {
                0..=3 => strip(&mut rng),
                4..=6 => {
                    let (width, height, gap) = (2 + rng.below(40), 2 + rng.below(40), 1 + rng.below(50));
                    grid(&mut rng, width, height, gap, case % 2 == 0)
                }
                _ => soup(&mut rng),
            };
            let method = METHODS[case % 4];
            let what = format!("case {case} ({} vertices, {method:?})", test.positions.len());
            let (deferred, resolved) = check(&test, method, rng.chance(50), true, &what, &mut seen);
            inherited += resolved;
            fell_back += deferred - resolved;
            repeated += test.repeated;
            split += usize::from(parallel::worker_count(8, &test.mesh()) > 1);
        }
        // The meshes do what they are for: many rings, vertices that fail to settle, repeated
        // corners, vertices nothing reaches, several workers.
        assert!(
            seen.rings > 500 && seen.failed > 100 && split > 100,
            "{seen:?}, {split} split"
        );
        assert!(
            inherited > 1000 && repeated > 100 && fell_back > 100,
            "{inherited} {repeated} {fell_back}"
        );
    }

    #[test]
    fn propagate_matches_the_quadratic_definition_on_several_workers() {
        let mut rng = Rng(0x0123_4567_89ab_cdef);
        let test = grid(&mut rng, 150, 150, 97, true);
        let mesh = test.mesh();
        for (threads, workers) in [(1, 1), (2, 2), (8, 8)] {
            assert_eq!(parallel::worker_count(threads, &mesh), workers, "{threads} threads");
        }
        let mut seen = Seen::default();
        let (_, inherited) = check(&test, Method::Angle, false, false, "150 x 150 grid", &mut seen);
        assert!(
            inherited > 1000 && seen.rings > 5 && seen.failed > 0,
            "{inherited} {seen:?}"
        );
    }
}
