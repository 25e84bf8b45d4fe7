//! Meshes of faces of any vertex count, as mikktspace.c's callback interface reads them, and every
//! set call mikktspace.c and `tbasis::mikktspace` make for them, to compare bit for bit: the
//! `Geometry` trait's test (`crates/tbasis/tests/geometry.rs`), the drop-in's C driver
//! (`tests/mikktspace_dropin.rs`, reading the file [`write_file`] writes) and the fuzz target
//! `generate`. The meshes themselves are built in `face_scenes`.

use std::io::{self, Write};
use std::path::Path;

use mikktspace_sys::MikkTSpaceInterface;
use tbasis::mikktspace::{generate_tangents, generate_tangents_with, Geometry, Settings};

use super::shapes::Vertex;

/// A mesh as the callbacks read it: face `f` reports `face_sizes[f]` vertices, and its vertex `k`
/// reads the attributes of vertex `face_vertices[first + k]`, `first` being the sum of the
/// earlier faces' sizes (negative sizes count as 0).
#[derive(Clone, Debug, Default)]
pub struct FaceMesh {
    /// What the tests print about it; the driver's `--dump` and `--perturb` take it.
    pub name: String,
    /// What `m_getNumFaces` returns: the number of faces, or a negative count.
    pub reported_faces: i32,
    /// What `m_getNumVerticesOfFace` returns per face: 3 and 4 count, any other is ignored.
    pub face_sizes: Vec<i32>,
    /// The vertex of each face vertex, face after face.
    pub face_vertices: Vec<u32>,
    /// Per vertex, read through `face_vertices`.
    pub positions: Vec<[f32; 3]>,
    /// Per vertex, unit length where the mesh is well formed.
    pub normals: Vec<[f32; 3]>,
    /// Per vertex.
    pub texcoords: Vec<[f32; 2]>,
}

impl FaceMesh {
    pub fn new(name: &str) -> FaceMesh {
        FaceMesh {
            name: name.to_string(),
            ..FaceMesh::default()
        }
    }

    /// Appends a vertex and returns its index.
    pub fn vertex(&mut self, vertex: Vertex) -> u32 {
        self.positions.push(vertex.position);
        self.normals.push(vertex.normal);
        self.texcoords.push(vertex.uv);
        (self.positions.len() - 1) as u32
    }

    /// Appends a face of these vertices.
    pub fn face(&mut self, vertices: &[u32]) {
        self.sized_face(vertices.len() as i32, vertices);
    }

    /// Appends a face that reports `size` vertices and stores `vertices` (as many, or none for a
    /// size below 1).
    pub fn sized_face(&mut self, size: i32, vertices: &[u32]) {
        assert_eq!(size.max(0) as usize, vertices.len(), "{}: face size", self.name);
        self.face_sizes.push(size);
        self.face_vertices.extend_from_slice(vertices);
        self.reported_faces = self.face_sizes.len() as i32;
    }

