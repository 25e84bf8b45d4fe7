//! The C entry points with caller scratch (and one thread) make no heap allocation at all, counted
//! on the calling thread like the Rust API's calls in `crates/tbasis/tests/allocation.rs`, which
//! also proves the counter.

// The C boundary's own source, compiled in to count what it allocates (the C library has no Rust
// interface).
#[allow(dead_code)]
#[path = "../src/codes.rs"]
mod codes;
#[path = "../src/fault.rs"]
mod fault;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/ffi.rs"]
mod ffi;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/status.rs"]
mod status;

use tbasis_test_support::alloc_count::{allocations, Counting};
use tbasis_test_support::cases::{mirror_fold, quantized_uv_sphere, unit_quad};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The C entry points with caller scratch allocate nothing either: the boundary's checks included.
#[test]
fn the_c_boundary_with_caller_scratch_allocates_nothing() {
    use std::ffi::c_void;
    use std::ptr::null_mut;

    for case in [unit_quad(), mirror_fold(), quantized_uv_sphere()] {
        let indices = case.indices.as_ref().unwrap();
        let mesh = ffi::tbasis_mesh {
            vertex_count: case.vertex_count(),
            positions: case.positions.as_ptr().cast(),
            positions_stride: 12,
            normals: case.normals.as_ptr().cast(),
            normals_stride: 12,
            texcoords: case.texcoords.as_ref().unwrap().as_ptr().cast(),
            texcoords_stride: 8,
            indices: indices.as_ptr().cast(),
            index_count: indices.len(),
            index_type: codes::TBASIS_INDEX_U32,
        };
        let mut options = ffi::tbasis_options {
            method: 0,
            degenerate_policy: 0,
            flags: 0,
            threads: 1,
            degenerate_threshold: 0.0,
            scratch: null_mut(),
            scratch_size: 0,
        };
        let needed = unsafe { ffi::tbasis_scratch_size(&mesh, &options) };
        let mut scratch = vec![0u8; needed];
        options.scratch = scratch.as_mut_ptr().cast::<c_void>();
        options.scratch_size = needed;
        let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
        let mut bitangents = vec![[0.0f32; 3]; case.vertex_count()];
        let mut corners = vec![[0.0f32; 4]; indices.len()];
        let output = ffi::tbasis_output {
            tangents: tangents.as_mut_ptr().cast(),
            tangents_stride: 16,
            bitangents: bitangents.as_mut_ptr().cast(),
            bitangents_stride: 12,
        };
        let before = allocations();
        let status = unsafe { ffi::tbasis_generate(&mesh, &options, &output, null_mut()) };
        let corner_status =
            unsafe { ffi::tbasis_generate_corners(&mesh, &options, corners.as_mut_ptr().cast(), 16, null_mut()) };
        let made = allocations() - before;
        assert_eq!(
            (status, corner_status),
            (status::TBASIS_OK, status::TBASIS_OK),
            "{}",
            case.name
        );
        assert_eq!(made, 0, "{}: the C calls allocated", case.name);
    }
}
