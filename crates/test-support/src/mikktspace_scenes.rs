//! Meshes that stress an exact reimplementation of mikktspace.c, each deterministic.
//!
//! mikktspace.c welds corners whose position, normal and texture coordinate compare equal with
//! `==` (so `+0.0` welds with `-0.0` and NaN with nothing), picks a representative per weld in an
//! order that depends on a spatial split of all positions, groups corners by UV orientation over
//! shared edges, drops triangles with two equal positions and copies their corners' frames from
//! elsewhere. Every scene here aims at one of those steps: mirror seams, quads split both ways,
//! collapsed and quantised UVs, poles and fans whose tangents cancel exactly, duplicates that
//! differ only in their normal or in the sign of a zero, non-finite, huge and subnormal values,
//! degenerate triangles, non-manifold edges, unindexed and 16-bit indexed meshes, a large grid
//! and a random soup.
//!
//! Used by `crates/tbasis/tests/mikktspace.rs`; it uses only its sibling
//! modules `cases`, `scenes` and `shapes`, so a fuzz target or bench can include it the same way.

use super::cases::{self, Case};
use super::scenes::{self, Pcg32, SceneSpec};
use super::shapes::{self, Poles, Vertex};
use tbasis::{Indices, Mesh, Strided};

/// The index buffer as stored.
#[derive(Clone, Debug)]
pub enum IndexData {
    /// Triangle `t` is vertices `3t..3t+3`.
    None,
    U16(Vec<u16>),
    U32(Vec<u32>),
}

/// A mesh with texture coordinates, in packed arrays.
#[derive(Clone, Debug)]
pub struct StressMesh {
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub texcoords: Vec<[f32; 2]>,
    pub indices: IndexData,
}

impl StressMesh {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The index count, or the vertex count when unindexed.
    pub fn corner_count(&self) -> usize {
        match &self.indices {
            IndexData::None => self.vertex_count(),
            IndexData::U16(indices) => indices.len(),
            IndexData::U32(indices) => indices.len(),
        }
    }

    /// The indices widened to u32; `None` when unindexed.
    pub fn indices_u32(&self) -> Option<Vec<u32>> {
        match &self.indices {
            IndexData::None => None,
            IndexData::U16(indices) => Some(indices.iter().map(|&i| u32::from(i)).collect()),
            IndexData::U32(indices) => Some(indices.clone()),
        }
    }

    /// The vertex of every corner.
    pub fn corner_vertices(&self) -> Vec<usize> {
        match self.indices_u32() {
            None => (0..self.vertex_count()).collect(),
            Some(indices) => indices.into_iter().map(|i| i as usize).collect(),
        }
    }

    /// The library's view of this mesh.
    pub fn mesh(&self) -> Mesh<'_> {
        Mesh {
            positions: Strided::from_slice(&self.positions),
            normals: Strided::from_slice(&self.normals),
            texcoords: Some(Strided::from_slice(&self.texcoords)),
            indices: match &self.indices {
                IndexData::None => Indices::None,
                IndexData::U16(indices) => Indices::U16(Strided::from_slice(indices)),
                IndexData::U32(indices) => Indices::U32(Strided::from_slice(indices)),
            },
        }
    }

    /// A test case as a stress mesh; `None` when it has no texture coordinates (mikktspace.c
    /// needs them).
    pub fn from_case(case: Case) -> Option<StressMesh> {
        Some(StressMesh {
            name: case.name,
            positions: case.positions,
            normals: case.normals,
            texcoords: case.texcoords?,
            indices: match case.indices {
                Some(indices) => IndexData::U32(indices),
                None => IndexData::None,
            },
        })
    }

    /// The same triangles without an index buffer: every corner its own vertex.
    pub fn unindexed(&self) -> StressMesh {
        let corners = self.corner_vertices();
        StressMesh {
            name: format!("{} unindexed", self.name),
            positions: corners.iter().map(|&v| self.positions[v]).collect(),
            normals: corners.iter().map(|&v| self.normals[v]).collect(),
            texcoords: corners.iter().map(|&v| self.texcoords[v]).collect(),
            indices: IndexData::None,
        }
    }

    /// The same mesh with 16-bit indices (it must have at most 65536 vertices).
    pub fn with_u16_indices(&self) -> StressMesh {
        let indices = self.corner_vertices();
        let indices = indices
            .iter()
            .map(|&v| u16::try_from(v).expect("16-bit index"))
            .collect();
        StressMesh {
            name: format!("{} u16", self.name),
            indices: IndexData::U16(indices),
            ..self.clone()
        }
    }
}

