//! What `EvalTspace` weighs at each corner of each good triangle, computed once per corner before
//! any group is evaluated: the triangle's unit dP/ds and dP/dt projected into the tangent plane
//! of the corner's welded normal and normalized (unless they are projected when read:
//! [`super::tspace::Directions`]), and the corner angle between its two edges, projected and
//! normalized likewise, `(float)acos((double)cos)`.
//!
//! These depend on the corner alone, not on its group, so a batch of triangles at a time runs
//! them in lanes that compile to SIMD ([`crate::simd`]): the same IEEE operations on every lane as
//! the scalar helpers of [`super::vector`], and [`acos_lanes`] gives [`crate::kernel::arc_cosine::acos`]'s
//! bits, so every corner gets the bits mikktspace.c computes for it.
#![forbid(unsafe_code)]

use crate::kernel::arc_cosine::acos_lanes;
use crate::kernel::lanes::{lane3, lanes_in_use, set_lane3, Lanes, LANES};
use crate::kernel::vector::{normal, position, project_normalized, projected_cosine, sub, Packed, Vec3};

/// Per corner `3 g + k` (corner `k` of good triangle `g`): the projected unit dP/ds and dP/dt
/// (`None`: not stored, [`super::tspace::Directions::Projected`]), and the corner angle.
pub(crate) struct CornerTerms<'a> {
    pub directions: Option<[&'a mut [Vec3]; 2]>,
    pub angle: &'a mut [f32],
}

/// Fills `terms` for the good triangles `ids` (their welded vertices, whose `attributes` these
/// are), with unit dP/ds and dP/dt `derivatives`.
pub(crate) fn compute(attributes: &[Packed], ids: &[[u32; 3]], derivatives: [&[Vec3]; 2], mut terms: CornerTerms) {
    crate::kernel::simd::run(
        #[inline(always)]
        || {
            let triangles = ids
                .chunks(LANES)
                .zip(derivatives[0].chunks(LANES))
                .zip(derivatives[1].chunks(LANES));
            for (batch_index, ((ids, tangent_s), tangent_t)) in triangles.enumerate() {
                let corners = 3 * batch_index * LANES..3 * (batch_index * LANES + ids.len());
                let directions = terms
                    .directions
                    .as_mut()
                    .map(|[s, t]| [&mut s[corners.clone()], &mut t[corners.clone()]]);
                let angle = &mut terms.angle[corners];
                batch(
                    attributes,
                    ids,
                    [tangent_s, tangent_t],
                    CornerTerms { directions, angle },
                );
            }
        },
    );
}

/// One batch of at most [`LANES`] triangles.
#[inline(always)]
fn batch(attributes: &[Packed], ids: &[[u32; 3]], derivatives: [&[Vec3]; 2], mut terms: CornerTerms) {
    // `[corner][component][lane]`, and each triangle's derivatives.
    let mut positions = [[[0.0; LANES]; 3]; 3];
    let mut normals = [[[0.0; LANES]; 3]; 3];
    let mut lanes_of_derivatives = [[[0.0; LANES]; 3]; 2];
    for (i, ids) in ids.iter().enumerate() {
        for (k, &id) in ids.iter().enumerate() {
            let packed = &attributes[id as usize];
            set_lane3(&mut positions[k], i, position(packed));
            set_lane3(&mut normals[k], i, normal(packed));
        }
        for (lanes, derivative) in lanes_of_derivatives.iter_mut().zip(derivatives) {
            set_lane3(lanes, i, derivative[i]);
        }
    }
    let lanes = lanes_in_use(ids.len());
    let lane = |v: &[Lanes; 3], i: usize| lane3(v, i).to_array();
    for k in 0..3 {
        let (next, previous) = ((k + 1) % 3, (k + 2) % 3);
        let mut cosines = [0.0; LANES];
        for (i, cosine) in cosines[..lanes].iter_mut().enumerate() {
            let corner = lane(&positions[k], i);
            let edges = (
                sub(lane(&positions[previous], i), corner),
                sub(lane(&positions[next], i), corner),
            );
            *cosine = projected_cosine(edges.0, edges.1, lane(&normals[k], i));
        }
        let mut angles = [0.0; LANES];
        acos_lanes(&cosines, &mut angles, lanes);
        for (i, &angle) in angles[..ids.len()].iter().enumerate() {
            terms.angle[3 * i + k] = angle;
        }
        if let Some([s, t]) = &mut terms.directions {
            let mut projected = [[[0.0; LANES]; 3]; 2];
            for i in 0..lanes {
                for (projected, derivative) in projected.iter_mut().zip(&lanes_of_derivatives) {
                    set_lane3(
                        projected,
                        i,
                        project_normalized(lane(derivative, i), lane(&normals[k], i)),
                    );
                }
            }
            for i in 0..ids.len() {
                s[3 * i + k] = lane(&projected[0], i);
                t[3 * i + k] = lane(&projected[1], i);
            }
        }
    }
}
