//! Test meshes as plain arrays, and the binary case file the C harness reads.
//!
//! Case file (little-endian): magic `b"TBC1"`, u32 case count, then per case:
//! u32 name length, name bytes (UTF-8), u64 vertex_count, u32 has_texcoords (0/1), u32 indexed (0/1),
//! u64 index_count, `f32 positions[3 * vertex_count]`, `f32 normals[3 * vertex_count]`,
//! `f32 texcoords[2 * vertex_count]` (only when has_texcoords), `u32 indices[index_count]` (only when indexed),
//! then the expected report for policies SKIP, INHERIT, REJECT in that order, each as six u64:
//! degenerate_triangles, first_degenerate_triangle (u64::MAX for none), fallback_vertices,
//! mirrored_vertices, unreferenced_vertices, inherited_vertices. For REJECT the report is the one the
//! call returns with TBASIS_ERROR_DEGENERATE_UV when degenerate_triangles > 0.

use std::io::Write;
use std::path::Path;

use tbasis::{DegeneratePolicy, Indices, Mesh, Options, Report, Strided};

use super::run::{run_mesh, Run};

use super::shapes::{cylinder, flat_grid, grid, grid_index, jitter, push, quantize_uvs, uv_sphere, Poles, Vertex};

/// A test mesh: packed per-vertex arrays and optional u32 indices.
#[derive(Clone, Debug, Default)]
pub struct Case {
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub texcoords: Option<Vec<[f32; 2]>>,
    pub indices: Option<Vec<u32>>,
}

impl Case {
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// The library's view of this case.
    pub fn mesh(&self) -> Mesh<'_> {
        Mesh {
            positions: Strided::from_slice(&self.positions),
            normals: Strided::from_slice(&self.normals),
            texcoords: self.texcoords.as_deref().map(Strided::from_slice),
            indices: match &self.indices {
                Some(indices) => Indices::U32(Strided::from_slice(indices)),
                None => Indices::None,
            },
        }
    }

    /// Runs the library on this case.
    pub fn run(&self, options: &Options) -> Run {
        run_mesh(&self.mesh(), self.vertex_count(), options)
    }

    /// The report a policy produces on this case (also on a REJECT refusal).
    pub fn expected_report(&self, policy: DegeneratePolicy) -> Report {
        self.run(&Options::default().with_policy(policy)).report
    }
}

/// Every stability case (one or more per failure class), shared by the Rust suite and the C harness.
pub fn all_cases() -> Vec<Case> {
    let mut cases = vec![
        unit_quad(),
        all_uvs_equal(),
        collinear_uvs(),
        collinear_uvs_rounded(),
        uv_scale_reference(),
        uv_scaled(1e-20, "uv_scaled_down_1e20"),
        uv_scaled(1e20, "uv_scaled_up_1e20"),
        zero_area_midpoint(),
        zero_area_coincident(),
        sliver(SLIVER_KEPT, "sliver_flipped_kept"),
        sliver(SLIVER_DEGENERATE, "sliver_below_threshold"),
        quantized_uv_sphere(),
        sphere_poles(Poles::PerSegment),
        sphere_poles(Poles::Shared),
        mirror_fold(),
        zero_normals_all(),
        zero_normal_center(),
        zero_normals_collapsed(),
        tiny_and_long_normals(),
        unreferenced_vertices(),
        no_triangles(),
        single_triangle(),
        single_triangle_unindexed(),
        single_degenerate_triangle(),
        empty_mesh(),
        empty_mesh_unindexed(),
        duplicate_indices(),
        texcoords_absent(),
        normals_near_negative_z(),
        normals_near_negative_z_fallback(),
        collapsed_band(),
        fully_collapsed(),
    ];
    for attribute in Attribute::ALL {
        for component in 0..attribute.components() {
            for (_, value) in BAD_VALUES {
                cases.push(bad_attribute(attribute, component, value));
            }
        }
    }
    cases
}

/// Two triangles in z = 0 with u along +x and v along +y.
pub fn unit_quad() -> Case {
    Case {
        name: "unit_quad".into(),
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        texcoords: Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
        indices: Some(vec![0, 1, 2, 0, 2, 3]),
    }
}

