//! A batch of files on several threads prints one line per file in the order the files were
//! given, whichever finishes first.

mod common;

use common::fixture::Fixture;
use common::tool;
use serde_json::json;

/// A grid of `side` by `side` vertices whose UVs mirror at its middle column, 16-bit indices:
/// large enough to take far longer than the mirrored quad.
fn grid(side: usize) -> Fixture {
    let mut f = Fixture::empty_primitive();
    let (mut positions, mut texcoords, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for y in 0..side {
        for x in 0..side {
            positions.push([x as f32, y as f32, ((x * 7 + y * 3) % 5) as f32 * 0.1]);
            texcoords.push([x.min(side - 1 - x) as f32 * 0.1, y as f32 * 0.1]);
        }
    }
    for y in 0..side - 1 {
        for x in 0..side - 1 {
            let v = (y * side + x) as u16;
            let s = side as u16;
            indices.extend([v, v + 1, v + s + 1, v, v + s + 1, v + s]);
        }
    }
    let position = f.floats(&positions, "VEC3", true);
    let normal = f.floats(&vec![[0.0f32, 0.0, 1.0]; positions.len()], "VEC3", false);
    let texcoord = f.floats(&texcoords, "VEC2", false);
    let indices = f.u16_indices(&indices);
    *f.primitive(0) = json!({ "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": texcoord }, "indices": indices, "mode": 4 });
    f
}

#[test]
fn summaries_follow_the_order_of_the_files() {
    let dir = tool::fresh_dir("batch-order");
    // The first file is slow, the others quick: on two threads the quick ones end first.
    let mut inputs = vec![grid(250).write_glb(&dir, "large")];
    inputs.extend((0..6).map(|k| Fixture::mirrored_quad().write_glb(&dir, &format!("quad{k}"))));
    let out = dir.join("out");
    let mut args = vec![
        "--jobs".into(),
        "2".into(),
        "--out-dir".into(),
        out.clone().into_os_string(),
    ];
    args.extend(inputs.iter().map(|input| input.clone().into_os_string()));
    let result = tool::run(&args);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{stdout}");
    let named: Vec<&str> = stdout
        .lines()
        .map(|line| line.split(" -> ").next().unwrap_or(line))
        .collect();
    let given: Vec<String> = inputs.iter().map(|input| input.display().to_string()).collect();
    assert_eq!(named, given, "{stdout}");
    // The premise: the large file took longer than each quad (`..., 0.25 s` ends each line).
    let seconds = |line: &str| -> f64 {
        line.rsplit(", ")
            .next()
            .unwrap()
            .trim_end_matches(" s")
            .parse()
            .unwrap()
    };
    let times: Vec<f64> = stdout.lines().map(seconds).collect();
    assert!(times[1..].iter().all(|&t| t <= times[0]), "{stdout}");
}
