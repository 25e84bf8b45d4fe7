//! Every primitive of every mesh in the shared corpus (`../shared/meshes/`), under every policy.
//!
//! SKIP and INHERIT must succeed with outputs that pass the shared invariant checker; REJECT must
//! succeed exactly when the mesh has no degenerate triangle and otherwise write nothing; LEGACY
//! must not panic. The reports of the robust policies must agree with each other. The corpus is not
//! part of the repository: without it the test says it is skipped and passes, except under CI,
//! where it fails (`tbasis_test_support::needs`).

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

use tbasis::{DegeneratePolicy, ErrorKind, Report};
use tbasis_test_support::invariants::check_invariants;
use tbasis_test_support::load::{self, MeshFile, Primitive};
use tbasis_test_support::needs;
use tbasis_test_support::run::{run_mesh, Run};

/// One thing found wrong.
#[derive(Clone, Debug)]
struct Failure {
    /// Corpus path of the file.
    path: String,
    message: String,
}

/// Runs the library on one primitive; a panic becomes an `Err` naming it.
fn run(primitive: &Primitive, policy: DegeneratePolicy) -> Result<Run, String> {
    // The views hold raw pointers, so the closure is not UnwindSafe; nothing is reused after a panic.
    catch_unwind(AssertUnwindSafe(|| {
        run_mesh(&primitive.mesh(), primitive.vertex_count(), &primitive.options(policy))
    }))
    .map_err(|panic| {
        let message = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        format!("{policy:?} panicked: {message}")
    })
}

/// Everything that is wrong with one primitive; empty when all holds.
fn check_primitive(primitive: &Primitive) -> Result<Vec<String>, String> {
    let skip = run(primitive, DegeneratePolicy::Skip)?;
    let inherit = run(primitive, DegeneratePolicy::Inherit)?;
    let reject = run(primitive, DegeneratePolicy::Reject)?;
    let legacy = run(primitive, DegeneratePolicy::Legacy)?;
    let mut failures = Vec::new();
    // SKIP and INHERIT accept any mesh and keep every frame finite, unit and orthogonal; so does
    // REJECT when it accepts.
    for (name, run) in [("SKIP", &skip), ("INHERIT", &inherit), ("REJECT", &reject)] {
        if run.result.is_ok() {
            if let Err(e) = check_invariants(&primitive.normals, &run.tangents, Some(&run.bitangents)) {
                failures.push(format!("{name} invariants: {e}"));
            }
        }
    }
    let mut expect = |ok: bool, message: String| {
        if !ok {
            failures.push(message);
        }
    };
    for (name, run) in [("SKIP", &skip), ("INHERIT", &inherit)] {
        expect(run.result.is_ok(), format!("{name} failed: {:?}", run.result));
    }

    // Which triangles are degenerate, and which vertices mirrored or unused, is a property of the
    // mesh, not of the policy (LEGACY, which counts zero determinants only, aside).
    let facts = |r: &Report| {
        (
            r.degenerate_triangles,
            r.first_degenerate_triangle,
            r.mirrored_vertices,
            r.unreferenced_vertices,
        )
    };
    for (name, run) in [("INHERIT", &inherit), ("REJECT", &reject)] {
        expect(
            facts(&run.report) == facts(&skip.report),
            format!("{name} report {:?} disagrees with SKIP {:?}", run.report, skip.report),
        );
    }
    // INHERIT resolves some of the vertices SKIP falls back on, and no others.
    expect(
        skip.report.inherited_vertices == 0
            && inherit.report.inherited_vertices + inherit.report.fallback_vertices == skip.report.fallback_vertices,
        format!(
            "INHERIT {:?} does not split SKIP's fallbacks {:?}",
            inherit.report, skip.report
        ),
    );
    // Without texture coordinates nothing can be measured: every vertex falls back.
    if primitive.texcoords.is_none() {
        expect(
            skip.report.fallback_vertices == primitive.vertex_count() && skip.report.degenerate_triangles == 0,
            format!("no TEXCOORD_0, yet SKIP reports {:?}", skip.report),
        );
    }

    // REJECT succeeds exactly when no triangle is degenerate, and then does what SKIP does;
    // a refusal writes nothing.
    let degenerate = skip.report.degenerate_triangles;
    match reject.result {
        Ok(()) => {
            expect(
                degenerate == 0,
                format!("REJECT accepted {degenerate} degenerate triangles"),
            );
            expect(
                reject.report == skip.report
                    && reject.tangents == skip.tangents
                    && reject.bitangents == skip.bitangents,
                "REJECT on a clean mesh differs from SKIP".to_string(),
            );
        }
        Err(ErrorKind::DegenerateUv) => {
            expect(
                degenerate > 0,
                "REJECT refused a mesh without degenerate triangles".to_string(),
            );
            expect(reject.untouched(), "REJECT wrote output before refusing".to_string());
        }
        Err(e) => expect(false, format!("REJECT failed with {e:?}")),
    }

    // LEGACY only has to come back (no panic, which `run` caught); it needs texture coordinates.
    let legacy_ok = match (&legacy.result, &primitive.texcoords) {
        (Ok(()), Some(_)) => true,
        (Err(ErrorKind::MissingTexcoords), None) => legacy.untouched(),
        _ => false,
    };
    expect(legacy_ok, format!("LEGACY returned {:?}", legacy.result));
    Ok(failures)
}

