//! One test per failure class of tangent generation (collapsed or extreme UVs, degenerate or
//! non-finite geometry, poles, mirror folds, odd topology), each under SKIP, INHERIT and REJECT:
//! the shared invariants hold, REJECT refuses exactly the meshes with degenerate triangles and
//! then writes nothing, and every report count equals what the mesh's construction implies.
//!
//! Every mesh here comes from `tbasis_test_support::cases`, whose `all_cases()` the C harness runs as well.

use tbasis::{
    DegeneratePolicy as Policy, ErrorKind, Method, Options, Output, Report, StridedMut, DEFAULT_DEGENERATE_THRESHOLD,
};
use tbasis_test_support::cases::{self, Attribute, Case, BAD_VALUES, BAD_VERTEX, BAND_CYLINDER, BAND_ROWS};
use tbasis_test_support::invariants::{check_invariants, cross, dot, unit_normal};
use tbasis_test_support::run::{generate_into, Run};
use tbasis_test_support::shapes::{grid_index, tangent_at_u, uv_sphere, Poles};

fn run_with(case: &Case, options: &Options) -> Run {
    case.run(options)
}

fn run(case: &Case, policy: Policy) -> Run {
    run_with(case, &Options::default().with_policy(policy))
}

/// The frames the library builds from the normals alone: the same geometry without texture
/// coordinates, where every vertex falls back.
fn normal_only_frames(case: &Case) -> Vec<[f32; 4]> {
    let bare = Case {
        texcoords: None,
        ..case.clone()
    };
    let run = run(&bare, Policy::Skip);
    assert_eq!(run.result, Ok(()));
    assert_eq!(run.report.fallback_vertices, case.vertex_count());
    run.tangents
}

/// Report counts a mesh's construction implies.
#[derive(Clone, Copy, Debug, Default)]
struct Expected {
    degenerate: usize,
    first: Option<usize>,
    mirrored: usize,
    unreferenced: usize,
    /// Normals zero, not finite or off unit length by more than 1e-3.
    abnormal: usize,
    /// Fallback vertices under SKIP (REJECT, when it accepts, gives the same).
    skip_fallback: usize,
    /// Fallback and inherited vertices under INHERIT.
    inherit_fallback: usize,
    inherited: usize,
}

impl Expected {
    /// Degenerate triangles `count`, the first `first`, and `fallback` vertices with nothing to
    /// inherit from (the same under SKIP and INHERIT).
    fn degenerate(count: usize, first: usize, fallback: usize) -> Self {
        Expected {
            degenerate: count,
            first: Some(first),
            skip_fallback: fallback,
            inherit_fallback: fallback,
            ..Expected::default()
        }
    }

    fn report(&self, policy: Policy) -> Report {
        let (fallback_vertices, inherited_vertices) = match policy {
            Policy::Skip => (self.skip_fallback, 0),
            Policy::Inherit => (self.inherit_fallback, self.inherited),
            // A refusal resolves nothing; an accepted mesh is resolved as SKIP resolves it.
            Policy::Reject if self.degenerate > 0 => (0, 0),
            Policy::Reject => (self.skip_fallback, 0),
            _ => unreachable!("LEGACY is not checked against constructed counts"),
        };
        Report {
            degenerate_triangles: self.degenerate,
            first_degenerate_triangle: self.first,
            fallback_vertices,
            mirrored_vertices: self.mirrored,
            unreferenced_vertices: self.unreferenced,
            inherited_vertices,
            abnormal_normals: self.abnormal,
            ..Report::default()
        }
    }
}

/// Every method: report counts and invariants are properties of the mesh and the policy.
const METHODS: [Method; 4] = [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform];

/// Runs SKIP, INHERIT and REJECT on `case` with every method: statuses, reports and invariants.
/// Returns the SKIP and INHERIT runs of the default method (LENGYEL) for checks of the tangents.
fn check_policies(case: &Case, expected: &Expected) -> (Run, Run) {
    check_policies_with(case, expected, &METHODS)
}

/// [`check_policies`] with the given methods; returns the SKIP and INHERIT runs of the first.
fn check_policies_with(case: &Case, expected: &Expected, methods: &[Method]) -> (Run, Run) {
    let name = &case.name;
    let mut first_runs = None;
    for &method in methods {
        let mut runs = Vec::new();
        for policy in [Policy::Skip, Policy::Inherit, Policy::Reject] {
            let options = Options::default().with_method(method).with_policy(policy);
            let run = run_with(case, &options);
            let refused = policy == Policy::Reject && expected.degenerate > 0;
            let mut wanted = expected.report(policy);
            if refused {
                // The header leaves open whether a refusal counts abnormal normals; not asserted.
                wanted.abnormal_normals = run.report.abnormal_normals;
            }
            assert_eq!(run.report, wanted, "{name}: {method:?} {policy:?} report");
            if refused {
                assert_eq!(
                    run.result,
                    Err(ErrorKind::DegenerateUv),
                    "{name}: {method:?} REJECT status"
                );
                assert!(run.untouched(), "{name}: {method:?} REJECT wrote output while refusing");
            } else {
                assert_eq!(run.result, Ok(()), "{name}: {method:?} {policy:?} status");
                if let Err(e) = check_invariants(&case.normals, &run.tangents, Some(&run.bitangents)) {
                    panic!("{name}: {method:?} {policy:?}: {e}");
                }
            }
            if method == Method::DEFAULT {
                // The C harness compares its reports with these.
                let file = case.expected_report(policy);
                assert_eq!(file, run.report, "{name}: {policy:?} case file report");
            }
            runs.push(run);
        }
        if first_runs.is_none() {
            runs.truncate(2);
            let inherit = runs.pop().unwrap();
            let skip = runs.pop().unwrap();
            first_runs = Some((skip, inherit));
        }
    }
    first_runs.expect("at least one method")
}

