//! One tangent per corner from its group (`GenerateTSpaces` and `EvalTspace`).
//!
//! Within a group, mikktspace.c gives each triangle the sub-group of the group's triangles whose
//! projected dP/ds and dP/dt both lie within the angular threshold of its own (with the default
//! 180 degrees: cosines above -1, so only exactly opposite directions part), and the corner's
//! tangent is the corner-angle-weighted sum of the projected dP/ds of that sub-group's usable
//! triangles, in ascending triangle order. Comparing every pair is quadratic in a vertex's valence;
//! when all projected directions of a group lie in one open half-space no pair can part, the
//! sub-group is the whole group, and one sum serves every corner.
#![forbid(unsafe_code)]

use super::faces::GROUP_WITH_ANY;
use super::vector::{
    add, dot, normal, normalize, position, project_normalized, projected_cosine, scale, sub, vector_not_zero, Packed,
    Vec3,
};
use crate::arc_cosine::acos;

/// Cosine of the default 180-degree angular threshold, as mikktspace.c computes it in float.
fn threshold_cosine() -> f32 {
    let angle = (180.0f32 * core::f32::consts::PI) / 180.0f32;
    f64::from(angle).cos() as f32
}

/// What the per-group pass reads.
pub(crate) struct Inputs<'a> {
    /// Attributes of each welded vertex.
    pub attributes: &'a [Packed],
    /// Welded vertices of each good triangle.
    pub ids: &'a [[u32; 3]],
    /// Unit dP/ds and dP/dt of each good triangle.
    pub tangent_s: &'a [Vec3],
    pub tangent_t: &'a [Vec3],
    /// Flags of each good triangle (after grouping).
    pub flags: &'a [u8],
    /// The triangle each good triangle is.
    pub order: &'a [u32],
}

/// Per member of the group being evaluated (room for the largest group): its corner `3g + k`,
/// its triangle's dP/ds and dP/dt projected into the tangent plane of the group's welded normal
/// and normalized, and the corner angle measured in that plane (0 for a triangle with no usable
/// derivative, which adds nothing).
pub(crate) struct MemberTerms<'a> {
    pub corner: &'a mut [u32],
    pub s: &'a mut [Vec3],
    pub t: &'a mut [Vec3],
    pub angle: &'a mut [f32],
}

impl MemberTerms<'_> {
    /// Runs `job` with terms of its own for groups of up to `len` triangles.
    pub fn with_owned<R>(len: usize, job: impl FnOnce(&mut MemberTerms) -> R) -> R {
        let (mut corner, mut s, mut t, mut angle) =
            (vec![0; len], vec![[0.0; 3]; len], vec![[0.0; 3]; len], vec![0.0; len]);
        job(&mut MemberTerms {
            corner: &mut corner,
            s: &mut s,
            t: &mut t,
            angle: &mut angle,
        })
    }
}

/// A corner (its index), its tangent and its orientation, for another worker's range.
pub(crate) type Spilled = (u32, Vec3, u8);

/// Where one worker writes: the corners of the good triangles `goods`, its part of the per-corner
/// arrays beginning with triangle `first_triangle`; the corners of its groups outside its range
/// go to `spilled`, written once every worker is done.
pub(crate) struct Written<'a> {
    pub tangents: &'a mut [Vec3],
    pub orientation: &'a mut [u8],
    pub goods: core::ops::Range<u32>,
    pub first_triangle: usize,
    pub spilled: &'a mut Vec<Spilled>,
}

