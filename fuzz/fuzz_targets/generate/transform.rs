//! `tbasis_to_tangent_space` and `tbasis_from_tangent_space` on frames and directions drawn from
//! the bytes (any floats; frames near the parallel limit; NULL pointers; the result at unaligned
//! addresses, apart from the inputs or over one of them), and on the frames `tbasis_generate`
//! wrote. Checked against the header: the status the inputs call for (and its string); on an
//! error no byte written; on OK only the result written, finite, with the bits of the Rust API's
//! function (whatever the result overlaps: every input is read first); both functions accept the
//! same frames; and, for well-conditioned frames, each undoes the other within the rounding
//! bound below.

use core::ptr;

use arbitrary::{Arbitrary, Result, Unstructured};

use crate::status::*;

use crate::arena::{bit, first_change_outside, put_f32, vec_at};
use crate::call::debugging;
use crate::ffi::{tbasis_from_tangent_space, tbasis_to_tangent_space};
use crate::input::{mixed, one_in, pick_encoding, special, vector, weighted};
use crate::statuses::{check_status, Expect};

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// A normal: mostly unit or small, sometimes anything.
fn normal(u: &mut Unstructured) -> Result<[f32; 3]> {
    let encoding = pick_encoding(u)?;
    vector(u, encoding)
}

/// A tangent: a vector and a handedness, mostly +1 or -1, sometimes any value (0 included).
fn tangent(u: &mut Unstructured) -> Result<[f32; 4]> {
    let encoding = pick_encoding(u)?;
    let [x, y, z] = vector(u, encoding)?;
    let w = match weighted(u, &[6, 1, 1])? {
        0 if bool::arbitrary(u)? => -1.0,
        0 => 1.0,
        1 => mixed(u)?,
        _ => special(u)?,
    };
    Ok([x, y, z, w])
}

/// Sometimes: the tangent made nearly parallel to the normal, `sin` of the angle between them
/// about the given value (the library's limit is 1e-6), at the given scale.
fn near_parallel(u: &mut Unstructured) -> Result<Option<(f32, f32)>> {
    if weighted(u, &[6, 1])? == 0 {
        return Ok(None);
    }
    let sine = *u.choose(&[1e-3, 1e-5, 2e-6, 1.01e-6, 1e-6, 0.99e-6, 5e-7, 1e-8, 0.0])?;
    let scale = *u.choose(&[1.0, -1.0, 3.0, 1e-20, 1e20, -0.25])?;
    Ok(Some((sine, scale)))
}

/// Where the result goes: apart from the inputs, onto one of them, or across one (4 bytes on).
#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
enum ResultAt {
    Apart,
    Direction,
    Normal,
    Tangent,
    AcrossDirection,
}

#[derive(Arbitrary, Clone, Copy, Debug, PartialEq, Eq)]
struct Layout {
    #[arbitrary(with = one_in::<32>)]
    normal_null: bool,
    #[arbitrary(with = one_in::<32>)]
    tangent_null: bool,
    #[arbitrary(with = one_in::<32>)]
    direction_null: bool,
    #[arbitrary(with = one_in::<32>)]
    result_null: bool,
    result: ResultAt,
    /// Bytes before the normal, the tangent, the direction and the result (unaligned).
    #[arbitrary(with = gaps)]
    gaps: [usize; 4],
}

fn gaps(u: &mut Unstructured) -> Result<[usize; 4]> {
    Ok([
        u.int_in_range(0..=3)?,
        u.int_in_range(0..=3)?,
        u.int_in_range(0..=3)?,
        u.int_in_range(0..=3)?,
    ])
}

const APART: Layout = Layout {
    normal_null: false,
    tangent_null: false,
    direction_null: false,
    result_null: false,
    result: ResultAt::Apart,
    gaps: [0; 4],
};

/// A frame, a direction and a layout for both calls.
#[derive(Arbitrary, Debug)]
pub struct Case {
    #[arbitrary(with = normal)]
    normal: [f32; 3],
    #[arbitrary(with = tangent)]
    tangent: [f32; 4],
    #[arbitrary(with = near_parallel)]
    near_parallel: Option<(f32, f32)>,
    #[arbitrary(with = normal)]
    direction: [f32; 3],
    layout: Layout,
}

/// Which of the two functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Way {
    /// `tbasis_to_tangent_space`: `inverse(M) * direction`.
    To,
    /// `tbasis_from_tangent_space`: `M * direction`.
    From,
}

