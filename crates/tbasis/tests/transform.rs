//! `to_tangent_space` and `from_tangent_space` against the definitions, computed here in `f64`
//! without the library: `M = [T B N]` (columns, Lengyel 2001), `B = w * cross(N, T)`, tangent
//! space through `M⁻¹` from a Gauss-Jordan elimination, object space through `M`. Their C entry
//! points are tested by `tests/transform.rs` at the repository root.

use tbasis::{from_tangent_space, to_tangent_space, Error, ErrorKind};
use tbasis_test_support::scenes::{cross, dot};

type M3 = [[f64; 3]; 3];

/// splitmix64: a fixed, dependency-free sequence.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn vector(&mut self, scale: f64) -> [f32; 3] {
        [0; 3].map(|_| (self.uniform(-1.0, 1.0) * scale) as f32)
    }

    fn unit(&mut self) -> [f64; 3] {
        loop {
            let v = [0; 3].map(|_| self.uniform(-1.0, 1.0));
            let length = norm(v);
            if length > 0.1 && length <= 1.0 {
                return v.map(|x| x / length);
            }
        }
    }
}

fn wide<const N: usize>(v: [f32; N]) -> [f64; N] {
    v.map(f64::from)
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `M = [T B N]` with `B = w * cross(N, T)`, from the float inputs.
fn frame_matrix(normal: [f32; 3], tangent: [f32; 4]) -> M3 {
    let n = wide(normal);
    let t = [tangent[0], tangent[1], tangent[2]].map(f64::from);
    let b = cross(n, t).map(|x| f64::from(tangent[3]) * x);
    [0, 1, 2].map(|row| [t[row], b[row], n[row]])
}

fn apply(m: &M3, v: [f64; 3]) -> [f64; 3] {
    m.map(|row| dot(row, v))
}

fn transpose(m: &M3) -> M3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| m[j][i]))
}

/// Gauss-Jordan elimination with partial pivoting on `[M | I]`.
fn inverse(m: &M3) -> M3 {
    let mut a = *m;
    let mut inv = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for col in 0..3 {
        let pivot = (col..3)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = a[col][col];
        assert!(p != 0.0, "singular test matrix");
        for k in 0..3 {
            a[col][k] /= p;
            inv[col][k] /= p;
        }
        for row in (0..3).filter(|&r| r != col) {
            let f = a[row][col];
            for k in 0..3 {
                a[row][k] -= f * a[col][k];
                inv[row][k] -= f * inv[col][k];
            }
        }
    }
    inv
}

fn frobenius(m: &M3) -> f64 {
    m.iter().flatten().map(|x| x * x).sum::<f64>().sqrt()
}

/// Each component of `got` within `tolerance * |want|` of `want`.
fn assert_close(got: [f32; 3], want: [f64; 3], tolerance: f64, what: &str) {
    let scale = norm(want);
    for k in 0..3 {
        let error = (f64::from(got[k]) - want[k]).abs();
        assert!(
            error <= tolerance * scale,
            "{what}: component {k} is {} , expected {} (error {error:e}, allowed {:e})",
            got[k],
            want[k],
            tolerance * scale
        );
    }
}

/// One rounding to float is at most 2⁻²⁴ relative; 2⁻²³ leaves room for the f64 work on either side.
const ROUNDING: f64 = f32::EPSILON as f64;

/// A random frame: normal of length 0.25..4, tangent of length 0.25..4 at 10..170 degrees from the
/// normal, `w = ±1`, so `M` is neither orthonormal nor badly conditioned.
fn skewed_frame(rng: &mut Rng) -> ([f32; 3], [f32; 4]) {
    let n = rng.unit();
    loop {
        let t = rng.unit();
        let sine = norm(cross(n, t));
        if sine < 10f64.to_radians().sin() {
            continue;
        }
        let (ln, lt) = (rng.uniform(0.25, 4.0), rng.uniform(0.25, 4.0));
        let w = if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
        return (
            n.map(|x| (x * ln) as f32),
            [(t[0] * lt) as f32, (t[1] * lt) as f32, (t[2] * lt) as f32, w],
        );
    }
}

/// A random orthonormal frame: unit normal, unit tangent orthogonal to it (Gram-Schmidt in f64).
fn orthonormal_frame(rng: &mut Rng, w: f32) -> ([f32; 3], [f32; 4]) {
    let n = rng.unit();
    let t = loop {
        let t = rng.unit();
        let along = dot(n, t);
        let t = [0, 1, 2].map(|k| t[k] - along * n[k]);
        if norm(t) > 0.1 {
            break t.map(|x| x / norm(t));
        }
    };
    (n.map(|x| x as f32), [t[0] as f32, t[1] as f32, t[2] as f32, w])
}

