//! What the policies other than LEGACY change in mikktspace.c's result: SKIP, INHERIT and REJECT
//! (whose refusal of degenerate triangles comes before this pipeline runs) make the smallest change
//! that turns each corner's tangent into a valid frame.
#![forbid(unsafe_code)]

use glam::Vec3 as GlamVec3;

use super::frames::Frames;
use super::NONE;
use crate::kernel::frame::{
    fallback_tangent, is_unit_length, length_and_direction, orthonormalize, FRAME_TOLERANCE, NO_NORMAL_TANGENT,
};
use crate::kernel::mesh::Mesh;
use crate::kernel::options::DegeneratePolicy;
use crate::kernel::report::Report;
use crate::kernel::simd::PREFETCH_CORNERS;
use crate::kernel::vector::Vec3;

/// A unit tangent whose component off the normal is below this is along the normal: what is left
/// is rounding, not a direction.
const MIN_IN_PLANE: f32 = 1e-3;

/// How far off the unit normal's plane a tangent mikktspace.c wrote may be and still be kept bit
/// for bit (at most 1e-4 radians, 0.006 degrees, from the plane). mikktspace.c removes the normal
/// from each corner's term, then normalizes the group's sum, where terms that nearly cancel magnify
/// the off-plane rounding (up to 6.7e-5 on the corpus's unit normals).
const KEPT_OFF_PLANE: f32 = 1e-4;

/// A caller's normal as the repair reads it.
#[derive(Clone, Copy)]
struct Normal {
    /// Unit length; `None` when the normal is zero or not finite.
    unit: Option<GlamVec3>,
    /// `|1 - |n|^2|` for a normal unit length within 1e-3 (else 0): mikktspace.c removes the normal
    /// as the caller gave it, so its tangent is off the unit normal's plane by up to this much
    /// more, the normal's error, not the tangent's (0.99996-long normals leave tangents 1.1e-5 off).
    slack: f32,
}

impl Normal {
    fn of_vertex(mesh: &Mesh, v: usize) -> Self {
        match length_and_direction(GlamVec3::from_array(mesh.normals.get(v))) {
            Some((length, unit)) => Normal {
                unit: Some(unit),
                slack: if is_unit_length(length) {
                    (1.0 - length * length).abs()
                } else {
                    0.0
                },
            },
            None => Normal { unit: None, slack: 0.0 },
        }
    }
}

/// True when mikktspace.c's `tangent` is kept bit for bit: finite, unit length within
/// [`FRAME_TOLERANCE`], and off the unit normal's plane by at most [`KEPT_OFF_PLANE`] plus the
/// normal's own error.
fn is_kept(tangent: Vec3, normal: Normal) -> bool {
    let t = GlamVec3::from_array(tangent);
    let unit = t.is_finite() && (t.length() - 1.0).abs() <= FRAME_TOLERANCE;
    unit && normal
        .unit
        .is_none_or(|n| n.dot(t).abs() <= KEPT_OFF_PLANE + normal.slack)
}

/// The unit tangent nearest to `tangent` in the normal's plane: the normal removed, normalized.
/// `None` when `tangent` is zero, not finite, or (all but) along the normal.
fn nearest_valid(tangent: Vec3, normal: Normal) -> Option<Vec3> {
    let (_, direction) = length_and_direction(GlamVec3::from_array(tangent))?;
    match orthonormalize(direction, normal.unit)? {
        (in_plane, unit) if in_plane > MIN_IN_PLANE => Some(unit.to_array()),
        _ => None,
    }
}

