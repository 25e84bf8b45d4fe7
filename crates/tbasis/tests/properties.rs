//! Property tests: random small meshes with adversarial values (NaN, infinities, signed zeros,
//! subnormals, 1e-30 .. f32::MAX), random topology (out-of-range and repeated indices, index counts
//! that are not multiples of 3), in random memory layouts (separate strided buffers with padding
//! and unaligned starts, or one interleaved vertex record holding inputs and outputs), with every
//! policy, method and a random threshold and `flip_v`.
//!
//! For every call: it does not panic; the status is the one the input's construction calls for;
//! on an error no byte anywhere changed; on success no byte outside the output elements changed,
//! every frame keeps the invariants (all policies but LEGACY), the report agrees with what the
//! mesh's construction says, and the results are bit for bit those of the same mesh in packed
//! arrays.

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::Config;
use tbasis::{
    scratch_size, scratch_size_for, scratch_size_for_counts, DegeneratePolicy, ErrorKind, Indices, Mesh, Method,
    Options, Output, Report, Strided, StridedMut, DEFAULT_DEGENERATE_THRESHOLD,
};
use tbasis_test_support::invariants::{check_invariants, unit_normal};
use tbasis_test_support::run::generate_into;

/// Values that break naive arithmetic: non-finite, signed zeros, subnormals, extremes.
const SPECIALS: [f32; 18] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -0.0,
    1e-45, // the smallest subnormal
    -1e-45,
    f32::MIN_POSITIVE * 0.5, // a subnormal
    f32::MIN_POSITIVE,
    1e-30,
    -1e-30,
    1e-20,
    1e20,
    1e30,
    -1e30,
    f32::MAX,
    f32::MIN,
    f32::EPSILON,
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum IndexKind {
    None,
    U16,
    U32,
}

/// How the texture coordinates are shaped after being drawn.
#[derive(Clone, Copy, Debug)]
enum UvShape {
    Random,
    AllEqual,
    Collinear,
    Scaled(f32),
}

/// How the normals are shaped after being drawn.
#[derive(Clone, Copy, Debug)]
enum NormalShape {
    Unit,
    Raw,
    Zero,
    NegativeZ,
}

/// A mesh as plain arrays; `indices` holds the values as stored (already cut to 16 bits for U16).
#[derive(Clone, Debug)]
struct MeshData {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    texcoords: Option<Vec<[f32; 2]>>,
    kind: IndexKind,
    indices: Vec<u32>,
}

impl MeshData {
    fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    fn index_count(&self) -> usize {
        match self.kind {
            IndexKind::None => self.vertex_count(),
            _ => self.indices.len(),
        }
    }

    /// Vertices of the complete triangles.
    fn corners(&self) -> Vec<usize> {
        match self.kind {
            IndexKind::None => (0..self.vertex_count()).collect(),
            _ => self.indices.iter().map(|&i| i as usize).collect(),
        }
    }
}

fn position() -> impl Strategy<Value = f32> {
    // Half steps make coincident and collinear corners (zero-area triangles) common.
    prop_oneof![3 => -2.0f32..2.0, 1 => (-4i32..=4).prop_map(|k| k as f32 * 0.5)]
}

fn texcoord() -> impl Strategy<Value = f32> {
    prop_oneof![3 => -1.0f32..2.0, 1 => (0i32..=4).prop_map(|k| k as f32 * 0.25)]
}

fn uv_shape() -> impl Strategy<Value = UvShape> {
    prop_oneof![
        8 => Just(UvShape::Random),
        1 => Just(UvShape::AllEqual),
        1 => Just(UvShape::Collinear),
        2 => prop::sample::select(vec![1e-20f32, 1e-3, 1e3, 1e20]).prop_map(UvShape::Scaled),
    ]
}

fn normal_shape() -> impl Strategy<Value = NormalShape> {
    prop_oneof![
        6 => Just(NormalShape::Unit),
        2 => Just(NormalShape::Raw),
        1 => Just(NormalShape::Zero),
        1 => Just(NormalShape::NegativeZ),
    ]
}

fn index_kind() -> impl Strategy<Value = IndexKind> {
    prop_oneof![Just(IndexKind::None), Just(IndexKind::U16), Just(IndexKind::U32)]
}

/// A special value for `(attribute, vertex, component)`.
type Special = (usize, Index, usize, f32);

