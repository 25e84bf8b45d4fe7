//! Speed of every method and policy against the C port of the listing and against the machine's
//! read bandwidth, in one run; and of method MIKKTSPACE against mikktspace.c itself.
//!
//! ```text
//! cargo run --release -p tbasis-compare --example bench [-- [--quick] [FILTER]]
//! cargo run --release -p tbasis-compare --example bench -- --calls COUNT CONFIGURATION [FILTER]
//! cargo run --release -p tbasis-compare --example bench -- --parts ROUNDS CONFIGURATION...
//! ```
//!
//! Scenes: the irregular torus of `docs/chart.md` at about 1M vertices (`crates/test-support/src/scenes.rs`),
//! `../shared/meshes/derived/FlightHelmet.cc1.glb` (a real asset of 849k vertices, one call per
//! primitive; skipped with a message when the corpus is absent) and a 24-vertex cube with a UV
//! square per face (per-call overhead). Last, with configurations of its own, a 1M-vertex grid
//! whose UVs collapse everywhere but on a small island, where policy INHERIT must spread tangents
//! across the whole mesh (its time against SKIP's).
//!
//! `FILTER` runs only the scenes whose name contains it (`torus`, `asset`, `cube`, `grid`) and
//! rewrites no part of `docs/bench.md` but the collapsed grid's section, when it ran. `--quick`
//! times [`QUICK_ROUNDS`] rounds per scene (mikktspace.c in one) and writes `target/bench/bench.md`
//! instead, to check the output in about a minute; its figures are not worth quoting. `--calls`
//! times one configuration (named as in the tables) `COUNT` times in a row in one process and
//! prints every call's time, to show how the times of one configuration move, and the fresh memory
//! a call faults in ([`consecutive_calls`]).
//! `--parts` times configurations on each primitive of the asset apart ([`per_primitive`]), to show
//! which primitives a scene's time comes from.
//!
//! Every configuration runs on the same buffers, interleaved round by round so that a drift in the
//! machine's speed touches them all alike; each time is the median over the rounds. Besides
//! ns/vertex, each result is given as a ratio to the C port of the listing (`c_tests/listing.c`,
//! linked by `build.rs`) and as a share of the bandwidth limit: the time the bytes a per-vertex
//! method must touch take at the read bandwidth measured at the start of the run.
//!
//! Method MIKKTSPACE runs per corner (`generate_corners`), and through mikktspace.c's callback
//! interface (`tbasis::mikktspace::generate_tangents`, whose callbacks read the same arrays as
//! mikktspace.c's), against mikktspace.c through the
//! wrapper the tests use (`crates/test-support/src/mikktspace_reference.rs`, reading the mesh through its
//! index buffer, V up as the C port gets it). Before any timing, each scene's corners from both,
//! with one and two threads and through the callbacks, must agree bit for bit (a NaN matching any NaN), or the run stops.
//! mikktspace.c takes seconds per call on the large scenes: it is timed in only
//! [`SLOW_SAMPLES`] of the rounds. meshoptimizer's `meshopt_generateTangents` runs per corner too,
//! in its MikkTSpace-compatible mode and its default one, with the same V-up coordinates, reading
//! the mesh through its index buffer; its frames are not mikktspace.c's bits and are not checked.
//!
//! Prints the tables, method MIKKTSPACE's ratios to mikktspace.c and meshoptimizer, the goals
//! with what this run measured, and writes `docs/bench.md`.

#[path = "common/fresh_memory.rs"]
mod fresh_memory;
#[path = "../../../c_tests/listing.rs"]
mod listing;
#[path = "common/machine.rs"]
mod machine;
#[path = "common/meshopt_tangents.rs"]
mod meshopt_tangents;

use std::fmt::Write as _;
use std::fs;
use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use fresh_memory::{Faults, Fresh};
use listing::listing_tangents;
use machine::{load_average, machine};
use meshopt::TangentOptions;
use meshopt_tangents::meshopt_tangents;
use mikktspace_reference::Geometry;
use tbasis::mikktspace::generate_tangents;
use tbasis::{
    generate, generate_corners, generate_corners_with_scratch, generate_with_scratch, scratch_size_for,
    DegeneratePolicy, Error, Indices, Mesh, Method, Options, Output, Report, Strided, StridedMut,
};
use tbasis_test_support::{load, mikktspace_reference, scenes};

/// The command, as the report shows it.
const COMMAND: &str = "cargo run --release -p tbasis-compare --example bench";

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

/// Samples of a slow configuration (mikktspace.c: about 3 s per call on the torus), spread over
/// the rounds; the others run in every round.
const SLOW_SAMPLES: usize = 3;

/// Rounds of every scene with `--quick` (the slow configurations in the first only).
const QUICK_ROUNDS: usize = 3;

/// The flag of a quick run.
const QUICK_FLAG: &str = "--quick";

/// The flag of a run of consecutive calls of one configuration ([`consecutive_calls`]).
const CALLS_FLAG: &str = "--calls";

/// The flag of a run per primitive of the asset ([`per_primitive`]).
const PARTS_FLAG: &str = "--parts";

/// A mode that prints its own output, from the arguments after its flag.
type Mode = fn(&[String]) -> Result<(), String>;

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

    /// Triangle corners: one per index.
    fn corners(&self) -> usize {
        self.indices.len()
    }

    /// The part as mikktspace.c's callbacks read it: through the index buffer, V up.
    fn geometry(&self) -> Geometry<'_> {
        Geometry {
            positions: &self.positions,
            normals: &self.normals,
            texcoords: &self.listing_texcoords,
            indices: Some(&self.indices),
        }
    }

    /// The part as the library reads it.
    fn mesh(&self) -> Mesh<'_> {
        Mesh {
            positions: Strided::from_slice(&self.positions),
            normals: Strided::from_slice(&self.normals),
            texcoords: Some(Strided::from_slice(&self.texcoords)),
            indices: Indices::U32(Strided::from_slice(&self.indices)),
        }
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
    /// For the goals and the comparison with mikktspace.c.
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
    Library(Call),
    /// mikktspace.c, one frame per corner: the wrapper's callbacks read the part through its index
    /// buffer, with the C port's V-up texture coordinates (what `flip_v` computes for glTF).
    MikktspaceC,
    /// meshoptimizer's `meshopt_generateTangents`, one frame per corner, with those coordinates too.
    Meshopt(TangentOptions),
    /// `tbasis::mikktspace::generate_tangents`, mikktspace.c's callback interface: the same
    /// callbacks as [`Generator::MikktspaceC`]'s, reading the same arrays.
    Callbacks,
}

