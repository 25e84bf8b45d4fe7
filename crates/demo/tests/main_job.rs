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

    // The mesh's size as the demo states it: the file must hold all of it, no more, no less.
    let counts = stdout
        .lines()
        .find_map(|l| l.strip_prefix("torus: "))
        .expect("the torus line");
    let count = |unit: &str| -> usize {
        let words: Vec<&str> = counts.split([' ', ',', ';']).collect();
        let k = words
            .iter()
            .position(|w| *w == unit)
            .unwrap_or_else(|| panic!("no {unit} in {counts}"));
        words[k - 1].parse().unwrap()
    };
    let (vertices, triangles) = (count("vertices"), count("triangles"));
    assert!(vertices > 0 && triangles > 0, "{counts}");

    let text = std::fs::read_to_string(&out).unwrap();
    let (header, body) = text.split_once("end_header\n").unwrap();
    let declared = |element: &str| -> usize {
        let prefix = format!("element {element} ");
        header
            .lines()
            .find_map(|l| l.strip_prefix(prefix.as_str()))
            .unwrap()
            .parse()
            .unwrap()
    };
    assert_eq!((declared("vertex"), declared("face")), (vertices, triangles));
    assert!(header.contains("property float tw"));
    let lines: Vec<&str> = body.lines().collect();
    assert_eq!(lines.len(), vertices + triangles, "lines after the header");
    for line in &lines[..vertices] {
        let v: Vec<f32> = line.split(' ').map(|f| f.parse().unwrap()).collect();
        assert_eq!(v.len(), 12, "{line}");
        let (t, w) = (&v[8..11], v[11]);
        let length = t.iter().map(|x| x * x).sum::<f32>().sqrt();
        assert!((length - 1.0).abs() < 1e-5 && w.abs() == 1.0, "{line}");
    }
    for line in &lines[vertices..] {
        let face: Vec<usize> = line.split(' ').map(|f| f.parse().unwrap()).collect();
        assert!(
            face.len() == 4 && face[0] == 3 && face[1..].iter().all(|&i| i < vertices),
            "{line}"
        );
    }
    assert!(!dir.join("torus.ply.partial").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
