//! Method MIKKTSPACE against mikktspace.c itself (`crates/test-support/src/mikktspace_reference.rs`, through
//! `mikktspace-sys`): per corner, the same bits (a NaN matching any NaN) under policy LEGACY; under
//! SKIP, INHERIT and REJECT, the same bits wherever mikktspace.c's frame is kept (valid, or off the
//! normal's plane by rounding) and a valid frame with mikktspace.c's sign wherever it is not,
//! `repaired_corners` counting those; per vertex, the first corner's frame. On a mesh where mikktspace.c itself would run for seconds (`generate/mikktspace_cost.rs`), only the
//! checks that need no reference: the robust policies' frames, the report's counts, the threads,
//! the per-vertex frames.

use crate::ffi::tbasis_report;
use tbasis::{generate, generate_corners, DegeneratePolicy, Options, Output, StridedMut};

use crate::call::describe_report;
use tbasis_test_support::face_meshes::{both, FaceMesh, Run};
use crate::frames::{check_robust_tangent, dot, length, same_frame, show, unit};
use crate::packed::Packed;

/// Where mikktspace.c's frame of a corner stands against one of the library's tests: the harness
/// decides in f64 with a margin of a tenth either side and leaves the rest undecided.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Verdict {
    Surely,
    Maybe,
    Not,
}

/// How far `t` is from unit length, and how far off the unit `normal`'s plane; `None` when not
/// finite.
fn deviations(t: [f32; 4], normal: [f32; 3]) -> Option<(f64, f64)> {
    let v = [t[0], t[1], t[2]].map(f64::from);
    if !t[..3].iter().all(|x| x.is_finite()) {
        return None;
    }
    let off_plane = unit(normal).map_or(0.0, |n| dot(v, n).abs());
    Some(((length(v) - 1.0).abs(), off_plane))
}

fn verdict(within: impl Fn(f64) -> bool) -> Verdict {
    if within(0.9) {
        Verdict::Surely
    } else if within(1.1) {
        Verdict::Maybe
    } else {
        Verdict::Not
    }
}

/// Whether the library keeps mikktspace.c's frame bit for bit: finite, unit length within 1e-5,
/// off the unit normal's plane by at most 1e-4 plus `|1 - |n|^2|` (for a normal unit length within
/// 1e-3: mikktspace.c removes the normal as given). Every other corner is changed and counted by
/// `repaired_corners`.
fn kept(t: [f32; 4], normal: [f32; 3]) -> Verdict {
    let Some((off_length, off_plane)) = deviations(t, normal) else {
        return Verdict::Not;
    };
    verdict(|margin| off_length <= margin * 1e-5 && off_plane <= margin * kept_off_plane(normal))
}

/// A robust policy's frame that may be mikktspace.c's, kept: as [`check_robust_tangent`], but as
/// far off the plane as a kept frame may be.
pub fn check_kept_tangent(t: [f32; 4], normal: [f32; 3], context: impl Fn() -> String) {
    if let Some(n) = unit(normal) {
        let off_plane = dot([t[0], t[1], t[2]].map(f64::from), n).abs();
        assert!(off_plane <= 1.1 * kept_off_plane(normal), "{}: off the normal's plane", context());
    }
    // Length and sign as for any robust frame (a zero normal: the plane is checked above).
    check_robust_tangent(t, [0.0; 3], context);
}

/// How far off the unit normal's plane a kept frame may be.
fn kept_off_plane(normal: [f32; 3]) -> f64 {
    let n = normal.map(f64::from);
    let length = dot(n, n).sqrt();
    let slack = if unit(normal).is_some() && (length - 1.0).abs() <= 1e-3 {
        (1.0 - length * length).abs()
    } else {
        0.0
    };
    1e-4 + slack
}

/// Prints the mesh and stops: a mismatch against mikktspace.c is the finding this harness is for.
fn mismatch(mesh: &Packed, options: &Options, message: String) -> ! {
    eprintln!("mesh of the failing call ({options:?}):");
    mesh.describe();
    panic!("{message}");
}

/// Per vertex, its first corner.
fn first_corners(mesh: &Packed) -> Vec<Option<usize>> {
    let mut first = vec![None; mesh.vertex_count()];
    for c in 0..mesh.corner_count() {
        first[mesh.corner_vertex(c)].get_or_insert(c);
    }
    first
}

