//! Method MIKKTSPACE against mikktspace.c itself (the `mikktspace-sys` crate, which builds the
//! original C file with `cc`): for every corner `3t + k`, exactly the tangent and sign that
//! `genTangSpaceDefault` hands to `setTSpaceBasic(face t, vert k)` when its callbacks read the mesh
//! through its index buffer (`tbasis_test_support::mikktspace_reference`), `to_bits` on all four floats.
//!
//! NaN outputs match any NaN: mikktspace.c's own NaN payloads and signs depend on how it is
//! compiled (on `non_finite_scattered seed 2`, gcc 12 at -O0 and -O2 gives 0xffc00000 where -O3
//! passes the input's 0x7fc01234 through; cargo builds the C at -O0 for tests and at -O3 with
//! `--release`). Every other value, signed zeros included, must match bit for bit.
//!
//! Checked, with `flip_v` off and on (the reference then gets `v' = 1 - v` per vertex):
//! - every primitive with texture coordinates of every mesh in `../shared/meshes/` (raw V with
//!   `threads` 1, `flip_v` with 8);
//! - the stored TANGENT of the glTF files whose manifest marks it as MikkTSpace's (see
//!   [`stored_tangents_agree_with_flip_v`] for the comparison that holds, and why it is not bits);
//! - the stress scenes of `tbasis_test_support::mikktspace_scenes`, with `threads` 1, 2 and 8 (the
//!   largest ones with fewer runs, see [`LARGE_SCENES`]);
//! - random meshes drawn from small value sets (proptest), with `threads` 1 and 2;
//! - the per-vertex output (each vertex gets its first corner's frame; a vertex no triangle uses
//!   gets a finite unit frame, the fallback frame of its normal: [`an_unused_vertex_gets_the_fallback_frame`])
//!   and the report's `split_vertices` (vertices whose corners do not
//!   all have identical bits) and `unreferenced_vertices`, on both paths;
//! - caller scratch of `scratch_size_for` bytes at unaligned offsets, identical to allocating.
//!
//! Runtime of a debug build: about 60 s of CPU, half of it the corpus (mikktspace.c costs 9-17 us
//! per vertex there, this library's debug build about as much; `--release` is 4x faster), so about
//! 35 s on two idle cores. Debug builds skip corpus meshes above [`load::DEBUG_MAX_VERTICES`] (only
//! `FlightHelmet.cc1.glb`, 849k vertices) and say so; `cargo test --release -p tbasis --test mikktspace`
//! checks them too. Without the corpus the corpus tests are skipped, except under CI (`CI` set),
//! where they fail (`tbasis_test_support::needs`).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;
use std::time::Instant;

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::sample::select;
use proptest::test_runner::Config;
use tbasis::{generate_corners, scratch_size_for, Indices, Mesh, Options, Output, Report, Strided, StridedMut};
use tbasis_test_support::load::{self, ManifestRow, Primitive};
use tbasis_test_support::mikktspace_reference::reference_corners;
use tbasis_test_support::mikktspace_scenes::{self, IndexData, StressMesh};
use tbasis_test_support::needs;
use tbasis_test_support::run::{frame_with_bits, generate_corners_into, generate_into, UNTOUCHED};

/// Mismatching corners shown per mesh and run; the rest are counted.
const SHOWN: usize = 4;

/// Largest angle, in degrees, between our `flip_v` tangent and a stored `mikktspace-exact` one
/// (measured maximum 0.027 degrees, `25_anisotropy.gltf` mesh 17).
const STORED_ANGLE_DEG: f64 = 0.05;

// ---------------------------------------------------------------------------------------------
// Comparing with the reference

/// Equal bits, or both NaN (see the file's comment).
fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_frame(a: [f32; 4], b: [f32; 4]) -> bool {
    (0..4).all(|k| same(a[k], b[k]))
}

/// One mesh as both sides read it.
struct Subject<'a> {
    name: String,
    mesh: Mesh<'a>,
    positions: &'a [[f32; 3]],
    normals: &'a [[f32; 3]],
    texcoords: &'a [[f32; 2]],
    /// The index buffer widened to u32 (`None`: unindexed).
    indices: Option<Vec<u32>>,
    /// The vertex of every corner.
    corner_vertices: Vec<usize>,
}

impl<'a> Subject<'a> {
    fn of_stress(mesh: &'a StressMesh) -> Self {
        Subject {
            name: mesh.name.clone(),
            mesh: mesh.mesh(),
            positions: &mesh.positions,
            normals: &mesh.normals,
            texcoords: &mesh.texcoords,
            indices: mesh.indices_u32(),
            corner_vertices: mesh.corner_vertices(),
        }
    }

    /// `None` when the primitive has no texture coordinates (mikktspace.c needs them).
    fn of_primitive(path: &str, primitive: &'a Primitive) -> Option<Self> {
        Some(Subject {
            name: format!("{path} {}", primitive.name),
            mesh: primitive.mesh(),
            positions: &primitive.positions,
            normals: &primitive.normals,
            texcoords: primitive.texcoords.as_deref()?,
            indices: Some(primitive.indices.clone()),
            corner_vertices: primitive.indices.iter().map(|&v| v as usize).collect(),
        })
    }

    fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// mikktspace.c's corners; empty when it returns false, which it may only do without
    /// triangles.
    fn reference(&self, flip_v: bool) -> Result<Vec<[f32; 4]>, String> {
        match reference_corners(
            self.positions,
            self.normals,
            self.texcoords,
            self.indices.as_deref(),
            flip_v,
        ) {
            Some(corners) => Ok(corners),
            None if self.corner_vertices.is_empty() => Ok(Vec::new()),
            None => Err(format!(
                "{}: mikktspace.c returned false on {} corners",
                self.name,
                self.corner_vertices.len()
            )),
        }
    }

    /// The corner `c` in words: its triangle and vertex.
    fn corner(&self, c: usize) -> String {
        format!("corner {c} (triangle {} vertex {})", c / 3, self.corner_vertices[c])
    }

    /// Per vertex, its first corner (lowest corner index referencing it).
    fn first_corners(&self) -> Vec<Option<usize>> {
        let mut first = vec![None; self.vertex_count()];
        for (c, &v) in self.corner_vertices.iter().enumerate() {
            first[v].get_or_insert(c);
        }
        first
    }

    /// `split_vertices` and `unreferenced_vertices` as the report must give them for `corners`:
    /// vertices whose corners do not all have identical bits, and vertices without a corner.
    fn expected_counts(&self, corners: &[[f32; 4]]) -> (usize, usize) {
        let first = self.first_corners();
        let mut split = vec![false; self.vertex_count()];
        for (c, &v) in self.corner_vertices.iter().enumerate() {
            let f = first[v].expect("a referenced vertex has a first corner");
            split[v] |= corners[c].map(f32::to_bits) != corners[f].map(f32::to_bits);
        }
        let unreferenced = first.iter().filter(|f| f.is_none()).count();
        (split.iter().filter(|&&s| s).count(), unreferenced)
    }
}

/// `Options::mikktspace()` with `flip_v` and `threads`.
fn options(flip_v: bool, threads: u32) -> Options {
    Options::mikktspace().with_flip_v(flip_v).with_threads(threads)
}

/// Our per-corner frames and report.
fn our_corners(subject: &Subject, options: &Options) -> Result<(Vec<[f32; 4]>, Report), String> {
    let mut corners = vec![[UNTOUCHED; 4]; subject.corner_vertices.len()];
    let report = generate_corners(&subject.mesh, options, &mut StridedMut::from_slice(&mut corners))
        .map_err(|e| format!("generate_corners failed: {e:?}"))?;
    Ok((corners, report))
}

/// Our per-vertex frames and report.
fn our_vertices(subject: &Subject, options: &Options) -> Result<(Vec<[f32; 4]>, Report), String> {
    let mut tangents = vec![[UNTOUCHED; 4]; subject.vertex_count()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: None,
    };
    let report =
        tbasis::generate(&subject.mesh, options, &mut output).map_err(|e| format!("generate failed: {e:?}"))?;
    Ok((tangents, report))
}

/// Where `ours` differs from `reference`: the first few corners in full, then a count.
fn compare_corners(subject: &Subject, ours: &[[f32; 4]], reference: &[[f32; 4]]) -> Result<(), String> {
    assert_eq!(ours.len(), reference.len());
    let bad: Vec<usize> = (0..ours.len())
        .filter(|&c| !same_frame(ours[c], reference[c]))
        .collect();
    if bad.is_empty() {
        return Ok(());
    }
    let lines: Vec<String> = bad
        .iter()
        .take(SHOWN)
        .map(|&c| {
            format!(
                "{}: ours {} reference {}",
                subject.corner(c),
                frame_with_bits(ours[c]),
                frame_with_bits(reference[c])
            )
        })
        .collect();
    Err(format!(
        "{} of {} corners differ from mikktspace.c; {}",
        bad.len(),
        ours.len(),
        lines.join("; ")
    ))
}

/// The report's MIKKTSPACE counts against those of `corners`.
fn check_counts(subject: &Subject, corners: &[[f32; 4]], report: &Report) -> Result<(), String> {
    let (split, unreferenced) = subject.expected_counts(corners);
    if (report.split_vertices, report.unreferenced_vertices) != (split, unreferenced) {
        return Err(format!(
            "report has split_vertices {} and unreferenced_vertices {}; the corners give {split} and {unreferenced}",
            report.split_vertices, report.unreferenced_vertices
        ));
    }
    Ok(())
}

