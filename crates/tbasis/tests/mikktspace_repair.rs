//! Policies SKIP and INHERIT of method MIKKTSPACE change mikktspace.c's frames only as much as
//! making them valid takes: on every corpus glTF file, wherever mikktspace.c's tangent (which
//! MIKKTSPACE under LEGACY gives bit for bit) is already about right (finite, unit length within
//! 1e-3, perpendicular to the normal within 1e-4 of the normal's length), the repaired tangent
//! keeps its sign and lies within 0.05 degrees of it, and `repaired_corners` counts exactly the
//! corners that differ from mikktspace.c's, none of them nearly valid. Khronos's NormalTangentMirrorTest, whose normals are 0.99996 long, leaves mikktspace.c's
//! tangents just past 1e-5 off the unit normal's plane: they must not be replaced.
//!
//! Without the corpus that test is skipped, except under CI (`CI` set), where it fails
//! (`tbasis_test_support::needs`). Debug builds leave the largest files to `--release`. Two tests
//! on small meshes of their own pin what MIKKTSPACE's report counts as degenerate.

use tbasis::{generate_corners, DegeneratePolicy, Options, Report, StridedMut};
use tbasis_test_support::load::{self, Primitive};
use tbasis_test_support::needs;

/// Largest angle between mikktspace.c's nearly valid tangent and its repaired one.
const MAX_ANGLE_DEG: f64 = 0.05;