impl Generator {
    /// A per-vertex library call with these options, allocating its scratch.
    fn library(options: Options) -> Self {
        Generator::Library(Call {
            options,
            corners: false,
            caller_scratch: false,
        })
    }

    /// Seconds per call on the large scenes: sampled in [`SLOW_SAMPLES`] rounds only.
    fn slow(&self) -> bool {
        matches!(self, Generator::MikktspaceC)
    }

    /// Writes one frame per corner rather than per vertex.
    fn per_corner(&self) -> bool {
        match self {
            Generator::Library(call) => call.corners,
            Generator::MikktspaceC | Generator::Meshopt(_) | Generator::Callbacks => true,
            Generator::Listing => false,
        }
    }

    fn threads(&self) -> usize {
        match self {
            Generator::Library(call) => call.options.threads.max(1) as usize,
            Generator::Listing | Generator::MikktspaceC | Generator::Meshopt(_) | Generator::Callbacks => 1,
        }
    }
}

/// One library call, as a configuration makes it.
#[derive(Clone, Copy)]
struct Call {
    options: Options,
    /// Per corner (`generate_corners`) rather than per vertex (`generate`).
    corners: bool,
    /// With caller scratch, allocated and touched once before the timing: what a caller that
    /// keeps its scratch between calls pays. Otherwise each call allocates its own.
    caller_scratch: bool,
}

struct Config {
    name: String,
    generator: Generator,
}

fn upper(value: impl std::fmt::Debug) -> String {
    format!("{value:?}").to_uppercase()
}

/// The name of method MIKKTSPACE's configuration with `threads` (and caller scratch).
fn mikktspace_name(threads: u32, caller_scratch: bool) -> String {
    let mut name = "MIKKTSPACE per corner".to_string();
    if caller_scratch {
        name.push_str(", caller scratch");
    }
    if threads > 1 {
        name.push_str(&format!(", threads={threads}"));
    }
    name
}

/// Method MIKKTSPACE (policy LEGACY: exactly mikktspace.c) per corner.
fn mikktspace(threads: u32, caller_scratch: bool) -> Generator {
    Generator::Library(Call {
        options: Options::mikktspace().with_threads(threads),
        corners: true,
        caller_scratch,
    })
}

/// The C port first (the reference of every ratio), then every method and policy, the default,
/// all on the calling thread, then two configurations again with two threads; last method
/// MIKKTSPACE per corner, meshoptimizer's two modes and mikktspace.c.
fn configs() -> Vec<Config> {
    let library = |method, policy, threads| {
        Generator::library(
            Options::default()
                .with_method(method)
                .with_policy(policy)
                .with_threads(threads),
        )
    };
    let with_scratch = |options| {
        Generator::Library(Call {
            options,
            corners: false,
            caller_scratch: true,
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
        generator: Generator::library(defaults.with_threads(1)),
    });
    configs.push(Config {
        name: "LENGYEL+LEGACY, caller scratch".to_string(),
        generator: with_scratch(
            defaults
                .with_method(Method::Lengyel)
                .with_policy(DegeneratePolicy::Legacy),
        ),
    });
    configs.push(Config {
        name: format!("{default_name}, caller scratch"),
        generator: with_scratch(defaults),
    });
    configs.push(Config {
        name: "LENGYEL+LEGACY, threads=2".to_string(),
        generator: library(Method::Lengyel, DegeneratePolicy::Legacy, 2),
    });
    configs.push(Config {
        name: format!("{default_name}, threads=2"),
        generator: Generator::library(defaults.with_threads(2)),
    });
    for (threads, caller_scratch) in [(1, false), (1, true), (2, false)] {
        configs.push(Config {
            name: mikktspace_name(threads, caller_scratch),
            generator: mikktspace(threads, caller_scratch),
        });
    }
    for (name, options) in [
        (MESHOPT_COMPATIBLE, TangentOptions::Compatible),
        (MESHOPT, TangentOptions::None),
    ] {
        configs.push(Config {
            name: name.to_string(),
            generator: Generator::Meshopt(options),
        });
    }
    configs.push(Config {
        name: CALLBACKS.to_string(),
        generator: Generator::Callbacks,
    });
    configs.push(Config {
        name: MIKKTSPACE_C.to_string(),
        generator: Generator::MikktspaceC,
    });
    configs
}

/// The name of the callback interface's configuration.
const CALLBACKS: &str = "tbasis::mikktspace callbacks per corner";

/// The name of mikktspace.c's configuration.
const MIKKTSPACE_C: &str = "mikktspace.c per corner";

/// The names of meshoptimizer's configurations: MikkTSpace-compatible, and its default.
const MESHOPT_COMPATIBLE: &str = "meshopt compatible per corner";
const MESHOPT: &str = "meshopt per corner";

/// Index of a configuration by name (the ones the goals compare).
fn find(configs: &[Config], name: &str) -> usize {
    configs
        .iter()
        .position(|c| c.name == name)
        .unwrap_or_else(|| panic!("no configuration {name}"))
}

/// Output buffers for every part of a scene: one frame per vertex, and one per corner.
struct Outputs {
    vertices: Vec<Vec<[f32; 4]>>,
    corners: Vec<Vec<[f32; 4]>>,
}

impl Outputs {
    fn of(scene: &Scene) -> Self {
        let frames = |count: fn(&Part) -> usize| scene.parts.iter().map(|p| vec![[0.0; 4]; count(p)]).collect();
        Outputs {
            vertices: frames(Part::vertices),
            corners: frames(Part::corners),
        }
    }

    /// The buffers `generator` writes.
    fn of_generator(&mut self, generator: Generator) -> &mut [Vec<[f32; 4]>] {
        if generator.per_corner() {
            &mut self.corners
        } else {
            &mut self.vertices
        }
    }
}

/// What [`run`] measured.
struct Timed {
    /// The time of every call.
    time: Duration,
    /// Calls the library refused (policy REJECT on a degenerate triangle).
    refused: usize,
    /// The fresh memory the calls faulted in, where the system tells ([`fresh_memory`]).
    fresh: Option<Fresh>,
}

/// Runs `generator` on every part of `scene`, `calls` times over.
fn run(generator: Generator, scene: &Scene, outputs: &mut Outputs, calls: usize) -> Timed {
    let outputs = outputs.of_generator(generator);
    let mut refused = 0;
    let mut scratch = Vec::new();
    if let Generator::Library(call) = generator {
        if call.caller_scratch {
            let largest = scene
                .parts
                .iter()
                .map(|p| scratch_size_for(&p.mesh(), &call.options).expect("scratch size"));
            scratch = vec![1u8; largest.max().unwrap_or(0)];
        }
    }
    let faults = Faults::now();
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
                Generator::MikktspaceC => {
                    assert!(
                        black_box(mikktspace_reference::generate(part.geometry(), tangents)),
                        "mikktspace.c failed"
                    );
                }
                Generator::Callbacks => {
                    let mut callbacks = Callbacks(part.geometry(), tangents);
                    assert!(black_box(generate_tangents(&mut callbacks)), "generate_tangents failed");
                }
                Generator::Meshopt(options) => {
                    // SAFETY: load.rs and scenes.rs keep every index below the vertex count.
                    unsafe {
                        meshopt_tangents(
                            &part.indices,
                            &part.positions,
                            &part.normals,
                            &part.listing_texcoords,
                            options,
                            tangents,
                        )
                    };
                }
                Generator::Library(call) => {
                    let options = call.options.with_flip_v(part.flip_v);
                    let mesh = part.mesh();
                    let scratch = call.caller_scratch.then_some(scratch.as_mut_slice());
                    let result = if call.corners {
                        let mut corners = StridedMut::from_slice(tangents);
                        match scratch {
                            Some(bytes) => generate_corners_with_scratch(&mesh, &options, &mut corners, bytes),
                            None => generate_corners(&mesh, &options, &mut corners),
                        }
                    } else {
                        let mut output = Output::new(StridedMut::from_slice(tangents));
                        match scratch {
                            Some(bytes) => generate_with_scratch(&mesh, &options, &mut output, bytes),
                            None => generate(&mesh, &options, &mut output),
                        }
                    };
                    match black_box(result) {
                        Ok(_) => {}
                        Err(Error::DegenerateUv { .. }) => refused += 1,
                        Err(e) => panic!("the library refused a benchmark mesh: {e:?}"),
                    }
                }
            }
        }
        black_box(&mut *outputs);
    }
    let time = start.elapsed();
    Timed {
        time,
        refused,
        fresh: faults.zip(Faults::now()).map(|(before, after)| after.since(&before)),
    }
}