/// Checks the file against its manifest row, then every primitive.
fn check_file(file: &MeshFile) -> Vec<Failure> {
    let row = &file.row;
    let mut found: Vec<String> = Vec::new();
    // The loader must see the mesh the manifest describes.
    if (file.vertex_count(), file.triangle_count()) != (row.vertices, row.triangles) {
        found.push(format!(
            "loaded {} vertices, {} triangles; the manifest says {}, {}",
            file.vertex_count(),
            file.triangle_count(),
            row.vertices,
            row.triangles
        ));
    }
    let has_stored = file.primitives.iter().any(|p| p.stored_tangents.is_some());
    if has_stored != (row.stored_tangents != "none") {
        found.push(format!(
            "stored tangents loaded: {has_stored}; manifest: {}",
            row.stored_tangents
        ));
    }
    for primitive in &file.primitives {
        match check_primitive(primitive) {
            Ok(messages) => found.extend(messages.into_iter().map(|m| format!("{}: {m}", primitive.name))),
            Err(panic) => found.push(format!("{}: {panic}", primitive.name)),
        }
    }
    found
        .into_iter()
        .map(|message| Failure {
            path: row.path.clone(),
            message,
        })
        .collect()
}

/// Loads and checks every file of the corpus, several at a time.
fn check_corpus() -> Vec<Failure> {
    let dir = load::corpus_dir().expect("the corpus");
    let started = Instant::now();
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get()).min(8);
    let (rows, found) = load::check_in_parallel(
        &dir,
        workers,
        |_| true,
        |row, file| match file {
            Ok(file) => check_file(&file),
            Err(message) => vec![Failure {
                path: row.path.clone(),
                message: format!("cannot load: {message}"),
            }],
        },
    );
    let mut failures: Vec<Failure> = found.into_iter().flatten().collect();
    failures.sort_by(|a, b| (&a.path, &a.message).cmp(&(&b.path, &b.message)));
    eprintln!(
        "{} corpus files x 4 policies checked in {:.1?}",
        rows.len(),
        started.elapsed()
    );
    failures
}

fn assert_none(failures: Vec<&Failure>) {
    let lines: Vec<String> = failures.iter().map(|f| format!("{}: {}", f.path, f.message)).collect();
    assert!(lines.is_empty(), "{} failures:\n{}", lines.len(), lines.join("\n"));
}

/// Every check on every file of the corpus.
#[test]
fn every_corpus_mesh_under_every_policy() {
    if !needs::CORPUS.found_or_skip() {
        return;
    }
    assert_none(check_corpus().iter().collect());
}
