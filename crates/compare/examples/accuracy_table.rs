//! The default method's accuracy against mikktspace.c's, scene by scene, on a set of analytic
//! scenes grown beyond the chart's so that no tuning can fit one shape (`accuracy_specs` in
//! `crates/test-support/src/scenes.rs`, which `crates/tbasis/tests/accuracy.rs` also checks).
//!
//! ```text
//! cargo run --release -p tbasis-compare --example accuracy_table
//! ```
//!
//! Prints the table and writes `docs/accuracy.md`. Accuracy only, no timing: it takes seconds.

use std::fmt::Write as _;
use std::fs;
use std::path::PathBuf;

use scenes::{Accuracy, Scene};
use tbasis::{generate, Mesh, Options, Output};
use tbasis_test_support::{mikktspace_reference, scenes};

/// The scene's size as the table shows it: its grid, and its vertex count.
fn size(scene: &Scene) -> String {
    format!(
        "{} x {} quads, {} vertices",
        scene.grid.0,
        scene.grid.1,
        scene.vertex_count()
    )
}

/// The library's per-vertex tangents with `options`.
fn library(scene: &Scene, options: &Options) -> Vec<[f32; 4]> {
    let mesh = Mesh::new(&scene.positions[..], &scene.normals[..])
        .with_texcoords(&scene.texcoords[..])
        .with_indices(&scene.indices[..]);
    let mut tangents = vec![[0.0f32; 4]; scene.vertex_count()];
    generate(&mesh, options, &mut Output::new(&mut tangents[..])).expect("the scene is valid");
    tangents
}

/// mikktspace.c's per-corner tangents, each vertex taking its first corner's.
fn mikktspace_c(scene: &Scene) -> Vec<[f32; 4]> {
    mikktspace_reference::first_corner_frames(mikktspace_reference::Geometry {
        positions: &scene.positions,
        normals: &scene.normals,
        texcoords: &scene.texcoords,
        indices: Some(&scene.indices),
    })
}

/// `ours / theirs`, shown to three places.
fn ratio(ours: f64, theirs: f64) -> String {
    if theirs > 0.0 {
        format!("{:.3}", ours / theirs)
    } else {
        "-".to_string()
    }
}

fn main() {
    let mut md = String::from(
        "# The default method against mikktspace.c, scene by scene\n\n\
         Mean and 99th-percentile angle (degrees) between each vertex's tangent and the true one \
         (the surface's analytic dP/ds projected onto the vertex's tangent plane), and the share of \
         vertices whose handedness `w` is wrong, for the default method (ANGLE, default options) and \
         for mikktspace.c (`mikktspace-sys`, each vertex taking its first corner's frame), and how \
         many vertices get exactly mikktspace.c's bits from the default (which sums mikktspace.c's \
         own terms: README, \"Methods\"). Ratios above 1 would be scenes where the default is less \
         accurate. Scenes: `crates/test-support/src/scenes.rs`; \
         the first seven are the chart's, the others were grown for this table: coarse grids, a \
         height field, non-uniformly scaled tori (x 1, 0.5, 2) and spheres (x 1.6, 1, 0.6), \
         jittered texture coordinates (by up to 0.1 of a cell) and quantised ones (to 1/256 or \
         1/1024); the truth is the smooth map's, so texture noise counts as error.\n\n\
         Reproduce (seconds; writes this file):\n\n\
         ```text\ncargo run --release -p tbasis-compare --example accuracy_table\n```\n\n\
         | scene | size | vertices with mikktspace.c's bits | default mean | mikktspace.c mean | ratio | default p99 | mikktspace.c p99 | ratio | wrong w default / mikktspace.c |\n\
         |---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    // Scenes where the default is less accurate at all, and by more than 0.1%; the largest ratios.
    let (mut worse_mean, mut worse_p99, mut clearly_worse) = (0, 0, 0);
    let (mut worst_mean, mut worst_p99) = ((0.0f64, String::new()), (0.0f64, String::new()));
    // Vertices with mikktspace.c's bits, of all vertices.
    let (mut same_total, mut vertex_total) = (0, 0);
    let specs = scenes::accuracy_specs();
    for spec in &specs {
        let scene = scenes::build(spec);
        let (ours_frames, theirs_frames) = (library(&scene, &Options::default()), mikktspace_c(&scene));
        let same_bits = ours_frames
            .iter()
            .zip(&theirs_frames)
            .filter(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits))
            .count();
        (same_total, vertex_total) = (same_total + same_bits, vertex_total + ours_frames.len());
        let ours: Accuracy = scenes::accuracy(&scene, &ours_frames);
        let theirs: Accuracy = scenes::accuracy(&scene, &theirs_frames);
        worse_mean += usize::from(ours.mean_deg > theirs.mean_deg);
        worse_p99 += usize::from(ours.p99_deg > theirs.p99_deg);
        let (mean_ratio, p99_ratio) = (ours.mean_deg / theirs.mean_deg, ours.p99_deg / theirs.p99_deg);
        clearly_worse += usize::from(mean_ratio > 1.001 || p99_ratio > 1.001);
        let label = || format!("{}, {}", scene.name, size(&scene));
        if mean_ratio > worst_mean.0 {
            worst_mean = (mean_ratio, label());
        }
        if p99_ratio > worst_p99.0 {
            worst_p99 = (p99_ratio, label());
        }
        let line = format!(
            "| {} | {} | {} | {:.4} | {:.4} | {} | {:.4} | {:.4} | {} | {:.2}% / {:.2}% |",
            scene.name,
            size(&scene),
            same_bits,
            ours.mean_deg,
            theirs.mean_deg,
            ratio(ours.mean_deg, theirs.mean_deg),
            ours.p99_deg,
            theirs.p99_deg,
            ratio(ours.p99_deg, theirs.p99_deg),
            100.0 * ours.wrong_handedness_share(),
            100.0 * theirs.wrong_handedness_share(),
        );
        println!("{line}");
        md.push_str(&line);
        md.push('\n');
    }
    writeln!(
        md,
        "\nOf {} scenes, the default's mean error is above mikktspace.c's on {worse_mean} and its 99th \
         percentile on {worse_p99}; by more than 0.1% on {clearly_worse}. Largest ratios: mean {:.5} \
         ({}), 99th percentile {:.5} ({}). {same_total} of {vertex_total} vertices have exactly \
         mikktspace.c's bits.",
        specs.len(),
        worst_mean.0,
        worst_mean.1,
        worst_p99.0,
        worst_p99.1
    )
    .unwrap();
    print!("{}", md.lines().last().unwrap_or_default());
    println!();
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/accuracy.md");
    fs::write(&path, md).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}
