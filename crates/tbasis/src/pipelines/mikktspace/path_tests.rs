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
    // Corners per way: by value, replayed for the attributes, replayed for the last run.
    let mut corners = [0usize; 3];
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
            let way = match path {
                WeldPath::ByValue => 0,
                WeldPath::ReplayedForAttributes => 1,
                WeldPath::ReplayedForLastRun => 2,
            };
            corners[way] += indices.len();
            lines.push(format!("{} #{p}: {} corners, {path:?}", row.path, indices.len()));
        }
    }
    eprintln!("{}", lines.join("\n"));
    let [by_value, for_attributes, for_last_run] = corners;
    eprintln!(
        "corners welded by value: {by_value}; replayed for their attributes: {for_attributes}; \
         replayed for the last run: {for_last_run}"
    );
    // Each way is taken somewhere: none goes untested by the corpus.
    assert!(by_value > 0, "no corpus mesh welds by value");
    assert!(
        for_attributes > 0,
        "no corpus mesh has attributes the weld by value declines"
    );
    assert!(for_last_run > 0, "no corpus mesh needs the last run replayed");
}