prop_compose! {
    fn mesh_data()(
        drawn_count in 0usize..64,
        kind in index_kind(),
        whole_triangles in prop::bool::weighted(0.9),
        has_texcoords in prop::bool::weighted(0.9),
    )(
        positions in vec([position(), position(), position()], vertex_count(drawn_count, kind, whole_triangles)),
        normals in vec([-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0], vertex_count(drawn_count, kind, whole_triangles)),
        texcoords in vec([texcoord(), texcoord()], vertex_count(drawn_count, kind, whole_triangles)),
        uv_shape in uv_shape(),
        normal_shape in normal_shape(),
        triangles in vec([any::<Index>(), any::<Index>(), any::<Index>()], 0..40),
        specials in prop_oneof![
            1 => Just(Vec::<Special>::new()),
            1 => vec((0usize..3, any::<Index>(), 0usize..3, prop::sample::select(SPECIALS.to_vec())), 1..5),
        ],
        out_of_range in prop::option::weighted(
            0.06,
            (any::<Index>(), prop::sample::select(vec![0u32, 1, 2, 65_535, u32::MAX])),
        ),
        dangling in prop_oneof![20 => Just(0usize), 1 => 1usize..3],
        kind in Just(kind),
        has_texcoords in Just(has_texcoords),
    ) -> MeshData {
        let shapes = (uv_shape, normal_shape);
        let topology = (kind, &triangles[..], out_of_range, dangling);
        build_mesh(positions, normals, has_texcoords.then_some(texcoords), shapes, topology, &specials)
    }
}

/// Unindexed meshes need a multiple of 3 vertices; most draws respect that.
fn vertex_count(drawn: usize, kind: IndexKind, whole_triangles: bool) -> usize {
    if kind == IndexKind::None && whole_triangles {
        drawn - drawn % 3
    } else {
        drawn
    }
}

/// Triangles as drawn, one index to make out of range, and how many indices to leave dangling.
type Topology<'a> = (IndexKind, &'a [[Index; 3]], Option<(Index, u32)>, usize);

fn build_mesh(
    positions: Vec<[f32; 3]>,
    mut normals: Vec<[f32; 3]>,
    mut texcoords: Option<Vec<[f32; 2]>>,
    (uv_shape, normal_shape): (UvShape, NormalShape),
    (kind, triangles, out_of_range, dangling): Topology,
    specials: &[Special],
) -> MeshData {
    let n = positions.len();
    for uv in texcoords.iter_mut().flatten() {
        match uv_shape {
            UvShape::Random => {}
            UvShape::AllEqual => *uv = [0.25, 0.5],
            UvShape::Collinear => uv[1] = 0.5 * uv[0] + 0.125,
            UvShape::Scaled(s) => *uv = uv.map(|x| x * s),
        }
    }
    for normal in &mut normals {
        *normal = match normal_shape {
            NormalShape::Unit => {
                let length = normal.iter().map(|x| x * x).sum::<f32>().sqrt();
                if length > 1e-3 {
                    normal.map(|x| x / length)
                } else {
                    [0.0, 0.0, 1.0]
                }
            }
            NormalShape::Raw => *normal,
            NormalShape::Zero => [0.0; 3],
            NormalShape::NegativeZ => [0.0, 0.0, -1.0],
        };
    }
    let mut mesh = MeshData {
        positions,
        normals,
        texcoords,
        kind,
        indices: Vec::new(),
    };
    for &(attribute, vertex, component, value) in specials {
        if n == 0 {
            break;
        }
        let v = vertex.index(n);
        match attribute {
            0 => mesh.positions[v][component] = value,
            1 => mesh.normals[v][component] = value,
            _ => {
                if let Some(uvs) = &mut mesh.texcoords {
                    uvs[v][component % 2] = value;
                }
            }
        }
    }
    if kind != IndexKind::None {
        if n > 0 {
            mesh.indices = triangles.iter().flatten().map(|i| i.index(n) as u32).collect();
        }
        if let Some((at, value)) = out_of_range {
            // At least n: out of range for any count, also once cut to 16 bits (n < 64).
            let bad = if value < 3 { n as u32 + value } else { value };
            let bad = if kind == IndexKind::U16 {
                u32::from(bad as u16)
            } else {
                bad
            };
            if mesh.indices.is_empty() {
                mesh.indices.extend([bad; 3]);
            } else {
                let k = at.index(mesh.indices.len());
                mesh.indices[k] = bad;
            }
        }
        for _ in 0..dangling {
            mesh.indices.push(0);
        }
    }
    mesh
}

const METHODS: [Method; 4] = [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform];
const ROBUST_POLICIES: [DegeneratePolicy; 3] = [
    DegeneratePolicy::Skip,
    DegeneratePolicy::Inherit,
    DegeneratePolicy::Reject,
];

fn options() -> impl Strategy<Value = Options> {
    let method = prop::sample::select(METHODS.to_vec());
    let mut policies = ROBUST_POLICIES.to_vec();
    policies.push(DegeneratePolicy::Legacy);
    let policy = prop::sample::select(policies);
    let threshold = prop_oneof![
        6 => Just(DEFAULT_DEGENERATE_THRESHOLD),
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => 0.0f32..0.2,
        1 => Just(1e-30f32),
        1 => Just(0.95f32),
        1 => prop::sample::select(vec![-1e-6f32, f32::NAN, f32::INFINITY, f32::NEG_INFINITY]),
    ];
    (method, policy, threshold, any::<bool>()).prop_map(|(method, policy, threshold, flip_v)| {
        Options::default()
            .with_method(method)
            .with_policy(policy)
            .with_flip_v(flip_v)
            .with_degenerate_threshold(threshold)
            .with_threads(0)
    })
}

