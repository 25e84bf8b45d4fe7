//! Meshes as mikktspace.c's callback interface sees them: faces of any vertex count (3 and 4
//! count, others are ignored), one position, normal and texture coordinate per face vertex; and
//! every `setTSpace` call mikktspace.c makes for them, for comparing its drop-in bit for bit.

use super::mikktspace_scenes::StressMesh;
use super::scenes::Pcg32;

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
    fn push_face(&mut self, vertices: impl IntoIterator<Item = ([f32; 3], [f32; 3], [f32; 2])>) {
        self.starts.push(self.positions.len());
        let before = self.positions.len();
        for (p, n, t) in vertices {
            self.positions.push(p);
            self.normals.push(n);
            self.texcoords.push(t);
        }
        self.sizes.push(self.positions.len() - before);
    }

    /// A triangle mesh's faces; with `quads`, each two triangles `(a, b, c)`, `(a, c, d)` in a row
    /// become the quad `(a, b, c, d)`.
    pub fn from_triangles(mesh: &StressMesh, quads: bool) -> FaceMesh {
        let corners = mesh.corner_vertices();
        let vertex = |v: usize| (mesh.positions[v], mesh.normals[v], mesh.texcoords[v]);
        let mut out = FaceMesh {
            name: format!("{}{}", mesh.name, if quads { " as quads" } else { "" }),
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

    /// A grid of `cols` by `rows` quads over a bumpy sheet, with each quad's UVs stretched so that
    /// either diagonal can be the shorter, some with tied UV diagonals, and mirrored columns.
    pub fn quad_grid(seed: u64, cols: usize, rows: usize) -> FaceMesh {
        let mut rng = Pcg32::new(seed, 27);
        let mut out = FaceMesh {
            name: format!("quad grid {cols}x{rows} (seed {seed})"),
            ..FaceMesh::default()
        };
        let height = |i: usize, j: usize| ((i * 7 + j * 3) % 5) as f32 * 0.1;
        let point = |i: usize, j: usize| [i as f32, j as f32, height(i, j)];
        let normal = |i: usize, j: usize| {
            let [x, y, z] = [height(i, j) - 0.2, 0.3 - height(j, i), 1.0];
            let l = (x * x + y * y + z * z).sqrt();
            [x / l, y / l, z / l]
        };
        for j in 0..rows {
            for i in 0..cols {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let stretch = match below(&mut rng, 3) {
                    0 => 1.0,
                    1 => 0.25,
                    _ => 4.0,
                };
                let mirror = if i % 4 == 3 { -1.0 } else { 1.0 };
                let uv = |(a, b): (usize, usize)| [mirror * a as f32 * 0.1 * stretch, b as f32 * 0.1];
                out.push_face(corners.map(|(a, b)| (point(a, b), normal(a, b), uv((a, b)))));
            }
        }
        out
    }

    /// Faces of 3, 4 and 5 vertices drawn from small pools of values, so that corners weld,
    /// faces degenerate, UVs collapse and mirror, and zeros of both signs and NaN appear.
    pub fn random_faces(seed: u64, faces: usize) -> FaceMesh {
        let mut rng = Pcg32::new(seed, 27);
        let mut out = FaceMesh {
            name: format!("random faces (seed {seed})"),
            ..FaceMesh::default()
        };
        let special = [0.0f32, -0.0, f32::NAN, 1.0, -1.0, 0.5];
        let value = |rng: &mut Pcg32, spread: u32| -> f32 {
            match below(rng, 40) {
                0 => special[below(rng, special.len() as u32) as usize],
                _ => below(rng, spread) as f32 * 0.25,
            }
        };
        for _ in 0..faces {
            let size = [3, 3, 4, 4, 4, 5][below(&mut rng, 6) as usize];
            let vertices: Vec<_> = (0..size)
                .map(|_| {
                    let p = [value(&mut rng, 5), value(&mut rng, 5), value(&mut rng, 3)];
                    let n = [[0.0, 0.0, 1.0], [0.0, 0.6, 0.8], [0.8, 0.0, 0.6], [0.0, -0.0, 1.0]][below(&mut rng, 4) as usize];
                    let t = if below(&mut rng, 8) == 0 { [0.5, 0.5] } else { [value(&mut rng, 4), value(&mut rng, 4)] };
                    (p, n, t)
                })
                .collect();
            out.push_face(vertices);
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
    pub fn new(tangent: [f32; 3], bitangent: [f32; 3], mag_s: f32, mag_t: f32, preserving: bool, face: usize, vert: usize) -> Call {
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

/// Uniform in `0..n`.
fn below(rng: &mut Pcg32, n: u32) -> u32 {
    rng.next_u32() % n
}
