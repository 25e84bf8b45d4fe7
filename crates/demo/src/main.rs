//! Builds a textured torus (the texture mirrored on one half, as artists do to save texels, and
//! collapsed on a thin band, as UV unwraps leave it), computes its tangents in place in its
//! interleaved vertex buffer, then mikktspace.c's per-corner tangents split into an indexed mesh,
//! and writes the result as a PLY file with tangent properties.
//!
//! `cargo run --release -p tbasis-demo [-- OUT.ply]` (default `target/tbasis-demo/torus.ply`).

use std::f32::consts::TAU;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use tbasis::{generate_corners, generate_interleaved, split_corners, Mesh, Options, StridedMut, VertexLayout};

/// Floats per interleaved vertex: position, normal, uv, tangent.
const FLOATS: usize = 3 + 3 + 2 + 4;
const LAYOUT_STRIDE: usize = FLOATS * 4;

/// The torus as an engine stores it: interleaved vertices (tangent zeroed) and 32-bit indices.
fn torus(rings: usize, sides: usize) -> (Vec<[f32; FLOATS]>, Vec<u32>) {
    let (major, minor) = (1.0f32, 0.3f32);
    let mut vertices = Vec::with_capacity((rings + 1) * (sides + 1));
    for i in 0..=rings {
        for j in 0..=sides {
            let (u, v) = (i as f32 / rings as f32, j as f32 / sides as f32);
            let (a, b) = (u * TAU, v * TAU);
            let normal = [a.cos() * b.cos(), a.sin() * b.cos(), b.sin()];
            let radius = major + minor * b.cos();
            let mirrored_u = if u > 0.5 { 1.0 - u } else { u };
            // A band of collapsed texture coordinates: every vertex of rings 10 and 11 maps to one
            // texel, so their triangles give no tangent.
            let uv = if i == 10 || i == 11 {
                [0.25, 0.5]
            } else {
                [mirrored_u * 4.0, v]
            };
            let position = [radius * a.cos(), radius * a.sin(), minor * b.sin()];
            let mut vertex = [0.0; FLOATS];
            vertex[..3].copy_from_slice(&position);
            vertex[3..6].copy_from_slice(&normal);
            vertex[6..8].copy_from_slice(&uv);
            vertices.push(vertex);
        }
    }
    let row = sides as u32 + 1;
    let mut indices = Vec::with_capacity(rings * sides * 6);
    for i in 0..rings as u32 {
        for j in 0..sides as u32 {
            let (a, b, c, d) = (i * row + j, (i + 1) * row + j, (i + 1) * row + j + 1, i * row + j + 1);
            indices.extend_from_slice(&[a, b, c, a, c, d]);
        }
    }
    (vertices, indices)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repository = Path::new(env!("CARGO_MANIFEST_DIR")).ancestors().nth(2).unwrap();
    let out = std::env::args_os()
        .nth(1)
        .map_or_else(|| repository.join("target/tbasis-demo/torus.ply"), PathBuf::from);
    let (mut vertices, indices) = torus(256, 128);
    println!(
        "torus: {} vertices, {} triangles; texture mirrored on one half, collapsed on two rings",
        vertices.len(),
        indices.len() / 3
    );

    // 1. The default method, in place in the interleaved buffer (tangent at byte 32).
    let layout = VertexLayout::new(LAYOUT_STRIDE, 0, 12, 32).with_texcoord(24);
    let mut bytes: Vec<u8> = vertices.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
    let start = Instant::now();
    let report = generate_interleaved(&mut bytes, &layout, &indices[..], &Options::default().with_threads(2))?;
    let elapsed = start.elapsed();
    for (vertex, chunk) in vertices.iter_mut().zip(bytes.chunks_exact(LAYOUT_STRIDE)) {
        for (k, float) in chunk.chunks_exact(4).enumerate() {
            vertex[k] = f32::from_le_bytes(float.try_into()?);
        }
    }
    println!("\ndefault method, 2 threads: {:.1} ms", elapsed.as_secs_f64() * 1e3);
    println!("  {report:#?}");

    // 2. mikktspace.c's tangents per corner, then the vertices whose corners differ split.
    let positions: Vec<[f32; 3]> = vertices.iter().map(|v| [v[0], v[1], v[2]]).collect();
    let normals: Vec<[f32; 3]> = vertices.iter().map(|v| [v[3], v[4], v[5]]).collect();
    let texcoords: Vec<[f32; 2]> = vertices.iter().map(|v| [v[6], v[7]]).collect();
    let mesh = Mesh::new(&positions[..], &normals[..])
        .with_texcoords(&texcoords[..])
        .with_indices(&indices[..]);
    let mut corners = vec![[0.0f32; 4]; indices.len()];
    let start = Instant::now();
    let mikk = generate_corners(&mesh, &Options::mikktspace(), &mut StridedMut::from_slice(&mut corners))?;
    let split = split_corners(&mesh, &(&corners[..]).into())?;
    println!(
        "\nMikkTSpace per corner + seam split: {:.1} ms; {} vertices split, {} appended",
        start.elapsed().as_secs_f64() * 1e3,
        mikk.split_vertices,
        split.sources.len()
    );

    // 3. The per-vertex result, written where the user can open it.
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    write_ply(&out, &vertices, &indices)?;
    println!("\nwrote {} (PLY with tx, ty, tz, tw per vertex)", out.display());
    Ok(())
}

/// Writes an ASCII PLY file: position, normal, uv and tangent per vertex, then the triangles. A
/// temporary file is renamed over `path` at the end, so no half-written file is left.
fn write_ply(path: &Path, vertices: &[[f32; FLOATS]], indices: &[u32]) -> std::io::Result<()> {
    let partial = path.with_extension("ply.partial");
    let mut file = std::io::BufWriter::new(std::fs::File::create(&partial)?);
    writeln!(file, "ply\nformat ascii 1.0\nelement vertex {}", vertices.len())?;
    for name in ["x", "y", "z", "nx", "ny", "nz", "s", "t", "tx", "ty", "tz", "tw"] {
        writeln!(file, "property float {name}")?;
    }
    writeln!(
        file,
        "element face {}\nproperty list uchar uint vertex_indices\nend_header",
        indices.len() / 3
    )?;
    for vertex in vertices {
        let fields: Vec<String> = vertex.iter().map(f32::to_string).collect();
        writeln!(file, "{}", fields.join(" "))?;
    }
    for t in indices.chunks_exact(3) {
        writeln!(file, "3 {} {} {}", t[0], t[1], t[2])?;
    }
    file.into_inner().map_err(|e| e.into_error())?.sync_all()?;
    std::fs::rename(&partial, path)
}