/// Buffers: positions, normals, texcoords, tangents, bitangents.
const FIELDS: usize = 5;
const SIZES: [usize; FIELDS] = [12, 12, 8, 16, 12];
const TANGENTS: usize = 3;
const BITANGENTS: usize = 4;

/// Where the index buffer's elements sit: `pad` bytes between them, `offset` bytes before.
#[derive(Clone, Copy, Debug)]
struct IndexPlacement {
    pad: usize,
    offset: usize,
}

#[derive(Clone, Debug)]
enum Layout {
    /// One buffer per field, element `i` at `offsets[f] + i * (SIZES[f] + pads[f])`.
    Separate {
        pads: [usize; FIELDS],
        offsets: [usize; FIELDS],
        /// One view (normals, texcoords, tangents or bitangents) one element longer or shorter.
        miscount: Option<(usize, bool)>,
    },
    /// One buffer of vertex records holding every field, in `order`, `gaps[f]` bytes before
    /// field `f`, `tail` bytes after the last, the first record at byte `base`. With `overlap`,
    /// the tangent is moved onto the positions (or normals) plus a shift: bytes shared.
    Interleaved {
        order: Vec<usize>,
        gaps: [usize; FIELDS],
        tail: usize,
        base: usize,
        overlap: Option<(bool, usize)>,
    },
}

fn layout() -> impl Strategy<Value = Layout> {
    let separate = (
        [0usize..10, 0usize..10, 0usize..10, 0usize..10, 0usize..10],
        [0usize..4, 0usize..4, 0usize..4, 0usize..4, 0usize..4],
        prop::option::weighted(0.05, (1usize..5, any::<bool>())),
    )
        .prop_map(|(pads, offsets, miscount)| Layout::Separate {
            pads,
            offsets,
            miscount,
        });
    let interleaved = (
        Just((0..FIELDS).collect::<Vec<_>>()).prop_shuffle(),
        [0usize..6, 0usize..6, 0usize..6, 0usize..6, 0usize..6],
        0usize..8,
        0usize..8,
        prop::option::weighted(0.1, (any::<bool>(), 0usize..12)),
    )
        .prop_map(|(order, gaps, tail, base, overlap)| Layout::Interleaved {
            order,
            gaps,
            tail,
            base,
            overlap,
        });
    prop_oneof![separate, interleaved]
}

#[derive(Clone, Debug)]
struct Scenario {
    mesh: MeshData,
    options: Options,
    layout: Layout,
    indices: IndexPlacement,
    bitangents: bool,
    /// Caller scratch: its start offset, and whether it is 4 bytes short.
    scratch: Option<(usize, bool)>,
    salt: u8,
}

prop_compose! {
    fn scenario()(
        mesh in mesh_data(),
        options in options(),
        layout in layout(),
        index_pad in 0usize..4,
        index_offset in 0usize..4,
        bitangents in any::<bool>(),
        scratch in prop::option::weighted(0.25, (0usize..4, prop::bool::weighted(0.2))),
        salt in any::<u8>(),
    ) -> Scenario {
        Scenario {
            mesh,
            options,
            layout,
            indices: IndexPlacement { pad: index_pad, offset: index_offset },
            bitangents,
            scratch,
            salt,
        }
    }
}

/// Bytes no call should touch: a pattern that differs from byte to byte.
fn garbage(len: usize, salt: u8) -> Vec<u8> {
    (0..len)
        .map(|i| (i as u8).wrapping_mul(37).wrapping_add(salt) ^ 0x5A)
        .collect()
}

const GUARD: usize = 24;

fn put(buffer: &mut [u8], at: usize, values: &[f32]) {
    for (k, x) in values.iter().enumerate() {
        buffer[at + 4 * k..at + 4 * k + 4].copy_from_slice(&x.to_ne_bytes());
    }
}

fn get<const N: usize>(buffer: &[u8], at: usize) -> [f32; N] {
    core::array::from_fn(|k| f32::from_ne_bytes(buffer[at + 4 * k..at + 4 * k + 4].try_into().unwrap()))
}

/// The index buffer: values at `offset + i * stride`, garbage around them.
fn index_buffer(mesh: &MeshData, placement: IndexPlacement, salt: u8) -> (Vec<u8>, usize) {
    let size = if mesh.kind == IndexKind::U16 { 2 } else { 4 };
    let stride = size + placement.pad;
    let mut bytes = garbage(
        placement.offset + mesh.indices.len() * stride + GUARD,
        salt.wrapping_add(11),
    );
    for (i, &value) in mesh.indices.iter().enumerate() {
        let at = placement.offset + i * stride;
        match mesh.kind {
            IndexKind::U16 => bytes[at..at + 2].copy_from_slice(&(value as u16).to_ne_bytes()),
            _ => bytes[at..at + 4].copy_from_slice(&value.to_ne_bytes()),
        }
    }
    (bytes, stride)
}