/// Angle in degrees between the tangent's xyz and a unit direction.
fn angle_degrees(tangent: [f32; 4], truth: [f64; 3]) -> f64 {
    let t = [tangent[0], tangent[1], tangent[2]].map(f64::from);
    let c = cross(t, truth);
    dot(c, c).sqrt().atan2(dot(t, truth)).to_degrees()
}

const X: [f64; 3] = [1.0, 0.0, 0.0];

/// Asserts vertex `v`'s tangent is within `degrees` of `truth` with handedness `w`.
fn assert_frame(case: &str, run: &Run, v: usize, truth: [f64; 3], w: f32, degrees: f64) {
    let t = run.tangent(v);
    let angle = angle_degrees(t, truth);
    assert!(
        angle <= degrees && t[3] == w,
        "{case}: vertex {v}: tangent {t:?} is {angle} degrees from {truth:?} (w expected {w})"
    );
}

#[test]
fn all_uvs_equal() {
    let case = cases::all_uvs_equal();
    // Both triangles collapse; no vertex has a measured neighbour to inherit from.
    let (skip, inherit) = check_policies(&case, &Expected::degenerate(2, 0, 4));
    let frames = normal_only_frames(&case);
    assert_eq!(skip.tangents, frames, "SKIP gives the frames built from the normals");
    assert_eq!(inherit.tangents, frames, "INHERIT has nothing to inherit");
}

#[test]
fn collinear_uvs() {
    for case in [cases::collinear_uvs(), cases::collinear_uvs_rounded()] {
        let (skip, _) = check_policies(&case, &Expected::degenerate(2, 0, 4));
        assert_eq!(skip.tangents, normal_only_frames(&case), "{}", case.name);
    }
}

#[test]
fn uvs_scaled_to_1e_minus_20_and_1e20() {
    let reference = cases::uv_scale_reference();
    let (cols, rows) = cases::SCALE_GRID;
    // The separate collinear triangle comes after the grid's and is the only degenerate one.
    let expected = Expected::degenerate(1, 2 * cols * rows, 3);
    let (reference_skip, reference_inherit) = check_policies(&reference, &expected);
    for case in [
        cases::uv_scaled(1e-20, "uv_scaled_down_1e20"),
        cases::uv_scaled(1e20, "uv_scaled_up_1e20"),
    ] {
        let (skip, inherit) = check_policies(&case, &expected);
        for (policy, scaled, unscaled) in [
            ("SKIP", &skip, &reference_skip),
            ("INHERIT", &inherit, &reference_inherit),
        ] {
            for (v, (a, b)) in scaled.tangents.iter().zip(&unscaled.tangents).enumerate() {
                let close = (0..3).all(|k| (a[k] - b[k]).abs() <= 1e-5) && a[3] == b[3];
                assert!(close, "{} {policy}: vertex {v}: {a:?} vs unscaled {b:?}", case.name);
            }
        }
    }
}

/// The README's degenerate test: its shape quality `q` does not change with the UVs' rotation or the
/// order of a triangle's corners, but for rounding. One triangle at a time, for UV triangles of
/// `q` down to 5% from the threshold on either side (the rounding of these coordinates moves `q`
/// by under 1%), the test's outcome is the same at every angle and in every corner order.
#[test]
fn degenerate_test_ignores_uv_rotation_and_corner_order() {
    let threshold = DEFAULT_DEGENERATE_THRESHOLD;
    // A UV triangle (0, 0), (1, 0), (0.5, h) has q = 2 sqrt(3) h / (1.5 + 2 h^2).
    let qualities = [1e-7f32, 5e-6, 9.5e-6, 1.05e-5, 2e-5, 1e-3, 0.8];
    let orders: [[u32; 3]; 3] = [[0, 1, 2], [1, 2, 0], [0, 2, 1]];
    for q in qualities {
        let h = q * 1.5 / (2.0 * 3f32.sqrt());
        for angle in [0.0f32, 0.3, 1.0, 2.5, 4.0] {
            let (sin, cos) = angle.sin_cos();
            let turn = |[u, v]: [f32; 2]| [0.37 + cos * u - sin * v, 0.61 + sin * u + cos * v];
            for order in orders {
                let case = Case {
                    name: format!("q {q:e}, angle {angle}, corners {order:?}"),
                    positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.866, 0.0]],
                    normals: vec![[0.0, 0.0, 1.0]; 3],
                    texcoords: Some([[0.0, 0.0], [1.0, 0.0], [0.5, h]].map(turn).to_vec()),
                    indices: Some(order.to_vec()),
                };
                for method in [Method::Angle, Method::Lengyel] {
                    let run = run_with(&case, &Options::default().with_method(method).with_policy(Policy::Skip));
                    assert_eq!(run.result, Ok(()), "{}", case.name);
                    let degenerate = usize::from(q < threshold);
                    assert_eq!(run.report.degenerate_triangles, degenerate, "{} {method:?}", case.name);
                }
            }
        }
    }
}

