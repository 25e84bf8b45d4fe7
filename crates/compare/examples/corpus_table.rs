//! Runs every policy on every mesh of the shared corpus (`../shared/meshes/`) and writes what the
//! reports say to `docs/corpus.md`, one table row per file and policy, summed over the file's
//! primitives.
//!
//! ```text
//! cargo run --release -p tbasis-compare --example corpus_table
//! ```

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use load::{MeshFile, Primitive};
use tbasis::{DegeneratePolicy, Report};
use tbasis_test_support::{load, run};

const POLICIES: [(DegeneratePolicy, &str); 4] = [
    (DegeneratePolicy::Skip, "SKIP"),
    (DegeneratePolicy::Inherit, "INHERIT"),
    (DegeneratePolicy::Reject, "REJECT"),
    (DegeneratePolicy::Legacy, "LEGACY"),
];

/// One file under one policy, summed over its primitives.
#[derive(Default)]
struct Totals {
    /// How many primitives ended with each error (absent: all succeeded).
    errors: BTreeMap<String, usize>,
    degenerate_triangles: usize,
    fallback_vertices: usize,
    inherited_vertices: usize,
    mirrored_vertices: usize,
    unreferenced_vertices: usize,
    /// Vertices written with a non-finite tangent component (only LEGACY can write one).
    non_finite_vertices: usize,
}

impl Totals {
    fn add(&mut self, result: Result<(), tbasis::ErrorKind>, report: &Report, non_finite: usize) {
        if let Err(error) = result {
            *self.errors.entry(format!("{error:?}")).or_default() += 1;
        }
        self.degenerate_triangles += report.degenerate_triangles;
        self.fallback_vertices += report.fallback_vertices;
        self.inherited_vertices += report.inherited_vertices;
        self.mirrored_vertices += report.mirrored_vertices;
        self.unreferenced_vertices += report.unreferenced_vertices;
        self.non_finite_vertices += non_finite;
    }

    fn status(&self, primitives: usize) -> String {
        if self.errors.is_empty() {
            return "ok".to_string();
        }
        let failures: Vec<String> = self
            .errors
            .iter()
            .map(|(error, count)| format!("{error} {count}/{primitives}"))
            .collect();
        failures.join(", ")
    }
}

/// Runs the library on one primitive; returns the result, the report (also filled when REJECT
/// refuses) and how many vertices got a non-finite tangent.
fn run(primitive: &Primitive, policy: DegeneratePolicy) -> (Result<(), tbasis::ErrorKind>, Report, usize) {
    let run = run::run_mesh(&primitive.mesh(), primitive.vertex_count(), &primitive.options(policy));
    // Nothing is written on failure, so only a successful call can leave non-finite tangents.
    let non_finite = match run.result {
        Ok(()) => run.tangents.iter().filter(|t| !t.iter().all(|x| x.is_finite())).count(),
        Err(_) => 0,
    };
    (run.result, run.report, non_finite)
}

fn table(files: &[MeshFile]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "| file | policy | vertices | triangles | status | degenerate_triangles | fallback_vertices \
         | inherited_vertices | mirrored_vertices | unreferenced_vertices | non-finite (LEGACY) |"
    );
    let _ = writeln!(out, "|---|---|--:|--:|---|--:|--:|--:|--:|--:|--:|");
    let mut grand: Vec<Totals> = POLICIES.iter().map(|_| Totals::default()).collect();
    for file in files {
        for (&policy, grand) in POLICIES.iter().zip(&mut grand) {
            let mut totals = Totals::default();
            for primitive in &file.primitives {
                let (result, report, non_finite) = run(primitive, policy.0);
                totals.add(result, &report, non_finite);
                grand.add(result, &report, non_finite);
            }
            let size = (file.vertex_count(), file.triangle_count(), file.primitives.len());
            write_row(&mut out, &file.row.path, policy, size, &totals);
        }
    }
    let size = (
        files.iter().map(MeshFile::vertex_count).sum(),
        files.iter().map(MeshFile::triangle_count).sum(),
        files.iter().map(|f| f.primitives.len()).sum(),
    );
    let label = format!("**all {} files**", files.len());
    for (&policy, totals) in POLICIES.iter().zip(&grand) {
        write_row(&mut out, &label, policy, size, totals);
    }
    out
}

