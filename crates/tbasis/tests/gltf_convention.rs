//! glTF's texture coordinates have V pointing down; `Options::flip_v` (`TBASIS_FLAG_FLIP_V`) is
//! how the library is told. Proven on the corpus files whose stored tangents are MikkTSpace's own
//! (`mikktspace-exact` in `../shared/meshes/MANIFEST.tsv`): with the flag the handedness `w`
//! agrees with the stored one on nearly every vertex, without it it is inverted on nearly every
//! vertex, and with the flag the tangent directions agree too. Without the corpus the test is
//! skipped, except under CI, where it fails (`tbasis_test_support::needs`).

use tbasis_test_support::{load, needs};

use load::Primitive;
use tbasis::{generate, Indices, Mesh, Method, Options, Output, Strided, StridedMut};

/// Degrees within which a tangent counts as agreeing with the stored one.
const ANGLE_DEG: f64 = 5.0;

/// Lowest share of vertices, per file, whose `w` must match the file's with the flag; the highest
/// share allowed to match without it is `1 - W_AGREE_ALL`. Measured minimum (armor.gltf, both
/// methods): 98.95%. Every front-facing vertex must match with the flag and none without it.
const W_AGREE_ALL: f64 = 0.97;
/// Lowest share of front-facing vertices, per file, within `ANGLE_DEG` and with the same `w`, with
/// the flag. Measured minimum: ANGLE 99.1% (armor.gltf), LENGYEL 94.8% (armor.gltf); LENGYEL sums
/// unnormalized triangle tangents, MikkTSpace angle-weighted unit ones.
const DIRECTION_AGREE: [(Method, f64); 2] = [(Method::Angle, 0.95), (Method::Lengyel, 0.90)];

/// Counts over one file (or all) for one method.
#[derive(Default, Clone, Copy, Debug)]
struct Tally {
    /// Vertices compared: used by a triangle of nonzero UV area.
    vertices: usize,
    /// Vertices left out: every triangle using them has zero UV area.
    no_uv_area: usize,
    /// Of `vertices`: same `w` as the file, with and without the flag.
    w_with_flag: usize,
    w_without_flag: usize,
    /// Of `vertices`: the flag's result is the unflagged one with `w` negated (xyz within 0.01°).
    negated: usize,
    /// Of `vertices`: those whose normal faces the winding of every triangle using them.
    front: usize,
    /// Of `front`: same `w` with and without the flag; same `w` and within `ANGLE_DEG`, with it.
    front_w_with_flag: usize,
    front_w_without_flag: usize,
    front_direction_with_flag: usize,
}

impl Tally {
    fn add(&mut self, o: &Tally) {
        self.vertices += o.vertices;
        self.no_uv_area += o.no_uv_area;
        self.w_with_flag += o.w_with_flag;
        self.w_without_flag += o.w_without_flag;
        self.negated += o.negated;
        self.front += o.front;
        self.front_w_with_flag += o.front_w_with_flag;
        self.front_w_without_flag += o.front_w_without_flag;
        self.front_direction_with_flag += o.front_direction_with_flag;
    }

    fn line(&self, name: &str) -> String {
        let pct = |part: usize, whole: usize| 100.0 * part as f64 / whole.max(1) as f64;
        format!(
            "{name:<46} {:>5} vertices: same w {:6.2}% with FLIP_V, {:5.2}% without | {:>5} front-facing: \
             same w {:6.2}% / {:5.2}%, within {ANGLE_DEG} deg {:6.2}% | {} without UV area left out",
            self.vertices,
            pct(self.w_with_flag, self.vertices),
            pct(self.w_without_flag, self.vertices),
            self.front,
            pct(self.front_w_with_flag, self.front),
            pct(self.front_w_without_flag, self.front),
            pct(self.front_direction_with_flag, self.front),
            self.no_uv_area,
        )
    }
}

