//! Builds a torus with a mirrored texture on one half, computes its tangents with the listing and
//! with the default options, and shows what each did.
//!
//! `cargo run --release --example demo`

use std::f32::consts::TAU;

use tbasis::{generate, DegeneratePolicy, Indices, Mesh, Options, Output, Report, Strided, StridedMut};

/// An interleaved vertex, as an engine would store it; the tangent is written in place.
#[derive(Clone, Copy, Default)]
#[repr(C)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
    tangent: [f32; 4],
}

fn torus(rings: usize, sides: usize) -> (Vec<Vertex>, Vec<u32>) {
    let (major, minor) = (1.0f32, 0.3f32);
    let mut vertices = Vec::new();
    for i in 0..=rings {
        for j in 0..=sides {
            let (u, v) = (i as f32 / rings as f32, j as f32 / sides as f32);
            let (a, b) = (u * TAU, v * TAU);
            let normal = [a.cos() * b.cos(), a.sin() * b.cos(), b.sin()];
            let radius = major + minor * b.cos();
            // The second half of the torus mirrors the texture in u, as artists do to save texels.
            let mirrored_u = if u > 0.5 { 1.0 - u } else { u };
            vertices.push(Vertex {
                position: [radius * a.cos(), radius * a.sin(), minor * b.sin()],
                normal,
                uv: [mirrored_u * 4.0, v],
                tangent: [0.0; 4],
            });
        }
    }
    let mut indices = Vec::new();
    let row = sides as u32 + 1;
    for i in 0..rings as u32 {
        for j in 0..sides as u32 {
            let (a, b, c, d) = (i * row + j, (i + 1) * row + j, (i + 1) * row + j + 1, i * row + j + 1);
            indices.extend_from_slice(&[a, b, c, a, c, d]);
        }
    }
    (vertices, indices)
}

fn run(vertices: &mut [Vertex], indices: &[u32], options: &Options) -> Result<Report, tbasis::Error> {
    let stride = std::mem::size_of::<Vertex>();
    let base = vertices.as_mut_ptr().cast::<u8>();
    let count = vertices.len();
    // SAFETY: each view covers `count` records of `stride` bytes inside `vertices`; the outputs
    // (tangent field) share no byte with the inputs, which the library checks as well.
    let (mesh, mut output) = unsafe {
        let field = |offset: usize| base.add(offset);
        let mesh = Mesh {
            positions: Strided::from_raw(field(0), stride, count),
            normals: Strided::from_raw(field(12), stride, count),
            texcoords: Some(Strided::from_raw(field(24), stride, count)),
            indices: Indices::U32(Strided::from_slice(indices)),
        };
        let output = Output {
            tangents: StridedMut::from_raw(field(32), stride, count),
            bitangents: None,
        };
        (mesh, output)
    };
    generate(&mesh, options, &mut output)
}

fn main() {
    let (mut vertices, indices) = torus(48, 24);
    println!(
        "torus: {} vertices, {} triangles, texture mirrored on one half",
        vertices.len(),
        indices.len() / 3
    );
    for (name, options) in [
        ("listing (LENGYEL + LEGACY)", Options::legacy()),
        ("default", Options::default()),
        (
            "REJECT",
            Options {
                degenerate_policy: DegeneratePolicy::Reject,
                ..Options::default()
            },
        ),
    ] {
        match run(&mut vertices, &indices, &options) {
            Ok(report) => {
                let left_handed = vertices.iter().filter(|v| v.tangent[3] < 0.0).count();
                println!("\n{name}: OK\n  {report:?}\n  left-handed vertices (w = -1): {left_handed}");
                for k in [0, vertices.len() / 2] {
                    let v = &vertices[k];
                    println!("  vertex {k}: uv {:?} tangent {:?}", v.uv, v.tangent);
                }
            }
            Err(error) => println!("\n{name}: refused: {error}"),
        }
    }
}
