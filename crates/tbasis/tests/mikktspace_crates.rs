//! A user of the `mikktspace` crate (0.3) or of bevy_mikktspace's API before 1.0 (0.16) moves to
//! `tbasis::mikktspace` by changing one `use` line (README, "Drop-in for mikktspace.c"): the same
//! code, below once, compiles against all three with only that line's path changed, and gets the
//! same tangents, bit for bit, on a mesh of quads that split either way.

use tbasis_test_support::face_meshes::FaceMesh;
use tbasis_test_support::face_scenes;

/// A user's code, written once: a `Geometry` over a face mesh that keeps what `set_tangent_encoded`
/// receives, and the call. `$krate` is the path its one `use` line names.
macro_rules! users_code {
    ($module:ident, $($krate:ident)::+) => {
        mod $module {
            use $($krate)::+::{generate_tangents, Geometry};

            use super::FaceMesh;

            struct Faces<'m> {
                mesh: &'m FaceMesh,
                first_vertex: Vec<usize>,
                tangents: Vec<[f32; 4]>,
            }

            impl Faces<'_> {
                fn vertex(&self, face: usize, vert: usize) -> usize {
                    self.mesh.face_vertices[self.first_vertex[face] + vert] as usize
                }
            }

            impl Geometry for Faces<'_> {
                fn num_faces(&self) -> usize {
                    self.mesh.face_sizes.len()
                }

                fn num_vertices_of_face(&self, face: usize) -> usize {
                    self.mesh.face_sizes[face] as usize
                }

                fn position(&self, face: usize, vert: usize) -> [f32; 3] {
                    self.mesh.positions[self.vertex(face, vert)]
                }

                fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
                    self.mesh.normals[self.vertex(face, vert)]
                }

                fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
                    self.mesh.texcoords[self.vertex(face, vert)]
                }

                fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
                    let slot = self.first_vertex[face] + vert;
                    self.tangents[slot] = tangent;
                }
            }

            /// Whether the call succeeded, and every face vertex's tangent, face after face.
            pub fn tangents(mesh: &FaceMesh) -> (bool, Vec<[f32; 4]>) {
                let first_vertex = mesh
                    .face_sizes
                    .iter()
                    .scan(0, |next, &size| {
                        let first = *next;
                        *next += size as usize;
                        Some(first)
                    })
                    .collect();
                let mut faces = Faces {
                    mesh,
                    first_vertex,
                    tangents: vec![[f32::NAN; 4]; mesh.face_vertices.len()],
                };
                let done = generate_tangents(&mut faces);
                (done, faces.tangents)
            }
        }
    };
}

users_code!(with_mikktspace, mikktspace);
users_code!(with_bevy_mikktspace_0_16, bevy_mikktspace_0_16);
users_code!(with_tbasis, tbasis::mikktspace);

/// The first face vertex whose tangents differ in a bit, with both.
fn first_difference(a: &[[f32; 4]], b: &[[f32; 4]]) -> Option<(usize, [f32; 4], [f32; 4])> {
    assert_eq!(a.len(), b.len());
    let bits = |t: &[f32; 4]| t.map(f32::to_bits);
    (0..a.len())
        .find(|&i| bits(&a[i]) != bits(&b[i]))
        .map(|i| (i, a[i], b[i]))
}

#[test]
fn code_for_the_mikktspace_crates_runs_on_tbasis_with_its_use_line_changed() {
    // Quads that split either way, with mirrored columns: each tangent set, none NaN.
    let mesh = face_scenes::quad_grid(7, 12, 9);
    let (done, ours) = with_tbasis::tangents(&mesh);
    assert!(done, "tbasis::mikktspace::generate_tangents failed");
    assert!(
        ours.iter().flatten().all(|x| x.is_finite()),
        "a face vertex got no tangent"
    );
    for (name, (done, theirs)) in [
        ("mikktspace 0.3", with_mikktspace::tangents(&mesh)),
        ("bevy_mikktspace 0.16", with_bevy_mikktspace_0_16::tangents(&mesh)),
    ] {
        assert!(done, "{name} failed");
        // Both port mikktspace.c's float operations, and tbasis gives mikktspace.c's bits: on
        // this mesh, theirs too.
        let difference = first_difference(&ours, &theirs);
        assert_eq!(difference, None, "{name}: face vertex, tbasis's tangent, theirs");
    }
}
