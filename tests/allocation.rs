//! The C entry points with caller scratch (and one thread) make no heap allocation at all, counted
//! on the calling thread like the Rust API's calls in `crates/tbasis/tests/allocation.rs`, which
//! also proves the counter; without caller scratch, each allocation a call makes may fail, and the
//! call then returns `TBASIS_ERROR_OUT_OF_MEMORY` with its outputs untouched (on one thread;
//! `tests/allocation_threads.rs` does the same on one and two threads, on larger meshes).

// The C boundary's own source, compiled in to count what it allocates (the C library has no Rust
// interface).
#[path = "common/c_calls.rs"]
mod c_calls;
#[allow(dead_code)]
#[path = "../src/codes.rs"]
mod codes;
#[path = "../src/fault.rs"]
mod fault;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/ffi.rs"]
mod ffi;
#[path = "../src/guard.rs"]
mod guard;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/status.rs"]
mod status;

use c_calls::{assert_out_of_memory, c_mesh, Entry, UNTOUCHED};
use tbasis_test_support::alloc_count::{allocations, fail_allocation, Counting};
use tbasis_test_support::cases::{
    all_uvs_equal, disk_after_a_triangle, mirror_fold, quantized_uv_sphere, sphere_poles, unit_quad, Case,
};
use tbasis_test_support::shapes::Poles;

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The C entry points with caller scratch allocate nothing either, the boundary's checks
/// included: every method and policy, and the defaults.
#[test]
fn the_c_boundary_with_caller_scratch_allocates_nothing() {
    use codes::*;
    let methods = [
        0,
        TBASIS_METHOD_LENGYEL,
        TBASIS_METHOD_ANGLE,
        TBASIS_METHOD_AREA,
        TBASIS_METHOD_UNIFORM,
        TBASIS_METHOD_MIKKTSPACE,
    ];
    let policies = [
        0,
        TBASIS_DEGENERATE_LEGACY,
        TBASIS_DEGENERATE_SKIP,
        TBASIS_DEGENERATE_INHERIT,
        TBASIS_DEGENERATE_REJECT,
    ];
    let sphere = quantized_uv_sphere();
    for case in [unit_quad(), mirror_fold(), sphere.clone()] {
        for (method, policy) in methods.into_iter().flat_map(|m| policies.map(|p| (m, p))) {
            check_c_calls_allocate_nothing(&case, method, policy, case.name == sphere.name);
        }
    }
}

/// [`the_c_boundary_with_caller_scratch_allocates_nothing`] for one case, method and policy: the
/// status the options and the mesh call for (`degenerate`: the case has degenerate triangles),
/// per vertex and per corner, and no allocation.
fn check_c_calls_allocate_nothing(case: &Case, method: u32, policy: u32, degenerate: bool) {
    use codes::*;
    use std::ffi::c_void;
    use std::ptr::null_mut;

    // Method 0 with policy LEGACY is the listing's, LENGYEL.
    let legacy_form = [0, TBASIS_METHOD_LENGYEL, TBASIS_METHOD_MIKKTSPACE].contains(&method);
    let expected = if policy == TBASIS_DEGENERATE_LEGACY && !legacy_form {
        status::TBASIS_ERROR_NO_LEGACY_FORM
    } else if policy == TBASIS_DEGENERATE_REJECT && degenerate {
        status::TBASIS_ERROR_DEGENERATE_UV
    } else {
        status::TBASIS_OK
    };
    let indices = case.indices.as_ref().unwrap();
    let mesh = c_mesh(case);
    let mut options = ffi::tbasis_options {
        method,
        degenerate_policy: policy,
        flags: 0,
        threads: 1,
        degenerate_threshold: 0.0,
        scratch: null_mut(),
        scratch_size: 0,
    };
    // SIZE_MAX: options the call refuses (LEGACY without a legacy form), given no scratch.
    let needed = unsafe { ffi::tbasis_scratch_size(&mesh, &options) };
    let mut scratch = vec![0u8; if needed == usize::MAX { 0 } else { needed }];
    options.scratch = scratch.as_mut_ptr().cast::<c_void>();
    options.scratch_size = scratch.len();
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
    let what = format!("{} method {method} policy {policy}", case.name);
    assert_eq!(
        (status, corner_status),
        (expected, expected),
        "{what}: per vertex, per corner"
    );
    assert_eq!(made, 0, "{what}: the C calls allocated");
}

/// Methods LENGYEL, ANGLE, AREA and UNIFORM under every policy (one thread, the library's own
/// scratch), per vertex and per corner: each allocation a call makes may fail.
#[test]
fn each_allocation_of_a_per_vertex_method_may_fail_and_the_call_says_so() {
    use codes::*;
    let robust = [
        TBASIS_DEGENERATE_SKIP,
        TBASIS_DEGENERATE_INHERIT,
        TBASIS_DEGENERATE_REJECT,
    ];
    let combinations: Vec<(u32, u32)> = [(TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_LEGACY)]
        .into_iter()
        .chain(
            [
                TBASIS_METHOD_LENGYEL,
                TBASIS_METHOD_ANGLE,
                TBASIS_METHOD_AREA,
                TBASIS_METHOD_UNIFORM,
            ]
            .into_iter()
            .flat_map(|method| robust.map(|policy| (method, policy))),
        )
        .collect();
    fail_each_allocation(&combinations, small_cases);
    // Working memory of megabytes, which the library once took from a zeroed allocation that
    // aborts when it fails: one combination is enough, the memory is the same for all.
    fail_each_allocation(&[(TBASIS_METHOD_ANGLE, TBASIS_DEGENERATE_INHERIT)], || {
        vec![quantized_uv_sphere()]
    });
}

