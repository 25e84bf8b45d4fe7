//! `tbasis::mikktspace`, the `mikktspace` crate's interface, against mikktspace.c itself: the same
//! return value and every `setTSpace` argument bit for bit, for triangles, quads split either
//! way, faces of other sizes, every angular threshold tried, and hostile values (a NaN matches
//! any NaN, as in `mikktspace.rs`).

use tbasis_test_support::alloc_count::{allocations, fail_allocation, Counting};
use tbasis_test_support::face_meshes::{first_difference, mikktspace_c, tbasis_calls, FaceMesh};
use tbasis_test_support::{face_scenes, load, needs};

/// Counts each thread's allocations, and fails one on request.
#[global_allocator]
static GLOBAL: Counting = Counting;

/// Asserts the same return value and calls as mikktspace.c, naming the first that differs.
fn check(mesh: &FaceMesh, angular_threshold: Option<f32>, threads: u32) {
    let reference = mikktspace_c(mesh, angular_threshold);
    let ours = tbasis_calls(mesh, angular_threshold, threads);
    if let Some(difference) = first_difference(&ours, &reference) {
        panic!(
            "{} at {angular_threshold:?} degrees, {threads} threads: {difference}",
            mesh.name
        );
    }
}

#[test]
fn generated_meshes_give_mikktspace_c_calls_at_every_threshold() {
    for mesh in face_scenes::all() {
        for threshold in [None, Some(180.0), Some(90.0), Some(30.0)] {
            check(&mesh, threshold, 1);
        }
    }
}

#[test]
fn two_threads_give_the_same_calls() {
    for mesh in face_scenes::all() {
        check(&mesh, None, 2);
        check(&mesh, Some(60.0), 2);
    }
}

#[test]
fn no_face_of_three_or_four_vertices_returns_false_with_no_call() {
    let mut mesh = face_scenes::random_faces(1, 10);
    mesh.sizes.iter_mut().for_each(|s| *s = if *s == 5 { 5 } else { 2 });
    for (start, size) in mesh.starts.clone().into_iter().zip(mesh.sizes.clone()) {
        assert!(start + size <= mesh.positions.len());
    }
    check(&mesh, None, 1);
    assert!(!tbasis_calls(&mesh, None, 1).0);
}

#[test]
fn corpus_meshes_give_mikktspace_c_calls_as_triangles_and_as_quads() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    let (mut checked, mut quad_faces) = (0, 0);
    for row in load::read_manifest(&dir).expect("MANIFEST.tsv") {
        if load::left_to_optimized_builds(&row) {
            continue;
        }
        let file = load::load(&dir, &row).unwrap_or_else(|e| panic!("{}: {e}", row.path));
        for primitive in &file.primitives {
            let (Some(triangles), Some(quads)) = (
                face_scenes::from_primitive(primitive, false),
                face_scenes::from_primitive(primitive, true),
            ) else {
                continue;
            };
            let name = |mesh: FaceMesh| FaceMesh {
                name: format!("{} {}", row.path, mesh.name),
                ..mesh
            };
            check(&name(triangles), None, 1);
            quad_faces += quads.sizes.iter().filter(|&&size| size == 4).count();
            check(&name(quads), Some(90.0), 2);
            checked += 1;
        }
    }
    assert!(
        checked > 0 && quad_faces > 0,
        "{checked} primitives, {quad_faces} quads"
    );
    eprintln!("{checked} corpus primitives checked, {quad_faces} quads among their faces");
}

#[test]
fn a_failed_allocation_returns_false_with_no_call() {
    // Quads, 5-vertex faces, degenerate faces (a spill-free single thread) and, at 30 degrees,
    // the pairwise sub-group search with its own allocations.
    let mesh = face_scenes::random_faces(3, 80);
    for threshold in [None, Some(30.0)] {
        let before = allocations();
        let (ok, calls) = tbasis_calls(&mesh, threshold, 1);
        let count = allocations() - before - 1;
        assert!(ok && !calls.is_empty());
        assert!(count >= 10, "{count} allocations");
        for k in 0..count {
            // The recorder's own allocation comes first.
            fail_allocation(Some(allocations() + 1 + k));
            let (ok, calls) = tbasis_calls(&mesh, threshold, 1);
            fail_allocation(None);
            assert!(
                !ok && calls.is_empty(),
                "allocation {k} of {count} failed at {threshold:?}"
            );
        }
        eprintln!("{count} allocations at {threshold:?} degrees, each failing cleanly");
    }
}