#[test]
fn orthonormal_frame_to_tangent_space_is_the_transpose_product() {
    let mut rng = Rng(1);
    for _ in 0..2000 {
        let w = if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
        let (n, t) = orthonormal_frame(&mut rng, w);
        let d = rng.vector(10.0);
        let m = frame_matrix(n, t);
        // (dot(T, d), dot(B, d), dot(N, d)): exact for the float frame only up to its own
        // orthonormality (~1e-7), hence the looser bound than for the exact inverse below.
        let want = apply(&transpose(&m), wide(d));
        assert_close(to_tangent_space(n, t, d).unwrap(), want, 1e-6, "transpose product");
        assert_close(
            from_tangent_space(n, t, d).unwrap(),
            apply(&m, wide(d)),
            ROUNDING,
            "M d",
        );
    }
}

#[test]
fn axis_frame_gives_exact_values() {
    let (n, t) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(to_tangent_space(n, t, [0.25, -0.5, 2.0]), Ok([0.25, -0.5, 2.0]));
    assert_eq!(from_tangent_space(n, t, [0.25, -0.5, 2.0]), Ok([0.25, -0.5, 2.0]));
    // Normal +Y, tangent +Z: B = cross(Y, Z) = +X.
    let (n, t) = ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0, 1.0]);
    assert_eq!(to_tangent_space(n, t, [1.0, 2.0, 3.0]), Ok([3.0, 1.0, 2.0]));
    assert_eq!(from_tangent_space(n, t, [3.0, 1.0, 2.0]), Ok([1.0, 2.0, 3.0]));
}

#[test]
fn negative_w_flips_the_bitangent_coordinate_only() {
    let mut rng = Rng(2);
    for _ in 0..2000 {
        let (n, t) = skewed_frame(&mut rng);
        let mirrored = [t[0], t[1], t[2], -t[3]];
        let d = rng.vector(3.0);
        let a = to_tangent_space(n, t, d).unwrap();
        let b = to_tangent_space(n, mirrored, d).unwrap();
        // Negating B negates det M and the second row of its adjugate, both exactly.
        assert_eq!(b, [a[0], -a[1], a[2]]);
        let flipped_y = [d[0], -d[1], d[2]];
        assert_eq!(from_tangent_space(n, mirrored, d), from_tangent_space(n, t, flipped_y));
    }
}

#[test]
fn skewed_frame_uses_the_exact_inverse() {
    let mut rng = Rng(3);
    let mut worst_transpose_error = 0.0f64;
    for _ in 0..5000 {
        let (n, t) = skewed_frame(&mut rng);
        let d = rng.vector(5.0);
        let m = frame_matrix(n, t);
        let inv = inverse(&m);
        let condition = frobenius(&m) * frobenius(&inv);
        let want = apply(&inv, wide(d));
        // The library rounds its f64 result once; the elimination here adds ~condition * 1e-16.
        assert_close(
            to_tangent_space(n, t, d).unwrap(),
            want,
            ROUNDING + condition * 1e-14,
            "M^-1 d",
        );
        let transposed = apply(&transpose(&m), wide(d));
        worst_transpose_error =
            worst_transpose_error.max(norm([0, 1, 2].map(|k| transposed[k] - want[k])) / norm(want));
    }
    // The frames are far from orthonormal: the transpose would be badly wrong.
    assert!(
        worst_transpose_error > 0.5,
        "transpose error only {worst_transpose_error}"
    );
}

#[test]
fn skewed_frame_round_trips() {
    let mut rng = Rng(4);
    for _ in 0..5000 {
        let (n, t) = skewed_frame(&mut rng);
        let m = frame_matrix(n, t);
        let condition = frobenius(&m) * frobenius(&inverse(&m));
        // A float rounding of the intermediate, amplified by the condition of M (or M^-1).
        let tolerance = 4.0 * condition * f64::from(f32::EPSILON);

        let v = rng.vector(2.0);
        let object = from_tangent_space(n, t, v).unwrap();
        assert_close(
            to_tangent_space(n, t, object).unwrap(),
            wide(v),
            tolerance,
            "to(from(v))",
        );

        // to_tangent_space(M v) == v with M v formed here in f64.
        let mv = apply(&m, wide(v)).map(|x| x as f32);
        assert_close(to_tangent_space(n, t, mv).unwrap(), wide(v), tolerance, "to(M v)");

        let d = rng.vector(2.0);
        let tangent_space = to_tangent_space(n, t, d).unwrap();
        assert_close(
            from_tangent_space(n, t, tangent_space).unwrap(),
            wide(d),
            tolerance,
            "from(to(d))",
        );
    }
}

