//! Meshes for mikktspace.c's callback interface (`face_meshes`): what the triangle scenes cannot
//! express, [`polygon_meshes`] (quads split along either diagonal, the shorter one in UV or in
//! position when the UV diagonals tie; faces of 5 and other counts mikktspace.c ignores, mixed
//! with triangles and quads; quads with one degenerate triangle; the meshes on which it returns
//! 0); quad grids whose quads split either way, random faces of 3, 4 and 5 vertices from small
//! pools of hostile values, meshes behind an ignored first face (whose vertex 0 starts
//! mikktspace.c's bounding box); and every triangle scene and corpus primitive, as triangles and
//! paired into quads. [`generated`] gathers them.

use super::face_meshes::FaceMesh;
use super::load::Primitive;
use super::mikktspace_scenes::{self, height, height_normal, StressMesh};
use super::scenes::Pcg32;
use super::shapes::{grid_index, jitter, Vertex};

/// A stress mesh's faces, as triangles or (pairs of them) as quads.
pub fn from_stress(mesh: &StressMesh, quads: bool) -> FaceMesh {
    let corners: Vec<u32> = mesh.corner_vertices().into_iter().map(|v| v as u32).collect();
    let vertices = [&mesh.positions[..], &mesh.normals[..]];
    FaceMesh::from_triangles(mesh.name.clone(), vertices, &mesh.texcoords, &corners, quads)
}

/// A corpus primitive's faces, as triangles or paired into quads; `None` without texture
/// coordinates, which mikktspace.c needs.
pub fn from_primitive(file: &str, primitive: &Primitive, quads: bool) -> Option<FaceMesh> {
    let name = format!("{file} {}", primitive.name);
    let vertices = [&primitive.positions[..], &primitive.normals[..]];
    let texcoords = primitive.texcoords.as_deref()?;
    Some(FaceMesh::from_triangles(
        name,
        vertices,
        texcoords,
        &primitive.indices,
        quads,
    ))
}

/// What a grid cell becomes: its corners `a = (i, j)`, `b = (i + 1, j)`, `c = (i + 1, j + 1)`,
/// `d = (i, j + 1)`.
#[derive(Clone, Copy, Debug)]
enum Cell {
    /// `a b c d`.
    Quad,
    /// `b c d a`: the same quad, its diagonals numbered the other way.
    QuadTurned,
    /// `a b c` and `a c d`.
    TrianglesAc,
    /// `a b d` and `b c d`.
    TrianglesBd,
    /// A face reporting this many vertices (not 3 or 4: ignored), cycling through `a b c d`.
    Other(i32),
}

/// A grid of `cols x rows` cells whose `(cols + 1) x (rows + 1)` vertices are shared, vertex
/// `(i, j)` at [`grid_index`].
fn grid(
    name: &str,
    (cols, rows): (usize, usize),
    vertex: impl Fn(usize, usize) -> Vertex,
    cell: impl Fn(usize, usize) -> Cell,
) -> FaceMesh {
    let mut mesh = FaceMesh::new(name);
    for j in 0..=rows {
        for i in 0..=cols {
            mesh.vertex(vertex(i, j));
        }
    }
    for j in 0..rows {
        for i in 0..cols {
            let [a, b, c, d] = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| grid_index(cols, i, j));
            add_cell(&mut mesh, cell(i, j), [a, b, c, d]);
        }
    }
    mesh
}

fn add_cell(mesh: &mut FaceMesh, cell: Cell, [a, b, c, d]: [u32; 4]) {
    match cell {
        Cell::Quad => mesh.face(&[a, b, c, d]),
        Cell::QuadTurned => mesh.face(&[b, c, d, a]),
        Cell::TrianglesAc => {
            mesh.face(&[a, b, c]);
            mesh.face(&[a, c, d]);
        }
        Cell::TrianglesBd => {
            mesh.face(&[a, b, d]);
            mesh.face(&[b, c, d]);
        }
        Cell::Other(size) => {
            let vertices: Vec<u32> = [a, b, c, d].into_iter().cycle().take(size.max(0) as usize).collect();
            mesh.sized_face(size, &vertices);
        }
    }
}

