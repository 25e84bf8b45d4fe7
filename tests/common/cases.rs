//! Test meshes as plain arrays, and the binary case file the C harness reads.
//!
//! Case file (little-endian): magic `b"TBC1"`, u32 case count, then per case:
//! u32 name length, name bytes (UTF-8), u64 vertex_count, u32 has_texcoords (0/1), u32 indexed (0/1),
//! u64 index_count, f32 positions[3 * vertex_count], f32 normals[3 * vertex_count],
//! f32 texcoords[2 * vertex_count] (only when has_texcoords), u32 indices[index_count] (only when indexed),
//! then the expected report for policies SKIP, INHERIT, REJECT in that order, each as six u64:
//! degenerate_triangles, first_degenerate_triangle (u64::MAX for none), fallback_vertices,
//! mirrored_vertices, unreferenced_vertices, inherited_vertices. For REJECT the report is the one the
//! call returns with TBASIS_ERROR_DEGENERATE_UV when degenerate_triangles > 0.

use std::io::Write;
use std::path::Path;

use tbasis::{DegeneratePolicy, Indices, Mesh, Options, Output, Report, Strided, StridedMut};

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

    /// Runs the library on this case; returns tangents, bitangents and the result.
    pub fn run(&self, options: &Options) -> (Vec<[f32; 4]>, Vec<[f32; 3]>, Result<Report, tbasis::Error>) {
        let mut tangents = vec![[0.0f32; 4]; self.vertex_count()];
        let mut bitangents = vec![[0.0f32; 3]; self.vertex_count()];
        let mut report = Report::default();
        let result = {
            let mut output = Output {
                tangents: StridedMut::from_slice(&mut tangents),
                bitangents: Some(StridedMut::from_slice(&mut bitangents)),
            };
            tbasis::generate_into(&self.mesh(), options, &mut output, None, &mut report)
        };
        (tangents, bitangents, result.map(|()| report))
    }

    /// The report a policy produces on this case (also on a REJECT refusal).
    pub fn expected_report(&self, policy: DegeneratePolicy) -> Report {
        let options = Options { degenerate_policy: policy, ..Options::default() };
        let mut tangents = vec![[0.0f32; 4]; self.vertex_count()];
        let mut output = Output { tangents: StridedMut::from_slice(&mut tangents), bitangents: None };
        let mut report = Report::default();
        let _ = tbasis::generate_into(&self.mesh(), &options, &mut output, None, &mut report);
        report
    }
}

/// Every stability case (one or more per failure class), shared by the Rust suite and the C harness.
pub fn all_cases() -> Vec<Case> {
    vec![unit_quad()]
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
        for policy in [DegeneratePolicy::Skip, DegeneratePolicy::Inherit, DegeneratePolicy::Reject] {
            let r = case.expected_report(policy);
            let fields = [
                r.degenerate_triangles,
                r.first_degenerate_triangle,
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
