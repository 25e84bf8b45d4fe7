//! What a successful call wrote: the per-vertex frames of `tbasis_generate` and the per-corner
//! frames of `tbasis_generate_corners`, each against what the header promises for its method and
//! policy.

use tbasis::{DegeneratePolicy, Method, Options, DEFAULT_DEGENERATE_THRESHOLD};

use crate::codes::*;
use crate::ffi::*;

use crate::arena::vec_at;
use crate::call::describe_report;
use crate::frames::{check_robust_tangent, cross, dot, length, same, unit, TOLERANCE};
use crate::listing_entry::listing;
use crate::mikktspace;
use crate::packed::Packed;
use crate::plan::{Plan, BIT, NRM, POS, TAN, UV};

/// The options of the plan's call, as the Rust API takes them (the call succeeded or refused the
/// mesh with DEGENERATE_UV: they are valid). The codes are mapped as the header defines them, the
/// method and policy 0 resolved by the plan, not by the library's own mapping.
pub fn options(plan: &Plan) -> Options {
    if plan.options_null {
        return Options::default();
    }
    let method = match plan.resolved_method() {
        TBASIS_METHOD_LENGYEL => Method::Lengyel,
        TBASIS_METHOD_ANGLE => Method::Angle,
        TBASIS_METHOD_AREA => Method::Area,
        TBASIS_METHOD_UNIFORM => Method::Uniform,
        TBASIS_METHOD_MIKKTSPACE => Method::Mikktspace,
        m => panic!("the call accepted method {m}, which the harness does not know"),
    };
    let policy = match plan.resolved_policy() {
        TBASIS_DEGENERATE_LEGACY => DegeneratePolicy::Legacy,
        TBASIS_DEGENERATE_SKIP => DegeneratePolicy::Skip,
        TBASIS_DEGENERATE_INHERIT => DegeneratePolicy::Inherit,
        TBASIS_DEGENERATE_REJECT => DegeneratePolicy::Reject,
        p => panic!("the call accepted policy {p}, which the harness does not know"),
    };
    assert_eq!(
        plan.flags & !TBASIS_FLAG_FLIP_V,
        0,
        "the call accepted flags {:#x}",
        plan.flags
    );
    // 0 (or -0) means the default threshold.
    let threshold = if plan.threshold == 0.0 {
        DEFAULT_DEGENERATE_THRESHOLD
    } else {
        plan.threshold
    };
    Options::default()
        .with_method(method)
        .with_policy(policy)
        .with_flip_v(plan.flip_v())
        .with_threads(plan.threads)
        .with_degenerate_threshold(threshold)
}

