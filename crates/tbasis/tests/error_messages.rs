//! One test per error of the Rust crate: a call that makes it, the details it carries, and its
//! message, which names the cause (the triangle, index or buffer at fault and the valid range).
//! The C statuses these map to are reached and named by the C harness (`tests/c_harness.rs`).

use tbasis::{
    copy_split_vertices, generate, generate_interleaved, generate_with_scratch, span_bytes, split_corners,
    to_tangent_space, Buffer, DegeneratePolicy, Error, Mesh, Method, Options, Output, Strided, VertexLayout,
};

const POSITIONS: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
const NORMALS: [[f32; 3]; 3] = [[0.0, 0.0, 1.0]; 3];
const TEXCOORDS: [[f32; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

/// The error of one `generate` call on a triangle (with `texcoords` and `indices`), checking that
/// the output stayed as it was.
fn generate_error(texcoords: Option<&[[f32; 2]]>, indices: &[u32], options: &Options) -> Error {
    let mut mesh = Mesh::new(&POSITIONS, &NORMALS).with_indices(indices);
    mesh.texcoords = texcoords.map(Strided::from_slice);
    let mut tangents = [[-7.5f32; 4]; 3];
    let error = generate(&mesh, options, &mut Output::new(&mut tangents)).unwrap_err();
    assert_eq!(tangents, [[-7.5; 4]; 3], "{error}: the output was written");
    error
}

fn check(error: Error, expected: Error, message: &str) {
    assert_eq!(error, expected);
    assert_eq!(error.to_string(), message);
}

#[test]
fn missing_texcoords() {
    check(
        generate_error(None, &[0, 1, 2], &Options::legacy()),
        Error::MissingTexcoords {
            method: Method::Lengyel,
            policy: DegeneratePolicy::Legacy,
        },
        "method Lengyel with policy Legacy needs texture coordinates, and the mesh has none",
    );
}

#[test]
fn texcoords_of_the_wrong_length() {
    check(
        generate_error(Some(&TEXCOORDS[..2]), &[0, 1, 2], &Options::default()),
        Error::LengthMismatch {
            buffer: Buffer::Texcoords,
            len: 2,
            expected: 3,
        },
        "texcoords has 2 elements where the mesh needs 3",
    );
}

#[test]
fn invalid_index_count() {
    check(
        generate_error(Some(&TEXCOORDS), &[0, 1, 2, 0], &Options::default()),
        Error::InvalidIndexCount { count: 4 },
        "4 indices (or unindexed vertices) do not make whole triangles: the count must be a multiple of 3",
    );
}

#[test]
fn index_out_of_range_names_the_first_triangle() {
    for threads in [1, 2] {
        check(
            generate_error(
                Some(&TEXCOORDS),
                &[0, 1, 2, 2, 1, 9, 0, 1, 5],
                &Options::default().with_threads(threads),
            ),
            Error::IndexOutOfRange {
                triangle: 1,
                index: 9,
                vertex_count: 3,
            },
            "triangle 1 uses vertex 9, but the mesh has 3 vertices (0..3)",
        );
    }
}

#[test]
fn invalid_threshold() {
    check(
        generate_error(
            Some(&TEXCOORDS),
            &[0, 1, 2],
            &Options::default().with_degenerate_threshold(-1.0),
        ),
        Error::InvalidThreshold { threshold: -1.0 },
        "degenerate_threshold -1 is not a finite number >= 0",
    );
}

#[test]
fn no_legacy_form() {
    check(
        generate_error(
            Some(&TEXCOORDS),
            &[0, 1, 2],
            &Options::legacy().with_method(Method::Uniform),
        ),
        Error::NoLegacyForm {
            method: Method::Uniform,
        },
        "policy Legacy reproduces the listing (method Lengyel) or mikktspace.c (method Mikktspace); method Uniform has no legacy form",
    );
}

#[test]
fn degenerate_uv_carries_the_report() {
    let collapsed = [[0.5f32, 0.5]; 3];
    let error = generate_error(
        Some(&collapsed),
        &[0, 1, 2],
        &Options::default().with_policy(DegeneratePolicy::Reject),
    );
    let Error::DegenerateUv { triangle, report } = &error else {
        panic!("{error:?}");
    };
    assert_eq!((*triangle, report.degenerate_triangles), (0, 1));
    assert_eq!(
        error.to_string(),
        "policy Reject: triangle 0 has degenerate texture coordinates, zero area or non-finite input (1 degenerate triangles in all)"
    );
}

#[test]
fn scratch_too_small() {
    let mesh = Mesh::new(&POSITIONS, &NORMALS).with_texcoords(&TEXCOORDS);
    let mut tangents = [[0.0f32; 4]; 3];
    let mut scratch = [0u8; 10];
    let options = Options::default().with_policy(DegeneratePolicy::Skip);
    check(
        generate_with_scratch(&mesh, &options, &mut Output::new(&mut tangents), &mut scratch).unwrap_err(),
        Error::ScratchTooSmall { needed: 90, len: 10 },
        "the scratch holds 10 bytes; this call needs 90 (scratch_size_for)",
    );
}

#[test]
fn overlap_names_both_buffers() {
    // The tangent's 16 bytes start inside the normal.
    let mut vertices = vec![0u8; 3 * 48];
    let layout = VertexLayout::new(48, 0, 12, 20).with_texcoord(40);
    check(
        generate_interleaved(&mut vertices, &layout, &[0u16, 1, 2], &Options::default()).unwrap_err(),
        Error::Overlap {
            written: Buffer::Tangents,
            other: Buffer::Normals,
        },
        "the tangents output shares bytes with the normals buffer",
    );
    assert!(vertices.iter().all(|&b| b == 0));
}

#[test]
fn attribute_beyond_the_vertex_is_an_invalid_stride() {
    let mut vertices = vec![0u8; 3 * 48];
    let layout = VertexLayout::new(48, 0, 12, 40);
    check(
        generate_interleaved(&mut vertices, &layout, &[0u16, 1, 2], &Options::default()).unwrap_err(),
        Error::InvalidStride {
            stride: 48,
            element_size: 56,
        },
        "a stride of 48 bytes is smaller than its 56-byte element",
    );
}

#[test]
fn short_byte_buffer_and_short_stride() {
    let bytes = [0u8; 20];
    check(
        Strided::<[f32; 3]>::from_bytes(&bytes, 12, 2).map(|_| ()).unwrap_err(),
        Error::BufferTooShort { len: 20, needed: 24 },
        "a buffer of 20 bytes is shorter than the 24 bytes its elements span",
    );
    check(
        Strided::<[f32; 3]>::from_bytes(&bytes, 8, 2).map(|_| ()).unwrap_err(),
        Error::InvalidStride {
            stride: 8,
            element_size: 12,
        },
        "a stride of 8 bytes is smaller than its 12-byte element",
    );
    check(
        span_bytes(usize::MAX, 16, 12).unwrap_err(),
        Error::SizeOverflow,
        "a buffer's size overflows the address space",
    );
}

#[test]
fn split_errors() {
    let mesh = Mesh::new(&POSITIONS, &NORMALS).with_indices(&[0u32, 1, 2]);
    let tangents = [[1.0f32, 0.0, 0.0, 1.0]; 2];
    check(
        split_corners(&mesh, &Strided::from_slice(&tangents)).unwrap_err(),
        Error::LengthMismatch {
            buffer: Buffer::CornerTangents,
            len: 2,
            expected: 3,
        },
        "corner tangents has 2 elements where the mesh needs 3",
    );
    let mut attribute = [0u8; 16];
    check(
        copy_split_vertices(&mut attribute, 4, 4, 3, &[7]).unwrap_err(),
        Error::SourceOutOfRange {
            position: 0,
            source: 7,
            vertex_count: 3,
        },
        "sources[0] is vertex 7, but the mesh has 3 vertices (0..3)",
    );
}

#[test]
fn invalid_frame() {
    check(
        to_tangent_space([0.0; 3], [1.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0]).unwrap_err(),
        Error::InvalidFrame,
        "the tangent frame is singular (normal or tangent zero or parallel, handedness zero), or an input or the result is not finite",
    );
}

/// Out of memory and too many vertices need more memory than a test has to reach from Rust; the C
/// harness reaches both (an impossible allocation, a seam split of a mesh that claims 2^32
/// vertices). Their messages:
#[test]
fn messages_of_the_errors_a_test_cannot_reach_from_rust() {
    assert_eq!(
        Error::OutOfMemory.to_string(),
        "out of memory: an allocation of the call failed"
    );
    assert_eq!(
        Error::TooManyVertices.to_string(),
        "the split mesh would need vertex indices beyond 32 bits"
    );
}
