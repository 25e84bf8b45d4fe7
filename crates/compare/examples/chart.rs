//! Speed against accuracy: every method of this library and its peers on the analytic scenes of
//! `crates/test-support/src/scenes.rs`, from about 500 to 1M vertices; then agreement with the MikkTSpace
//! tangents stored in the real meshes of `../shared/meshes/` (skipped when it is absent).
//!
//! ```text
//! cargo run --release -p tbasis-compare --example chart
//! ```
//!
//! Writes `docs/chart.csv` (every scene, size and method), `docs/chart.svg` (ns per vertex against
//! mean angular error on the torus) and `docs/chart.md` (tables). Both mark each size's Pareto
//! front of time against mean error (`tbasis_compare::pareto`), and the tables list each peer with
//! the methods of this library that dominate it. `--max-vertices N` runs only the sizes up to N and
//! writes to `target/chart/` instead, for a quick look.
//!
//! Peers: the original listing (its C port, `c_tests/listing.c`, linked by `build.rs`),
//! meshoptimizer's `meshopt_generateTangents` (the `meshopt` crate; default and MikkTSpace-compatible
//! modes), mikktspace.c (`mikktspace-sys`, through `crates/test-support/src/mikktspace_reference.rs`) and
//! `bevy_mikktspace`. Every generator runs on the calling thread; the time is the median of several
//! runs of the generating call alone. meshoptimizer and MikkTSpace write one tangent per triangle
//! corner: each vertex takes the tangent of the first corner that references it, as this library's
//! method MIKKTSPACE does in its per-vertex call, so its errors must equal mikktspace.c's exactly
//! (the run stops otherwise). MikkTSpace reads the mesh as unindexed triangles, built from the
//! indexed mesh before timing.

#[path = "../../../c_tests/listing.rs"]
mod listing;
#[path = "common/machine.rs"]
mod machine;
#[path = "common/meshopt_tangents.rs"]
mod meshopt_tangents;

use std::collections::HashMap;
use std::fmt::Write as _;
use std::fs;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use listing::listing_tangents;
use machine::{load_average, machine};
use meshopt::TangentOptions;
use meshopt_tangents::meshopt_tangents;
use scenes::{Accuracy, Scene, SceneSpec};
use tbasis::{generate, DegeneratePolicy, Indices, Mesh, Method, Options, Output, Strided, StridedMut};
use tbasis_compare::pareto::{self, Point};
use tbasis_test_support::{load, mikktspace_reference, scenes};

/// Who computes the tangents.
#[derive(Clone, Copy, PartialEq)]
enum Generator {
    Library(Options),
    Listing,
    Meshopt(TangentOptions),
    MikktspaceC,
    BevyMikktspace,
}

impl Generator {
    /// MikkTSpace takes seconds per million vertices: it gets fewer repetitions. This library's
    /// method MIKKTSPACE, under half a second there, gets as many as the others: its calls fault in
    /// hundreds of megabytes of fresh memory, which scatters their times (with three, the median
    /// on the 1M-vertex mirrored torus went from 812 to 1,398 ns per vertex between two runs).
    fn slow(&self) -> bool {
        match self {
            Generator::MikktspaceC | Generator::BevyMikktspace => true,
            Generator::Library(_) | Generator::Listing | Generator::Meshopt(_) => false,
        }
    }

    /// This library, rather than a peer.
    fn library(&self) -> bool {
        matches!(self, Generator::Library(_))
    }
}

struct Entry {
    name: String,
    generator: Generator,
}

/// The earlier entry that makes the same call as the one named `name` (the default repeats one of
/// the methods), if any: its time differs from its twin's by noise alone, so the Pareto
/// comparison leaves it out.
fn twin_of<'a>(entries: &'a [Entry], name: &str) -> Option<&'a Entry> {
    let k = entries.iter().position(|e| e.name == name)?;
    entries[..k].iter().find(|e| e.generator == entries[k].generator)
}

/// Whether the entry named `name` is a peer (not this library).
fn is_peer(entries: &[Entry], name: &str) -> bool {
    entries
        .iter()
        .find(|e| e.name == name)
        .is_some_and(|e| !e.generator.library())
}

fn entries() -> Vec<Entry> {
    let entry = |name: &str, generator: Generator| Entry {
        name: name.to_string(),
        generator,
    };
    let library = |method: Method, policy: DegeneratePolicy| {
        Generator::Library(Options::default().with_method(method).with_policy(policy))
    };
    // The default is whatever Options::default() says today; the name shows what that is.
    let defaults = Options::default();
    let default_name = format!(
        "tbasis default ({}+{})",
        format!("{:?}", defaults.method).to_uppercase(),
        format!("{:?}", defaults.degenerate_policy).to_uppercase()
    );
    vec![
        entry(
            "tbasis LENGYEL+LEGACY",
            library(Method::Lengyel, DegeneratePolicy::Legacy),
        ),
        entry("tbasis LENGYEL", library(Method::Lengyel, DegeneratePolicy::Inherit)),
        entry("tbasis ANGLE", library(Method::Angle, DegeneratePolicy::Inherit)),
        entry("tbasis AREA", library(Method::Area, DegeneratePolicy::Inherit)),
        entry("tbasis UNIFORM", library(Method::Uniform, DegeneratePolicy::Inherit)),
        entry(MIKKTSPACE, Generator::Library(Options::mikktspace())),
        entry(&default_name, Generator::Library(defaults)),
        entry("listing.c", Generator::Listing),
        entry("meshopt", Generator::Meshopt(TangentOptions::None)),
        entry("meshopt compatible", Generator::Meshopt(TangentOptions::Compatible)),
        entry(MIKKTSPACE_C, Generator::MikktspaceC),
        entry("bevy_mikktspace", Generator::BevyMikktspace),
    ]
}

/// The entry of method MIKKTSPACE, and the one whose errors it must equal.
const MIKKTSPACE: &str = "tbasis MIKKTSPACE";
const MIKKTSPACE_C: &str = "mikktspace.c";