/// A flat disk of `spokes` triangles around its centre, texture coordinates following the
/// positions, after a triangle of its own: the index buffer names the centre only after three
/// other vertices, so that a method working vertex by vertex reaches the centre's fan of `spokes`
/// corners after others.
pub fn disk_after_a_triangle(spokes: usize) -> Case {
    let mut positions = vec![[10.0, 0.0, 0.0], [11.0, 0.0, 0.0], [10.0, 1.0, 0.0], [0.0, 0.0, 0.0]];
    let mut texcoords = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5]];
    let mut indices = vec![0, 1, 2];
    for i in 0..spokes {
        let angle = i as f32 * core::f32::consts::TAU / spokes as f32;
        let (y, x) = angle.sin_cos();
        positions.push([x, y, 0.0]);
        texcoords.push([0.5 + 0.5 * x, 0.5 + 0.5 * y]);
        indices.extend([3, 4 + i as u32, 4 + ((i + 1) % spokes) as u32]);
    }
    Case {
        name: format!("disk_of_{spokes}_after_a_triangle"),
        normals: vec![[0.0, 0.0, 1.0]; positions.len()],
        positions,
        texcoords: Some(texcoords),
        indices: Some(indices),
    }
}

/// `case` renamed, with other texture coordinates.
fn with_uvs(case: Case, name: &str, uvs: Vec<[f32; 2]>) -> Case {
    assert_eq!(uvs.len(), case.vertex_count());
    Case {
        name: name.into(),
        texcoords: Some(uvs),
        ..case
    }
}

/// The unit quad with one UV for all four vertices: both triangles collapse to a point.
pub fn all_uvs_equal() -> Case {
    with_uvs(unit_quad(), "all_uvs_equal", vec![[0.25, 0.75]; 4])
}

/// The unit quad with UVs exactly on the line v = 2u: both triangles collapse to a segment.
pub fn collinear_uvs() -> Case {
    let uvs = vec![[0.0, 0.0], [0.125, 0.25], [0.5, 1.0], [0.25, 0.5]];
    with_uvs(unit_quad(), "collinear_uvs", uvs)
}

/// The unit quad with UVs on the line v = 0.1u + 0.3, computed in f32: collinear up to rounding,
/// so the determinants are rounding noise (quality near 1e-7, far below the 1e-5 threshold).
pub fn collinear_uvs_rounded() -> Case {
    let uvs = [0.1f32, 0.7, 0.35, 0.9].map(|u| [u, 0.1 * u + 0.3]).to_vec();
    with_uvs(unit_quad(), "collinear_uvs_rounded", uvs)
}

/// Columns and rows of quads of [`uv_scale_reference`]'s curved grid.
pub const SCALE_GRID: (usize, usize) = (4, 3);

/// A curved, irregularly mapped grid plus one separate triangle with collinear UVs (the last
/// triangle, number `2 * cols * rows`), the mesh the UV scale tests scale.
pub fn uv_scale_reference() -> Case {
    let (cols, rows) = SCALE_GRID;
    let mut case = grid("uv_scale_reference", cols, rows, |i, j| {
        let (x, y) = (i as f32 * 0.5, j as f32 * 0.5);
        let slope = [0.2 * x.cos() * y.cos(), -0.2 * x.sin() * y.sin()];
        let normal = [-slope[0], -slope[1], 1.0];
        let length = (normal[0] * normal[0] + normal[1] * normal[1] + 1.0).sqrt();
        Vertex {
            position: [x, y, 0.2 * x.sin() * y.cos()],
            normal: normal.map(|c| c / length),
            uv: [
                0.3 * x + 0.05 * y + 0.01 * jitter(i, j),
                0.3 * y - 0.04 * x + 0.01 * jitter(j + 7, i),
            ],
        }
    });
    let first = case.vertex_count() as u32;
    for (position, uv) in [
        ([3.0, 0.0, 0.0], [0.1, 0.1]),
        ([4.0, 0.0, 0.0], [0.2, 0.2]),
        ([3.0, 1.0, 0.0], [0.4, 0.4]),
    ] {
        push(
            &mut case,
            Vertex {
                position,
                normal: [0.0, 0.0, 1.0],
                uv,
            },
        );
    }
    case.indices.as_mut().unwrap().extend([first, first + 1, first + 2]);
    case
}