    /// Where each face's vertices start in `face_vertices`.
    pub fn face_starts(&self) -> Vec<usize> {
        let mut start = 0;
        self.face_sizes
            .iter()
            .map(|&size| {
                let first = start;
                start += size.max(0) as usize;
                first
            })
            .collect()
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Appends a face of new vertices (position, normal, texture coordinate).
    pub fn push_face(&mut self, vertices: impl IntoIterator<Item = ([f32; 3], [f32; 3], [f32; 2])>) {
        let added: Vec<u32> = vertices
            .into_iter()
            .map(|(position, normal, uv)| self.vertex(Vertex { position, normal, uv }))
            .collect();
        self.face(&added);
    }

    /// Faces from a triangle list (`corners` names each corner's vertex); with `quads`, each two
    /// triangles `(a, b, c)`, `(a, c, d)` in a row become the quad `(a, b, c, d)`.
    pub fn from_triangles(
        name: String,
        vertices: [&[[f32; 3]]; 2],
        texcoords: &[[f32; 2]],
        corners: &[u32],
        quads: bool,
    ) -> FaceMesh {
        let mut mesh = FaceMesh {
            name: format!("{name}{}", if quads { " as quads" } else { "" }),
            positions: vertices[0].to_vec(),
            normals: vertices[1].to_vec(),
            texcoords: texcoords.to_vec(),
            ..FaceMesh::default()
        };
        let triangles: Vec<&[u32]> = corners.chunks_exact(3).collect();
        let mut t = 0;
        while t < triangles.len() {
            match (triangles[t], triangles.get(t + 1)) {
                (a, Some(b)) if quads && a[0] == b[0] && a[2] == b[1] => {
                    mesh.face(&[a[0], a[1], a[2], b[2]]);
                    t += 2;
                }
                (a, _) => {
                    mesh.face(a);
                    t += 1;
                }
            }
        }
        mesh
    }
}

/// A float's bits, every NaN as one: which NaN an operation on NaN returns is fixed neither by C
/// nor by Rust.
fn bits(value: f32) -> u32 {
    if value.is_nan() {
        0x7fc0_0000
    } else {
        value.to_bits()
    }
}

/// One `set_tangent` (or `set_tspace`) call; `bi_tangent` and the magnitudes are zero for the
/// encoded form, whose sign is in `mag_s`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Call {
    pub face: usize,
    pub vert: usize,
    pub tangent: [u32; 3],
    pub bi_tangent: [u32; 3],
    pub mag_s: u32,
    pub mag_t: u32,
    pub preserves_orientation: bool,
}

/// A mesh read through both traits, recording every set call.
struct Recorder<'a> {
    mesh: &'a FaceMesh,
    starts: Vec<usize>,
    calls: Vec<Call>,
}

impl<'a> Recorder<'a> {
    fn new(mesh: &'a FaceMesh) -> Self {
        Recorder {
            mesh,
            starts: mesh.face_starts(),
            calls: Vec::with_capacity(mesh.face_vertices.len()),
        }
    }

    /// The attribute index of a face vertex; `None` for one that does not exist (mikktspace.c
    /// asks for face 0's vertex 0 whatever face 0's count: the answer is zeros).
    fn vertex(&self, face: usize, vert: usize) -> Option<usize> {
        let size = usize::try_from(self.mesh.face_sizes[face]).unwrap_or(0);
        (vert < size).then(|| self.mesh.face_vertices[self.starts[face] + vert] as usize)
    }

    fn faces(&self) -> usize {
        usize::try_from(self.mesh.reported_faces).expect("meshes with a negative count are left out")
    }

    /// The face's count as the trait returns it: a negative one wraps to a huge `usize`, which
    /// mikktspace-sys hands back to C as the same negative `int`.
    fn size(&self, face: usize) -> usize {
        self.mesh.face_sizes[face] as isize as usize
    }

    fn read_position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.vertex(face, vert).map_or([0.0; 3], |v| self.mesh.positions[v])
    }

    fn read_normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.vertex(face, vert).map_or([0.0; 3], |v| self.mesh.normals[v])
    }

    fn read_tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.vertex(face, vert).map_or([0.0; 2], |v| self.mesh.texcoords[v])
    }

    #[allow(clippy::too_many_arguments)]
    fn record(&mut self, t: [f32; 3], b: [f32; 3], s: f32, m: f32, o: bool, face: usize, vert: usize) {
        self.calls.push(Call {
            face,
            vert,
            tangent: t.map(bits),
            bi_tangent: b.map(bits),
            mag_s: bits(s),
            mag_t: bits(m),
            preserves_orientation: o,
        });
    }
}