fn from_case(case: Case) -> StressMesh {
    StressMesh::from_case(case).expect("the case has texture coordinates")
}

fn from_scene(scene: scenes::Scene, name: &str) -> StressMesh {
    StressMesh {
        name: name.to_string(),
        positions: scene.positions,
        normals: scene.normals,
        texcoords: scene.texcoords,
        indices: IndexData::U32(scene.indices),
    }
}

/// Every stress scene, from a few triangles up to the large grid (about 100k vertices).
pub fn all() -> Vec<StressMesh> {
    let mut meshes = Vec::new();
    // Every stability case with texture coordinates: collapsed and collinear UVs, slivers,
    // zero-area triangles, repeated indices, a NaN, +-inf in every component, zero normals ...
    meshes.extend(cases::all_cases().into_iter().filter_map(StressMesh::from_case));
    meshes.extend(mirror_seams());
    meshes.extend(quads_split_both_ways());
    meshes.extend(collapsed_uvs());
    meshes.extend(quantised_uvs());
    meshes.extend(poles());
    meshes.extend(duplicate_positions());
    meshes.extend(signed_zeros());
    meshes.extend(non_finite());
    meshes.extend(extreme_magnitudes());
    meshes.extend(degenerate_triangles());
    meshes.extend(non_manifold());
    meshes.push(random_soup(1000, 2000, 7));
    meshes.push(large_grid());
    // The same triangles unindexed and with 16-bit indices, for a few of the trickier scenes.
    let variants: Vec<StressMesh> = meshes
        .iter()
        .filter(|m| VARIANT_SOURCES.contains(&m.name.as_str()))
        .flat_map(|m| [m.unindexed(), m.with_u16_indices()])
        .collect();
    assert_eq!(variants.len(), 2 * VARIANT_SOURCES.len(), "every variant source exists");
    meshes.extend(variants);
    meshes
}

/// Scenes also checked unindexed and with 16-bit indices.
const VARIANT_SOURCES: [&str; 8] = [
    "mirror_fold",
    "mirror_fold_split_seam",
    "quads_random_diagonals",
    "signed_zeros lifted seed 1 copies 3",
    "non_finite_scattered seed 1",
    "butterfly 4 mixed winding",
    "polar_fan 64 cone",
    "degenerate_mix",
];

/// A smooth height field `z(x, y)`, so that the diagonal a quad is split along matters.
pub fn height(x: f32, y: f32) -> f32 {
    0.3 * (0.7 * x).sin() * (0.5 * y).cos()
}

/// Its unit normal.
pub fn height_normal(x: f32, y: f32) -> [f32; 3] {
    let dx = 0.3 * 0.7 * (0.7 * x).cos() * (0.5 * y).cos();
    let dy = -0.3 * 0.5 * (0.7 * x).sin() * (0.5 * y).sin();
    let n = [-dx, -dy, 1.0];
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / length)
}

/// A jittered height-field grid of `cols x rows` quads over `[0, cols] x [0, rows]`, UVs following
/// x and y with jitter; quad `(i, j)` is split along a-c when `split(i, j)`, else along b-d.
fn height_grid(
    name: &str,
    cols: usize,
    rows: usize,
    uv_scale: f32,
    split: impl Fn(usize, usize) -> bool,
) -> StressMesh {
    let mut mesh = StressMesh {
        name: name.to_string(),
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        indices: IndexData::U32(Vec::new()),
    };
    for j in 0..=rows {
        for i in 0..=cols {
            let (x, y) = (i as f32, j as f32);
            mesh.positions.push([x, y, height(x, y)]);
            mesh.normals.push(height_normal(x, y));
            let uv = [
                (x + 0.2 * shapes::jitter(i, j)) * uv_scale,
                (y + 0.2 * shapes::jitter(j + 11, i)) * uv_scale,
            ];
            mesh.texcoords.push(uv);
        }
    }
    let IndexData::U32(indices) = &mut mesh.indices else {
        unreachable!()
    };
    for j in 0..rows {
        for i in 0..cols {
            let [a, b, c, d] =
                [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| shapes::grid_index(cols, i, j));
            if split(i, j) {
                indices.extend([a, b, c, a, c, d]);
            } else {
                indices.extend([a, b, d, b, c, d]);
            }
        }
    }
    mesh
}