/// A mirror fold, collapsed UVs (INHERIT's adjacency), a sphere with degenerate pole triangles.
fn small_cases() -> Vec<Case> {
    vec![unit_quad(), mirror_fold(), all_uvs_equal(), sphere_poles(Poles::Shared)]
}

/// Method MIKKTSPACE under every policy, likewise.
#[test]
fn each_allocation_of_mikktspace_may_fail_and_the_call_says_so() {
    use codes::*;
    let policies = [
        TBASIS_DEGENERATE_LEGACY,
        TBASIS_DEGENERATE_SKIP,
        TBASIS_DEGENERATE_INHERIT,
        TBASIS_DEGENERATE_REJECT,
    ];
    // Per corner, MIKKTSPACE writes the caller's output in place, fan by fan: a fan of 40
    // corners, past the scan limit, after another, makes it reserve the large fan's arrays
    // before it writes the first.
    let cases = || {
        let mut cases = small_cases();
        cases.push(disk_after_a_triangle(40));
        cases
    };
    fail_each_allocation(&policies.map(|policy| (TBASIS_METHOD_MIKKTSPACE, policy)), cases);
}

/// For each `(method, policy)`, on `cases`, per vertex and per corner: for each `k` up
/// to the number of allocations a successful call makes, the call whose `k`-th allocation fails
/// returns `TBASIS_ERROR_OUT_OF_MEMORY` and writes no output byte.
fn fail_each_allocation(combinations: &[(u32, u32)], cases: impl Fn() -> Vec<Case>) {
    let (mut failed, mut calls) = (0, 0);
    for &(method, policy) in combinations {
        for case in cases() {
            let indices = case.indices.as_ref().unwrap();
            let mesh = c_mesh(&case);
            let options = c_calls::options(method, policy, 1);
            let (per_vertex, per_corner) = (
                c_calls::per_vertex(&mesh, &options),
                c_calls::per_corner(&mesh, &options),
            );
            let entries: [(&str, &Entry, usize); 2] = [
                ("tbasis_generate", &per_vertex, case.vertex_count()),
                ("tbasis_generate_corners", &per_corner, indices.len()),
            ];
            for (entry, call, count) in entries {
                let what = format!("{entry}, method {method}, policy {policy}, {}", case.name);
                let mut output = vec![[UNTOUCHED; 4]; count];
                let mut written = output.clone();
                // Counted on a second call: the first may make one-time allocations (the
                // thread's own state) that later ones do not.
                call(&mut written);
                let before = allocations();
                let status = call(&mut written);
                let made = allocations() - before;
                // REJECT refuses the degenerate cases, after allocating all the same.
                assert!(
                    status == status::TBASIS_OK || status == status::TBASIS_ERROR_DEGENERATE_UV,
                    "{what}: status {status}"
                );
                for k in 0..made {
                    fail_allocation(Some(allocations() + k));
                    let status = call(&mut output);
                    fail_allocation(None);
                    assert_out_of_memory(status, &output, &format!("{what}: allocation {k} of {made}"));
                }
                failed += made;
                calls += 1;
            }
        }
    }
    eprintln!("{calls} calls, {failed} allocations failed one at a time");
    assert!(failed > 0, "no call allocated: nothing was tested");
}

/// `tbasis_split_corners` on corners whose tangents differ at a mirror fold (it appends vertices):
/// each of its allocations may fail, and then it writes nothing.
#[test]
fn each_allocation_of_a_seam_split_may_fail_and_the_call_says_so() {
    use std::ptr::null_mut;

    let case = mirror_fold();
    let indices = case.indices.as_ref().unwrap();
    let mesh = ffi::tbasis_mesh {
        vertex_count: case.vertex_count(),
        positions: case.positions.as_ptr().cast(),
        positions_stride: 12,
        normals: case.normals.as_ptr().cast(),
        normals_stride: 12,
        texcoords: null_mut(),
        texcoords_stride: 0,
        indices: indices.as_ptr().cast(),
        index_count: indices.len(),
        index_type: codes::TBASIS_INDEX_U32,
    };
    // Every corner a tangent of its own: every corner after a vertex's first is appended.
    let corners: Vec<[f32; 4]> = (0..indices.len()).map(|c| [1.0, 0.0, 0.0, c as f32]).collect();
    const UNTOUCHED: u32 = 0xdead;
    let split = |new_indices: &mut [u32], sources: &mut [u32], appended: &mut usize| unsafe {
        ffi::tbasis_split_corners(
            &mesh,
            corners.as_ptr().cast(),
            16,
            new_indices.as_mut_ptr(),
            sources.as_mut_ptr(),
            appended,
        )
    };
    let (mut new_indices, mut sources, mut appended) = (
        vec![UNTOUCHED; indices.len()],
        vec![UNTOUCHED; indices.len()],
        usize::MAX,
    );
    split(&mut new_indices.clone(), &mut sources.clone(), &mut 0);
    let before = allocations();
    let status = split(&mut new_indices.clone(), &mut sources.clone(), &mut 0);
    let made = allocations() - before - 2;
    assert_eq!(status, status::TBASIS_OK);
    assert!(made > 0, "the split allocated nothing: nothing was tested");
    for k in 0..made {
        fail_allocation(Some(allocations() + k));
        let status = split(&mut new_indices, &mut sources, &mut appended);
        fail_allocation(None);
        assert_eq!(
            status,
            status::TBASIS_ERROR_OUT_OF_MEMORY,
            "allocation {k} of {made} failed"
        );
        assert!(
            new_indices.iter().chain(&sources).all(|&x| x == UNTOUCHED) && appended == usize::MAX,
            "allocation {k} of {made} failed, yet an output was written"
        );
    }
}
