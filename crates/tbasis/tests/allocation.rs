//! With caller scratch (and one thread), a call makes no heap allocation at all, per-vertex or
//! per-corner, counted on the calling thread. The C entry points are held to the same by
//! `tests/allocation.rs` at the repository root, with the same counter.

use tbasis::{
    scratch_size_for, DegeneratePolicy, Error, ErrorKind, Method, Options, Output, Report, ScratchBuffer, StridedMut,
};
use tbasis_test_support::alloc_count::{allocations, Counting};
use tbasis_test_support::cases::{mirror_fold, quantized_uv_sphere, unit_quad, Case};

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

#[test]
fn a_scratch_buffer_allocates_only_for_a_mesh_larger_than_all_before() {
    let (small, large) = (unit_quad(), quantized_uv_sphere());
    for method in [Method::Lengyel, Method::Angle, Method::Mikktspace] {
        let options = Options::default().with_method(method);
        let mut scratch = ScratchBuffer::new();
        let mut per_vertex = |case: &Case| {
            let mesh = case.mesh();
            let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
            let mut output = Output {
                tangents: StridedMut::from_slice(&mut tangents),
                bitangents: None,
            };
            let (count, result) = allocations_during(|| scratch.generate(&mesh, &options, &mut output));
            result.unwrap();
            count
        };
        assert!(per_vertex(&small) > 0, "{method:?}: the first mesh allocates");
        assert!(per_vertex(&large) > 0, "{method:?}: a larger mesh grows the buffer");
        for case in [&small, &large, &small] {
            assert_eq!(per_vertex(case), 0, "{method:?}: no larger than before");
        }
        let mut per_corner = |case: &Case| {
            let mesh = case.mesh();
            let mut corners = vec![[0.0f32; 4]; mesh.corner_count()];
            let mut tangents = StridedMut::from_slice(&mut corners);
            let (count, result) = allocations_during(|| scratch.generate_corners(&mesh, &options, &mut tangents));
            result.unwrap();
            count
        };
        for case in [&small, &large] {
            assert_eq!(per_corner(case), 0, "{method:?} per corner: the buffer holds enough");
        }
    }
}
