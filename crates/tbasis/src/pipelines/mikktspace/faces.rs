//! Per triangle: which are degenerate, and each good one's texture-space derivatives
//! (mikktspace.c's degenerate marking, `DegenPrologue` and the first half of `InitTriInfo`).
#![forbid(unsafe_code)]

use crate::kernel::vector::{add, equal, length, not_zero, position, scale, sub, texcoord, Packed, Vec3};

/// The triangle's texture area is positive (its UVs keep the winding).
pub(crate) const ORIENT_PRESERVING: u8 = 1;
/// The triangle has no usable derivative: it joins any group that reaches it and adds nothing.
pub(crate) const GROUP_WITH_ANY: u8 = 2;

/// Marks with 1 each triangle of `marks` (triangles `first..`) with two equal welded positions:
/// degenerate.
pub(crate) fn mark_degenerate(attributes: &[Packed], welded: &[u32], first: usize, marks: &mut [u8]) {
    let position = |corner: usize| position(&attributes[welded[corner] as usize]);
    for (t, mark) in (first..).zip(marks.iter_mut()) {
        let [p0, p1, p2] = [0, 1, 2].map(|k| position(3 * t + k));
        *mark = u8::from(equal(p0, p1) || equal(p0, p2) || equal(p1, p2));
    }
}

/// Fills `order` with the triangles `marks` leaves unmarked, in triangle order, then the marked
/// (degenerate) ones. Returns how many are good.
pub(crate) fn good_first(marks: &[u8], order: &mut [u32]) -> usize {
    let mut good = 0;
    let mut degenerate = order.len();
    for (t, &mark) in marks.iter().enumerate() {
        // Degenerate triangles keep no particular order: each only copies from good ones.
        if mark != 0 {
            degenerate -= 1;
            order[degenerate] = t as u32;
        } else {
            order[good] = t as u32;
            good += 1;
        }
    }
    good
}

/// Writes, for each good triangle `g` (triangle `order[g]`), its unit dP/ds and dP/dt signed by
/// the UV orientation (zero where they vanish) and its flags (`InitTriInfo`, eq. 18 and 19).
pub(crate) fn derivatives(
    attributes: &[Packed],
    welded: &[u32],
    order: &[u32],
    tangent_s: &mut [Vec3],
    tangent_t: &mut [Vec3],
    flags: &mut [u8],
) {
    for (g, &t) in order.iter().enumerate() {
        let vertex = |k: usize| &attributes[welded[3 * t as usize + k] as usize];
        let [v1, v2, v3] = [0, 1, 2].map(|k| position(vertex(k)));
        let [t1, t2, t3] = [0, 1, 2].map(|k| texcoord(vertex(k)));
        let (t21x, t21y) = (t2[0] - t1[0], t2[1] - t1[1]);
        let (t31x, t31y) = (t3[0] - t1[0], t3[1] - t1[1]);
        let (d1, d2) = (sub(v2, v1), sub(v3, v1));
        let signed_area = t21x * t31y - t21y * t31x;
        let os = sub(scale(t31y, d1), scale(t21y, d2));
        let ot = add(scale(-t31x, d1), scale(t21x, d2));

        let mut flag = GROUP_WITH_ANY;
        if signed_area > 0.0 {
            flag |= ORIENT_PRESERVING;
        }
        let (mut s, mut tt) = ([0.0; 3], [0.0; 3]);
        if not_zero(signed_area) {
            let abs_area = signed_area.abs();
            let (length_s, length_t) = (length(os), length(ot));
            let sign = if flag & ORIENT_PRESERVING == 0 { -1.0 } else { 1.0 };
            if not_zero(length_s) {
                s = scale(sign / length_s, os);
            }
            if not_zero(length_t) {
                tt = scale(sign / length_t, ot);
            }
            // The magnitudes |dP/ds|, |dP/dt| only decide whether the triangle is usable.
            if not_zero(length_s / abs_area) && not_zero(length_t / abs_area) {
                flag &= !GROUP_WITH_ANY;
            }
        }
        tangent_s[g] = s;
        tangent_t[g] = tt;
        flags[g] = flag;
    }
}
