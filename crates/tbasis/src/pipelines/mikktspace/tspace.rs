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
use super::frames::Frames;
use crate::kernel::error::Error;
use crate::kernel::vector::{add, dot, equal, normal, normalize_if_not_zero, project_normalized, scale, Packed, Vec3};

/// Cosine of an angular threshold in degrees, as mikktspace.c computes it in float
/// (`genTangSpace`): -1 for the default 180 degrees.
pub(crate) fn threshold_cosine(degrees: f32) -> f32 {
    let angle = (degrees * core::f32::consts::PI) / 180.0f32;
    f64::from(angle).cos() as f32
}

/// What the per-group pass reads.
pub(crate) struct Inputs<'a> {
    /// Flags of each good triangle (after grouping).
    pub flags: &'a [u8],
    /// The triangle each good triangle is.
    pub order: &'a [u32],
    /// Per corner `3 g + k` of good triangle `g`: its projected unit dP/ds and dP/dt
    /// ([`Inputs::directions`]) and its corner angle ([`super::corner_terms`]).
    pub directions: Directions<'a>,
    pub angle: &'a [f32],
    /// Per good triangle: |dP/ds| and |dP/dt| over the texture area (read by [`Space::Full`]
    /// sums only).
    pub magnitudes: &'a [[f32; 2]],
    /// The threshold's cosine ([`threshold_cosine`]).
    pub threshold: f32,
    /// Per triangle: the face it splits from (two triangles of a quad always share a sub-group);
    /// `None`: every triangle is a face.
    pub face_of: Option<&'a [u32]>,
}

/// Where each corner's projected unit dP/ds and dP/dt (`EvalTspace`'s `vOs` and `vOt`) come from.
#[derive(Clone, Copy)]
pub(crate) enum Directions<'a> {
    /// Stored per corner by [`super::corner_terms`].
    Stored { s: &'a [Vec3], t: &'a [Vec3] },
    /// Projected when read, as [`super::corner_terms`] projects them: from each good triangle's
    /// welded vertices `ids`, their `attributes` (the normal) and the triangle's unit dP/ds and
    /// dP/dt `derivatives`. The fans project each corner's once, in lanes, which saves writing
    /// and reading back 24 bytes per corner, and the first touch of their memory; the pairwise
    /// comparison of a group, rare, projects them again for every pair it compares.
    Projected {
        attributes: &'a [Packed],
        ids: &'a [[u32; 3]],
        derivatives: [&'a [Vec3]; 2],
    },
}

impl Inputs<'_> {
    /// Corner `c`'s projected unit dP/ds and dP/dt: the triangle's unit derivatives with their
    /// components along the corner's normal removed, normalized (`EvalTspace`).
    #[inline(always)]
    pub fn directions(&self, c: usize) -> [Vec3; 2] {
        match self.directions {
            Directions::Stored { s, t } => [s[c], t[c]],
            Directions::Projected {
                attributes,
                ids,
                derivatives,
            } => {
                let g = c / 3;
                projected(attributes, ids[g][c % 3], [derivatives[0][g], derivatives[1][g]])
            }
        }
    }
}

/// [`Directions::Projected`]'s directions of a corner whose welded vertex is `id`. Out of line:
/// only the rare pairwise comparison reads them one by one.
#[inline(never)]
fn projected(attributes: &[Packed], id: u32, derivatives: [Vec3; 2]) -> [Vec3; 2] {
    let n = normal(&attributes[id as usize]);
    [
        project_normalized(derivatives[0], n),
        project_normalized(derivatives[1], n),
    ]
}