/// mikktspace.c's callbacks in Rust, as [`mikktspace_reference`]'s wrapper implements them: each
/// face a triangle read through the index buffer, each tangent stored per corner.
struct Callbacks<'a>(Geometry<'a>, &'a mut [[f32; 4]]);

impl tbasis::mikktspace::Geometry for Callbacks<'_> {
    fn num_faces(&self) -> usize {
        self.0.corner_count() / 3
    }
    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }
    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.0.positions[self.vertex(face, vert)]
    }
    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.0.normals[self.vertex(face, vert)]
    }
    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.0.texcoords[self.vertex(face, vert)]
    }
    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        self.1[3 * face + vert] = tangent;
    }
}

impl Callbacks<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.0
            .indices
            .map_or(3 * face + vert, |indices| indices[3 * face + vert] as usize)
    }
}

/// What one configuration measured on one scene.
struct Measured {
    /// Median time of one pass over the scene (every part once).
    median: Duration,
    /// Interquartile range of the samples, as a share of the median.
    spread: f64,
    /// The fastest pass: the least disturbed by other work on the machine.
    fastest: Duration,
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

/// The quantiles `qs` of `samples`, which this sorts.
fn quantiles<const N: usize>(samples: &mut [f64], qs: [f64; N]) -> [f64; N] {
    samples.sort_by(f64::total_cmp);
    qs.map(|q| quantile(samples, q))
}

/// Times every configuration on `scene`, round by round (a slow one in [`SLOW_SAMPLES`] of them;
/// with `quick`, [`QUICK_ROUNDS`] rounds and a slow one in the first).
fn measure(scene: &Scene, configs: &[Config], quick: bool) -> Vec<Measured> {
    let mut outputs = Outputs::of(scene);
    let calls = if scene.small { CUBE_CALLS } else { 1 };
    // A first round warms caches, allocator and page tables, and sizes the rounds from the
    // configurations that run in every round (the slow ones ran in the check before).
    let round: f64 = configs
        .iter()
        .filter(|c| !c.generator.slow())
        .map(|c| run(c.generator, scene, &mut outputs, calls).time.as_secs_f64())
        .sum();
    let rounds = if quick {
        QUICK_ROUNDS
    } else if scene.small {
        CUBE_ROUNDS
    } else {
        ((LARGE_SCENE_BUDGET.as_secs_f64() / round.max(1e-9)) as usize).clamp(MIN_ROUNDS, MAX_ROUNDS)
    };
    let slow_every = rounds.div_ceil(if quick { 1 } else { SLOW_SAMPLES });
    let mut samples = vec![Vec::with_capacity(rounds); configs.len()];
    let mut refused = vec![0; configs.len()];
    for r in 0..rounds {
        for (k, config) in configs.iter().enumerate() {
            if config.generator.slow() && r % slow_every != 0 {
                continue;
            }
            let Timed {
                time,
                refused: refusals,
                ..
            } = run(config.generator, scene, &mut outputs, calls);
            samples[k].push(time.as_secs_f64() / calls as f64);
            refused[k] = refusals / calls;
        }
    }
    samples
        .into_iter()
        .zip(refused)
        .map(|(mut s, refused)| {
            let [q1, median, q3] = quantiles(&mut s, [0.25, 0.5, 0.75]);
            Measured {
                median: Duration::from_secs_f64(median),
                spread: (q3 - q1) / median,
                fastest: Duration::from_secs_f64(s[0]),
                samples: s.len(),
                refused,
                calls: scene.parts.len(),
            }
        })
        .collect()
}

/// `--calls COUNT CONFIGURATION [FILTER]`: one process calls the configuration the tables name
/// CONFIGURATION `COUNT` times in a row on the torus, the asset and the cube (or those whose name
/// contains FILTER), after an untimed call, and prints each call's time in order, then their
/// quartiles and the median call's fresh memory (Linux: [`fresh_memory`]; the huge pages are
/// counted over the whole system, so other work on the machine adds to it).
/// The tables give medians over rounds; this shows how one configuration's times move within a
/// process. Writes nothing.
fn consecutive_calls(args: &[String]) -> Result<(), String> {
    let usage = || format!("usage: bench {CALLS_FLAG} COUNT CONFIGURATION [FILTER]");
    let (Some(count), Some(name), None) = (
        args.first().and_then(|n| n.parse::<usize>().ok()).filter(|&n| n > 0),
        args.get(1),
        args.get(3),
    ) else {
        return Err(usage());
    };
    let configs = configs();
    let config = named(&configs, name, &usage())?;
    let filter = args.get(2);
    println!("{}; load average {}", machine(), load_average());
    let builders: [(&str, SceneBuilder); 3] = [("torus", || Ok(torus())), ("asset", asset), ("cube", || Ok(cube()))];
    for (what, build) in builders {
        if filter.is_some_and(|f| !what.contains(f.as_str())) {
            continue;
        }
        let scene = build().map_err(|why| format!("{what}: {why}"))?;
        let mut outputs = Outputs::of(&scene);
        run(config.generator, &scene, &mut outputs, 1);
        let per_vertex = |time: Duration| ns(time) / scene.vertices() as f64;
        let mut fresh = Vec::with_capacity(count);
        let times: Vec<f64> = (0..count)
            .map(|_| {
                let timed = run(config.generator, &scene, &mut outputs, 1);
                fresh.extend(timed.fresh);
                per_vertex(timed.time)
            })
            .collect();
        println!(
            "\n{}\n{name}, {count} calls in a row, ns/vertex in order:",
            scene.title()
        );
        for row in times.chunks(12) {
            let row: Vec<String> = row.iter().map(|t| format!("{t:.1}")).collect();
            println!("  {}", row.join(" "));
        }
        let mut times = times;
        let [low, q1, median, q3, high] = quantiles(&mut times, [0.0, 0.25, 0.5, 0.75, 1.0]);
        println!("fastest {low:.1}, quartiles {q1:.1} / {median:.1} / {q3:.1}, slowest {high:.1}");
        if fresh.len() == count {
            fresh.sort_by_key(Fresh::bytes);
            let median = &fresh[count / 2];
            println!(
                "fresh memory faulted in per call (median): {:.1} MiB, {} faults of a huge page and {} of a base page",
                median.bytes() as f64 / f64::from(1 << 20),
                median.huge_faults,
                median.other_faults
            );
        }
    }
    Ok(())
}

/// The configuration the tables call `name`, or `usage` and the names there are.
fn named<'c>(configs: &'c [Config], name: &str, usage: &str) -> Result<&'c Config, String> {
    configs.iter().find(|c| c.name == name).ok_or_else(|| {
        let names: Vec<&str> = configs.iter().map(|c| c.name.as_str()).collect();
        format!("{usage}\nno configuration {name:?}; they are: {}", names.join("; "))
    })
}