/// A vertex of the height field at `(x, y)` with texture coordinate `uv`.
fn on_height_field(x: f32, y: f32, uv: [f32; 2]) -> Vertex {
    Vertex {
        position: [x, y, height(x, y)],
        normal: height_normal(x, y),
        uv,
    }
}

/// The height field over the grid, texture coordinates following x and y scaled by `scale`, each
/// moved by up to `uv_jitter` (in grid units) so that either diagonal of a quad can be the
/// shorter one.
fn height_vertex(scale: f32, uv_jitter: f32) -> impl Fn(usize, usize) -> Vertex {
    move |i, j| {
        let (x, y) = (i as f32, j as f32);
        let uv = [
            (x + uv_jitter * jitter(i, j)) * scale,
            (y + uv_jitter * jitter(j + 11, i)) * scale,
        ];
        on_height_field(x, y, uv)
    }
}

/// A flat vertex at `(x, y, 0)` facing +z.
fn flat(x: f32, y: f32, uv: [f32; 2]) -> Vertex {
    Vertex {
        position: [x, y, 0.0],
        normal: [0.0, 0.0, 1.0],
        uv,
    }
}

/// Cells drawn at random: mostly quads either way round, triangles split either way, and faces
/// of other counts (5, 6, 0, 1, 2, -1) that mikktspace.c ignores.
fn mixed_cells(cols: usize, rows: usize, seed: u64) -> Vec<Cell> {
    let mut rng = Pcg32::new(seed, 29);
    (0..cols * rows)
        .map(|_| match rng.next_u32() % 16 {
            0..=4 => Cell::Quad,
            5..=7 => Cell::QuadTurned,
            8..=9 => Cell::TrianglesAc,
            10..=11 => Cell::TrianglesBd,
            12 => Cell::Other(5),
            13 => Cell::Other(6),
            14 => Cell::Other([0, 1, 2][rng.next_u32() as usize % 3]),
            _ => Cell::Other(-1),
        })
        .collect()
}

/// Quads whose diagonals differ in UV (either one the shorter), tie in UV and differ in position,
/// or tie in both; in both vertex orders.
fn quad_diagonals() -> Vec<FaceMesh> {
    let turned = |i: usize, j: usize| {
        if (i * 3 + j) % 4 == 0 {
            Cell::QuadTurned
        } else {
            Cell::Quad
        }
    };
    // UV on an exact binary grid: both UV diagonals of every cell have the same length in float.
    let square_uv = |i: usize, j: usize| [i as f32 * 0.125, j as f32 * 0.125];
    vec![
        grid("quads: uv diagonals differ", (12, 10), height_vertex(0.1, 0.3), turned),
        grid(
            "quads: uv diagonals differ, large jitter",
            (12, 10),
            height_vertex(0.1, 0.45),
            |_, _| Cell::Quad,
        ),
        grid(
            "quads: uv diagonals tie, positions decide",
            (12, 10),
            |i, j| {
                let (x, y) = (i as f32 + 0.3 * jitter(i, j), j as f32 + 0.3 * jitter(j + 5, i));
                on_height_field(x, y, square_uv(i, j))
            },
            turned,
        ),
        grid(
            "quads: uv diagonals tie, sheared positions",
            (8, 6),
            |i, j| flat(i as f32 + 0.5 * j as f32, j as f32, square_uv(i, j)),
            turned,
        ),
        grid(
            "quads: both diagonals tie",
            (8, 6),
            |i, j| flat(i as f32, j as f32, square_uv(i, j)),
            turned,
        ),
    ]
}