/// UV mirrored halves with the seam split into copies of equal attributes (which mikktspace.c
/// welds back together), on flat and curved surfaces, and a height field sharing its seam.
pub fn mirror_seams() -> Vec<StressMesh> {
    let fold = from_case(cases::mirror_fold());
    // The same grid with the seam column (x = 0) duplicated: the right half uses the copies.
    let (cols, rows) = cases::MIRROR_GRID;
    let mut split = fold.clone();
    split.name = "mirror_fold_split_seam".into();
    let seam = cols / 2;
    let mut copy_of = vec![None; fold.vertex_count()];
    for j in 0..=rows {
        let v = shapes::grid_index(cols, seam, j) as usize;
        copy_of[v] = Some(split.positions.len() as u32);
        split.positions.push(fold.positions[v]);
        split.normals.push(fold.normals[v]);
        split.texcoords.push(fold.texcoords[v]);
    }
    let IndexData::U32(indices) = &mut split.indices else {
        unreachable!()
    };
    for triangle in indices.chunks_exact_mut(3) {
        // Right of the seam: some corner has x > 0.
        if triangle.iter().any(|&v| fold.positions[v as usize][0] > 0.0) {
            for v in triangle.iter_mut() {
                if let Some(copy) = copy_of[*v as usize] {
                    *v = copy;
                }
            }
        }
    }
    let torus = from_scene(scenes::build(&SceneSpec::mirrored_torus(2_000)), "mirrored_torus");
    let sphere = from_scene(
        scenes::build(&SceneSpec {
            mirrored: true,
            ..SceneSpec::sphere(2_000)
        }),
        "mirrored_sphere",
    );
    // A height field mirrored in u about x = 4, its seam vertices shared.
    let mut height_mirror = height_grid("height_mirror", 8, 6, 0.125, |i, j| (i + j) % 3 != 0);
    for (uv, p) in height_mirror.texcoords.iter_mut().zip(&height_mirror.positions) {
        uv[0] = (p[0] - 4.0).abs() * 0.125;
    }
    // `mirror_fold` itself is one of the stability cases.
    vec![split, torus, sphere, height_mirror]
}

/// Non-planar quads split along either diagonal: all one way, all the other, alternating, random.
pub fn quads_split_both_ways() -> Vec<StressMesh> {
    let mut rng = Pcg32::new(3, 17);
    let random: Vec<bool> = (0..12 * 10).map(|_| rng.next_u32() & 1 == 1).collect();
    vec![
        height_grid("quads_ac_diagonals", 12, 10, 0.1, |_, _| true),
        height_grid("quads_bd_diagonals", 12, 10, 0.1, |_, _| false),
        height_grid("quads_checkerboard_diagonals", 12, 10, 0.1, |i, j| (i + j) % 2 == 0),
        height_grid("quads_random_diagonals", 12, 10, 0.1, |i, j| random[j * 12 + i]),
    ]
}

/// Grids with blocks of equal UVs (whole triangles collapsed to a point, their neighbours to
/// segments), rows collapsed to a line, and one fully collapsed.
pub fn collapsed_uvs() -> Vec<StressMesh> {
    let (cols, rows) = (10, 8);
    let mut block = height_grid("collapsed_uv_block", cols, rows, 0.1, |i, j| (i * 7 + j) % 3 != 0);
    for j in 2..=5 {
        for i in 3..=6 {
            block.texcoords[shapes::grid_index(cols, i, j) as usize] = [0.4, 0.3];
        }
    }
    // Two blocks of the same UV far apart, and single collapsed triangles scattered.
    let mut scattered = height_grid("collapsed_uv_scattered", cols, rows, 0.1, |i, j| (i + 2 * j) % 4 != 0);
    let IndexData::U32(indices) = scattered.indices.clone() else {
        unreachable!()
    };
    for (t, triangle) in indices.chunks_exact(3).enumerate() {
        if t % 7 == 3 {
            let uv = scattered.texcoords[triangle[0] as usize];
            for &v in triangle {
                scattered.texcoords[v as usize] = uv;
            }
        }
    }
    let mut rows_collapsed = height_grid("collapsed_uv_rows", cols, rows, 0.1, |_, _| true);
    for j in [2, 3, 6] {
        for i in 0..=cols {
            rows_collapsed.texcoords[shapes::grid_index(cols, i, j) as usize][1] = 0.25;
        }
    }
    let mut everything = height_grid("collapsed_uv_everywhere", 4, 4, 0.1, |i, _| i % 2 == 0);
    everything.texcoords.iter_mut().for_each(|uv| *uv = [0.5, 0.5]);
    vec![block, scattered, rows_collapsed, everything]
}

