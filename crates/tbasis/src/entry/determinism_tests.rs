//! Neither `threads = N` nor the SIMD path the CPU takes changes a bit, on random meshes of up to
//! 10k vertices.
//!
//! Under `cfg(test)` a worker needs only 8 triangles instead of thousands, so these small meshes
//! really are split across 2 and 8 workers, at every place a range boundary can fall: shared
//! vertices, degenerate and collapsed-UV triangles, mirror folds, vertices to inherit from far
//! away.
#![forbid(unsafe_code)]

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

use crate::kernel::simd::{self, Path};
use crate::kernel::test_rng::TestRng;
use crate::{
    generate, generate_corners, DegeneratePolicy, Error, Indices, Mesh, Method, Options, Output, Report, Strided,
    StridedMut,
};

/// A mesh drawn from a seed: positions on a wavy sheet, UVs that are smooth, mirrored on one side
/// and collapsed in patches, triangles mostly between nearby vertices (so a split pays off and
/// the workers really run) with a few long ones across ranges.
#[derive(Debug)]
pub(crate) struct RandomMesh {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    indices: Option<Vec<u32>>,
}

impl RandomMesh {
    pub(crate) fn new(vertex_count: usize, seed: u64, indexed: bool) -> Self {
        let mut bits = TestRng(seed | 1);
        let width = (vertex_count as f32).sqrt().ceil() as usize;
        let mut mesh = RandomMesh {
            positions: Vec::with_capacity(vertex_count),
            normals: Vec::with_capacity(vertex_count),
            texcoords: Vec::with_capacity(vertex_count),
            indices: None,
        };
        for v in 0..vertex_count {
            let (x, y) = ((v % width) as f32, (v / width) as f32);
            let z = (0.3 * x).sin() * (0.2 * y).cos() + 0.1 * bits.unit();
            mesh.positions.push([x + 0.4 * bits.unit(), y + 0.4 * bits.unit(), z]);
            let normal = match bits.below(50) {
                0 => [0.0; 3],
                1 => [f32::NAN, 0.0, 1.0],
                _ => [0.2 * bits.unit() - 0.1, 0.2 * bits.unit() - 0.1, 1.0],
            };
            mesh.normals.push(normal);
            // Mirrored left of x = width/2; collapsed to a point in some rows; quantised in others.
            let u = if 2 * (v % width) < width { -x } else { x } / width as f32;
            let uv = match (v / width) % 7 {
                3 => [0.5, 0.5],
                5 => [(u * 4.0).round() / 4.0, (y / 8.0).round()],
                _ => [u + 0.01 * bits.unit(), y / width as f32],
            };
            mesh.texcoords.push(uv);
        }
        if vertex_count < 3 {
            mesh.indices = indexed.then(Vec::new);
            return mesh;
        }
        let mut indices = Vec::with_capacity(6 * vertex_count);
        for v in 0..vertex_count {
            for _ in 0..2 {
                let near = |bits: &mut TestRng| (v + bits.below(2 * width + 2)).min(vertex_count - 1) as u32;
                let far = bits.below(vertex_count) as u32;
                let second = near(&mut bits);
                let third = if bits.below(40) == 0 { far } else { near(&mut bits) };
                indices.extend([v as u32, second, third]);
            }
        }
        if indexed {
            mesh.indices = Some(indices);
        } else {
            // Each corner its own vertex, as an unindexed mesh stores them.
            let corner = |list: &Vec<[f32; 3]>| indices.iter().map(|&i| list[i as usize]).collect::<Vec<_>>();
            let texcoords = indices.iter().map(|&i| mesh.texcoords[i as usize]).collect();
            mesh = RandomMesh {
                positions: corner(&mesh.positions),
                normals: corner(&mesh.normals),
                texcoords,
                indices: None,
            };
        }
        mesh
    }

    /// The same indexed mesh with its vertices in a random order, as some exporters leave them:
    /// nearly every triangle then has corners in every range of vertices.
    pub(crate) fn shuffled(mut self, seed: u64) -> Self {
        let Some(indices) = &mut self.indices else {
            return self;
        };
        let mut bits = TestRng(seed.rotate_left(17) | 1);
        let mut new_of: Vec<u32> = (0..self.positions.len() as u32).collect();
        for i in (1..new_of.len()).rev() {
            new_of.swap(i, bits.below(i + 1));
        }
        fn moved<T: Copy>(list: &mut Vec<T>, new_of: &[u32]) {
            let mut out = list.clone();
            for (old, &new) in new_of.iter().enumerate() {
                out[new as usize] = list[old];
            }
            *list = out;
        }
        moved(&mut self.positions, &new_of);
        moved(&mut self.normals, &new_of);
        moved(&mut self.texcoords, &new_of);
        for index in indices.iter_mut() {
            *index = new_of[*index as usize];
        }
        self
    }

    pub(crate) fn mesh(&self) -> Mesh<'_> {
        Mesh {
            positions: Strided::from_slice(&self.positions),
            normals: Strided::from_slice(&self.normals),
            texcoords: Some(Strided::from_slice(&self.texcoords)),
            indices: match &self.indices {
                Some(indices) => Indices::U32(Strided::from_slice(indices)),
                None => Indices::None,
            },
        }
    }
}

