//! Per-corner output (`generate_corners`) for the per-vertex methods: every corner gets exactly the
//! frame `generate` writes for its vertex, except at a mirror fold, where a corner on the side the
//! vertex's frame does not come from gets its own side's frame (valid, with that side's `w`).
//! Also: threads change no bit, errors write nothing, and caller scratch at any alignment gives
//! the same bits.

use tbasis::{
    scratch_size, scratch_size_for, DegeneratePolicy as Policy, ErrorKind, Indices, Method, Options, Report, Strided,
    StridedMut,
};
use tbasis_test_support::cases::{all_cases, collapsed_band, mirror_fold, Case};
use tbasis_test_support::invariants::check_frame;
use tbasis_test_support::run::{generate_corners_into, UNTOUCHED};
use tbasis_test_support::scenes::{angle_deg, build, Scene, SceneSpec};

const METHODS: [Method; 4] = [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform];
const POLICIES: [Policy; 4] = [Policy::Legacy, Policy::Skip, Policy::Inherit, Policy::Reject];

/// One `generate_corners_into` call's outcome, its output prefilled with [`UNTOUCHED`].
struct CornerRun {
    result: Result<(), ErrorKind>,
    report: Report,
    corners: Vec<[f32; 4]>,
}

impl CornerRun {
    fn untouched(&self) -> bool {
        self.corners.iter().flatten().all(|&x| x == UNTOUCHED)
    }
}

fn corner_count(case: &Case) -> usize {
    case.indices.as_ref().map_or(case.vertex_count(), Vec::len)
}

/// The vertex of corner `c`.
fn corner_vertex(case: &Case, c: usize) -> usize {
    case.indices.as_ref().map_or(c, |indices| indices[c] as usize)
}

fn run_corners(case: &Case, options: &Options, scratch: Option<&mut [u8]>) -> CornerRun {
    let mut corners = vec![[UNTOUCHED; 4]; corner_count(case)];
    let mut report = Report::default();
    let result = generate_corners_into(
        &case.mesh(),
        options,
        &mut StridedMut::from_slice(&mut corners),
        scratch,
        &mut report,
    );
    CornerRun {
        result,
        report,
        corners,
    }
}

fn options(method: Method, policy: Policy) -> Options {
    Options::default().with_method(method).with_policy(policy)
}

fn bits(frame: [f32; 4]) -> [u32; 4] {
    frame.map(f32::to_bits)
}

fn all_bits(frames: &[[f32; 4]]) -> Vec<[u32; 4]> {
    frames.iter().copied().map(bits).collect()
}

/// The UV determinant of the triangle corner `c` belongs to, in f64.
fn uv_determinant(case: &Case, c: usize) -> f64 {
    let uvs = case.texcoords.as_ref().expect("texcoords");
    let t = c / 3;
    let [a, b, d] = [0, 1, 2].map(|k| uvs[corner_vertex(case, 3 * t + k)].map(f64::from));
    (b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1])
}

/// Vertices some triangles use with a positive UV determinant and others with a negative one: every
/// vertex the library can treat as a mirror fold is among them.
fn two_sided_vertices(case: &Case) -> Vec<bool> {
    let mut signs = vec![(false, false); case.vertex_count()];
    if case.texcoords.is_some() {
        for c in 0..corner_count(case) {
            let det = uv_determinant(case, c);
            let sign = &mut signs[corner_vertex(case, c)];
            sign.0 |= det > 0.0;
            sign.1 |= det < 0.0;
        }
    }
    signs
        .into_iter()
        .map(|(positive, negative)| positive && negative)
        .collect()
}

/// A scene as a case, with every vertex its own copy (as built: seams and mirror lines split).
fn scene_case(scene: &Scene) -> Case {
    Case {
        name: scene.name.clone(),
        positions: scene.positions.clone(),
        normals: scene.normals.clone(),
        texcoords: Some(scene.texcoords.clone()),
        indices: Some(scene.indices.clone()),
    }
}