/// The corners of `primitive` under method MIKKTSPACE and `policy`, with the report.
fn corners(primitive: &Primitive, policy: DegeneratePolicy) -> (Vec<[f32; 4]>, Report) {
    let options = Options::mikktspace().with_flip_v(primitive.v_down).with_policy(policy);
    let mut corners = vec![[0.0; 4]; primitive.indices.len()];
    let report = generate_corners(&primitive.mesh(), &options, &mut StridedMut::from_slice(&mut corners))
        .unwrap_or_else(|e| panic!("{policy:?}: {e}"));
    (corners, report)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn xyz(t: [f32; 4]) -> [f64; 3] {
    [t[0], t[1], t[2]].map(f64::from)
}

/// mikktspace.c's tangent is finite, unit length within 1e-3 and perpendicular to `normal` within
/// 1e-4 of the normal's length.
fn nearly_valid(t: [f32; 4], normal: [f32; 3]) -> bool {
    let (t, n) = (xyz(t), normal.map(f64::from));
    t.iter().all(|x| x.is_finite())
        && (dot(t, t).sqrt() - 1.0).abs() <= 1e-3
        && dot(t, n).abs() <= 1e-4 * dot(n, n).sqrt()
}

/// Angle in degrees between two tangents.
fn angle_deg(a: [f32; 4], b: [f32; 4]) -> f64 {
    let (a, b) = (xyz(a), xyz(b));
    (dot(a, b) / (dot(a, a) * dot(b, b)).sqrt())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// What one primitive shows under `policy`: failures, and the nearly valid corners mikktspace.c
/// leaves more than 1e-5 off the unit normal's plane (the case the test is for).
fn check(what: &str, primitive: &Primitive, legacy: &[[f32; 4]], policy: DegeneratePolicy) -> (Vec<String>, usize) {
    let (repaired, report) = corners(primitive, policy);
    let (mut failures, mut near_misses, mut not_nearly_valid, mut moved) = (Vec::new(), 0, 0, 0);
    let changed = repaired
        .iter()
        .zip(legacy)
        .filter(|(a, b)| a.map(f32::to_bits) != b.map(f32::to_bits))
        .count();
    if report.repaired_corners != changed {
        failures.push(format!(
            "{what} {policy:?}: {} corners repaired, {changed} differ from mikktspace.c's",
            report.repaired_corners
        ));
    }
    for (c, (&ours, &theirs)) in repaired.iter().zip(legacy).enumerate() {
        let normal = primitive.normals[primitive.indices[c] as usize];
        let angle = angle_deg(ours, theirs);
        let far = ours[3] != theirs[3] || angle.is_nan() || angle > MAX_ANGLE_DEG;
        moved += usize::from(far);
        if !nearly_valid(theirs, normal) {
            not_nearly_valid += 1;
            continue;
        }
        let n = normal.map(f64::from);
        near_misses += usize::from(dot(xyz(theirs), n).abs() / dot(n, n).sqrt() > 1e-5);
        if far && failures.len() < 4 {
            failures.push(format!(
                "{what} {policy:?}: corner {c}: mikktspace.c's {theirs:?} became {ours:?} ({angle:.3} degrees)"
            ));
        }
    }
    if !(moved..=not_nearly_valid).contains(&report.repaired_corners) {
        failures.push(format!(
            "{what} {policy:?}: {} corners repaired, expected {moved} (moved) to {not_nearly_valid} (not nearly valid)",
            report.repaired_corners
        ));
    }
    (failures, near_misses)
}

#[test]
fn repairs_keep_every_nearly_valid_mikktspace_tangent() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let dir = load::corpus_dir().expect("the corpus");
    let rows = load::read_manifest(&dir).expect("MANIFEST.tsv");
    let (mut files, mut near_misses, mut failures) = (0, 0, Vec::new());
    for row in rows.iter().filter(|row| matches!(row.format.as_str(), "gltf" | "glb")) {
        if load::left_to_optimized_builds(row) {
            continue;
        }
        files += 1;
        let file = load::load(&dir, row).unwrap_or_else(|e| panic!("{e}"));
        for primitive in file.primitives.iter().filter(|p| p.texcoords.is_some()) {
            let what = format!("{} {}", row.path, primitive.name);
            let (legacy, _) = corners(primitive, DegeneratePolicy::Legacy);
            for policy in [DegeneratePolicy::Skip, DegeneratePolicy::Inherit] {
                let (found, near) = check(&what, primitive, &legacy, policy);
                failures.extend(found);
                near_misses += near;
            }
        }
    }
    eprintln!("{files} glTF files, {near_misses} nearly valid corners past 1e-5 kept");
    assert!(files > 0, "no glTF file in the corpus");
    assert!(
        near_misses > 0,
        "no corner just off the plane: the test no longer shows the case it is for"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Policy REJECT's test decides what is degenerate for every method. A triangle whose positions
/// are so small that mikktspace.c's derivatives underflow (it cannot use it), while REJECT's test
/// with threshold 0 passes it, leaves a successful call's report with no degenerate triangle.
#[test]
fn reject_that_succeeds_reports_no_degenerate_triangle() {
    let bits = |b: [u32; 3]| b.map(f32::from_bits);
    let positions = [bits([0xbe00; 3]), [0.0; 3], bits([0xbe, 0x0200_00be, 0xc1])];
    let normals = [[0.0f32; 3], [-0.125, -0.125, -8.125], [0.0, -0.125, -0.125]];
    let texcoords = [[-6.5f32, -8.0], [0.0, 0.0], [0.0, 1.0]];
    let indices = [0u32, 1, 2];
    let mesh = tbasis::Mesh::new(&positions, &normals)
        .with_texcoords(&texcoords)
        .with_indices(&indices[..]);
    let options = tbasis::Options::mikktspace()
        .with_policy(tbasis::DegeneratePolicy::Reject)
        .with_degenerate_threshold(0.0);
    let mut corners = [[0.0f32; 4]; 3];
    let report = tbasis::generate_corners(&mesh, &options, &mut tbasis::StridedMut::from_slice(&mut corners))
        .expect("REJECT's test passes the triangle");
    assert_eq!(
        (report.degenerate_triangles, report.first_degenerate_triangle),
        (0, None)
    );
}

/// With method MIKKTSPACE the report counts the triangles mikktspace.c cannot use: two corners at
/// one position (its degenerate triangles) or no texture derivatives (zero UV area: it groups them
/// with any neighbour), under every policy that succeeds; REJECT refuses the mesh. The listing
/// (LENGYEL with LEGACY) counts the zero UV determinant alone on the same mesh.
#[test]
fn mikktspace_counts_the_triangles_mikktspace_c_cannot_use() {
    // A strip of four triangles: 0 and 3 ordinary, 1 with two corners at one position (its UVs
    // apart), 2 with its three UVs on one line.
    let positions = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
        [3.0, 0.0, 0.0],
    ];
    let normals = [[0.0f32, 0.0, 1.0]; 8];
    let texcoords = [
        [0.0f32, 0.0],
        [1.0, 0.0],
        [0.0, 1.0],
        [1.0, 1.0],
        [0.5, 0.7],
        [2.0, 1.0],
        [3.0, 2.0],
        [4.0, 0.0],
    ];
    let indices = [0u32, 1, 2, 1, 3, 4, 1, 5, 6, 6, 7, 5];
    let mesh = tbasis::Mesh::new(&positions, &normals)
        .with_texcoords(&texcoords)
        .with_indices(&indices[..]);
    let mut corners = [[0.0f32; 4]; 12];
    let mut run = |options: Options| generate_corners(&mesh, &options, &mut StridedMut::from_slice(&mut corners));
    for policy in [
        DegeneratePolicy::Legacy,
        DegeneratePolicy::Skip,
        DegeneratePolicy::Inherit,
    ] {
        let report = run(Options::mikktspace().with_policy(policy)).unwrap_or_else(|e| panic!("{policy:?}: {e}"));
        assert_eq!(
            (report.degenerate_triangles, report.first_degenerate_triangle),
            (2, Some(1)),
            "{policy:?}"
        );
    }
    let refused = run(Options::mikktspace().with_policy(DegeneratePolicy::Reject));
    assert!(
        matches!(refused, Err(tbasis::Error::DegenerateUv { triangle: 1, .. })),
        "{refused:?}"
    );
    let listing = run(Options::legacy()).expect("the listing takes any mesh");
    assert_eq!(
        (listing.degenerate_triangles, listing.first_degenerate_triangle),
        (1, Some(2))
    );
}