/// [`uv_scale_reference`] with every texture coordinate multiplied by `scale`.
pub fn uv_scaled(scale: f32, name: &str) -> Case {
    let base = uv_scale_reference();
    let uvs = base
        .texcoords
        .clone()
        .unwrap()
        .iter()
        .map(|uv| uv.map(|x| x * scale))
        .collect();
    with_uvs(base, name, uvs)
}

/// Two triangles; the second, `[1, 3, 2]`, has vertex 3 at the midpoint of vertices 1 and 2: zero
/// area in space with good UVs. Vertex 3 belongs to that triangle only.
pub fn zero_area_midpoint() -> Case {
    Case {
        name: "zero_area_midpoint".into(),
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, 0.0]],
        normals: vec![[0.0, 0.0, 1.0]; 4],
        texcoords: Some(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]),
        indices: Some(vec![0, 1, 2, 1, 3, 2]),
    }
}

/// One triangle whose three positions coincide.
pub fn zero_area_coincident() -> Case {
    Case {
        name: "zero_area_coincident".into(),
        positions: vec![[0.5, -0.25, 2.0]; 3],
        normals: vec![[0.0, 0.0, 1.0]; 3],
        texcoords: Some(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]),
        indices: Some(vec![0, 1, 2]),
    }
}

/// Height of the sliver of [`sliver`] that stays above the threshold (quality about 1e-3).
pub const SLIVER_KEPT: f32 = 1e-3;
/// Height of the sliver of [`sliver`] below the threshold (quality about 1e-7).
pub const SLIVER_DEGENERATE: f32 = 1e-7;

/// The unit square in z = 0, uv = (x, y), cut into `[0,1,2]`, the sliver `[0,2,4]`, `[0,4,3]` and
/// `[4,2,3]`, where vertex 4 sits `eps` above the diagonal in space but `eps` below it in UV: the
/// sliver is flipped in UV (as rounding does to slivers), the other triangles are not.
pub fn sliver(eps: f32, name: &str) -> Case {
    Case {
        name: name.into(),
        positions: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5 + eps, 0.0],
        ],
        normals: vec![[0.0, 0.0, 1.0]; 5],
        texcoords: Some(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5 - eps]]),
        indices: Some(vec![0, 1, 2, 0, 2, 4, 0, 4, 3, 4, 2, 3]),
    }
}

/// Segments and rings of the quantized sphere: both steps (1/288, 1/272) are finer than 1/255,
/// so rounding to 8 bits collapses some columns and rows of UVs to zero width.
pub const QUANTIZED_SPHERE: (usize, usize) = (288, 272);

/// A dense UV sphere with texture coordinates rounded to multiples of 1/255 (8-bit UVs).
pub fn quantized_uv_sphere() -> Case {
    let (segments, rings) = QUANTIZED_SPHERE;
    let sphere = uv_sphere("quantized_uv_sphere", segments, rings, Poles::PerSegment);
    let uvs = quantize_uvs(&sphere, 255.0);
    with_uvs(sphere, "quantized_uv_sphere", uvs)
}

/// Segments and rings of the small spheres of the pole cases.
pub const POLE_SPHERE: (usize, usize) = (16, 8);

/// A small UV sphere with poles made as `poles` says.
pub fn sphere_poles(poles: Poles) -> Case {
    let (segments, rings) = POLE_SPHERE;
    let name = match poles {
        Poles::PerSegment => "uv_sphere_poles_per_segment",
        Poles::Shared => "uv_sphere_poles_shared",
    };
    uv_sphere(name, segments, rings, poles)
}

/// Columns of quads of [`mirror_fold`] (the seam is the middle vertex column) and rows.
pub const MIRROR_GRID: (usize, usize) = (4, 2);

