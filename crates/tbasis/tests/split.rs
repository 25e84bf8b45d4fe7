//! Seam splitting (`split_corners`, `copy_split_vertices`): every corner is drawn with a vertex
//! that has its own tangent and its original attributes, no two output vertices share a source
//! vertex and a tangent, and used vertices keep their index for their first tangent. On random
//! meshes whose corners draw tangents from a small set (so that they often agree), and on the
//! MIKKTSPACE corners of every mesh of the corpus.

use proptest::prelude::*;
use std::collections::HashMap;
use tbasis::{
    copy_split_vertices, generate_corners, split_corners, Buffer, Error, ErrorKind, Indices, Mesh, Options, SeamSplit,
    Strided, StridedMut,
};
use tbasis_test_support::{load, needs};

/// Checks `split` of a mesh with `vertex_count` vertices whose corner `c` is vertex
/// `corner_vertex[c]` with tangent `tangents[c]`; `positions` is a per-vertex attribute to copy.
fn check_split(
    what: &str,
    corner_vertex: &[usize],
    tangents: &[[f32; 4]],
    positions: &[[f32; 3]],
    split: &SeamSplit,
) -> Result<(), String> {
    let vertex_count = positions.len();
    let total = vertex_count + split.sources.len();
    if split.indices.len() != corner_vertex.len() || split.sources.len() > corner_vertex.len() {
        return Err(format!(
            "{what}: {} indices, {} sources",
            split.indices.len(),
            split.sources.len()
        ));
    }
    let source_of = |n: usize| {
        if n < vertex_count {
            n
        } else {
            split.sources[n - vertex_count] as usize
        }
    };
    let mut tangent_of: Vec<Option<[u32; 4]>> = vec![None; total];
    let mut seen = vec![false; vertex_count];
    for (c, (&v, t)) in corner_vertex.iter().zip(tangents).enumerate() {
        let n = split.indices[c] as usize;
        let bits = t.map(f32::to_bits);
        if n >= total || source_of(n) != v {
            return Err(format!("{what}: corner {c} of vertex {v} is drawn with vertex {n}"));
        }
        if !std::mem::replace(&mut seen[v], true) && n != v {
            return Err(format!("{what}: vertex {v}'s first corner {c} moved to {n}"));
        }
        if *tangent_of[n].get_or_insert(bits) != bits {
            return Err(format!("{what}: corner {c} does not carry the tangent of vertex {n}"));
        }
    }
    let mut distinct = HashMap::new();
    for (n, bits) in tangent_of.iter().enumerate() {
        let Some(bits) = bits else {
            if n >= vertex_count {
                return Err(format!("{what}: appended vertex {n} is never drawn"));
            }
            continue;
        };
        if let Some(other) = distinct.insert((source_of(n), *bits), n) {
            return Err(format!("{what}: vertices {other} and {n} share vertex and tangent"));
        }
    }
    // Appended vertices copy their source's attributes, in place after the originals.
    let element = |p: &[f32; 3]| p.iter().flat_map(|x| x.to_ne_bytes()).collect::<Vec<u8>>();
    let mut bytes: Vec<u8> = positions.iter().flat_map(element).collect();
    bytes.resize(12 * total, 0xA5);
    copy_split_vertices(&mut bytes, 12, 12, vertex_count, &split.sources).map_err(|e| format!("{what}: copy: {e}"))?;
    for (n, copied) in bytes.chunks_exact(12).enumerate() {
        if copied != element(&positions[source_of(n)]) {
            return Err(format!("{what}: vertex {n} is not a copy of vertex {}", source_of(n)));
        }
    }
    Ok(())
}

fn mesh<'a>(positions: &'a [[f32; 3]], indices: Option<&'a [u32]>) -> Mesh<'a> {
    Mesh {
        positions: Strided::from_slice(positions),
        normals: Strided::from_slice(positions),
        texcoords: None,
        indices: indices.map_or(Indices::None, |i| Indices::U32(Strided::from_slice(i))),
    }
}

/// A few tangents, with +0/-0 and NaN, so that equal and differing bits both occur often.
const PALETTE: [[f32; 4]; 5] = [
    [1.0, 0.0, 0.0, 1.0],
    [1.0, 0.0, 0.0, -1.0],
    [1.0, -0.0, 0.0, 1.0],
    [0.0, 1.0, 0.0, 1.0],
    [f32::NAN, 0.0, 0.0, 1.0],
];