/// Per-vertex frames: each referenced vertex its first corner's frame (of the reference, and bit
/// for bit of our own corners); each unreferenced one a finite unit frame.
fn check_vertices(
    subject: &Subject,
    tangents: &[[f32; 4]],
    reference: &[[f32; 4]],
    our_corners: &[[f32; 4]],
) -> Result<(), String> {
    let mut bad = Vec::new();
    let mut count = 0;
    for (v, first) in subject.first_corners().into_iter().enumerate() {
        let t = tangents[v];
        let problem = match first {
            Some(c) if !same_frame(t, reference[c]) => Some(format!("reference {}", frame_with_bits(reference[c]))),
            Some(c) if t.map(f32::to_bits) != our_corners[c].map(f32::to_bits) => {
                Some(format!("our corner {c} {}", frame_with_bits(our_corners[c])))
            }
            Some(_) => None,
            None => {
                let length = t[..3].iter().map(|&x| f64::from(x) * f64::from(x)).sum::<f64>().sqrt();
                (!t.iter().all(|x| x.is_finite()) || (length - 1.0).abs() > 1e-5)
                    .then(|| "unreferenced: not a finite unit frame".to_string())
            }
        };
        if let Some(problem) = problem {
            count += 1;
            if bad.len() < SHOWN {
                bad.push(format!(
                    "vertex {v} (first corner {first:?}): ours {}, {problem}",
                    frame_with_bits(t)
                ));
            }
        }
    }
    if count == 0 {
        Ok(())
    } else {
        Err(format!(
            "{count} of {} vertices wrong; {}",
            tangents.len(),
            bad.join("; ")
        ))
    }
}

/// What to run for one `flip_v`.
#[derive(Clone, Copy)]
struct Runs {
    flip_v: bool,
    /// Thread counts of per-corner calls; all must give the same bits.
    corner_threads: &'static [u32],
    /// Thread counts of per-vertex calls.
    vertex_threads: &'static [u32],
}

/// Both `flip_v`, every thread count the contract names, both paths.
const EVERYTHING: [Runs; 2] = [
    Runs {
        flip_v: false,
        corner_threads: &[1, 2, 8],
        vertex_threads: &[1, 8],
    },
    Runs {
        flip_v: true,
        corner_threads: &[1, 2, 8],
        vertex_threads: &[1, 8],
    },
];

/// Everything wrong with `subject` under `runs`, and our corners of the last `flip_v` run.
fn check_subject(subject: &Subject, runs: &[Runs]) -> (Vec<String>, Option<Vec<[f32; 4]>>) {
    let mut failures = Vec::new();
    let mut last = None;
    for run in runs.iter().filter(|run| !run.corner_threads.is_empty()) {
        let reference = match subject.reference(run.flip_v) {
            Ok(reference) => reference,
            Err(e) => {
                failures.push(e);
                continue;
            }
        };
        let mut first: Option<Vec<[f32; 4]>> = None;
        for &threads in run.corner_threads {
            let what = format!("{} flip_v={} threads={threads} per corner", subject.name, run.flip_v);
            let (corners, report) = match our_corners(subject, &options(run.flip_v, threads)) {
                Ok(done) => done,
                Err(e) => {
                    failures.push(format!("{what}: {e}"));
                    continue;
                }
            };
            let results = [
                compare_corners(subject, &corners, &reference),
                check_counts(subject, &corners, &report),
                match &first {
                    Some(one) if bits(one) != bits(&corners) => {
                        Err(format!("bits differ from threads={}", run.corner_threads[0]))
                    }
                    _ => Ok(()),
                },
            ];
            failures.extend(
                results
                    .into_iter()
                    .filter_map(Result::err)
                    .map(|e| format!("{what}: {e}")),
            );
            first.get_or_insert(corners);
        }
        for &threads in run.vertex_threads {
            let what = format!("{} flip_v={} threads={threads} per vertex", subject.name, run.flip_v);
            let Some(corners) = &first else {
                failures.push(format!("{what}: not checked, no per-corner result"));
                continue;
            };
            match our_vertices(subject, &options(run.flip_v, threads)) {
                Ok((tangents, report)) => {
                    let results = [
                        check_vertices(subject, &tangents, &reference, corners),
                        check_counts(subject, corners, &report),
                    ];
                    failures.extend(
                        results
                            .into_iter()
                            .filter_map(Result::err)
                            .map(|e| format!("{what}: {e}")),
                    );
                }
                Err(e) => failures.push(format!("{what}: {e}")),
            }
        }
        last = first;
    }
    (failures, last)
}

fn bits(frames: &[[f32; 4]]) -> Vec<u32> {
    frames.iter().flatten().map(|x| x.to_bits()).collect()
}