/// Every method.
pub(crate) const METHODS: [Method; 5] = [
    Method::Lengyel,
    Method::Angle,
    Method::Area,
    Method::Uniform,
    Method::Mikktspace,
];

/// Everything a call gives back, as bits.
#[derive(Debug, PartialEq)]
pub(crate) struct Outcome {
    result: Result<Report, Error>,
    vertex_bits: Vec<u32>,
    corner_result: Result<Report, Error>,
    corner_bits: Vec<u32>,
}

/// `generate` and `generate_corners` on `mesh`.
pub(crate) fn run(mesh: &RandomMesh, options: &Options) -> Outcome {
    let mesh_view = mesh.mesh();
    let mut tangents = vec![[0.0f32; 4]; mesh.positions.len()];
    let mut bitangents = vec![[0.0f32; 3]; mesh.positions.len()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: Some(StridedMut::from_slice(&mut bitangents)),
    };
    let result = generate(&mesh_view, options, &mut output);
    let mut corners = vec![[0.0f32; 4]; mesh_view.corner_count()];
    let corner_result = generate_corners(&mesh_view, options, &mut StridedMut::from_slice(&mut corners));
    let vertex_bits = tangents.iter().flatten().chain(bitangents.iter().flatten());
    Outcome {
        result,
        vertex_bits: vertex_bits.map(|x| x.to_bits()).collect(),
        corner_result,
        corner_bits: corners.iter().flatten().map(|x| x.to_bits()).collect(),
    }
}

/// Vertex counts spread evenly over orders of magnitude, 0 to 10k.
fn vertex_count() -> impl Strategy<Value = usize> {
    (0u32..=400).prop_map(|step| (10f64.powf(f64::from(step) / 100.0) as usize).saturating_sub(1))
}

proptest! {
    #![proptest_config(Config {
        cases: 12,
        rng_seed: RngSeed::Fixed(0x7EAD_5EED),
        failure_persistence: None,
        ..Config::default()
    })]

    #[test]
    fn every_method_and_policy_gives_the_same_bits_on_1_2_and_8_threads(
        vertex_count in vertex_count(),
        seed in any::<u64>(),
        indexed in prop::bool::weighted(0.8),
        shuffled in any::<bool>(),
    ) {
        let mesh = RandomMesh::new(vertex_count, seed, indexed);
        let mesh = if shuffled { mesh.shuffled(seed) } else { mesh };
        let policies = [
            DegeneratePolicy::Legacy,
            DegeneratePolicy::Skip,
            DegeneratePolicy::Inherit,
            DegeneratePolicy::Reject,
        ];
        for method in METHODS {
            for policy in policies {
                if policy == DegeneratePolicy::Legacy && !method.has_legacy_form() {
                    continue;
                }
                let options = Options { method, degenerate_policy: policy, ..Options::default() };
                let one = run(&mesh, &Options { threads: 1, ..options });
                for threads in [2, 8] {
                    let many = run(&mesh, &Options { threads, ..options });
                    prop_assert!(
                        many == one,
                        "{method:?} {policy:?}, {vertex_count} vertices: threads={threads} differs from 1"
                    );
                }
            }
        }
    }
}

#[test]
fn shuffled_meshes_are_split_by_triangles() {
    for vertex_count in [1000, 10_000] {
        let mesh = RandomMesh::new(vertex_count, 7, true).shuffled(7);
        // Each half of the vertices has a corner of 7 triangles in 8: vertex ranges do not pay,
        // and the workers solve or measure ranges of triangles.
        assert_eq!(crate::kernel::parallel::worker_count(2, &mesh.mesh()), 1);
        assert_eq!(
            crate::kernel::parallel::workers_for(2, mesh.mesh().corner_count() / 3),
            2
        );
    }
}

#[test]
fn the_random_meshes_are_split_across_workers() {
    for vertex_count in [1000, 10_000] {
        let mesh = RandomMesh::new(vertex_count, 7, true);
        for threads in [2, 8] {
            let workers = crate::kernel::parallel::worker_count(threads, &mesh.mesh());
            assert_eq!(workers, threads as usize, "{vertex_count} vertices, threads={threads}");
        }
    }
}