#[test]
fn zero_area_triangles() {
    // Vertex 3 lies on the zero-area triangle only; its neighbours 1 and 2 have tangent +x.
    let case = cases::zero_area_midpoint();
    let expected = Expected {
        degenerate: 1,
        first: Some(1),
        skip_fallback: 1,
        inherit_fallback: 0,
        inherited: 1,
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&case, &expected);
    for v in 0..3 {
        assert_frame(&case.name, &skip, v, X, 1.0, 1e-3);
    }
    assert_eq!(skip.tangent(3), normal_only_frames(&case)[3]);
    assert_frame(&case.name, &inherit, 3, X, 1.0, 1e-3);

    // All three corners in one point: nothing to measure or inherit.
    check_policies(&cases::zero_area_coincident(), &Expected::degenerate(1, 0, 3));
}

#[test]
fn sliver() {
    // Flipped in UV but above the threshold: it counts, as a mirrored contribution at its three
    // corners (0, 2, 4), weighted down so that it cannot outvote the good triangles.
    let kept = cases::sliver(cases::SLIVER_KEPT, "sliver_flipped_kept");
    let expected = Expected {
        mirrored: 3,
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&kept, &expected);
    for run in [&skip, &inherit] {
        for v in 0..kept.vertex_count() {
            // The good triangles' own tangents deviate from +x by at most 4 * eps rad (0.23 degrees).
            assert_frame(&kept.name, run, v, X, 1.0, 0.5);
        }
    }

    // Below the threshold: degenerate, and every corner still has good triangles.
    let thin = cases::sliver(cases::SLIVER_DEGENERATE, "sliver_below_threshold");
    let expected = Expected {
        degenerate: 1,
        first: Some(1),
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&thin, &expected);
    for run in [&skip, &inherit] {
        for v in 0..thin.vertex_count() {
            assert_frame(&thin.name, run, v, X, 1.0, 1e-3);
        }
    }
}

/// Splits the vertices that have no non-degenerate triangle into those INHERIT can reach (a chain
/// of shared triangles leads to a vertex that has one) and the others: `(inherited, fallback)`.
fn inherit_split(vertex_count: usize, indices: &[u32], measured: &[bool]) -> (usize, usize) {
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    let mut parent: Vec<usize> = (0..vertex_count).collect();
    for tri in indices.chunks(3) {
        for &v in &tri[1..] {
            let (a, b) = (root(&mut parent, tri[0] as usize), root(&mut parent, v as usize));
            parent[a] = b;
        }
    }
    let mut region_measured = vec![false; vertex_count];
    for v in (0..vertex_count).filter(|&v| measured[v]) {
        let r = root(&mut parent, v);
        region_measured[r] = true;
    }
    let (mut inherited, mut fallback) = (0, 0);
    for v in (0..vertex_count).filter(|&v| !measured[v]) {
        if region_measured[root(&mut parent, v)] {
            inherited += 1;
        } else {
            fallback += 1;
        }
    }
    (inherited, fallback)
}

/// Angle errors in degrees against the true tangent of a sphere.
#[derive(Debug)]
struct ErrorStats {
    mean: f64,
    p99: f64,
    max: f64,
    /// Vertices whose handedness is not the true +1.
    wrong_w: usize,
}

/// Errors over the vertices `include` accepts.
fn sphere_errors_over(run: &Run, truth: &Case, include: impl Fn(usize) -> bool) -> ErrorStats {
    let uvs = truth.texcoords.as_ref().unwrap();
    let vertices: Vec<usize> = (0..truth.vertex_count()).filter(|&v| include(v)).collect();
    let mut angles: Vec<f64> = vertices
        .iter()
        .map(|&v| angle_degrees(run.tangent(v), tangent_at_u(uvs[v][0])))
        .collect();
    let wrong_w = vertices.iter().filter(|&&v| run.tangent(v)[3] != 1.0).count();
    let mean = angles.iter().sum::<f64>() / angles.len() as f64;
    angles.sort_by(f64::total_cmp);
    ErrorStats {
        mean,
        p99: angles[angles.len() * 99 / 100],
        max: *angles.last().unwrap(),
        wrong_w,
    }
}

fn sphere_errors(run: &Run, truth: &Case) -> ErrorStats {
    sphere_errors_over(run, truth, |_| true)
}