fn assert_no_failures(what: &str, failures: &[String]) {
    assert!(
        failures.is_empty(),
        "{what}: {} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

// ---------------------------------------------------------------------------------------------
// The comparison itself

#[test]
fn the_comparison_catches_one_flipped_bit_and_matches_nan_with_nan() {
    let scene = mikktspace_scenes::polar_fan(8, 1.0, "fan");
    let subject = Subject::of_stress(&scene);
    let reference = subject.reference(false).unwrap();
    assert!(compare_corners(&subject, &reference, &reference).is_ok());
    let mut wrong = reference.clone();
    wrong[7][1] = f32::from_bits(wrong[7][1].to_bits() ^ 1);
    let message = compare_corners(&subject, &wrong, &reference).unwrap_err();
    assert!(message.starts_with("1 of 24 corners differ") && message.contains("corner 7 (triangle 2 vertex"));
    let zero = reference
        .iter()
        .flatten()
        .position(|&x| x == 0.0)
        .expect("a zero component");
    let mut signed_zero = reference.clone();
    signed_zero[zero / 4][zero % 4] = -signed_zero[zero / 4][zero % 4];
    assert!(compare_corners(&subject, &signed_zero, &reference).is_err());
    let mut nan = reference.clone();
    nan[0][0] = f32::NAN;
    let mut other_nan = reference;
    other_nan[0][0] = f32::from_bits(0xffc0_0000);
    assert!(compare_corners(&subject, &nan, &other_nan).is_ok());
}

#[test]
fn the_reference_reads_through_the_index_buffer_and_flips_v_per_vertex() {
    // mikktspace.c sees values, not indices: indexed, 16-bit and unindexed give the same corners.
    let scene = mikktspace_scenes::signed_zeros_grid(1, 3, true);
    let unindexed = scene.unindexed();
    for flip_v in [false, true] {
        let indexed = Subject::of_stress(&scene).reference(flip_v).unwrap();
        assert_eq!(
            bits(&indexed),
            bits(&Subject::of_stress(&unindexed).reference(flip_v).unwrap())
        );
        let mut flipped = scene.clone();
        flipped.texcoords.iter_mut().for_each(|uv| uv[1] = 1.0 - uv[1]);
        let by_hand = Subject::of_stress(&flipped).reference(false).unwrap();
        assert_eq!(flip_v, bits(&indexed) == bits(&by_hand), "flip_v={flip_v}");
    }
    // No triangles: mikktspace.c returns false and writes nothing.
    let empty = StressMesh {
        indices: IndexData::U32(Vec::new()),
        ..scene
    };
    assert_eq!(Subject::of_stress(&empty).reference(false), Ok(Vec::new()));
}

// ---------------------------------------------------------------------------------------------
// The corpus

/// What the corpus run found: per check, its failures.
#[derive(Default)]
struct CorpusOutcome {
    bit_exact: Vec<String>,
    stored: Vec<String>,
    /// Per file with stored MikkTSpace tangents, what was found (printed by the stored test).
    stored_notes: Vec<String>,
}

/// Loads and checks the corpus once per test process.
fn corpus_outcome() -> &'static CorpusOutcome {
    static OUTCOME: OnceLock<CorpusOutcome> = OnceLock::new();
    OUTCOME.get_or_init(check_corpus)
}

fn check_corpus() -> CorpusOutcome {
    let dir = load::corpus_dir().expect("the corpus");
    let started = Instant::now();
    let corners = AtomicUsize::new(0);
    let wanted = |row: &load::ManifestRow| !load::left_to_optimized_builds(row);
    let (rows, found) = load::check_in_parallel(&dir, 2, wanted, |row, file| match file {
        Ok(file) => check_corpus_file(row, &file.primitives, &corners),
        Err(e) => CorpusOutcome {
            bit_exact: vec![format!("{}: cannot load: {e}", row.path)],
            ..CorpusOutcome::default()
        },
    });
    let mut outcome = CorpusOutcome::default();
    for found in found {
        outcome.bit_exact.extend(found.bit_exact);
        outcome.stored.extend(found.stored);
        outcome.stored_notes.extend(found.stored_notes);
    }
    outcome.bit_exact.sort();
    outcome.stored.sort();
    outcome.stored_notes.sort();
    eprintln!(
        "{} corpus files, {} corners compared with mikktspace.c (raw V and flip_v) in {:.1?}",
        rows.len(),
        corners.into_inner(),
        started.elapsed()
    );
    outcome
}

/// Raw V with one thread, `flip_v` with eight: every corpus mesh meets the reference twice. The
/// per-vertex path and the other thread counts are checked on the stress scenes.
const CORPUS_RUNS: [Runs; 2] = [
    Runs {
        flip_v: false,
        corner_threads: &[1],
        vertex_threads: &[],
    },
    Runs {
        flip_v: true,
        corner_threads: &[8],
        vertex_threads: &[],
    },
];

fn check_corpus_file(row: &ManifestRow, primitives: &[Primitive], corners: &AtomicUsize) -> CorpusOutcome {
    let mut outcome = CorpusOutcome::default();
    for primitive in primitives {
        let Some(subject) = Subject::of_primitive(&row.path, primitive) else {
            continue;
        };
        let (failures, flipped) = check_subject(&subject, &CORPUS_RUNS);
        outcome.bit_exact.extend(failures);
        corners.fetch_add(2 * subject.corner_vertices.len(), Ordering::Relaxed);
        let stored = primitive.stored_tangents.as_deref();
        if let (true, Some(stored)) = (row.stored_tangents.starts_with("mikktspace"), stored) {
            match flipped {
                Some(ours) => {
                    let (failures, note) = check_stored(row, &subject, &ours, stored);
                    outcome.stored.extend(failures);
                    outcome.stored_notes.push(note);
                }
                None => outcome
                    .stored
                    .push(format!("{}: no flip_v result to compare", subject.name)),
            }
        }
    }
    outcome
}

/// Angle in degrees between two directions.
fn angle_deg(a: [f32; 4], b: [f32; 4]) -> f64 {
    let (a, b) = ([a[0], a[1], a[2]].map(f64::from), [b[0], b[1], b[2]].map(f64::from));
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let sine = cross.iter().map(|x| x * x).sum::<f64>().sqrt();
    sine.atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).to_degrees()
}

