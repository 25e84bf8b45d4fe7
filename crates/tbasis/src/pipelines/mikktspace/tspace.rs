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
use crate::kernel::error::Error;
use crate::kernel::vector::{add, dot, normalize_if_not_zero, scale, Vec3};

/// Cosine of the default 180-degree angular threshold, as mikktspace.c computes it in float.
fn threshold_cosine() -> f32 {
    let angle = (180.0f32 * core::f32::consts::PI) / 180.0f32;
    f64::from(angle).cos() as f32
}

/// What the per-group pass reads.
pub(crate) struct Inputs<'a> {
    /// Welded vertices of each good triangle.
    pub ids: &'a [[u32; 3]],
    /// Flags of each good triangle (after grouping).
    pub flags: &'a [u8],
    /// The triangle each good triangle is.
    pub order: &'a [u32],
    /// Per corner `3 g + k` of good triangle `g`: its projected unit dP/ds and dP/dt and its
    /// corner angle ([`super::corner_terms`]).
    pub s: &'a [Vec3],
    pub t: &'a [Vec3],
    pub angle: &'a [f32],
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
/// Fails when memory for a spill or for the pairwise comparison cannot be had.
pub(crate) fn evaluate_group(
    inputs: &Inputs,
    faces: &[u32],
    vertex: u32,
    preserving: bool,
    out: &mut Written,
) -> Result<(), Error> {
    let corner = |j: usize| {
        let f = faces[j] as usize;
        3 * f + inputs.ids[f].iter().position(|&id| id == vertex).unwrap_or(0)
    };
    let (s, t, angle) = (inputs.s, inputs.t, inputs.angle);
    let usable = |j: usize| inputs.flags[faces[j] as usize] & GROUP_WITH_ANY == 0;
    let write = |j: usize, tangent: Vec3, out: &mut Written| -> Result<(), Error> {
        let (triangle, k) = (inputs.order[faces[j] as usize] as usize, corner(j) % 3);
        if out.goods.contains(&faces[j]) {
            let corner = 3 * (triangle - out.first_triangle) + k;
            out.tangents[corner] = tangent;
            out.orientation[corner] = u8::from(preserving);
        } else {
            out.spilled.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
            out.spilled
                .push(((3 * triangle + k) as u32, tangent, u8::from(preserving)));
        }
        Ok(())
    };
    let count = faces.len();

    // The usual case in one pass: the whole group's sum, and whether its directions lie in one
    // half-space (then it is every member's sub-group).
    let (mut sum, mut half_s, mut half_t) = ([0.0; 3], HalfSpace::default(), HalfSpace::default());
    for j in (0..count).filter(|&j| usable(j)) {
        let c = corner(j);
        half_s.admit(s[c]);
        half_t.admit(t[c]);
        sum = add(sum, scale(angle[c], s[c]));
    }
    if half_s.holds && half_t.holds {
        let tangent = normalize_if_not_zero(sum);
        for j in 0..count {
            write(j, tangent, out)?;
        }
        return Ok(());
    }

    // Some directions may be exactly opposite: compare every pair, as mikktspace.c does.
    let threshold = threshold_cosine();
    let within = |terms: &[Vec3], j: usize, k: usize| dot(terms[corner(j)], terms[corner(k)]) > threshold;
    let member = |j: usize, k: usize| !usable(j) || !usable(k) || j == k || (within(s, j, k) && within(t, j, k));
    let mut subgroups: Vec<(Vec<usize>, Vec3)> = Vec::new();
    subgroups.try_reserve_exact(count).map_err(|_| Error::OutOfMemory)?;
    for j in 0..count {
        let mut own = Vec::new();
        own.try_reserve_exact(count).map_err(|_| Error::OutOfMemory)?;
        own.extend((0..count).filter(|&k| member(j, k)));
        let tangent = match subgroups.iter().find(|(m, _)| *m == own) {
            Some((_, tangent)) => *tangent,
            None => {
                let mut sum = [0.0; 3];
                for &k in own.iter().filter(|&&k| usable(k)) {
                    sum = add(sum, scale(angle[corner(k)], s[corner(k)]));
                }
                let tangent = normalize_if_not_zero(sum);
                subgroups.push((own, tangent));
                tangent
            }
        };
        write(j, tangent, out)?;
    }
    Ok(())
}

/// Whether no two of the directions admitted so far can have a cosine of -1 or less, nor a `NaN`
/// one: every one is finite and either short (length at most 1/2, whose cosine with any of these
/// stays above -1) or unit length within 1e-4 and more than 0.01 along the first unit one. Two
/// such unit vectors sum to at least 0.02 along that axis, so their computed dot product stays
/// above -1 + 1e-4 minus a few float roundings.
struct HalfSpace {
    axis: Option<Vec3>,
    holds: bool,
}

impl Default for HalfSpace {
    fn default() -> Self {
        HalfSpace {
            axis: None,
            holds: true,
        }
    }
}

impl HalfSpace {
    #[inline(always)]
    fn admit(&mut self, d: Vec3) {
        let squared = dot(d, d);
        let admitted = if !d.iter().all(|x| x.is_finite()) {
            false
        } else if squared <= 0.25 {
            true
        } else if (squared - 1.0).abs() > 1e-4 {
            false
        } else {
            match self.axis {
                None => {
                    self.axis = Some(d);
                    true
                }
                Some(a) => dot(a, d) > 0.01,
            }
        };
        self.holds &= admitted;
    }
}