/// The mirrored torus with its mirror line welded: the triangles right of the line use the left
/// copies of the line's vertices (bit-identical positions, normals and UVs), so those vertices are
/// mirror folds. Returns the case and the scene, whose vertex `v + 1` holds the truth of the right
/// side of fold vertex `v`.
fn welded_mirrored_torus(target_vertices: usize) -> (Case, Scene) {
    let scene = build(&SceneSpec::mirrored_torus(target_vertices));
    let (n_a, _) = scene.grid;
    let columns = n_a + 2;
    let mirror_copy = n_a / 2 + 1;
    let mut case = scene_case(&scene);
    case.name = format!("welded-{}", case.name);
    for index in case.indices.as_mut().unwrap() {
        let v = *index as usize;
        if v % columns == mirror_copy {
            let welded = v - 1;
            let same = |a: [f32; 3], b: [f32; 3]| a.map(f32::to_bits) == b.map(f32::to_bits);
            assert!(same(scene.positions[v], scene.positions[welded]) && same(scene.normals[v], scene.normals[welded]));
            assert_eq!(scene.texcoords[v], scene.texcoords[welded]);
            *index = welded as u32;
        }
    }
    (case, scene)
}

/// Small instances of every analytic scene, the mirror line welded in one.
fn small_scenes() -> Vec<Case> {
    vec![
        scene_case(&build(&SceneSpec::torus(2_000))),
        scene_case(&build(&SceneSpec::sphere(2_000))),
        scene_case(&build(&SceneSpec::mirrored_torus(2_000))),
        welded_mirrored_torus(2_000).0,
    ]
}

/// Per-corner against per-vertex on one case: same status and report; nothing written on error;
/// on success each corner has its vertex's bits, or (a fold corner on the other side) a valid frame
/// with the opposite `w`. Returns how many corners took a side frame.
fn compare_with_vertices(case: &Case, options: &Options, two_sided: &[bool]) -> usize {
    let what = format!("{} {:?} {:?}", case.name, options.method, options.degenerate_policy);
    let vertices = case.run(options);
    let corners = run_corners(case, options, None);
    assert_eq!(corners.result, vertices.result, "{what}: status");
    if vertices.result.is_ok() || vertices.result == Err(ErrorKind::DegenerateUv) {
        assert_eq!(corners.report, vertices.report, "{what}: report");
    }
    if corners.result.is_err() {
        assert!(corners.untouched(), "{what}: a failed call wrote output");
        return 0;
    }
    let mut side_frames = 0;
    for (c, &corner) in corners.corners.iter().enumerate() {
        let v = corner_vertex(case, c);
        let vertex = vertices.tangent(v);
        if bits(corner) == bits(vertex) {
            continue;
        }
        side_frames += 1;
        assert!(
            options.degenerate_policy != Policy::Legacy && two_sided[v],
            "{what}: corner {c} is {corner:?}, its vertex {v} (no mirror fold) has {vertex:?}"
        );
        assert_eq!(corner[3], -vertex[3], "{what}: corner {c} at fold vertex {v}: w");
        if let Err(problem) = check_frame(case.normals[v], corner, None) {
            panic!("{what}: corner {c} at fold vertex {v}: {problem}");
        }
    }
    side_frames
}

#[test]
fn every_corner_gets_its_vertex_frame_except_on_the_other_side_of_a_fold() {
    let cases: Vec<Case> = all_cases().into_iter().chain(small_scenes()).collect();
    let mut side_frames = 0;
    for case in &cases {
        let two_sided = two_sided_vertices(case);
        for method in METHODS {
            for policy in POLICIES {
                if policy == Policy::Legacy && !method.has_legacy_form() {
                    continue;
                }
                side_frames += compare_with_vertices(case, &options(method, policy), &two_sided);
            }
        }
        // The defaults (ANGLE, INHERIT) are what policy 0 gives.
        compare_with_vertices(case, &Options::default(), &two_sided);
    }
    assert!(side_frames > 0, "no case exercised a side frame");
}

