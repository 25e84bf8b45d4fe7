//! Orthonormal-frame helpers: Gram-Schmidt, careful normalization and the normal-only fallback.
#![forbid(unsafe_code)]

use glam::Vec3;

use crate::kernel::mesh::Mesh;
use crate::kernel::vector::normalize_if_not_zero;

/// Removes the normal's component: `T' = T - (N . T) N` (Lengyel 2001, Gram-Schmidt step).
#[inline(always)]
pub fn reject_normal(tangent: Vec3, unit_normal: Vec3) -> Vec3 {
    tangent - unit_normal * unit_normal.dot(tangent)
}

/// A squared length far enough inside f32's range (1e-30 to 1e30) that squaring, summing and
/// dividing by the length neither overflow nor lose precision to subnormals.
#[inline(always)]
pub fn is_well_scaled(squared: f32) -> bool {
    (squared > 1e-30) & (squared < 1e30)
}

/// `(|v|, v / |v|)`, or `None` when `v` is zero or not finite.
///
/// One square root and one division when `|v|^2` is comfortably inside f32's range; otherwise
/// (UVs scaled by 1e-20 give tangents of length 1e20, whose square overflows) it divides by the
/// largest component first.
#[inline(always)]
pub fn length_and_direction(v: Vec3) -> Option<(f32, Vec3)> {
    let (length, direction, exact) = length_and_direction_fast(v);
    if exact {
        return Some((length, direction));
    }
    length_and_direction_scaled(v)
}

/// The common case of [`length_and_direction`], without a branch so that it runs in SIMD lanes;
/// `exact` is false when the squared length is near the float limits (or not finite).
#[inline(always)]
pub fn length_and_direction_fast(v: Vec3) -> (f32, Vec3, bool) {
    let squared = v.length_squared();
    let length = squared.sqrt();
    (length, v * (1.0 / length), is_well_scaled(squared))
}

#[cold]
fn length_and_direction_scaled(v: Vec3) -> Option<(f32, Vec3)> {
    let largest = v.abs().max_element();
    if !(v.is_finite() && largest > 0.0) {
        return None;
    }
    let scaled = v / largest;
    let length = scaled.length();
    Some((largest * length, scaled / length))
}

/// `v / |v|`, or `None` when `v` is zero or not finite.
#[inline(always)]
pub fn normalize_careful(v: Vec3) -> Option<Vec3> {
    length_and_direction(v).map(|(_, direction)| direction)
}

/// Gram-Schmidt, `T' = T - (N . T) N` (Lengyel 2001), then normalize: `(|T'|, T' / |T'|)`, or
/// `None` when nothing is left. Without a usable normal, `T` itself is normalized.
///
/// One f32 pass leaves `T'` off orthogonal by about float precision times `|N . T| / |T'|`; when
/// the sum nearly follows the normal that exceeds 1e-6, so a second pass removes the rest
/// ("twice is enough").
#[inline(always)]
pub fn orthonormalize(tangent: Vec3, normal: Option<Vec3>) -> Option<(f32, Vec3)> {
    let Some(n) = normal else {
        return length_and_direction(tangent);
    };
    let (length, direction, exact) = orthonormalize_fast(tangent, n);
    if exact {
        return Some((length, direction));
    }
    let squared = tangent.length_squared();
    if !is_well_scaled(squared) {
        // Far from unit scale (a subnormal sum from tiny triangles, or a huge one), the products
        // below would underflow or overflow: work on the direction and scale the length back.
        let (length, direction) = length_and_direction(tangent)?;
        return orthonormalize(direction, normal).map(|(share, unit)| (share * length, unit));
    }
    let along = n.dot(tangent);
    let (length, direction) = length_and_direction(tangent - n * along)?;
    if along.abs() <= 8.0 * length {
        return Some((length, direction));
    }
    normalize_careful(reject_normal(direction, n)).map(|direction| (length, direction))
}

/// The common case of [`orthonormalize`] (unit normal `n`), without a branch so that it runs in
/// SIMD lanes: `(length, direction, exact)` of `t - n (n . t)`. `exact` is false when the numbers
/// are far from unit scale, or the tangent so nearly follows the normal that one pass of
/// Gram-Schmidt leaves a visible error; then [`orthonormalize`] decides.
#[inline(always)]
pub fn orthonormalize_fast(tangent: Vec3, n: Vec3) -> (f32, Vec3, bool) {
    let squared = tangent.length_squared();
    let along = n.dot(tangent);
    let (length, direction, in_range) = length_and_direction_fast(tangent - n * along);
    let exact = is_well_scaled(squared) & in_range & (along.abs() <= 8.0 * length);
    (length, direction, exact)
}

/// How far from unit length, and how far off the tangent plane, a finished tangent may be.
pub const FRAME_TOLERANCE: f32 = 1e-5;

/// True when `tangent` is finite, unit length and perpendicular to the unit `normal` (when there
/// is one), all within `tolerance`.
#[inline(always)]
pub fn is_unit_and_perpendicular(tangent: Vec3, normal: Option<Vec3>, tolerance: f32) -> bool {
    let unit = tangent.is_finite() & ((tangent.length() - 1.0).abs() <= tolerance);
    unit & normal.is_none_or(|n| n.dot(tangent).abs() <= tolerance)
}