/// `--parts ROUNDS CONFIGURATION...`: the configurations the tables name on each primitive of the
/// asset, each primitive its own scene: `ROUNDS` rounds after an untimed one, every configuration
/// and primitive once per round, interleaved as in the tables. Prints a Markdown table of median
/// ns/vertex per primitive, with each configuration's time over the first's. Writes nothing.
fn per_primitive(args: &[String]) -> Result<(), String> {
    let usage = || format!("usage: bench {PARTS_FLAG} ROUNDS CONFIGURATION...");
    let Some(rounds) = args.first().and_then(|n| n.parse::<usize>().ok()).filter(|&n| n > 0) else {
        return Err(usage());
    };
    let all = configs();
    let chosen = args[1..]
        .iter()
        .map(|name| named(&all, name, &usage()))
        .collect::<Result<Vec<_>, _>>()?;
    if chosen.is_empty() {
        return Err(usage());
    }
    let asset = asset().map_err(|why| format!("asset: {why}"))?;
    println!("{}; load average {}", machine(), load_average());
    println!("\n{}", asset.title());
    let scenes: Vec<Scene> = asset
        .parts
        .into_iter()
        .map(|part| Scene {
            name: asset.name.clone(),
            short: asset.short.clone(),
            parts: vec![part],
            small: false,
        })
        .collect();
    let mut outputs: Vec<Outputs> = scenes.iter().map(Outputs::of).collect();
    // samples[primitive][configuration], and the configurations that refused a primitive.
    let mut samples = vec![vec![Vec::new(); chosen.len()]; scenes.len()];
    let mut refusals = Vec::new();
    for round in 0..=rounds {
        for (p, (scene, outputs)) in scenes.iter().zip(outputs.iter_mut()).enumerate() {
            for (k, config) in chosen.iter().enumerate() {
                let Timed { time, refused, .. } = run(config.generator, scene, outputs, 1);
                if round == 0 && refused > 0 {
                    refusals.push(format!(
                        "{} refused primitive {p}: its times are the refusal's",
                        config.name
                    ));
                }
                if round > 0 {
                    samples[p][k].push(ns(time) / scene.vertices() as f64);
                }
            }
        }
    }
    let mut header = "| primitive | vertices | corners |".to_string();
    let mut rule = "|---:|---:|---:|".to_string();
    for config in &chosen {
        write!(header, " {} ns/vertex |", config.name).unwrap();
        rule.push_str("---:|");
    }
    for config in &chosen[1..] {
        write!(header, " {} / {} |", config.name, chosen[0].name).unwrap();
        rule.push_str("---:|");
    }
    println!("\n{rounds} rounds, median ns/vertex per primitive:\n\n{header}\n{rule}");
    for (p, (scene, samples)) in scenes.iter().zip(&mut samples).enumerate() {
        let medians: Vec<f64> = samples.iter_mut().map(|times| quantiles(times, [0.5])[0]).collect();
        let part = &scene.parts[0];
        let mut row = format!("| {p} | {} | {} |", part.vertices(), part.corners());
        for median in &medians {
            write!(row, " {median:.1} |").unwrap();
        }
        for median in &medians[1..] {
            write!(row, " {:.2}x |", median / medians[0]).unwrap();
        }
        println!("{row}");
    }
    for refusal in refusals {
        println!("\n{refusal}");
    }
    Ok(())
}

