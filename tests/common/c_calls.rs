//! The C boundary's calls as the allocation tests make them, on a test case: its mesh, the
//! options of a method and policy, and the two generating entry points writing into the elements
//! they are given (tangents per vertex, frames per corner), each allocating its own scratch.
//! Included by path next to the boundary's own sources (`ffi`, `codes`).

use std::ptr::null_mut;

use tbasis_test_support::cases::Case;

use crate::{codes, ffi, status};

/// A C entry point writing into the given elements, returning its status.
pub type Entry<'a> = dyn Fn(&mut [[f32; 4]]) -> u32 + 'a;

/// `case` as the C ABI reads it: packed arrays with texture coordinates, 32-bit indices.
pub fn c_mesh(case: &Case) -> ffi::tbasis_mesh {
    let indices = case.indices.as_ref().expect("an indexed case");
    ffi::tbasis_mesh {
        vertex_count: case.vertex_count(),
        positions: case.positions.as_ptr().cast(),
        positions_stride: 12,
        normals: case.normals.as_ptr().cast(),
        normals_stride: 12,
        texcoords: case.texcoords.as_ref().expect("texture coordinates").as_ptr().cast(),
        texcoords_stride: 8,
        indices: indices.as_ptr().cast(),
        index_count: indices.len(),
        index_type: codes::TBASIS_INDEX_U32,
    }
}

/// Options for `method` and `policy` on `threads`, without caller scratch.
pub fn options(method: u32, policy: u32, threads: u32) -> ffi::tbasis_options {
    ffi::tbasis_options {
        method,
        degenerate_policy: policy,
        flags: 0,
        threads,
        degenerate_threshold: 0.0,
        scratch: null_mut(),
        scratch_size: 0,
    }
}

/// `tbasis_generate`, writing tangents only.
pub fn per_vertex<'a>(
    mesh: &'a ffi::tbasis_mesh,
    options: &'a ffi::tbasis_options,
) -> impl Fn(&mut [[f32; 4]]) -> u32 + 'a {
    move |tangents| {
        let output = ffi::tbasis_output {
            tangents: tangents.as_mut_ptr().cast(),
            tangents_stride: 16,
            bitangents: null_mut(),
            bitangents_stride: 0,
        };
        // SAFETY: the mesh's arrays outlive the call; `tangents` holds a frame per vertex.
        unsafe { ffi::tbasis_generate(mesh, options, &output, null_mut()) }
    }
}

/// `tbasis_generate_corners`.
pub fn per_corner<'a>(
    mesh: &'a ffi::tbasis_mesh,
    options: &'a ffi::tbasis_options,
) -> impl Fn(&mut [[f32; 4]]) -> u32 + 'a {
    // SAFETY: the mesh's arrays outlive the call; `corners` holds a frame per index.
    move |corners| unsafe { ffi::tbasis_generate_corners(mesh, options, corners.as_mut_ptr().cast(), 16, null_mut()) }
}

/// What an output element holds before a call that must not write it.
pub const UNTOUCHED: f32 = -7.5;

/// Asserts that a call whose allocation failed (`failed`, for the message) returned
/// `TBASIS_ERROR_OUT_OF_MEMORY` and left every element of `output` [`UNTOUCHED`].
pub fn assert_out_of_memory(status: u32, output: &[[f32; 4]], failed: &str) {
    assert_eq!(status, status::TBASIS_ERROR_OUT_OF_MEMORY, "{failed} failed");
    assert!(
        output.iter().flatten().all(|&x| x == UNTOUCHED),
        "{failed} failed, yet the output was written"
    );
}