proptest! {
    #![proptest_config(tbasis_test_support::proptest_config::fixed(256, 0x5EA5_5117))]

    #[test]
    fn random_splits_keep_every_corner_and_nothing_more(
        vertex_count in 1usize..300,
        triangles in prop::collection::vec(([any::<prop::sample::Index>(), any::<prop::sample::Index>(), any::<prop::sample::Index>()], [0usize..5, 0usize..5, 0usize..5]), 0..200),
        palette_size in 1usize..=5,
        indexed in prop::bool::weighted(0.8),
    ) {
        let mut corner_vertex = Vec::new();
        let mut tangents = Vec::new();
        for (vertices, picks) in &triangles {
            for k in 0..3 {
                corner_vertex.push(vertices[k].index(vertex_count));
                tangents.push(PALETTE[picks[k] % palette_size]);
            }
        }
        let (positions, indices): (Vec<[f32; 3]>, Option<Vec<u32>>) = if indexed {
            let positions = (0..vertex_count).map(|v| [v as f32, 0.5, -(v as f32)]).collect();
            (positions, Some(corner_vertex.iter().map(|&v| v as u32).collect()))
        } else {
            corner_vertex = (0..corner_vertex.len()).collect();
            (corner_vertex.iter().map(|&v| [v as f32, 1.0, 2.0]).collect(), None)
        };
        let split = split_corners(&mesh(&positions, indices.as_deref()), &Strided::from_slice(&tangents))
            .map_err(|e| TestCaseError::fail(format!("split refused: {e}")))?;
        check_split("random", &corner_vertex, &tangents, &positions, &split).map_err(TestCaseError::fail)?;
    }
}

#[test]
fn bad_input_is_refused() {
    let positions = [[0.0f32; 3]; 3];
    let tangents = [PALETTE[0]; 3];
    let short = [PALETTE[0]; 2];
    let out_of_range = [0u32, 1, 3];
    let four = [0u32, 1, 2, 0];
    let split =
        |indices: Option<&[u32]>, t: &[[f32; 4]]| split_corners(&mesh(&positions, indices), &Strided::from_slice(t));
    assert_eq!(
        split(None, &short).unwrap_err(),
        Error::LengthMismatch {
            buffer: Buffer::CornerTangents,
            len: 2,
            expected: 3
        }
    );
    assert_eq!(
        split(Some(&out_of_range), &tangents).unwrap_err(),
        Error::IndexOutOfRange {
            triangle: 0,
            index: 3,
            vertex_count: 3
        }
    );
    assert_eq!(
        split(Some(&four), &[PALETTE[0]; 4]).unwrap_err(),
        Error::InvalidIndexCount { count: 4 }
    );
    assert_eq!(split(None, &tangents).map(|s| s.sources.len()), Ok(0));

    let mut bytes = [7u8; 16];
    assert_eq!(
        copy_split_vertices(&mut bytes, 4, 8, 2, &[0]),
        Err(Error::InvalidStride {
            stride: 4,
            element_size: 8
        })
    );
    assert_eq!(
        copy_split_vertices(&mut bytes, 4, 4, 2, &[2]),
        Err(Error::SourceOutOfRange {
            position: 0,
            source: 2,
            vertex_count: 2
        })
    );
    assert_eq!(
        copy_split_vertices(&mut bytes, 4, 4, 2, &[0, 1, 0]),
        Err(Error::BufferTooShort { len: 16, needed: 20 })
    );
    assert_eq!(
        copy_split_vertices(&mut bytes, usize::MAX, 4, 2, &[0]).map_err(|e| e.kind()),
        Err(ErrorKind::SizeOverflow)
    );
    assert_eq!(bytes, [7u8; 16], "an error wrote");
}

#[test]
fn every_corpus_mesh_splits_its_mikktspace_seams() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    let rows = load::read_manifest(&dir).expect("MANIFEST.tsv");
    let (mut primitives, mut appended, mut split_vertices) = (0, 0, 0);
    let mut failures = Vec::new();
    for row in &rows {
        if load::left_to_optimized_builds(row) {
            continue;
        }
        let file = load::load(&dir, row).unwrap_or_else(|e| panic!("{}: {e}", row.path));
        for (k, primitive) in file.primitives.iter().enumerate() {
            if primitive.texcoords.is_none() {
                continue;
            }
            let what = format!("{} primitive {k}", row.path);
            let options = Options::mikktspace().with_flip_v(primitive.v_down);
            let mesh = primitive.mesh();
            let mut tangents = vec![[0.0f32; 4]; mesh.corner_count()];
            let report = generate_corners(&mesh, &options, &mut StridedMut::from_slice(&mut tangents))
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let split = split_corners(&mesh, &Strided::from_slice(&tangents)).unwrap_or_else(|e| panic!("{what}: {e}"));
            let corner_vertex: Vec<usize> = primitive.indices.iter().map(|&i| i as usize).collect();
            if let Err(e) = check_split(&what, &corner_vertex, &tangents, &primitive.positions, &split) {
                failures.push(e);
            }
            // Every split vertex appends at least one copy.
            if split.sources.len() < report.split_vertices {
                failures.push(format!(
                    "{what}: {} appended, {} split",
                    split.sources.len(),
                    report.split_vertices
                ));
            }
            primitives += 1;
            appended += split.sources.len();
            split_vertices += report.split_vertices;
        }
    }
    eprintln!("{primitives} primitives: {split_vertices} split vertices, {appended} vertices appended");
    assert!(primitives > 0, "no primitive with texture coordinates");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
