//! Per-triangle tangents for every policy but LEGACY, weighted per method and summed per vertex
//! by handedness.
#![forbid(unsafe_code)]

use glam::{Vec2, Vec3};

use crate::degenerate::Shape;
use crate::frame::length_and_direction;
use crate::mesh::Mesh;
use crate::options::{Method, Options};
use crate::report::Report;
use crate::scratch::{flag, Scratch};
use crate::status::Error;
use crate::strided::Strided;

/// What one non-degenerate triangle contributes.
struct FaceTangent {
    /// Direction of dP/du, unit length.
    direction: Vec3,
    /// `|dP/du|`, kept apart from the direction so that neither overflows at extreme UV scales
    /// (UVs of 1e-20 give a length near 1e20, whose square no f32 holds).
    length: f32,
    /// `|edges[0] x edges[1]|`.
    twice_area: f32,
    /// Position edges `Q1`, `Q2` divided by their largest component.
    edges: [Vec3; 2],
    /// `edges[0] x edges[1]`: the face normal the winding gives, its length twice the scaled area.
    face_normal: Vec3,
    /// The largest component of `Q1`, `Q2`, to undo the scaling of areas.
    position_scale: f32,
    /// Sign of the UV determinant: true when the UV triangle winds counter-clockwise.
    positive_uv: bool,
    /// How much of its weight the triangle keeps (see [`Shape::confidence`]).
    confidence: f32,
}

/// Solves `Q1 = s1 T + t1 B`, `Q2 = s2 T + t2 B` for `T` (Lengyel 2001), or `None` when the
/// triangle is degenerate: a non-finite input, or a UV or position quality below `threshold`.
///
/// Both the UV and the position edges are divided by their largest component first: the quality
/// test and the 2x2 solve then work on numbers near 1 whatever the scale of the mesh or its UVs.
#[inline(always)]
fn face_tangent(p: &[Vec3; 3], uv: [Vec2; 3], v_sign: f32, threshold: f32) -> Option<FaceTangent> {
    let (q1, q2) = (p[1] - p[0], p[2] - p[0]);
    let flip = Vec2::new(1.0, v_sign);
    let (e1, e2) = ((uv[1] - uv[0]) * flip, (uv[2] - uv[0]) * flip);
    let uv_scale = e1.abs().max(e2.abs()).max_element();
    let position_scale = q1.abs().max(q2.abs()).max_element();
    // Also false for NaN: a non-finite input makes the triangle degenerate.
    let measurable =
        uv_scale > 0.0 && uv_scale < f32::INFINITY && position_scale > 0.0 && position_scale < f32::INFINITY;
    if !measurable {
        return None;
    }
    let (e1, e2) = (e1 * (1.0 / uv_scale), e2 * (1.0 / uv_scale));
    let (s1, s2) = (q1 * (1.0 / position_scale), q2 * (1.0 / position_scale));
    let det = e1.perp_dot(e2);
    let face_normal = s1.cross(s2);
    let uv_shape = Shape {
        twice_area: det.abs(),
        squared_edges: e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared(),
    };
    let position_shape = Shape {
        twice_area: face_normal.length(),
        squared_edges: s1.length_squared() + s2.length_squared() + (s2 - s1).length_squared(),
    };
    if !(uv_shape.at_least(threshold) && position_shape.at_least(threshold)) {
        return None;
    }
    // T = (t2 Q1 - t1 Q2) / det; with scaled UV edges, det = det' * uv_scale^2.
    let (numerator_length, direction) = length_and_direction(q1 * e2.y - q2 * e1.y)?;
    let length = numerator_length / (det.abs() * uv_scale);
    length.is_finite().then_some(FaceTangent {
        direction: direction * det.signum(),
        length,
        edges: [s1, s2],
        face_normal,
        position_scale,
        positive_uv: det > 0.0,
        confidence: uv_shape.confidence(),
        twice_area: position_shape.twice_area,
    })
}

/// The interior angle at corner `k`: `atan2(|e1 x e2|, e1 . e2)`, accurate for small and obtuse
/// angles alike; `|e1 x e2|` is the same at every corner (twice the area).
#[inline(always)]
fn corner_angle(face: &FaceTangent, k: usize) -> f32 {
    let [a, b] = face.edges;
    let (e1, e2) = match k {
        0 => (a, b),
        1 => (b - a, -a),
        _ => (-b, a - b),
    };
    atan2_upper(face.twice_area, e1.dot(e2))
}

/// `atan2(y, x)` for `y >= 0`, within 2e-6 radians: ample for a weight, and far cheaper than libm.
///
/// The octant is folded onto `atan(a)` with `a = min/max` in [0, 1], where an odd polynomial of
/// degree 11 (a minimax fit, maximum error 1.7e-6) stands in for it.
#[inline(always)]
fn atan2_upper(y: f32, x: f32) -> f32 {
    const C: [f32; 6] = [
        0.999_977_2,
        -0.332_622_86,
        0.193_540_4,
        -0.116_426_39,
        0.052_647_17,
        -0.011_719_046,
    ];
    let ax = x.abs();
    let (small, large) = if y <= ax { (y, ax) } else { (ax, y) };
    if large <= 0.0 {
        return 0.0;
    }
    let a = small / large;
    let s = a * a;
    let atan = a * (C[0] + s * (C[1] + s * (C[2] + s * (C[3] + s * (C[4] + s * C[5])))));
    let first_quadrant = if y > ax {
        core::f32::consts::FRAC_PI_2 - atan
    } else {
        atan
    };
    if x < 0.0 {
        core::f32::consts::PI - first_quadrant
    } else {
        first_quadrant
    }
}

