//! Speed of every method and policy against the C port of the listing and against the machine's
//! read bandwidth, in one run.
//!
//! ```text
//! cargo run --release --example bench
//! ```
//!
//! Scenes: the irregular torus of `docs/chart.md` at about 1M vertices (`tests/common/scenes.rs`),
//! `../shared/meshes/derived/FlightHelmet.cc1.glb` (a real asset of 849k vertices, one call per
//! primitive; skipped with a message when the corpus is absent) and a 24-vertex cube with a UV
//! square per face (per-call overhead).
//!
//! Every configuration runs on the same buffers, interleaved round by round so that a drift in the
//! machine's speed touches them all alike; each time is the median over the rounds. Besides
//! ns/vertex, each result is given as a ratio to the C port of the listing (`c_tests/listing.c`,
//! linked by `build.rs`) and as a share of the bandwidth limit: the time the bytes a per-vertex
//! method must touch take at the read bandwidth measured at the start of the run.
//!
//! Prints the tables and writes `docs/bench.md`.

#[path = "../c_tests/listing.rs"]
mod listing;
#[allow(dead_code)]
#[path = "../tests/common/load.rs"]
mod load;
#[path = "common/machine.rs"]
mod machine;
#[allow(dead_code)]
#[path = "../tests/common/scenes.rs"]
mod scenes;

use std::fmt::Write as _;
use std::fs;
use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use listing::listing_tangents;
use machine::{load_average, machine};
use tbasis::{generate_into, DegeneratePolicy, Error, Indices, Mesh, Method, Options, Output, Strided, StridedMut};

/// The command, as the report shows it.
const COMMAND: &str = "cargo run --release --example bench";

/// Vertices of the torus (the largest size of the chart's sweep).
const TORUS_VERTICES: usize = 1_000_000;

/// The real asset, relative to the corpus folder.
const ASSET: &str = "derived/FlightHelmet.cc1.glb";

/// Bytes of the array summed to measure the read bandwidth: far beyond any cache.
const BANDWIDTH_BYTES: usize = 256 << 20;

/// Passes over that array per thread count; the fastest counts.
const BANDWIDTH_PASSES: usize = 5;

/// Scratch bytes per vertex (`tbasis::scratch_size`): 28 bytes of sums and one flag byte.
const SCRATCH_BYTES_PER_VERTEX: usize = 29;

/// Time the rounds of one large scene should take, all configurations together.
const LARGE_SCENE_BUDGET: Duration = Duration::from_secs(40);

/// Rounds on a large scene: at least this many, whatever the budget.
const MIN_ROUNDS: usize = 7;

/// Rounds on a large scene: at most this many.
const MAX_ROUNDS: usize = 31;

/// Calls per timed sample on the cube: one call is a microsecond or so, far below the clock's
/// resolution and the noise of a single measurement.
const CUBE_CALLS: usize = 10_000;

/// Samples per configuration on the cube.
const CUBE_ROUNDS: usize = 15;

/// One array the library reads: a primitive of the asset, or the whole of a generated scene.
struct Part {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    /// What the library reads: the file's own coordinates (V down for glTF, with `flip_v`).
    texcoords: Vec<[f32; 2]>,
    /// What the C port reads: V up (`1 - v` for glTF), as the listing expects.
    listing_texcoords: Vec<[f32; 2]>,
    indices: Vec<u32>,
    flip_v: bool,
}

impl Part {
    fn vertices(&self) -> usize {
        self.positions.len()
    }

    /// Bytes a per-vertex method must touch at least once: the inputs and the output, once each,
    /// and its scratch (the sums and flags) written and read back.
    fn bytes(&self) -> usize {
        let n = self.vertices();
        self.positions.len() * 12
            + self.normals.len() * 12
            + self.texcoords.len() * 8
            + n * 16
            + self.indices.len() * 4
            + 2 * n * SCRATCH_BYTES_PER_VERTEX
    }
}

/// Builds a scene, or says why it cannot.
type SceneBuilder = fn() -> Result<Scene, String>;