/// What a corner's sub-group sum holds: the tangent alone, or all of `setTSpace`'s outputs.
pub(crate) trait Space: Copy + Send + Sync {
    /// The running sum over a sub-group's usable corners.
    type Sum: Default;
    /// Adds corner `c` (of good triangle `c / 3`), whose projected directions are `directions`,
    /// weighted by its angle (`EvalTspace`).
    fn add_with(sum: &mut Self::Sum, inputs: &Inputs, c: usize, directions: [Vec3; 2]);
    /// [`Space::add_with`] with the directions read from `inputs`.
    #[inline(always)]
    fn add(sum: &mut Self::Sum, inputs: &Inputs, c: usize) {
        Self::add_with(sum, inputs, c, inputs.directions(c));
    }
    /// The sub-group's space from its sum.
    fn finish(sum: Self::Sum) -> Self;
    /// The spaces as tangents alone, when they are nothing more.
    fn tangents(spaces: &mut [Self]) -> Option<&mut [Vec3]>;
}

impl Space for Vec3 {
    type Sum = Vec3;
    #[inline(always)]
    fn add_with(sum: &mut Vec3, inputs: &Inputs, c: usize, [s, _]: [Vec3; 2]) {
        *sum = add(*sum, scale(inputs.angle[c], s));
    }
    #[inline(always)]
    fn finish(sum: Vec3) -> Vec3 {
        normalize_if_not_zero(sum)
    }
    fn tangents(spaces: &mut [Vec3]) -> Option<&mut [Vec3]> {
        Some(spaces)
    }
}

/// `STSpace` without its orientation: unit tangent and bitangent, and the angle-weighted means of
/// |dP/ds| and |dP/dt|.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Full {
    pub s: Vec3,
    pub t: Vec3,
    pub mag_s: f32,
    pub mag_t: f32,
}

impl Full {
    /// What a corner no group reaches keeps (`genTangSpace`'s initial value).
    pub const DEFAULT: Full = Full {
        s: [1.0, 0.0, 0.0],
        t: [0.0, 1.0, 0.0],
        mag_s: 1.0,
        mag_t: 1.0,
    };

    /// `AvgTSpace`: two triangles of a quad meet at this face vertex. Equal spaces stay as they
    /// are (averaging would move their last bits).
    pub fn average(self, other: Full) -> Full {
        if self.mag_s == other.mag_s && self.mag_t == other.mag_t && equal(self.s, other.s) && equal(self.t, other.t) {
            return self;
        }
        Full {
            s: normalize_if_not_zero(add(self.s, other.s)),
            t: normalize_if_not_zero(add(self.t, other.t)),
            mag_s: 0.5 * (self.mag_s + other.mag_s),
            mag_t: 0.5 * (self.mag_t + other.mag_t),
        }
    }
}

impl Space for Full {
    /// The sums of angle * dP/ds, angle * dP/dt, angle * |dP/ds|, angle * |dP/dt| and angle.
    type Sum = (Full, f32);
    #[inline(always)]
    fn add_with((sum, angles): &mut (Full, f32), inputs: &Inputs, c: usize, [s, t]: [Vec3; 2]) {
        let angle = inputs.angle[c];
        let [mag_s, mag_t] = inputs.magnitudes[c / 3];
        sum.s = add(sum.s, scale(angle, s));
        sum.t = add(sum.t, scale(angle, t));
        sum.mag_s += angle * mag_s;
        sum.mag_t += angle * mag_t;
        *angles += angle;
    }
    #[inline(always)]
    fn finish((sum, angles): (Full, f32)) -> Full {
        let (mut mag_s, mut mag_t) = (sum.mag_s, sum.mag_t);
        if angles > 0.0 {
            mag_s /= angles;
            mag_t /= angles;
        }
        Full {
            s: normalize_if_not_zero(sum.s),
            t: normalize_if_not_zero(sum.t),
            mag_s,
            mag_t,
        }
    }
    fn tangents(_: &mut [Full]) -> Option<&mut [Vec3]> {
        None
    }
}

impl Default for Full {
    /// The zero sum.
    fn default() -> Full {
        Full {
            s: [0.0; 3],
            t: [0.0; 3],
            mag_s: 0.0,
            mag_t: 0.0,
        }
    }
}

/// A corner (its index), its space and its orientation, for another worker's range.
pub(crate) type Spilled<S> = (u32, S, u8);

