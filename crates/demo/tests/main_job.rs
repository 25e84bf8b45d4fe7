//! The main job runs and leaves a PLY file whose tangents are unit length with w = +1 or -1.

use std::process::Command;

#[test]
fn the_demo_writes_unit_tangents_to_its_ply_file() {
    let dir = std::env::temp_dir().join(format!("tbasis-demo-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("torus.ply");
    let run = Command::new(env!("CARGO_BIN_EXE_tbasis-demo"))
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", String::from_utf8_lossy(&run.stderr));
    assert!(stdout.contains("degenerate_triangles: 512"), "{stdout}");

    let text = std::fs::read_to_string(&out).unwrap();
    let (header, body) = text.split_once("end_header\n").unwrap();
    let vertices: usize = header
        .lines()
        .find_map(|l| l.strip_prefix("element vertex "))
        .unwrap()
        .parse()
        .unwrap();
    assert!(header.contains("property float tw"));
    for line in body.lines().take(vertices) {
        let v: Vec<f32> = line.split(' ').map(|f| f.parse().unwrap()).collect();
        let (t, w) = (&v[8..11], v[11]);
        let length = t.iter().map(|x| x * x).sum::<f32>().sqrt();
        assert!((length - 1.0).abs() < 1e-5 && w.abs() == 1.0, "{line}");
    }
    assert!(!dir.join("torus.ply.partial").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