/// Triangles, quads and ignored faces of other counts in one mesh, at two sizes; and one whose
/// face 0, a pentagon, lies far from the rest: mikktspace.c reads face 0's vertex 0 into the
/// bounding box of its weld whatever face 0's count.
fn mixed_faces() -> Vec<FaceMesh> {
    let mut meshes: Vec<FaceMesh> = [(10, 8, 1), (60, 50, 2)]
        .into_iter()
        .map(|(cols, rows, seed)| {
            let cells = mixed_cells(cols, rows, seed);
            grid(
                &format!("mixed 3-, 4- and other faces {cols}x{rows}"),
                (cols, rows),
                height_vertex(0.1, 0.3),
                |i, j| cells[j * cols + i],
            )
        })
        .collect();
    let mut far = meshes[0].clone();
    far.name = "mixed faces: face 0 an ignored pentagon far away".into();
    let pentagon: Vec<u32> = (0..5)
        .map(|k| far.vertex(flat(1000.0 + k as f32, -700.0, [0.1 * k as f32, 0.0])))
        .collect();
    far.face_sizes.insert(0, 5);
    far.face_vertices.splice(0..0, pentagon);
    far.reported_faces += 1;
    meshes.push(far);
    meshes
}

/// UV mirrored about a column (its vertices shared by both sides) and about a row.
fn mirrored_uvs() -> Vec<FaceMesh> {
    let mirrored_u = |i: usize, j: usize| {
        let (x, y) = (i as f32, j as f32);
        on_height_field(x, y, [(x - 6.0).abs() * 0.1, (y + 0.2 * jitter(j, i)) * 0.1])
    };
    let mirrored_v = |i: usize, j: usize| {
        let (x, y) = (i as f32, j as f32);
        on_height_field(x, y, [(x + 0.2 * jitter(i, j)) * 0.1, (y - 4.0).abs() * 0.1])
    };
    let cells = mixed_cells(12, 8, 3);
    vec![
        grid("quads: u mirrored", (12, 8), mirrored_u, |_, _| Cell::Quad),
        grid("mixed faces: v mirrored", (12, 8), mirrored_v, |i, j| cells[j * 12 + i]),
    ]
}

/// Texture coordinates collapsed: a block of vertices to one point, a row to a line, all of them.
fn collapsed_uvs() -> Vec<FaceMesh> {
    let block = |i: usize, j: usize| {
        let vertex = height_vertex(0.1, 0.2)(i, j);
        if (3..=6).contains(&i) && (2..=5).contains(&j) {
            Vertex {
                uv: [0.4, 0.3],
                ..vertex
            }
        } else {
            vertex
        }
    };
    let row = |i: usize, j: usize| {
        let vertex = height_vertex(0.1, 0.2)(i, j);
        Vertex {
            uv: [vertex.uv[0], if j == 3 || j == 4 { 0.35 } else { vertex.uv[1] }],
            ..vertex
        }
    };
    let all = |i: usize, j: usize| Vertex {
        uv: [0.5, 0.5],
        ..height_vertex(0.1, 0.0)(i, j)
    };
    let cells = mixed_cells(10, 8, 4);
    vec![
        grid("quads: uv block collapsed", (10, 8), block, |_, _| Cell::Quad),
        grid("mixed faces: uv rows collapsed", (10, 8), row, |i, j| cells[j * 10 + i]),
        grid("quads: all uvs equal", (6, 4), all, |_, _| Cell::Quad),
    ]
}

/// Faces of no area: quads whose four corners coincide or lie on a line, in an otherwise flat
/// grid, and a grid of triangles and quads all at one point.
fn zero_area_faces() -> Vec<FaceMesh> {
    let pinched = |i: usize, j: usize| {
        let uv = [i as f32 * 0.1 + 0.02 * jitter(i, j), j as f32 * 0.1];
        // Column 4 is pulled onto column 3 on rows 2 to 4 (cells (3, 2..4) have no area); row 6
        // is pulled onto row 5 on columns 0 to 2.
        let x = if i == 4 && (2..=4).contains(&j) { 3.0 } else { i as f32 };
        let y = if j == 6 && i <= 2 { 5.0 } else { j as f32 };
        flat(x, y, uv)
    };
    let point = |i: usize, j: usize| flat(1.0, 1.0, [i as f32 * 0.1, j as f32 * 0.1]);
    let cells = mixed_cells(6, 4, 5);
    vec![
        grid("quads: zero-area cells", (8, 8), pinched, |_, _| Cell::Quad),
        grid("mixed faces: all at one point", (6, 4), point, |i, j| cells[j * 6 + i]),
    ]
}

