//! When is a triangle degenerate, and how much may a nearly degenerate one weigh.
#![forbid(unsafe_code)]

/// `2 * sqrt(3)`: scales the quality measure so that an equilateral triangle scores 1.
const EQUILATERAL: f32 = 3.464_101_6;

/// Quality below which a triangle's weight is scaled down in proportion (see [`confidence`]).
///
/// 0.01 is an aspect ratio near 170:1, far past any texture stretch an artist means (a 10:1
/// anisotropic stretch scores about 0.17), so ordinary triangles keep their full weight.
pub(crate) const FULL_WEIGHT_QUALITY: f32 = 0.01;

/// The two numbers a triangle's shape quality comes from: twice its area and the sum of its
/// squared edge lengths, `q = 2*sqrt(3) * 2A / (|e0|^2 + |e1|^2 + |e2|^2)`.
///
/// `q` is 1 for an equilateral triangle, 0 for a collapsed one, and unchanged when the triangle is
/// scaled, rotated or its corners relabelled: this is the sine-of-angle style test, scale-free.
/// Callers build it from edges divided by their largest component, so the squares neither
/// overflow nor underflow in f32 whatever the UV or position scale.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    /// Twice the triangle's area.
    pub twice_area: f32,
    /// `|e0|^2 + |e1|^2 + |e2|^2`.
    pub squared_edges: f32,
}

impl Shape {
    /// The quality `q` (0 when it is not a number).
    #[inline]
    pub fn quality(&self) -> f32 {
        let q = EQUILATERAL * self.twice_area / self.squared_edges;
        if q.is_finite() {
            q
        } else {
            0.0
        }
    }

    /// `q >= threshold` and `q > 0`, compared without dividing; false when either is NaN.
    #[inline(always)]
    pub fn at_least(&self, threshold: f32) -> bool {
        let scaled_area = EQUILATERAL * self.twice_area;
        (scaled_area > 0.0) & (scaled_area >= threshold * self.squared_edges)
    }

    /// How much of its weight the triangle keeps: `min(1, q / FULL_WEIGHT_QUALITY)`.
    ///
    /// The tangent a triangle solves for grows like `1 / q` as its UVs collapse and its direction
    /// becomes rounding noise; scaling by `q` keeps such a triangle from dominating a vertex sum.
    #[inline(always)]
    pub fn confidence(&self) -> f32 {
        if self.at_least(FULL_WEIGHT_QUALITY) {
            1.0
        } else {
            self.quality() / FULL_WEIGHT_QUALITY
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    fn uv_shape(a: Vec2, b: Vec2, c: Vec2) -> Shape {
        let (e1, e2) = (b - a, c - a);
        Shape {
            twice_area: e1.perp_dot(e2).abs(),
            squared_edges: e1.length_squared() + e2.length_squared() + (e2 - e1).length_squared(),
        }
    }

    fn uv_quality(a: Vec2, b: Vec2, c: Vec2) -> f32 {
        uv_shape(a, b, c).quality()
    }

    #[test]
    fn quality_is_one_for_equilateral_and_zero_for_collapsed() {
        let (a, b, c) = (Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.5, 3f32.sqrt() / 2.0));
        assert!((uv_quality(a, b, c) - 1.0).abs() < 1e-6);
        assert_eq!(uv_quality(a, b, b * 2.0), 0.0);
        assert_eq!(uv_quality(a, a, a), 0.0);
    }

    #[test]
    fn quality_ignores_corner_order() {
        let (a, b, c) = (Vec2::new(0.1, 0.2), Vec2::new(0.9, 0.25), Vec2::new(0.3, 0.7));
        let reference = uv_quality(a, b, c);
        assert!((uv_quality(b, c, a) - reference).abs() <= 1e-6);
        assert!((uv_quality(c, a, b) - reference).abs() <= 1e-6);
    }

    #[test]
    fn threshold_test_agrees_with_the_quality() {
        let (a, b) = (Vec2::ZERO, Vec2::new(1.0, 0.0));
        for height in [0.0f32, 1e-7, 1e-5, 1e-3, 0.1, 0.9] {
            let shape = uv_shape(a, b, Vec2::new(0.5, height));
            for threshold in [1e-6f32, 1e-5, 1e-3, 0.5] {
                assert_eq!(
                    shape.at_least(threshold),
                    shape.quality() >= threshold && shape.quality() > 0.0
                );
            }
        }
        let nan = Shape {
            twice_area: f32::NAN,
            squared_edges: 1.0,
        };
        assert!(!nan.at_least(0.0));
    }

    #[test]
    fn confidence_is_full_for_ordinary_triangles() {
        let ordinary = uv_shape(Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0));
        assert_eq!(ordinary.confidence(), 1.0);
        let sliver = uv_shape(Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.5, 1e-3));
        assert!(sliver.confidence() < 0.3 && sliver.confidence() > 0.0);
    }
}
