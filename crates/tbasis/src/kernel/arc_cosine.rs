//! The arc cosine mikktspace.c weighs a corner with, `(float)acos((double)x)`, bit for bit, in a
//! form that runs in SIMD lanes.
//!
//! In double precision, `acos(x) = pi/2 - asin(x)` for `|x| <= 1/2`, and `2 asin(s)` (or `pi`
//! minus it for negative `x`) with `s = sqrt((1 - |x|) / 2)` above; both need `asin(s)` only for
//! `s^2 <= 1/4`, where `asin(s) = s + s z P(z)`, `z = s^2`, with `P` a degree-9 polynomial fitted
//! by least squares (relative error below 2^-46). Rounded to float, that double gives the float
//! nearest the true arc cosine, which is also libm's double rounded to float, unless the true value
//! lies within the error of a boundary between two floats: where the result minus and plus
//! [`ERROR`] of itself round to different floats (about one input in 200 000), libm decides. The
//! tests check every float in [-1, 1] against libm.
#![forbid(unsafe_code)]

/// `P(z)`'s coefficients, lowest degree first (`P(0) = 1/6`, the series' `z^1` term).
const P: [f64; 10] = [
    0.166_666_666_666_618_78,
    0.075_000_000_037_829_22,
    0.044_642_852_224_176_01,
    0.030_382_191_629_358_59,
    0.022_365_882_515_612_154,
    0.017_443_628_149_945_288,
    0.013_173_365_233_711_152,
    0.015_733_489_741_212_338,
    -0.003_063_653_250_888_272_3,
    0.028_017_521_204_230_27,
];

/// Bound on the relative error of [`acos_double`]: 2^-40, 64 times the largest measured.
const ERROR: f64 = 1.0 / (1u64 << 40) as f64;

/// `asin(s)` for `s^2 <= 1/4`, the polynomial in Estrin's form (a short dependency chain).
#[inline(always)]
fn asin_small(s: f64) -> f64 {
    let z = s * s;
    let z2 = z * z;
    let z4 = z2 * z2;
    let low = (P[0] + z * P[1]) + z2 * (P[2] + z * P[3]);
    let high = (P[4] + z * P[5]) + z2 * (P[6] + z * P[7]);
    let p = low + z4 * (high + z4 * (P[8] + z * P[9]));
    s + s * z * p
}

/// `acos(x)` in double precision, without a branch (every lane takes the same path).
#[inline(always)]
fn acos_double(x: f64) -> f64 {
    let a = x.abs();
    let large = a > 0.5;
    let s = if large { ((1.0 - a) * 0.5).sqrt() } else { x };
    // acos = base + factor * asin(s): pi/2 - asin(x), 2 asin(s), or pi - 2 asin(s).
    let (base, factor) = if !large {
        (core::f64::consts::FRAC_PI_2, -1.0)
    } else if x > 0.0 {
        (0.0, 2.0)
    } else {
        (core::f64::consts::PI, -2.0)
    };
    base + factor * asin_small(s)
}

/// The float of `acos_double(x)` and whether it is certain: the whole error interval around it
/// rounds to that float (never for `NaN`, nor for `|x| > 1`, whose square root is `NaN`).
#[inline(always)]
fn rounded(x: f32) -> (f32, bool) {
    let r = acos_double(f64::from(x));
    let (low, high) = ((r - r * ERROR) as f32, (r + r * ERROR) as f32);
    (low, low == high)
}

/// libm's `acos` in double precision, rounded to float: what mikktspace.c computes.
#[cold]
fn acos_libm(x: f32) -> f32 {
    f64::from(x).acos() as f32
}

/// `(float)acos((double)x)`.
#[inline(always)]
pub(crate) fn acos(x: f32) -> f32 {
    match rounded(x) {
        (angle, true) => angle,
        _ => acos_libm(x),
    }
}

/// [`acos`] of the first `lanes` of `cosines` into `angles`: a lane loop that compiles to SIMD,
/// then libm for the rare lanes it leaves undecided.
#[inline(always)]
pub(crate) fn acos_lanes<const N: usize>(cosines: &[f32; N], angles: &mut [f32; N], lanes: usize) {
    let mut undecided = 0u32;
    for (angle, &x) in angles[..lanes].iter_mut().zip(&cosines[..lanes]) {
        let (value, certain) = rounded(x);
        *angle = value;
        undecided |= u32::from(!certain);
    }
    if undecided != 0 {
        for (angle, &x) in angles[..lanes].iter_mut().zip(&cosines[..lanes]) {
            *angle = acos(x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every float in [-1, 1] (both zeros included), in an optimized build; every 4099th one in a
    /// debug build, where all would take minutes. CI runs the optimized test.
    #[test]
    fn every_float_in_range_gives_libms_bits() {
        let step = if cfg!(debug_assertions) { 4099 } else { 1 };
        let workers = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
        let one = 1.0f32.to_bits();
        let mismatches: u64 = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..workers)
                .map(|w| {
                    scope.spawn(move || {
                        let mut mismatches = 0u64;
                        let mut bits = w * step;
                        while bits <= one {
                            for x in [f32::from_bits(bits), -f32::from_bits(bits)] {
                                if acos(x).to_bits() != acos_libm(x).to_bits() {
                                    mismatches += 1;
                                    eprintln!("acos({x:e}): {:e}, libm {:e}", acos(x), acos_libm(x));
                                }
                            }
                            bits += workers * step;
                        }
                        mismatches
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().expect("no panic")).sum()
        });
        assert_eq!(mismatches, 0);
    }

    #[test]
    fn the_fast_path_is_taken_nearly_always_and_libm_decides_the_rest() {
        let inputs: Vec<f32> = (0..=200_000).map(|i| i as f32 / 100_000.0 - 1.0).collect();
        let certain = inputs.iter().filter(|&&x| rounded(x).1).count();
        assert!(certain + 10 >= inputs.len(), "{certain} of {}", inputs.len());
        for x in [f32::NAN, 1.5, -1.0000001, f32::INFINITY] {
            assert!(!rounded(x).1, "{x}");
            assert!(acos(x).is_nan());
        }
    }

    #[test]
    fn lanes_give_the_scalar_bits() {
        let mut cosines = [0.0f32; 64];
        for (i, c) in cosines.iter_mut().enumerate() {
            *c = (i as f32 * 0.731).sin();
        }
        cosines[5] = f32::NAN;
        let mut angles = [0.0f32; 64];
        acos_lanes(&cosines, &mut angles, 64);
        for (&c, &a) in cosines.iter().zip(&angles) {
            assert_eq!(a.to_bits(), acos_libm(c).to_bits(), "{c}");
        }
    }
}