fn index_view<'a>(mesh: &MeshData, bytes: &'a [u8], placement: IndexPlacement, stride: usize) -> Indices<'a> {
    let bytes = &bytes[placement.offset..];
    let count = mesh.indices.len();
    match mesh.kind {
        IndexKind::None => Indices::None,
        IndexKind::U16 => Indices::U16(Strided::from_bytes(bytes, stride, count).unwrap()),
        IndexKind::U32 => Indices::U32(Strided::from_bytes(bytes, stride, count).unwrap()),
    }
}

/// What one call did, read back from the caller's memory.
struct Outcome {
    result: Result<(), ErrorKind>,
    report: Report,
    /// Every buffer before and after the call, with a mask of the bytes the call may write.
    buffers: Vec<(Vec<u8>, Vec<u8>, Vec<bool>)>,
    tangents: Vec<[f32; 4]>,
    bitangents: Option<Vec<[f32; 3]>>,
    /// Whether the layout shares output bytes with inputs.
    overlapping: bool,
    /// Whether some view's length differs from the vertex count.
    miscounted: bool,
}

/// A report no call produces, to tell whether one was written.
fn unwritten_report() -> Report {
    Report {
        degenerate_triangles: 12_345,
        first_degenerate_triangle: Some(12_345),
        fallback_vertices: 12_345,
        mirrored_vertices: 12_345,
        unreferenced_vertices: 12_345,
        inherited_vertices: 12_345,
        abnormal_normals: 12_345,
        repaired_corners: 12_345,
        split_vertices: 12_345,
    }
}

/// Runs the call with caller scratch as the scenario says.
fn call(s: &Scenario, mesh: &Mesh, output: &mut Output, report: &mut Report) -> Result<(), ErrorKind> {
    match s.scratch {
        None => generate_into(mesh, &s.options, output, None, report),
        Some((offset, short)) => {
            let needed = scratch_size_for(mesh, &s.options).unwrap();
            let size = if short { needed.saturating_sub(4) } else { needed };
            let mut scratch = vec![0u8; offset + size];
            generate_into(mesh, &s.options, output, Some(&mut scratch[offset..]), report)
        }
    }
}

fn run_separate(
    s: &Scenario,
    pads: [usize; FIELDS],
    offsets: [usize; FIELDS],
    miscount: Option<(usize, bool)>,
) -> Outcome {
    let m = &s.mesh;
    let n = m.vertex_count();
    // View lengths: the vertex count, except one miscounted view when drawn.
    let mut counts = [n; FIELDS];
    let mut miscounted = false;
    if let Some((field, longer)) = miscount {
        let present = match field {
            2 => m.texcoords.is_some(),
            BITANGENTS => s.bitangents,
            _ => true,
        };
        if present && (longer || n > 0) {
            counts[field] = if longer { n + 1 } else { n - 1 };
            miscounted = true;
        }
    }
    let strides: [usize; FIELDS] = core::array::from_fn(|f| SIZES[f] + pads[f]);
    let mut buffers: Vec<Vec<u8>> = (0..FIELDS)
        .map(|f| {
            garbage(
                offsets[f] + counts[f] * strides[f] + GUARD,
                s.salt.wrapping_add(f as u8 * 50),
            )
        })
        .collect();
    let element = |f: usize, i: usize| offsets[f] + i * strides[f];
    for i in 0..counts[0] {
        put(&mut buffers[0], element(0, i), &m.positions[i]);
    }
    for i in 0..counts[1] {
        put(
            &mut buffers[1],
            element(1, i),
            &m.normals.get(i).copied().unwrap_or([0.0, 0.0, 1.0]),
        );
    }
    if let Some(uvs) = &m.texcoords {
        for i in 0..counts[2] {
            put(&mut buffers[2], element(2, i), &uvs.get(i).copied().unwrap_or([0.0; 2]));
        }
    }
    let (index_bytes, index_stride) = index_buffer(m, s.indices, s.salt);
    let before: Vec<Vec<u8>> = buffers.iter().chain([&index_bytes]).cloned().collect();

    let mut report = unwritten_report();
    let result = {
        let [positions, normals, texcoords, tangents, bitangents] = &mut buffers[..] else {
            unreachable!()
        };
        let mesh = Mesh {
            positions: Strided::from_bytes(&positions[offsets[0]..], strides[0], counts[0]).unwrap(),
            normals: Strided::from_bytes(&normals[offsets[1]..], strides[1], counts[1]).unwrap(),
            texcoords: m
                .texcoords
                .as_ref()
                .map(|_| Strided::from_bytes(&texcoords[offsets[2]..], strides[2], counts[2]).unwrap()),
            indices: index_view(m, &index_bytes, s.indices, index_stride),
        };
        let mut output = Output {
            tangents: StridedMut::from_bytes(&mut tangents[offsets[3]..], strides[3], counts[3]).unwrap(),
            bitangents: s
                .bitangents
                .then(|| StridedMut::from_bytes(&mut bitangents[offsets[4]..], strides[4], counts[4]).unwrap()),
        };
        call(s, &mesh, &mut output, &mut report)
    };

    let tangents = (0..counts[3]).map(|i| get(&buffers[3], element(3, i))).collect();
    let bitangents = s
        .bitangents
        .then(|| (0..counts[4]).map(|i| get(&buffers[4], element(4, i))).collect());
    let mut masks: Vec<Vec<bool>> = before.iter().map(|b| vec![false; b.len()]).collect();
    for f in [TANGENTS, BITANGENTS] {
        if f == BITANGENTS && !s.bitangents {
            continue;
        }
        for i in 0..counts[f] {
            masks[f][element(f, i)..element(f, i) + SIZES[f]].fill(true);
        }
    }
    let after = buffers.into_iter().chain([index_bytes]);
    Outcome {
        result,
        report,
        buffers: zip3(before, after, masks),
        tangents,
        bitangents,
        overlapping: false,
        miscounted,
    }
}