/// One table row; `size` is (vertices, triangles, primitives).
fn write_row(
    out: &mut String,
    label: &str,
    (policy, name): (DegeneratePolicy, &str),
    (vertices, triangles, primitives): (usize, usize, usize),
    totals: &Totals,
) {
    // Only LEGACY may write non-finite tangents; the others' promise is checked by crates/tbasis/tests/corpus.rs.
    let non_finite = if policy == DegeneratePolicy::Legacy {
        totals.non_finite_vertices.to_string()
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "| {label} | {name} | {vertices} | {triangles} | {} | {} | {} | {} | {} | {} | {non_finite} |",
        totals.status(primitives),
        totals.degenerate_triangles,
        totals.fallback_vertices,
        totals.inherited_vertices,
        totals.mirrored_vertices,
        totals.unreferenced_vertices,
    );
}

/// The list items that depend on the corpus: which files lack normals or texture coordinates.
fn notes(files: &[MeshFile]) -> String {
    let listed = |keep: &dyn Fn(&Primitive) -> bool| {
        let paths: Vec<String> = files
            .iter()
            .filter(|f| f.primitives.iter().any(keep))
            .map(|f| format!("`{}`", f.row.path))
            .collect();
        paths.join(", ")
    };
    format!(
        "- Files with primitives without normals ({}) get area-weighted vertex normals computed by \
         the loader (`crates/test-support/src/load.rs`).\n\
         - Files with primitives without TEXCOORD_0 ({}): every vertex of those primitives falls \
         back under SKIP, INHERIT and REJECT; LEGACY refuses them.\n",
        listed(&|p| p.normals_computed),
        listed(&|p| p.texcoords.is_none()),
    )
}

const HEADER: &str = "\
# Corpus report

Regenerate with:

```sh
cargo run --release -p tbasis-compare --example corpus_table
```

Every mesh of the shared corpus (`../shared/meshes/`, see its `MANIFEST.tsv` and `README.md`),
run through `tbasis::generate` with each degenerate policy and the default threshold.
`flip_v` is set for glTF files (V stored downward) and not for OBJ.
One row per file and policy, summed over the file's primitives (glTF mesh primitives, OBJ models;
OBJ corners with distinct v/vt/vn tuples are distinct vertices).

- **status**: `ok` when every primitive succeeded, else each error with the number of primitives
  it ended (`DegenerateUv`: REJECT refused the primitive; `MissingTexcoords`: LEGACY needs texture
  coordinates and the primitive has no TEXCOORD_0).
- **degenerate_triangles** .. **unreferenced_vertices**: the `Report` fields. A refused or failed
  primitive contributes what its report holds: REJECT's refusal reports the degenerate, mirrored and
  unreferenced counts, writes nothing and so falls back nowhere. LEGACY counts only triangles with
  an exactly-zero UV determinant.
- **non-finite (LEGACY)**: vertices LEGACY wrote with an inf or NaN tangent component (the listing
  divides by a zero determinant and normalizes zero vectors); the other policies never do.
";

fn main() -> ExitCode {
    let Some(dir) = load::corpus_dir() else {
        eprintln!(
            "corpus_table: no mesh corpus at {}/../shared/meshes/ (MANIFEST.tsv missing)",
            env!("CARGO_MANIFEST_DIR")
        );
        return ExitCode::FAILURE;
    };
    let started = Instant::now();
    let loaded: Result<Vec<MeshFile>, String> =
        load::read_manifest(&dir).and_then(|rows| rows.iter().map(|row| load::load(&dir, row)).collect());
    let files = match loaded {
        Ok(files) => files,
        Err(error) => {
            eprintln!("corpus_table: {error}");
            return ExitCode::FAILURE;
        }
    };
    let load_time = started.elapsed();
    let started = Instant::now();
    let document = format!("{HEADER}{}\n{}", notes(&files), table(&files));
    let run_time = started.elapsed();

    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/corpus.md");
    if let Err(error) = std::fs::write(&path, document) {
        eprintln!("corpus_table: {}: {error}", path.display());
        return ExitCode::FAILURE;
    }
    eprintln!(
        "corpus_table: wrote {} ({} files; loading {:.2?}, 4 policies {:.2?})",
        path.display(),
        files.len(),
        load_time,
        run_time
    );
    ExitCode::SUCCESS
}