/// Quads of which one triangle, once split, has two equal positions (mikktspace.c's
/// one-degenerate-triangle quads), on their own and sharing vertices in a grid.
fn quads_with_one_degenerate_triangle() -> Vec<FaceMesh> {
    let mut separate = FaceMesh::new("quads: one degenerate triangle, separate");
    let mut rng = Pcg32::new(6, 31);
    for q in 0..40 {
        let (x, y) = ((q % 8) as f32 * 1.5, (q / 8) as f32 * 1.5);
        let mut corners = [[x, y], [x + 1.0, y], [x + 1.0, y + 1.0], [x, y + 1.0]];
        // Corner k takes the position of corner k + 1; every fifth quad two corners collapse.
        let k = rng.next_u32() as usize % 4;
        corners[k] = corners[(k + 1) % 4];
        if q % 5 == 0 {
            corners[(k + 2) % 4] = corners[(k + 3) % 4];
        }
        let uv_jitter = rng.symmetric(0.2) as f32;
        let uvs = [[0.0, 0.0], [1.0 + uv_jitter, 0.0], [1.0, 1.0], [0.0, 1.0 - uv_jitter]];
        let vertices: Vec<u32> = corners
            .iter()
            .zip(uvs)
            .map(|(&[x, y], uv)| separate.vertex(flat(x, y, uv)))
            .collect();
        separate.face(&vertices);
    }
    // In a grid: some vertices moved onto their right neighbour, so that the cells on both sides of
    // that edge have one degenerate triangle.
    let mut rng = Pcg32::new(7, 31);
    let moved: Vec<bool> = (0..11 * 9).map(|_| rng.next_u32() % 6 == 0).collect();
    let shared = grid(
        "quads: one degenerate triangle, shared",
        (10, 8),
        |i, j| {
            let vertex = height_vertex(0.1, 0.3)(i, j);
            if i < 10 && moved[j * 11 + i] {
                Vertex {
                    position: height_vertex(0.1, 0.3)(i + 1, j).position,
                    ..vertex
                }
            } else {
                vertex
            }
        },
        |i, j| if (i + j) % 2 == 0 { Cell::Quad } else { Cell::QuadTurned },
    );
    vec![separate, shared]
}

/// NaN in a position, a normal and a texture coordinate, and `+0`/`-0` in otherwise equal
/// vertices: a flat grid at z = 0 whose quads each have their own vertices (which mikktspace.c
/// welds), zeros signed at random.
fn non_finite_and_signed_zeros() -> Vec<FaceMesh> {
    let mut zeros = FaceMesh::new("quads: signed zeros");
    let mut rng = Pcg32::new(8, 37);
    let mut signed = |value: f32| {
        if value == 0.0 && rng.next_u32() & 1 == 1 {
            -0.0
        } else {
            value
        }
    };
    for j in 0..6 {
        for i in 0..8 {
            let vertices: Vec<u32> = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
                .iter()
                .map(|&(i, j)| {
                    let (x, y) = (i as f32 - 4.0, j as f32 - 3.0);
                    let vertex = Vertex {
                        position: [signed(x), signed(y), signed(0.0)],
                        normal: [signed(0.0), signed(0.0), 1.0],
                        uv: [signed(x * 0.125), signed(y * 0.125)],
                    };
                    zeros.vertex(vertex)
                })
                .collect();
            zeros.face(&vertices);
        }
    }
    let nan = |i: usize, j: usize| {
        let mut vertex = height_vertex(0.1, 0.3)(i, j);
        match (i, j) {
            (2, 2) => vertex.position[1] = f32::NAN,
            (6, 3) => vertex.normal[0] = f32::NAN,
            (4, 6) => vertex.uv[0] = f32::NAN,
            (8, 6) => vertex.position = [f32::NAN; 3],
            _ => {}
        }
        vertex
    };
    let cells = mixed_cells(10, 8, 9);
    vec![zeros, grid("mixed faces: NaN", (10, 8), nan, |i, j| cells[j * 10 + i])]
}