/// The getters of either trait, under its names, reading the [`Recorder`] of `self`.
macro_rules! getters {
    (MikkTSpaceInterface) => {
        getters!(
            get_num_faces,
            get_num_vertices_of_face,
            get_position,
            get_normal,
            get_tex_coord
        );
    };
    (Geometry) => {
        getters!(num_faces, num_vertices_of_face, position, normal, tex_coord);
    };
    ($faces:ident, $size:ident, $position:ident, $normal:ident, $tex_coord:ident) => {
        fn $faces(&self) -> usize {
            self.recorder().faces()
        }
        fn $size(&self, face: usize) -> usize {
            self.recorder().size(face)
        }
        fn $position(&self, face: usize, vert: usize) -> [f32; 3] {
            self.recorder().read_position(face, vert)
        }
        fn $normal(&self, face: usize, vert: usize) -> [f32; 3] {
            self.recorder().read_normal(face, vert)
        }
        fn $tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
            self.recorder().read_tex_coord(face, vert)
        }
    };
}

impl Recorder<'_> {
    fn recorder(&self) -> &Self {
        self
    }
}

impl MikkTSpaceInterface for Recorder<'_> {
    getters!(MikkTSpaceInterface);
    fn set_tspace(&mut self, t: [f32; 3], b: [f32; 3], s: f32, m: f32, o: bool, face: usize, vert: usize) {
        self.record(t, b, s, m, o, face, vert);
    }
}

impl Geometry for Recorder<'_> {
    getters!(Geometry);
    fn set_tangent(&mut self, t: [f32; 3], b: [f32; 3], s: f32, m: f32, o: bool, face: usize, vert: usize) {
        self.record(t, b, s, m, o, face, vert);
    }
}

/// The tangent and its sign alone, recorded with a zero bitangent and the sign in `mag_s`: what a
/// user of the `mikktspace` crate writes (the getters and `set_tangent_encoded`), and mikktspace.c's
/// `set_tspace_basic`.
struct Signed<'a>(Recorder<'a>);

impl<'a> Signed<'a> {
    fn recorder(&self) -> &Recorder<'a> {
        &self.0
    }
}

impl Geometry for Signed<'_> {
    getters!(Geometry);
    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        let [x, y, z, sign] = tangent;
        self.0.record([x, y, z], [0.0; 3], sign, 0.0, false, face, vert);
    }
}

impl MikkTSpaceInterface for Signed<'_> {
    getters!(MikkTSpaceInterface);
    fn set_tspace_basic(&mut self, tangent: [f32; 3], sign: f32, face: usize, vert: usize) {
        self.0.record(tangent, [0.0; 3], sign, 0.0, false, face, vert);
    }
}

/// How one comparison calls both sides.
#[derive(Clone, Copy, Debug)]
pub enum Run {
    /// `generate_tangents` against `gen_tang_space_default`.
    Default,
    /// `generate_tangents_with` at this threshold and thread count against `gen_tang_space`.
    With(f32, u32),
    /// `generate_tangents` into `set_tangent_encoded` against `set_tspace_basic`.
    Encoded,
}

pub const RUNS: [Run; 6] = [
    Run::Default,
    Run::With(180.0, 1),
    Run::With(90.0, 1),
    Run::With(30.0, 1),
    Run::With(90.0, 2),
    Run::Encoded,
];

/// mikktspace.c's and this crate's return value and calls for `run`.
pub fn both(mesh: &FaceMesh, run: Run) -> [(bool, Vec<Call>); 2] {
    [mikktspace_c_calls(mesh, run), tbasis_calls(mesh, run)]
}

/// mikktspace.c's return value and calls for `run`.
pub fn mikktspace_c_calls(mesh: &FaceMesh, run: Run) -> (bool, Vec<Call>) {
    match run {
        Run::Default => {
            let mut c = Recorder::new(mesh);
            (mikktspace_sys::gen_tang_space_default(&mut c), c.calls)
        }
        Run::With(angular_threshold, _) => {
            let mut c = Recorder::new(mesh);
            (mikktspace_sys::gen_tang_space(&mut c, angular_threshold), c.calls)
        }
        Run::Encoded => {
            let mut c = Signed(Recorder::new(mesh));
            (mikktspace_sys::gen_tang_space_default(&mut c), c.0.calls)
        }
    }
}