/// A scene: one or more parts, each computed by its own call.
struct Scene {
    name: String,
    /// For the summary table.
    short: String,
    parts: Vec<Part>,
    /// Large scenes are timed one call per sample; small ones in loops of [`CUBE_CALLS`] calls.
    small: bool,
}

impl Scene {
    fn vertices(&self) -> usize {
        self.parts.iter().map(Part::vertices).sum()
    }

    fn triangles(&self) -> usize {
        self.parts.iter().map(|p| p.indices.len() / 3).sum()
    }

    fn bytes(&self) -> usize {
        self.parts.iter().map(Part::bytes).sum()
    }

    fn title(&self) -> String {
        let calls = if self.parts.len() > 1 {
            let sizes: Vec<String> = self.parts.iter().map(|p| p.vertices().to_string()).collect();
            format!(
                ", {} calls (one per primitive, of {} vertices)",
                self.parts.len(),
                sizes.join(", ")
            )
        } else {
            String::new()
        };
        format!(
            "{}: {} vertices, {} triangles{calls}",
            self.name,
            self.vertices(),
            self.triangles()
        )
    }
}

fn torus() -> Scene {
    let scene = scenes::build(&scenes::SceneSpec::torus(TORUS_VERTICES));
    Scene {
        name: "Irregular torus".to_string(),
        short: "torus".to_string(),
        parts: vec![Part {
            listing_texcoords: scene.texcoords.clone(),
            positions: scene.positions,
            normals: scene.normals,
            texcoords: scene.texcoords,
            indices: scene.indices,
            flip_v: false,
        }],
        small: false,
    }
}

/// The asset, or why it is not there.
fn asset() -> Result<Scene, String> {
    let dir = load::corpus_dir().ok_or("../shared/meshes is absent")?;
    let manifest = load::read_manifest(&dir)?;
    let row = manifest
        .iter()
        .find(|row| row.path == ASSET)
        .ok_or_else(|| format!("{ASSET} is not in ../shared/meshes/MANIFEST.tsv"))?;
    if !dir.join(ASSET).is_file() {
        return Err(format!("../shared/meshes/{ASSET} is absent"));
    }
    let file = load::load(&dir, row)?;
    let mut parts = Vec::new();
    let mut skipped = 0;
    for primitive in file.primitives {
        let Some(uvs) = primitive.texcoords else {
            skipped += 1;
            continue;
        };
        let listing_texcoords = if primitive.v_down {
            uvs.iter().map(|&[u, v]| [u, 1.0 - v]).collect()
        } else {
            uvs.clone()
        };
        parts.push(Part {
            positions: primitive.positions,
            normals: primitive.normals,
            texcoords: uvs,
            listing_texcoords,
            indices: primitive.indices,
            flip_v: primitive.v_down,
        });
    }
    if skipped > 0 {
        println!("{ASSET}: {skipped} primitives without texture coordinates left out");
    }
    if parts.is_empty() {
        return Err(format!("{ASSET} has no primitive with texture coordinates"));
    }
    Ok(Scene {
        name: "FlightHelmet.cc1.glb".to_string(),
        short: "FlightHelmet".to_string(),
        parts,
        small: false,
    })
}

/// A unit cube: 6 faces of 4 vertices each (no vertex shared between faces, as a textured cube
/// has them), each face a full UV square, 2 triangles per face wound outwards.
fn cube() -> Scene {
    let mut part = Part {
        positions: Vec::new(),
        normals: Vec::new(),
        texcoords: Vec::new(),
        listing_texcoords: Vec::new(),
        indices: Vec::new(),
        flip_v: false,
    };
    // Per face: the outward normal and the directions of u and v (right-handed: u x v = normal).
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
    ];
    for (normal, u, v) in faces {
        let first = part.positions.len() as u32;
        for [s, t] in [[0.0f32, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
            let (a, b) = (2.0 * s - 1.0, 2.0 * t - 1.0);
            part.positions
                .push([0, 1, 2].map(|k| 0.5 * (normal[k] + a * u[k] + b * v[k])));
            part.normals.push(normal);
            part.texcoords.push([s, t]);
        }
        part.indices
            .extend_from_slice(&[first, first + 1, first + 2, first, first + 2, first + 3]);
    }
    part.listing_texcoords = part.texcoords.clone();
    Scene {
        name: "Cube".to_string(),
        short: "cube".to_string(),
        parts: vec![part],
        small: true,
    }
}