impl Way {
    fn name(self) -> &'static str {
        match self {
            Way::To => "tbasis_to_tangent_space",
            Way::From => "tbasis_from_tangent_space",
        }
    }
    fn rust(self, n: [f32; 3], t: [f32; 4], d: [f32; 3]) -> core::result::Result<[f32; 3], tbasis::Error> {
        match self {
            Way::To => tbasis::to_tangent_space(n, t, d),
            Way::From => tbasis::from_tangent_space(n, t, d),
        }
    }
}

/// The columns of `M = [T B N]` in f64: `T = tangent.xyz`, `B = w * cross(N, T)`, `N`.
fn columns(n: [f32; 3], t: [f32; 4]) -> [V3; 3] {
    let nn = n.map(f64::from);
    let tt = [t[0], t[1], t[2]].map(f64::from);
    let b = cross(nn, tt).map(|x| f64::from(t[3]) * x);
    [tt, b, nn]
}

/// `M * x`.
fn apply(cols: &[V3; 3], x: V3) -> V3 {
    core::array::from_fn(|k| (0..3).map(|j| cols[j][k] * x[j]).sum())
}

/// `inverse(M) * d` by Gaussian elimination with partial pivoting (not the library's adjugate),
/// `None` when singular.
fn solve(cols: &[V3; 3], d: V3) -> Option<V3> {
    let mut a: [[f64; 4]; 3] = core::array::from_fn(|k| [cols[0][k], cols[1][k], cols[2][k], d[k]]);
    for c in 0..3 {
        let p = (c..3).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        a.swap(c, p);
        if a[c][c] == 0.0 {
            return None;
        }
        let pivot = a[c];
        for row in &mut a[c + 1..] {
            let f = row[c] / pivot[c];
            for (x, p) in row[c..].iter_mut().zip(&pivot[c..]) {
                *x -= f * p;
            }
        }
    }
    let mut x = [0.0; 3];
    for c in (0..3).rev() {
        x[c] = (a[c][3] - (c + 1..3).map(|k| a[c][k] * x[k]).sum::<f64>()) / a[c][c];
    }
    Some(x)
}

/// `sin^2` of the angle between the normal and `T`, as the library tests it: `|N x T|^2` against
/// `|N|^2 |T|^2` (all of it exact enough in f64, which holds every product of floats).
fn sine_squared(n: [f32; 3], t: [f32; 4]) -> f64 {
    let nn = n.map(f64::from);
    let tt = [t[0], t[1], t[2]].map(f64::from);
    let c = cross(nn, tt);
    dot(c, c) / (dot(nn, nn) * dot(tt, tt))
}

/// The smallest magnitude that rounds to infinity as a float: `f32::MAX` plus half its ulp.
const F32_OVERFLOW: f64 = f32::MAX as f64 + (1u128 << 103) as f64;

/// The rows of `inverse(M)`, by elimination on the unit vectors (`None`: numerically singular).
fn inverse_rows(cols: &[V3; 3]) -> Option<[V3; 3]> {
    let mut inverse_columns = [[0.0; 3]; 3];
    for (k, column) in inverse_columns.iter_mut().enumerate() {
        *column = solve(cols, core::array::from_fn(|i| f64::from(u8::from(i == k))))?;
    }
    Some(core::array::from_fn(|j| {
        core::array::from_fn(|k| inverse_columns[k][j])
    }))
}

