//! Which way each corpus mesh's weld takes ([`super::WeldPath`]), so that a fast path no mesh
//! uses shows up.
#![forbid(unsafe_code)]

use super::{compute, scratch_bytes, WeldPath};
use crate::kernel::mesh::Mesh;
use crate::kernel::options::Options;
use crate::kernel::report::Report;
use tbasis_test_support::{load, needs, scenes};

/// The weld `compute` took on one mesh.
fn path_of(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    texcoords: &[[f32; 2]],
    indices: &[u32],
    flip_v: bool,
) -> WeldPath {
    let mesh = Mesh::new(positions, normals)
        .with_texcoords(texcoords)
        .with_indices(indices);
    let options = Options::mikktspace().with_flip_v(flip_v);
    let mut bytes = vec![0u8; scratch_bytes(positions.len(), indices.len()).expect("a scratch size")];
    let (_, path) = compute(&mesh, &options, &mut bytes, &mut Report::default()).expect("a result");
    path
}

#[test]
fn the_benchmark_torus_welds_by_value() {
    let torus = scenes::build(&scenes::SceneSpec::torus(20_000));
    let path = path_of(
        &torus.positions,
        &torus.normals,
        &torus.texcoords,
        &torus.indices,
        false,
    );
    assert_eq!(path, WeldPath::ByValue);
}

#[test]
fn every_corpus_mesh_reports_the_weld_it_takes() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    let mut corners = [0usize; 2];
    let mut lines = Vec::new();
    for row in load::read_manifest(&dir).expect("MANIFEST.tsv") {
        // Debug builds leave out the largest meshes, as the corpus tests do.
        if cfg!(debug_assertions) && row.vertices > 200_000 {
            continue;
        }
        let file = load::load(&dir, &row).expect("a corpus file");
        for (p, primitive) in file.primitives.iter().enumerate() {
            let Some(texcoords) = &primitive.texcoords else {
                continue;
            };
            let (positions, normals, indices) = (&primitive.positions, &primitive.normals, &primitive.indices);
            let path = path_of(positions, normals, texcoords, indices, primitive.v_down);
            corners[usize::from(path == WeldPath::Replayed)] += indices.len();
            lines.push(format!("{} #{p}: {} corners, {path:?}", row.path, indices.len()));
        }
    }
    eprintln!("{}", lines.join("\n"));
    eprintln!(
        "corners welded by value: {}, by replaying the splitting: {}",
        corners[0], corners[1]
    );
    assert!(corners[0] > 0, "no corpus mesh welds by value");
    assert!(
        corners[1] > 0,
        "no corpus mesh replays the splitting: that path goes untested here"
    );
}