/// Makes every corner tangent valid with the smallest change, the sign kept: a tangent
/// [`is_kept`] stays as it is; one with a direction off the normal's plane is moved into it and
/// normalized; one without (zero, not finite, along the normal) takes, under INHERIT, the tangent
/// of the first corner of the same vertex that has one, moved into the plane (a kept tangent may
/// lie off it by [`KEPT_OFF_PLANE`] plus the normal's own error), else (and under SKIP and REJECT)
/// the fallback tangent built from the normal. `report.repaired_corners` counts the corners
/// changed. `first_usable` holds a word per vertex.
pub(crate) fn repair(
    mesh: &Mesh,
    policy: DegeneratePolicy,
    frames: &mut impl Frames<Vec3>,
    first_usable: &mut [u32],
    report: &mut Report,
) {
    // The corners' vertices are scattered: each normal is asked for ahead of its corner.
    let corner_count = frames.corners();
    let mut without_direction = 0usize;
    for c in 0..corner_count {
        if c + PREFETCH_CORNERS < corner_count {
            mesh.normals.prefetch(mesh.indices.corner(c + PREFETCH_CORNERS));
        }
        let normal = Normal::of_vertex(mesh, mesh.indices.corner(c));
        let (tangent, preserving) = frames.get(c);
        if is_kept(tangent, normal) {
            continue;
        }
        report.repaired_corners += 1;
        let repaired = nearest_valid(tangent, normal).unwrap_or_else(|| {
            without_direction += 1;
            WITHOUT_DIRECTION
        });
        frames.set(c, repaired, preserving);
    }
    if without_direction == 0 {
        return;
    }
    // Rare: each vertex's first corner with a tangent, then the corners without one.
    let has_direction = |tangent: &Vec3| tangent[0].to_bits() != WITHOUT_DIRECTION[0].to_bits();
    first_usable.fill(NONE);
    for c in 0..corner_count {
        let first = &mut first_usable[mesh.indices.corner(c)];
        if *first == NONE && has_direction(&frames.get(c).0) {
            *first = c as u32;
        }
    }
    for c in 0..corner_count {
        let (tangent, preserving) = frames.get(c);
        if has_direction(&tangent) {
            continue;
        }
        let v = mesh.indices.corner(c);
        let normal = Normal::of_vertex(mesh, v);
        let fallback = || normal.unit.map_or(NO_NORMAL_TANGENT, fallback_tangent).to_array();
        let repaired = match first_usable[v] {
            donor if donor != NONE && policy == DegeneratePolicy::Inherit => {
                nearest_valid(frames.get(donor as usize).0, normal).unwrap_or_else(fallback)
            }
            _ => fallback(),
        };
        frames.set(c, repaired, preserving);
    }
}

/// What a corner without a direction holds between the two passes of [`repair`]: a NaN, which no
/// kept or moved tangent is.
const WITHOUT_DIRECTION: Vec3 = [f32::NAN; 3];

#[cfg(test)]
mod tests {
    use super::super::frames::Arrays;
    use super::*;

    #[test]
    fn an_inherited_tangent_lies_in_the_unit_normals_plane() {
        // A normal 1.0005 long: mikktspace.c's tangent at its vertex is kept 6e-4 off the unit
        // normal's plane (the normal's own error), and the corner without a tangent inherits it.
        let normal = [-0.03125, 0.0, 1.0];
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let normals = [normal; 3];
        let indices = [0u32, 1, 2, 0, 2, 1];
        let mesh = Mesh::new(&positions[..], &normals[..]).with_indices(&indices[..]);
        let n = GlamVec3::from_array(normal).normalize();
        let in_plane = (GlamVec3::X - n * n.x).normalize();
        let kept = (in_plane + 6e-4 * n).normalize();
        let mut tangents = [
            kept.to_array(),
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
        ];
        tangents[1] = (GlamVec3::Y - n * n.y).normalize().to_array();
        tangents[2] = tangents[1];
        tangents[4] = tangents[1];
        tangents[5] = tangents[1];
        let mut report = Report::default();
        repair(
            &mesh,
            DegeneratePolicy::Inherit,
            &mut Arrays {
                spaces: &mut tangents,
                orientation: &mut [1; 6],
            },
            &mut [0; 3],
            &mut report,
        );
        assert_eq!(tangents[0], kept.to_array(), "mikktspace.c's tangent is kept");
        let inherited = GlamVec3::from_array(tangents[3]);
        assert!(
            inherited.dot(n).abs() <= 1e-6,
            "{inherited} is off the plane by {}",
            inherited.dot(n)
        );
        assert!((inherited.length() - 1.0).abs() <= 1e-6);
        assert!(
            inherited.dot(in_plane) > 0.9999,
            "{inherited} is not the inherited direction"
        );
        assert_eq!(report.repaired_corners, 1);
    }
}