/// The smallest meshes, and those on which mikktspace.c returns 0: no face, a negative face count,
/// and faces of no count it takes.
fn edge_cases() -> Vec<FaceMesh> {
    let quad = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut single_quad = FaceMesh::new("a single quad");
    let vertices: Vec<u32> = quad
        .iter()
        .map(|&[x, y]| single_quad.vertex(flat(x, y, [x, y])))
        .collect();
    single_quad.face(&vertices);

    let mut single_triangle = FaceMesh::new("a single triangle");
    let vertices: Vec<u32> = quad[..3]
        .iter()
        .map(|&[x, y]| single_triangle.vertex(flat(x, y, [x, y])))
        .collect();
    single_triangle.face(&vertices);

    let mut no_face = single_quad.clone();
    no_face.name = "no face".into();
    no_face.face_sizes.clear();
    no_face.face_vertices.clear();
    no_face.reported_faces = 0;

    let mut negative = single_quad.clone();
    negative.name = "a negative face count".into();
    negative.reported_faces = -1;

    let mut ignored = FaceMesh::new("only faces of other counts");
    let vertices: Vec<u32> = quad.iter().map(|&[x, y]| ignored.vertex(flat(x, y, [x, y]))).collect();
    for size in [5, 2, 0, -3, 6, 1] {
        let face: Vec<u32> = vertices.iter().copied().cycle().take(size.max(0) as usize).collect();
        ignored.sized_face(size, &face);
    }
    vec![single_quad, single_triangle, no_face, negative, ignored]
}

/// The face meshes built here, a few vertices to about 3000 each.
pub fn polygon_meshes() -> Vec<FaceMesh> {
    let mut meshes = Vec::new();
    meshes.extend(quad_diagonals());
    meshes.extend(mixed_faces());
    meshes.extend(mirrored_uvs());
    meshes.extend(collapsed_uvs());
    meshes.extend(zero_area_faces());
    meshes.extend(quads_with_one_degenerate_triangle());
    meshes.extend(non_finite_and_signed_zeros());
    meshes.extend(edge_cases());
    meshes
}

/// Every generated mesh: [`polygon_meshes`], the stress scenes as triangles and as quads, quad
/// grids, random faces, and meshes behind an ignored first face.
pub fn generated() -> Vec<FaceMesh> {
    let mut meshes = polygon_meshes();
    for stress in mikktspace_scenes::all() {
        meshes.push(from_stress(&stress, false));
        meshes.push(from_stress(&stress, true));
    }
    for seed in 0..4 {
        meshes.push(quad_grid(seed, 12, 9));
    }
    for seed in 0..40 {
        meshes.push(random_faces(seed, 60));
    }
    // Welded corners that differ in the sign of a zero (which one represents them, and so the
    // bits of their tangent, depends on the grid), and a first position with a NaN (which makes
    // the box NaN when it starts it, and nothing when an ignored face's vertex does).
    let stress = mikktspace_scenes::signed_zeros()
        .into_iter()
        .chain(mikktspace_scenes::non_finite());
    let grid_sensitive: Vec<FaceMesh> = stress
        .flat_map(|stress| [from_stress(&stress, false), from_stress(&stress, true)])
        .collect();
    for far in [100.0, -1e30, f32::NAN] {
        meshes.push(after_ignored_face(&quad_grid(7, 6, 5), far));
        meshes.push(after_ignored_face(&random_faces(41, 60), far));
        meshes.extend(grid_sensitive.iter().map(|mesh| after_ignored_face(mesh, far)));
    }
    meshes
}