#[test]
fn quantized_8bit_uvs_on_a_dense_mesh() {
    let case = cases::quantized_uv_sphere();
    let (segments, rings) = cases::QUANTIZED_SPHERE;
    let truth = uv_sphere("truth", segments, rings, Poles::PerSegment);

    // Expected counts from the 8-bit integers: a triangle is degenerate exactly when its integer
    // UV determinant is 0 (a nonzero one on these few-unit triangles has quality far above 1e-5).
    let k: Vec<[i64; 2]> = case
        .texcoords
        .as_ref()
        .unwrap()
        .iter()
        .map(|uv| uv.map(|x| (x * 255.0).round() as i64))
        .collect();
    let indices = case.indices.as_ref().unwrap();
    let mut has_good_triangle = vec![false; case.vertex_count()];
    let (mut degenerate, mut first) = (0, None);
    for (t, tri) in indices.chunks(3).enumerate() {
        let [a, b, c] = [0, 1, 2].map(|i| k[tri[i] as usize]);
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        // Rounding is monotone, so no triangle flips: nothing can be mirrored.
        assert!(det >= 0, "triangle {t} flipped by rounding");
        if det == 0 {
            degenerate += 1;
            first.get_or_insert(t);
        } else {
            tri.iter().for_each(|&v| has_good_triangle[v as usize] = true);
        }
    }
    // Steps of 1/288 and 1/272 exceed half of 1/255, so no two neighbouring steps both collapse
    // and every ring vertex keeps a good triangle; a pole vertex has a single triangle, which
    // collapses with its column, and then inherits from that triangle's ring vertices.
    assert!(
        degenerate > 1000,
        "construction should collapse many triangles, got {degenerate}"
    );
    let unmeasured = has_good_triangle.iter().filter(|&&g| !g).count();
    assert!(unmeasured > 0 && unmeasured < 2 * segments);
    let (inherited, inherit_fallback) = inherit_split(case.vertex_count(), indices, &has_good_triangle);
    let expected = Expected {
        degenerate,
        first,
        skip_fallback: unmeasured,
        inherit_fallback,
        inherited,
        ..Expected::default()
    };
    println!(
        "quantized {segments}x{rings} sphere: {} vertices, {} triangles, {degenerate} degenerate, \
         {unmeasured} vertices on degenerate triangles only",
        case.vertex_count(),
        indices.len() / 3
    );
    let baseline = sphere_errors(&run(&truth, Policy::Skip), &truth);
    println!("  unquantized UVs (tessellation error): {baseline:?}");
    // Bounds a few times what was measured (LENGYEL: mean 0.11 degrees, max 0.63, the same max as
    // the unquantized sphere's); SKIP's fallback frames at the collapsed poles are left out.
    for method in METHODS {
        let (skip, inherit) = check_policies_with(&case, &expected, &[method]);
        let skip_all = sphere_errors(&skip, &truth);
        let skip_measured = sphere_errors_over(&skip, &truth, |v| has_good_triangle[v]);
        let inherit_all = sphere_errors(&inherit, &truth);
        println!("  {method:?} SKIP, all vertices:      {skip_all:?}");
        println!("  {method:?} SKIP, measured vertices: {skip_measured:?}");
        println!("  {method:?} INHERIT, all vertices:   {inherit_all:?}");
        for (what, errors) in [("SKIP", &skip_measured), ("INHERIT", &inherit_all)] {
            assert!(errors.mean < 0.5, "{method:?} {what}: mean angle error {errors:?}");
            assert!(
                errors.p99 < 1.5,
                "{method:?} {what}: 99th percentile angle error {errors:?}"
            );
            assert!(errors.max < 2.0, "{method:?} {what}: largest angle error {errors:?}");
            assert_eq!(errors.wrong_w, 0, "{method:?} {what}: handedness flipped by rounding");
        }
    }
    let legacy = run_with(&case, &Options::legacy());
    let non_finite = legacy
        .tangents
        .iter()
        .filter(|t| t.iter().any(|x| !x.is_finite()))
        .count();
    println!("  LEGACY: {non_finite} vertices written with inf or NaN");
}

#[test]
fn uv_sphere_poles() {
    let (segments, rings) = cases::POLE_SPHERE;

    // One pole vertex per segment: each sees one triangle whose u edge is the chord of its
    // segment, so its tangent is the true one at the segment's middle u.
    let case = cases::sphere_poles(Poles::PerSegment);
    let (skip, inherit) = check_policies(&case, &Expected::default());
    let uvs = case.texcoords.as_ref().unwrap();
    let poles = (0..segments).chain(case.vertex_count() - segments..case.vertex_count());
    for v in poles {
        for run in [&skip, &inherit] {
            assert_frame(&case.name, run, v, tangent_at_u(uvs[v][0]), 1.0, 1e-3);
        }
    }
    // Elsewhere only the coarse tessellation's own error (16 segments: up to ~10 degrees next to
    // the seam, where a vertex sees one side's triangles only).
    let errors = sphere_errors(&skip, &case);
    assert!(errors.max < 15.0 && errors.mean < 3.0, "{errors:?}");

    // One shared vertex per pole: its triangles' u edges are the chords of a closed ring and sum
    // to zero, so SKIP has no tangent to measure there. INHERIT takes one from the ring around it,
    // as its region has measured tangents.
    let case = cases::sphere_poles(Poles::Shared);
    let shared_poles = [0, case.vertex_count() - 1];
    let expected = Expected {
        skip_fallback: 2,
        inherit_fallback: 0,
        inherited: 2,
        ..Expected::default()
    };
    let skip = run(&case, Policy::Skip);
    assert_eq!(skip.report, expected.report(Policy::Skip));
    let frames = normal_only_frames(&case);
    for v in shared_poles {
        assert_eq!(skip.tangent(v), frames[v]);
    }
    let _ = rings;
    check_policies(&case, &expected);
}

#[test]
fn mirror_fold_with_shared_vertices() {
    let case = cases::mirror_fold();
    let (cols, rows) = cases::MIRROR_GRID;
    // The seam is the middle column, one vertex per row, used by both halves.
    let expected = Expected {
        mirrored: rows + 1,
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&case, &expected);
    for run in [&skip, &inherit] {
        for j in 0..=rows {
            for i in 0..=cols {
                let v = grid_index(cols, i, j) as usize;
                let t = run.tangent(v);
                // Right half: u along +x, w = +1; left half: u along -x, w = -1. Either way the
                // bitangent w * cross(n, t) is +y, the true direction of v on both halves.
                let side = (i as f64 - (cols / 2) as f64).clamp(-1.0, 1.0);
                if side != 0.0 {
                    assert_frame(&case.name, run, v, [side, 0.0, 0.0], side as f32, 1e-3);
                } else {
                    // The seam keeps one half's frame whole rather than a cancelled sum.
                    assert_frame(&case.name, run, v, [f64::from(t[3]), 0.0, 0.0], t[3], 1e-3);
                }
                let b = run.bitangents[v];
                assert!((b[1] - 1.0).abs() < 1e-5, "{}: vertex {v}: bitangent {b:?}", case.name);
            }
        }
    }
}