/// At every vertex where triangles of both UV orientations meet (away from degenerate ones), each
/// corner's `w` is its own triangle's orientation and its frame is valid; on the welded torus the
/// tangent also follows the true tangent of its own side.
#[test]
fn fold_corners_take_the_handedness_of_their_own_triangle() {
    let (torus, scene) = welded_mirrored_torus(2_000);
    let flat = mirror_fold();
    for (case, truth) in [(&flat, None), (&torus, Some(&scene))] {
        let two_sided = two_sided_vertices(case);
        let folds = two_sided.iter().filter(|&&f| f).count();
        assert!(folds >= 3, "{}: only {folds} fold vertices", case.name);
        for method in METHODS {
            for policy in [Policy::Skip, Policy::Inherit, Policy::Reject] {
                let what = format!("{} {method:?} {policy:?}", case.name);
                let run = run_corners(case, &options(method, policy), None);
                assert_eq!(run.result, Ok(()), "{what}");
                assert_eq!(run.report.mirrored_vertices, folds, "{what}: mirrored vertices");
                for (c, &corner) in run.corners.iter().enumerate() {
                    let v = corner_vertex(case, c);
                    if !two_sided[v] {
                        continue;
                    }
                    let orientation = uv_determinant(case, c).signum() as f32;
                    assert_eq!(corner[3], orientation, "{what}: corner {c} at fold vertex {v}");
                    if let Err(problem) = check_frame(case.normals[v], corner, None) {
                        panic!("{what}: corner {c} at fold vertex {v}: {problem}");
                    }
                    if let Some(scene) = truth {
                        // The right side's truth is that of the copy the welding replaced.
                        let copy = if orientation < 0.0 { v + 1 } else { v };
                        let t = [corner[0], corner[1], corner[2]];
                        let angle = angle_deg(t, &scene.truth[copy], case.normals[v]).unwrap();
                        assert_eq!(scene.truth[copy].sign as f32, corner[3], "{what}: corner {c}: true w");
                        assert!(
                            angle < 5.0,
                            "{what}: corner {c} is {angle} degrees off its side's tangent"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn threads_change_no_bit() {
    // Large enough for three workers; the welded mirror line gives folds in the middle worker.
    let (case, _) = welded_mirrored_torus(100_000);
    assert!(
        case.vertex_count() >= 3 * 32 * 1024,
        "{} is too small to split",
        case.vertex_count()
    );
    for method in METHODS {
        for policy in POLICIES {
            if policy == Policy::Legacy && !method.has_legacy_form() {
                continue;
            }
            let base = options(method, policy);
            let one = run_corners(&case, &base.with_threads(1), None);
            assert_eq!(one.result, Ok(()), "{method:?} {policy:?}");
            for threads in [2, 8] {
                let what = format!("{method:?} {policy:?} threads={threads}");
                let run = run_corners(&case, &base.with_threads(threads), None);
                assert_eq!(run.result, one.result, "{what}");
                assert_eq!(run.report, one.report, "{what}: report");
                assert!(
                    all_bits(&run.corners) == all_bits(&one.corners),
                    "{what}: corners differ"
                );
            }
        }
    }
}

#[test]
fn caller_scratch_at_any_alignment_gives_the_same_bits() {
    let (torus, _) = welded_mirrored_torus(2_000);
    for case in [mirror_fold(), torus, collapsed_band()] {
        for method in METHODS {
            for policy in POLICIES {
                if policy == Policy::Legacy && !method.has_legacy_form() {
                    continue;
                }
                let options = options(method, policy);
                let what = format!("{} {method:?} {policy:?}", case.name);
                let needed = scratch_size_for(&case.mesh(), &options).unwrap();
                // INHERIT adds its adjacency: 8 bytes per vertex and 4 per corner.
                let adjacency = match policy {
                    Policy::Inherit => 8 * case.vertex_count() + 4 * case.mesh().corner_count(),
                    _ => 0,
                };
                assert_eq!(
                    Some(needed),
                    scratch_size(case.vertex_count()).map(|size| size + adjacency),
                    "{what}: documented size"
                );
                let plain = run_corners(&case, &options, None);
                // Stale bytes in the scratch must not matter.
                let mut buffer = vec![0xA5u8; needed + 8];
                for offset in 0..4 {
                    let run = run_corners(&case, &options, Some(&mut buffer[offset..offset + needed]));
                    assert_eq!(run.result, plain.result, "{what} offset {offset}");
                    assert_eq!(run.report, plain.report, "{what} offset {offset}: report");
                    assert!(
                        all_bits(&run.corners) == all_bits(&plain.corners),
                        "{what} offset {offset}: corners differ"
                    );
                }
                let worst = (0..4).find(|&o| (buffer[o..].as_ptr() as usize) % 4 == 1).unwrap();
                let short = run_corners(&case, &options, Some(&mut buffer[worst..worst + needed - 1]));
                assert_eq!(short.result, Err(ErrorKind::ScratchTooSmall), "{what}: one byte short");
                assert!(short.untouched(), "{what}: one byte short wrote output");
            }
        }
    }
}

#[test]
fn errors_write_nothing() {
    let case = mirror_fold();
    let last = case.indices.as_ref().unwrap().len() - 1;
    let mut out_of_range = case.clone();
    out_of_range.indices.as_mut().unwrap()[last] = case.vertex_count() as u32;
    let mut short_indices = case.clone();
    short_indices.indices.as_mut().unwrap().pop();
    let mut collapsed = case.clone();
    collapsed.texcoords.as_mut().unwrap()[0] = collapsed.texcoords.as_ref().unwrap()[1];
    let bare = Case {
        texcoords: None,
        ..case.clone()
    };
    let bad_threshold = Options::default().with_degenerate_threshold(f32::NAN);
    let calls = [
        (
            &out_of_range,
            options(Method::Angle, Policy::Inherit),
            ErrorKind::IndexOutOfRange,
        ),
        (
            &out_of_range,
            options(Method::Lengyel, Policy::Legacy),
            ErrorKind::IndexOutOfRange,
        ),
        (&short_indices, Options::default(), ErrorKind::InvalidIndexCount),
        (
            &collapsed,
            options(Method::Angle, Policy::Reject),
            ErrorKind::DegenerateUv,
        ),
        (
            &bare,
            options(Method::Lengyel, Policy::Legacy),
            ErrorKind::MissingTexcoords,
        ),
        (&case, bad_threshold, ErrorKind::InvalidThreshold),
    ];
    for (case, options, error) in calls {
        let run = run_corners(case, &options, None);
        assert_eq!(run.result, Err(error), "{}", case.name);
        assert!(run.untouched(), "{:?} wrote output", error);
        if error == ErrorKind::DegenerateUv {
            assert_eq!(run.report.degenerate_triangles, 1);
            assert_eq!(run.report.first_degenerate_triangle, Some(0));
        }
    }

    // One element too few or too many: refused before anything is written.
    for extra in [-1isize, 1] {
        let count = (corner_count(&case) as isize + extra) as usize;
        let mut corners = vec![[UNTOUCHED; 4]; count];
        let result = generate_corners_into(
            &case.mesh(),
            &Options::default(),
            &mut StridedMut::from_slice(&mut corners),
            None,
            &mut Report::default(),
        );
        assert_eq!(result, Err(ErrorKind::LengthMismatch), "{count} corners");
        assert!(corners.iter().flatten().all(|&x| x == UNTOUCHED));
    }

    // Corners interleaved in one array with the positions they are computed from: refused.
    let mut shared = vec![0.0f32; 4 * corner_count(&case).max(case.vertex_count())];
    for (v, p) in case.positions.iter().enumerate() {
        shared[4 * v..4 * v + 3].copy_from_slice(p);
    }
    let before: Vec<u32> = shared.iter().map(|x| x.to_bits()).collect();
    let base = shared.as_mut_ptr().cast::<u8>();
    // SAFETY: both views lie inside `shared`, which outlives them; the library refuses the call
    // before it writes, so nothing is written through one view while the other reads.
    let (positions, mut corners) = unsafe {
        (
            Strided::<[f32; 3]>::from_raw(base, 16, case.vertex_count()),
            StridedMut::<[f32; 4]>::from_raw(base, 16, corner_count(&case)),
        )
    };
    let mesh = tbasis::Mesh {
        positions,
        normals: Strided::from_slice(&case.normals),
        texcoords: case.texcoords.as_deref().map(Strided::from_slice),
        indices: Indices::U32(Strided::from_slice(case.indices.as_ref().unwrap())),
    };
    let result = generate_corners_into(&mesh, &Options::default(), &mut corners, None, &mut Report::default());
    assert_eq!(result, Err(ErrorKind::Overlap));
    let after: Vec<u32> = shared.iter().map(|x| x.to_bits()).collect();
    assert!(after == before, "an overlapping call wrote");
}