/// Texture coordinates rounded to multiples of 1/256 on meshes finer than that: some triangles
/// collapse to segments or points, many share exactly equal UV edges.
pub fn quantised_uvs() -> Vec<StressMesh> {
    let quantise = |mut mesh: StressMesh, name: &str| {
        mesh.name = name.into();
        for uv in &mut mesh.texcoords {
            *uv = uv.map(|x| (x * 256.0).round() / 256.0);
        }
        mesh
    };
    let torus = from_scene(scenes::build(&SceneSpec::torus(3_000)), "torus");
    let sphere = from_case(shapes::uv_sphere("sphere", 300, 40, Poles::PerSegment));
    let grid = height_grid("grid", 40, 30, 1.0 / 300.0, |i, j| (i ^ j) & 1 == 0);
    vec![
        quantise(torus, "quantised_torus"),
        quantise(sphere, "quantised_sphere_300x40"),
        quantise(grid, "quantised_grid"),
    ]
}

/// Unit vectors at angles `2 pi k / n` (`n` a multiple of 4), exactly symmetric: the first
/// quarter is computed, the others are it turned by exact quarter turns, so that directions `k`
/// and `k + n/2` are exact negations.
pub fn symmetric_circle(n: usize) -> Vec<[f32; 2]> {
    assert!(n % 4 == 0 && n > 0);
    let quarter: Vec<[f32; 2]> = (0..n / 4)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / n as f64;
            [angle.cos() as f32, angle.sin() as f32]
        })
        .collect();
    (0..n)
        .map(|k| {
            let [c, s] = quarter[k % (n / 4)];
            match k / (n / 4) {
                0 => [c, s],
                1 => [-s, c],
                2 => [-c, -s],
                _ => [s, -c],
            }
        })
        .collect()
}

/// A fan of `n` triangles around one apex vertex at height `apex_height` over a unit rim in
/// z = 0, with a polar UV mapping: `u = k / n` around the rim (its last vertex repeats the first
/// at `u = 1`), `v = 0` on the rim, the apex at `(0.5, 1)`. Every triangle's tangent is its rim
/// chord, so opposite triangles' tangents are exact negations and the apex's angle-weighted sum
/// cancels.
pub fn polar_fan(n: usize, apex_height: f32, name: &str) -> StressMesh {
    let rim = symmetric_circle(n);
    let mut mesh = StressMesh {
        name: name.to_string(),
        positions: vec![[0.0, 0.0, apex_height]],
        normals: vec![[0.0, 0.0, 1.0]],
        texcoords: vec![[0.5, 1.0]],
        indices: IndexData::U32(Vec::new()),
    };
    // The cone's rim normals (c, s, h) / |(c, s, h)|, scaled by one exact factor for symmetry.
    let scale = 1.0 / (1.0 + apex_height * apex_height).sqrt();
    for k in 0..=n {
        let [c, s] = rim[k % n];
        mesh.positions.push([c, s, 0.0]);
        mesh.normals.push(if apex_height == 0.0 {
            [0.0, 0.0, 1.0]
        } else {
            [c * scale, s * scale, apex_height * scale]
        });
        mesh.texcoords.push([k as f32 / n as f32, 0.0]);
    }
    let IndexData::U32(indices) = &mut mesh.indices else {
        unreachable!()
    };
    for k in 0..n as u32 {
        indices.extend([0, k + 1, k + 2]);
    }
    mesh
}

/// UV spheres whose poles are one vertex shared by a fan, or one per segment; polar fans of 4, 8,
/// 64 and 1000 triangles as cones and flat disks; a fan whose apex is split per triangle into
/// copies of equal attributes.
pub fn poles() -> Vec<StressMesh> {
    let mut meshes = vec![
        from_case(shapes::uv_sphere("uv_sphere_shared_poles_16x8", 16, 8, Poles::Shared)),
        from_case(shapes::uv_sphere("uv_sphere_shared_poles_64x32", 64, 32, Poles::Shared)),
        from_case(shapes::uv_sphere(
            "uv_sphere_segment_poles_16x8",
            16,
            8,
            Poles::PerSegment,
        )),
    ];
    for n in [4, 8, 64, 1000] {
        meshes.push(polar_fan(n, 1.0, &format!("polar_fan {n} cone")));
        meshes.push(polar_fan(n, 0.0, &format!("polar_fan {n} disk")));
    }
    let mut split = polar_fan(8, 1.0, "polar_fan 8 cone split apex");
    let IndexData::U32(indices) = &mut split.indices else {
        unreachable!()
    };
    for triangle in indices.chunks_exact_mut(3).skip(1) {
        triangle[0] = split.positions.len() as u32;
        split.positions.push(split.positions[0]);
        split.normals.push(split.normals[0]);
        split.texcoords.push(split.texcoords[0]);
    }
    meshes.push(split);
    meshes
}

