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
    assert_far_first_corners_match(100.0, "far first corners");
}

/// The first corner at x = 1e7 instead: its grid index, `2048 * (x - min) / (max - min)` in a box
/// at most 1 wide, is past int's range, where mikktspace.c's conversion is undefined in C and
/// x86-64's gives `INT_MIN`, cell 0, which the library takes on every processor (the comparison
/// needs mikktspace.c built for x86-64).
#[cfg(target_arch = "x86_64")]
#[test]
fn a_first_corner_past_ints_range_takes_the_cell_x86_64_gives_it() {
    assert_far_first_corners_match(1e7, "first corners past int's range");
}

/// [`face_scenes::far_first_corner`] on 3000 seeds, the far corner at `far_x`, against mikktspace.c.
fn assert_far_first_corners_match(far_x: f32, what: &str) {
    let meshes: Vec<FaceMesh> = (0..3000)
        .map(|seed| face_scenes::far_first_corner(seed, far_x))
        .collect();
    let departures: Vec<String> = meshes.iter().flat_map(departures).collect();
    assert_no_departures(what, &departures, meshes.len());
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

/// Faces of no vertex but the first and the last, which are one triangle each: `face_count`
/// faces in all; records the faces of the set calls.
struct FarFaces {
    face_count: usize,
    set: Vec<usize>,
}

impl tbasis::mikktspace::Geometry for FarFaces {
    fn num_faces(&self) -> usize {
        self.face_count
    }
    fn num_vertices_of_face(&self, face: usize) -> usize {
        if face == 0 || face == self.face_count - 1 {
            3
        } else {
            0
        }
    }
    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        [vert as f32 % 2.0, (vert / 2) as f32, face.min(1) as f32]
    }
    fn normal(&self, _: usize, _: usize) -> [f32; 3] {
        [0.0, 0.0, 1.0]
    }
    fn tex_coord(&self, _: usize, vert: usize) -> [f32; 2] {
        [vert as f32 % 2.0, (vert / 2) as f32]
    }
    fn set_tangent_encoded(&mut self, _: [f32; 4], face: usize, _: usize) {
        self.set.push(face);
    }
}

#[test]
fn a_face_numbered_past_int_max_over_4_returns_false_with_no_call() {
    // mikktspace.c numbers a face vertex `4 * face + vert` in an int: `4 * (INT_MAX / 4) + 3` is
    // INT_MAX, and the next face overflows it. The library takes faces up to INT_MAX / 4, the
    // last face of the first mesh (`include/tbasis_mikktspace.h`), and refuses the next.
    let largest = (i32::MAX / 4) as usize;
    let mut within = FarFaces {
        face_count: largest + 1,
        set: Vec::new(),
    };
    assert!(tbasis::mikktspace::generate_tangents(&mut within));
    assert_eq!(within.set, [0, 0, 0, largest, largest, largest]);

    let mut beyond = FarFaces {
        face_count: largest + 2,
        set: Vec::new(),
    };
    assert!(!tbasis::mikktspace::generate_tangents(&mut beyond));
    assert!(beyond.set.is_empty(), "{:?}", &beyond.set[..beyond.set.len().min(6)]);
}