/// Checks the report's MIKKTSPACE counts against `corners`: vertices whose corners differ in any
/// bit (split), whose corners have both signs (mirrored), and that no corner uses.
fn check_counts(mesh: &Packed, corners: &[[f32; 4]], report: &tbasis_report, what: &str) {
    let first = first_corners(mesh);
    let (mut split, mut mirrored) = (vec![false; mesh.vertex_count()], vec![false; mesh.vertex_count()]);
    for (c, t) in corners.iter().enumerate() {
        let v = mesh.corner_vertex(c);
        let f = corners[first[v].expect("a used vertex has a first corner")];
        split[v] |= t.map(f32::to_bits) != f.map(f32::to_bits);
        mirrored[v] |= t[3].to_bits() != f[3].to_bits();
    }
    let count = |marks: &[bool]| marks.iter().filter(|&&m| m).count();
    let expected = (
        count(&split),
        count(&mirrored),
        first.iter().filter(|f| f.is_none()).count(),
    );
    let got = (
        report.split_vertices,
        report.mirrored_vertices,
        report.unreferenced_vertices,
    );
    assert_eq!(
        got,
        expected,
        "{what}: (split, mirrored, unreferenced) vertices of the report ({}) are not the corners'",
        describe_report(report)
    );
}

/// Checks the library's corners of `mesh` under `options` (method MIKKTSPACE) against
/// mikktspace.c's, and the report when there is one.
pub fn check_corners(mesh: &Packed, options: &Options, ours: &[[f32; 4]], report: Option<&tbasis_report>, what: &str) {
    assert!(
        mesh.texcoords.is_some(),
        "{what}: MIKKTSPACE succeeded without texcoords"
    );
    let legacy = options.degenerate_policy == DegeneratePolicy::Legacy;
    let Some(reference) = mesh.reference(options.flip_v) else {
        // mikktspace.c would take too long on this mesh: only what needs no reference.
        if !legacy {
            for (c, &t) in ours.iter().enumerate() {
                let normal = mesh.normals[mesh.corner_vertex(c)];
                check_kept_tangent(t, normal, || format!("{what}, {options:?}: corner {c}: {}", show(t)));
            }
        }
        if let Some(report) = report {
            check_counts(mesh, ours, report, what);
        }
        return;
    };
    assert_eq!(ours.len(), reference.len(), "{what}: corner count");
    let (mut surely, mut maybe) = (0, 0);
    for (c, (&t, &r)) in ours.iter().zip(reference).enumerate() {
        let v = mesh.corner_vertex(c);
        let where_ = || format!("{what}, {options:?}: corner {c} (triangle {} vertex {v})", c / 3);
        if legacy {
            if !same_frame(t, r) {
                mismatch(
                    mesh,
                    options,
                    format!("{}: ours {}, mikktspace.c {}", where_(), show(t), show(r)),
                );
            }
            continue;
        }
        let normal = mesh.normals[v];
        let state = kept(r, normal);
        surely += usize::from(state == Verdict::Not);
        maybe += usize::from(state != Verdict::Surely);
        let same_bits = t.map(f32::to_bits) == r.map(f32::to_bits);
        if state == Verdict::Surely && !same_bits {
            mismatch(
                mesh,
                options,
                format!(
                    "{}: mikktspace.c's frame {} is usable, yet replaced by {}",
                    where_(),
                    show(r),
                    show(t)
                ),
            );
        }
        if same_bits && state != Verdict::Not {
            check_kept_tangent(t, normal, || format!("{}: {}", where_(), show(t)));
        } else {
            check_robust_tangent(t, normal, || format!("{}: {}", where_(), show(t)));
        }
        assert_eq!(
            t[3],
            r[3],
            "{}: the sign of {} is not mikktspace.c's ({})",
            where_(),
            show(t),
            show(r)
        );
    }
    if let Some(report) = report {
        check_counts(mesh, ours, report, what);
        if !legacy {
            assert!(
                (surely..=maybe).contains(&report.repaired_corners),
                "{what}: repaired_corners {} should be in {surely}..={maybe}",
                report.repaired_corners
            );
        }
    }
}

/// The library's corners of `mesh` under `options` through the Rust API, with its report.
fn our_corners(mesh: &Packed, options: &Options) -> (Vec<[f32; 4]>, tbasis_report) {
    let mut corners = vec![[f32::NAN; 4]; mesh.corner_count()];
    let report = generate_corners(&mesh.mesh(), options, &mut StridedMut::from_slice(&mut corners))
        .unwrap_or_else(|e| panic!("generate_corners refused a valid mesh with {options:?}: {e:?}"));
    (corners, report.into())
}

/// Checks the per-vertex frames of `tangents` (method MIKKTSPACE) and their report: each used
/// vertex has exactly the bits of its first corner in the library's own corners (themselves
/// checked against mikktspace.c), each unused one the fallback frame (valid, `w = +1`), and the
/// report is the corners' but for those fallbacks.
pub fn check_vertices(
    mesh: &Packed,
    options: &Options,
    tangents: &[[f32; 4]],
    report: Option<&tbasis_report>,
    what: &str,
) {
    let (corners, corner_report) = our_corners(mesh, options);
    check_corners(mesh, options, &corners, Some(&corner_report), "generate_corners");
    vertex_frames(mesh, options, tangents, &corners, what);
    if let Some(report) = report {
        let expected = tbasis_report {
            fallback_vertices: corner_report.unreferenced_vertices,
            ..corner_report
        };
        assert_eq!(
            describe_report(report),
            describe_report(&expected),
            "{what}, {options:?}: the report is not generate_corners' with the unused vertices as fallbacks"
        );
    }
}