/// Equal positions with different normals: a hard-edged cube, and a grid whose every vertex has
/// a second copy with a tilted normal that alternate triangles use.
pub fn duplicate_positions() -> Vec<StressMesh> {
    let mut cube = StressMesh {
        name: "hard_edged_cube".into(),
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        indices: IndexData::U32(Vec::new()),
    };
    // Per face: the normal axis and sign; corners from the two other axes.
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let first = cube.positions.len() as u32;
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            for (s, t) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let mut p = [0.0; 3];
                p[axis] = sign;
                p[a] = s * sign;
                p[b] = t;
                let mut n = [0.0; 3];
                n[axis] = sign;
                cube.positions.push(p);
                cube.normals.push(n);
                cube.texcoords.push([(s + 1.0) * 0.5, (t + 1.0) * 0.5]);
            }
            let IndexData::U32(indices) = &mut cube.indices else {
                unreachable!()
            };
            indices.extend([first, first + 1, first + 2, first, first + 2, first + 3]);
        }
    }
    let mut grid = height_grid("duplicate_positions_tilted_normals", 6, 5, 0.2, |i, j| (i + j) % 2 == 1);
    let n = grid.vertex_count() as u32;
    for v in 0..n as usize {
        grid.positions.push(grid.positions[v]);
        let [x, y, z] = grid.normals[v];
        let tilted = [x + 0.1, y, z];
        let length = (tilted[0] * tilted[0] + tilted[1] * tilted[1] + tilted[2] * tilted[2]).sqrt();
        grid.normals.push(tilted.map(|c| c / length));
        grid.texcoords.push(grid.texcoords[v]);
    }
    let IndexData::U32(indices) = &mut grid.indices else {
        unreachable!()
    };
    for (t, triangle) in indices.chunks_exact_mut(3).enumerate() {
        for (k, v) in triangle.iter_mut().enumerate() {
            if (t + k) % 2 == 1 {
                *v += n;
            }
        }
    }
    vec![cube, grid]
}

/// `x` with a random sign when it is zero.
fn random_zero_sign(x: f32, rng: &mut Pcg32) -> f32 {
    if x == 0.0 && rng.next_u32() & 1 == 1 {
        -x
    } else {
        x
    }
}

/// A 4 x 4 quad grid over `[-2, 2]^2` in z = 0 with normal +z and `uv = (x, y) / 4`, whose every
/// vertex has `copies` copies that differ only in the signs of their zero components (positions,
/// normals, UVs: equal under `==`, so mikktspace.c welds them); each triangle corner picks a random
/// copy, and the copies come in random order in the vertex buffer.
pub fn signed_zeros_grid(seed: u64, copies: usize, lifted: bool) -> StressMesh {
    let mut rng = Pcg32::new(seed, 0x5167);
    let cols = 4;
    let base = shapes::grid("base", cols, cols, |i, j| {
        let (x, y) = (i as f32 - 2.0, j as f32 - 2.0);
        Vertex {
            position: [x, y, if lifted { height(x, y) } else { 0.0 }],
            normal: if lifted { height_normal(x, y) } else { [0.0, 0.0, 1.0] },
            uv: [x * 0.25, y * 0.25],
        }
    });
    let n = base.vertex_count();
    // Slot s of vertex v holds copy `order[v][s]` of it.
    let mut mesh = StressMesh {
        name: format!(
            "signed_zeros{} seed {seed} copies {copies}",
            if lifted { " lifted" } else { "" }
        ),
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        indices: IndexData::U32(Vec::new()),
    };
    let mut slots = vec![Vec::new(); n];
    let mut order: Vec<(usize, usize)> = (0..n).flat_map(|v| (0..copies).map(move |c| (v, c))).collect();
    for k in (1..order.len()).rev() {
        order.swap(k, rng.next_u32() as usize % (k + 1));
    }
    for (v, _) in order {
        slots[v].push(mesh.positions.len() as u32);
        mesh.positions
            .push(base.positions[v].map(|x| random_zero_sign(x, &mut rng)));
        mesh.normals
            .push(base.normals[v].map(|x| random_zero_sign(x, &mut rng)));
        mesh.texcoords
            .push(base.texcoords.as_ref().unwrap()[v].map(|x| random_zero_sign(x, &mut rng)));
    }
    let IndexData::U32(indices) = &mut mesh.indices else {
        unreachable!()
    };
    for &v in base.indices.as_ref().unwrap() {
        indices.push(slots[v as usize][rng.next_u32() as usize % copies]);
    }
    mesh
}