#[allow(clippy::too_many_arguments)]
fn run_interleaved(
    s: &Scenario,
    order: &[usize],
    gaps: [usize; FIELDS],
    tail: usize,
    base: usize,
    overlap: Option<(bool, usize)>,
) -> Outcome {
    let m = &s.mesh;
    let n = m.vertex_count();
    let present = |f: usize| match f {
        2 => m.texcoords.is_some(),
        BITANGENTS => s.bitangents,
        _ => true,
    };
    let mut field_offset = [0usize; FIELDS];
    let mut end = 0;
    for &f in order.iter().filter(|&&f| present(f)) {
        field_offset[f] = end + gaps[f];
        end = field_offset[f] + SIZES[f];
    }
    if let Some((onto_normals, shift)) = overlap {
        field_offset[TANGENTS] = field_offset[usize::from(onto_normals)] + shift;
        end = end.max(field_offset[TANGENTS] + SIZES[TANGENTS]);
    }
    let stride = end + tail;
    let at = |f: usize, i: usize| base + i * stride + field_offset[f];
    let mut bytes = garbage(base + n.max(1) * stride + GUARD, s.salt);
    for i in 0..n {
        put(&mut bytes, at(0, i), &m.positions[i]);
        put(&mut bytes, at(1, i), &m.normals[i]);
        if let Some(uvs) = &m.texcoords {
            put(&mut bytes, at(2, i), &uvs[i]);
        }
    }
    let (index_bytes, index_stride) = index_buffer(m, s.indices, s.salt);
    let before = vec![bytes.clone(), index_bytes.clone()];

    let mut report = unwritten_report();
    let base_ptr = bytes.as_mut_ptr();
    let result = {
        // SAFETY: every view stays inside `bytes` (n records of `stride` bytes from `base`, each
        // field inside its record, at least one record allocated), and `bytes` is not otherwise
        // touched while the views live. Inputs and outputs share no byte unless `overlap`, which
        // the library must refuse before writing.
        let (mesh, mut output) = unsafe {
            let field = |f: usize| base_ptr.add(base + field_offset[f]);
            let mesh = Mesh {
                positions: Strided::from_raw(field(0), stride, n),
                normals: Strided::from_raw(field(1), stride, n),
                texcoords: m.texcoords.as_ref().map(|_| Strided::from_raw(field(2), stride, n)),
                indices: index_view(m, &index_bytes, s.indices, index_stride),
            };
            let output = Output {
                tangents: StridedMut::from_raw(field(TANGENTS), stride, n),
                bitangents: s.bitangents.then(|| StridedMut::from_raw(field(BITANGENTS), stride, n)),
            };
            (mesh, output)
        };
        call(s, &mesh, &mut output, &mut report)
    };

    let tangents = (0..n).map(|i| get(&bytes, at(TANGENTS, i))).collect();
    let bitangents = s
        .bitangents
        .then(|| (0..n).map(|i| get(&bytes, at(BITANGENTS, i))).collect());
    let mut mask = vec![false; bytes.len()];
    for i in 0..n {
        mask[at(TANGENTS, i)..at(TANGENTS, i) + 16].fill(true);
        if s.bitangents {
            mask[at(BITANGENTS, i)..at(BITANGENTS, i) + 12].fill(true);
        }
    }
    let index_mask = vec![false; index_bytes.len()];
    let masks = [mask, index_mask];
    let after = [bytes, index_bytes];
    Outcome {
        result,
        report,
        buffers: zip3(before, after, masks),
        tangents,
        bitangents,
        overlapping: overlap.is_some() && n > 0,
        miscounted: false,
    }
}

/// A call on packed arrays and what it wrote.
struct Packed {
    result: Result<(), ErrorKind>,
    tangents: Vec<[f32; 4]>,
    bitangents: Vec<[f32; 3]>,
}

/// The same call on the same mesh in packed arrays, without caller scratch.
fn run_packed(s: &Scenario) -> Packed {
    let m = &s.mesh;
    let n = m.vertex_count();
    let short: Vec<u16> = m.indices.iter().map(|&i| i as u16).collect();
    let mut tangents = vec![[0.0f32; 4]; n];
    let mut bitangents = vec![[0.0f32; 3]; n];
    let mesh = Mesh {
        positions: Strided::from_slice(&m.positions),
        normals: Strided::from_slice(&m.normals),
        texcoords: m.texcoords.as_deref().map(Strided::from_slice),
        indices: match m.kind {
            IndexKind::None => Indices::None,
            IndexKind::U16 => Indices::U16(Strided::from_slice(&short)),
            IndexKind::U32 => Indices::U32(Strided::from_slice(&m.indices)),
        },
    };
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: s.bitangents.then(|| StridedMut::from_slice(&mut bitangents)),
    };
    let result = generate_into(&mesh, &s.options, &mut output, None, &mut Report::default());
    Packed {
        result,
        tangents,
        bitangents,
    }
}