/// Vertices where LENGYEL+LEGACY and the C port differ in any bit (the library promises none).
fn legacy_mismatches(scene: &Scene) -> usize {
    let mut mine = Outputs::of(scene);
    let mut theirs = Outputs::of(scene);
    run(Generator::library(Options::legacy()), scene, &mut mine, 1);
    run(Generator::Listing, scene, &mut theirs, 1);
    mine.vertices
        .iter()
        .flatten()
        .zip(theirs.vertices.iter().flatten())
        .filter(|(a, b)| a.map(f32::to_bits) != b.map(f32::to_bits))
        .count()
}

/// Equal bits, a NaN matching any NaN: which NaN an operation on NaN operands returns is fixed
/// neither by C nor by Rust.
fn same_frame(a: [f32; 4], b: [f32; 4]) -> bool {
    (0..4).all(|k| a[k].to_bits() == b[k].to_bits() || (a[k].is_nan() && b[k].is_nan()))
}

/// Checks that method MIKKTSPACE per corner, with one and with two threads, gives mikktspace.c's
/// bits on every corner of `scene`, as the timed calls compute them; stops the run otherwise.
/// Returns the corners compared.
fn check_mikktspace(scene: &Scene) -> usize {
    let mut reference = Outputs::of(scene);
    run(Generator::MikktspaceC, scene, &mut reference, 1);
    for (name, generator) in [
        (mikktspace_name(1, false), mikktspace(1, false)),
        (mikktspace_name(2, false), mikktspace(2, false)),
        (CALLBACKS.to_string(), Generator::Callbacks),
    ] {
        let mut ours = Outputs::of(scene);
        run(generator, scene, &mut ours, 1);
        for (p, (mine, theirs)) in ours.corners.iter().zip(&reference.corners).enumerate() {
            if let Some(c) = (0..mine.len()).find(|&c| !same_frame(mine[c], theirs[c])) {
                panic!(
                    "{}, part {p}, corner {c}: {name} gives {:?}, mikktspace.c {:?}",
                    scene.name, mine[c], theirs[c]
                );
            }
        }
    }
    scene.parts.iter().map(Part::corners).sum()
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
    /// Corners on which MIKKTSPACE and mikktspace.c were checked equal before the timing.
    mikktspace_corners: usize,
}

impl SceneResult {
    /// How many samples the configurations have: every round's, and the slow ones'.
    fn samples(&self, configs: &[Config]) -> String {
        let slow = configs.iter().position(|c| c.generator.slow());
        let every = self.measured[0].samples;
        match slow.map(|k| self.measured[k].samples) {
            Some(fewer) if fewer != every => format!("{every} samples per configuration ({MIKKTSPACE_C}: {fewer})"),
            _ => format!("{every} samples per configuration"),
        }
    }
}

fn ns(d: Duration) -> f64 {
    d.as_secs_f64() * 1e9
}