/// Vertices equal under `==` but differing in the sign of zeros, in several counts and orders.
pub fn signed_zeros() -> Vec<StressMesh> {
    let mut meshes = Vec::new();
    for (seed, copies) in [(1, 3), (2, 2), (3, 4), (4, 6)] {
        meshes.push(signed_zeros_grid(seed, copies, true));
    }
    meshes.push(signed_zeros_grid(5, 3, false));
    // One triangle per sign pattern of the origin corner, every pattern its own vertex.
    let mut origin = StressMesh {
        name: "signed_zero_origin_patterns".into(),
        positions: vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        normals: vec![[0.0, 0.0, 1.0]; 2],
        texcoords: vec![[1.0, 0.0], [0.0, 1.0]],
        indices: IndexData::U32(Vec::new()),
    };
    for pattern in 0..64u32 {
        let sign = |bit: u32| if pattern >> bit & 1 == 1 { -0.0 } else { 0.0 };
        let v = origin.positions.len() as u32;
        origin.positions.push([sign(0), sign(1), sign(2)]);
        origin.normals.push([sign(3), sign(4), 1.0]);
        origin.texcoords.push([sign(5), -sign(5)]);
        let IndexData::U32(indices) = &mut origin.indices else {
            unreachable!()
        };
        indices.extend([v, 0, 1]);
    }
    meshes.push(origin);
    meshes
}

/// NaN with other payloads and signs than `f32::NAN`, and a signalling NaN.
pub const ODD_NANS: [u32; 3] = [0xFFC0_0000, 0x7FC0_1234, 0x7FA0_0000];

/// Grids with non-finite values: scattered through every attribute, all positions NaN, a NaN of
/// each odd payload, infinities on whole rows.
pub fn non_finite() -> Vec<StressMesh> {
    let mut meshes = Vec::new();
    let specials = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::from_bits(ODD_NANS[0]),
        f32::from_bits(ODD_NANS[1]),
        f32::from_bits(ODD_NANS[2]),
    ];
    for seed in 1..=3u64 {
        let mut rng = Pcg32::new(seed, 0x004e_614e);
        let mut mesh = height_grid(&format!("non_finite_scattered seed {seed}"), 8, 6, 0.125, |i, j| {
            (i + j) % 2 == 0
        });
        let n = mesh.vertex_count();
        for _ in 0..12 {
            let v = rng.next_u32() as usize % n;
            let value = specials[rng.next_u32() as usize % specials.len()];
            let component = rng.next_u32() as usize % 8;
            match component {
                0..=2 => mesh.positions[v][component] = value,
                3..=5 => mesh.normals[v][component - 3] = value,
                _ => mesh.texcoords[v][component - 6] = value,
            }
        }
        meshes.push(mesh);
    }
    let mut all_nan = height_grid("non_finite_all_positions_nan", 3, 3, 0.25, |_, _| true);
    all_nan.positions.iter_mut().for_each(|p| *p = [f32::NAN; 3]);
    meshes.push(all_nan);
    let mut first_nan = height_grid("non_finite_first_position_nan", 3, 3, 0.25, |_, _| true);
    first_nan.positions[0] = [f32::NAN, 0.0, 0.0];
    meshes.push(first_nan);
    for (k, bits) in ODD_NANS.into_iter().enumerate() {
        let mut mesh = height_grid(&format!("non_finite_nan_{bits:08x}"), 3, 3, 0.25, |_, _| true);
        let v = 5 + k;
        mesh.positions[v][0] = f32::from_bits(bits);
        mesh.normals[v + 1][1] = f32::from_bits(bits);
        mesh.texcoords[v + 2][0] = f32::from_bits(bits);
        meshes.push(mesh);
    }
    let mut inf_rows = height_grid("non_finite_infinite_rows", 5, 4, 0.2, |i, _| i % 2 == 0);
    for i in 0..=5 {
        inf_rows.positions[shapes::grid_index(5, i, 1) as usize][2] = f32::INFINITY;
        inf_rows.texcoords[shapes::grid_index(5, i, 3) as usize][1] = f32::NEG_INFINITY;
    }
    meshes.push(inf_rows);
    meshes
}