/// Who computes the tangents, and how.
#[derive(Clone, Copy)]
enum Generator {
    Listing,
    Library(Options),
    /// With caller scratch, allocated and touched once before the timing: what a caller that
    /// keeps its scratch between calls pays.
    LibraryWithScratch(Options),
}

struct Config {
    name: String,
    generator: Generator,
}

fn upper(value: impl std::fmt::Debug) -> String {
    format!("{value:?}").to_uppercase()
}

/// The C port first (the reference of every ratio), then every method and policy, the default,
/// all on the calling thread, then two configurations again with two threads.
fn configs() -> Vec<Config> {
    let library = |method, policy, threads| {
        Generator::Library(Options {
            method,
            degenerate_policy: policy,
            threads,
            ..Options::default()
        })
    };
    let defaults = Options::default();
    let default_name = format!(
        "default ({}+{})",
        upper(defaults.method),
        upper(defaults.degenerate_policy)
    );
    let mut configs = vec![
        Config {
            name: "listing.c (C port)".to_string(),
            generator: Generator::Listing,
        },
        Config {
            name: "LENGYEL+LEGACY".to_string(),
            generator: library(Method::Lengyel, DegeneratePolicy::Legacy, 1),
        },
    ];
    for method in [Method::Lengyel, Method::Angle, Method::Area, Method::Uniform] {
        for policy in [
            DegeneratePolicy::Skip,
            DegeneratePolicy::Inherit,
            DegeneratePolicy::Reject,
        ] {
            configs.push(Config {
                name: format!("{}+{}", upper(method), upper(policy)),
                generator: library(method, policy, 1),
            });
        }
    }
    configs.push(Config {
        name: default_name.clone(),
        generator: Generator::Library(Options { threads: 1, ..defaults }),
    });
    configs.push(Config {
        name: "LENGYEL+LEGACY, caller scratch".to_string(),
        generator: Generator::LibraryWithScratch(Options {
            method: Method::Lengyel,
            degenerate_policy: DegeneratePolicy::Legacy,
            ..defaults
        }),
    });
    configs.push(Config {
        name: format!("{default_name}, caller scratch"),
        generator: Generator::LibraryWithScratch(defaults),
    });
    configs.push(Config {
        name: "LENGYEL+LEGACY, threads=2".to_string(),
        generator: library(Method::Lengyel, DegeneratePolicy::Legacy, 2),
    });
    configs.push(Config {
        name: format!("{default_name}, threads=2"),
        generator: Generator::Library(Options { threads: 2, ..defaults }),
    });
    configs
}

/// Index of a configuration by name (the ones the summary compares).
fn find(configs: &[Config], name: &str) -> usize {
    configs
        .iter()
        .position(|c| c.name == name)
        .unwrap_or_else(|| panic!("no configuration {name}"))
}