/// Our `flip_v` corners against the file's per-vertex TANGENT: `w` bit for bit on every corner
/// (`mikktspace-exact` and `mikktspace-near`), the direction within [`STORED_ANGLE_DEG`]
/// (`mikktspace-exact` only). The note says how many corners match in all bits, and which
/// vertices our corners split.
fn check_stored(row: &ManifestRow, subject: &Subject, ours: &[[f32; 4]], stored: &[[f32; 4]]) -> (Vec<String>, String) {
    let exact_file = row.stored_tangents == "mikktspace-exact";
    let (mut w_wrong, mut far, mut identical, mut max_angle) = (Vec::new(), Vec::new(), 0, 0.0f64);
    for (c, &v) in subject.corner_vertices.iter().enumerate() {
        let (t, s) = (ours[c], stored[v]);
        identical += usize::from(t.map(f32::to_bits) == s.map(f32::to_bits));
        if t[3].to_bits() != s[3].to_bits() {
            w_wrong.push(c);
        }
        let angle = angle_deg(t, s);
        max_angle = max_angle.max(if angle.is_nan() { 180.0 } else { angle });
        if exact_file && (angle.is_nan() || angle > STORED_ANGLE_DEG) {
            far.push(c);
        }
    }
    let (split, _) = subject.expected_counts(ours);
    let first = subject.first_corners();
    let mut split_list: Vec<usize> = subject
        .corner_vertices
        .iter()
        .enumerate()
        .filter(|&(c, &v)| first[v].is_some_and(|f| ours[c].map(f32::to_bits) != ours[f].map(f32::to_bits)))
        .map(|(_, &v)| v)
        .collect();
    split_list.sort_unstable();
    split_list.dedup();
    split_list.truncate(SHOWN);
    let note = format!(
        "{} ({}): {} corners, {identical} identical in all bits to the stored tangent, max angle {max_angle:.2e} deg, \
         {split} split vertices{}",
        subject.name,
        row.stored_tangents,
        ours.len(),
        if split > 0 {
            format!(" (first: {split_list:?})")
        } else {
            String::new()
        }
    );
    let mut failures = Vec::new();
    for (list, what) in [
        (&w_wrong, "w differs from the stored w".to_string()),
        (
            &far,
            format!("tangent more than {STORED_ANGLE_DEG} deg from the stored one"),
        ),
    ] {
        if let Some(&c) = list.first() {
            let v = subject.corner_vertices[c];
            failures.push(format!(
                "{}: {} of {} corners: {what}; first {}: ours {} stored {}",
                subject.name,
                list.len(),
                ours.len(),
                subject.corner(c),
                frame_with_bits(ours[c]),
                frame_with_bits(stored[v])
            ));
        }
    }
    (failures, note)
}

#[test]
fn every_corpus_mesh_matches_mikktspace_c() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let outcome = corpus_outcome();
    assert_no_failures("corpus against mikktspace.c", &outcome.bit_exact);
}

/// The files marked `mikktspace-exact` store, per vertex, MikkTSpace's tangent for `v' = 1 - v`,
/// but not mikktspace.c's bits: mikktspace.c itself reproduces them in all four floats on only
/// 1-30% of corners (NormalTangentTest 264 of 23,322; Blender's exporter ran its own port of
/// MikkTSpace, whose rounding differs, and turns tiny components into exact zeros). What holds on
/// every corner, for mikktspace.c as for this library: `w` is bit for bit the stored `w` (also on
/// the `mikktspace-near` files), and the direction is within [`STORED_ANGLE_DEG`] of the stored
/// one (on `mikktspace-exact` files; `mikktspace-near` ones differ by up to 180 degrees where their
/// exporter welded or re-split vertices). No vertex's corners split in those files.
#[test]
fn stored_tangents_agree_with_flip_v() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    let outcome = corpus_outcome();
    for note in &outcome.stored_notes {
        eprintln!("{note}");
    }
    assert!(
        !outcome.stored_notes.is_empty(),
        "no stored MikkTSpace tangents compared"
    );
    assert_no_failures("stored tangents", &outcome.stored);
}

