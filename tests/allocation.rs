//! With caller scratch (and one thread), a call makes no heap allocation at all, per-vertex or
//! per-corner, counted on the calling thread.

#[path = "common/mod.rs"]
mod common;

// The C boundary's own source, compiled in to count what it allocates (the C library has no Rust
// interface).
#[allow(dead_code)]
#[path = "../src/codes.rs"]
mod codes;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/ffi.rs"]
mod ffi;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/status.rs"]
mod status;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use common::cases::{mirror_fold, quantized_uv_sphere, unit_quad, Case};
use tbasis::{scratch_size_for, DegeneratePolicy, Error, ErrorKind, Method, Options, Output, Report, StridedMut};

/// Counts the allocations of each thread, so that other tests running at the same time (and the
/// test harness's own threads) neither add to a count nor hide one.
struct Counting;

thread_local! {
    // A const-initialized Cell needs no allocation of its own, not even on first use.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Allocations the calling thread has made so far.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

fn count_one() {
    // `try_with`: a thread being torn down may still free and allocate.
    let _ = ALLOCATIONS.try_with(|count| count.set(count.get() + 1));
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_one();
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_one();
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations `call` makes on this thread (with caller scratch and one thread, the library makes
/// all of them here), and what it returned.
fn allocations_during(call: impl FnOnce() -> Result<Report, Error>) -> (usize, Result<Report, Error>) {
    let before = allocations();
    let result = call();
    let after = allocations();
    (after - before, result)
}

/// Allocations made by one call with caller scratch, and its result.
fn allocations_during_call(case: &Case, options: &Options) -> (usize, Result<Report, Error>) {
    let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
    let mut bitangents = vec![[0.0f32; 3]; case.vertex_count()];
    let mesh = case.mesh();
    let mut scratch = vec![0u8; scratch_size_for(&mesh, options).unwrap()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: Some(StridedMut::from_slice(&mut bitangents)),
    };
    allocations_during(|| tbasis::generate_with_scratch(&mesh, options, &mut output, &mut scratch))
}

/// Allocations made by one per-corner call with caller scratch, and its result.
fn allocations_during_corners_call(case: &Case, options: &Options) -> (usize, Result<Report, Error>) {
    let mesh = case.mesh();
    let mut corners = vec![[0.0f32; 4]; mesh.corner_count()];
    let mut scratch = vec![0u8; scratch_size_for(&mesh, options).unwrap()];
    let mut tangents = StridedMut::from_slice(&mut corners);
    allocations_during(|| tbasis::generate_corners_with_scratch(&mesh, options, &mut tangents, &mut scratch))
}

#[test]
fn caller_scratch_means_no_allocation() {
    // The INHERIT cases need propagation, the mirror fold both handedness sums; REJECT refuses the
    // sphere's degenerate pole triangles and computes the others.
    let cases = [unit_quad(), mirror_fold(), quantized_uv_sphere()];
    let (mut refused, mut rejected, mut computed_under_reject) = (0, 0, 0);
    for case in &cases {
        for method in [
            Method::Lengyel,
            Method::Angle,
            Method::Area,
            Method::Uniform,
            Method::Mikktspace,
        ] {
            for policy in [
                DegeneratePolicy::Legacy,
                DegeneratePolicy::Skip,
                DegeneratePolicy::Inherit,
                DegeneratePolicy::Reject,
            ] {
                let options = Options::default().with_method(method).with_policy(policy);
                let what = format!("{} {method:?} {policy:?}", case.name);
                let calls = [
                    (allocations_during_call(case, &options), "per vertex"),
                    (allocations_during_corners_call(case, &options), "per corner"),
                ];
                for ((made, result), output) in calls {
                    assert_eq!(made, 0, "{what} {output}: allocated");
                    match result.as_ref().map_err(Error::kind) {
                        Ok(_) if policy == DegeneratePolicy::Reject => computed_under_reject += 1,
                        Ok(_) => {}
                        Err(ErrorKind::NoLegacyForm) => refused += 1,
                        Err(ErrorKind::DegenerateUv) if policy == DegeneratePolicy::Reject => rejected += 1,
                        Err(error) => panic!("{what} {output}: {error:?}"),
                    }
                }
            }
        }
    }
    // Every path ran: refused options, REJECT's refusal and REJECT's computation.
    assert_eq!(
        refused,
        cases.len() * 3 * 2,
        "policy LEGACY with ANGLE, AREA and UNIFORM"
    );
    assert!(
        rejected > 0 && computed_under_reject > 0,
        "{rejected} {computed_under_reject}"
    );
}

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

#[test]
fn the_counter_sees_the_library_allocate_without_caller_scratch() {
    // Proves the counter works: without caller scratch the library allocates its own.
    let case = unit_quad();
    let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: None,
    };
    let before = allocations();
    tbasis::generate(&case.mesh(), &Options::default(), &mut output).unwrap();
    assert!(allocations() > before);
    // And it counts this thread only: another thread's allocations leave the count as it was.
    let before = allocations();
    std::thread::scope(|scope| {
        scope.spawn(|| vec![0u8; 64]);
    });
    let spawning = allocations() - before;
    let before = allocations();
    std::thread::scope(|scope| {
        scope.spawn(|| (0..100).map(|k| vec![k as u8; 64]).collect::<Vec<_>>());
    });
    assert_eq!(
        allocations() - before,
        spawning,
        "another thread's allocations were counted here"
    );
}
