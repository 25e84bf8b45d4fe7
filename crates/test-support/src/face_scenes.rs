//! Meshes for mikktspace.c's callback interface (`face_meshes`): the stress scenes and corpus
//! primitives as triangles and as quads, quad grids whose quads split either way, and random
//! faces of 3, 4 and 5 vertices drawn from small pools of hostile values.

use super::face_meshes::FaceMesh;
use super::load::Primitive;
use super::mikktspace_scenes::{self, StressMesh};
use super::scenes::Pcg32;

/// A stress mesh's faces, as triangles or (pairs of them) as quads.
pub fn from_stress(mesh: &StressMesh, quads: bool) -> FaceMesh {
    let vertices = [&mesh.positions[..], &mesh.normals[..]];
    FaceMesh::from_triangles(
        mesh.name.clone(),
        vertices,
        &mesh.texcoords,
        &mesh.corner_vertices(),
        quads,
    )
}

/// A corpus primitive's faces, with `v' = 1 - v` when its file stores V downward as glTF does;
/// `None` without texture coordinates.
pub fn from_primitive(primitive: &Primitive, quads: bool) -> Option<FaceMesh> {
    let texcoords = primitive.texcoords.as_ref()?;
    let flip = |[u, v]: [f32; 2]| if primitive.v_down { [u, 1.0 - v] } else { [u, v] };
    let texcoords: Vec<[f32; 2]> = texcoords.iter().copied().map(flip).collect();
    let corners: Vec<usize> = primitive.indices.iter().map(|&i| i as usize).collect();
    let vertices = [&primitive.positions[..], &primitive.normals[..]];
    Some(FaceMesh::from_triangles(
        primitive.name.clone(),
        vertices,
        &texcoords,
        &corners,
        quads,
    ))
}

/// Every generated mesh: the stress scenes both ways, quad grids and random faces.
pub fn all() -> Vec<FaceMesh> {
    let mut meshes = Vec::new();
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
    // Welded corners that differ in the sign of a zero: which one represents them, and so the
    // bits of their tangent, depends on the grid.
    let signed_zeros: Vec<FaceMesh> = mikktspace_scenes::signed_zeros()
        .iter()
        .flat_map(|stress| [from_stress(stress, false), from_stress(stress, true)])
        .collect();
    for far in [100.0, -1e30, f32::NAN] {
        meshes.push(after_ignored_face(&quad_grid(7, 6, 5), far));
        meshes.push(after_ignored_face(&random_faces(41, 60), far));
        meshes.extend(signed_zeros.iter().map(|mesh| after_ignored_face(mesh, far)));
    }
    meshes
}

/// `mesh` behind a first face of 5 vertices at `far`, which mikktspace.c ignores but for its
/// vertex 0's position: that starts the bounding box of its weld, and so moves its grid.
pub fn after_ignored_face(mesh: &FaceMesh, far: f32) -> FaceMesh {
    let mut out = FaceMesh {
        name: format!("{} after an ignored face at {far}", mesh.name),
        ..FaceMesh::default()
    };
    out.push_face((0..5).map(|k| ([far, far + k as f32, far], [0.0, 0.0, 1.0], [0.0, 0.0])));
    for (&start, &size) in mesh.starts.iter().zip(&mesh.sizes) {
        let vertex = |v: usize| (mesh.positions[v], mesh.normals[v], mesh.texcoords[v]);
        out.push_face((start..start + size).map(vertex));
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
