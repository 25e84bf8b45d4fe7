//! Moving a direction between object space and one vertex's tangent space.
//!
//! A vertex's frame is its normal `N`, its tangent `T` (`tangent.xyz`) and the bitangent
//! `B = w * cross(N, T)` (`w = tangent[3]`), the convention the library writes. The matrix
//! `M = [T B N]` (columns) maps tangent-space coordinates to object space (Lengyel 2001:
//! "we can transform from tangent space into object space using the matrix" with columns T, B, N).
//! The other way is `M⁻¹`, which equals the transpose `Mᵀ` only for an orthonormal frame, so it is
//! computed exactly: the rows of `M⁻¹` are `cross(B, N)`, `cross(N, T)` and `cross(T, B)`, each
//! divided by `det M = dot(T, cross(B, N))`.
#![forbid(unsafe_code)]

use crate::kernel::error::Error;

/// `sin` of the angle between normal and tangent below which a frame counts as singular: the two
/// are then parallel to within about 16 roundings of a float (2⁻²⁴ each), so the bitangent and the
/// inverse are rounding noise.
const MIN_SINE: f64 = 1e-6;

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

fn widen<const N: usize>(v: [f32; N]) -> [f64; N] {
    v.map(f64::from)
}

/// The frame in double precision, checked: `(T, B, N)` with `B = w * cross(N, T)`.
///
/// Every product of two floats is exact in `f64` and no sum here can overflow it (floats stay below
/// 2¹²⁸), so the only rounding is `f64`'s, far below the float result's.
fn frame(normal: [f32; 3], tangent: [f32; 4]) -> Result<(V3, V3, V3), Error> {
    if !normal.iter().chain(&tangent).all(|x| x.is_finite()) {
        return Err(Error::InvalidFrame);
    }
    let n = widen(normal);
    let [tx, ty, tz, w] = widen(tangent);
    let t = [tx, ty, tz];
    let n_cross_t = cross(n, t);
    // |N x T|^2 = |N|^2 |T|^2 sin^2; zero for a zero normal or tangent too.
    let sine_squared_scaled = dot(n_cross_t, n_cross_t);
    if w == 0.0 || sine_squared_scaled <= MIN_SINE * MIN_SINE * dot(n, n) * dot(t, t) {
        return Err(Error::InvalidFrame);
    }
    Ok((t, n_cross_t.map(|x| w * x), n))
}

/// Rounds to float once, refusing a result that overflows it.
fn narrow(v: V3) -> Result<[f32; 3], Error> {
    let out = v.map(|x| x as f32);
    if out.iter().all(|x| x.is_finite()) {
        Ok(out)
    } else {
        Err(Error::InvalidFrame)
    }
}

/// Object-space `direction` in the tangent space of the vertex with `normal` and `tangent`:
/// `M⁻¹ · direction`, where `M = [T B N]` (columns), `T = tangent.xyz` and
/// `B = tangent[3] * cross(normal, T)`.
///
/// `M⁻¹` is the exact inverse, so the frame need not be orthonormal: `normal` and `T` may have any
/// length and any angle between them, and `to_tangent_space(n, t, from_tangent_space(n, t, v)?)`
/// gives `v` back up to rounding. For an orthonormal frame (unit normal and tangent, orthogonal,
/// `w = ±1`) it equals `(dot(T, d), dot(B, d), dot(N, d))`. The inverse is computed in double
/// precision from the rows `cross(B, N)`, `cross(N, T)`, `cross(T, B)` over `det M`, and the result
/// rounded to float once.
///
/// `tangent[3]` is the handedness `w` the library writes (`+1` or `-1`); another nonzero value
/// scales `B` by it.
///
/// # Errors
/// [`Error::InvalidFrame`] when an input is NaN or infinite, when the frame is singular (`normal`
/// or `T` zero, `w` zero, or `normal` and `T` parallel: `|normal × T| <= 1e-6 |normal| |T|`), or
/// when a component of the result overflows a float.
///
/// # Example
/// ```
/// // The frame of a surface facing +Z with its tangent along +X and w = +1: B = +Y.
/// let (normal, tangent) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]);
/// let light = [0.0, 0.6, 0.8];
/// let in_tangent_space = tbasis::to_tangent_space(normal, tangent, light)?;
/// assert_eq!(in_tangent_space, [0.0, 0.6, 0.8]);
/// // w = -1 mirrors the bitangent, so the light's y flips.
/// let mirrored = tbasis::to_tangent_space(normal, [1.0, 0.0, 0.0, -1.0], light)?;
/// assert_eq!(mirrored, [0.0, -0.6, 0.8]);
/// assert_eq!(tbasis::from_tangent_space(normal, tangent, in_tangent_space)?, light);
/// // A tangent parallel to the normal spans no frame.
/// assert_eq!(
///     tbasis::to_tangent_space(normal, [0.0, 0.0, 2.0, 1.0], light),
///     Err(tbasis::Error::InvalidFrame)
/// );
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn to_tangent_space(normal: [f32; 3], tangent: [f32; 4], direction: [f32; 3]) -> Result<[f32; 3], Error> {
    let (t, b, n) = frame(normal, tangent)?;
    if !direction.iter().all(|x| x.is_finite()) {
        return Err(Error::InvalidFrame);
    }
    let d = widen(direction);
    // M^-1 = [B x N; N x T; T x B] / det M, det M = T . (B x N) (the adjugate over the determinant).
    let rows = [cross(b, n), cross(n, t), cross(t, b)];
    let det = dot(t, rows[0]);
    narrow(rows.map(|row| dot(row, d) / det))
}

/// Tangent-space `direction` (x along `T`, y along `B`, z along the normal) in object space:
/// `M · direction = x T + y B + z N`, with `M`, `T` and `B` as in [`to_tangent_space`], computed in
/// double precision and rounded to float once. Nothing is normalized: a normal-map sample `(x, y, z)`
/// comes out in the units of the frame it was given.
///
/// The frame is checked as in [`to_tangent_space`], so that every frame one function accepts the
/// other does too, and the two invert each other.
///
/// # Errors
/// [`Error::InvalidFrame`] as for [`to_tangent_space`].
///
/// # Example
/// ```
/// // A surface facing +Y with its tangent along +X and w = +1: B = cross(N, T) = -Z.
/// let (normal, tangent) = ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0, 1.0]);
/// assert_eq!(tbasis::from_tangent_space(normal, tangent, [0.0, 0.0, 1.0])?, normal);
/// assert_eq!(tbasis::from_tangent_space(normal, tangent, [0.0, 1.0, 0.0])?, [0.0, 0.0, -1.0]);
/// assert_eq!(tbasis::from_tangent_space(normal, tangent, [0.6, 0.0, 0.8])?, [0.6, 0.8, 0.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn from_tangent_space(normal: [f32; 3], tangent: [f32; 4], direction: [f32; 3]) -> Result<[f32; 3], Error> {
    let (t, b, n) = frame(normal, tangent)?;
    if !direction.iter().all(|x| x.is_finite()) {
        return Err(Error::InvalidFrame);
    }
    let [x, y, z] = widen(direction);
    narrow([0, 1, 2].map(|k| x * t[k] + y * b[k] + z * n[k]))
}