fn vertex_frames(mesh: &Packed, options: &Options, tangents: &[[f32; 4]], corners: &[[f32; 4]], what: &str) {
    for (v, first) in first_corners(mesh).into_iter().enumerate() {
        let t = tangents[v];
        match first {
            Some(c) => assert_eq!(
                t.map(f32::to_bits),
                corners[c].map(f32::to_bits),
                "{what}, {options:?}: vertex {v} is {}, its first corner {c} {}",
                show(t),
                show(corners[c])
            ),
            None => {
                let context = || format!("{what}: unused vertex {v}: {}", show(t));
                check_robust_tangent(t, mesh.normals[v], context);
                assert_eq!(t[3], 1.0, "{}: the fallback frame has w = +1", context());
            }
        }
    }
}

/// Method MIKKTSPACE with policy LEGACY through the Rust API, with `flip_v` off and on, per corner
/// with each of `threads` and per vertex with the first, against mikktspace.c: per corner, per
/// vertex and in the report.
pub fn check(mesh: &Packed, threads: &[u32]) {
    if mesh.texcoords.is_none() {
        return;
    }
    check_face_interface(mesh, threads);
    let bits = |frames: &[[f32; 4]]| frames.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    for flip_v in [false, true] {
        let mut first: Option<(Vec<[f32; 4]>, tbasis_report)> = None;
        for &threads in threads {
            let options = Options::mikktspace().with_flip_v(flip_v).with_threads(threads);
            assert_eq!(options.degenerate_policy, DegeneratePolicy::Legacy);
            let (corners, report) = our_corners(mesh, &options);
            match &first {
                Some((one, _)) => assert!(bits(one) == bits(&corners), "{options:?}: bits differ from threads=1"),
                None => {
                    check_corners(mesh, &options, &corners, Some(&report), "generate_corners");
                    assert_eq!(report.repaired_corners, 0, "repaired corners under LEGACY");
                    first = Some((corners, report));
                }
            }
        }
        let Some((corners, report)) = first else {
            return;
        };
        let options = Options::mikktspace().with_flip_v(flip_v).with_threads(threads[0]);
        let mut tangents = vec![[f32::NAN; 4]; mesh.vertex_count()];
        let mut output = Output::new(&mut tangents[..]);
        let vertex_report = generate(&mesh.mesh(), &options, &mut output)
            .unwrap_or_else(|e| panic!("generate refused a valid mesh with {options:?}: {e:?}"));
        vertex_frames(mesh, &options, &tangents, &corners, "generate");
        let expected = tbasis_report {
            fallback_vertices: report.unreferenced_vertices,
            ..report
        };
        assert_eq!(
            describe_report(&vertex_report.into()),
            describe_report(&expected),
            "generate, {options:?}: the report is not generate_corners' with the unused vertices as fallbacks"
        );
    }
}

/// `tbasis::mikktspace` (mikktspace.c's callback interface) against mikktspace.c on the mesh's
/// triangles as faces at the default threshold, and on them paired into quads (`(a, b, c)`,
/// `(a, c, d)` in a row) at 90 degrees on each thread count: the same return value and set calls,
/// a NaN matching any NaN.
fn check_face_interface(mesh: &Packed, threads: &[u32]) {
    let (Some(texcoords), Some(_)) = (mesh.texcoords.as_deref(), mesh.reference(false)) else {
        return;
    };
    let corners: Vec<u32> = (0..mesh.corner_count()).map(|c| mesh.corner_vertex(c) as u32).collect();
    let vertices = [&mesh.positions[..], &mesh.normals[..]];
    let runs = |quads: bool| -> Vec<Run> {
        match quads {
            false => vec![Run::Default],
            true => threads.iter().map(|&threads| Run::With(90.0, threads)).collect(),
        }
    };
    for quads in [false, true] {
        let faces = FaceMesh::from_triangles(String::new(), vertices, texcoords, &corners, quads);
        for run in runs(quads) {
            let [reference, ours] = both(&faces, run);
            if ours != reference {
                let k = ours.1.iter().zip(&reference.1).position(|(a, b)| a != b);
                let message = format!("faces (quads {quads}, {run:?}): returned {}, mikktspace.c {}; first differing call {k:?}", ours.0, reference.0);
                mismatch(mesh, &Options::mikktspace(), message);
            }
        }
    }
}