/// Runs `generator` on every part of `scene`, `calls` times over; returns the time of it all and
/// how many calls the library refused (policy REJECT on a degenerate triangle).
fn run(generator: Generator, scene: &Scene, outputs: &mut [Vec<[f32; 4]>], calls: usize) -> (Duration, usize) {
    let mut refused = 0;
    let mut scratch = Vec::new();
    if let Generator::LibraryWithScratch(_) = generator {
        let largest = scene.parts.iter().map(Part::vertices).max().unwrap_or(0);
        scratch = vec![1u8; tbasis::scratch_size(largest).expect("scratch size")];
    }
    let start = Instant::now();
    for _ in 0..calls {
        for (part, tangents) in scene.parts.iter().zip(outputs.iter_mut()) {
            match generator {
                Generator::Listing => {
                    // SAFETY: load.rs and scenes.rs keep every index below the vertex count.
                    unsafe {
                        listing_tangents(
                            &part.positions,
                            &part.normals,
                            &part.listing_texcoords,
                            &part.indices,
                            tangents,
                        )
                    };
                }
                Generator::Library(options) | Generator::LibraryWithScratch(options) => {
                    let options = Options {
                        flip_v: part.flip_v,
                        ..options
                    };
                    let mesh = Mesh {
                        positions: Strided::from_slice(&part.positions),
                        normals: Strided::from_slice(&part.normals),
                        texcoords: Some(Strided::from_slice(&part.texcoords)),
                        indices: Indices::U32(Strided::from_slice(&part.indices)),
                    };
                    let mut output = Output {
                        tangents: StridedMut::from_slice(tangents),
                        bitangents: None,
                    };
                    let with_scratch = matches!(generator, Generator::LibraryWithScratch(_));
                    let mut report = tbasis::Report::default();
                    let scratch = with_scratch.then_some(scratch.as_mut_slice());
                    match black_box(generate_into(&mesh, &options, &mut output, scratch, &mut report)) {
                        Ok(()) => {}
                        Err(Error::DegenerateUv) => refused += 1,
                        Err(e) => panic!("the library refused a benchmark mesh: {e:?}"),
                    }
                }
            }
        }
        black_box(&mut *outputs);
    }
    (start.elapsed(), refused)
}

/// What one configuration measured on one scene.
struct Measured {
    /// Median time of one pass over the scene (every part once).
    median: Duration,
    /// Interquartile range of the samples, as a share of the median.
    spread: f64,
    samples: usize,
    /// Calls refused per pass, and calls per pass.
    refused: usize,
    calls: usize,
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    let position = q * (sorted.len() - 1) as f64;
    let (low, high) = (position.floor() as usize, position.ceil() as usize);
    sorted[low] + (sorted[high] - sorted[low]) * (position - low as f64)
}

/// Times every configuration on `scene`, round by round.
fn measure(scene: &Scene, configs: &[Config]) -> Vec<Measured> {
    let mut outputs: Vec<Vec<[f32; 4]>> = scene.parts.iter().map(|p| vec![[0.0; 4]; p.vertices()]).collect();
    let calls = if scene.small { CUBE_CALLS } else { 1 };
    // A first round warms caches, allocator and page tables, and sizes the rounds.
    let warm: Vec<(Duration, usize)> = configs
        .iter()
        .map(|c| run(c.generator, scene, &mut outputs, calls))
        .collect();
    let rounds = if scene.small {
        CUBE_ROUNDS
    } else {
        let round: f64 = warm.iter().map(|(t, _)| t.as_secs_f64()).sum();
        ((LARGE_SCENE_BUDGET.as_secs_f64() / round.max(1e-9)) as usize).clamp(MIN_ROUNDS, MAX_ROUNDS)
    };
    let mut samples = vec![Vec::with_capacity(rounds); configs.len()];
    let mut refused = vec![0; configs.len()];
    for _ in 0..rounds {
        for (k, config) in configs.iter().enumerate() {
            let (time, r) = run(config.generator, scene, &mut outputs, calls);
            samples[k].push(time.as_secs_f64() / calls as f64);
            refused[k] = r / calls;
        }
    }
    samples
        .into_iter()
        .zip(refused)
        .map(|(mut s, refused)| {
            s.sort_by(f64::total_cmp);
            let median = quantile(&s, 0.5);
            Measured {
                median: Duration::from_secs_f64(median),
                spread: (quantile(&s, 0.75) - quantile(&s, 0.25)) / median,
                samples: s.len(),
                refused,
                calls: scene.parts.len(),
            }
        })
        .collect()
}

/// Vertices where LENGYEL+LEGACY and the C port differ in any bit (the library promises none).
fn legacy_mismatches(scene: &Scene) -> usize {
    let mut mine: Vec<Vec<[f32; 4]>> = scene.parts.iter().map(|p| vec![[0.0; 4]; p.vertices()]).collect();
    let mut theirs = mine.clone();
    run(Generator::Library(Options::legacy()), scene, &mut mine, 1);
    run(Generator::Listing, scene, &mut theirs, 1);
    mine.iter()
        .flatten()
        .zip(theirs.iter().flatten())
        .filter(|(a, b)| a.map(f32::to_bits) != b.map(f32::to_bits))
        .count()
}