// ---------------------------------------------------------------------------------------------
// Stress scenes

/// Stress scenes whose calls take over a second each in a debug build, with fewer runs: a test of
/// their own, so that they run beside the others. The large grid, which several workers split,
/// meets every thread count with raw V; `flip_v` and the other thread counts are checked on the
/// smaller scenes; the 1000-triangle fans are quadratic in mikktspace.c.
const LARGE_SCENES: [(&str, [Runs; 2]); 4] = [
    (
        "large_grid",
        [
            Runs {
                flip_v: false,
                corner_threads: &[1, 2, 8],
                vertex_threads: &[8],
            },
            NOTHING,
        ],
    ),
    ("quantized_uv_sphere", RAW_ONLY),
    ("polar_fan 1000 cone", RAW_ONLY),
    ("polar_fan 1000 disk", RAW_ONLY),
];

/// Not run.
const NOTHING: Runs = Runs {
    flip_v: true,
    corner_threads: &[],
    vertex_threads: &[],
};

/// Raw V only, one thread count per path.
const RAW_ONLY: [Runs; 2] = [
    Runs {
        flip_v: false,
        corner_threads: &[8],
        vertex_threads: &[2],
    },
    NOTHING,
];

fn check_scenes(large: bool) {
    let scenes: Vec<StressMesh> = mikktspace_scenes::all()
        .into_iter()
        .filter(|m| LARGE_SCENES.iter().any(|(name, _)| *name == m.name) == large)
        .collect();
    let mut failures = Vec::new();
    let mut corners = 0;
    for scene in &scenes {
        let subject = Subject::of_stress(scene);
        let runs = LARGE_SCENES
            .iter()
            .find(|(name, _)| *name == scene.name)
            .map_or(&EVERYTHING, |(_, runs)| runs);
        failures.extend(check_subject(&subject, runs).0);
        corners += scene.corner_count();
    }
    eprintln!("{} scenes, {corners} corners compared", scenes.len());
    assert_no_failures("stress scenes", &failures);
}

#[test]
fn stress_scenes_match_mikktspace_c() {
    check_scenes(false);
}

#[test]
fn large_stress_scenes_match_mikktspace_c() {
    let large = mikktspace_scenes::large_grid();
    assert!(large.vertex_count() >= 100_000, "{} vertices", large.vertex_count());
    check_scenes(true);
}

#[test]
fn the_scenes_reach_what_they_aim_at() {
    // Without these, the comparisons above would prove less than their names say.
    let scenes = mikktspace_scenes::all();
    let reference = |name: &str, flip_v: bool| {
        let scene = scenes.iter().find(|m| m.name == name).unwrap();
        let subject = Subject::of_stress(scene);
        let corners = subject.reference(flip_v).unwrap();
        let counts = subject.expected_counts(&corners);
        (corners, counts)
    };
    // Mirror seams split their vertices; the random soup too.
    assert!(reference("mirror_fold", false).1 .0 > 0);
    assert!(reference("random_soup 1000", false).1 .0 > 0);
    // Fans: opposite triangles' tangents are exactly antiparallel, so their cosine is exactly -1,
    // not above mikktspace.c's threshold cos(180 deg) = -1: at the apex each triangle's sub-group
    // leaves its opposite out, and the apex corners come out exact opposites.
    let (fan, _) = reference("polar_fan 4 disk", false);
    for k in 0..2 {
        let (a, b) = (fan[3 * k], fan[3 * (k + 2)]);
        assert!((0..3).all(|i| a[i] == -b[i]), "apex corners {a:?} {b:?}");
    }
    // Signed zeros: mikktspace.c welds copies that differ only in the signs of zeros, never writes
    // -0.0 (its sums start at +0.0f, and +0 + -0 = +0) and gives the same bits when every zero of
    // the input is made +0.0; an exact implementation must wash the signs out the same way.
    for name in ["signed_zeros lifted seed 1 copies 3", "signed_zero_origin_patterns"] {
        let scene = scenes.iter().find(|m| m.name == name).unwrap();
        let mut positive = scene.clone();
        let plus = |x: &mut f32| *x = if *x == 0.0 { 0.0 } else { *x };
        positive.positions.iter_mut().flatten().for_each(plus);
        positive.normals.iter_mut().flatten().for_each(plus);
        positive.texcoords.iter_mut().flatten().for_each(plus);
        let negative_zero = |x: &f32| x.to_bits() == 0x8000_0000;
        assert!(
            scene.positions.iter().flatten().any(negative_zero),
            "{name} has no -0.0 position"
        );
        assert!(
            scene.texcoords.iter().flatten().any(negative_zero),
            "{name} has no -0.0 UV"
        );
        let (corners, _) = reference(name, false);
        assert!(
            corners.iter().flatten().all(|x| x.to_bits() != 0x8000_0000),
            "{name}: -0.0"
        );
        let plain = Subject::of_stress(&positive).reference(false).unwrap();
        assert_eq!(bits(&corners), bits(&plain), "{name}");
    }
    // Non-finite inputs give NaN outputs.
    assert!(reference("non_finite_scattered seed 2", false)
        .0
        .iter()
        .flatten()
        .any(|x| x.is_nan()));
    // Unreferenced vertices are counted.
    assert_eq!(reference("unreferenced_vertices", false).1 .1, 3);
}