/// One scene's table, Markdown.
fn table(result: &SceneResult, configs: &[Config], bandwidth: &Bandwidth) -> String {
    let listing = &result.measured[find(configs, "listing.c (C port)")];
    let mut text = String::from(
        "| configuration | ns/vertex | vs C port | share of bandwidth limit | per pass | spread (IQR) | fastest |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
    );
    for (config, m) in configs.iter().zip(&result.measured) {
        let threads = config.generator.threads();
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
            "| {name} | {:.2} | {:.2}x | {:.0}% | {} | {:.1}% | {:.2} |",
            ns(m.median) / result.vertices as f64,
            m.median.as_secs_f64() / listing.median.as_secs_f64(),
            100.0 * limit / m.median.as_secs_f64(),
            human(m.median),
            100.0 * m.spread,
            ns(m.fastest) / result.vertices as f64
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
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mode: Option<Mode> = match args.first().map(String::as_str) {
        Some(CALLS_FLAG) => Some(consecutive_calls),
        Some(PARTS_FLAG) => Some(per_primitive),
        _ => None,
    };
    if let Some(mode) = mode {
        if let Err(why) = mode(&args[1..]) {
            eprintln!("{why}");
            std::process::exit(2);
        }
        return;
    }
    let quick = args.iter().any(|a| a == QUICK_FLAG);
    let filter = args.iter().find(|a| *a != QUICK_FLAG).cloned();
    if args.len() > usize::from(quick) + 1 || filter.as_deref().is_some_and(|f| f.starts_with('-')) {
        eprintln!(
            "usage: bench [{QUICK_FLAG}] [FILTER] | {CALLS_FLAG} COUNT CONFIGURATION [FILTER] | {PARTS_FLAG} ROUNDS \
             CONFIGURATION..."
        );
        std::process::exit(2);
    }
    // A quick run checks the output: it leaves the record in docs/ alone.
    let out_dir =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(if quick { "../../target/bench" } else { "../../docs" });
    fs::create_dir_all(&out_dir).unwrap_or_else(|e| panic!("{}: {e}", out_dir.display()));
    let out_path = out_dir.join("bench.md");
    let selected = |what: &str| filter.as_deref().is_none_or(|f| what.contains(f));
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
        if !selected(what) {
            continue;
        }
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
        let mikktspace_corners = check_mikktspace(&scene);
        println!("MIKKTSPACE (threads 1 and 2) and mikktspace.c agree on all {mikktspace_corners} corners");
        let measured = measure(&scene, &configs, quick);
        // The asset's LEGACY run reads V down with flip_v, the C port 1 - v: not comparable bits.
        let mismatches = (scene.parts.iter().all(|p| !p.flip_v)).then(|| legacy_mismatches(&scene));
        let result = SceneResult {
            title,
            short: scene.short.clone(),
            vertices: scene.vertices(),
            bytes: scene.bytes(),
            measured,
            mismatches,
            mikktspace_corners,
        };
        print!("{}", table(&result, &configs, &bandwidth));
        println!("{}", mikktspace_ratios(&result, &configs));
        match mismatches {
            Some(0) => println!("LENGYEL+LEGACY and the C port agree bit for bit"),
            Some(m) => println!("LENGYEL+LEGACY and the C port differ on {m} vertices"),
            None => {}
        }
        println!(
            "bandwidth limit: {} bytes, {} at {:.2} GB/s; {}",
            result.bytes,
            human(Duration::from_secs_f64(result.bytes as f64 / bandwidth.one)),
            bandwidth.one / 1e9,
            result.samples(&configs)
        );
        results.push(result);
    }
    let grid = selected("grid").then(|| grid_section(quick));
    let load_after = load_average();
    let elapsed = started.elapsed();
    if filter.is_some() {
        if let Some(section) = grid {
            // A first quick run has no file yet: the section alone then.
            let old = fs::read_to_string(&out_path).unwrap_or_default();
            fs::write(&out_path, with_grid_section(&old, &section))
                .unwrap_or_else(|e| panic!("{}: {e}", out_path.display()));
            println!("rewrote the collapsed grid's section of {}", out_path.display());
        }
        return;
    }

    let goals = goals(&results, &configs);
    let against_c = mikktspace_table(&results, &configs);
    println!("\n{against_c}\n{goals}");
    println!(
        "load average: {load_before} at the start, {load_after} at the end; {:.0} s",
        elapsed.as_secs_f64()
    );

    let mut md = String::from(
        "# Benchmark\n\n\
         Reproduce (a few minutes on 2 cores, this run's time below; prints the tables and writes this file):\n\n",
    );
    writeln!(md, "```text\n{COMMAND}\n```\n").unwrap();
    writeln!(
        md,
        "`{COMMAND} -- {QUICK_FLAG}` times {QUICK_ROUNDS} rounds per scene and writes \
         `target/bench/bench.md` instead: a check of the output, not a measurement.\n"
    )
    .unwrap();
    if quick {
        writeln!(md, "**This is such a quick run: its figures are not worth quoting.**\n").unwrap();
    }
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
         - **fastest**: the fastest sample's ns/vertex, the one other work on the machine slowed least.\n\
         - REJECT refuses a mesh with a degenerate triangle; such rows say so and time the refusal.\n\
         - The asset is one call per primitive, with `flip_v` (glTF stores V down); the C port gets \
         V up (`1 - v`, converted before timing).\n\
         - **MIKKTSPACE per corner**: method MIKKTSPACE with policy LEGACY (`Options::mikktspace()`, \
         exactly mikktspace.c), one frame per triangle corner (`generate_corners`). \
         **mikktspace.c per corner**: mikktspace.c itself (`mikktspace-sys`, built by `cc` at `-O3`) \
         through `crates/test-support/src/mikktspace_reference.rs`, whose callbacks read the mesh through its \
         index buffer with the C port's V-up coordinates; it allocates its own memory on every call. \
         **meshopt compatible per corner** and **meshopt per corner**: meshoptimizer's \
         `meshopt_generateTangents` (the `meshopt` crate, 0.7.0), in its MikkTSpace-compatible mode \
         (`TangentOptions::Compatible`, not mikktspace.c's bits) and its default one, called \
         directly so that it writes into the caller's buffer, reading the mesh through its index \
         buffer with the same V-up coordinates. All write into one buffer of a frame per corner \
         allocated before the timing; their ns/vertex are still per vertex. mikktspace.c is timed \
         in a few rounds only, spread over the run (seconds per call on the large scenes).\n\n",
    );
    for result in &results {
        writeln!(md, "## {}\n", result.title).unwrap();
        writeln!(
            md,
            "Bandwidth limit: {} bytes, {} at {:.2} GB/s. {}{}.\n",
            result.bytes,
            human(Duration::from_secs_f64(result.bytes as f64 / bandwidth.one)),
            bandwidth.one / 1e9,
            result.samples(&configs),
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
        writeln!(
            md,
            "\nMIKKTSPACE (threads 1 and 2) and mikktspace.c agreed bit for bit on all {} corners, \
             checked before the timing.",
            result.mikktspace_corners
        )
        .unwrap();
        writeln!(md, "\n{}", mikktspace_ratios(result, &configs)).unwrap();
        md.push('\n');
    }
    if let Some(why) = skipped {
        writeln!(md, "## {ASSET}\n\nSkipped: {why}.\n").unwrap();
    }
    if let Some(section) = grid {
        md.push_str(&section);
    }
    md.push_str("## MIKKTSPACE against mikktspace.c\n\n");
    md.push_str(&against_c);
    md.push_str(
        "\n## Goals\n\n\
         Each cell: the ratio of the two median times the goal compares, measured in this run, and \
         whether it meets the goal; when it does not, by how much: how many times shorter the time \
         the goal is about (the faster side, or the one held to a bound) would have to be. In \
         brackets, the same ratio of the two fastest samples.\n\n",
    );
    md.push_str(&goals);
    fs::write(&out_path, md).unwrap_or_else(|e| panic!("{}: {e}", out_path.display()));
    println!("wrote {}", out_path.display());
}

/// Per scene, mikktspace.c's time and how many times as long it takes as each configuration of
/// method MIKKTSPACE.
fn mikktspace_table(results: &[SceneResult], configs: &[Config]) -> String {
    let reference = find(configs, MIKKTSPACE_C);
    let mut text = String::from(
        "| scene | configuration | ns/vertex | per pass | mikktspace.c / this |\n|---|---|---:|---:|---:|\n",
    );
    for r in results {
        let c = r.measured[reference].median;
        for (config, m) in configs
            .iter()
            .zip(&r.measured)
            .filter(|(c, _)| c.generator.per_corner())
        {
            writeln!(
                text,
                "| {} | {} | {:.1} | {} | {:.1}x |",
                r.short,
                config.name,
                ns(m.median) / r.vertices as f64,
                human(m.median),
                c.as_secs_f64() / m.median.as_secs_f64()
            )
            .unwrap();
        }
    }
    text
}