/// A flat grid over x in [-2, 2], y in [0, 2] with `u = |x| / 4`: the UVs mirror about the
/// column x = 0, whose vertices both halves share.
pub fn mirror_fold() -> Case {
    let (cols, rows) = MIRROR_GRID;
    grid("mirror_fold", cols, rows, |i, j| {
        let (x, y) = (i as f32 - (cols / 2) as f32, j as f32);
        Vertex {
            position: [x, y, 0.0],
            normal: [0.0, 0.0, 1.0],
            uv: [x.abs() * 0.25, y * 0.5],
        }
    })
}

/// Which per-vertex input a bad value goes into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Attribute {
    Position,
    Normal,
    Texcoord,
}

impl Attribute {
    pub const ALL: [Attribute; 3] = [Attribute::Position, Attribute::Normal, Attribute::Texcoord];

    pub fn components(self) -> usize {
        match self {
            Attribute::Texcoord => 2,
            _ => 3,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Attribute::Position => "position",
            Attribute::Normal => "normal",
            Attribute::Texcoord => "texcoord",
        }
    }
}

/// The non-finite values each attribute component is tried with.
pub const BAD_VALUES: [(&str, f32); 3] = [
    ("nan", f32::NAN),
    ("inf", f32::INFINITY),
    ("neg_inf", f32::NEG_INFINITY),
];

/// The vertex that gets the bad value: the centre of a 3 x 3 vertex grid, used by six of its
/// eight triangles (0, 1, 3, 4, 6 and 7; see [`grid`]).
pub const BAD_VERTEX: usize = 4;

/// A flat 2 x 2 quad grid (uv = (x, y) / 2) with component `component` of `attribute` of the
/// centre vertex set to `value`.
pub fn bad_attribute(attribute: Attribute, component: usize, value: f32) -> Case {
    let label = BAD_VALUES
        .iter()
        .find(|(_, v)| v.to_bits() == value.to_bits())
        .map_or("value", |(n, _)| n);
    let axes = match attribute {
        Attribute::Texcoord => ["u", "v", ""],
        _ => ["x", "y", "z"],
    };
    let name = format!("{}_{}_{label}", attribute.name(), axes[component]);
    let mut case = flat_grid(&name, 2, 2, 0.5);
    match attribute {
        Attribute::Position => case.positions[BAD_VERTEX][component] = value,
        Attribute::Normal => case.normals[BAD_VERTEX][component] = value,
        Attribute::Texcoord => case.texcoords.as_mut().unwrap()[BAD_VERTEX][component] = value,
    }
    case
}

/// The unit quad with every normal zero.
pub fn zero_normals_all() -> Case {
    Case {
        name: "zero_normals_all".into(),
        normals: vec![[0.0, 0.0, 0.0], [-0.0, 0.0, 0.0], [0.0, -0.0, -0.0], [0.0; 3]],
        ..unit_quad()
    }
}

/// A flat 2 x 2 quad grid whose centre vertex has a zero normal.
pub fn zero_normal_center() -> Case {
    let mut case = flat_grid("zero_normal_center", 2, 2, 0.5);
    case.normals[BAD_VERTEX] = [0.0; 3];
    case
}

/// Zero normals and collapsed UVs: nothing to measure and nothing to build a frame from.
pub fn zero_normals_collapsed() -> Case {
    with_uvs(zero_normals_all(), "zero_normals_collapsed", vec![[0.5, 0.5]; 4])
}

/// The unit quad with normals along +z of subnormal, tiny and long lengths: the library normalizes
/// them, so they act as +z.
pub fn tiny_and_long_normals() -> Case {
    Case {
        name: "tiny_and_long_normals".into(),
        normals: vec![[0.0, 0.0, 1e-40], [0.0, 0.0, 1e-30], [0.0, 0.0, 7.0], [0.0, 0.0, 1e30]],
        ..unit_quad()
    }
}