/// The error the input's construction calls for, in the order the library checks, or `None`
/// when the call must succeed (or, under REJECT, may refuse degenerate triangles).
fn predicted_error(s: &Scenario, outcome: &Outcome) -> Option<ErrorKind> {
    let m = &s.mesh;
    let n = m.vertex_count();
    let threshold = s.options.degenerate_threshold;
    if !threshold.is_finite() || threshold < 0.0 {
        return Some(ErrorKind::InvalidThreshold);
    }
    if s.options.degenerate_policy == DegeneratePolicy::Legacy && !s.options.method.has_legacy_form() {
        return Some(ErrorKind::NoLegacyForm);
    }
    if outcome.miscounted {
        return Some(ErrorKind::LengthMismatch);
    }
    if m.texcoords.is_none() && s.options.degenerate_policy == DegeneratePolicy::Legacy {
        return Some(ErrorKind::MissingTexcoords);
    }
    if m.index_count() % 3 != 0 {
        return Some(ErrorKind::InvalidIndexCount);
    }
    if outcome.overlapping {
        return Some(ErrorKind::Overlap);
    }
    if s.scratch.is_some_and(|(_, short)| short) && n > 0 {
        return Some(ErrorKind::ScratchTooSmall);
    }
    if m.corners().iter().any(|&v| v >= n) {
        return Some(ErrorKind::IndexOutOfRange);
    }
    None
}

/// Normals the library must count as abnormal: (surely, possibly), the band between allowing
/// for its f32 test of `|length^2 - 1| <= 2e-3`.
fn abnormal_bounds(normals: &[[f32; 3]]) -> (usize, usize) {
    let mut sure = 0;
    let mut possible = 0;
    for n in normals {
        let length = unit_normal(*n).map(|_| n.iter().map(|&x| f64::from(x).powi(2)).sum::<f64>().sqrt());
        match length {
            None => {
                sure += 1;
                possible += 1;
            }
            Some(l) => {
                let off = (l - 1.0).abs();
                sure += usize::from(off > 1.01e-3);
                possible += usize::from(off > 0.99e-3);
            }
        }
    }
    (sure, possible)
}

fn check_report(s: &Scenario, report: &Report, refused: bool) -> Result<(), TestCaseError> {
    let m = &s.mesh;
    let n = m.vertex_count();
    let triangles = m.index_count() / 3;
    let policy = s.options.degenerate_policy;
    let r = report;
    let mut used = vec![false; n];
    m.corners().iter().for_each(|&v| used[v] = true);
    let unreferenced = used.iter().filter(|&&u| !u).count();

    prop_assert_eq!(r.unreferenced_vertices, unreferenced);
    prop_assert!(r.degenerate_triangles <= triangles);
    match r.first_degenerate_triangle {
        None => prop_assert_eq!(r.degenerate_triangles, 0),
        Some(first) => {
            prop_assert!(r.degenerate_triangles > 0);
            prop_assert!(first < triangles);
            prop_assert!(r.degenerate_triangles <= triangles - first);
        }
    }
    prop_assert!(r.mirrored_vertices <= n - unreferenced);
    prop_assert!(r.fallback_vertices + r.inherited_vertices <= n);
    if refused {
        prop_assert!(r.degenerate_triangles > 0);
        prop_assert_eq!((r.fallback_vertices, r.inherited_vertices), (0, 0));
        return Ok(());
    }
    match policy {
        DegeneratePolicy::Legacy => {
            prop_assert_eq!(
                (r.fallback_vertices, r.inherited_vertices, r.abnormal_normals),
                (0, 0, 0)
            );
        }
        _ => {
            // A vertex no triangle uses has nothing but its normal.
            prop_assert!(r.fallback_vertices >= unreferenced);
            let (sure, possible) = abnormal_bounds(&m.normals);
            prop_assert!(
                (sure..=possible).contains(&r.abnormal_normals),
                "abnormal normals {} not in {}..={}",
                r.abnormal_normals,
                sure,
                possible
            );
            if policy != DegeneratePolicy::Inherit {
                prop_assert_eq!(r.inherited_vertices, 0);
            }
            if policy == DegeneratePolicy::Reject {
                prop_assert_eq!(r.degenerate_triangles, 0);
            }
            if m.texcoords.is_none() {
                prop_assert_eq!(r.fallback_vertices, n);
                prop_assert_eq!((r.degenerate_triangles, r.mirrored_vertices), (0, 0));
            }
        }
    }
    Ok(())
}