/// Method MIKKTSPACE per corner on one thread against the other per-corner generators, from the
/// medians of this run: how many times faster (or slower) than each.
fn mikktspace_ratios(result: &SceneResult, configs: &[Config]) -> String {
    let time = |name: &str| result.measured[find(configs, name)].median.as_secs_f64();
    let ours = time(&mikktspace_name(1, false));
    let against: Vec<String> = [MIKKTSPACE_C, MESHOPT_COMPATIBLE, MESHOPT]
        .into_iter()
        .map(|name| {
            let ratio = time(name) / ours;
            if ratio >= 1.0 {
                format!("{ratio:.2}x faster than {name}")
            } else {
                format!("{:.2}x slower than {name}", 1.0 / ratio)
            }
        })
        .collect();
    format!(
        "{} (one thread), from the medians of this run: {}.",
        mikktspace_name(1, false),
        against.join("; ")
    )
}

/// What a goal asks of a ratio of two median times.
#[derive(Clone, Copy)]
enum Bound {
    AtLeast(f64),
    /// Strictly more: "faster than".
    Above(f64),
    AtMost(f64),
}

impl Bound {
    /// "met", or "missed by F": F is how many times shorter the time the goal is about would have
    /// to be (the one in the ratio's denominator for a lower bound, in its numerator for an upper).
    fn verdict(self, ratio: f64) -> String {
        let (met, short_by) = match self {
            Bound::AtLeast(goal) => (ratio >= goal, goal / ratio),
            Bound::Above(goal) => (ratio > goal, goal / ratio),
            Bound::AtMost(goal) => (ratio <= goal, ratio / goal),
        };
        if met {
            "met".to_string()
        } else {
            format!("missed by {short_by:.2}x")
        }
    }
}

/// A speed goal: the median time of configuration `numerator` over that of `denominator`, within
/// `bound`.
struct Goal {
    text: String,
    numerator: usize,
    denominator: usize,
    bound: Bound,
}

/// Scenes this small have no goal but the cube's per-call one.
const GOAL_VERTICES: usize = 100_000;

/// Two threads against one: the speedup every threaded configuration should reach.
const THREAD_SPEEDUP_GOAL: f64 = 1.8;

/// The goals on the large scenes, one row each with a column per scene; then, on the cube, each
/// per-vertex configuration's time per call against its goal of 1 µs.
fn goals(results: &[SceneResult], configs: &[Config]) -> String {
    let defaults = Options::default();
    let default_name = format!(
        "default ({}+{})",
        upper(defaults.method),
        upper(defaults.degenerate_policy)
    );
    let listing = find(configs, "listing.c (C port)");
    let legacy = find(configs, "LENGYEL+LEGACY");
    let default = find(configs, &default_name);
    let mikktspace = find(configs, &mikktspace_name(1, false));
    let goal = |text: String, numerator: usize, denominator: usize, bound: Bound| Goal {
        text,
        numerator,
        denominator,
        bound,
    };
    let mut list = vec![
        goal(
            "LENGYEL+LEGACY at most 1.0x the C port's time, one thread".to_string(),
            legacy,
            listing,
            Bound::AtMost(1.0),
        ),
        goal(
            format!("{default_name} at most 2.5x the C port's time, one thread"),
            default,
            listing,
            Bound::AtMost(2.5),
        ),
        goal(
            "MIKKTSPACE per corner at least 20x faster than mikktspace.c, one thread".to_string(),
            find(configs, MIKKTSPACE_C),
            mikktspace,
            Bound::AtLeast(20.0),
        ),
        goal(
            "MIKKTSPACE per corner faster than meshopt compatible, one thread".to_string(),
            find(configs, MESHOPT_COMPATIBLE),
            mikktspace,
            Bound::Above(1.0),
        ),
        goal(
            format!("{CALLBACKS} at least 10x faster than mikktspace.c, one thread"),
            find(configs, MIKKTSPACE_C),
            find(configs, CALLBACKS),
            Bound::AtLeast(10.0),
        ),
        goal(
            format!("{CALLBACKS} at most 1.3x MIKKTSPACE per corner's time, one thread"),
            find(configs, CALLBACKS),
            mikktspace,
            Bound::AtMost(1.3),
        ),
    ];
    for (name, one) in [
        (mikktspace_name(1, false), mikktspace),
        (default_name.clone(), default),
        ("LENGYEL+LEGACY".to_string(), legacy),
    ] {
        list.push(goal(
            format!("{name}: threads=2 at least {THREAD_SPEEDUP_GOAL}x faster than threads=1"),
            one,
            find(configs, &format!("{name}, threads=2")),
            Bound::AtLeast(THREAD_SPEEDUP_GOAL),
        ));
    }

    let large: Vec<&SceneResult> = results.iter().filter(|r| r.vertices >= GOAL_VERTICES).collect();
    let mut text = String::from("| goal |");
    for r in &large {
        write!(text, " {} |", r.short).unwrap();
    }
    text.push_str("\n|---|");
    text.push_str(&"---|".repeat(large.len()));
    text.push('\n');
    for g in &list {
        write!(text, "| {} |", g.text).unwrap();
        for r in &large {
            let (top, bottom) = (&r.measured[g.numerator], &r.measured[g.denominator]);
            let ratio = top.median.as_secs_f64() / bottom.median.as_secs_f64();
            let fastest = top.fastest.as_secs_f64() / bottom.fastest.as_secs_f64();
            write!(
                text,
                " {ratio:.2}x: {} (fastest passes: {fastest:.2}x) |",
                g.bound.verdict(ratio)
            )
            .unwrap();
        }
        text.push('\n');
    }

    for r in results.iter().filter(|r| r.vertices < GOAL_VERTICES) {
        writeln!(
            text,
            "\n{}, goal: every per-vertex configuration under 1 µs per call.\n\n\
             | configuration | per call | |\n|---|---:|---|",
            r.short
        )
        .unwrap();
        let per_vertex = configs
            .iter()
            .enumerate()
            .filter(|(_, c)| matches!(c.generator, Generator::Library(call) if !call.corners));
        for (k, config) in per_vertex {
            let per_call = r.measured[k].median;
            writeln!(
                text,
                "| {} | {} | {} |",
                config.name,
                human(per_call),
                Bound::AtMost(1e-6).verdict(per_call.as_secs_f64())
            )
            .unwrap();
        }
        writeln!(
            text,
            "| (listing.c (C port), for reference) | {} | |",
            human(r.measured[listing].median)
        )
        .unwrap();
    }
    text
}