/// A mesh as every generator reads it. `texcoords` have V up; `library_texcoords` and `flip_v` are
/// what the library gets (a glTF file's own V-down coordinates with `flip_v`, or the same).
struct Input<'a> {
    positions: &'a [[f32; 3]],
    normals: &'a [[f32; 3]],
    texcoords: &'a [[f32; 2]],
    library_texcoords: &'a [[f32; 2]],
    flip_v: bool,
    indices: &'a [u32],
}

/// The same mesh as unindexed triangles, for MikkTSpace.
struct Corners {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
}

impl Corners {
    fn of(input: &Input) -> Self {
        let gather = |k: usize| input.indices[k] as usize;
        let corners = 0..input.indices.len();
        Corners {
            positions: corners.clone().map(|k| input.positions[gather(k)]).collect(),
            normals: corners.clone().map(|k| input.normals[gather(k)]).collect(),
            texcoords: corners.map(|k| input.texcoords[gather(k)]).collect(),
        }
    }
}

/// bevy_mikktspace's view of the same.
struct MikkBevy<'a> {
    corners: &'a Corners,
    result: &'a mut [[f32; 4]],
}

impl bevy_mikktspace::Geometry for MikkBevy<'_> {
    fn num_faces(&self) -> usize {
        self.corners.positions.len() / 3
    }
    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }
    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.corners.positions[3 * face + vert]
    }
    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.corners.normals[3 * face + vert]
    }
    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.corners.texcoords[3 * face + vert]
    }
    fn set_tangent(&mut self, tangent_space: Option<bevy_mikktspace::TangentSpace>, face: usize, vert: usize) {
        // None: no tangent could be had; mikktspace.c writes its default frame then.
        self.result[3 * face + vert] = tangent_space.unwrap_or_default().tangent_encoded();
    }
}

/// Per-corner results to per-vertex ones: the first corner referencing each vertex wins.
fn first_corner(indices: &[u32], per_corner: &[[f32; 4]], vertex_count: usize) -> Vec<[f32; 4]> {
    let mut result = vec![[0.0, 0.0, 0.0, 1.0]; vertex_count];
    let mut seen = vec![false; vertex_count];
    for (&v, t) in indices.iter().zip(per_corner) {
        let v = v as usize;
        if !seen[v] {
            seen[v] = true;
            result[v] = *t;
        }
    }
    result
}

/// How many times to run: enough for about `BUDGET` in all, at least 3 for MikkTSpace (seconds a
/// run at 1M vertices) and 9 for the others (large meshes allocate and fault in fresh scratch pages
/// on every call, which scatters single runs), at most 1001 (small meshes run in microseconds, so
/// many runs steady the median).
const BUDGET: Duration = Duration::from_millis(500);

fn repetitions(first_run: Duration, slow: bool) -> usize {
    let wanted = (BUDGET.as_secs_f64() / first_run.as_secs_f64().max(1e-9)) as usize;
    wanted.clamp(if slow { 3 } else { 9 }, 1001)
}

/// How often to run a generator: repeatedly for its time, or once for its result only.
#[derive(Clone, Copy, PartialEq)]
enum Timing {
    Median { slow: bool },
    Once,
}

/// Runs `body` and returns its last result and the median time of one run.
fn timed<R>(timing: Timing, mut body: impl FnMut() -> R) -> (R, Duration) {
    let start = Instant::now();
    let mut result = black_box(body());
    let mut times = vec![start.elapsed()];
    let runs = match timing {
        Timing::Median { slow } => repetitions(times[0], slow),
        Timing::Once => 1,
    };
    for _ in 1..runs {
        let start = Instant::now();
        result = black_box(body());
        times.push(start.elapsed());
    }
    times.sort();
    (result, times[times.len() / 2])
}

/// Runs one generator on one mesh: per-vertex tangents and the median time of the call (`time`:
/// false runs it once, for its result only).
fn run(generator: Generator, input: &Input, corners: &Corners, time: bool) -> (Vec<[f32; 4]>, Duration) {
    let vertex_count = input.positions.len();
    let timing = if time {
        Timing::Median { slow: generator.slow() }
    } else {
        Timing::Once
    };
    match generator {
        Generator::Library(options) => {
            // One thread, like every peer, whatever the default becomes.
            let options = options.with_flip_v(input.flip_v).with_threads(1);
            let mesh = Mesh {
                positions: Strided::from_slice(input.positions),
                normals: Strided::from_slice(input.normals),
                texcoords: Some(Strided::from_slice(input.library_texcoords)),
                indices: Indices::U32(Strided::from_slice(input.indices)),
            };
            let mut tangents = vec![[0.0f32; 4]; vertex_count];
            let (_, time) = timed(timing, || {
                let mut output = Output {
                    tangents: StridedMut::from_slice(&mut tangents),
                    bitangents: None,
                };
                generate(&mesh, &options, &mut output).expect("the library refused a corpus or scene mesh")
            });
            (tangents, time)
        }
        Generator::Listing => {
            let mut tangents = vec![[0.0f32; 4]; vertex_count];
            // SAFETY: scenes.rs keeps every index below the vertex count.
            let (_, time) = timed(timing, || unsafe {
                listing_tangents(
                    input.positions,
                    input.normals,
                    input.texcoords,
                    input.indices,
                    &mut tangents,
                );
            });
            (tangents, time)
        }
        Generator::Meshopt(options) => {
            let mut per_corner = vec![[0.0f32; 4]; input.indices.len()];
            // SAFETY: scenes.rs and load.rs keep every index below the vertex count.
            let (_, time) = timed(timing, || unsafe {
                meshopt_tangents(
                    input.indices,
                    input.positions,
                    input.normals,
                    input.texcoords,
                    options,
                    &mut per_corner,
                );
            });
            (first_corner(input.indices, &per_corner, vertex_count), time)
        }
        Generator::MikktspaceC => {
            let mut per_corner = vec![[0.0f32; 4]; input.indices.len()];
            // The gathered corners, unindexed, as the shared reference wrapper reads them.
            let geometry = mikktspace_reference::Geometry {
                positions: &corners.positions,
                normals: &corners.normals,
                texcoords: &corners.texcoords,
                indices: None,
            };
            let (_, time) = timed(timing, || {
                assert!(mikktspace_reference::generate(geometry, &mut per_corner));
            });
            (first_corner(input.indices, &per_corner, vertex_count), time)
        }
        Generator::BevyMikktspace => {
            let mut per_corner = vec![[0.0f32; 4]; input.indices.len()];
            let (_, time) = timed(timing, || {
                let mut geometry = MikkBevy {
                    corners,
                    result: &mut per_corner,
                };
                bevy_mikktspace::generate_tangents(&mut geometry).expect("bevy_mikktspace");
            });
            (first_corner(input.indices, &per_corner, vertex_count), time)
        }
    }
}