/// Writes the tangent and orientation of the corners of the group's triangles `faces` (in
/// ascending order) around welded vertex `vertex`: those outside `out`'s range are spilled.
pub(crate) fn evaluate_group(
    inputs: &Inputs,
    faces: &[u32],
    vertex: u32,
    preserving: bool,
    terms: &mut MemberTerms,
    out: &mut Written,
) {
    let count = faces.len();
    let n = normal(&inputs.attributes[vertex as usize]);
    let usable = |f: u32| inputs.flags[f as usize] & GROUP_WITH_ANY == 0;
    for (j, &f) in faces.iter().enumerate() {
        let ids = inputs.ids[f as usize];
        let k = ids.iter().position(|&id| id == vertex).unwrap_or(0);
        terms.corner[j] = 3 * f + k as u32;
        terms.s[j] = project_normalized(inputs.tangent_s[f as usize], n);
        terms.t[j] = project_normalized(inputs.tangent_t[f as usize], n);
        terms.angle[j] = if usable(f) {
            corner_angle(inputs.attributes, ids, k, n)
        } else {
            0.0
        };
    }
    let (s, t, angle) = (&terms.s[..count], &terms.t[..count], &terms.angle[..count]);
    let usable = |j: usize| usable(faces[j]);
    let sum = |chosen: &mut dyn Iterator<Item = usize>| weighted_sum(chosen.map(|j| (angle[j], s[j])));
    let write = |j: usize, tangent: Vec3, out: &mut Written| {
        let (triangle, k) = (inputs.order[faces[j] as usize] as usize, terms.corner[j] as usize % 3);
        if out.goods.contains(&faces[j]) {
            let corner = 3 * (triangle - out.first_triangle) + k;
            out.tangents[corner] = tangent;
            out.orientation[corner] = u8::from(preserving);
        } else {
            out.spilled
                .push(((3 * triangle + k) as u32, tangent, u8::from(preserving)));
        }
    };

    if one_half_space(s, &usable) && one_half_space(t, &usable) {
        let tangent = sum(&mut (0..count).filter(|&j| usable(j)));
        for j in 0..count {
            write(j, tangent, out);
        }
        return;
    }

    // Some directions may be exactly opposite: compare every pair, as mikktspace.c does.
    let threshold = threshold_cosine();
    let member = |j: usize, k: usize| {
        !usable(j) || !usable(k) || j == k || (dot(s[j], s[k]) > threshold && dot(t[j], t[k]) > threshold)
    };
    let mut subgroups: Vec<(Vec<usize>, Vec3)> = Vec::new();
    for j in 0..count {
        let own: Vec<usize> = (0..count).filter(|&k| member(j, k)).collect();
        let tangent = match subgroups.iter().find(|(m, _)| *m == own) {
            Some((_, tangent)) => *tangent,
            None => {
                let tangent = sum(&mut own.iter().copied().filter(|&k| usable(k)));
                subgroups.push((own, tangent));
                tangent
            }
        };
        write(j, tangent, out);
    }
}

/// The corner angle at `ids[i]`, its two edges projected into the tangent plane of `n` first.
fn corner_angle(attributes: &[Packed], ids: [u32; 3], i: usize, n: Vec3) -> f32 {
    let position = |id: u32| position(&attributes[id as usize]);
    let p0 = position(ids[(i + 2) % 3]);
    let p1 = position(ids[i]);
    let p2 = position(ids[(i + 1) % 3]);
    acos(projected_cosine(sub(p0, p1), sub(p2, p1), n))
}

/// `sum(angle * s)` over `terms` in ascending triangle order, normalized when not zero.
fn weighted_sum(terms: impl Iterator<Item = (f32, Vec3)>) -> Vec3 {
    let mut sum = [0.0f32; 3];
    for (angle, s) in terms {
        sum = add(sum, scale(angle, s));
    }
    if vector_not_zero(sum) {
        normalize(sum)
    } else {
        sum
    }
}

/// True when no two usable `directions` can have a cosine of -1 or
/// less, nor a `NaN` one: every one is finite and either short (length at most 1/2, whose cosine
/// with any of these stays above -1) or unit length within 1e-4 and more than 0.01 along the
/// first unit one. Two such unit vectors sum to at least 0.02 along that axis, so their computed
/// dot product stays above -1 + 1e-4 minus a few float roundings.
fn one_half_space(directions: &[Vec3], usable: &dyn Fn(usize) -> bool) -> bool {
    let mut axis: Option<Vec3> = None;
    for (j, &d) in directions.iter().enumerate() {
        if !usable(j) {
            continue;
        }
        if !d.iter().all(|x| x.is_finite()) {
            return false;
        }
        let squared = dot(d, d);
        if squared <= 0.25 {
            continue;
        }
        if (squared - 1.0).abs() > 1e-4 {
            return false;
        }
        match axis {
            None => axis = Some(d),
            Some(a) => {
                if dot(a, d) <= 0.01 {
                    return false;
                }
            }
        }
    }
    true
}
