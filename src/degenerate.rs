//! When is a triangle degenerate, and how much may a nearly degenerate one weigh.
#![forbid(unsafe_code)]

use glam::{DVec3, Vec2, Vec3};

/// `2 * sqrt(3)`: scales the quality measure so that an equilateral triangle scores 1.
const EQUILATERAL: f64 = 3.464_101_615_137_754_6;

/// Quality below which a triangle's weight is scaled down in proportion (see [`confidence`]).
///
/// 0.01 is an aspect ratio near 170:1, far past any texture stretch an artist means (a 10:1
/// anisotropic stretch scores about 0.17), so ordinary triangles keep their full weight.
pub(crate) const FULL_WEIGHT_QUALITY: f32 = 0.01;

/// Shape quality of the triangle with edges `e1`, `e2` from its first corner, in 2D:
/// `2*sqrt(3) * |e1 x e2| / (|e1|^2 + |e2|^2 + |e2 - e1|^2)`.
///
/// 1 for an equilateral triangle, 0 for a collapsed one, and unchanged when the triangle is
/// scaled, rotated or its corners relabelled: this is the sine-of-angle style test, scale-free.
/// Evaluated in f64 so UV edges of 1e-20 or 1e20 neither underflow nor overflow when squared.
#[inline]
pub fn uv_quality(e1: Vec2, e2: Vec2) -> f32 {
    let (e1, e2) = (e1.as_dvec2(), e2.as_dvec2());
    let twice_area = e1.perp_dot(e2).abs();
    quality(
        twice_area,
        e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared(),
    )
}

/// The same shape quality for the triangle's positions, with edges `e1`, `e2` in 3D.
#[inline]
pub fn position_quality(e1: Vec3, e2: Vec3) -> f32 {
    let (e1, e2): (DVec3, DVec3) = (e1.as_dvec3(), e2.as_dvec3());
    let twice_area = e1.cross(e2).length();
    quality(
        twice_area,
        e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared(),
    )
}

#[inline]
fn quality(twice_area: f64, sum_of_squared_edges: f64) -> f32 {
    if sum_of_squared_edges > 0.0 {
        (EQUILATERAL * twice_area / sum_of_squared_edges) as f32
    } else {
        0.0
    }
}

/// How much of its weight a triangle of UV quality `q` keeps: `min(1, q / FULL_WEIGHT_QUALITY)`.
///
/// The tangent a triangle solves for grows like `1 / q` as its UVs collapse and its direction
/// becomes rounding noise; scaling by `q` keeps such a triangle from dominating a vertex sum.
#[inline]
pub fn confidence(q: f32) -> f32 {
    (q / FULL_WEIGHT_QUALITY).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quality_is_one_for_equilateral_and_zero_for_collapsed() {
        let e1 = Vec2::new(1.0, 0.0);
        let e2 = Vec2::new(0.5, 3f32.sqrt() / 2.0);
        assert!((uv_quality(e1, e2) - 1.0).abs() < 1e-6);
        assert_eq!(uv_quality(e1, e1 * 2.0), 0.0);
        assert_eq!(uv_quality(Vec2::ZERO, Vec2::ZERO), 0.0);
    }

    #[test]
    fn quality_ignores_scale_and_corner_order() {
        let (a, b, c) = (Vec2::new(0.1, 0.2), Vec2::new(0.9, 0.25), Vec2::new(0.3, 0.7));
        let reference = uv_quality(b - a, c - a);
        for scale in [1e-20f32, 1e-6, 1e6, 1e20] {
            let q = uv_quality((b - a) * scale, (c - a) * scale);
            assert!((q - reference).abs() <= 1e-5 * reference, "{scale}: {q} vs {reference}");
        }
        assert!((uv_quality(c - b, a - b) - reference).abs() <= 1e-6);
    }

    #[test]
    fn confidence_is_full_for_ordinary_triangles() {
        assert_eq!(confidence(0.5), 1.0);
        assert!(confidence(FULL_WEIGHT_QUALITY / 4.0) < 0.3);
    }
}