/// On random meshes with mirror folds, collapsed and quantised UVs, zero and NaN normals, long
/// triangles (above), indexed and not, and with the triangles shuffled, on one thread and two
/// (whose workers follow the pinned path): every method and policy, per vertex and per corner.
#[test]
fn every_supported_simd_path_gives_the_same_bits() {
    let paths = simd::tests::supported_paths();
    let policies = [
        DegeneratePolicy::Skip,
        DegeneratePolicy::Inherit,
        DegeneratePolicy::Legacy,
    ];
    let cases = [
        (3000, 11, true, 1),
        (5000, 12, true, 1),
        (1000, 13, false, 1),
        (3000, 14, true, 2),
    ];
    for (vertex_count, seed, indexed, threads) in cases {
        // Shuffled, two threads measure ranges of triangles apart and add them in order.
        let mesh = match threads {
            1 => RandomMesh::new(vertex_count, seed, indexed),
            _ => RandomMesh::new(vertex_count, seed, indexed).shuffled(seed),
        };
        let valid = |&(method, policy): &(Method, DegeneratePolicy)| {
            policy != DegeneratePolicy::Legacy || method.has_legacy_form()
        };
        for (method, policy) in METHODS.into_iter().flat_map(|m| policies.map(|p| (m, p))).filter(valid) {
            let options = Options::default()
                .with_method(method)
                .with_policy(policy)
                .with_threads(threads);
            let along = |path: Path| simd::tests::along(path, || run(&mesh, &options));
            let baseline = along(Path::Baseline);
            for &path in &paths[1..] {
                assert!(
                    along(path) == baseline,
                    "{method:?} {policy:?}: {path:?} differs from the baseline"
                );
            }
        }
    }
}

/// A shuffled mesh with an index out of range in a late triangle: the workers that measure ranges
/// of triangles apart stop together, every thread count reports the same first bad triangle, and
/// the output stays as it was.
#[test]
fn an_index_out_of_range_stops_every_worker() {
    for shuffled in [true, false] {
        let mesh = RandomMesh::new(3000, 15, true);
        let mut mesh = if shuffled { mesh.shuffled(15) } else { mesh };
        let indices = mesh.indices.as_mut().expect("indexed");
        let bad = indices.len() - 7;
        indices[bad] = 3000;
        // Triangles measured apart, or vertex ranges whose workers skip blocks by their bounds.
        let workers = if shuffled { 1 } else { 2 };
        assert_eq!(crate::kernel::parallel::worker_count(2, &mesh.mesh()), workers);
        index_out_of_range_stops_every_worker(&mesh, bad);
    }
}

/// [`an_index_out_of_range_stops_every_worker`] on one mesh, whose index `bad` is 3000.
fn index_out_of_range_stops_every_worker(mesh: &RandomMesh, bad: usize) {
    let configurations = [
        (Method::Angle, DegeneratePolicy::Inherit),
        (Method::Lengyel, DegeneratePolicy::Inherit),
        (Method::Area, DegeneratePolicy::Inherit),
        (Method::Lengyel, DegeneratePolicy::Legacy),
    ];
    for (method, policy) in configurations {
        for threads in [1, 2, 8] {
            let options = Options::default()
                .with_method(method)
                .with_policy(policy)
                .with_threads(threads);
            let outcome = run(mesh, &options);
            let error = Error::IndexOutOfRange {
                triangle: bad / 3,
                index: 3000,
                vertex_count: 3000,
            };
            assert_eq!(
                outcome.result,
                Err(error.clone()),
                "{method:?} {policy:?}, threads={threads}"
            );
            assert_eq!(
                outcome.corner_result,
                Err(error),
                "{method:?} {policy:?}, threads={threads}"
            );
            assert!(outcome.vertex_bits.iter().chain(&outcome.corner_bits).all(|&b| b == 0));
        }
    }
}

/// Where the workers take vertex ranges, a packed index buffer lets them skip blocks of triangles
/// by their bounds; a strided one does not. Both give the same bits on every thread count.
#[test]
fn a_strided_index_buffer_gives_the_bits_of_a_packed_one() {
    let mesh = RandomMesh::new(3000, 21, true);
    assert_eq!(crate::kernel::parallel::worker_count(2, &mesh.mesh()), 2);
    let indices = mesh.indices.as_ref().expect("indexed");
    // Each index beside a word of padding: a stride of 8 bytes.
    let padded: Vec<[u32; 2]> = indices.iter().map(|&i| [i, u32::MAX]).collect();
    let bytes: Vec<u8> = padded.iter().flatten().flat_map(|w| w.to_ne_bytes()).collect();
    let strided = Strided::<u32>::from_bytes(&bytes, 8, indices.len()).expect("a valid view");
    assert!(strided.packed().is_none());
    let bits = |mesh: &Mesh, options: &Options| {
        let mut corners = vec![[0.0f32; 4]; mesh.corner_count()];
        let result = generate_corners(mesh, options, &mut StridedMut::from_slice(&mut corners));
        (
            result,
            corners.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>(),
        )
    };
    let configurations = [
        (Method::Lengyel, DegeneratePolicy::Legacy),
        (Method::Angle, DegeneratePolicy::Inherit),
        (Method::Uniform, DegeneratePolicy::Skip),
    ];
    for (method, policy) in configurations {
        let options = Options::default().with_method(method).with_policy(policy);
        let packed = bits(&mesh.mesh(), &options.with_threads(1));
        for threads in [1, 2, 8] {
            let options = options.with_threads(threads);
            let through_stride = Mesh {
                indices: Indices::U32(strided),
                ..mesh.mesh()
            };
            assert_eq!(
                bits(&through_stride, &options),
                packed,
                "{method:?} {policy:?}, strided, {threads}"
            );
            assert_eq!(
                bits(&mesh.mesh(), &options),
                packed,
                "{method:?} {policy:?}, packed, {threads}"
            );
        }
    }
}