/// A jittered height field over `[-1, 1]^2`, its positions, UVs and normals then scaled.
fn scaled_grid(name: &str, position_scale: f32, uv_scale: f32, normal_scale: f32) -> StressMesh {
    let mut mesh = height_grid(name, 6, 6, 1.0 / 6.0, |i, j| (i + j) % 3 != 1);
    for p in &mut mesh.positions {
        *p = [p[0] / 3.0 - 1.0, p[1] / 3.0 - 1.0, p[2]].map(|x| x * position_scale);
    }
    for uv in &mut mesh.texcoords {
        *uv = uv.map(|x| x * uv_scale);
    }
    for n in &mut mesh.normals {
        *n = n.map(|x| x * normal_scale);
    }
    mesh
}

/// Huge values (1e38, 3e38: differences and squares overflow) and subnormal ones (1e-40: products
/// underflow) in positions, UVs and normals.
pub fn extreme_magnitudes() -> Vec<StressMesh> {
    let mut meshes = Vec::new();
    for (label, scale) in [("1e38", 1e38f32), ("3e38", 3e38), ("1e-40", 1e-40)] {
        meshes.push(scaled_grid(&format!("positions_x{label}"), scale, 1.0, 1.0));
        meshes.push(scaled_grid(&format!("uvs_x{label}"), 1.0, scale, 1.0));
        meshes.push(scaled_grid(&format!("normals_x{label}"), 1.0, 1.0, scale));
        meshes.push(scaled_grid(&format!("everything_x{label}"), scale, scale, scale));
    }
    let mut denormal_normals = scaled_grid("denormal_normal_components", 1.0, 1.0, 1.0);
    for (v, n) in denormal_normals.normals.iter_mut().enumerate() {
        match v % 3 {
            0 => *n = [1e-40, 0.0, 1.0],
            1 => *n = [0.0, 0.0, 1e-40],
            _ => {}
        }
    }
    meshes.push(denormal_normals);
    meshes
}

/// Repeated indices, coincident and collinear positions, and triangles whose corners are distinct
/// vertices at one position, interleaved with good triangles.
pub fn degenerate_triangles() -> Vec<StressMesh> {
    let mut mesh = height_grid("degenerate_mix", 6, 4, 0.15, |i, _| i % 2 == 0);
    let first = mesh.vertex_count() as u32;
    // Vertex `first`: a copy of vertex 8 with another UV; `first + 1..first + 4`: on a line.
    mesh.positions.push(mesh.positions[8]);
    mesh.normals.push(mesh.normals[8]);
    mesh.texcoords.push([0.9, 0.1]);
    for k in 0..3 {
        mesh.positions.push([10.0 + k as f32, 2.0 * k as f32, 0.5]);
        mesh.normals.push([0.0, 0.0, 1.0]);
        mesh.texcoords.push([0.1 * k as f32, 0.3 + 0.05 * k as f32 * k as f32]);
    }
    let IndexData::U32(indices) = &mut mesh.indices else {
        unreachable!()
    };
    let good: Vec<u32> = indices.clone();
    let bad: [[u32; 3]; 8] = [
        [8, 8, 9],
        [9, 8, 8],
        [8, 9, 8],
        [12, 12, 12],
        [8, first, 9],
        [first + 1, first + 2, first + 3],
        [first, 8, 15],
        [first + 3, first + 1, first + 2],
    ];
    indices.clear();
    for (t, triangle) in good.chunks_exact(3).enumerate() {
        if t % 5 == 0 {
            indices.extend(bad[(t / 5) % bad.len()]);
        }
        indices.extend_from_slice(triangle);
    }
    indices.extend([8, first, 9, 0, 0, 0]);
    // Only degenerate triangles.
    let only_bad = StressMesh {
        name: "degenerate_only".into(),
        positions: vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0], [0.0, 0.0, 0.0]],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        texcoords: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
        indices: IndexData::U32(vec![0, 0, 1, 0, 3, 1, 0, 1, 2, 2, 2, 2]),
    };
    vec![mesh, only_bad]
}