/// The six triangles of the 3 x 3 grid that use [`BAD_VERTEX`] are degenerate when one of its
/// inputs is not finite: vertices 0 and 8 then lie on degenerate triangles only (they inherit
/// from 1, 3 and 5, 7), and so does 4.
fn check_bad_attribute(attribute: Attribute) {
    for component in 0..attribute.components() {
        for (_, value) in BAD_VALUES {
            let case = cases::bad_attribute(attribute, component, value);
            let expected = match attribute {
                Attribute::Normal => Expected {
                    abnormal: 1,
                    ..Expected::default()
                },
                Attribute::Position | Attribute::Texcoord => Expected {
                    degenerate: 6,
                    first: Some(0),
                    skip_fallback: 3,
                    inherit_fallback: 0,
                    inherited: 3,
                    ..Expected::default()
                },
            };
            let (skip, inherit) = check_policies(&case, &expected);
            let frames = normal_only_frames(&case);
            for (v, &frame) in frames.iter().enumerate() {
                if attribute == Attribute::Normal && v == BAD_VERTEX {
                    // No usable normal: the measured direction stands, w has no meaning.
                    for run in [&skip, &inherit] {
                        let angle = angle_degrees(run.tangent(v), X);
                        assert!(angle < 1e-3, "{}: {:?}", case.name, run.tangent(v));
                    }
                    continue;
                }
                if attribute == Attribute::Normal || ![0, BAD_VERTEX, 8].contains(&v) {
                    assert_frame(&case.name, &skip, v, X, 1.0, 1e-3);
                } else {
                    assert_eq!(skip.tangent(v), frame, "{}: vertex {v}", case.name);
                }
                assert_frame(&case.name, &inherit, v, X, 1.0, 1e-3);
            }
        }
    }
}

#[test]
fn nan_and_inf_in_positions() {
    check_bad_attribute(Attribute::Position);
}

#[test]
fn nan_and_inf_in_normals() {
    check_bad_attribute(Attribute::Normal);
}

#[test]
fn nan_and_inf_in_texcoords() {
    check_bad_attribute(Attribute::Texcoord);
}

#[test]
fn zero_normals() {
    // Zero normals do not make triangles degenerate: the tangent is the measured one, unprojected.
    for (case, abnormal) in [(cases::zero_normals_all(), 4), (cases::zero_normal_center(), 1)] {
        let expected = Expected {
            abnormal,
            ..Expected::default()
        };
        let (skip, inherit) = check_policies(&case, &expected);
        for v in 0..case.vertex_count() {
            for run in [&skip, &inherit] {
                let angle = angle_degrees(run.tangent(v), X);
                assert!(angle < 1e-3, "{}: vertex {v}: {:?}", case.name, run.tangent(v));
            }
        }
    }
    // Nothing measured and no normal: still a unit tangent, w = +-1 and a unit bitangent.
    let expected = Expected {
        abnormal: 4,
        ..Expected::degenerate(2, 0, 4)
    };
    check_policies(&cases::zero_normals_collapsed(), &expected);

    // Subnormal, tiny and long normals along +z act as +z (and are counted as not unit).
    let case = cases::tiny_and_long_normals();
    let expected = Expected {
        abnormal: 4,
        ..Expected::default()
    };
    let (skip, _) = check_policies(&case, &expected);
    for (v, n) in case.normals.iter().enumerate() {
        assert_eq!(unit_normal(*n), Some([0.0, 0.0, 1.0]));
        assert_frame(&case.name, &skip, v, X, 1.0, 1e-3);
    }
}

#[test]
fn unreferenced_vertices() {
    // Vertices 1, 3 and 6 are used by no triangle, so they fall back under both policies; vertex
    // 1's normal is NaN.
    let case = cases::unreferenced_vertices();
    let expected = Expected {
        unreferenced: 3,
        abnormal: 1,
        skip_fallback: 3,
        inherit_fallback: 3,
        ..Expected::default()
    };
    let (skip, _) = check_policies(&case, &expected);
    for v in [0, 2, 4, 5] {
        assert_frame(&case.name, &skip, v, X, 1.0, 1e-3);
    }

    let case = cases::no_triangles();
    let expected = Expected {
        unreferenced: 6,
        skip_fallback: 6,
        inherit_fallback: 6,
        ..Expected::default()
    };
    check_policies(&case, &expected);
}

#[test]
fn single_triangle() {
    // dP/du = (2, 0, 1) and dP/dv = (0, 1, 0); cross(n, t) points along +y, so w = +1.
    let truth = [2.0 / 5f64.sqrt(), 0.0, 1.0 / 5f64.sqrt()];
    for case in [cases::single_triangle(), cases::single_triangle_unindexed()] {
        let (skip, inherit) = check_policies(&case, &Expected::default());
        for v in 0..3 {
            assert_frame(&case.name, &skip, v, truth, 1.0, 1e-3);
            assert_frame(&case.name, &inherit, v, truth, 1.0, 1e-3);
        }
    }
    check_policies(&cases::single_degenerate_triangle(), &Expected::degenerate(1, 0, 3));
}