/// The unit quad's vertices at indices 0, 2, 4, 5 with three vertices no triangle uses in between
/// and after (one with a NaN position and normal, one facing -z).
pub fn unreferenced_vertices() -> Case {
    let nan = f32::NAN;
    Case {
        name: "unreferenced_vertices".into(),
        positions: vec![
            [0.0, 0.0, 0.0],
            [nan, nan, nan],
            [1.0, 0.0, 0.0],
            [5.0, 5.0, 5.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [9.0, 0.0, 0.0],
        ],
        normals: vec![
            [0.0, 0.0, 1.0],
            [nan, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.6, 0.8, 0.0],
        ],
        texcoords: Some(vec![
            [0.0, 0.0],
            [nan, nan],
            [1.0, 0.0],
            [0.3, 0.3],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.0, 0.0],
        ]),
        indices: Some(vec![0, 2, 4, 0, 4, 5]),
    }
}

/// Six vertices and an empty index list: every vertex unreferenced.
pub fn no_triangles() -> Case {
    Case {
        name: "no_triangles".into(),
        positions: (0..6).map(|i| [i as f32, 0.0, 0.0]).collect(),
        normals: vec![[0.0, 0.0, 1.0]; 6],
        texcoords: Some((0..6).map(|i| [i as f32 * 0.1, 0.0]).collect()),
        indices: Some(Vec::new()),
    }
}

/// One triangle in a tilted plane; its tangent is the normalized `dP/du = (2, 0, 1)`.
pub fn single_triangle() -> Case {
    let normal = [-0.447_213_6, 0.0, 0.894_427_2]; // (-1, 0, 2) / sqrt(5), normal of the plane z = x / 2
    Case {
        name: "single_triangle".into(),
        positions: vec![[0.0, 0.0, 0.0], [2.0, 0.0, 1.0], [0.0, 1.0, 0.0]],
        normals: vec![normal; 3],
        texcoords: Some(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]),
        indices: Some(vec![0, 1, 2]),
    }
}

/// [`single_triangle`] without an index buffer.
pub fn single_triangle_unindexed() -> Case {
    Case {
        name: "single_triangle_unindexed".into(),
        indices: None,
        ..single_triangle()
    }
}

/// [`single_triangle`] with all three UVs equal.
pub fn single_degenerate_triangle() -> Case {
    with_uvs(single_triangle(), "single_degenerate_triangle", vec![[0.5, 0.5]; 3])
}

/// No vertices, an empty index buffer.
pub fn empty_mesh() -> Case {
    Case {
        name: "empty_mesh".into(),
        texcoords: Some(Vec::new()),
        indices: Some(Vec::new()),
        ..Case::default()
    }
}

/// No vertices and no index buffer.
pub fn empty_mesh_unindexed() -> Case {
    Case {
        name: "empty_mesh_unindexed".into(),
        indices: None,
        ..empty_mesh()
    }
}