/// Where one worker writes: the corners of the good triangles `goods`, in `frames`, its part of
/// the per-corner frames beginning with triangle `first_triangle`; the corners of its groups
/// outside its range go to `spilled`, written once every worker is done (it has room for all of
/// them before the first is written: see [`super::write_in_ranges`]).
pub(crate) struct Written<'a, S, F> {
    pub frames: F,
    pub goods: core::ops::Range<u32>,
    pub first_triangle: usize,
    pub spilled: &'a mut Vec<Spilled<S>>,
}

impl<S: Copy, F: Frames<S>> Written<'_, S, F> {
    /// Writes corner `c` (`3 g + k` for corner `k` of good triangle `g`, triangle `order[g]`), or
    /// spills it when `g` is outside the range. Fails when memory for a spill cannot be had.
    #[inline(always)]
    pub fn write(&mut self, order: &[u32], c: usize, space: S, preserving: bool) -> Result<(), Error> {
        let (good, k) = (c / 3, c % 3);
        let triangle = order[good] as usize;
        if self.goods.contains(&(good as u32)) {
            let corner = 3 * (triangle - self.first_triangle) + k;
            self.frames.set(corner, space, u8::from(preserving));
        } else {
            self.spilled.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
            self.spilled
                .push(((3 * triangle + k) as u32, space, u8::from(preserving)));
        }
        Ok(())
    }
}

/// Writes the space and orientation of the group's `corners` (`3 g + k` for corner `k` of good
/// triangle `g`, one per triangle, in ascending order): those outside `out`'s range are spilled.
/// Fails when memory for a spill cannot be had.
pub(crate) fn evaluate_group<S: Space, F: Frames<S>>(
    inputs: &Inputs,
    corners: &[u32],
    preserving: bool,
    out: &mut Written<S, F>,
) -> Result<(), Error> {
    let corner = |j: usize| corners[j] as usize;
    let good = |j: usize| corners[j] / 3;
    let usable = |j: usize| inputs.flags[good(j) as usize] & GROUP_WITH_ANY == 0;
    let write = |j: usize, space: S, out: &mut Written<S, F>| out.write(inputs.order, corner(j), space, preserving);
    let count = corners.len();

    // The usual case in one pass: the whole group's sum, and whether its directions lie in one
    // half-space (then, at 180 degrees, it is every member's sub-group).
    let (mut sum, mut half_s, mut half_t) = (S::Sum::default(), HalfSpace::default(), HalfSpace::default());
    for j in (0..count).filter(|&j| usable(j)) {
        let c = corner(j);
        let directions = inputs.directions(c);
        half_s.admit(directions[0]);
        half_t.admit(directions[1]);
        S::add_with(&mut sum, inputs, c, directions);
    }
    if half_s.holds && half_t.holds && inputs.threshold <= -1.0 {
        let space = S::finish(sum);
        for j in 0..count {
            write(j, space, out)?;
        }
        return Ok(());
    }

    // Some directions may lie past the threshold: compare every pair, as mikktspace.c does. Two
    // triangles of one face, or one without a usable derivative, always share a sub-group. The C
    // evaluates each distinct sub-group once and hands its space to every triangle whose
    // sub-group has the same members; the sum over the same members in the same order has the
    // same bits, so each member's is summed again here, which needs no memory.
    let within = |j: usize, k: usize| {
        let ([s_j, t_j], [s_k, t_k]) = (inputs.directions(corner(j)), inputs.directions(corner(k)));
        dot(s_j, s_k) > inputs.threshold && dot(t_j, t_k) > inputs.threshold
    };
    let face = |j: usize| {
        let triangle = inputs.order[good(j) as usize];
        inputs.face_of.map_or(triangle, |face_of| face_of[triangle as usize])
    };
    let member = |j: usize, k: usize| !usable(j) || !usable(k) || face(j) == face(k) || within(j, k);
    for j in 0..count {
        let mut sum = S::Sum::default();
        for k in (0..count).filter(|&k| usable(k) && member(j, k)) {
            S::add(&mut sum, inputs, corner(k));
        }
        write(j, S::finish(sum), out)?;
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