#[test]
fn empty_mesh() {
    for case in [cases::empty_mesh(), cases::empty_mesh_unindexed()] {
        check_policies(&case, &Expected::default());
        // Output views of zero elements over guard bytes: nothing may be written, by any policy.
        for policy in [Policy::Legacy, Policy::Skip, Policy::Inherit, Policy::Reject] {
            let mut tangent_bytes = [0xA5u8; 32];
            let mut bitangent_bytes = [0x5Au8; 32];
            let mut report = Report {
                degenerate_triangles: 7,
                first_degenerate_triangle: Some(7),
                fallback_vertices: 7,
                mirrored_vertices: 7,
                unreferenced_vertices: 7,
                inherited_vertices: 7,
                abnormal_normals: 7,
                repaired_corners: 7,
                split_vertices: 7,
            };
            let result = {
                let mut output = Output {
                    tangents: StridedMut::from_bytes(&mut tangent_bytes, 16, 0).unwrap(),
                    bitangents: Some(StridedMut::from_bytes(&mut bitangent_bytes, 12, 0).unwrap()),
                };
                let options = match policy {
                    Policy::Legacy => Options::legacy(),
                    policy => Options::default().with_policy(policy),
                };
                generate_into(&case.mesh(), &options, &mut output, None, &mut report)
            };
            assert_eq!(result, Ok(()), "{}: {policy:?}", case.name);
            assert_eq!(report, Report::default(), "{}: {policy:?}", case.name);
            assert_eq!(report.first_degenerate_triangle, None);
            assert!(tangent_bytes.iter().all(|&b| b == 0xA5) && bitangent_bytes.iter().all(|&b| b == 0x5A));
        }
    }
}

#[test]
fn duplicate_indices_in_one_triangle() {
    // Triangles 2 [0,0,1], 3 [3,2,3] and 4 [4,4,4] are degenerate; vertex 4 is used (so not
    // unreferenced) but only by [4,4,4], which offers no neighbour to inherit from.
    let case = cases::duplicate_indices();
    let (skip, _) = check_policies(&case, &Expected::degenerate(3, 2, 1));
    for v in 0..4 {
        assert_frame(&case.name, &skip, v, X, 1.0, 1e-3);
    }
}

#[test]
fn texcoords_absent() {
    // Nothing is degenerate without texture coordinates (REJECT accepts), every vertex falls back.
    let case = cases::texcoords_absent();
    let expected = Expected {
        unreferenced: 1,
        skip_fallback: 5,
        inherit_fallback: 5,
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&case, &expected);
    assert_eq!(skip.tangents, inherit.tangents);
    // LEGACY needs texture coordinates and writes nothing without them.
    let legacy = run_with(&case, &Options::legacy());
    assert_eq!(legacy.result, Err(ErrorKind::MissingTexcoords));
    assert!(legacy.untouched());
}

#[test]
fn normals_near_negative_z() {
    // Vertex 3's normal (0, 0, -1e-30) is far from unit length.
    let case = cases::normals_near_negative_z();
    let expected = Expected {
        abnormal: 1,
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&case, &expected);
    for v in 0..case.vertex_count() {
        // Normals tilt by at most 1.5e-4 rad from -z; the measured +x moves by no more.
        assert_frame(&case.name, &skip, v, X, -1.0, 0.01);
        assert_frame(&case.name, &inherit, v, X, -1.0, 0.01);
    }

    // The frames built from these normals alone must not jump between nearby normals: the one
    // for exactly (0, 0, -1) is within a few times the tilt of every other one.
    let case = cases::normals_near_negative_z_fallback();
    let expected = Expected {
        abnormal: 1,
        ..Expected::degenerate(2, 0, 6)
    };
    let (skip, _) = check_policies(&case, &expected);
    let reference = skip.tangent(0);
    let reference = [reference[0], reference[1], reference[2]].map(f64::from);
    for v in 1..case.vertex_count() {
        let angle = angle_degrees(skip.tangent(v), reference);
        assert!(
            angle < 0.05,
            "vertex {v}: fallback {:?} is {angle} degrees away",
            skip.tangent(v)
        );
    }
}

#[test]
fn legacy_zero_determinant_writes_non_finite_values() {
    // The listing divides by the zero UV determinant: kept on purpose for bit-exactness.
    for case in [cases::all_uvs_equal(), cases::collinear_uvs()] {
        let legacy = run_with(&case, &Options::legacy());
        assert_eq!(legacy.result, Ok(()), "{}", case.name);
        assert_eq!(legacy.report.degenerate_triangles, 2, "{}", case.name);
        for (v, t) in legacy.tangents.iter().enumerate() {
            assert!(
                t[..3].iter().any(|x| !x.is_finite()),
                "{}: vertex {v}: {t:?}",
                case.name
            );
        }
    }
}

#[test]
fn inherit_fills_a_collapsed_region_from_its_neighbours() {
    let case = cases::collapsed_band();
    let (segments, _) = BAND_CYLINDER;
    let [below, middle, above] = BAND_ROWS;
    // Each quad between rows 3 and 5 has two corners in one column: same UV, zero area. Row 4
    // touches only those; rows 3 and 5 also touch good triangles on their outer side.
    let expected = Expected {
        degenerate: 2 * 2 * segments,
        first: Some(2 * below * segments),
        skip_fallback: segments + 1,
        inherit_fallback: 0,
        inherited: segments + 1,
        ..Expected::default()
    };
    let (skip, inherit) = check_policies(&case, &expected);
    let frames = normal_only_frames(&case);
    let uvs = case.texcoords.as_ref().unwrap();
    for v in 0..case.vertex_count() {
        if (v / (segments + 1)) != middle {
            assert_eq!(skip.tangent(v), inherit.tangent(v), "vertex {v}: measured frames agree");
        }
    }
    for i in 0..=segments {
        let inner = grid_index(segments, i, middle) as usize;
        assert_eq!(
            skip.tangent(inner),
            frames[inner],
            "SKIP: vertex {inner} gets its fallback frame"
        );
        let t = inherit.tangent(inner);
        assert_frame(&case.name, &inherit, inner, tangent_at_u(uvs[inner][0]), 1.0, 1.0);
        for row in [below, above] {
            let neighbour = inherit.tangent(grid_index(segments, i, row) as usize);
            let along = [neighbour[0], neighbour[1], neighbour[2]].map(f64::from);
            let angle = angle_degrees(t, along);
            assert!(
                angle < 2.0 && neighbour[3] == t[3],
                "vertex {inner}: {t:?} vs neighbour {neighbour:?}"
            );
        }
    }
}

