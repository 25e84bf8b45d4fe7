//! `tbasis::mikktspace`, the `mikktspace` crate's interface, against mikktspace.c itself: the same
//! return value and every `setTSpace` argument bit for bit, for triangles, quads split either
//! way, faces of other sizes, every angular threshold tried, and hostile values (a NaN matches
//! any NaN, as in `mikktspace.rs`).

use tbasis::mikktspace::{generate_tangents, generate_tangents_with, Geometry, Settings};
use tbasis_test_support::face_meshes::{mikktspace_c, Call, FaceMesh};
use tbasis_test_support::mikktspace_scenes;

/// The drop-in's calls, through the trait as a user of the `mikktspace` crate implements it.
struct Recorder<'a>(&'a FaceMesh, Vec<Call>);

impl Geometry for Recorder<'_> {
    fn num_faces(&self) -> usize {
        self.0.sizes.len()
    }
    fn num_vertices_of_face(&self, face: usize) -> usize {
        self.0.sizes[face]
    }
    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.0.positions[self.0.starts[face] + vert]
    }
    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.0.normals[self.0.starts[face] + vert]
    }
    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.0.texcoords[self.0.starts[face] + vert]
    }
    fn set_tangent(&mut self, s: [f32; 3], t: [f32; 3], ms: f32, mt: f32, o: bool, face: usize, vert: usize) {
        self.1.push(Call::new(s, t, ms, mt, o, face, vert));
    }
}

fn tbasis_calls(mesh: &FaceMesh, angular_threshold: Option<f32>, threads: u32) -> (bool, Vec<Call>) {
    let mut recorder = Recorder(mesh, Vec::new());
    let ok = match angular_threshold {
        None if threads == 1 => generate_tangents(&mut recorder),
        _ => {
            let angular_threshold = angular_threshold.unwrap_or(180.0);
            generate_tangents_with(&mut recorder, &Settings { angular_threshold, threads })
        }
    };
    (ok, recorder.1)
}

/// Asserts equal calls, naming the first that differs.
fn check(mesh: &FaceMesh, angular_threshold: Option<f32>, threads: u32) {
    let (expected_ok, expected) = mikktspace_c(mesh, angular_threshold);
    let (ok, calls) = tbasis_calls(mesh, angular_threshold, threads);
    let what = format!("{} at {angular_threshold:?} degrees, {threads} threads", mesh.name);
    assert_eq!(ok, expected_ok, "{what}: return value");
    assert_eq!(calls.len(), expected.len(), "{what}: call count");
    if let Some(i) = (0..calls.len()).find(|&i| !calls[i].matches(&expected[i])) {
        panic!("{what}: call {i} differs:\n  tbasis {:?}\n  mikktspace.c {:?}", calls[i], expected[i]);
    }
}

fn generated() -> Vec<FaceMesh> {
    let mut meshes = Vec::new();
    for stress in mikktspace_scenes::all() {
        meshes.push(FaceMesh::from_triangles(&stress, false));
        meshes.push(FaceMesh::from_triangles(&stress, true));
    }
    for seed in 0..4 {
        meshes.push(FaceMesh::quad_grid(seed, 12, 9));
    }
    for seed in 0..40 {
        meshes.push(FaceMesh::random_faces(seed, 60));
    }
    meshes
}

#[test]
fn generated_meshes_give_mikktspace_c_calls_at_every_threshold() {
    for mesh in generated() {
        for threshold in [None, Some(180.0), Some(90.0), Some(30.0)] {
            check(&mesh, threshold, 1);
        }
    }
}

#[test]
fn two_threads_give_the_same_calls() {
    for mesh in generated() {
        check(&mesh, None, 2);
        check(&mesh, Some(60.0), 2);
    }
}

#[test]
fn no_face_of_three_or_four_vertices_returns_false_with_no_call() {
    let mut mesh = FaceMesh::random_faces(1, 10);
    mesh.sizes.iter_mut().for_each(|s| *s = if *s == 5 { 5 } else { 2 });
    for (start, size) in mesh.starts.clone().into_iter().zip(mesh.sizes.clone()) {
        assert!(start + size <= mesh.positions.len());
    }
    check(&mesh, None, 1);
    assert!(!tbasis_calls(&mesh, None, 1).0);
}