fn check(s: &Scenario) -> Result<(), TestCaseError> {
    let outcome = match &s.layout {
        Layout::Separate {
            pads,
            offsets,
            miscount,
        } => run_separate(s, *pads, *offsets, *miscount),
        Layout::Interleaved {
            order,
            gaps,
            tail,
            base,
            overlap,
        } => run_interleaved(s, order, *gaps, *tail, *base, *overlap),
    };
    let predicted = predicted_error(s, &outcome);
    let policy = s.options.degenerate_policy;
    match (predicted, outcome.result) {
        (Some(e), result) => prop_assert_eq!(result, Err(e)),
        (None, Ok(())) => {}
        (None, Err(ErrorKind::DegenerateUv)) if policy == DegeneratePolicy::Reject => {}
        (None, Err(e)) => prop_assert!(false, "unexpected {:?}", e),
    }

    if let Err(error) = outcome.result {
        for (k, (before, after, _)) in outcome.buffers.iter().enumerate() {
            prop_assert!(before == after, "buffer {} changed on {:?}", k, error);
        }
        if error == ErrorKind::DegenerateUv {
            check_report(s, &outcome.report, true)?;
        } else {
            prop_assert_eq!(outcome.report, unwritten_report(), "report written on {:?}", error);
        }
        return Ok(());
    }

    for (k, (before, after, mask)) in outcome.buffers.iter().enumerate() {
        let changed = (0..before.len()).find(|&i| !mask[i] && before[i] != after[i]);
        prop_assert!(
            changed.is_none(),
            "buffer {} byte {:?} outside the outputs changed",
            k,
            changed
        );
    }
    check_report(s, &outcome.report, false)?;
    if policy != DegeneratePolicy::Legacy {
        if let Err(e) = check_invariants(&s.mesh.normals, &outcome.tangents, outcome.bitangents.as_deref()) {
            prop_assert!(false, "{}", e);
        }
    }

    // The layout (strides, alignment, interleaving, scratch) must not change a single bit.
    let Packed {
        result,
        tangents,
        bitangents,
    } = run_packed(s);
    prop_assert_eq!(result, Ok(()));
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (v, (a, b)) in outcome.tangents.iter().zip(&tangents).enumerate() {
        prop_assert_eq!(bits(a), bits(b), "tangent {} differs from the packed run", v);
    }
    if let Some(strided) = &outcome.bitangents {
        for (v, (a, b)) in strided.iter().zip(&bitangents).enumerate() {
            prop_assert_eq!(bits(a), bits(b), "bitangent {} differs from the packed run", v);
        }
    }
    Ok(())
}

fn config(cases: u32) -> Config {
    tbasis_test_support::proptest_config::fixed(cases, 0x7B45_1515)
}

proptest! {
    #![proptest_config(config(512))]

    #[test]
    fn random_meshes_in_random_layouts(s in scenario()) {
        check(&s)?;
    }
}

/// Meshes that are valid in every respect but their values: every call must succeed (REJECT may
/// refuse), so the invariants are checked on many more successful calls than the general test.
fn valid_scenario() -> impl Strategy<Value = Scenario> {
    scenario().prop_map(|mut s| {
        let n = s.mesh.vertex_count();
        if s.mesh.kind == IndexKind::None {
            s.mesh.positions.truncate(n - n % 3);
            s.mesh.normals.truncate(n - n % 3);
            if let Some(uvs) = &mut s.mesh.texcoords {
                uvs.truncate(n - n % 3);
            }
        } else {
            let n = n as u32;
            s.mesh.indices.retain(|&i| i < n);
            let whole = s.mesh.indices.len() - s.mesh.indices.len() % 3;
            s.mesh.indices.truncate(whole);
        }
        if !s.options.degenerate_threshold.is_finite() || s.options.degenerate_threshold < 0.0 {
            s.options.degenerate_threshold = DEFAULT_DEGENERATE_THRESHOLD;
        }
        if s.options.degenerate_policy == DegeneratePolicy::Legacy {
            s.options.degenerate_policy = DegeneratePolicy::Inherit;
        }
        match &mut s.layout {
            Layout::Separate { miscount, .. } => *miscount = None,
            Layout::Interleaved { overlap, .. } => *overlap = None,
        }
        s.scratch = s
            .scratch
            .filter(|_| s.mesh.vertex_count() > 0)
            .map(|(offset, _)| (offset, false));
        s
    })
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn valid_meshes_always_succeed_with_sound_frames(s in valid_scenario()) {
        let policy = s.options.degenerate_policy;
        let result = run_packed(&s).result;
        prop_assert!(result.is_ok() || (policy == DegeneratePolicy::Reject && result == Err(ErrorKind::DegenerateUv)));
        check(&s)?;
    }
}

/// A unit normal at `angle` radians from the unit vector `t`, turned towards `side` (any vector
/// not parallel to `t`).
fn tilted_from(t: [f32; 3], side: [f32; 3], angle: f32) -> [f32; 3] {
    let along = side[0] * t[0] + side[1] * t[1] + side[2] * t[2];
    let perpendicular = [0, 1, 2].map(|k| side[k] - along * t[k]);
    let length = perpendicular.iter().map(|x| x * x).sum::<f32>().sqrt();
    let n = [0, 1, 2].map(|k| t[k] * angle.cos() + perpendicular[k] / length * angle.sin());
    let length = n.iter().map(|x| x * x).sum::<f32>().sqrt();
    n.map(|x| x / length)
}

