//! `tbasis::mikktspace`, the `mikktspace` crate's trait and `generate_tangents`, against
//! mikktspace.c itself through the crate mikktspace-sys (its `gen_tang_space` with the full
//! `set_tspace` callback): the same return value and, call for call, the same `set_tangent`
//! arguments, every float bit for bit (any NaN matching any NaN), on the face meshes of
//! `tbasis_test_support::face_meshes` (quads split both ways, faces of other counts, degenerate
//! and non-finite input, every triangle scene) and on every corpus mesh; at 180, 90 and 30
//! degrees, on 1 and 2 threads; and through `set_tangent_encoded`, the method a user of the
//! `mikktspace` crate implements, against `set_tspace_basic`.

use tbasis::mikktspace::{generate_tangents, generate_tangents_with, Geometry, Settings};
use tbasis_test_support::face_meshes::{self, FaceMesh};
use tbasis_test_support::mikktspace_sys::{self, MikkTSpaceInterface};
use tbasis_test_support::{load, needs};

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
struct Call {
    face: usize,
    vert: usize,
    tangent: [u32; 3],
    bi_tangent: [u32; 3],
    mag_s: u32,
    mag_t: u32,
    preserves_orientation: bool,
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
            calls: Vec::new(),
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
enum Run {
    /// `generate_tangents` against `gen_tang_space_default`.
    Default,
    /// `generate_tangents_with` at this threshold and thread count against `gen_tang_space`.
    With(f32, u32),
    /// `generate_tangents` into `set_tangent_encoded` against `set_tspace_basic`.
    Encoded,
}

const RUNS: [Run; 6] = [
    Run::Default,
    Run::With(180.0, 1),
    Run::With(90.0, 1),
    Run::With(30.0, 1),
    Run::With(90.0, 2),
    Run::Encoded,
];

/// mikktspace.c's and this crate's return value and calls for `run`.
fn both(mesh: &FaceMesh, run: Run) -> [(bool, Vec<Call>); 2] {
    match run {
        Run::Default => {
            let (mut c, mut ours) = (Recorder::new(mesh), Recorder::new(mesh));
            let (c_ok, ok) = (
                mikktspace_sys::gen_tang_space_default(&mut c),
                generate_tangents(&mut ours),
            );
            [(c_ok, c.calls), (ok, ours.calls)]
        }
        Run::With(angular_threshold, threads) => {
            let (mut c, mut ours) = (Recorder::new(mesh), Recorder::new(mesh));
            let c_ok = mikktspace_sys::gen_tang_space(&mut c, angular_threshold);
            let settings = Settings {
                angular_threshold,
                threads,
            };
            let ok = generate_tangents_with(&mut ours, &settings);
            [(c_ok, c.calls), (ok, ours.calls)]
        }
        Run::Encoded => {
            let (mut c, mut ours) = (Signed(Recorder::new(mesh)), Signed(Recorder::new(mesh)));
            let (c_ok, ok) = (
                mikktspace_sys::gen_tang_space_default(&mut c),
                generate_tangents(&mut ours),
            );
            [(c_ok, c.0.calls), (ok, ours.0.calls)]
        }
    }
}

/// Where this crate departs from mikktspace.c on `mesh`, one line per run that does.
fn departures(mesh: &FaceMesh) -> Vec<String> {
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
fn assert_no_departures(what: &str, departures: &[String], meshes: usize) {
    assert!(
        departures.is_empty(),
        "{what}: {} of {} runs on {meshes} meshes depart from mikktspace.c:\n{}",
        departures.len(),
        meshes * RUNS.len(),
        departures.iter().take(20).cloned().collect::<Vec<_>>().join("\n")
    );
}

#[test]
fn generate_tangents_makes_mikktspace_c_calls_on_generated_meshes() {
    // The trait counts faces in a usize: a negative count is mikktspace.c's alone (the C driver of
    // tests/mikktspace_dropin.rs gives one to the drop-in).
    let meshes: Vec<FaceMesh> = face_meshes::generated()
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
    let (mut meshes, mut found) = (0, Vec::new());
    for row in load::read_manifest(&dir).expect("MANIFEST.tsv") {
        if load::left_to_optimized_builds(&row) {
            continue;
        }
        let file = load::load(&dir, &row).unwrap_or_else(|e| panic!("{}: {e}", row.path));
        for mesh in file
            .primitives
            .iter()
            .filter_map(|p| FaceMesh::from_primitive(&row.path, p))
        {
            meshes += 1;
            found.extend(departures(&mesh));
        }
    }
    assert!(meshes >= 50, "only {meshes} corpus meshes");
    assert_no_departures("the corpus", &found, meshes);
}