/// This crate's return value and calls for `run`. Two allocations come before the call (the
/// faces' starts, and room for every call): the call itself records without allocating.
pub fn tbasis_calls(mesh: &FaceMesh, run: Run) -> (bool, Vec<Call>) {
    match run {
        Run::Default => {
            let mut ours = Recorder::new(mesh);
            (generate_tangents(&mut ours), ours.calls)
        }
        Run::With(angular_threshold, threads) => {
            let mut ours = Recorder::new(mesh);
            let settings = Settings {
                angular_threshold,
                threads,
            };
            (generate_tangents_with(&mut ours, &settings), ours.calls)
        }
        Run::Encoded => {
            let mut ours = Signed(Recorder::new(mesh));
            (generate_tangents(&mut ours), ours.0.calls)
        }
    }
}

/// Where this crate departs from mikktspace.c on `mesh`, one line per run that does.
pub fn departures(mesh: &FaceMesh) -> Vec<String> {
    let mut found = Vec::new();
    for run in RUNS {
        let [(c_ok, c_calls), (ok, calls)] = both(mesh, run);
        if (c_ok, &c_calls) == (ok, &calls) {
            continue;
        }
        let detail = match c_calls.iter().zip(&calls).position(|(c, ours)| c != ours) {
            Some(k) => format!("call {k}: mikktspace.c {:?}, this crate {:?}", c_calls[k], calls[k]),
            None => format!("{} calls against mikktspace.c's {}", calls.len(), c_calls.len()),
        };
        found.push(format!(
            "{} ({run:?}): returned {ok} against mikktspace.c's {c_ok}; {detail}",
            mesh.name
        ));
    }
    found
}

/// Panics with the first departures, if any.
pub fn assert_no_departures(what: &str, departures: &[String], meshes: usize) {
    assert!(
        departures.is_empty(),
        "{what}: {} of {} runs on {meshes} meshes depart from mikktspace.c:\n{}",
        departures.len(),
        meshes * RUNS.len(),
        departures.iter().take(20).cloned().collect::<Vec<_>>().join("\n")
    );
}

/// Writes `meshes` for the C driver (`c_tests/mikktspace/driver.c`), in native byte order: the
/// magic `TBMK`, the mesh count (u32), then per mesh the name's length (u32) and bytes, the vertex
/// count (u32), `reported_faces` (i32), the face count and the face-vertex count (u32 each),
/// positions, normals and texture coordinates (f32), the face sizes (i32) and the face vertices
/// (u32).
pub fn write_file(path: &Path, meshes: &[FaceMesh]) -> io::Result<()> {
    let mut out = io::BufWriter::new(std::fs::File::create(path)?);
    let count = |n: usize| u32::try_from(n).expect("counts fit 32 bits").to_ne_bytes();
    out.write_all(b"TBMK")?;
    out.write_all(&count(meshes.len()))?;
    for mesh in meshes {
        out.write_all(&count(mesh.name.len()))?;
        out.write_all(mesh.name.as_bytes())?;
        out.write_all(&count(mesh.vertex_count()))?;
        out.write_all(&mesh.reported_faces.to_ne_bytes())?;
        out.write_all(&count(mesh.face_sizes.len()))?;
        out.write_all(&count(mesh.face_vertices.len()))?;
        let floats = mesh.positions.iter().flatten().chain(mesh.normals.iter().flatten());
        for value in floats.chain(mesh.texcoords.iter().flatten()) {
            out.write_all(&value.to_ne_bytes())?;
        }
        for size in &mesh.face_sizes {
            out.write_all(&size.to_ne_bytes())?;
        }
        for vertex in &mesh.face_vertices {
            out.write_all(&vertex.to_ne_bytes())?;
        }
    }
    out.flush()
}
