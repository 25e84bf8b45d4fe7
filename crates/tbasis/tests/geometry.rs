//! `tbasis::mikktspace`, the `mikktspace` crate's trait and `generate_tangents`, against
//! mikktspace.c itself through the crate mikktspace-sys (its `gen_tang_space` with the full
//! `set_tspace` callback): the same return value and, call for call, the same `set_tangent`
//! arguments, every float bit for bit (any NaN matching any NaN), on the face meshes of
//! `tbasis_test_support::face_meshes` (quads split both ways, faces of other counts, degenerate
//! and non-finite input, every triangle scene) and on every corpus mesh; at 180, 90 and 30
//! degrees, on 1 and 2 threads; and through `set_tangent_encoded`, the method a user of the
//! `mikktspace` crate implements, against `set_tspace_basic`.

use tbasis_test_support::alloc_count::{allocations, fail_allocation, Counting};
use tbasis_test_support::face_meshes::{assert_no_departures, both, departures, tbasis_calls, FaceMesh, Run};
use tbasis_test_support::{face_scenes, load, needs};

/// Counts each thread's allocations, and fails one on request.
#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn generate_tangents_makes_mikktspace_c_calls_on_generated_meshes() {
    // The trait counts faces in a usize: a negative count is mikktspace.c's alone (the C driver of
    // tests/mikktspace_dropin.rs gives one to the drop-in).
    let meshes: Vec<FaceMesh> = face_scenes::generated()
        .into_iter()
        .filter(|mesh| mesh.reported_faces >= 0)
        .collect();
    let departures: Vec<String> = meshes.iter().flat_map(departures).collect();
    assert_no_departures("generated meshes", &departures, meshes.len());
}

#[test]
fn generate_tangents_makes_mikktspace_c_calls_on_every_corpus_mesh() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    let (mut meshes, mut found, mut quad_faces) = (0, Vec::new(), 0);
    for row in load::read_manifest(&dir).expect("MANIFEST.tsv") {
        if load::left_to_optimized_builds(&row) {
            continue;
        }
        let file = load::load(&dir, &row).unwrap_or_else(|e| panic!("{}: {e}", row.path));
        for primitive in &file.primitives {
            let Some(triangles) = face_scenes::from_primitive(&row.path, primitive, false) else {
                continue;
            };
            meshes += 1;
            found.extend(departures(&triangles));
            // Paired into quads (a, b, c), (a, c, d): the corpus's quads as an exporter gave them.
            let quads = face_scenes::from_primitive(&row.path, primitive, true).expect("texture coordinates");
            quad_faces += quads.face_sizes.iter().filter(|&&size| size == 4).count();
            found.extend(departures(&quads));
        }
    }
    assert!(
        meshes >= 50 && quad_faces > 0,
        "{meshes} corpus meshes, {quad_faces} quads"
    );
    assert_no_departures("the corpus", &found, meshes);
}

#[test]
fn a_far_first_corner_behind_an_ignored_face_leaves_the_weld_box_alone() {
    // Thousands of small meshes: a widened box moves the grid on a few percent of them only.
    let meshes: Vec<FaceMesh> = (0..3000).map(face_scenes::far_first_corner).collect();
    let departures: Vec<String> = meshes.iter().flat_map(departures).collect();
    assert_no_departures("far first corners", &departures, meshes.len());
}

#[test]
fn a_failed_allocation_returns_false_with_no_call() {
    // Quads, 5-vertex faces and degenerate faces on one thread and, at 30 degrees, the pairwise
    // sub-group search with its own allocations.
    let mesh = face_scenes::random_faces(3, 80);
    for run in [Run::Default, Run::With(30.0, 1)] {
        let before = allocations();
        let (ok, calls) = tbasis_calls(&mesh, run);
        // The recording's two come first.
        let count = allocations() - before - 2;
        assert!(ok && !calls.is_empty());
        assert!(count >= 10, "{count} allocations");
        for k in 0..count {
            fail_allocation(Some(allocations() + 2 + k));
            let (ok, calls) = tbasis_calls(&mesh, run);
            fail_allocation(None);
            assert!(!ok && calls.is_empty(), "{run:?}: allocation {k} of {count} failed");
        }
        eprintln!("{run:?}: {count} allocations, each failing cleanly");
    }
}

#[test]
fn without_a_face_of_three_or_four_vertices_nothing_is_called() {
    let mut mesh = FaceMesh::new("faces of 5 and 2 vertices");
    for size in [5, 2, 5] {
        mesh.push_face((0..size).map(|k| ([k as f32, 0.0, 0.0], [0.0, 0.0, 1.0], [k as f32, 1.0])));
    }
    let [reference, ours] = both(&mesh, Run::Default);
    assert_eq!((ours.0, ours.1.len()), (false, 0));
    assert_eq!(ours, reference);
}