/// Tangents for a glTF primitive, as an application loading glTF asks for them.
fn gltf_tangents(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    texcoords: &[[f32; 2]],
    indices: &[u32],
) -> Vec<[f32; 4]> {
    let mesh = Mesh {
        positions: Strided::from_slice(positions),
        normals: Strided::from_slice(normals),
        texcoords: Some(Strided::from_slice(texcoords)),
        indices: Indices::U32(Strided::from_slice(indices)),
    };
    // glTF's TEXCOORD_0 has V pointing down.
    let options = Options::default().with_flip_v(true);
    let mut tangents = vec![[0.0f32; 4]; positions.len()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: None,
    };
    generate(&mesh, &options, &mut output).expect("tangents");
    tangents
}

/// The primitive's tangents with `flip_v` set as given (default policy).
fn tangents(primitive: &Primitive, method: Method, flip_v: bool) -> Vec<[f32; 4]> {
    // Set explicitly: `Primitive::options` would choose flip_v from the file format.
    let options = Options::default().with_method(method).with_flip_v(flip_v);
    let mut tangents = vec![[0.0f32; 4]; primitive.vertex_count()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: None,
    };
    generate(&primitive.mesh(), &options, &mut output).expect("tangents");
    tangents
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Degrees between the xyz parts of two tangents; 180 when either has no direction.
fn angle_deg(a: [f32; 4], b: [f32; 4]) -> f64 {
    let (a, b) = ([a[0], a[1], a[2]].map(f64::from), [b[0], b[1], b[2]].map(f64::from));
    let c = cross(a, b);
    let (sine, cosine) = (dot(c, c).sqrt(), dot(a, b));
    if !sine.is_finite() || !cosine.is_finite() || sine == 0.0 && cosine == 0.0 {
        return 180.0;
    }
    sine.atan2(cosine).to_degrees()
}

/// What the file's geometry says about each vertex, independently of any tangent generator.
struct VertexFacts {
    referenced: Vec<bool>,
    /// Used by a triangle of nonzero UV area. Where every triangle has zero UV area there is no
    /// UV orientation: MikkTSpace writes its default, the library its fallback, and neither `w`
    /// means anything.
    uv_area: Vec<bool>,
    /// The normal is on the side the winding of every triangle using the vertex faces:
    /// `dot(n, (p1 - p0) x (p2 - p0)) >= 0`. MikkTSpace's `w` is the sign of the UV area in winding
    /// order alone; the library's is the handedness of the frame, `sign(dot(cross(n, T), B))`,
    /// and `cross(T, B) = (Q1 x Q2) / det` (Lengyel's solution), so the two differ by the sign of
    /// `dot(n, Q1 x Q2)`: where the normal faces against a triangle they are different quantities.
    front: Vec<bool>,
}

fn vertex_facts(primitive: &Primitive) -> VertexFacts {
    let n = primitive.vertex_count();
    let uvs = primitive.texcoords.as_deref().expect("texcoords");
    let mut facts = VertexFacts {
        referenced: vec![false; n],
        uv_area: vec![false; n],
        front: vec![true; n],
    };
    for triangle in primitive.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| uvs[triangle[k] as usize].map(f64::from));
        let uv_area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let [p0, p1, p2] = [0, 1, 2].map(|k| primitive.positions[triangle[k] as usize].map(f64::from));
        let face = cross(sub(p1, p0), sub(p2, p0));
        for &v in triangle {
            let v = v as usize;
            facts.referenced[v] = true;
            facts.uv_area[v] |= uv_area != 0.0;
            facts.front[v] &= dot(primitive.normals[v].map(f64::from), face) >= 0.0;
        }
    }
    facts
}