/// `tbasis_generate`: LENGYEL+LEGACY has the listing's bits, MIKKTSPACE each vertex its first
/// corner's frame, and every policy but LEGACY keeps the invariants.
pub fn check_vertex_outputs(
    plan: &Plan,
    before: &[u8],
    after: &[u8],
    triangles: &[[usize; 3]],
    report: Option<&tbasis_report>,
    mesh: &Packed,
) {
    let b = &plan.bufs;
    let vc = plan.vertex_count;
    let tangent = |i: usize| -> [f32; 4] { vec_at(after, b[TAN].element(i)) };
    let bitangent = |i: usize| -> Option<[f32; 3]> { (!b[BIT].null).then(|| vec_at(after, b[BIT].element(i))) };
    let normal = |i: usize| -> [f32; 3] { vec_at(before, b[NRM].element(i)) };

    if plan.mikktspace() {
        let tangents: Vec<[f32; 4]> = (0..vc).map(tangent).collect();
        mikktspace::check_vertices(mesh, &options(plan), &tangents, report, "tbasis_generate");
    }
    if plan.resolved_policy() == TBASIS_DEGENERATE_LEGACY {
        // The header promises the listing's bits for method LENGYEL; FLIP_V is not the listing.
        let listing_exact = plan.resolved_method() == TBASIS_METHOD_LENGYEL && !plan.flip_v();
        if listing_exact {
            let expected = listing(
                vc,
                triangles,
                |i| vec_at(before, b[POS].element(i)),
                normal,
                |i| vec_at(before, b[UV].element(i)),
            );
            for (i, want) in expected.iter().enumerate() {
                let got = tangent(i);
                assert!(
                    (0..4).all(|k| same(got[k], want[k])),
                    "LEGACY tangent {i} is {got:?}, the listing gives {want:?}"
                );
            }
        }
        for i in 0..vc {
            let [x, y, z, w] = tangent(i);
            assert!(w == 1.0 || w == -1.0, "LEGACY w of vertex {i} is {w}");
            if let Some(got) = bitangent(i) {
                let n = normal(i);
                let c = [n[1] * z - n[2] * y, n[2] * x - n[0] * z, n[0] * y - n[1] * x];
                let want = c.map(|c| c * w);
                assert!(
                    (0..3).all(|k| same(got[k], want[k])),
                    "LEGACY bitangent {i} is {got:?}, w * cross(n, t) is {want:?}"
                );
            }
        }
        return;
    }

    for i in 0..vc {
        let t4 = tangent(i);
        let context = || {
            format!(
                "vertex {i}: tangent {t4:?}, normal {:?}, bitangent {:?}",
                normal(i),
                bitangent(i)
            )
        };
        if plan.mikktspace() {
            // mikktspace.c's frame where the policy keeps it: off the plane by its rounding.
            mikktspace::check_kept_tangent(t4, normal(i), context);
        } else {
            check_robust_tangent(t4, normal(i), context);
        }
        let Some(b3) = bitangent(i) else {
            continue;
        };
        let [x, y, z, w] = t4.map(f64::from);
        let t = [x, y, z];
        let bv = b3.map(f64::from);
        assert!(b3.iter().all(|v| v.is_finite()), "{}: bitangent not finite", context());
        match unit(normal(i)) {
            Some(n) => {
                let want = cross(n, t).map(|c| c * w);
                assert!(
                    (0..3).all(|k| (bv[k] - want[k]).abs() <= TOLERANCE),
                    "{}: bitangent is not w * cross(n, t)",
                    context()
                );
            }
            None => {
                assert!(
                    (length(bv) - 1.0).abs() <= TOLERANCE,
                    "{}: bitangent not unit",
                    context()
                );
                assert!(dot(bv, t).abs() <= TOLERANCE, "{}: bitangent not orthogonal", context());
            }
        }
    }
}

/// `tbasis_generate_corners`: MIKKTSPACE gives mikktspace.c's frames (repaired where unusable,
/// under the policies other than LEGACY); the per-vertex methods give each corner its vertex's
/// bits from the same options' `tbasis_generate` (except the far side of a mirror fold, which the
/// invariants cover), with the same report.
pub fn check_corner_outputs(plan: &Plan, before: &[u8], after: &[u8], report: Option<&tbasis_report>, mesh: &Packed) {
    let b = &plan.bufs;
    let corners: Vec<[f32; 4]> = (0..plan.outputs()).map(|c| vec_at(after, b[TAN].element(c))).collect();
    let normal = |c: usize| -> [f32; 3] { vec_at(before, b[NRM].element(mesh.corner_vertex(c))) };
    let options = options(plan);
    let what = "tbasis_generate_corners";
    if plan.mikktspace() {
        mikktspace::check_corners(mesh, &options, &corners, report, what);
        return;
    }
    let legacy = plan.resolved_policy() == TBASIS_DEGENERATE_LEGACY;
    if !legacy {
        for (c, &t4) in corners.iter().enumerate() {
            check_robust_tangent(t4, normal(c), || format!("{what}: corner {c}: tangent {t4:?}"));
        }
    }
    // The same mesh and options per vertex, through the Rust API.
    let mut vertices = vec![[f32::NAN; 4]; plan.vertex_count];
    let mut output = tbasis::Output::new(&mut vertices[..]);
    let vertex_report = tbasis::generate(&mesh.mesh(), &options, &mut output)
        .unwrap_or_else(|e| panic!("{what} succeeded, tbasis::generate failed: {e:?}"));
    let vertex_report = tbasis_report::from(vertex_report);
    if let Some(r) = report {
        assert_eq!(
            describe_report(r),
            describe_report(&vertex_report),
            "{what}: the report differs from tbasis_generate's"
        );
    }
    // Off mirror folds (and everywhere under LEGACY, which has no sides), a corner has exactly its
    // vertex's bits.
    if legacy || vertex_report.mirrored_vertices == 0 {
        for (c, t) in corners.iter().enumerate() {
            let v = mesh.corner_vertex(c);
            assert_eq!(
                t.map(f32::to_bits),
                vertices[v].map(f32::to_bits),
                "{what}: corner {c} is {t:?}, its vertex {v} has {:?}",
                vertices[v]
            );
        }
    }
}
