//! Per triangle: which are degenerate, and each good one's texture-space derivatives
//! (mikktspace.c's degenerate marking, `DegenPrologue` and the first half of `InitTriInfo`).
#![forbid(unsafe_code)]

use crate::kernel::lanes::{lane3, lanes_in_use, set_lane3, LANES};
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
    // The usual mesh has no degenerate triangle: a loop without branches, which vectorizes.
    if marks.iter().all(|&mark| mark == 0) {
        order.iter_mut().zip(0..).for_each(|(slot, t)| *slot = t);
        return order.len();
    }
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

/// Writes, for each good triangle `g` (welded vertices `ids[g]`), its unit dP/ds and dP/dt signed by
/// the UV orientation (zero where they vanish), its flags (`InitTriInfo`, eq. 18 and 19) and, when
/// asked, |dP/ds| and |dP/dt| over the texture area (`fMagS`, `fMagT`; only usable triangles'
/// are ever read). A
/// batch of triangles at a time, one per lane: every lane performs the C's operations in its
/// order, so the SIMD paths give its bits ([`crate::kernel::simd`]).
pub(crate) fn derivatives(
    attributes: &[Packed],
    ids: &[[u32; 3]],
    tangent_s: &mut [Vec3],
    tangent_t: &mut [Vec3],
    flags: &mut [u8],
    mut magnitudes: Option<&mut [[f32; 2]]>,
) {
    crate::kernel::simd::run(
        #[inline(always)]
        || {
            let outputs = tangent_s
                .chunks_mut(LANES)
                .zip(tangent_t.chunks_mut(LANES))
                .zip(flags.chunks_mut(LANES));
            for (batch, (ids, ((s, t), flags))) in ids.chunks(LANES).zip(outputs).enumerate() {
                let magnitudes = magnitudes.as_deref_mut().map(|m| &mut m[batch * LANES..][..ids.len()]);
                derivatives_batch(attributes, ids, [s, t], flags, magnitudes);
            }
        },
    );
}

/// [`derivatives`] for at most [`LANES`] triangles.
#[inline(always)]
fn derivatives_batch(
    attributes: &[Packed],
    ids: &[[u32; 3]],
    out: [&mut [Vec3]; 2],
    flags: &mut [u8],
    magnitudes: Option<&mut [[f32; 2]]>,
) {
    // `[corner][component][lane]`.
    let mut positions = [[[0.0; LANES]; 3]; 3];
    let mut texcoords = [[[0.0; LANES]; 2]; 3];
    for (i, ids) in ids.iter().enumerate() {
        for (k, &id) in ids.iter().enumerate() {
            let vertex = &attributes[id as usize];
            set_lane3(&mut positions[k], i, position(vertex));
            let [u, v] = texcoord(vertex);
            (texcoords[k][0][i], texcoords[k][1][i]) = (u, v);
        }
    }
    let mut lanes_out = [[[0.0; LANES]; 3]; 2];
    let mut lane_flags = [0u32; LANES];
    let mut lane_magnitudes = [[0.0f32; 2]; LANES];
    let [t1, t2, t3] = &texcoords;
    for i in 0..lanes_in_use(ids.len()) {
        let [v1, v2, v3] = [0, 1, 2].map(|k| lane3(&positions[k], i).to_array());
        let (t21x, t21y) = (t2[0][i] - t1[0][i], t2[1][i] - t1[1][i]);
        let (t31x, t31y) = (t3[0][i] - t1[0][i], t3[1][i] - t1[1][i]);
        let (d1, d2) = (sub(v2, v1), sub(v3, v1));
        let signed_area = t21x * t31y - t21y * t31x;
        let os = sub(scale(t31y, d1), scale(t21y, d2));
        let ot = add(scale(-t31x, d1), scale(t21x, d2));

        let preserving = signed_area > 0.0;
        let has_area = not_zero(signed_area);
        let abs_area = signed_area.abs();
        let (length_s, length_t) = (length(os), length(ot));
        let sign = if preserving { 1.0 } else { -1.0 };
        let s = if has_area && not_zero(length_s) {
            scale(sign / length_s, os)
        } else {
            [0.0; 3]
        };
        let t = if has_area && not_zero(length_t) {
            scale(sign / length_t, ot)
        } else {
            [0.0; 3]
        };
        // The magnitudes |dP/ds|, |dP/dt| only decide whether the triangle is usable.
        let magnitudes = [length_s / abs_area, length_t / abs_area];
        let usable = has_area & not_zero(magnitudes[0]) & not_zero(magnitudes[1]);
        lane_magnitudes[i] = magnitudes;
        set_lane3(&mut lanes_out[0], i, s);
        set_lane3(&mut lanes_out[1], i, t);
        let any = if usable { 0 } else { u32::from(GROUP_WITH_ANY) };
        let orientation = if preserving { u32::from(ORIENT_PRESERVING) } else { 0 };
        lane_flags[i] = any | orientation;
    }
    let [s, t] = out;
    for i in 0..ids.len() {
        s[i] = lane3(&lanes_out[0], i).to_array();
        t[i] = lane3(&lanes_out[1], i).to_array();
        flags[i] = lane_flags[i] as u8;
    }
    if let Some(magnitudes) = magnitudes {
        magnitudes.copy_from_slice(&lane_magnitudes[..ids.len()]);
    }
}

/// Gives the two good triangles of a quad one orientation where their texture coordinates
/// disagree (`InitTriInfo`): one without usable derivatives takes the other's, else the larger
/// texture area decides (the first triangle's on a tie). `ids`, `flags` are per good triangle,
/// `order` the triangle each is, and `face_of` each triangle's face.
pub(crate) fn force_quad_orientation(
    attributes: &[Packed],
    ids: &[[u32; 3]],
    order: &[u32],
    face_of: &[u32],
    flags: &mut [u8],
) {
    let texture_area = |ids: [u32; 3]| {
        let [t1, t2, t3] = ids.map(|id| texcoord(&attributes[id as usize]));
        let (t21x, t21y) = (t2[0] - t1[0], t2[1] - t1[1]);
        let (t31x, t31y) = (t3[0] - t1[0], t3[1] - t1[1]);
        (t21x * t31y - t21y * t31x).abs()
    };
    for b in 1..ids.len() {
        let a = b - 1;
        let same_face = face_of[order[a] as usize] == face_of[order[b] as usize];
        if !same_face || (flags[a] ^ flags[b]) & ORIENT_PRESERVING == 0 {
            continue;
        }
        let keep_first = flags[b] & GROUP_WITH_ANY != 0 || texture_area(ids[a]) >= texture_area(ids[b]);
        let (from, to) = if keep_first { (a, b) } else { (b, a) };
        flags[to] = (flags[to] & !ORIENT_PRESERVING) | (flags[from] & ORIENT_PRESERVING);
    }
}
