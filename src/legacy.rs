//! The original listing (Lengyel 2001, `CalculateTangentArray`), operation for operation.
//!
//! Kept apart from the other kernels on purpose: every float operation here runs in the listing's
//! order, so policy LEGACY reproduces its bits, including the inf/NaN it writes when a triangle's
//! UV determinant is zero. Rust never fuses a multiply and an add, so no FMA changes a result.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::mesh::{Mesh, OutputPart};
use crate::report::Report;
use crate::scratch::{flag, Scratch};
use crate::status::Error;
use crate::strided::Strided;

/// First loop of the listing: per triangle, solve `[T B] = [Q1 Q2] * inverse([s1 t1; s2 t2])`
/// and add `sdir` (dP/du) to `tan1`, `tdir` (dP/dv) to `tan2` of its three vertices, in triangle
/// order, for the vertices `scratch` holds. Also checks every index, and counts the
/// zero-determinant or non-finite triangles whose first vertex it holds.
pub fn accumulate(
    mesh: &Mesh,
    texcoords: Strided<[f32; 2]>,
    flip_v: bool,
    scratch: &mut Scratch,
) -> Result<Report, Error> {
    let mut report = Report::default();
    let v_sign = if flip_v { -1.0 } else { 1.0 };
    for a in 0..mesh.indices.triangle_count(mesh.vertex_count())? {
        let [i1, i2, i3] = mesh.checked_triangle(a)?;
        let slots = [i1, i2, i3].map(|i| scratch.slot(i));
        if slots == [None; 3] {
            continue;
        }
        let (v1, v2, v3) = (mesh.positions.get(i1), mesh.positions.get(i2), mesh.positions.get(i3));
        let (w1, w2, w3) = (texcoords.get(i1), texcoords.get(i2), texcoords.get(i3));

        let x1 = v2[0] - v1[0];
        let x2 = v3[0] - v1[0];
        let y1 = v2[1] - v1[1];
        let y2 = v3[1] - v1[1];
        let z1 = v2[2] - v1[2];
        let z2 = v3[2] - v1[2];

        let s1 = w2[0] - w1[0];
        let s2 = w3[0] - w1[0];
        let t1 = (w2[1] - w1[1]) * v_sign;
        let t2 = (w3[1] - w1[1]) * v_sign;

        let det = s1 * t2 - s2 * t1;
        let r = 1.0f32 / det;
        let sdir = [
            (t2 * x1 - t1 * x2) * r,
            (t2 * y1 - t1 * y2) * r,
            (t2 * z1 - t1 * z2) * r,
        ];
        let tdir = [
            (s1 * x2 - s2 * x1) * r,
            (s1 * y2 - s2 * y1) * r,
            (s1 * z2 - s2 * z1) * r,
        ];

        let finite = [x1, x2, y1, y2, z1, z2, s1, s2, t1, t2].iter().all(|x| x.is_finite());
        let orientation = if det == 0.0 || !finite {
            if slots[0].is_some() {
                report.note_degenerate(a);
            }
            0
        } else if det > 0.0 {
            flag::POSITIVE_UV
        } else {
            flag::NEGATIVE_UV
        };

        for slot in slots.into_iter().flatten() {
            let sums = &mut scratch.sums[slot];
            for k in 0..3 {
                sums.primary[k] += sdir[k];
                sums.secondary[k] += tdir[k];
            }
            scratch.flags[slot] |= flag::REFERENCED | orientation;
        }
    }
    Ok(report)
}

/// Second loop of the listing: `T' = normalize(t - n * dot(n, t))`,
/// `w = dot(cross(n, t), tan2) < 0 ? -1 : 1`.
pub fn resolve(mesh: &Mesh, scratch: &Scratch, output: &mut OutputPart) {
    for (slot, sums) in scratch.sums.iter().enumerate() {
        let a = scratch.first + slot;
        let n = Vec3::from_array(mesh.normals.get(a));
        let t = Vec3::from_array(sums.primary);
        let tan2 = Vec3::from_array(sums.secondary);

        let orthogonal = t - n * dot(n, t);
        let tangent = orthogonal * (1.0 / dot(orthogonal, orthogonal).sqrt());
        let w = if dot(cross(n, t), tan2) < 0.0 { -1.0 } else { 1.0 };
        output.write(a, tangent, w, n);
    }
}

/// The listing's `Dot`: `x*x' + y*y' + z*z'`, summed left to right.
#[inline(always)]
fn dot(a: Vec3, b: Vec3) -> f32 {
    a.x * b.x + a.y * b.y + a.z * b.z
}

/// The listing's `Cross`.
#[inline(always)]
fn cross(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}
