//! The corner angle's arc cosine, as mikktspace.c takes it: `(float)acos((double)x)`.
#![forbid(unsafe_code)]

/// `acos` in double precision, rounded to float.
#[inline(always)]
pub(crate) fn acos(x: f32) -> f32 {
    f64::from(x).acos() as f32
}