/// Best read bandwidth in bytes per second with `threads` threads, each summing its share of a
/// [`BANDWIDTH_BYTES`] array of u64 (filled first, so every page is real memory).
fn read_bandwidth(data: &[u64], threads: usize) -> f64 {
    let chunk = data.len().div_ceil(threads);
    let mut best = f64::INFINITY;
    for _ in 0..BANDWIDTH_PASSES {
        let start = Instant::now();
        std::thread::scope(|scope| {
            let handles: Vec<_> = data
                .chunks(chunk)
                .map(|part| scope.spawn(move || black_box(part).iter().fold(0u64, |a, &x| a.wrapping_add(x))))
                .collect();
            for handle in handles {
                black_box(handle.join().expect("bandwidth thread"));
            }
        });
        best = best.min(start.elapsed().as_secs_f64());
    }
    std::mem::size_of_val(data) as f64 / best
}

/// Everything one scene gave.
struct SceneResult {
    title: String,
    short: String,
    vertices: usize,
    bytes: usize,
    measured: Vec<Measured>,
    mismatches: Option<usize>,
}

fn ns(d: Duration) -> f64 {
    d.as_secs_f64() * 1e9
}

/// One scene's table, Markdown.
fn table(result: &SceneResult, configs: &[Config], bandwidth: &Bandwidth) -> String {
    let listing = &result.measured[find(configs, "listing.c (C port)")];
    let mut text = String::from(
        "| configuration | ns/vertex | vs C port | share of bandwidth limit | per pass | spread (IQR) |\n\
         |---|---:|---:|---:|---:|---:|\n",
    );
    for (config, m) in configs.iter().zip(&result.measured) {
        let threads = match config.generator {
            Generator::Library(o) | Generator::LibraryWithScratch(o) => o.threads.max(1) as usize,
            Generator::Listing => 1,
        };
        let limit = result.bytes as f64 / bandwidth.for_threads(threads);
        let name = if m.refused > 0 {
            format!(
                "{} — refused ({} of {} calls): time of the refusal",
                config.name, m.refused, m.calls
            )
        } else {
            config.name.clone()
        };
        writeln!(
            text,
            "| {name} | {:.2} | {:.2}x | {:.0}% | {} | {:.1}% |",
            ns(m.median) / result.vertices as f64,
            m.median.as_secs_f64() / listing.median.as_secs_f64(),
            100.0 * limit / m.median.as_secs_f64(),
            human(m.median),
            100.0 * m.spread
        )
        .unwrap();
    }
    text
}

/// A duration with a unit that suits it.
fn human(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1e-3 {
        format!("{:.2} ms", s * 1e3)
    } else if s >= 1e-6 {
        format!("{:.3} µs", s * 1e6)
    } else {
        format!("{:.0} ns", s * 1e9)
    }
}

/// Read bandwidth, bytes per second, with one and with two threads.
struct Bandwidth {
    one: f64,
    two: f64,
}

impl Bandwidth {
    fn for_threads(&self, threads: usize) -> f64 {
        if threads >= 2 {
            self.two
        } else {
            self.one
        }
    }
}

