//! Times `tbasis-gltf --overwrite` end to end (process start to file written) on
//! FlightHelmet.cc1.glb from the corpus and on a generated 1M-vertex torus, against
//! `npx @gltf-transform/cli@4.5 tangents --overwrite` when npx is installed:
//!
//! ```sh
//! cargo build --release -p tbasis-gltf --examples --bins
//! cargo run --release -p tbasis-gltf --example gltf_bench
//! ```
//!
//! Prints a Markdown table (docs/gltf.md records a run). Each command runs once untimed (the
//! first run of a file pays for what the ones after find ready: the input in the page cache,
//! npx's package lookup), then `RUNS` times, the two tools taking turns; the table gives the
//! median.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

const RUNS: usize = 3;

fn main() {
    let dir = std::env::temp_dir().join("tbasis-gltf-bench");
    std::fs::create_dir_all(&dir).expect("create the bench folder");
    let tool = tool_path();
    assert!(tool.is_file(), "build it first: cargo build --release -p tbasis-gltf");

    let mut inputs = Vec::new();
    let helmet = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes/derived/FlightHelmet.cc1.glb");
    if helmet.is_file() {
        inputs.push(("FlightHelmet.cc1.glb (848,870 vertices)".to_string(), helmet));
    } else {
        eprintln!("{} is missing: the corpus row is left out", helmet.display());
    }
    let (torus, vertices) = write_torus(&dir, 1024, 1024);
    inputs.push((format!("torus.glb ({vertices} vertices, generated)"), torus));

    let npx = Command::new("npx")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    println!("| file | tbasis-gltf | gltf-transform 4.5 `tangents` | ratio |");
    println!("|---|---:|---:|---:|");
    for (name, input) in &inputs {
        let mut ours = || {
            let out = dir.join("tbasis-out.glb");
            let status = Command::new(&tool)
                .args(["--overwrite", "-q"])
                .arg(input)
                .arg("-o")
                .arg(&out)
                .status();
            status.is_ok_and(|s| s.success())
        };
        let mut theirs = || {
            let out = dir.join("gltf-transform-out.glb");
            let status = Command::new("npx")
                .args(["--yes", "@gltf-transform/cli@4.5", "tangents"])
                .arg(input)
                .arg(&out)
                .arg("--overwrite")
                .stdout(std::process::Stdio::null())
                .status();
            status.is_ok_and(|s| s.success())
        };
        let mut commands: Vec<&mut dyn FnMut() -> bool> = vec![&mut ours];
        if npx {
            commands.push(&mut theirs);
        }
        let times = medians(&mut commands);
        let seconds = |d: Option<Duration>| d.map_or("failed".into(), |d| format!("{:.2} s", d.as_secs_f64()));
        let (ours, theirs) = (times[0], times.get(1).copied());
        let (theirs_text, ratio) = match theirs {
            Some(theirs) => (
                seconds(theirs),
                match (ours, theirs) {
                    (Some(a), Some(b)) => format!("{:.1}x", b.as_secs_f64() / a.as_secs_f64()),
                    _ => "-".into(),
                },
            ),
            None => ("npx not installed".into(), "-".into()),
        };
        println!("| {name} | {} | {theirs_text} | {ratio} |", seconds(ours));
    }
}

/// The release binary beside this example (target/release/examples/gltf_bench -> target/release).
fn tool_path() -> PathBuf {
    let exe = std::env::current_exe().expect("the example's path");
    let release = exe.parent().and_then(Path::parent).expect("target/<profile>");
    release.join(format!("tbasis-gltf{}", std::env::consts::EXE_SUFFIX))
}