/// The unit quad plus a vertex 4, with triangles `[0,0,1]`, `[3,2,3]` and `[4,4,4]` after the
/// quad's two: three degenerate triangles, and vertex 4 used by a degenerate triangle only.
pub fn duplicate_indices() -> Case {
    let mut case = unit_quad();
    case.name = "duplicate_indices".into();
    push(
        &mut case,
        Vertex {
            position: [2.0, 2.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            uv: [2.0, 2.0],
        },
    );
    case.indices.as_mut().unwrap().extend([0, 0, 1, 3, 2, 3, 4, 4, 4]);
    case
}

/// The unit quad plus one unreferenced vertex, without texture coordinates.
pub fn texcoords_absent() -> Case {
    let mut case = unit_quad();
    case.name = "texcoords_absent".into();
    case.texcoords = None;
    case.positions.push([3.0, 3.0, 3.0]);
    case.normals.push([0.0, 1.0, 0.0]);
    case
}

/// Normals at and within 1.5e-4 rad of (0, 0, -1), on the vertices of [`normals_near_negative_z`].
pub const NEAR_NEGATIVE_Z: [[f32; 3]; 6] = [
    [0.0, 0.0, -1.0],
    [1e-7, -1e-7, -1.0],
    [-0.0, 0.0, -1.0],
    [0.0, 0.0, -1e-30],
    [1e-4, -1e-4, -1.0],
    [-1e-4, 5e-5, -1.0],
];

/// Two unindexed triangles in z = 0 wound to face -z, uv = (x, y), normals near (0, 0, -1).
/// Seen from -z the UVs turn clockwise: the true frame is t = +x with w = -1.
pub fn normals_near_negative_z() -> Case {
    let positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let texcoords = positions.iter().map(|p: &[f32; 3]| [p[0], p[1]]).collect();
    Case {
        name: "normals_near_negative_z".into(),
        positions,
        normals: NEAR_NEGATIVE_Z.to_vec(),
        texcoords: Some(texcoords),
        indices: None,
    }
}

/// [`normals_near_negative_z`] with every UV equal: every vertex gets the fallback frame.
pub fn normals_near_negative_z_fallback() -> Case {
    with_uvs(
        normals_near_negative_z(),
        "normals_near_negative_z_fallback",
        vec![[0.5, 0.5]; 6],
    )
}

/// Segments around and rows of quads of the cylinders of [`collapsed_band`] and [`fully_collapsed`].
pub const BAND_CYLINDER: (usize, usize) = (16, 8);
/// Vertex rows of [`collapsed_band`] whose `v` collapses to the middle one's.
pub const BAND_ROWS: [usize; 3] = [3, 4, 5];

/// A cylinder whose vertex rows 3, 4 and 5 all get row 4's `v` (each keeps its own `u`): the quads
/// between rows 3 and 5 collapse to segments in UV, a band around the cylinder with good triangles
/// on both sides. Row 4's vertices touch collapsed triangles only.
pub fn collapsed_band() -> Case {
    let (segments, rows) = BAND_CYLINDER;
    let mut case = cylinder("collapsed_band", segments, rows, 0.4);
    let middle = BAND_ROWS[1] as f32 / rows as f32;
    for j in BAND_ROWS {
        for i in 0..=segments {
            case.texcoords.as_mut().unwrap()[grid_index(segments, i, j) as usize][1] = middle;
        }
    }
    case
}

/// The cylinder of [`collapsed_band`] with every UV equal.
pub fn fully_collapsed() -> Case {
    let (segments, rows) = BAND_CYLINDER;
    let case = cylinder("fully_collapsed", segments, rows, 0.4);
    let n = case.vertex_count();
    with_uvs(case, "fully_collapsed", vec![[0.5, 0.5]; n])
}

/// Writes `cases` in the format described at the top of this file.
pub fn write_case_file(path: &Path, cases: &[Case]) -> std::io::Result<()> {
    let mut out = Vec::new();
    out.extend_from_slice(b"TBC1");
    out.extend_from_slice(&(cases.len() as u32).to_le_bytes());
    for case in cases {
        out.extend_from_slice(&(case.name.len() as u32).to_le_bytes());
        out.extend_from_slice(case.name.as_bytes());
        out.extend_from_slice(&(case.vertex_count() as u64).to_le_bytes());
        out.extend_from_slice(&u32::from(case.texcoords.is_some()).to_le_bytes());
        out.extend_from_slice(&u32::from(case.indices.is_some()).to_le_bytes());
        out.extend_from_slice(&(case.indices.as_ref().map_or(0, Vec::len) as u64).to_le_bytes());
        let floats = case.positions.iter().flatten().chain(case.normals.iter().flatten());
        let uvs = case.texcoords.iter().flatten().flatten();
        for value in floats.chain(uvs) {
            out.extend_from_slice(&value.to_le_bytes());
        }
        for index in case.indices.iter().flatten() {
            out.extend_from_slice(&index.to_le_bytes());
        }
        for policy in [
            DegeneratePolicy::Skip,
            DegeneratePolicy::Inherit,
            DegeneratePolicy::Reject,
        ] {
            let r = case.expected_report(policy);
            let fields = [
                r.degenerate_triangles,
                r.first_degenerate_triangle.unwrap_or(usize::MAX),
                r.fallback_vertices,
                r.mirrored_vertices,
                r.unreferenced_vertices,
                r.inherited_vertices,
            ];
            for field in fields {
                out.extend_from_slice(&(field as u64).to_le_bytes());
            }
        }
    }
    std::fs::File::create(path)?.write_all(&out)
}