fn main() {
    let load_before = load_average();
    println!("{}; load average {load_before}", machine());
    let started = Instant::now();

    // Bandwidth first, on a quiet process: nothing else of this run is resident yet.
    let data: Vec<u64> = (0..(BANDWIDTH_BYTES / 8) as u64).collect();
    let bandwidth = Bandwidth {
        one: read_bandwidth(&data, 1),
        two: read_bandwidth(&data, 2),
    };
    drop(data);
    println!(
        "read bandwidth: {:.2} GB/s with 1 thread, {:.2} GB/s with 2 threads (best of {BANDWIDTH_PASSES} sums of {} MiB)",
        bandwidth.one / 1e9,
        bandwidth.two / 1e9,
        BANDWIDTH_BYTES >> 20
    );

    let configs = configs();
    let mut results = Vec::new();
    let mut skipped = None;
    let builders: [(&str, SceneBuilder); 3] = [("torus", || Ok(torus())), ("asset", asset), ("cube", || Ok(cube()))];
    for (what, build) in builders {
        let scene = match build() {
            Ok(scene) => scene,
            Err(why) => {
                println!("{what} skipped: {why}");
                skipped = Some(why);
                continue;
            }
        };
        let title = scene.title();
        println!("\n{title}");
        let measured = measure(&scene, &configs);
        // The asset's LEGACY run reads V down with flip_v, the C port 1 - v: not comparable bits.
        let mismatches = (scene.parts.iter().all(|p| !p.flip_v)).then(|| legacy_mismatches(&scene));
        let result = SceneResult {
            title,
            short: scene.short.clone(),
            vertices: scene.vertices(),
            bytes: scene.bytes(),
            measured,
            mismatches,
        };
        print!("{}", table(&result, &configs, &bandwidth));
        match mismatches {
            Some(0) => println!("LENGYEL+LEGACY and the C port agree bit for bit"),
            Some(m) => println!("LENGYEL+LEGACY and the C port differ on {m} vertices"),
            None => {}
        }
        println!(
            "bandwidth limit: {} bytes, {} at {:.2} GB/s; {} samples per configuration",
            result.bytes,
            human(Duration::from_secs_f64(result.bytes as f64 / bandwidth.one)),
            bandwidth.one / 1e9,
            result.measured[0].samples
        );
        results.push(result);
    }
    let load_after = load_average();
    let elapsed = started.elapsed();

    let summary = summary(&results, &configs);
    println!("\n{summary}");
    println!(
        "load average: {load_before} at the start, {load_after} at the end; {:.0} s",
        elapsed.as_secs_f64()
    );

    let mut md = String::from(
        "# Benchmark\n\n\
         Reproduce (about 2 minutes on 2 cores; prints the tables and writes this file):\n\n",
    );
    writeln!(md, "```text\n{COMMAND}\n```\n").unwrap();
    writeln!(
        md,
        "Measured on {}. Load average (1, 5, 15 min): {load_before} at the start, {load_after} at \
         the end; the run took {:.0} s. Other work on the machine slows and scatters the times, the \
         two-thread ones most: compare configurations within one run.\n",
        machine(),
        elapsed.as_secs_f64()
    )
    .unwrap();
    writeln!(
        md,
        "Read bandwidth: **{:.2} GB/s** with one thread, {:.2} GB/s with two (the fastest of \
         {BANDWIDTH_PASSES} sums of a {} MiB array of u64).\n",
        bandwidth.one / 1e9,
        bandwidth.two / 1e9,
        BANDWIDTH_BYTES >> 20
    )
    .unwrap();
    md.push_str(
        "How to read the tables:\n\n\
         - **ns/vertex**: the median time of one pass over the scene (every call once) divided by \
         its vertices. Every configuration runs on the same buffers, interleaved round by round; \
         each call allocates its own scratch, as a caller without scratch of its own has it, \
         except in the rows marked *caller scratch*, which pass one buffer allocated before the \
         timing (as the C port allocates its own, those rows show what the allocation costs).\n\
         - **vs C port**: that time over the time of `c_tests/listing.c`, the C port of the listing \
         (compiled by `build.rs` at the profile's optimization level, `-O3` in release, with \
         `-ffp-contract=off`).\n\
         - **share of bandwidth limit**: the time the bytes a per-vertex method must touch take at \
         the read bandwidth above, over the measured time (100% would be a method limited by \
         memory alone). Those bytes: positions 12, normals 12, texture coordinates 8 and the \
         output tangent 16 per vertex, indices 4 per corner (12 per triangle), and the 29 bytes \
         of scratch per vertex (sums and flags) counted twice, written and read back. Rows with \
         two threads use the two-thread bandwidth. The cube fits in the L1 cache, where the share \
         only says how far a call is from streaming its bytes.\n\
         - **spread (IQR)**: the interquartile range of the samples over their median.\n\
         - REJECT refuses a mesh with a degenerate triangle; such rows say so and time the refusal.\n\
         - The asset is one call per primitive, with `flip_v` (glTF stores V down); the C port gets \
         V up (`1 - v`, converted before timing).\n\n",
    );
    for result in &results {
        writeln!(md, "## {}\n", result.title).unwrap();
        writeln!(
            md,
            "Bandwidth limit: {} bytes, {} at {:.2} GB/s. {} samples per configuration{}.\n",
            result.bytes,
            human(Duration::from_secs_f64(result.bytes as f64 / bandwidth.one)),
            bandwidth.one / 1e9,
            result.measured[0].samples,
            if result.vertices < 100 {
                format!(", each the mean of a loop of {CUBE_CALLS} calls")
            } else {
                String::new()
            }
        )
        .unwrap();
        md.push_str(&table(result, &configs, &bandwidth));
        if let Some(m) = result.mismatches {
            if m == 0 {
                md.push_str("\nLENGYEL+LEGACY and the C port agreed bit for bit.\n");
            } else {
                writeln!(md, "\nLENGYEL+LEGACY and the C port differed on {m} vertices.").unwrap();
            }
        }
        md.push('\n');
    }
    if let Some(why) = skipped {
        writeln!(md, "## {ASSET}\n\nSkipped: {why}.\n").unwrap();
    }
    md.push_str("## Summary\n\n");
    md.push_str(&summary);
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/bench.md");
    fs::write(&path, md).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    println!("wrote {}", path.display());
}

