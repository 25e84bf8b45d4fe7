//! What the policies other than LEGACY change in mikktspace.c's result: SKIP, INHERIT and REJECT
//! (whose refusal of degenerate triangles comes before this pipeline runs) replace only the
//! corners where mikktspace.c writes no usable frame.
#![forbid(unsafe_code)]

use glam::Vec3 as GlamVec3;

use super::NONE;
use crate::kernel::frame::{
    fallback_tangent, is_unit_and_perpendicular, VertexNormal, FRAME_TOLERANCE, NO_NORMAL_TANGENT,
};
use crate::kernel::mesh::Mesh;
use crate::kernel::options::DegeneratePolicy;
use crate::kernel::report::Report;
use crate::kernel::vector::Vec3;

/// True when `tangent` is a unit tangent perpendicular to `normal`.
fn usable(tangent: Vec3, normal: Option<GlamVec3>) -> bool {
    is_unit_and_perpendicular(GlamVec3::from_array(tangent), normal, FRAME_TOLERANCE)
}

/// Replaces every corner tangent that is not [`usable`]: under INHERIT by the first usable
/// tangent among the corners of the same vertex, else (and under SKIP and REJECT) by the fallback
/// tangent built from the normal. The sign is kept. `first_usable` holds a word per vertex.
pub(crate) fn repair(
    mesh: &Mesh,
    policy: DegeneratePolicy,
    tangents: &mut [Vec3],
    first_usable: &mut [u32],
    report: &mut Report,
) {
    let normal = |v: usize| VertexNormal::new(mesh.normals.get(v)).unit;
    first_usable.fill(NONE);
    if policy == DegeneratePolicy::Inherit {
        for (c, &tangent) in tangents.iter().enumerate() {
            let v = mesh.indices.corner(c);
            if first_usable[v] == NONE && usable(tangent, normal(v)) {
                first_usable[v] = c as u32;
            }
        }
    }
    for c in 0..tangents.len() {
        let v = mesh.indices.corner(c);
        let n = normal(v);
        if usable(tangents[c], n) {
            continue;
        }
        report.repaired_corners += 1;
        tangents[c] = match first_usable[v] {
            NONE => n.map_or(NO_NORMAL_TANGENT, fallback_tangent).to_array(),
            donor => tangents[donor as usize],
        };
    }
}