/// One measured point.
struct Row {
    scene: String,
    vertices: usize,
    method: String,
    ns_per_vertex: f64,
    accuracy: Accuracy,
}

impl Row {
    fn point(&self) -> Point {
        Point {
            ns_per_vertex: self.ns_per_vertex,
            mean_error_deg: self.accuracy.mean_deg,
        }
    }
}

/// The rows of one scene and size that the Pareto comparison takes (all but twins), in entry
/// order, and whether each is on the front.
struct Compared<'a> {
    rows: Vec<&'a Row>,
    points: Vec<Point>,
    on_front: Vec<bool>,
}

impl<'a> Compared<'a> {
    fn of(rows: &'a [Row], entries: &[Entry], scene: &str, vertices: usize) -> Self {
        let rows: Vec<&Row> = rows
            .iter()
            .filter(|r| r.scene == scene && r.vertices == vertices && twin_of(entries, &r.method).is_none())
            .collect();
        let points: Vec<Point> = rows.iter().map(|r| r.point()).collect();
        let on_front = pareto::front(&points);
        Compared { rows, points, on_front }
    }

    /// Whether the method named `method` is on the front; `None` when it is not compared.
    fn on_front(&self, method: &str) -> Option<bool> {
        let k = self.rows.iter().position(|r| r.method == method)?;
        Some(self.on_front[k])
    }

    /// The rows on the front, fastest first: the corners of the front's staircase.
    fn front(&self) -> Vec<&'a Row> {
        let mut front: Vec<&Row> = self
            .rows
            .iter()
            .zip(&self.on_front)
            .filter(|(_, &on)| on)
            .map(|(r, _)| *r)
            .collect();
        front.sort_by(|a, b| a.ns_per_vertex.total_cmp(&b.ns_per_vertex));
        front
    }

    /// Each peer, with the methods of this library that dominate it.
    fn dominated_peers(&self, entries: &[Entry]) -> Vec<(&'a str, Vec<&'a str>)> {
        (0..self.rows.len())
            .filter(|&k| is_peer(entries, &self.rows[k].method))
            .map(|k| {
                let by = pareto::dominators(&self.points, k)
                    .into_iter()
                    .map(|d| self.rows[d].method.as_str())
                    .filter(|&name| !is_peer(entries, name))
                    .collect();
                (self.rows[k].method.as_str(), by)
            })
            .collect()
    }
}

/// Measures every entry on `scene`; returns how many vertices of LENGYEL+LEGACY differ in any bit
/// from listing.c (the library promises none). Stops the run when the errors of method MIKKTSPACE
/// are not exactly mikktspace.c's.
fn measure_scene(scene: &Scene, entries: &[Entry], rows: &mut Vec<Row>) -> usize {
    let input = Input {
        positions: &scene.positions,
        normals: &scene.normals,
        texcoords: &scene.texcoords,
        library_texcoords: &scene.texcoords,
        flip_v: false,
        indices: &scene.indices,
    };
    let corners = Corners::of(&input);
    let (mut legacy, mut listing) = (None, None);
    for entry in entries {
        let (tangents, time) = run(entry.generator, &input, &corners, true);
        let accuracy = scenes::accuracy(scene, &tangents);
        let ns_per_vertex = time.as_secs_f64() * 1e9 / scene.vertex_count() as f64;
        println!(
            "{:<15} {:>8} {:<30} {:>9.1} ns/v  mean {:.5}  p99 {:.5}  max {:.4}  wrong w {:.4}",
            scene.name,
            scene.vertex_count(),
            entry.name,
            ns_per_vertex,
            accuracy.mean_deg,
            accuracy.p99_deg,
            accuracy.max_deg,
            accuracy.wrong_handedness_share()
        );
        rows.push(Row {
            scene: scene.name.clone(),
            vertices: scene.vertex_count(),
            method: entry.name.clone(),
            ns_per_vertex,
            accuracy,
        });
        match entry.generator {
            Generator::Library(o) if o == Options::legacy() => legacy = Some(tangents),
            Generator::Listing => listing = Some(tangents),
            _ => {}
        }
    }
    let errors = |name: &str| {
        rows.iter()
            .rev()
            .find(|r| r.scene == scene.name && r.vertices == scene.vertex_count() && r.method == name)
            .map(|r| error_bits(&r.accuracy))
    };
    assert_eq!(
        errors(MIKKTSPACE),
        errors(MIKKTSPACE_C),
        "{} {}: the errors of {MIKKTSPACE} and {MIKKTSPACE_C} differ",
        scene.name,
        scene.vertex_count()
    );
    match (legacy, listing) {
        (Some(a), Some(b)) => a
            .iter()
            .zip(&b)
            .filter(|(x, y)| x.map(f32::to_bits) != y.map(f32::to_bits))
            .count(),
        _ => 0,
    }
}

/// An accuracy's error statistics, exactly: the bits of its floats and its counts.
fn error_bits(a: &Accuracy) -> [u64; 5] {
    [
        a.mean_deg.to_bits(),
        a.p99_deg.to_bits(),
        a.max_deg.to_bits(),
        a.wrong_handedness as u64,
        a.non_finite as u64,
    ]
}