/// What a call with these inputs must return. `INVALID_FRAME` is due for a non-finite input, a
/// singular frame (zero normal, tangent or `w`; `|N x T| <= 1e-6 |N| |T|`) or a result beyond
/// float. The harness decides the angle in f64 (products of floats are exact there; the cross
/// product's rounding is 1e-16 of `|N| |T|`, far inside a 1e-9 band around the limit) and leaves
/// the band undecided. Whether a result overflows it decides from its own f64 estimate with an
/// uncertainty per component: f64 rounding, about `10 * 2^-53` of the natural scale of each
/// component, `|inverse(M) row j| |d|` (to) or `Σ_j |col_j| |d_j|` (from), times up to
/// `1 + 2 / sin` for the elimination; `2^-40` of that scale covers both. The scale is absolute:
/// when the columns differ in length by many orders of magnitude, a coordinate that is exactly 0
/// can come out of f64 beyond float (or not), and then either status is allowed.
fn expect(way: Way, n: [f32; 3], t: [f32; 4], d: [f32; 3], layout: &Layout) -> Expect {
    let frame_error = Expect {
        hard: bit(TBASIS_ERROR_INVALID_FRAME),
        soft: 0,
    };
    if layout.normal_null || layout.tangent_null || layout.direction_null || layout.result_null {
        return Expect {
            hard: bit(TBASIS_ERROR_NULL_POINTER),
            soft: 0,
        };
    }
    if !n.iter().chain(&t).chain(&d).all(|x| x.is_finite()) {
        return frame_error;
    }
    let zero = |v: &[f32]| v.iter().all(|&x| x == 0.0);
    if zero(&n) || zero(&t[..3]) || t[3] == 0.0 {
        return frame_error;
    }
    let limit = 1e-12;
    let sine2 = sine_squared(n, t);
    if sine2 <= limit * (1.0 - 1e-9) {
        return frame_error;
    }
    let mut soft = 0;
    if sine2 <= limit * (1.0 + 1e-9) {
        soft |= bit(TBASIS_ERROR_INVALID_FRAME);
    }
    let cols = columns(n, t);
    let dd = d.map(f64::from);
    let elimination = 1.0 + 2.0 / sine2.sqrt();
    let estimate = match way {
        Way::From => {
            let scale: f64 = (0..3).map(|j| norm(cols[j]) * dd[j].abs()).sum();
            Some((apply(&cols, dd), [scale; 3]))
        }
        Way::To => solve(&cols, dd).zip(inverse_rows(&cols)).map(|(x, rows)| {
            let d_norm = norm(dd);
            (x, rows.map(|row| norm(row) * d_norm * elimination))
        }),
    };
    let Some((x, scale)) = estimate else {
        // Numerically singular to the harness's elimination, not to the library's test.
        return Expect {
            hard: 0,
            soft: soft | bit(TBASIS_ERROR_INVALID_FRAME),
        };
    };
    let uncertainty = |j: usize| scale[j] * f64::powi(2.0, -40) + x[j].abs() * 1e-6;
    if (0..3).any(|j| x[j].abs() - uncertainty(j) >= F32_OVERFLOW) {
        return frame_error;
    }
    if (0..3).any(|j| x[j].abs() + uncertainty(j) >= F32_OVERFLOW) {
        soft |= bit(TBASIS_ERROR_INVALID_FRAME);
    }
    Expect { hard: 0, soft }
}

/// One call with the inputs at the layout's places in a byte arena; returns the status and the
/// result (on OK). Checks the status, that an error wrote nothing and OK only the result, and the
/// result against the Rust API's.
fn check_call(way: Way, n: [f32; 3], t: [f32; 4], d: [f32; 3], layout: &Layout) -> (tbasis_status, [f32; 3]) {
    let what = way.name();
    let [g0, g1, g2, g3] = layout.gaps;
    let normal_at = g0;
    let tangent_at = normal_at + 12 + g1;
    let direction_at = tangent_at + 16 + g2;
    let result_at = match layout.result {
        ResultAt::Apart => direction_at + 12 + g3,
        ResultAt::Direction => direction_at,
        ResultAt::Normal => normal_at,
        ResultAt::Tangent => tangent_at + 4 * g3.min(1),
        ResultAt::AcrossDirection => direction_at + 4,
    };
    let mut arena = vec![0xa5u8; direction_at + 12 + g3 + 12 + 4];
    for (k, x) in n.iter().enumerate() {
        put_f32(&mut arena, normal_at + 4 * k, *x);
    }
    for (k, x) in t.iter().enumerate() {
        put_f32(&mut arena, tangent_at + 4 * k, *x);
    }
    for (k, x) in d.iter().enumerate() {
        put_f32(&mut arena, direction_at + 4 * k, *x);
    }
    let before = arena.clone();
    let base = arena.as_mut_ptr();
    // SAFETY: every offset leaves room for its floats in the arena; the pointers are unaligned,
    // which the header allows.
    let status = unsafe {
        let at = |null: bool, offset: usize| {
            if null {
                ptr::null_mut()
            } else {
                base.add(offset).cast::<f32>()
            }
        };
        let normal = at(layout.normal_null, normal_at);
        let tangent = at(layout.tangent_null, tangent_at);
        let direction = at(layout.direction_null, direction_at);
        let result = at(layout.result_null, result_at);
        match way {
            Way::To => tbasis_to_tangent_space(normal, tangent, direction, result),
            Way::From => tbasis_from_tangent_space(normal, tangent, direction, result),
        }
    };
    let expect = expect(way, n, t, d, layout);
    if debugging() {
        eprintln!(
            "{what}: n {n:?} t {t:?} d {d:?} {layout:?}: status {status}, expected {:#x} (or {:#x})",
            expect.hard, expect.soft
        );
    }
    check_status(status, &expect, 0, what);
    let ok = status == TBASIS_OK;
    let writable = if ok {
        vec![(result_at, result_at + 12)]
    } else {
        Vec::new()
    };
    if let Some(at) = first_change_outside(&before, &arena, writable) {
        panic!("{what} returned {status} and changed byte {at} outside its result");
    }
    let result: [f32; 3] = vec_at(&arena, result_at);
    let rust = way.rust(n, t, d);
    if ok {
        assert!(
            result.iter().all(|x| x.is_finite()),
            "{what}: n {n:?} t {t:?} d {d:?}: TBASIS_OK with a result not finite: {result:?}"
        );
        assert!(
            rust.as_ref().map(|r| r.map(f32::to_bits)) == Ok(result.map(f32::to_bits)),
            "{what}: n {n:?} t {t:?} d {d:?} ({layout:?}): the C call gives {result:?}, the Rust API {rust:?}"
        );
    } else if status != TBASIS_ERROR_NULL_POINTER {
        assert!(
            rust.as_ref().is_err_and(|e| status_of(e.kind()) == status),
            "{what}: n {n:?} t {t:?} d {d:?}: the C call returns {status}, the Rust API {rust:?}"
        );
    }
    (status, result)
}

