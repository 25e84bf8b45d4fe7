//! Vector arithmetic in double precision and the comparisons of frames.

/// Tolerance on unit length and orthogonality for the robust policies.
pub const TOLERANCE: f64 = 1e-4;

/// Equal bits, a NaN matching any NaN: which NaN an operation on NaN operands returns is fixed
/// neither by C nor by Rust (mikktspace.c gives 0xffc00000 where Rust may carry an input's payload).
pub fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// [`same`] on every component.
pub fn same_frame(a: [f32; 4], b: [f32; 4]) -> bool {
    (0..4).all(|k| same(a[k], b[k]))
}

/// A frame with its bits, for failure messages.
pub fn show(t: [f32; 4]) -> String {
    let [x, y, z, w] = t.map(f32::to_bits);
    format!("{t:?} [{x:08x} {y:08x} {z:08x} {w:08x}]")
}

/// The invariants of every policy but LEGACY: the tangent is finite, unit length and orthogonal
/// to the normalized `normal` (when it has a direction), and `w` is exactly +1 or -1.
pub fn check_robust_tangent(t4: [f32; 4], normal: [f32; 3], context: impl Fn() -> String) {
    let [x, y, z, w] = t4.map(f64::from);
    let t = [x, y, z];
    assert!(t4.iter().all(|v| v.is_finite()), "{}: not finite", context());
    assert!((length(t) - 1.0).abs() <= TOLERANCE, "{}: not unit length", context());
    assert!(w == 1.0 || w == -1.0, "{}: w is not +1 or -1", context());
    if let Some(n) = unit(normal) {
        assert!(
            dot(t, n).abs() <= TOLERANCE,
            "{}: not orthogonal to the normal",
            context()
        );
    }
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn length(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The normalized normal, when the normal is finite and not zero (f64 holds any f32 square).
pub fn unit(n: [f32; 3]) -> Option<[f64; 3]> {
    if !n.iter().all(|x| x.is_finite()) || n.iter().all(|&x| x == 0.0) {
        return None;
    }
    let n = n.map(f64::from);
    let len = length(n);
    Some(n.map(|x| x / len))
}