fn csv(rows: &[Row]) -> String {
    let mut text =
        String::from("scene,vertices,method,ns_per_vertex,mean_deg,p99_deg,max_deg,wrong_handedness_share\n");
    for r in rows {
        let a = &r.accuracy;
        writeln!(
            text,
            "{},{},{},{:.2},{:.6},{:.6},{:.6},{:.6}",
            r.scene,
            r.vertices,
            r.method,
            r.ns_per_vertex,
            a.mean_deg,
            a.p99_deg,
            a.max_deg,
            a.wrong_handedness_share()
        )
        .unwrap();
    }
    text
}

/// Marker colours, one per entry, in entry order.
const COLOURS: [&str; 12] = [
    "#1f77b4", "#17becf", "#2ca02c", "#98df8a", "#9467bd", "#bcbd22", "#000000", "#d62728", "#ff7f0e", "#ffbb78",
    "#8c564b", "#e377c2",
];

/// The colour of the Pareto front's staircase and rings.
const FRONT_COLOUR: &str = "#333333";

/// The torus rows as a log-log scatter, one polyline per method through its sizes, and each size's
/// Pareto front.
fn svg(rows: &[Row], entries: &[Entry], scene: &str) -> String {
    let points: Vec<&Row> = rows
        .iter()
        .filter(|r| r.scene == scene && r.ns_per_vertex > 0.0 && r.accuracy.mean_deg > 0.0)
        .collect();
    let decade_range = |values: Vec<f64>| {
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min).log10().floor();
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max).log10().ceil();
        (lo, hi.max(lo + 1.0))
    };
    let (x_lo, x_hi) = decade_range(points.iter().map(|r| r.ns_per_vertex).collect());
    let (y_lo, y_hi) = decade_range(points.iter().map(|r| r.accuracy.mean_deg).collect());
    let (left, top, width, height) = (80.0, 40.0, 560.0, 420.0);
    let x_of = |ns: f64| left + (ns.log10() - x_lo) / (x_hi - x_lo) * width;
    let y_of = |deg: f64| top + (y_hi - deg.log10()) / (y_hi - y_lo) * height;

    let mut s = String::new();
    let total_width = left + width + 250.0;
    // Tall enough for the legend: a row per entry, the front's, and the notes.
    let total_height = (top + height + 70.0).max(top + 20.0 * entries.len() as f64 + 200.0);
    writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{total_width}" height="{total_height}" font-family="sans-serif" font-size="12">"#
    )
    .unwrap();
    writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#).unwrap();
    writeln!(
        s,
        r#"<text x="{}" y="22" text-anchor="middle" font-size="14">Speed against accuracy: jittered torus with warped UVs, {} to {} vertices</text>"#,
        left + width / 2.0,
        points.iter().map(|r| r.vertices).min().unwrap_or(0),
        points.iter().map(|r| r.vertices).max().unwrap_or(0)
    )
    .unwrap();
    // Decade grid lines with labels, and unlabelled 2x and 5x lines.
    for decade in x_lo as i32..=x_hi as i32 {
        for (k, strong) in [(1.0, true), (2.0, false), (5.0, false)] {
            let value = k * 10f64.powi(decade);
            if value.log10() > x_hi + 1e-9 {
                continue;
            }
            let x = x_of(value);
            let colour = if strong { "#bbbbbb" } else { "#e8e8e8" };
            writeln!(
                s,
                r#"<line x1="{x:.1}" y1="{top}" x2="{x:.1}" y2="{}" stroke="{colour}"/>"#,
                top + height
            )
            .unwrap();
            if strong {
                writeln!(
                    s,
                    r#"<text x="{x:.1}" y="{}" text-anchor="middle">{}</text>"#,
                    top + height + 16.0,
                    label(value)
                )
                .unwrap();
            }
        }
    }
    for decade in y_lo as i32..=y_hi as i32 {
        for (k, strong) in [(1.0, true), (2.0, false), (5.0, false)] {
            let value = k * 10f64.powi(decade);
            if value.log10() > y_hi + 1e-9 {
                continue;
            }
            let y = y_of(value);
            let colour = if strong { "#bbbbbb" } else { "#e8e8e8" };
            writeln!(
                s,
                r#"<line x1="{left}" y1="{y:.1}" x2="{}" y2="{y:.1}" stroke="{colour}"/>"#,
                left + width
            )
            .unwrap();
            if strong {
                writeln!(
                    s,
                    r#"<text x="{}" y="{:.1}" text-anchor="end">{}</text>"#,
                    left - 6.0,
                    y + 4.0,
                    label(value)
                )
                .unwrap();
            }
        }
    }
    writeln!(
        s,
        r#"<rect x="{left}" y="{top}" width="{width}" height="{height}" fill="none" stroke="black"/>"#
    )
    .unwrap();
    writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">time per vertex (ns, median, one thread; log scale)</text>"#,
        left + width / 2.0,
        top + height + 40.0
    )
    .unwrap();
    writeln!(
        s,
        r#"<text transform="translate(22 {}) rotate(-90)" text-anchor="middle">mean angle to the true tangent (degrees; log scale)</text>"#,
        top + height / 2.0
    )
    .unwrap();

    for (k, entry) in entries.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let mut mine: Vec<&&Row> = points.iter().filter(|r| r.method == entry.name).collect();
        mine.sort_by_key(|r| r.vertices);
        let path: Vec<String> = mine
            .iter()
            .map(|r| format!("{:.1},{:.1}", x_of(r.ns_per_vertex), y_of(r.accuracy.mean_deg)))
            .collect();
        writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-opacity="0.5"/>"#,
            path.join(" ")
        )
        .unwrap();
        let library = entry.generator.library();
        // The default repeats one of the methods: a ring lets the point beneath it show.
        let paint = if entry.name.starts_with("tbasis default") {
            format!(r#"fill="none" stroke="{colour}" stroke-width="2""#)
        } else {
            format!(r#"fill="{colour}""#)
        };
        for (i, r) in mine.iter().enumerate() {
            // Larger markers for larger meshes: the biggest one is the 1M-vertex point.
            let size = 2.5 + 1.2 * i as f64;
            let (x, y) = (x_of(r.ns_per_vertex), y_of(r.accuracy.mean_deg));
            let title = format!(
                "{}, {} vertices: {:.1} ns/vertex, mean {:.4} deg",
                entry.name, r.vertices, r.ns_per_vertex, r.accuracy.mean_deg
            );
            if library {
                writeln!(
                    s,
                    r#"<circle cx="{x:.1}" cy="{y:.1}" r="{size:.1}" {paint}><title>{title}</title></circle>"#
                )
                .unwrap();
            } else {
                writeln!(
                    s,
                    r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="{colour}"><title>{title}</title></rect>"#,
                    x - size,
                    y - size,
                    2.0 * size,
                    2.0 * size
                )
                .unwrap();
            }
        }
        let ly = top + 10.0 + 20.0 * k as f64;
        let lx = left + width + 20.0;
        if library {
            writeln!(s, r#"<circle cx="{}" cy="{ly}" r="5" {paint}/>"#, lx + 5.0).unwrap();
        } else {
            writeln!(
                s,
                r#"<rect x="{lx}" y="{}" width="10" height="10" fill="{colour}"/>"#,
                ly - 5.0
            )
            .unwrap();
        }
        writeln!(s, r#"<text x="{}" y="{}">{}</text>"#, lx + 16.0, ly + 4.0, entry.name).unwrap();
    }
    // The Pareto front of each size, on top: a staircase through its points, fastest first (the
    // points above and to the right of it are dominated), and a ring around each.
    let mut sizes: Vec<usize> = points.iter().map(|r| r.vertices).collect();
    sizes.sort_unstable();
    sizes.dedup();
    for (i, &n) in sizes.iter().enumerate() {
        let front: Vec<(f64, f64)> = Compared::of(rows, entries, scene, n)
            .front()
            .iter()
            .filter(|r| r.ns_per_vertex > 0.0 && r.accuracy.mean_deg > 0.0)
            .map(|r| (x_of(r.ns_per_vertex), y_of(r.accuracy.mean_deg)))
            .collect();
        let mut staircase = Vec::new();
        for (k, &(x, y)) in front.iter().enumerate() {
            if k > 0 {
                staircase.push(format!("{x:.1},{:.1}", front[k - 1].1));
            }
            staircase.push(format!("{x:.1},{y:.1}"));
        }
        writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{FRONT_COLOUR}" stroke-dasharray="4 3"/>"#,
            staircase.join(" ")
        )
        .unwrap();
        let ring = 2.5 + 1.2 * i as f64 + 2.5;
        for (x, y) in front {
            writeln!(
                s,
                r#"<circle cx="{x:.1}" cy="{y:.1}" r="{ring:.1}" fill="none" stroke="{FRONT_COLOUR}" stroke-width="1.5"/>"#
            )
            .unwrap();
        }
    }
    let front_y = top + 10.0 + 20.0 * entries.len() as f64;
    let lx = left + width + 20.0;
    writeln!(
        s,
        r#"<line x1="{lx}" y1="{front_y}" x2="{}" y2="{front_y}" stroke="{FRONT_COLOUR}" stroke-dasharray="4 3"/>"#,
        lx + 10.0
    )
    .unwrap();
    writeln!(
        s,
        r#"<circle cx="{}" cy="{front_y}" r="4" fill="none" stroke="{FRONT_COLOUR}" stroke-width="1.5"/>"#,
        lx + 5.0
    )
    .unwrap();
    writeln!(
        s,
        r#"<text x="{}" y="{}">Pareto front, per size</text>"#,
        lx + 16.0,
        front_y + 4.0
    )
    .unwrap();

    let note_y = front_y + 30.0;
    let largest = points.iter().map(|r| r.vertices).max().unwrap_or(0);
    for (i, line) in [
        "Circles: this library;".to_string(),
        "squares: peers.".to_string(),
        "Each line joins one method's".to_string(),
        "sizes; larger markers are".to_string(),
        "larger meshes (largest:".to_string(),
        format!("{largest} vertices)."),
        "Ringed: no other method is".to_string(),
        "faster and at least as".to_string(),
        "accurate at that size.".to_string(),
    ]
    .iter()
    .enumerate()
    {
        writeln!(
            s,
            r##"<text x="{}" y="{}" fill="#555555">{line}</text>"##,
            left + width + 20.0,
            note_y + 16.0 * i as f64
        )
        .unwrap();
    }
    s.push_str("</svg>\n");
    s
}

/// `0.001`, `0.01`, ... `1`, `10`, `100`, `1000` without trailing noise.
fn label(value: f64) -> String {
    if value >= 1.0 {
        format!("{value:.0}")
    } else {
        let digits = (-value.log10()).ceil() as usize;
        format!("{value:.digits$}")
    }
}

/// One scene and size: every method's row, whether it is on the Pareto front, and then each peer
/// with the methods of this library that dominate it.
fn table(rows: &[Row], entries: &[Entry], scene: &str, vertices: usize) -> String {
    let compared = Compared::of(rows, entries, scene, vertices);
    let mut text = String::from(
        "| method | ns/vertex | mean (deg) | p99 (deg) | max (deg) | wrong w | front |\n\
         |---|---:|---:|---:|---:|---:|---|\n",
    );
    for r in rows.iter().filter(|r| r.scene == scene && r.vertices == vertices) {
        let a = &r.accuracy;
        let front = match (compared.on_front(&r.method), twin_of(entries, &r.method)) {
            (Some(true), _) => "yes".to_string(),
            (_, Some(twin)) => format!("(same call as {})", twin.name),
            _ => String::new(),
        };
        writeln!(
            text,
            "| {} | {:.1} | {:.4} | {:.4} | {:.3} | {:.2}% | {front} |",
            r.method,
            r.ns_per_vertex,
            a.mean_deg,
            a.p99_deg,
            a.max_deg,
            100.0 * a.wrong_handedness_share()
        )
        .unwrap();
    }
    text.push('\n');
    text.push_str(&dominated_peers(&compared, entries));
    text
}

/// One line per peer: the methods of this library that dominate it, or that none does.
fn dominated_peers(compared: &Compared, entries: &[Entry]) -> String {
    let mut text = String::new();
    for (peer, by) in compared.dominated_peers(entries) {
        if by.is_empty() {
            writeln!(text, "- {peer}: no method of this library dominates it.").unwrap();
        } else {
            writeln!(text, "- {peer}: dominated by {}.", by.join(", ")).unwrap();
        }
    }
    text
}

/// Agreement of one method with the tangents stored in the corpus files, split by mirror seams.
#[derive(Default, Clone, Copy)]
struct Agreement {
    vertices: usize,
    agree: usize,
    seam_vertices: usize,
    seam_agree: usize,
}

impl Agreement {
    fn add(&mut self, other: &Agreement) {
        self.vertices += other.vertices;
        self.agree += other.agree;
        self.seam_vertices += other.seam_vertices;
        self.seam_agree += other.seam_agree;
    }
}

fn share(part: usize, whole: usize) -> String {
    if whole == 0 {
        "-".to_string()
    } else {
        format!("{:.1}%", 100.0 * part as f64 / whole as f64)
    }
}

/// Degrees between two vectors (any lengths); `None` if either is zero or not finite.
fn angle_between(a: [f32; 3], b: [f32; 3]) -> Option<f64> {
    let (a, b) = (a.map(f64::from), b.map(f64::from));
    let c = scenes::cross(a, b);
    let (length, d) = (scenes::dot(c, c).sqrt(), scenes::dot(a, b));
    (length.is_finite() && d.is_finite() && (length > 0.0 || d != 0.0)).then(|| length.atan2(d).to_degrees())
}

/// Per method, the share of vertices whose tangent is within 1 degree of the stored one and whose
/// `w` has its sign, over the corpus files whose stored tangents are exactly MikkTSpace's.
fn agreement(entries: &[Entry]) -> Option<String> {
    let Some(dir) = load::corpus_dir() else {
        println!("../shared/meshes is absent: agreement with real assets skipped");
        return None;
    };
    let manifest = match load::read_manifest(&dir) {
        Ok(manifest) => manifest,
        Err(e) => {
            println!("agreement skipped: {e}");
            return None;
        }
    };
    let mut text = String::new();
    let mut totals = vec![Agreement::default(); entries.len()];
    let mut per_file = Vec::new();
    let mut collapsed = 0;
    for row in manifest.iter().filter(|r| r.stored_tangents == "mikktspace-exact") {
        let file = match load::load(&dir, row) {
            Ok(file) => file,
            Err(e) => {
                println!("{}: not loaded ({e})", row.path);
                continue;
            }
        };
        let mut sums = vec![Agreement::default(); entries.len()];
        for primitive in &file.primitives {
            let (Some(uvs), Some(stored)) = (&primitive.texcoords, &primitive.stored_tangents) else {
                continue;
            };
            // MikkTSpace's reference on glTF was computed with v' = 1 - v; the peers get exactly
            // that, the library gets the file's coordinates with flip_v.
            let v_up: Vec<[f32; 2]> = if primitive.v_down {
                uvs.iter().map(|&[u, v]| [u, 1.0 - v]).collect()
            } else {
                uvs.clone()
            };
            let input = Input {
                positions: &primitive.positions,
                normals: &primitive.normals,
                texcoords: &v_up,
                library_texcoords: uvs,
                flip_v: primitive.v_down,
                indices: &primitive.indices,
            };
            let corners = Corners::of(&input);
            let kinds = vertex_kinds(&primitive.positions, &v_up, &primitive.indices);
            collapsed += kinds.collapsed.iter().filter(|&&c| c).count();
            for (k, entry) in entries.iter().enumerate() {
                let (tangents, _) = run(entry.generator, &input, &corners, false);
                for v in (0..tangents.len()).filter(|&v| kinds.referenced[v]) {
                    let (t, s) = (tangents[v], stored[v]);
                    let close = angle_between([t[0], t[1], t[2]], [s[0], s[1], s[2]]).is_some_and(|a| a < 1.0);
                    let ok = close && (t[3] < 0.0) == (s[3] < 0.0);
                    let sum = &mut sums[k];
                    sum.vertices += 1;
                    sum.agree += usize::from(ok);
                    sum.seam_vertices += usize::from(kinds.seam[v]);
                    sum.seam_agree += usize::from(kinds.seam[v] && ok);
                }
            }
        }
        if sums[0].vertices == 0 {
            continue;
        }
        for (total, sum) in totals.iter_mut().zip(&sums) {
            total.add(sum);
        }
        per_file.push((row.path.clone(), sums));
    }
    let agreed = |name: &str| entries.iter().position(|e| e.name == name).map(|k| totals[k]);
    let (ours, theirs) = (agreed(MIKKTSPACE), agreed(MIKKTSPACE_C));
    assert_eq!(
        ours.map(|a| (a.agree, a.seam_agree)),
        theirs.map(|a| (a.agree, a.seam_agree)),
        "the agreement of {MIKKTSPACE} and {MIKKTSPACE_C} differ"
    );

    writeln!(
        text,
        "Share of vertices whose tangent is within 1 degree of the stored MikkTSpace tangent and whose \
         w has the same sign, over the {} files of `../shared/meshes/MANIFEST.tsv` marked \
         `mikktspace-exact`: {} vertices used by triangles, {} of them on mirror seams (their position \
         is used by triangles of both UV orientations, whether the file splits the vertex there or \
         not). glTF files run with `flip_v`, peers with v' = 1 - v. {collapsed} vertices are used \
         only by triangles of zero UV area, where no tangent is defined and each generator has its own \
         fallback: MikkTSpace's is (1, 0, 0) with w = -1 when no neighbour lends one; this \
         library's (policies other than LEGACY), a frame built from the normal with w = +1.\n",
        per_file.len(),
        totals[0].vertices,
        totals[0].seam_vertices
    )
    .unwrap();
    text.push_str("| method | all vertices | off seams | on mirror seams |\n|---|---:|---:|---:|\n");
    for (entry, t) in entries.iter().zip(&totals) {
        writeln!(
            text,
            "| {} | {} | {} | {} |",
            entry.name,
            share(t.agree, t.vertices),
            share(t.agree - t.seam_agree, t.vertices - t.seam_vertices),
            share(t.seam_agree, t.seam_vertices)
        )
        .unwrap();
    }
    text.push_str("\nPer file (all vertices / on mirror seams):\n\n| method |");
    for (path, _) in &per_file {
        write!(text, " {} |", path.rsplit('/').next().unwrap_or(path)).unwrap();
    }
    text.push_str("\n|---|");
    text.push_str(&"---:|".repeat(per_file.len()));
    text.push('\n');
    for (k, entry) in entries.iter().enumerate() {
        write!(text, "| {} |", entry.name).unwrap();
        for (_, sums) in &per_file {
            let s = sums[k];
            write!(
                text,
                " {} / {} |",
                share(s.agree, s.vertices),
                share(s.seam_agree, s.seam_vertices)
            )
            .unwrap();
        }
        text.push('\n');
    }
    write!(text, "| (vertices / on seams) |").unwrap();
    for (_, sums) in &per_file {
        write!(text, " {} / {} |", sums[0].vertices, sums[0].seam_vertices).unwrap();
    }
    text.push('\n');
    println!("{text}");
    Some(text)
}

/// What each vertex is, for the agreement split.
struct VertexKinds {
    /// Some triangle uses it.
    referenced: Vec<bool>,
    /// On a mirror seam: its position is used by triangles of both UV orientations, whether the
    /// file shares the vertex across the seam or splits it (as exporters of MikkTSpace tangents do).
    seam: Vec<bool>,
    /// Every triangle using it has a zero UV area: no tangent is defined there, and each generator
    /// writes its own fallback.
    collapsed: Vec<bool>,
}

fn vertex_kinds(positions: &[[f32; 3]], uvs: &[[f32; 2]], indices: &[u32]) -> VertexKinds {
    let mut referenced = vec![false; uvs.len()];
    let mut oriented = vec![false; uvs.len()];
    let mut orientation: HashMap<[u32; 3], u8> = HashMap::new();
    for triangle in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| uvs[triangle[k] as usize].map(f64::from));
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let bit = if det > 0.0 {
            1
        } else if det < 0.0 {
            2
        } else {
            0
        };
        for &v in triangle {
            referenced[v as usize] = true;
            oriented[v as usize] |= bit != 0;
            *orientation.entry(positions[v as usize].map(f32::to_bits)).or_default() |= bit;
        }
    }
    let seam = positions
        .iter()
        .map(|p| orientation.get(&p.map(f32::to_bits)) == Some(&3))
        .collect();
    let collapsed = referenced.iter().zip(&oriented).map(|(&r, &o)| r && !o).collect();
    VertexKinds {
        referenced,
        seam,
        collapsed,
    }
}