proptest! {
    #![proptest_config(config(256))]

    /// One triangle whose vertex normals lie within a few milliradians of its tangent dP/du: the
    /// part of the tangent left after removing the normal is small, and must still come out
    /// orthogonal to the normal.
    #[test]
    fn tangent_nearly_parallel_to_the_normal_stays_orthogonal(
        angle in 1.1e-3f32..8e-3,
        side in [-1.0f32..1.0, -1.0f32..1.0, 1.0f32..2.0],
        method in prop::sample::select(METHODS.to_vec()),
        policy in prop::sample::select(ROBUST_POLICIES.to_vec()),
    ) {
        // Positions = UVs in z = 0: dP/du is exactly +x.
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0f32]];
        let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0f32]];
        let normals = [tilted_from([1.0, 0.0, 0.0], side, angle); 3];
        let mut tangents = [[0.0f32; 4]; 3];
        let mesh = Mesh {
            positions: Strided::from_slice(&positions),
            normals: Strided::from_slice(&normals),
            texcoords: Some(Strided::from_slice(&texcoords)),
            indices: Indices::None,
        };
        let mut output = Output {
            tangents: StridedMut::from_slice(&mut tangents),
            bitangents: None,
        };
        let options = Options::default().with_method(method).with_policy(policy);
        let mut report = Report::default();
        prop_assert_eq!(generate_into(&mesh, &options, &mut output, None, &mut report), Ok(()));
        if let Err(e) = check_invariants(&normals, &tangents, None) {
            prop_assert!(false, "{}", e);
        }
    }
}

/// `scratch_size(0)` is 0 and caller scratch may have any alignment, so an empty mesh must accept
/// an empty scratch slice wherever it starts.
#[test]
fn empty_mesh_takes_empty_scratch_at_any_alignment() {
    assert_eq!(scratch_size(0), Some(0));
    let nothing: [[f32; 3]; 0] = [];
    let mesh = Mesh {
        positions: Strided::from_slice(&nothing),
        normals: Strided::from_slice(&nothing),
        texcoords: None,
        indices: Indices::None,
    };
    let mut storage = [0u8; 8];
    let aligned = (0..4).find(|&k| storage[k..].as_ptr() as usize % 4 == 0).unwrap();
    let bytes = &mut storage[aligned..];
    for offset in 0..4 {
        let mut tangents: [[f32; 4]; 0] = [];
        let mut output = Output {
            tangents: StridedMut::from_slice(&mut tangents),
            bitangents: None,
        };
        let scratch = &mut bytes[offset..offset];
        let result = generate_into(
            &mesh,
            &Options::default(),
            &mut output,
            Some(scratch),
            &mut Report::default(),
        );
        assert_eq!(result, Ok(()), "empty scratch at byte {offset} of a 4-aligned buffer");
    }
}

/// Each buffer as (bytes before, bytes after, which bytes the call may write).
fn zip3<A, B, C>(
    a: impl IntoIterator<Item = A>,
    b: impl IntoIterator<Item = B>,
    c: impl IntoIterator<Item = C>,
) -> Vec<(A, B, C)> {
    a.into_iter().zip(b).zip(c).map(|((a, b), c)| (a, b, c)).collect()
}

/// The README's "Memory": `29 V + 3` bytes, and policy INHERIT's adjacency on top, `2 V + C`
/// entries of 4 bytes, or of 8 once `V` or `C` exceeds 2^32 - 1 (on 64-bit targets).
#[test]
fn scratch_sizes_follow_the_readme_formulas_with_narrow_and_wide_adjacency() {
    let inherit = Options::default().with_policy(DegeneratePolicy::Inherit);
    let skip = Options::default().with_policy(DegeneratePolicy::Skip);
    let wide_count = u64::from(u32::MAX) + 1;
    for (v, c) in [
        (4u64, 6u64),
        (wide_count - 1, 3),
        (3, wide_count - 1),
        (wide_count, 3),
        (3, wide_count),
    ] {
        let (Ok(vertices), Ok(corners)) = (usize::try_from(v), usize::try_from(c)) else {
            continue;
        };
        // In 64 bits, so that a size a 32-bit target cannot hold is `None` there.
        let entry = if v.max(c) > u64::from(u32::MAX) { 8 } else { 4 };
        let expected = |bytes: u64| usize::try_from(bytes).ok();
        assert_eq!(
            scratch_size_for_counts(&skip, vertices, corners),
            expected(29 * v + 3),
            "{v} vertices, {c} corners"
        );
        assert_eq!(
            scratch_size_for_counts(&inherit, vertices, corners),
            expected(29 * v + 3 + entry * (2 * v + c)),
            "{v} vertices, {c} corners"
        );
    }
}