#[test]
fn inherit_falls_back_everywhere_on_a_fully_collapsed_mesh() {
    let case = cases::fully_collapsed();
    let (segments, rows) = BAND_CYLINDER;
    let expected = Expected::degenerate(2 * segments * rows, 0, case.vertex_count());
    let (skip, inherit) = check_policies(&case, &expected);
    assert_eq!(inherit.tangents, skip.tangents);
    assert_eq!(skip.tangents, normal_only_frames(&case));
}

#[test]
fn every_case_keeps_the_invariants_under_every_robust_policy() {
    let cases = cases::all_cases();
    let mut names: Vec<&str> = cases.iter().map(|c| c.name.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), cases.len(), "case names must be unique");
    for case in &cases {
        let skip = run(case, Policy::Skip);
        for policy in [Policy::Skip, Policy::Inherit, Policy::Reject] {
            let run = run(case, policy);
            let report = run.report;
            match run.result {
                Ok(()) => {
                    if let Err(e) = check_invariants(&case.normals, &run.tangents, Some(&run.bitangents)) {
                        panic!("{}: {policy:?}: {e}", case.name);
                    }
                }
                Err(ErrorKind::DegenerateUv) if policy == Policy::Reject => {
                    assert!(run.untouched(), "{}: REJECT wrote while refusing", case.name);
                    assert!(report.degenerate_triangles > 0);
                }
                Err(e) => panic!("{}: {policy:?} failed: {e:?}", case.name),
            }
            // What the mesh holds does not depend on the policy; what is done about it does.
            assert_eq!(report.degenerate_triangles, skip.report.degenerate_triangles);
            assert_eq!(report.first_degenerate_triangle, skip.report.first_degenerate_triangle);
            assert_eq!(report.mirrored_vertices, skip.report.mirrored_vertices);
            assert_eq!(report.unreferenced_vertices, skip.report.unreferenced_vertices);
            if policy == Policy::Inherit {
                assert_eq!(
                    report.fallback_vertices + report.inherited_vertices,
                    skip.report.fallback_vertices,
                    "{}: INHERIT resolves exactly the vertices SKIP falls back on",
                    case.name
                );
            }
        }
    }
}