/// Behind a first face of 5 vertices, which mikktspace.c ignores but for its vertex 0's position,
/// 3 to 14 triangles over 3 to 8 vertices in a box at most 1 wide, the first triangle's first
/// corner alone far out at x = `far_x`. mikktspace.c's weld starts its bounding box at that
/// ignored vertex and leaves the first corner out: that corner's position must not widen the box,
/// whose grid decides which corner represents each welded vertex, and so the edge sort's last run.
pub fn far_first_corner(seed: u64, far_x: f32) -> FaceMesh {
    let mut rng = Pcg32::new(seed, 29);
    let mut below = |n: usize| rng.next_u32() as usize % n;
    let mut out = FaceMesh::new(&format!("far first corner behind an ignored face (seed {seed})"));
    out.push_face((0..5).map(|_| ([0.5, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0])));
    let up = [0.0, 0.0, 1.0];
    let far = out.vertex(Vertex {
        position: [far_x, 0.0, 0.0],
        normal: up,
        uv: [0.9, 0.1],
    });
    // Few distinct coordinates, so that positions repeat and weld.
    let levels = [0.0f32, 0.001, 0.003, 0.2, 0.5, 0.8, 1.0];
    let pool: Vec<u32> = (0..3 + below(6))
        .map(|_| {
            let [x, y] = [levels[below(levels.len())], levels[below(3)]];
            let uv = [3.0 * x + y, 5.0 * y - x];
            out.vertex(Vertex {
                position: [x, y, 0.0],
                normal: up,
                uv,
            })
        })
        .collect();
    for t in 0..3 + below(12) {
        let mut face = if t == 0 { vec![far] } else { Vec::new() };
        while face.len() < 3 {
            let v = pool[below(pool.len())];
            if !face.contains(&v) {
                face.push(v);
            }
        }
        out.face(&face);
    }
    out
}

/// `mesh` behind a first face of 5 vertices at `far`, which mikktspace.c ignores but for its
/// vertex 0's position: that starts the bounding box of its weld, and so moves its grid.
pub fn after_ignored_face(mesh: &FaceMesh, far: f32) -> FaceMesh {
    let mut out = FaceMesh::new(&format!("{} after an ignored face at {far}", mesh.name));
    out.push_face((0..5).map(|k| ([far, far + k as f32, far], [0.0, 0.0, 1.0], [0.0, 0.0])));
    for (start, &size) in mesh.face_starts().into_iter().zip(&mesh.face_sizes) {
        let vertex = |&v: &u32| {
            let v = v as usize;
            (mesh.positions[v], mesh.normals[v], mesh.texcoords[v])
        };
        out.push_face(
            mesh.face_vertices[start..start + size.max(0) as usize]
                .iter()
                .map(vertex),
        );
    }
    out
}

/// A grid of `cols` by `rows` quads over a bumpy sheet, with each quad's UVs stretched so that
/// either diagonal can be the shorter, some with tied UV diagonals, and mirrored columns.
pub fn quad_grid(seed: u64, cols: usize, rows: usize) -> FaceMesh {
    let mut rng = Pcg32::new(seed, 27);
    let mut out = FaceMesh::new(&format!("quad grid {cols}x{rows} (seed {seed})"));
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
    let mut out = FaceMesh::new(&format!("random faces (seed {seed})"));
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
                let n =
                    [[0.0, 0.0, 1.0], [0.0, 0.6, 0.8], [0.8, 0.0, 0.6], [0.0, -0.0, 1.0]][below(&mut rng, 4) as usize];
                let t = if below(&mut rng, 8) == 0 {
                    [0.5, 0.5]
                } else {
                    [value(&mut rng, 4), value(&mut rng, 4)]
                };
                (p, n, t)
            })
            .collect();
        out.push_face(vertices);
    }
    out
}

/// Uniform in `0..n`.
fn below(rng: &mut Pcg32, n: u32) -> u32 {
    rng.next_u32() % n
}
