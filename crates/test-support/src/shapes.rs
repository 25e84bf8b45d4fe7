//! Parametric meshes whose true tangents are known: grids over a parameter rectangle, cylinders
//! and UV spheres, built as [`Case`]s.
//!
//! Conventions shared by every builder: `u` grows with the first parameter and `v` with the
//! second, triangles wind counter-clockwise in UV and (seen from outside) in space, so the true
//! handedness is +1 and `bitangent = cross(n, t)` points towards increasing `v`.

use std::f64::consts::PI;

use super::cases::Case;

/// One vertex of a parametric surface.
#[derive(Clone, Copy, Debug)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
}

/// A grid of `(cols + 1) x (rows + 1)` vertices; `vertex(i, j)` gives column `i`, row `j`.
///
/// Vertex `(i, j)` has index `grid_index(cols, i, j)`. Quad `(i, j)` is number `q = j * cols + i`
/// (row by row) and gives triangles `2q = [a, b, c]` and `2q + 1 = [a, c, d]` with `a = (i, j)`,
/// `b = (i + 1, j)`, `c = (i + 1, j + 1)`, `d = (i, j + 1)`.
pub fn grid(name: &str, cols: usize, rows: usize, vertex: impl Fn(usize, usize) -> Vertex) -> Case {
    let mut case = Case {
        name: name.into(),
        texcoords: Some(Vec::new()),
        indices: Some(Vec::new()),
        ..Case::default()
    };
    for j in 0..=rows {
        for i in 0..=cols {
            push(&mut case, vertex(i, j));
        }
    }
    let indices = case.indices.as_mut().unwrap();
    for j in 0..rows {
        for i in 0..cols {
            let [a, b, c, d] = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| grid_index(cols, i, j));
            indices.extend([a, b, c, a, c, d]);
        }
    }
    case
}

/// Index of vertex `(i, j)` in a [`grid`] with `cols` columns of quads.
pub fn grid_index(cols: usize, i: usize, j: usize) -> u32 {
    (j * (cols + 1) + i) as u32
}

/// Appends one vertex to a case that has texture coordinates.
pub fn push(case: &mut Case, vertex: Vertex) {
    case.positions.push(vertex.position);
    case.normals.push(vertex.normal);
    case.texcoords.as_mut().expect("case has texcoords").push(vertex.uv);
}

/// A flat grid in z = 0 over `[0, cols] x [0, rows]` with normal +z and `uv = (x, y) * uv_scale`:
/// the true tangent is +x everywhere.
pub fn flat_grid(name: &str, cols: usize, rows: usize, uv_scale: f32) -> Case {
    grid(name, cols, rows, |i, j| {
        let (x, y) = (i as f32, j as f32);
        Vertex {
            position: [x, y, 0.0],
            normal: [0.0, 0.0, 1.0],
            uv: [x * uv_scale, y * uv_scale],
        }
    })
}

/// Angle around the z axis of column `i` of `segments`; the last column repeats the first exactly,
/// so a seam's two copies of a vertex share their position bit for bit.
fn column_angle(i: usize, segments: usize) -> f64 {
    2.0 * PI * (i % segments) as f64 / segments as f64
}

/// The unit direction of increasing angle around the z axis at angle `phi`: the true tangent of
/// the cylinder and of the sphere, whose `u` follows that angle.
pub fn around_z(phi: f64) -> [f64; 3] {
    [-phi.sin(), phi.cos(), 0.0]
}

fn f32x3(v: [f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
}

/// A unit-radius cylinder around z, `segments` columns around and `rows` rows of height `height`,
/// with a duplicated seam column; `u = i / segments`, `v = j / rows`.
pub fn cylinder(name: &str, segments: usize, rows: usize, height: f64) -> Case {
    grid(name, segments, rows, |i, j| {
        let phi = column_angle(i, segments);
        let radial = [phi.cos(), phi.sin(), 0.0];
        Vertex {
            position: f32x3([radial[0], radial[1], height * j as f64]),
            normal: f32x3(radial),
            uv: [i as f32 / segments as f32, j as f32 / rows as f32],
        }
    })
}

/// How a UV sphere's poles are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Poles {
    /// One pole vertex per segment, at the segment's middle `u` (the usual exporter output).
    PerSegment,
    /// A single vertex per pole shared by every segment, at `u = 0.5`.
    Shared,
}