/// The goals, each with what this run measured.
fn summary(results: &[SceneResult], configs: &[Config]) -> String {
    let defaults = Options::default();
    let default_name = format!(
        "default ({}+{})",
        upper(defaults.method),
        upper(defaults.degenerate_policy)
    );
    let listing = find(configs, "listing.c (C port)");
    let legacy = find(configs, "LENGYEL+LEGACY");
    let default = find(configs, &default_name);
    let legacy2 = find(configs, "LENGYEL+LEGACY, threads=2");
    let default2 = find(configs, &format!("{default_name}, threads=2"));
    let verdict = |ok: bool| if ok { "met" } else { "not met" };
    let secs = |r: &SceneResult, k: usize| r.measured[k].median.as_secs_f64();

    let mut text = String::from("| goal | scene | measured | |\n|---|---|---:|---|\n");
    for r in results.iter().filter(|r| r.vertices >= 100_000) {
        let ratio = secs(r, legacy) / secs(r, listing);
        writeln!(
            text,
            "| LENGYEL+LEGACY at most 0.6x the C port, one thread | {} | {ratio:.2}x | {} |",
            r.short,
            verdict(ratio <= 0.6)
        )
        .unwrap();
        let ratio = secs(r, default) / secs(r, listing);
        writeln!(
            text,
            "| {default_name} at most 1.0x the C port, one thread | {} | {ratio:.2}x | {} |",
            r.short,
            verdict(ratio <= 1.0)
        )
        .unwrap();
    }
    for r in results {
        for (one, two, name) in [
            (legacy, legacy2, "LENGYEL+LEGACY"),
            (default, default2, default_name.as_str()),
        ] {
            let speedup = secs(r, one) / secs(r, two);
            let goal = if r.vertices >= 100_000 {
                verdict(speedup >= 1.7)
            } else {
                "(below 100k vertices: no goal)"
            };
            writeln!(
                text,
                "| {name}: threads=2 at least 1.7x faster than threads=1 | {} | {speedup:.2}x | {goal} |",
                r.short
            )
            .unwrap();
        }
    }
    for r in results.iter().filter(|r| r.vertices < 100) {
        for (k, config) in configs
            .iter()
            .enumerate()
            .filter(|(_, c)| !matches!(c.generator, Generator::Listing))
        {
            let per_call = r.measured[k].median;
            writeln!(
                text,
                "| {}: under 1 µs per call | {} | {} | {} |",
                config.name,
                r.short,
                human(per_call),
                verdict(per_call < Duration::from_micros(1))
            )
            .unwrap();
        }
        let c = r.measured[listing].median;
        writeln!(
            text,
            "| (listing.c (C port), for reference) | {} | {} | |",
            r.short,
            human(c)
        )
        .unwrap();
    }
    text
}
