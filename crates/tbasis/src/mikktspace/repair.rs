//! What the policies other than LEGACY change in mikktspace.c's result: REJECT refuses degenerate
//! triangles up front, and SKIP, INHERIT (and REJECT) replace only the corners where mikktspace.c
//! writes no usable frame.
#![forbid(unsafe_code)]

use glam::Vec3 as GlamVec3;

use super::vector::Vec3;
use super::NONE;
use crate::error::Error;
use crate::mesh::Mesh;
use crate::options::{DegeneratePolicy, Method, Options};
use crate::report::count_flags;
use crate::report::Report;
use crate::robust::accumulate;
use crate::robust::frame::{fallback_tangent, NO_NORMAL_TANGENT};
use crate::robust::frame::{is_unit_and_perpendicular, VertexNormal, FRAME_TOLERANCE};
use crate::robust::resolve::count_abnormal_normals;
use crate::scratch::OwnedScratch;

/// Fails with [`Error::DegenerateUv`], which carries the report, when a triangle is degenerate by
/// the test every other method's REJECT applies (UV or position quality below the threshold, or
/// non-finite input).
pub(crate) fn reject_degenerate(mesh: &Mesh, options: &Options) -> Result<(), Error> {
    let mut owned = OwnedScratch::allocate(mesh.vertex_count(), 0)?;
    let robust = Options {
        method: Method::Angle,
        ..*options
    };
    let mut scratch = owned.scratch();
    let mut found = accumulate::accumulate(mesh, &robust, &mut scratch)?;
    if found.degenerate_triangles > 0 {
        // The report every method's REJECT gives.
        count_flags(scratch.flags, &mut found);
        found.abnormal_normals = count_abnormal_normals(mesh);
        return Err(Error::DegenerateUv {
            triangle: found.first_degenerate_triangle,
            report: found,
        });
    }
    Ok(())
}

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