/// A unit UV sphere: `segments` columns around z, `rings` bands from pole to pole.
///
/// `u = phi / 2 pi`, `v = 1 - theta / pi` (`v` grows northwards, so the handedness is +1), normals
/// are the positions. Vertex order: south pole vertices, rings 1..rings-1 from south to north
/// (`segments + 1` vertices each, the seam duplicated), north pole vertices. Triangle order:
/// the south cap (one per segment), the quads ring by ring as in [`grid`], the north cap.
pub fn uv_sphere(name: &str, segments: usize, rings: usize, poles: Poles) -> Case {
    assert!(segments >= 3 && rings >= 2);
    let mut case = Case {
        name: name.into(),
        texcoords: Some(Vec::new()),
        indices: Some(Vec::new()),
        ..Case::default()
    };
    let pole_count = match poles {
        Poles::PerSegment => segments,
        Poles::Shared => 1,
    };
    let pole = |case: &mut Case, z: f32, v: f32| {
        for i in 0..pole_count {
            let u = match poles {
                Poles::PerSegment => (i as f32 + 0.5) / segments as f32,
                Poles::Shared => 0.5,
            };
            push(
                case,
                Vertex {
                    position: [0.0, 0.0, z],
                    normal: [0.0, 0.0, z],
                    uv: [u, v],
                },
            );
        }
    };
    pole(&mut case, -1.0, 0.0);
    for k in 1..rings {
        let theta = PI * (1.0 - k as f64 / rings as f64);
        for i in 0..=segments {
            let phi = column_angle(i, segments);
            let p = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()];
            push(
                &mut case,
                Vertex {
                    position: f32x3(p),
                    normal: f32x3(p),
                    uv: [i as f32 / segments as f32, k as f32 / rings as f32],
                },
            );
        }
    }
    pole(&mut case, 1.0, 1.0);

    let ring = |k: usize, i: usize| (pole_count + (k - 1) * (segments + 1) + i) as u32;
    let south = |i: usize| (i % pole_count) as u32;
    let north = |i: usize| (pole_count + (rings - 1) * (segments + 1) + i % pole_count) as u32;
    let indices = case.indices.as_mut().unwrap();
    for i in 0..segments {
        indices.extend([south(i), ring(1, i + 1), ring(1, i)]);
    }
    for k in 1..rings - 1 {
        for i in 0..segments {
            let [a, b, c, d] = [ring(k, i), ring(k, i + 1), ring(k + 1, i + 1), ring(k + 1, i)];
            indices.extend([a, b, c, a, c, d]);
        }
    }
    for i in 0..segments {
        indices.extend([ring(rings - 1, i), ring(rings - 1, i + 1), north(i)]);
    }
    case
}

/// The true unit tangent of a [`uv_sphere`] (or [`cylinder`]) vertex with texture coordinate `u`.
pub fn tangent_at_u(u: f32) -> [f64; 3] {
    around_z(2.0 * PI * f64::from(u))
}

/// Rounds every texture coordinate to a multiple of `1 / levels` (8-bit UVs: `levels = 255`).
pub fn quantize_uvs(case: &Case, levels: f32) -> Vec<[f32; 2]> {
    let uvs = case.texcoords.as_ref().expect("case has texcoords");
    uvs.iter().map(|uv| uv.map(|x| (x * levels).round() / levels)).collect()
}

/// A deterministic value in `[-1, 1)` from two integers, for reproducible irregular meshes.
pub fn jitter(a: usize, b: usize) -> f32 {
    let mut h = (a as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (b as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h ^= h >> 29;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h ^= h >> 32;
    ((h >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
}
