//! The README's "Memory": policy INHERIT's adjacency (`8 V + 4 C` bytes of the scratch) is written
//! only when some vertex needs a neighbour's tangent. Seen in a caller's scratch filled with a
//! marker before the call: the adjacency's bytes keep it unless a vertex inherits.

use tbasis::{generate_with_scratch, scratch_size_for, DegeneratePolicy, Options, Output};
use tbasis_test_support::cases::{self, Case};
use tbasis_test_support::shapes::flat_grid;

const MARKER: u8 = 0xA5;

/// Bytes of a caller's scratch still holding the marker after a call on `case` with `policy`, and
/// how many vertices inherited.
fn untouched_after(case: &Case, policy: DegeneratePolicy) -> (usize, usize) {
    let mesh = case.mesh();
    let options = Options::default().with_policy(policy);
    let mut scratch = vec![MARKER; scratch_size_for(&mesh, &options).expect("a size")];
    let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
    let report = generate_with_scratch(&mesh, &options, &mut Output::new(tangents.as_mut_slice()), &mut scratch)
        .expect("generated");
    let untouched = scratch.iter().filter(|&&b| b == MARKER).count();
    (untouched, report.inherited_vertices)
}

/// INHERIT's scratch less SKIP's, which lays out the same arrays but the adjacency (and up to 3
/// bytes of alignment), and the bytes that INHERIT left untouched beyond what SKIP did; how many
/// vertices inherited.
fn adjacency_and_untouched(case: &Case) -> (usize, usize, usize) {
    let mesh = case.mesh();
    let size = |policy| scratch_size_for(&mesh, &Options::default().with_policy(policy)).expect("a size");
    let adjacency = size(DegeneratePolicy::Inherit) - size(DegeneratePolicy::Skip);
    let (skip, _) = untouched_after(case, DegeneratePolicy::Skip);
    let (inherit, inherited) = untouched_after(case, DegeneratePolicy::Inherit);
    (adjacency, inherit.saturating_sub(skip), inherited)
}

#[test]
fn inherit_writes_its_adjacency_only_when_a_vertex_inherits() {
    for case in [cases::unit_quad(), flat_grid("grid", 16, 16, 1.0 / 16.0)] {
        let (adjacency, untouched, inherited) = adjacency_and_untouched(&case);
        assert_eq!(inherited, 0, "{}", case.name);
        assert!(adjacency > 3, "{}: no adjacency", case.name);
        assert!(
            untouched + 3 >= adjacency && untouched <= adjacency + 3,
            "{}: {untouched} more bytes untouched than under SKIP, the adjacency takes {adjacency}",
            case.name
        );
    }
    // A vertex used only by a zero-area triangle takes its neighbours' tangent through it.
    let case = cases::zero_area_midpoint();
    let (adjacency, untouched, inherited) = adjacency_and_untouched(&case);
    assert!(inherited > 0, "{}: nothing inherited", case.name);
    assert!(
        untouched + 3 < adjacency,
        "{}: {untouched} more bytes untouched than under SKIP, the adjacency takes {adjacency}",
        case.name
    );
}
