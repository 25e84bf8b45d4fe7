//! The README's "Memory": policy INHERIT's adjacency (`8 V + 4 C` bytes of the scratch) is written
//! only when some vertex needs a neighbour's tangent. Seen in a caller's scratch filled with a
//! marker before the call: the adjacency's bytes keep it unless a vertex inherits.

use tbasis::{generate_with_scratch, scratch_size_for, DegeneratePolicy, Options, Output};
use tbasis_test_support::cases::{self, Case};
use tbasis_test_support::shapes::flat_grid;

const MARKER: u8 = 0xA5;

/// Bytes of the caller's scratch still holding the marker after an INHERIT call on `case`, the
/// adjacency's size (INHERIT's scratch less SKIP's), and how many vertices inherited.
fn untouched_after_inherit(case: &Case) -> (usize, usize, usize) {
    let mesh = case.mesh();
    let inherit = Options::default().with_policy(DegeneratePolicy::Inherit);
    let skip = Options::default().with_policy(DegeneratePolicy::Skip);
    let size = scratch_size_for(&mesh, &inherit).expect("a size");
    let adjacency = size - scratch_size_for(&mesh, &skip).expect("a size");
    let mut scratch = vec![MARKER; size];
    let mut tangents = vec![[0.0f32; 4]; case.vertex_count()];
    let report = generate_with_scratch(&mesh, &inherit, &mut Output::new(tangents.as_mut_slice()), &mut scratch)
        .expect("generated");
    let untouched = scratch.iter().filter(|&&b| b == MARKER).count();
    (untouched, adjacency, report.inherited_vertices)
}

#[test]
fn inherit_writes_its_adjacency_only_when_a_vertex_inherits() {
    for case in [cases::unit_quad(), flat_grid("grid", 16, 16, 1.0 / 16.0)] {
        let (untouched, adjacency, inherited) = untouched_after_inherit(&case);
        assert_eq!(inherited, 0, "{}", case.name);
        assert!(adjacency > 0, "{}: no adjacency", case.name);
        assert!(
            untouched >= adjacency,
            "{}: {untouched} bytes untouched, the adjacency takes {adjacency}",
            case.name
        );
    }
    // A vertex used only by a zero-area triangle takes its neighbours' tangent through it.
    let case = cases::zero_area_midpoint();
    let (untouched, adjacency, inherited) = untouched_after_inherit(&case);
    assert!(inherited > 0, "{}: nothing inherited", case.name);
    assert!(
        untouched < adjacency,
        "{}: {untouched} bytes untouched, the adjacency takes {adjacency}",
        case.name
    );
}
