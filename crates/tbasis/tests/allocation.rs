//! With caller scratch (and one thread), a call makes no heap allocation at all, per-vertex or
//! per-corner, counted on the calling thread. The C entry points are held to the same by
//! `tests/allocation.rs` at the repository root, with the same counter.

use tbasis::{scratch_size_for, DegeneratePolicy, Error, Method, Options, Output, Report, StridedMut};
use tbasis_test_support::alloc_count::{allocations, Counting};
use tbasis_test_support::cases::{mirror_fold, quantized_uv_sphere, unit_quad, Case};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations `call` makes on this thread (with caller scratch and one thread, the library makes
/// all of them here); it must return Ok.
fn allocations_during(what: &str, call: impl FnOnce() -> Result<Report, Error>) -> usize {
    let before = allocations();
    let result = call();
    let after = allocations();
    assert!(result.is_ok(), "{what}: {result:?}");
    after - before
}

/// Allocations made by one call with caller scratch; the result must be Ok.
fn allocations_during_call(case: &Case, options: &Options) -> usize {
    let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
    let mut bitangents = vec![[0.0f32; 3]; case.vertex_count()];
    let mesh = case.mesh();
    let mut scratch = vec![0u8; scratch_size_for(&mesh, options).unwrap()];
    let mut output = Output {
        tangents: StridedMut::from_slice(&mut tangents),
        bitangents: Some(StridedMut::from_slice(&mut bitangents)),
    };
    allocations_during(&case.name, || {
        tbasis::generate_with_scratch(&mesh, options, &mut output, &mut scratch)
    })
}

/// Allocations made by one per-corner call with caller scratch; the result must be Ok.
fn allocations_during_corners_call(case: &Case, options: &Options) -> usize {
    let mesh = case.mesh();
    let mut corners = vec![[0.0f32; 4]; mesh.corner_count()];
    let mut scratch = vec![0u8; scratch_size_for(&mesh, options).unwrap()];
    let mut tangents = StridedMut::from_slice(&mut corners);
    allocations_during(&case.name, || {
        tbasis::generate_corners_with_scratch(&mesh, options, &mut tangents, &mut scratch)
    })
}

#[test]
fn caller_scratch_means_no_allocation() {
    // The INHERIT cases need propagation, the mirror fold both handedness sums.
    let cases = [unit_quad(), mirror_fold(), quantized_uv_sphere()];
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
            ] {
                let options = Options::default().with_method(method).with_policy(policy);
                assert_eq!(
                    allocations_during_call(case, &options),
                    0,
                    "{} {method:?} {policy:?}",
                    case.name
                );
                assert_eq!(
                    allocations_during_corners_call(case, &options),
                    0,
                    "{} {method:?} {policy:?} per corner",
                    case.name
                );
            }
        }
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