/// The median wall time of each command over `RUNS` rounds, after an untimed round; a round runs
/// every command once, so that a change in the machine's speed during the bench falls on all of
/// them alike. `None` for a command that fails.
fn medians(commands: &mut [&mut dyn FnMut() -> bool]) -> Vec<Option<Duration>> {
    let mut times: Vec<Option<Vec<Duration>>> = commands.iter_mut().map(|run| run().then(Vec::new)).collect();
    for _ in 0..RUNS {
        for (run, times) in commands.iter_mut().zip(times.iter_mut()) {
            let Some(list) = times else { continue };
            let start = Instant::now();
            if run() {
                list.push(start.elapsed());
            } else {
                *times = None;
            }
        }
    }
    times
        .into_iter()
        .map(|list| {
            let mut list = list?;
            list.sort();
            Some(list[RUNS / 2])
        })
        .collect()
}

/// A torus of `(rings + 1) x (segments + 1)` vertices (UV seams duplicated) as a .glb with
/// POSITION, NORMAL, TEXCOORD_0 and 32-bit indices; returns its path and vertex count.
fn write_torus(dir: &Path, rings: usize, segments: usize) -> (PathBuf, usize) {
    let (major, minor) = (1.0f32, 0.35f32);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for i in 0..=rings {
        let u = i as f32 / rings as f32;
        let theta = u * std::f32::consts::TAU;
        for j in 0..=segments {
            let v = j as f32 / segments as f32;
            let phi = v * std::f32::consts::TAU;
            let normal = [theta.cos() * phi.cos(), theta.sin() * phi.cos(), phi.sin()];
            let radius = major + minor * phi.cos();
            positions.push([radius * theta.cos(), radius * theta.sin(), minor * phi.sin()]);
            normals.push(normal);
            // Three texture repeats around, mirrored every other: seams for the split to find.
            let mirrored = (3.0 * u).fract();
            let mirrored = if (3.0 * u) as usize % 2 == 0 {
                mirrored
            } else {
                1.0 - mirrored
            };
            uvs.push([mirrored, v]);
        }
    }
    let row = segments + 1;
    let mut indices = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b) = ((i * row + j) as u32, ((i + 1) * row + j) as u32);
            indices.extend_from_slice(&[a, b, b + 1, a, b + 1, a + 1]);
        }
    }
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut push = |bytes: Vec<u8>, target: u32| {
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{},"target":{target}}}"#,
            bin.len(),
            bytes.len()
        ));
        bin.extend_from_slice(&bytes);
    };
    let floats = |values: &[f32]| values.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    push(floats(positions.as_flattened()), 34962);
    push(floats(normals.as_flattened()), 34962);
    push(floats(uvs.as_flattened()), 34962);
    push(indices.iter().flat_map(|i| i.to_le_bytes()).collect(), 34963);
    let n = positions.len();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3}}]}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3","min":{min:?},"max":{max:?}}},
{{"bufferView":1,"componentType":5126,"count":{n},"type":"VEC3"}},
{{"bufferView":2,"componentType":5126,"count":{n},"type":"VEC2"}},
{{"bufferView":3,"componentType":5125,"count":{},"type":"SCALAR"}}],
"bufferViews":[{}],"buffers":[{{"byteLength":{}}}]}}"#,
        indices.len(),
        views.join(","),
        bin.len(),
        min = [0, 1, 2].map(|k| bound(&positions, k, f32::min)),
        max = [0, 1, 2].map(|k| bound(&positions, k, f32::max)),
    );
    let path = dir.join("torus.glb");
    std::fs::write(&path, glb(json.as_bytes(), &bin)).expect("write the torus");
    (path, n)
}

/// The smallest or largest component `k` of `values`.
fn bound(values: &[[f32; 3]], k: usize, pick: fn(f32, f32) -> f32) -> f32 {
    values.iter().map(|v| v[k]).reduce(pick).unwrap_or(0.0)
}

/// A .glb of `json` (padded with spaces) and `bin` (padded with zeros).
fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |len: usize| len.next_multiple_of(4);
    let (json_len, bin_len) = (pad(json.len()), pad(bin.len()));
    let total = 12 + 8 + json_len + 8 + bin_len;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(json);
    out.resize(20 + json_len, b' ');
    out.extend_from_slice(&(bin_len as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out.resize(total, 0);
    out
}