/// Vertices along each side of the collapsed grid.
const GRID_SIDE: usize = 1000;

/// Vertices along each side of its island of distinct UVs, in one corner.
const ISLAND_SIDE: usize = 8;

/// The heading of the collapsed grid's section, by which a filtered run finds it.
const GRID_HEADING: &str = "## Collapsed grid";

/// A flat square grid of [`GRID_SIDE`]^2 vertices whose UVs all collapse to one point except on an
/// [`ISLAND_SIDE`]^2 island in a corner: under SKIP nearly every vertex gets the fallback frame;
/// under INHERIT the island's tangents spread over the whole grid, one ring of vertices at a time.
fn collapsed_grid() -> Scene {
    let n = GRID_SIDE;
    let mut part = Part {
        positions: Vec::with_capacity(n * n),
        normals: vec![[0.0, 0.0, 1.0]; n * n],
        texcoords: Vec::with_capacity(n * n),
        listing_texcoords: Vec::new(),
        indices: Vec::with_capacity(6 * (n - 1) * (n - 1)),
        flip_v: false,
    };
    let step = 1.0 / (n - 1) as f32;
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f32 * step, j as f32 * step);
            part.positions.push([x, y, 0.0]);
            let island = i < ISLAND_SIDE && j < ISLAND_SIDE;
            part.texcoords.push(if island { [x, y] } else { [0.5, 0.5] });
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = (j * n + i) as u32;
            let (right, up) = (v + 1, v + n as u32);
            part.indices.extend_from_slice(&[v, right, up + 1, v, up + 1, up]);
        }
    }
    part.listing_texcoords = part.texcoords.clone();
    Scene {
        name: "Collapsed grid".to_string(),
        short: "grid".to_string(),
        parts: vec![part],
        small: false,
    }
}

/// SKIP and INHERIT with the default method, on the calling thread, allocating their scratch.
fn grid_configs() -> Vec<Config> {
    let method = Options::default().method;
    [DegeneratePolicy::Skip, DegeneratePolicy::Inherit]
        .into_iter()
        .map(|policy| Config {
            name: format!("{}+{}", upper(method), upper(policy)),
            generator: Generator::library(
                Options::default()
                    .with_method(method)
                    .with_policy(policy)
                    .with_threads(1),
            ),
        })
        .collect()
}

/// The report of one call of `config` on the scene's only part.
fn report_of(config: &Config, scene: &Scene) -> Report {
    let Generator::Library(call) = config.generator else {
        unreachable!("library configurations only")
    };
    let part = &scene.parts[0];
    let mut tangents = vec![[0.0f32; 4]; part.vertices()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: None,
    };
    tbasis::generate(&part.mesh(), &call.options, &mut output).expect("the collapsed grid is valid")
}

/// Times SKIP and INHERIT on the collapsed grid (`quick`: see [`measure`]), prints the table and
/// returns the section of `docs/bench.md` (its own command and load, since a filtered run rewrites
/// it alone).
fn grid_section(quick: bool) -> String {
    let load_before = load_average();
    let scene = collapsed_grid();
    let title = scene.title();
    println!("\n{title}");
    let configs = grid_configs();
    let reports: Vec<Report> = configs.iter().map(|c| report_of(c, &scene)).collect();
    let measured = measure(&scene, &configs, quick);
    let load_after = load_average();
    let skip = measured[0].median.as_secs_f64();
    let mut table = String::from(
        "| configuration | ns/vertex | vs SKIP | per pass | spread (IQR) | inherited | fallback |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
    );
    for ((config, m), report) in configs.iter().zip(&measured).zip(&reports) {
        writeln!(
            table,
            "| {} | {:.2} | {:.2}x | {} | {:.1}% | {} | {} |",
            config.name,
            ns(m.median) / scene.vertices() as f64,
            m.median.as_secs_f64() / skip,
            human(m.median),
            100.0 * m.spread,
            report.inherited_vertices,
            report.fallback_vertices
        )
        .unwrap();
    }
    let ratio = measured[1].median.as_secs_f64() / skip;
    let goal = format!(
        "Goal: INHERIT within 3x SKIP's time. Measured {ratio:.2}x: {}.",
        if ratio <= 3.0 { "met" } else { "not met" }
    );
    print!("{table}");
    println!("{goal}");

    let mut md = format!(
        "{GRID_HEADING}: {} vertices, {} triangles\n\n",
        scene.vertices(),
        scene.triangles()
    );
    writeln!(
        md,
        "A flat grid whose UVs collapse to one point everywhere but on an island of {ISLAND_SIDE} x \
         {ISLAND_SIDE} vertices in a corner. SKIP gives every vertex without a tangent of its own the fallback frame; \
         INHERIT spreads the island's tangents across the grid, one ring of vertices at a time ({} rings \
         to the farthest vertex). Reproduce this section alone (it rewrites only this section):\n\n\
         ```text\n{COMMAND} -- grid\n```\n\n\
         Measured on {}. Load average (1, 5, 15 min): {load_before} at the start, {load_after} at the end. \
         {}; each call allocates its scratch.\n",
        GRID_SIDE - ISLAND_SIDE,
        machine(),
        samples_of(&measured),
    )
    .unwrap();
    md.push_str(&table);
    writeln!(md, "\n{goal}\n").unwrap();
    md
}

/// "N samples per configuration", from the first configuration's samples.
fn samples_of(measured: &[Measured]) -> String {
    format!("{} samples per configuration", measured[0].samples)
}

/// `doc` with its collapsed grid section replaced by `section`, or `section` inserted before the
/// comparison with mikktspace.c (at the end when that is absent).
fn with_grid_section(doc: &str, section: &str) -> String {
    let start = doc.find(GRID_HEADING);
    let insert_at = start
        .or_else(|| doc.find("## MIKKTSPACE against mikktspace.c"))
        .unwrap_or(doc.len());
    let end = match start {
        Some(start) => doc[start + 1..]
            .find("\n## ")
            .map_or(doc.len(), |at| start + 1 + at + 1),
        None => insert_at,
    };
    format!("{}{section}{}", &doc[..insert_at], &doc[end..])
}