// ---------------------------------------------------------------------------------------------
// Caller scratch

#[test]
fn caller_scratch_at_any_offset_gives_the_allocating_results() {
    let scenes = [
        mikktspace_scenes::all()
            .into_iter()
            .find(|m| m.name == "quantised_torus")
            .unwrap(),
        mikktspace_scenes::signed_zeros_grid(1, 3, true),
        mikktspace_scenes::butterfly(4, true).unindexed(),
        mikktspace_scenes::polar_fan(64, 1.0, "fan").with_u16_indices(),
    ];
    let mut failures = Vec::new();
    for scene in &scenes {
        let subject = Subject::of_stress(scene);
        for threads in [1, 2] {
            let options = options(true, threads);
            let what = format!("{} threads={threads}", scene.name);
            // The allocating calls must themselves be right.
            let (corners, corner_report) = match our_corners(&subject, &options) {
                Ok(done) => done,
                Err(e) => {
                    failures.push(format!("{what}: {e}"));
                    continue;
                }
            };
            let reference = subject.reference(true).unwrap();
            if let Err(e) = compare_corners(&subject, &corners, &reference) {
                failures.push(format!("{what}: allocating call: {e}"));
            }
            let (vertices, vertex_report) = match our_vertices(&subject, &options) {
                Ok(done) => done,
                Err(e) => {
                    failures.push(format!("{what}: {e}"));
                    continue;
                }
            };
            let size = scratch_size_for(&subject.mesh, &options).expect("scratch size");
            for offset in [0, 1, 2, 3, 5, 7, 13] {
                let mut bytes = vec![0xA5u8; size + offset];
                let scratch = &mut bytes[offset..];

                let mut with_scratch = vec![[UNTOUCHED; 4]; corners.len()];
                let mut report = Report::default();
                let result = generate_corners_into(
                    &subject.mesh,
                    &options,
                    &mut StridedMut::from_slice(&mut with_scratch),
                    Some(&mut *scratch),
                    &mut report,
                );
                if result.is_err() || report != corner_report || bits(&with_scratch) != bits(&corners) {
                    failures.push(format!(
                        "{what}: per corner with {size} bytes of scratch at offset {offset}: {result:?}, report {report:?} \
                         (allocating: {corner_report:?}), same bits: {}",
                        bits(&with_scratch) == bits(&corners)
                    ));
                }

                let mut tangents = vec![[UNTOUCHED; 4]; vertices.len()];
                let mut report = Report::default();
                let mut output = Output {
                    tangents: StridedMut::from_slice(&mut tangents),
                    bitangents: None,
                };
                let result = generate_into(&subject.mesh, &options, &mut output, Some(scratch), &mut report);
                if result.is_err() || report != vertex_report || bits(&tangents) != bits(&vertices) {
                    failures.push(format!(
                        "{what}: per vertex with {size} bytes of scratch at offset {offset}: {result:?}, report {report:?} \
                         (allocating: {vertex_report:?}), same bits: {}",
                        bits(&tangents) == bits(&vertices)
                    ));
                }
            }
        }
    }
    assert_no_failures("caller scratch", &failures);
}

// ---------------------------------------------------------------------------------------------
// Random meshes

/// Component values: few, so that equal positions, welds, signed zeros and degenerate triangles
/// are common.
const POSITION_VALUES: [f32; 8] = [0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-3, -3.0];
const NORMAL_VALUES: [f32; 7] = [0.0, -0.0, 1.0, -1.0, 0.6, 0.8, -0.6];
const UV_VALUES: [f32; 7] = [0.0, -0.0, 0.25, 0.5, 1.0, -0.5, 0.75];
/// Mixed in now and then.
const SPECIAL_VALUES: [f32; 7] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e38, -3e38, 1e-40, -1e-45];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum IndexKind {
    None,
    U16,
    U32,
}

#[derive(Clone, Debug)]
struct RandomMesh {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    kind: IndexKind,
    indices: Vec<u32>,
    flip_v: bool,
}

/// One component: from `values`, or with `specials` now and then from [`SPECIAL_VALUES`].
fn component(values: &'static [f32], specials: bool) -> BoxedStrategy<f32> {
    if specials {
        prop_oneof![12 => select(values), 1 => select(&SPECIAL_VALUES[..])].boxed()
    } else {
        select(values).boxed()
    }
}