/// An edge shared by `wings` triangles, wound alternately (mixed) or all the same way.
pub fn butterfly(wings: usize, mixed: bool) -> StressMesh {
    let name = format!(
        "butterfly {wings} {}",
        if mixed { "mixed winding" } else { "same winding" }
    );
    let mut mesh = StressMesh {
        name,
        positions: vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        normals: vec![[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]],
        texcoords: vec![[0.5, 0.0], [0.5, 1.0]],
        indices: IndexData::U32(Vec::new()),
    };
    let directions = symmetric_circle(4);
    for k in 0..wings {
        let [c, s] = directions[k % 4];
        let v = mesh.positions.len() as u32;
        mesh.positions.push([c, 0.5, s]);
        mesh.normals.push([-s, 0.0, c]);
        mesh.texcoords.push([0.5 + 0.5 * c - 0.1 * s, 0.5 + 0.1 * k as f32]);
        let IndexData::U32(indices) = &mut mesh.indices else {
            unreachable!()
        };
        if mixed && k % 2 == 1 {
            indices.extend([1, 0, v]);
        } else {
            indices.extend([0, 1, v]);
        }
    }
    mesh
}

/// Non-manifold edges: butterflies of 3 and 4 wings, and two fans touching at one vertex.
pub fn non_manifold() -> Vec<StressMesh> {
    let mut bowtie = polar_fan(8, 0.5, "bowtie");
    let IndexData::U32(indices) = &mut bowtie.indices else {
        unreachable!()
    };
    let upper: Vec<u32> = indices.clone();
    let offset = bowtie.positions.len() as u32 - 1;
    for k in 1..bowtie.positions.len() {
        let [x, y, z] = bowtie.positions[k];
        bowtie.positions.push([x, y, 2.0 * bowtie.positions[0][2] - z]);
        let [nx, ny, nz] = bowtie.normals[k];
        bowtie.normals.push([nx, ny, -nz]);
        let uv = bowtie.texcoords[k];
        bowtie.texcoords.push(uv);
    }
    for triangle in upper.chunks_exact(3) {
        indices.extend([triangle[0], triangle[2] + offset, triangle[1] + offset]);
    }
    vec![
        butterfly(3, true),
        butterfly(4, true),
        butterfly(3, false),
        butterfly(4, false),
        bowtie,
    ]
}

/// `vertices` random vertices and `triangles` random triangles over them (now and then with a
/// repeated index), positions in the unit cube, unit normals, UVs in the unit square.
pub fn random_soup(vertices: usize, triangles: usize, seed: u64) -> StressMesh {
    let mut rng = Pcg32::new(seed, 0x500b);
    let mut mesh = StressMesh {
        name: format!("random_soup {vertices}"),
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        indices: IndexData::U32(Vec::new()),
    };
    for _ in 0..vertices {
        mesh.positions.push([0; 3].map(|_| rng.symmetric(1.0) as f32));
        let n = [0; 3].map(|_| rng.symmetric(1.0) as f32);
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-3);
        mesh.normals.push(n.map(|c| c / length));
        mesh.texcoords.push([0; 2].map(|_| rng.unit() as f32));
    }
    let IndexData::U32(indices) = &mut mesh.indices else {
        unreachable!()
    };
    for _ in 0..3 * triangles {
        indices.push(rng.next_u32() % vertices as u32);
    }
    mesh
}

/// Quads along each side of [`large_grid`]: 321 x 321 = 103,041 vertices.
pub const LARGE_GRID: usize = 320;

/// A jittered height field of [`LARGE_GRID`]^2 quads with random diagonals and a mirrored column
/// band, large enough for several workers.
pub fn large_grid() -> StressMesh {
    let mut rng = Pcg32::new(11, 0x0001_a26e);
    let n = LARGE_GRID;
    let diagonals: Vec<bool> = (0..n * n).map(|_| rng.next_u32() & 1 == 1).collect();
    let mut mesh = height_grid("large_grid", n, n, 1.0 / n as f32, |i, j| diagonals[j * n + i]);
    for (uv, p) in mesh.texcoords.iter_mut().zip(&mesh.positions) {
        if (100.0..=150.0).contains(&p[0]) {
            uv[0] = (250.0 - p[0]) / n as f32;
        }
    }
    mesh
}