/// What corner `k` (vertex normal `normal`) adds to its vertex: `(tangent * weight, weight)`.
///
/// LENGYEL adds the unnormalized dP/du, so long or stretched triangles dominate; ANGLE projects the
/// face tangent into the vertex's tangent plane, normalizes it and weights it by the corner angle
/// (as MikkTSpace does); AREA and UNIFORM add the unit face tangent weighted by area or by 1
/// (per-face averaging). Every weight is scaled by the triangle's confidence.
#[inline(always)]
fn corner_contribution(method: Method, face: &FaceTangent, k: usize, normal: Vec3) -> (Vec3, f32) {
    let (tangent, weight) = match method {
        Method::Lengyel => (face.direction, face.length),
        Method::Angle => {
            // T - N (N.T) / (N.N): the projection needs no unit normal, so no square root here.
            let n_squared = normal.length_squared();
            let projected = if n_squared > 0.0 && n_squared.is_finite() {
                face.direction - normal * (normal.dot(face.direction) / n_squared)
            } else {
                face.direction
            };
            (projected.normalize_or_zero(), corner_angle(face, k))
        }
        Method::Area => {
            let area = 0.5 * face.twice_area * face.position_scale * face.position_scale;
            (face.direction, area)
        }
        Method::Uniform => (face.direction, 1.0),
    };
    let weight = weight * face.confidence;
    (tangent * weight, weight)
}

/// Adds each triangle's tangent to its corners, split by the corner's handedness (the UV
/// orientation relative to the vertex normal), so that a vertex on a mirror fold can keep one
/// side's frame instead of a cancelled sum. Degenerate triangles only mark their vertices used.
pub fn accumulate(mesh: &Mesh, options: &Options, scratch: &mut Scratch) -> Result<Report, Error> {
    let mut report = Report::default();
    let v_sign = if options.flip_v { -1.0 } else { 1.0 };
    for t in 0..mesh.indices.triangle_count(mesh.vertex_count())? {
        let corners = mesh.checked_triangle(t)?;
        let slots = corners.map(|v| scratch.slot(v));
        if slots == [None; 3] {
            continue;
        }
        let p = corners.map(|v| Vec3::from_array(mesh.positions.get(v)));
        let face = mesh
            .texcoords
            .and_then(|uvs| face_tangent(&p, texcoords_of(uvs, corners), v_sign, options.degenerate_threshold));
        let Some(face) = face else {
            if mesh.texcoords.is_some() && slots[0].is_some() {
                report.note_degenerate(t);
            }
            slots
                .into_iter()
                .flatten()
                .for_each(|slot| scratch.flags[slot] |= flag::REFERENCED);
            continue;
        };
        let orientation = if face.positive_uv {
            flag::POSITIVE_UV
        } else {
            flag::NEGATIVE_UV
        };
        for (k, (&v, slot)) in corners.iter().zip(slots).enumerate() {
            let Some(slot) = slot else {
                continue;
            };
            let normal = Vec3::from_array(mesh.normals.get(v));
            let (contribution, weight) = corner_contribution(options.method, &face, k, normal);
            // A normal facing away from the winding turns the frame's handedness; a non-finite
            // normal says nothing about it.
            let facing_away = normal.is_finite() && normal.dot(face.face_normal) < 0.0;
            let right_handed = face.positive_uv != facing_away;
            let sums = &mut scratch.sums[slot];
            let side = if right_handed {
                &mut sums.primary
            } else {
                &mut sums.secondary
            };
            *side = (Vec3::from_array(*side) + contribution).to_array();
            sums.weight += weight;
            scratch.flags[slot] |= flag::REFERENCED | orientation;
        }
    }
    Ok(report)
}

#[inline(always)]
fn texcoords_of(uvs: Strided<[f32; 2]>, corners: [usize; 3]) -> [Vec2; 3] {
    corners.map(|v| Vec2::from_array(uvs.get(v)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_atan2_is_within_2e6_of_libm_over_the_upper_half_plane() {
        let mut worst = 0.0f32;
        for i in 0..=20_000 {
            let angle = core::f32::consts::PI * i as f32 / 20_000.0;
            for length in [1e-3f32, 1.0, 7.5e3] {
                let (y, x) = (angle.sin().abs() * length, angle.cos() * length);
                worst = worst.max((atan2_upper(y, x) - y.atan2(x)).abs());
            }
        }
        assert!(worst <= 2e-6, "worst error {worst}");
        assert_eq!(atan2_upper(0.0, 0.0), 0.0);
    }
}