/// A vertex's tangent from its sum, for every method but LEGACY: the sum normalized as
/// mikktspace.c normalizes it, where that is already a unit tangent perpendicular to the normal
/// within a tenth of [`FRAME_TOLERANCE`] (ANGLE's terms lie in the tangent plane of a unit normal),
/// else `orthonormalized`, the sum after Gram-Schmidt. On a vertex whose terms are all
/// mikktspace.c's, the result is then mikktspace.c's.
#[inline(always)]
pub fn finish_tangent(sum: Vec3, orthonormalized: Vec3, normal: Option<Vec3>) -> Vec3 {
    let normalized = Vec3::from_array(normalize_if_not_zero(sum.to_array()));
    // A tenth of the promised tolerance: the test itself rounds in f32.
    if is_unit_and_perpendicular(normalized, normal, 0.1 * FRAME_TOLERANCE) {
        normalized
    } else {
        orthonormalized
    }
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

/// The tangent for a vertex whose normal is unusable (zero or not finite): the x axis.
pub const NO_NORMAL_TANGENT: Vec3 = Vec3::X;

/// A vertex normal as the robust policies use it.
#[derive(Clone, Copy, Debug)]
pub struct VertexNormal {
    /// The normal scaled to unit length; `None` when it is zero or not finite.
    pub unit: Option<Vec3>,
    /// The normal was already unit length within 1e-3.
    pub was_unit: bool,
}

impl VertexNormal {
    /// Reads and normalizes a caller's normal.
    #[inline(always)]
    pub fn new(raw: [f32; 3]) -> Self {
        match length_and_direction(Vec3::from_array(raw)) {
            Some((length, unit)) => VertexNormal {
                unit: Some(unit),
                was_unit: is_unit_length(length),
            },
            None => VertexNormal {
                unit: None,
                was_unit: false,
            },
        }
    }
}

/// A normal's length counts as unit within 1e-3.
#[inline(always)]
pub(crate) fn is_unit_length(length: f32) -> bool {
    (length - 1.0).abs() <= 1e-3
}

/// The frame given to a vertex nothing measured: built from the normal alone, `w = +1`.
#[inline(always)]
pub fn fallback(normal: Option<Vec3>) -> (Vec3, f32) {
    (normal.map_or(NO_NORMAL_TANGENT, fallback_tangent), 1.0)
}

/// The frame the robust policies give a vertex no triangle gives a usable tangent: a unit tangent
/// perpendicular to `normal` built from the normal alone (Duff et al. 2017), or the x axis when
/// the normal is zero or not finite, with `w = 1`. For tools that fill frames of their own.
///
/// ```
/// let [x, y, z, w] = tbasis::fallback_frame([0.0, 0.0, 2.0]);
/// assert_eq!(([x, y, z], w), ([1.0, 0.0, 0.0], 1.0));
/// assert_eq!(tbasis::fallback_frame([0.0; 3]), [1.0, 0.0, 0.0, 1.0]);
/// ```
pub fn fallback_frame(normal: [f32; 3]) -> [f32; 4] {
    let (tangent, w) = fallback(VertexNormal::new(normal).unit);
    let [x, y, z] = tangent.to_array();
    [x, y, z, w]
}

/// Number of vertices whose normal is not unit length within 1e-3 (zero and non-finite included).
pub fn count_abnormal_normals(mesh: &Mesh) -> usize {
    (0..mesh.vertex_count())
        .filter(|&v| !VertexNormal::new(mesh.normals.get(v)).was_unit)
        .count()
}

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
    fn orthonormalize_is_orthogonal_even_when_the_tangent_nearly_follows_the_normal() {
        let n = Vec3::new(1.0, 0.0, 0.00105).normalize();
        for t in [Vec3::Z, Vec3::new(1.0, 1e-3, 0.0), Vec3::new(0.3, -0.2, 0.9)] {
            let (_, unit) = orthonormalize(t, Some(n)).unwrap();
            assert!(unit.dot(n).abs() <= 1e-6, "{t}: {}", unit.dot(n));
            assert!((unit.length() - 1.0).abs() <= 1e-6);
        }
        // Sums near the float limits, subnormal ones included, come out orthogonal too.
        for scale in [1e-42f32, 1e-36, 1e30] {
            let (_, unit) = orthonormalize(Vec3::new(0.8, -0.4, -0.4) * scale, Some(n)).unwrap();
            assert!(unit.dot(n).abs() <= 1e-6, "{scale}: {}", unit.dot(n));
        }
        // A tangent along the normal leaves only rounding residue, which callers measure as tiny.
        assert!(orthonormalize(n * 2.0, Some(n)).is_none_or(|(length, _)| length < 1e-6));
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
            let (length, _) = length_and_direction(Vec3::new(3.0, 4.0, 0.0) * scale).unwrap();
            assert!((length / (5.0 * scale) - 1.0).abs() < 1e-6, "{scale}: {length}");
        }
    }
}