/// `sin` of the normal-tangent angle from which a frame counts as well-conditioned here.
const WELL_CONDITIONED_SINE: f64 = 1e-3;

/// The round trips, on a frame both functions accepted (`to`: `to_tangent_space(n, t, d)`,
/// `from`: `from_tangent_space(n, t, d)`, either `None` when it failed).
///
/// Each function computes in f64 and rounds each component to float once: `r = M⁻¹d (1 + δ) + η`
/// with `|δ| <= 2^-24` and `|η| <= 2^-150` (half the subnormal spacing), plus the f64 error of
/// forming the product, at most about `10 * 2^-53` times `|column or row| |input|`, times the
/// frame's condition for the inverse. Mapping `r` back with the other function multiplies the
/// first rounding by `M` (resp. `M⁻¹`) and adds its own rounding, so componentwise
///
/// - to then from: `|d' - d|_k <= 2^-24 (Σ_j |col_j| |r_j| + |d'_k|) + 2^-150 (Σ_j |col_j| + 1)`
///   plus `10 * 2^-53 (Σ_j |col_j| |M⁻¹ row j|) |d|`, and `Σ_j |col_j| |M⁻¹ row j| <= 1 + 2 / sin`
///   (for `B`, orthogonal to `N` and `T`, the product is 1; for `T` and `N` it is `1 / sin` of the
///   angle between them);
/// - from then to: `|d'' - d|_j <= 2^-24 (Σ_k |M⁻¹_jk| |r'_k| + |d''_j|) + 2^-150 (Σ_k |M⁻¹_jk| + 1)`
///   plus `10 * 2^-53 Σ_k |M⁻¹_jk| |r'|`.
///
/// The tolerance doubles the two roundings (`2^-22` for `2^-24 + 2^-24`, with `|r'|` for `|r'_k|`
/// and `|d|` for `|d'_k|`, which differ by less than the bound) and the underflow term (`2^-148`):
/// the spare `2^-23` relative covers the f64 terms, below `10 * 2^-53 * 2001 ≈ 2e-12` relative for a
/// well-conditioned frame (`sin >= 1e-3`). Frames nearer the limit the library accepts (`sin` down
/// to 1e-6) would still fit (`2e-9`), but are only held to the other checks.
fn check_round_trips(n: [f32; 3], t: [f32; 4], d: [f32; 3], to: Option<[f32; 3]>, from: Option<[f32; 3]>) {
    if sine_squared(n, t) < WELL_CONDITIONED_SINE * WELL_CONDITIONED_SINE {
        return;
    }
    let cols = columns(n, t);
    let dd = d.map(f64::from);
    let d_norm = norm(dd);
    let col_norms = cols.map(norm);
    const REL: f64 = 1.0 / (1u64 << 22) as f64;
    // 2^-148.
    let abs = |scale: f64| (scale + 1.0) * f64::from(f32::from_bits(2));

    // The way back is checked like any call; a refusal, checked against the harness's own
    // estimate of its result, ends the trip (a frame whose columns differ in scale by many orders
    // of magnitude can map back beyond float).
    let to_and_back = to.map(|r| (r, check_call(Way::From, n, t, r, &APART)));
    if let Some((r, (TBASIS_OK, back))) = to_and_back {
        let spread: f64 = (0..3).map(|j| col_norms[j] * f64::from(r[j]).abs()).sum();
        let tolerance = REL * (spread + d_norm) + abs(col_norms.iter().sum());
        for k in 0..3 {
            let error = (f64::from(back[k]) - dd[k]).abs();
            assert!(
                error <= tolerance,
                "round trip to then from, n {n:?} t {t:?}: {d:?} -> {r:?} -> {back:?}, component {k} off by \
                 {error:e} > {tolerance:e}"
            );
        }
    }
    let from_and_back = from.map(|r| (r, check_call(Way::To, n, t, r, &APART)));
    if let Some((r, (TBASIS_OK, back))) = from_and_back {
        let rows = inverse_rows(&cols).expect("a well-conditioned frame");
        let r_norm = norm(r.map(f64::from));
        for j in 0..3 {
            let row_sum: f64 = rows[j].iter().map(|x| x.abs()).sum();
            let tolerance = REL * (row_sum * r_norm + d_norm) + abs(row_sum);
            let error = (f64::from(back[j]) - dd[j]).abs();
            assert!(
                error <= tolerance,
                "round trip from then to, n {n:?} t {t:?}: {d:?} -> {r:?} -> {back:?}, component {j} off by \
                 {error:e} > {tolerance:e}"
            );
        }
    }
}

