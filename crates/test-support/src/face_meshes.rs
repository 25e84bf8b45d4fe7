//! Meshes as mikktspace.c's callback interface sees them: faces of any vertex count (3 and 4
//! count, others are ignored), one position, normal and texture coordinate per face vertex; and
//! every `setTSpace` call mikktspace.c makes for them, and `tbasis::mikktspace`'s, to compare
//! bit for bit.
//!
//! It depends on nothing but `tbasis` and `mikktspace-sys`, so that the fuzz target includes it by
//! path; the meshes to run it on are in `face_scenes`.

use tbasis::mikktspace::{generate_tangents, generate_tangents_with, Geometry, Settings};

/// Faces of `sizes[f]` vertices each, their attributes face after face.
#[derive(Clone, Debug, Default)]
pub struct FaceMesh {
    pub name: String,
    pub sizes: Vec<usize>,
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub texcoords: Vec<[f32; 2]>,
    /// Where each face's vertices start.
    pub starts: Vec<usize>,
}

impl FaceMesh {
    pub fn push_face(&mut self, vertices: impl IntoIterator<Item = ([f32; 3], [f32; 3], [f32; 2])>) {
        self.starts.push(self.positions.len());
        let before = self.positions.len();
        for (p, n, t) in vertices {
            self.positions.push(p);
            self.normals.push(n);
            self.texcoords.push(t);
        }
        self.sizes.push(self.positions.len() - before);
    }

    /// Faces from a triangle list (`corners` names each corner's vertex); with `quads`, each two
    /// triangles `(a, b, c)`, `(a, c, d)` in a row become the quad `(a, b, c, d)`.
    pub fn from_triangles(
        name: String,
        vertices: [&[[f32; 3]]; 2],
        texcoords: &[[f32; 2]],
        corners: &[usize],
        quads: bool,
    ) -> FaceMesh {
        let vertex = |v: usize| (vertices[0][v], vertices[1][v], texcoords[v]);
        let mut out = FaceMesh {
            name: format!("{name}{}", if quads { " as quads" } else { "" }),
            ..FaceMesh::default()
        };
        let triangles: Vec<&[usize]> = corners.chunks_exact(3).collect();
        let mut t = 0;
        while t < triangles.len() {
            let (a, b) = (triangles[t], triangles.get(t + 1));
            match b {
                Some(b) if quads && a[0] == b[0] && a[2] == b[1] => {
                    out.push_face([a[0], a[1], a[2], b[2]].map(vertex));
                    t += 2;
                }
                _ => {
                    out.push_face(a.iter().map(|&v| vertex(v)));
                    t += 1;
                }
            }
        }
        out
    }
}

/// One `setTSpace` call, every argument as bits.
#[derive(Clone, Copy, Debug)]
pub struct Call {
    pub face: usize,
    pub vert: usize,
    pub tangent: [u32; 3],
    pub bitangent: [u32; 3],
    pub magnitudes: [u32; 2],
    pub preserving: bool,
}

impl Call {
    /// Equal in every bit, except that a NaN matches any NaN: mikktspace.c's own NaN payloads and
    /// signs change with its compiler's options (see `crates/tbasis/tests/mikktspace.rs`).
    pub fn matches(&self, other: &Call) -> bool {
        let same = |a: u32, b: u32| a == b || (f32::from_bits(a).is_nan() && f32::from_bits(b).is_nan());
        let floats = |c: &Call| {
            let mut all = [0u32; 8];
            all[..3].copy_from_slice(&c.tangent);
            all[3..6].copy_from_slice(&c.bitangent);
            all[6..].copy_from_slice(&c.magnitudes);
            all
        };
        (self.face, self.vert, self.preserving) == (other.face, other.vert, other.preserving)
            && floats(self).iter().zip(floats(other)).all(|(&a, b)| same(a, b))
    }

    #[allow(clippy::too_many_arguments)]
    pub fn new(
        tangent: [f32; 3],
        bitangent: [f32; 3],
        mag_s: f32,
        mag_t: f32,
        preserving: bool,
        face: usize,
        vert: usize,
    ) -> Call {
        Call {
            face,
            vert,
            tangent: tangent.map(f32::to_bits),
            bitangent: bitangent.map(f32::to_bits),
            magnitudes: [mag_s.to_bits(), mag_t.to_bits()],
            preserving,
        }
    }
}

/// mikktspace.c's return value and `setTSpace` calls for `mesh` at `angular_threshold` degrees
/// (`genTangSpaceDefault` when `None`).
pub fn mikktspace_c(mesh: &FaceMesh, angular_threshold: Option<f32>) -> (bool, Vec<Call>) {
    struct Recorder<'a>(&'a FaceMesh, Vec<Call>);
    impl mikktspace_sys::MikkTSpaceInterface for Recorder<'_> {
        fn get_num_faces(&self) -> usize {
            self.0.sizes.len()
        }
        fn get_num_vertices_of_face(&self, face: usize) -> usize {
            self.0.sizes[face]
        }
        fn get_position(&self, face: usize, vert: usize) -> [f32; 3] {
            self.0.positions[self.0.starts[face] + vert]
        }
        fn get_normal(&self, face: usize, vert: usize) -> [f32; 3] {
            self.0.normals[self.0.starts[face] + vert]
        }
        fn get_tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
            self.0.texcoords[self.0.starts[face] + vert]
        }
        fn set_tspace(&mut self, s: [f32; 3], t: [f32; 3], ms: f32, mt: f32, o: bool, face: usize, vert: usize) {
            self.1.push(Call::new(s, t, ms, mt, o, face, vert));
        }
    }
    let mut recorder = Recorder(mesh, Vec::new());
    let ok = match angular_threshold {
        None => mikktspace_sys::gen_tang_space_default(&mut recorder),
        Some(degrees) => mikktspace_sys::gen_tang_space(&mut recorder, degrees),
    };
    (ok, recorder.1)
}

/// The drop-in's return value and `set_tangent` calls for `mesh`, through the trait as a user of
/// the `mikktspace` crate implements it (`generate_tangents` when `angular_threshold` is `None`
/// and `threads` 1).
pub fn tbasis_calls(mesh: &FaceMesh, angular_threshold: Option<f32>, threads: u32) -> (bool, Vec<Call>) {
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
    // Room for every call: recording allocates nothing during the call.
    let mut recorder = Recorder(mesh, Vec::with_capacity(mesh.positions.len()));
    let ok = match angular_threshold {
        None if threads == 1 => generate_tangents(&mut recorder),
        _ => {
            let angular_threshold = angular_threshold.unwrap_or(180.0);
            generate_tangents_with(
                &mut recorder,
                &Settings {
                    angular_threshold,
                    threads,
                },
            )
        }
    };
    (ok, recorder.1)
}

/// The first call in which `ours` and mikktspace.c's differ, described; `None` when they agree.
pub fn first_difference(ours: &(bool, Vec<Call>), reference: &(bool, Vec<Call>)) -> Option<String> {
    if ours.0 != reference.0 {
        return Some(format!("returned {}, mikktspace.c {}", ours.0, reference.0));
    }
    if ours.1.len() != reference.1.len() {
        return Some(format!("{} calls, mikktspace.c {}", ours.1.len(), reference.1.len()));
    }
    let i = (0..ours.1.len()).find(|&i| !ours.1[i].matches(&reference.1[i]))?;
    Some(format!(
        "call {i} differs:\n  tbasis {:?}\n  mikktspace.c {:?}",
        ours.1[i], reference.1[i]
    ))
}