fn tally(primitive: &Primitive, stored: &[[f32; 4]], method: Method) -> Tally {
    let with_flag = tangents(primitive, method, true);
    let without_flag = tangents(primitive, method, false);
    let facts = vertex_facts(primitive);
    let mut t = Tally::default();
    for v in (0..primitive.vertex_count()).filter(|&v| facts.referenced[v]) {
        if !facts.uv_area[v] {
            t.no_uv_area += 1;
            continue;
        }
        let w = if stored[v][3] < 0.0 { -1.0 } else { 1.0 };
        let (same_with, same_without) = (with_flag[v][3] == w, without_flag[v][3] == w);
        let close = angle_deg(with_flag[v], stored[v]) <= ANGLE_DEG;
        t.vertices += 1;
        t.w_with_flag += usize::from(same_with);
        t.w_without_flag += usize::from(same_without);
        t.negated +=
            usize::from(with_flag[v][3] == -without_flag[v][3] && angle_deg(with_flag[v], without_flag[v]) <= 0.01);
        if facts.front[v] {
            t.front += 1;
            t.front_w_with_flag += usize::from(same_with);
            t.front_w_without_flag += usize::from(same_without);
            t.front_direction_with_flag += usize::from(same_with && close);
        }
    }
    t
}

#[test]
fn flip_v_matches_the_handedness_of_stored_gltf_tangents() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    let manifest = load::read_manifest(&dir).expect("MANIFEST.tsv");
    let rows: Vec<_> = manifest
        .iter()
        .filter(|r| r.stored_tangents == "mikktspace-exact")
        .collect();
    assert!(
        rows.iter()
            .any(|r| r.path == "derived/NormalTangentTest.blender-mikk.glb"),
        "the corpus lists no derived/NormalTangentTest.blender-mikk.glb as mikktspace-exact"
    );
    let mut failures = Vec::new();
    for (method, direction_share) in DIRECTION_AGREE {
        println!("{method:?}, policy INHERIT:");
        let mut total = Tally::default();
        for row in &rows {
            let file = load::load(&dir, row).unwrap_or_else(|e| panic!("{e}"));
            let mut sum = Tally::default();
            for primitive in &file.primitives {
                let (Some(_), Some(stored)) = (&primitive.texcoords, &primitive.stored_tangents) else {
                    continue;
                };
                assert!(primitive.v_down, "{}: {} is not glTF", row.path, primitive.name);
                sum.add(&tally(primitive, stored, method));
            }
            println!("  {}", sum.line(&row.path));
            total.add(&sum);

            let mut require = |ok: bool, what: &str| {
                if !ok {
                    failures.push(format!("{method:?} {}: {what}", row.path));
                }
            };
            let share = |part: usize, whole: usize| part as f64 / whole as f64;
            if sum.vertices > 0 {
                require(sum.negated == sum.vertices, "the flag does more than negate w");
                require(
                    share(sum.w_with_flag, sum.vertices) >= W_AGREE_ALL,
                    "w disagrees with the flag",
                );
                require(
                    share(sum.w_without_flag, sum.vertices) <= 1.0 - W_AGREE_ALL,
                    "w agrees without the flag",
                );
            }
            if sum.front > 0 {
                require(
                    sum.front_w_with_flag == sum.front,
                    "front-facing w disagrees with the flag",
                );
                require(sum.front_w_without_flag == 0, "front-facing w agrees without the flag");
                let direction = share(sum.front_direction_with_flag, sum.front);
                require(
                    direction >= direction_share,
                    "tangent directions disagree with the flag",
                );
            }
        }
        println!("  {}", total.line("all"));
        // Most of the corpus must actually be compared, or the shares above prove little.
        assert!(total.front > 20_000, "only {} vertices compared", total.front);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The snippet the README's glTF section quotes: the flag set, nothing else changed.
#[test]
fn readme_gltf_snippet_compiles_and_runs() {
    // One quad, V down as glTF stores it: v = 0 at the top edge.
    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let normals = [[0.0, 0.0, 1.0]; 4];
    let texcoords = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let indices = [0, 1, 2, 0, 2, 3];
    let tangents = gltf_tangents(&positions, &normals, &texcoords, &indices);
    for t in tangents {
        // T along +U (+X); B = w * cross(N, T) = +Y, the direction of decreasing stored v (up).
        assert_eq!(t, [1.0, 0.0, 0.0, 1.0]);
    }
}