/// A fan of congruent right triangles around vertex 0, each with its own two outer vertices, in
/// triangle order: `Some(true)` for a right-handed one (u along +x, tangent +x, w = +1),
/// `Some(false)` for a left-handed one (u along -x: tangent -x, w = -1), `None` for one whose UVs
/// collapse to a point (degenerate). Every non-degenerate triangle's term at vertex 0 has the same
/// length under every method, so each side's sum is as long as its triangle count.
fn fold_fan(fan: &[Option<bool>]) -> (Vec<[f32; 3]>, Vec<[f32; 2]>, Vec<u32>) {
    let (mut positions, mut texcoords, mut indices) = (vec![[0.0; 3]], vec![[0.0; 2]], Vec::new());
    for &right in fan {
        let first = positions.len() as u32;
        positions.extend([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        texcoords.extend(match right {
            Some(right) => [[if right { 1.0 } else { -1.0 }, 0.0], [0.0, 1.0]],
            None => [[0.0, 0.0]; 2],
        });
        indices.extend([0, first, first + 1]);
    }
    (positions, texcoords, indices)
}

/// The mirror-fold rule (README, "Degenerate UVs and mirror folds"): a fold vertex takes the side
/// of its first corner unless the other side's sum is more than twice as long; exactly twice keeps
/// the first. Per corner ("Per-corner output"), its corners on the other side get that side's own
/// frame and `w`, and its corner in a degenerate triangle the vertex's frame. Both orders, every
/// per-vertex method, SKIP and INHERIT.
#[test]
fn a_fold_vertex_keeps_its_first_side_unless_the_other_is_more_than_twice_as_long() {
    let (right, left, collapsed) = (Some(true), Some(false), None);
    // (the fan, the w vertex 0 must get)
    let fans: [(&[Option<bool>], f32); 4] = [
        (&[left, right, collapsed, right], -1.0),
        (&[left, right, right, right, collapsed], 1.0),
        (&[right, collapsed, left, left], 1.0),
        (&[right, left, left, left, collapsed], -1.0),
    ];
    for (fan, w) in fans {
        let (positions, texcoords, indices) = fold_fan(fan);
        let normals = vec![[0.0, 0.0, 1.0f32]; positions.len()];
        let mesh = tbasis::Mesh::new(&positions[..], &normals[..])
            .with_texcoords(&texcoords[..])
            .with_indices(&indices[..]);
        for method in [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform] {
            for policy in [Policy::Skip, Policy::Inherit] {
                let options = Options::default().with_method(method).with_policy(policy);
                let mut tangents = vec![[0.0f32; 4]; positions.len()];
                let report = tbasis::generate(&mesh, &options, &mut Output::new(&mut tangents[..])).unwrap();
                let what = format!("{fan:?}, {method:?}, {policy:?}");
                assert_eq!(
                    (report.mirrored_vertices, report.degenerate_triangles),
                    (1, 1),
                    "{what}"
                );
                let frame = tangents[0];
                assert_eq!(frame[3], w, "{what}: vertex 0's side");
                let close = |t: [f32; 4], side: f32| {
                    (t[0] - side).abs() < 1e-6 && t[1].abs() < 1e-6 && t[2].abs() < 1e-6 && t[3] == side
                };
                assert!(close(frame, w), "{what}: vertex 0's frame {frame:?}");
                let mut corners = vec![[0.0f32; 4]; indices.len()];
                tbasis::generate_corners(&mesh, &options, &mut StridedMut::from_slice(&mut corners)).unwrap();
                for (t, side) in fan.iter().enumerate() {
                    let corner = corners[3 * t];
                    let at = format!("{what}: triangle {t}'s corner at vertex 0, {corner:?}");
                    // A right-handed triangle's w is +1, a left-handed one's -1.
                    let on_the_other_side = side.is_some_and(|right| right != (w > 0.0));
                    if on_the_other_side {
                        assert!(close(corner, -w), "{at}: the other side's own frame");
                    } else {
                        assert_eq!(corner.map(f32::to_bits), frame.map(f32::to_bits), "{at}: the vertex's");
                    }
                }
            }
        }
    }
}

/// What uses vertex 0 in [`vertex_zero`].
#[derive(Clone, Copy, PartialEq)]
enum Fan {
    /// The triangle (0, 0, 0), (1, 0, 0), (0, 1, 0), u along +x.
    AlongX,
    /// The same triangle, u along +y.
    AlongY,
    /// That triangle, u along +x, and (0, 0, 0), (-1, 0, 0), (0, -1, 0), whose u runs along -x:
    /// the tangents cancel.
    Cancelled,
}

/// Vertex 0's frame and the report, with SKIP and `method`, on `fan`, with vertex 0's normal
/// `n0` and the others' +z.
fn vertex_zero(method: Method, n0: [f32; 3], fan: Fan) -> ([f32; 4], Report) {
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
    ];
    let mut normals = [[0.0, 0.0, 1.0f32]; 5];
    normals[0] = n0;
    // (u, v) = (x, y) on the first triangle, (y, -x) with `AlongY`; on the second, (-x, -y).
    let mut texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.0], [0.0, 1.0f32]];
    if fan == Fan::AlongY {
        texcoords[1..3].copy_from_slice(&[[0.0, -1.0], [1.0, 0.0]]);
    }
    let cancelled = fan == Fan::Cancelled;
    let indices: &[u32] = if cancelled { &[0, 1, 2, 0, 3, 4] } else { &[0, 1, 2] };
    let used = if cancelled { 5 } else { 3 };
    let mesh = tbasis::Mesh::new(&positions[..used], &normals[..used])
        .with_texcoords(&texcoords[..used])
        .with_indices(indices);
    let mut tangents = [[0.0f32; 4]; 5];
    let options = Options::default().with_method(method).with_policy(Policy::Skip);
    let report = tbasis::generate(&mesh, &options, &mut Output::new(&mut tangents[..used])).unwrap();
    (tangents[0], report)
}

/// README ("Degenerate UVs and mirror folds"): a tangent that Gram-Schmidt reduces below 1e-3 of
/// the weight that went into it is not used, whether it lies along the normal or cancels; ANGLE
/// weighs each triangle's tangent projected into the vertex's plane and normalized (mikktspace.c's
/// term), so there only a projection of zero length or a cancelled sum is dropped.
#[test]
fn a_tangent_gram_schmidt_reduces_below_a_thousandth_is_not_used() {
    // Vertex 0's normal tilted from its tangent, +x, by about `tilt` radians.
    let tilted = |tilt: f32| {
        let length = (1.0 + tilt * tilt).sqrt();
        [1.0 / length, tilt / length, 0.0]
    };
    for method in [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform] {
        for (tilt, reduced) in [(0.0, true), (5e-4, method != Method::Angle), (2e-3, false)] {
            let (t, report) = vertex_zero(method, tilted(tilt), Fan::AlongX);
            let what = format!("{method:?}, tilt {tilt}: {t:?}");
            assert_eq!(report.fallback_vertices, usize::from(reduced), "{what}");
            if !reduced {
                // What is left of +x across the normal: along -y, x about the tilt.
                assert!(t[1] < -0.99 && (t[0] - tilt).abs() < 1e-5 * tilt.max(1.0), "{what}");
            }
        }
        let (_, report) = vertex_zero(method, [0.0, 0.0, 1.0], Fan::Cancelled);
        assert_eq!(report.fallback_vertices, 1, "{method:?}: the cancelled sum");
    }
}

/// README: a zero or non-finite normal gives the tangent sum's direction when there is one, else
/// `(1, 0, 0)`, with `w = +1`.
#[test]
fn a_vertex_without_a_normal_takes_its_sums_direction_or_x() {
    for method in [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform] {
        for n0 in [[0.0, 0.0, 0.0], [f32::NAN, 0.0, 1.0], [f32::INFINITY, 0.0, 0.0]] {
            let what = format!("{method:?}, normal {n0:?}");
            let (t, report) = vertex_zero(method, n0, Fan::AlongY);
            assert_eq!(t, [0.0, 1.0, 0.0, 1.0], "{what}: the sum, +y");
            assert_eq!(report.abnormal_normals, 1, "{what}");
            let (t, report) = vertex_zero(method, n0, Fan::Cancelled);
            assert_eq!(t, [1.0, 0.0, 0.0, 1.0], "{what}: no sum");
            assert_eq!((report.fallback_vertices, report.abnormal_normals), (1, 1), "{what}");
        }
    }
}
