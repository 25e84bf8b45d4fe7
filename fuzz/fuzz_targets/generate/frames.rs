//! Vector arithmetic in double precision and the comparisons of frames.

/// Tolerance on unit length and orthogonality for the robust policies.
pub const TOLERANCE: f64 = 1e-4;

pub fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
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