/// CPU time, in clock ticks, spent by the whole machine and by this process so far (Linux; zero
/// elsewhere).
fn cpu_ticks() -> (u64, u64) {
    let stat = fs::read_to_string("/proc/stat").unwrap_or_default();
    let machine: Vec<u64> = stat
        .lines()
        .next()
        .unwrap_or("")
        .split_whitespace()
        .skip(1)
        .take(8)
        .filter_map(|x| x.parse().ok())
        .collect();
    // user nice system idle iowait irq softirq steal (guest time is already in user and nice):
    // busy is all but idle and iowait.
    let busy =
        machine.iter().sum::<u64>() - machine.get(3).copied().unwrap_or(0) - machine.get(4).copied().unwrap_or(0);
    let own = fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // After the parenthesised command name: state, then fields 4 onwards; utime and stime are
    // fields 14 and 15. Every position is kept (tpgid can be -1).
    let after_name = own.rsplit(')').next().unwrap_or("");
    let fields: Vec<u64> = after_name
        .split_whitespace()
        .skip(1)
        .map(|x| x.parse().unwrap_or(0))
        .collect();
    let mine = fields.get(10).copied().unwrap_or(0) + fields.get(11).copied().unwrap_or(0);
    (busy, mine)
}

/// How many cores other processes kept busy, on average, since `since` (ticks of 1/100 s).
fn other_load(since: (u64, u64), elapsed: Duration) -> f64 {
    let now = cpu_ticks();
    let others = (now.0 - since.0).saturating_sub(now.1 - since.1);
    others as f64 / 100.0 / elapsed.as_secs_f64().max(1e-9)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let max_vertices = match args.as_slice() {
        [] => None,
        [flag, n] if flag == "--max-vertices" => Some(n.parse::<usize>().expect("--max-vertices N")),
        _ => {
            eprintln!("usage: chart [--max-vertices N]");
            std::process::exit(2);
        }
    };
    let out_dir = if max_vertices.is_some() {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/chart")
    } else {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs")
    };
    fs::create_dir_all(&out_dir).expect("output directory");
    let load_before = load_average();
    println!("{}; load average {load_before}", machine());
    let (started, run_ticks) = (Instant::now(), cpu_ticks());

    let entries = entries();
    let sizes: Vec<usize> = scenes::SWEEP
        .iter()
        .copied()
        .filter(|&n| max_vertices.is_none_or(|max| n <= max))
        .collect();
    let mut rows = Vec::new();
    let mut torus_sizes = Vec::new();
    let mut legacy_mismatches = 0;
    // Cores kept busy by other processes while each scene and size ran.
    let mut interference: Vec<(String, usize, f64)> = Vec::new();
    for make in [SceneSpec::torus, SceneSpec::sphere, SceneSpec::mirrored_torus] {
        for &size in &sizes {
            let scene = scenes::build(&make(size));
            let (ticks, start) = (cpu_ticks(), Instant::now());
            if scene.name == "torus" {
                torus_sizes.push(scene.vertex_count());
            }
            let differing = measure_scene(&scene, &entries, &mut rows);
            println!(
                "Peers against this library (Pareto dominance), {} {}:",
                scene.name,
                scene.vertex_count()
            );
            print!(
                "{}",
                dominated_peers(
                    &Compared::of(&rows, &entries, &scene.name, scene.vertex_count()),
                    &entries
                )
            );
            if differing > 0 {
                println!("{} vertices of LENGYEL+LEGACY differ from listing.c", differing);
            }
            legacy_mismatches += differing;
            let busy = other_load(ticks, start.elapsed());
            println!("other processes kept {busy:.2} cores busy meanwhile");
            interference.push((scene.name.clone(), scene.vertex_count(), busy));
        }
    }
    let run_interference = other_load(run_ticks, started.elapsed());
    let agreement = agreement(&entries);
    let load_after = load_average();
    let elapsed = started.elapsed();

    write(&out_dir.join("chart.csv"), &csv(&rows));
    write(&out_dir.join("chart.svg"), &svg(&rows, &entries, "torus"));
    let mut md = String::from(
        "# Speed against accuracy\n\n\
         Every method of this library and its peers, on analytic scenes whose true tangent is known \
         in closed form (`crates/test-support/src/scenes.rs`): a torus and a sphere band, tessellated with \
         jittered vertices and random quad diagonals, with a smooth nonlinear UV warp, and a torus \
         whose texture is mirrored on one half (seam vertices duplicated). Error of a vertex: the \
         angle between its tangent and the true tangent dP/ds projected onto its tangent plane; \
         wrong w: the share of vertices whose handedness sign differs from the true one. Time: \
         median of repeated runs of the generating call alone, one thread, writing into an output \
         allocated before the timing. MikkTSpace and \
         meshoptimizer write per-corner tangents; each vertex takes its first corner's, as this \
         library's method MIKKTSPACE (`Options::mikktspace()`, mikktspace.c's frames bit for bit) \
         does in the per-vertex call timed here. Peers: \
         listing.c (`c_tests/listing.c`, the listing in C, built with -ffp-contract=off), meshopt \
         0.7.0 (meshoptimizer 1.3, `meshopt_generateTangents`, default and MikkTSpace-compatible), \
         mikktspace-sys 0.1.1 (mikktspace.c) and bevy_mikktspace 1.0.0.\n\n\
         Reproduce (a few minutes on 2 cores, this run's time below; writes docs/chart.csv, docs/chart.svg, docs/chart.md):\n\n\
         ```text\ncargo run --release -p tbasis-compare --example chart\n```\n\n",
    );
    writeln!(
        md,
        "Measured on {}. Load average (1, 5, 15 min): {load_before} at the start, {load_after} at the \
         end; the run took {:.0} s, during which other processes kept {run_interference:.2} cores \
         busy on average (per table below: while that size ran). On a loaded machine times are \
         slower and noisier: compare methods within one run.\n",
        machine(),
        elapsed.as_secs_f64()
    )
    .unwrap();
    writeln!(
        md,
        "Check: LENGYEL+LEGACY and listing.c {} on every scene; the errors of {MIKKTSPACE} equal \
         those of {MIKKTSPACE_C} exactly on every scene and size (the run stops otherwise).\n",
        if legacy_mismatches == 0 {
            "agreed bit for bit".to_string()
        } else {
            format!("differed on {legacy_mismatches} vertices in all")
        }
    )
    .unwrap();
    md.push_str(
        "Pareto front: on each scene and size, a method **dominates** another when it is faster \
         (ns/vertex) and at least as accurate (mean error), or exactly as fast and more accurate; \
         the **front** column says yes for the methods no other method dominates (the chart rings \
         them and joins each size's with a dashed staircase). The default makes the same call as \
         one of the methods listed, so only that one is compared (its time differs by noise \
         alone). Under each table, each peer with the methods of this library that dominate it. \
         Computed from the times and errors of this run, unrounded: two errors equal in the tables \
         may still differ.\n\n",
    );
    md.push_str("![ns per vertex against mean error, torus](chart.svg)\n\n");
    let mut shown: Vec<usize> = Vec::new();
    for index in [torus_sizes.len().wrapping_sub(1), 0, torus_sizes.len() / 2] {
        if let Some(&n) = torus_sizes.get(index) {
            if !shown.contains(&n) {
                shown.push(n);
            }
        }
    }
    let busy = |name: &str, n: usize| {
        interference
            .iter()
            .find(|(scene, vertices, _)| scene == name && *vertices == n)
            .map_or(0.0, |&(_, _, busy)| busy)
    };
    let largest = |name: &str| rows.iter().filter(|r| r.scene == name).map(|r| r.vertices).max();
    let tables = shown.into_iter().map(|n| ("torus", n)).chain(
        ["sphere", "mirrored-torus"]
            .into_iter()
            .filter_map(|name| Some((name, largest(name)?))),
    );
    for (name, n) in tables {
        writeln!(
            md,
            "## {}, {n} vertices\n\nOther processes kept {:.2} cores busy meanwhile.\n\n{}",
            capitalize(name),
            busy(name, n),
            table(&rows, &entries, name, n)
        )
        .unwrap();
    }
    md.push_str("Every scene and size: `chart.csv`.\n\n## Agreement with real assets\n\n");
    match &agreement {
        Some(text) => md.push_str(text),
        None => md.push_str("Skipped: `../shared/meshes` was absent.\n"),
    }
    write(&out_dir.join("chart.md"), &md);
    println!("wrote {} in {:.0} s", out_dir.display(), elapsed.as_secs_f64());
}

fn capitalize(name: &str) -> String {
    let mut chars = name.chars();
    chars
        .next()
        .map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
}

fn write(path: &Path, text: &str) {
    fs::write(path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}
