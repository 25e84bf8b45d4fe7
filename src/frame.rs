//! Orthonormal-frame helpers: Gram-Schmidt, careful normalization and the normal-only fallback.
#![forbid(unsafe_code)]

use glam::Vec3;

/// Removes the normal's component: `T' = T - (N . T) N` (Lengyel 2001, Gram-Schmidt step).
#[inline(always)]
pub fn reject_normal(tangent: Vec3, unit_normal: Vec3) -> Vec3 {
    tangent - unit_normal * unit_normal.dot(tangent)
}

/// `|v|` without overflow or underflow: scaled by the largest component first, so lengths near
/// 1e20 (whose square overflows f32) or 1e-30 (whose square underflows) come out right.
#[inline]
pub fn careful_length(v: Vec3) -> f32 {
    let largest = v.abs().max_element();
    if largest > 0.0 && largest.is_finite() {
        largest * (v / largest).length()
    } else {
        largest
    }
}

/// `v / |v|`, or `None` when `v` is zero or not finite.
///
/// Divides by the largest component first so that lengths near the float limits (UVs scaled by
/// 1e-20 give tangents of length 1e20, whose squared length overflows) still normalize.
#[inline]
pub fn normalize_careful(v: Vec3) -> Option<Vec3> {
    let largest = v.abs().max_element();
    if !(v.is_finite() && largest > 0.0) {
        return None;
    }
    let scaled = v / largest;
    Some(scaled / scaled.length())
}

/// A unit tangent orthogonal to the unit normal `n`, from `n` alone.
///
/// Duff et al. 2017, "Building an Orthonormal Basis, Revisited", listing 3: branch on the sign of
/// `n.z` so that `1 / (sign + n.z)` never divides by a number near zero, which keeps full precision
/// for every direction, including normals near (0, 0, -1) where Frisvad's original breaks down.
#[inline]
pub fn fallback_tangent(n: Vec3) -> Vec3 {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}

/// `in_plane` (already rid of most of the normal) as a unit vector orthogonal to `normal`.
///
/// Removing the normal once in f32 leaves an error of about float precision divided by the share
/// of the sum that lay in the plane, which for a sum nearly along the normal exceeds 1e-5; a
/// second rejection after normalizing brings it to rounding level ("twice is enough").
#[inline]
pub fn finish_tangent(in_plane: Vec3, normal: Option<Vec3>) -> Option<Vec3> {
    let once = normalize_careful(in_plane)?;
    match normal {
        Some(n) => normalize_careful(reject_normal(once, n)),
        None => Some(once),
    }
}

/// The tangent for a vertex whose normal is unusable (zero or not finite): the x axis.
pub const NO_NORMAL_TANGENT: Vec3 = Vec3::X;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fallback_is_unit_and_orthogonal_for_every_direction() {
        let mut worst = 0.0f32;
        let steps = 200;
        for i in 0..=steps {
            for j in 0..=steps {
                let theta = std::f32::consts::PI * i as f32 / steps as f32;
                let phi = 2.0 * std::f32::consts::PI * j as f32 / steps as f32;
                let n = Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()).normalize();
                let t = fallback_tangent(n);
                worst = worst.max((t.length() - 1.0).abs()).max(t.dot(n).abs());
            }
        }
        for n in [
            Vec3::NEG_Z,
            Vec3::new(1e-7, -1e-7, -1.0).normalize(),
            Vec3::new(0.0, 0.0, -0.0 - 1.0),
        ] {
            let t = fallback_tangent(n);
            worst = worst.max((t.length() - 1.0).abs()).max(t.dot(n).abs());
        }
        assert!(worst <= 1e-6, "worst deviation {worst}");
    }

    #[test]
    fn careful_normalize_survives_extreme_lengths() {
        for scale in [1e-30f32, 1e-20, 1.0, 1e20, 1e30] {
            let v = normalize_careful(Vec3::new(3.0, 4.0, 0.0) * scale).unwrap();
            assert!((v - Vec3::new(0.6, 0.8, 0.0)).length() < 1e-6, "{scale}: {v}");
        }
        assert_eq!(normalize_careful(Vec3::ZERO), None);
        assert_eq!(normalize_careful(Vec3::new(f32::NAN, 0.0, 1.0)), None);
        assert_eq!(normalize_careful(Vec3::new(f32::INFINITY, 0.0, 1.0)), None);
        for scale in [1e-30f32, 1e20, 1e30] {
            let length = careful_length(Vec3::new(3.0, 4.0, 0.0) * scale);
            assert!((length / (5.0 * scale) - 1.0).abs() < 1e-6, "{scale}: {length}");
        }
    }
}
