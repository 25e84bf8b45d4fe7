//! Per-triangle tangents for every policy but LEGACY, weighted per method and summed per vertex
//! by handedness.
#![forbid(unsafe_code)]

use glam::{Vec2, Vec3};

use crate::degenerate::{confidence, position_quality, uv_quality};
use crate::frame::{careful_length, normalize_careful};
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
    /// Unnormalized face normal `Q1 x Q2`, the orientation the winding gives; its length is twice
    /// the area.
    face_normal: Vec3,
    /// Sign of the UV determinant: true when the UV triangle winds counter-clockwise.
    positive_uv: bool,
    /// How much of its weight the triangle keeps (see [`confidence`]).
    confidence: f32,
}

/// Solves `Q1 = s1 T + t1 B`, `Q2 = s2 T + t2 B` for `T` (Lengyel 2001), or `None` when the
/// triangle is degenerate: a non-finite input, or a UV or position quality below `threshold`.
///
/// The UV edges are divided by their largest component before the 2x2 solve, so the determinant
/// stays near 1 whatever the UV scale (1e-20 would otherwise underflow it).
#[inline(always)]
fn face_tangent(p: &[Vec3; 3], uv: [Vec2; 3], v_sign: f32, threshold: f32) -> Option<FaceTangent> {
    let (q1, q2) = (p[1] - p[0], p[2] - p[0]);
    let flip = Vec2::new(1.0, v_sign);
    let (e1, e2) = ((uv[1] - uv[0]) * flip, (uv[2] - uv[0]) * flip);
    if !(q1.is_finite() && q2.is_finite() && e1.is_finite() && e2.is_finite()) {
        return None;
    }
    let uv_q = uv_quality(e1, e2);
    // Written so that a NaN quality counts as degenerate.
    let well_shaped = uv_q >= threshold && uv_q > 0.0 && position_quality(q1, q2) >= threshold;
    if !well_shaped {
        return None;
    }
    let scale = e1.abs().max(e2.abs()).max_element();
    let (e1, e2) = (e1 / scale, e2 / scale);
    let det = e1.perp_dot(e2);
    // T = (t2 Q1 - t1 Q2) / det, with the UV edges scaled: det' = det / scale^2.
    let numerator = q1 * e2.y - q2 * e1.y;
    let direction = normalize_careful(numerator)? * det.signum();
    let length = careful_length(numerator) / (det.abs() * scale);
    let face_normal = q1.cross(q2);
    (length.is_finite() && face_normal.is_finite()).then_some(FaceTangent {
        direction,
        length,
        face_normal,
        positive_uv: det > 0.0,
        confidence: confidence(uv_q),
    })
}

/// The interior angle at corner `k` of triangle `p`: `atan2(|e1 x e2|, e1 . e2)`, accurate for
/// small and obtuse angles alike; `|e1 x e2|` is the same at every corner (twice the area).
#[inline(always)]
fn corner_angle(p: &[Vec3; 3], k: usize, twice_area: f32) -> f32 {
    let e1 = p[(k + 1) % 3] - p[k];
    let e2 = p[(k + 2) % 3] - p[k];
    twice_area.atan2(e1.dot(e2))
}

/// What corner `k` (vertex normal `normal`) adds to its vertex: `(tangent * weight, weight)`.
///
/// LENGYEL adds the unnormalized dP/du, so long or stretched triangles dominate; ANGLE projects the
/// face tangent into the vertex's tangent plane, normalizes it and weights it by the corner angle
/// (as MikkTSpace does); AREA and UNIFORM add the unit face tangent weighted by area or by 1
/// (per-face averaging). Every weight is scaled by the triangle's confidence.
#[inline(always)]
fn corner_contribution(method: Method, face: &FaceTangent, p: &[Vec3; 3], k: usize, normal: Vec3) -> (Vec3, f32) {
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
            (
                projected.normalize_or_zero(),
                corner_angle(p, k, face.face_normal.length()),
            )
        }
        Method::Area => (face.direction, 0.5 * face.face_normal.length()),
        Method::Uniform => (face.direction, 1.0),
    };
    let weight = weight * face.confidence;
    (tangent * weight, weight)
}

/// Adds each triangle's tangent to its corners, split by the corner's handedness (the UV
/// orientation relative to the vertex normal), so that a vertex on a mirror fold can keep one
/// side's frame instead of a cancelled sum. Degenerate triangles only mark their vertices used.
pub fn accumulate(mesh: &Mesh, options: &Options, scratch: &mut Scratch, report: &mut Report) -> Result<(), Error> {
    let v_sign = if options.flip_v { -1.0 } else { 1.0 };
    for t in 0..mesh.indices.triangle_count(mesh.vertex_count())? {
        let corners = mesh.checked_triangle(t)?;
        let p = corners.map(|v| Vec3::from_array(mesh.positions.get(v)));
        let face = mesh
            .texcoords
            .and_then(|uvs| face_tangent(&p, texcoords_of(uvs, corners), v_sign, options.degenerate_threshold));
        let Some(face) = face else {
            if mesh.texcoords.is_some() {
                report.note_degenerate(t);
            }
            corners.iter().for_each(|&v| scratch.flags[v] |= flag::REFERENCED);
            continue;
        };
        let orientation = if face.positive_uv {
            flag::POSITIVE_UV
        } else {
            flag::NEGATIVE_UV
        };
        for (k, &v) in corners.iter().enumerate() {
            let normal = Vec3::from_array(mesh.normals.get(v));
            let (contribution, weight) = corner_contribution(options.method, &face, &p, k, normal);
            // A normal facing away from the winding turns the frame's handedness; a non-finite
            // normal says nothing about it.
            let facing_away = normal.is_finite() && normal.dot(face.face_normal) < 0.0;
            let right_handed = face.positive_uv != facing_away;
            let sums = &mut scratch.sums[v];
            let side = if right_handed {
                &mut sums.primary
            } else {
                &mut sums.secondary
            };
            *side = (Vec3::from_array(*side) + contribution).to_array();
            sums.weight += weight;
            scratch.flags[v] |= flag::REFERENCED | orientation;
        }
    }
    Ok(())
}

#[inline(always)]
fn texcoords_of(uvs: Strided<[f32; 2]>, corners: [usize; 3]) -> [Vec2; 3] {
    corners.map(|v| Vec2::from_array(uvs.get(v)))
}
