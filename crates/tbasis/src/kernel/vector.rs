//! mikktspace.c's vector arithmetic, operation for operation.
//!
//! Exactness needs each sum and product in the order and precision the C code uses (no fused
//! multiply-add, no reordering, `x * x + y * y + z * z` left to right), and its comparisons: a
//! `NaN` fails every `>` and `<`, so the C ternaries are kept as ternaries rather than
//! `f32::min`/`max`/`clamp`, which treat `NaN` differently.
#![forbid(unsafe_code)]

/// Three floats, as mikktspace.c's `SVec3`.
pub(crate) type Vec3 = [f32; 3];

/// A welded vertex's attributes, packed: position, normal, texture coordinate.
pub(crate) type Packed = [f32; 8];

#[inline(always)]
pub(crate) fn position(a: &Packed) -> Vec3 {
    [a[0], a[1], a[2]]
}

#[inline(always)]
pub(crate) fn normal(a: &Packed) -> Vec3 {
    [a[3], a[4], a[5]]
}

#[inline(always)]
pub(crate) fn texcoord(a: &Packed) -> [f32; 2] {
    [a[6], a[7]]
}

#[inline(always)]
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub(crate) fn scale(s: f32, v: Vec3) -> Vec3 {
    [s * v[0], s * v[1], s * v[2]]
}

#[inline(always)]
pub(crate) fn dot(a: Vec3, b: Vec3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub(crate) fn length(v: Vec3) -> f32 {
    dot(v, v).sqrt()
}

/// `==` on every component: +0 equals -0, `NaN` equals nothing.
#[inline(always)]
pub(crate) fn equal(a: Vec3, b: Vec3) -> bool {
    a[0] == b[0] && a[1] == b[1] && a[2] == b[2]
}

/// `|x| > FLT_MIN`: false for zero, subnormals and `NaN`.
#[inline(always)]
pub(crate) fn not_zero(x: f32) -> bool {
    x.abs() > f32::MIN_POSITIVE
}

#[inline(always)]
pub(crate) fn vector_not_zero(v: Vec3) -> bool {
    not_zero(v[0]) | not_zero(v[1]) | not_zero(v[2])
}

/// `v * (1 / |v|)`, as `Normalize` computes it.
#[inline(always)]
pub(crate) fn normalize(v: Vec3) -> Vec3 {
    scale(1.0 / length(v), v)
}

/// `v` without its component along `n`, normalized when anything is left:
/// `v - (n . v) n`, the projection every tangent and edge goes through before it is weighed.
#[inline(always)]
pub(crate) fn project_normalized(v: Vec3, n: Vec3) -> Vec3 {
    normalize_if_not_zero(sub(v, scale(dot(n, v), n)))
}

/// `v` normalized unless [`vector_not_zero`] says it is zero, as mikktspace.c guards each
/// `Normalize`.
#[inline(always)]
pub(crate) fn normalize_if_not_zero(v: Vec3) -> Vec3 {
    if vector_not_zero(v) {
        normalize(v)
    } else {
        v
    }
}

/// The cosine of the angle between `e1` and `e2`, both projected into the tangent plane of `n` and
/// normalized (`EvalTspace`), clamped to [-1, 1] by mikktspace.c's ternaries: a `NaN` passes
/// through, where `f32::clamp` is not promised to treat it alike.
#[inline(always)]
pub(crate) fn projected_cosine(e1: Vec3, e2: Vec3, n: Vec3) -> f32 {
    let cos = dot(project_normalized(e1, n), project_normalized(e2, n));
    #[allow(clippy::manual_clamp)]
    if cos > 1.0 {
        1.0
    } else if cos < -1.0 {
        -1.0
    } else {
        cos
    }
}