/// Both functions on the frame `n`, `t` and direction `d` with `layout`, then on the same frame
/// with a zero direction (whose result never overflows: both must accept or refuse the frame
/// alike), then the round trips.
fn check_frame(n: [f32; 3], t: [f32; 4], d: [f32; 3], layout: &Layout) {
    let (to_status, to) = check_call(Way::To, n, t, d, layout);
    let (from_status, from) = check_call(Way::From, n, t, d, layout);
    let frame_valid = |way: Way| check_call(way, n, t, [0.0; 3], &APART).0;
    let (to_zero, from_zero) = (frame_valid(Way::To), frame_valid(Way::From));
    assert_eq!(
        to_zero, from_zero,
        "n {n:?} t {t:?}: to_tangent_space and from_tangent_space do not accept the same frames"
    );
    if *layout == APART {
        check_round_trips(
            n,
            t,
            d,
            (to_status == TBASIS_OK).then_some(to),
            (from_status == TBASIS_OK).then_some(from),
        );
    }
}

/// A case drawn from the bytes.
pub fn check(u: &mut Unstructured) -> Result<()> {
    let case = Case::arbitrary(u)?;
    let mut t = case.tangent;
    if let Some((sine, scale)) = case.near_parallel {
        // T = scale * (N + sine |N| e), e a unit vector orthogonal to N.
        let n = case.normal.map(f64::from);
        let axis = if n[0].abs() <= n[1].abs() && n[0].abs() <= n[2].abs() {
            [1.0, 0.0, 0.0]
        } else if n[1].abs() <= n[2].abs() {
            [0.0, 1.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        };
        let e = cross(n, axis);
        let e_norm = norm(e);
        if e_norm > 0.0 && e_norm.is_finite() {
            let n_norm = norm(n);
            for k in 0..3 {
                t[k] = (f64::from(scale) * (n[k] + f64::from(sine) * n_norm * e[k] / e_norm)) as f32;
            }
        }
    }
    check_frame(case.normal, t, case.direction, &case.layout);
    Ok(())
}

/// The frames a successful `tbasis_generate` wrote (`normals`, `tangents`), with the positions as
/// directions.
pub fn check_generated(normals: &[[f32; 3]], tangents: &[[f32; 4]], positions: &[[f32; 3]]) {
    for ((&n, &t), &d) in normals.iter().zip(tangents).zip(positions) {
        check_frame(n, t, d, &APART);
    }
}