#[test]
fn a_longer_normal_shrinks_the_bitangent_and_normal_coordinates() {
    // With T orthogonal to N, scaling N by k scales B by k as well: M^-1 divides those two
    // coordinates by k, not multiplies (which the transpose would).
    let (t, d) = ([1.0, 0.0, 0.0, 1.0], [0.5, 0.25, 2.0]);
    let got = to_tangent_space([0.0, 0.0, 4.0], t, d).unwrap();
    assert_eq!(got, [0.5, 0.0625, 0.5]);
    assert_eq!(from_tangent_space([0.0, 0.0, 4.0], t, got).unwrap(), d);
}

const FRAME: ([f32; 3], [f32; 4]) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]);

fn both(normal: [f32; 3], tangent: [f32; 4], d: [f32; 3]) -> [Result<[f32; 3], ErrorKind>; 2] {
    [
        to_tangent_space(normal, tangent, d).map_err(|e| e.kind()),
        from_tangent_space(normal, tangent, d).map_err(|e| e.kind()),
    ]
}

#[test]
fn singular_frames_are_refused() {
    let n = [0.0, 0.0, 1.0];
    let tiny = 1e-7f32; // sine of the angle between normal and tangent, below the 1e-6 bound
    let cases: [(&str, [f32; 3], [f32; 4]); 7] = [
        ("tangent parallel to the normal", n, [0.0, 0.0, 2.0, 1.0]),
        ("tangent antiparallel", n, [0.0, 0.0, -1.0, -1.0]),
        ("tangent within 1e-7 rad of the normal", n, [tiny, 0.0, 1.0, 1.0]),
        ("zero tangent", n, [0.0, 0.0, 0.0, 1.0]),
        ("zero normal", [0.0; 3], [1.0, 0.0, 0.0, 1.0]),
        ("zero handedness", n, [1.0, 0.0, 0.0, 0.0]),
        ("negative zero handedness", n, [1.0, 0.0, 0.0, -0.0]),
    ];
    for (what, normal, tangent) in cases {
        for result in both(normal, tangent, [0.3, 0.4, 0.5]) {
            assert_eq!(result, Err(ErrorKind::InvalidFrame), "{what}");
        }
    }
    // Just above the bound the frame is usable, and still inverted exactly.
    let tangent = [1e-5, 0.0, 1.0, 1.0];
    let d = [0.3, 0.4, 0.5];
    let m = frame_matrix(n, tangent);
    let inv = inverse(&m);
    let condition = frobenius(&m) * frobenius(&inv);
    let got = to_tangent_space(n, tangent, d).unwrap();
    assert_close(got, apply(&inv, wide(d)), ROUNDING + condition * 1e-14, "near-singular");
}

#[test]
fn non_finite_inputs_are_refused() {
    let (n, t) = FRAME;
    let d = [0.3, 0.4, 0.5];
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for k in 0..3 {
            let mut normal = n;
            normal[k] = bad;
            let mut direction = d;
            direction[k] = bad;
            assert_eq!(
                both(normal, t, d),
                [Err(ErrorKind::InvalidFrame); 2],
                "normal[{k}] = {bad}"
            );
            assert_eq!(
                both(n, t, direction),
                [Err(ErrorKind::InvalidFrame); 2],
                "direction[{k}] = {bad}"
            );
        }
        for k in 0..4 {
            let mut tangent = t;
            tangent[k] = bad;
            assert_eq!(
                both(n, tangent, d),
                [Err(ErrorKind::InvalidFrame); 2],
                "tangent[{k}] = {bad}"
            );
        }
    }
}

#[test]
fn results_beyond_float_range_are_refused() {
    // |T| = 1e-30: coordinates along T grow by 1e30.
    assert_eq!(
        to_tangent_space([0.0, 0.0, 1.0], [1e-30, 0.0, 0.0, 1.0], [1e30, 0.0, 0.0]),
        Err(Error::InvalidFrame)
    );
    assert_eq!(
        from_tangent_space([0.0, 0.0, 1.0], [1e30, 0.0, 0.0, 1.0], [1e10, 0.0, 0.0]),
        Err(Error::InvalidFrame)
    );
    // Extreme but representable: |N| = 2^-70, |T| = 2^70, so B = +Y exactly and nothing on the
    // way (|N|^2 |T|^2, det M) overflows or underflows.
    let (small, big) = (2f32.powi(-70), 2f32.powi(70));
    assert_eq!(
        to_tangent_space([0.0, 0.0, small], [big, 0.0, 0.0, 1.0], [big, 1.0, small]),
        Ok([1.0, 1.0, 1.0])
    );
    assert_eq!(
        from_tangent_space([0.0, 0.0, small], [big, 0.0, 0.0, 1.0], [1.0, 1.0, 1.0]),
        Ok([big, 1.0, small])
    );
}