prop_compose! {
    /// A vertex pool of up to 40 prototypes; every vertex is a prototype with the signs of its
    /// zeros drawn anew, so that vertices equal under `==` but not in bits are common.
    fn random_mesh()(
        specials in prop::bool::weighted(0.25),
        pool in 1usize..=40,
        vertices in 1usize..=300,
        triangles in 0usize..=200,
        kind in select(vec![IndexKind::None, IndexKind::U16, IndexKind::U32]),
        flip_v in any::<bool>(),
    )(
        positions in vec([0; 3].map(|_| component(&POSITION_VALUES, specials)), pool),
        normals in vec([0; 3].map(|_| component(&NORMAL_VALUES, specials)), pool),
        texcoords in vec([0; 2].map(|_| component(&UV_VALUES, specials)), pool),
        picks in vec((0..pool, any::<u8>()), if kind == IndexKind::None { 3 * triangles } else { vertices }),
        indices in vec(0..vertices as u32, if kind == IndexKind::None { 0 } else { 3 * triangles }),
        kind in Just(kind),
        flip_v in Just(flip_v),
    ) -> RandomMesh {
        let sign = |x: f32, flip: bool| if x == 0.0 && flip { -x } else { x };
        RandomMesh {
            positions: picks.iter().map(|&(p, s)| [0, 1, 2].map(|k| sign(positions[p][k], s >> k & 1 == 1))).collect(),
            normals: picks.iter().map(|&(p, s)| [0, 1, 2].map(|k| sign(normals[p][k], s >> (k + 3) & 1 == 1))).collect(),
            texcoords: picks.iter().map(|&(p, s)| [0, 1].map(|k| sign(texcoords[p][k], s >> (k + 6) & 1 == 1))).collect(),
            kind,
            indices,
            flip_v,
        }
    }
}

fn check_random(m: &RandomMesh) -> Result<(), String> {
    let narrow: Vec<u16> = m.indices.iter().map(|&i| i as u16).collect();
    let mesh = Mesh {
        positions: Strided::from_slice(&m.positions),
        normals: Strided::from_slice(&m.normals),
        texcoords: Some(Strided::from_slice(&m.texcoords)),
        indices: match m.kind {
            IndexKind::None => Indices::None,
            IndexKind::U16 => Indices::U16(Strided::from_slice(&narrow)),
            IndexKind::U32 => Indices::U32(Strided::from_slice(&m.indices)),
        },
    };
    let indexed = m.kind != IndexKind::None;
    let subject = Subject {
        name: "random mesh".into(),
        mesh,
        positions: &m.positions,
        normals: &m.normals,
        texcoords: &m.texcoords,
        indices: indexed.then(|| m.indices.clone()),
        corner_vertices: if indexed {
            m.indices.iter().map(|&i| i as usize).collect()
        } else {
            (0..m.positions.len()).collect()
        },
    };
    let runs = [Runs {
        flip_v: m.flip_v,
        corner_threads: &[1, 2],
        vertex_threads: &[1],
    }];
    let (failures, _) = check_subject(&subject, &runs);
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failures.join("\n"))
    }
}

fn config(cases: u32) -> Config {
    tbasis_test_support::proptest_config::fixed(cases, 0x6d69_6b6b)
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn random_meshes_match_mikktspace_c(m in random_mesh()) {
        check_random(&m).map_err(TestCaseError::fail)?;
    }
}

/// README ("MikkTSpace"): a vertex no triangle uses gets the fallback frame, the one every method
/// builds from a normal alone (here: policy SKIP without texture coordinates), in normals of every
/// direction, the one straight down and a zero one included.
#[test]
fn an_unused_vertex_gets_the_fallback_frame() {
    let s = 1.0 / 14f32.sqrt();
    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 2.0, 2.0f32]];
    let texcoords = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.5f32]];
    for unused_normal in [
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [s, 2.0 * s, -3.0 * s],
        [0.0, 0.0, 0.0f32],
    ] {
        let normals = [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0], unused_normal];
        let indices = [0u32, 1, 2];
        let mesh = Mesh::new(&positions[..], &normals[..]).with_indices(&indices[..]);
        let mut fallback = [[0.0f32; 4]; 4];
        let alone = Options::default().with_policy(tbasis::DegeneratePolicy::Skip);
        tbasis::generate(&mesh, &alone, &mut Output::new(&mut fallback[..])).unwrap();
        for options in [
            Options::mikktspace(),
            Options::mikktspace().with_policy(tbasis::DegeneratePolicy::Skip),
        ] {
            let mut tangents = [[0.0f32; 4]; 4];
            let with_uvs = mesh.with_texcoords(&texcoords[..]);
            let report = tbasis::generate(&with_uvs, &options, &mut Output::new(&mut tangents[..])).unwrap();
            let what = format!("normal {unused_normal:?}, {:?}", options.degenerate_policy);
            assert_eq!(
                (report.unreferenced_vertices, report.fallback_vertices),
                (1, 1),
                "{what}"
            );
            assert_eq!(tangents[3].map(f32::to_bits), fallback[3].map(f32::to_bits), "{what}");
            assert_eq!(tangents[3][3], 1.0, "{what}: w");
        }
    }
}
