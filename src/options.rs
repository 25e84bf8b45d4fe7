//! What the caller can choose: the method, the degenerate-UV policy, flags and threshold.
#![forbid(unsafe_code)]

use crate::status::Error;

/// How per-triangle tangents are combined at a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum Method {
    /// The original listing: each triangle adds its unnormalized dP/du and dP/dv (Lengyel 2001).
    Lengyel = 1,
    /// Each triangle's tangent, projected into the vertex's tangent plane and normalized, weighted
    /// by the triangle's corner angle at the vertex (the weighting MikkTSpace uses).
    Angle = 2,
    /// Unit face tangents weighted by triangle area.
    Area = 3,
    /// Unit face tangents with equal weights (per-face averaging).
    Uniform = 4,
    /// Exactly what mikktspace.c's `genTangSpaceDefault` gives, float for float, per corner: the
    /// tangents almost every normal map is baked against. Its default policy is `Legacy`.
    Mikktspace = 5,
}

impl Method {
    /// The method used when the caller asks for the default (`0` in C): ANGLE, whose mean error
    /// on the analytic scenes of `docs/chart.md` is within 0.2% of mikktspace.c's on every scene
    /// and size and about half the listing's.
    pub const DEFAULT: Method = Method::Angle;

    /// The method with this C value; `0` is the default.
    pub fn from_code(code: u32) -> Result<Method, Error> {
        match code {
            0 => Ok(Method::DEFAULT),
            1 => Ok(Method::Lengyel),
            2 => Ok(Method::Angle),
            3 => Ok(Method::Area),
            4 => Ok(Method::Uniform),
            5 => Ok(Method::Mikktspace),
            _ => Err(Error::UnknownMethod),
        }
    }
}

/// What happens to triangles whose texture coordinates (or inputs) are degenerate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum DegeneratePolicy {
    /// Exactly the listing, bit for bit, including the inf/NaN it writes on a zero UV determinant.
    Legacy = 1,
    /// Degenerate triangles contribute nothing; a vertex left without a tangent gets a fallback
    /// frame built from its normal.
    Skip = 2,
    /// Like `Skip`, but a vertex left without a tangent first takes one from its neighbours across
    /// shared triangles, and falls back only when its whole connected region has none.
    Inherit = 3,
    /// Refuse the mesh with [`Error::DegenerateUv`], naming the first degenerate triangle.
    Reject = 4,
}

impl DegeneratePolicy {
    /// The policy used when the caller asks for the default (`0` in C).
    pub const DEFAULT: DegeneratePolicy = DegeneratePolicy::Inherit;

    /// The policy `0` stands for with `method`: `Legacy` for [`Method::Mikktspace`] (exactly
    /// mikktspace.c), [`DegeneratePolicy::DEFAULT`] for the others.
    pub fn default_for(method: Method) -> DegeneratePolicy {
        match method {
            Method::Mikktspace => DegeneratePolicy::Legacy,
            _ => DegeneratePolicy::DEFAULT,
        }
    }

    /// The policy with this C value for `method`; `0` is the method's default.
    pub fn from_code(code: u32, method: Method) -> Result<DegeneratePolicy, Error> {
        match code {
            0 => Ok(DegeneratePolicy::default_for(method)),
            1 => Ok(DegeneratePolicy::Legacy),
            2 => Ok(DegeneratePolicy::Skip),
            3 => Ok(DegeneratePolicy::Inherit),
            4 => Ok(DegeneratePolicy::Reject),
            _ => Err(Error::UnknownPolicy),
        }
    }
}

/// Flag bit: texture coordinates have V pointing down (glTF, Direct3D). See [`Options::flip_v`].
pub(crate) const FLAG_FLIP_V: u32 = 1;
/// Every flag bit the library knows.
pub(crate) const KNOWN_FLAGS: u32 = FLAG_FLIP_V;

/// The default for [`Options::degenerate_threshold`].
///
/// A triangle's UV quality `q = 2*sqrt(3)*|det| / (|e0|^2 + |e1|^2 + |e2|^2)` is 1 for an
/// equilateral triangle, about 0.87 for a grid's right triangle, and falls like `sqrt(3)/k` for a
/// sliver of aspect ratio `k`. Below 1e-5 (aspect ratios beyond ~170 000:1) the UV edges that define
/// the tangent differ by less than a float's relative precision of the coordinates they come from,
/// so the solved tangent is rounding noise.
pub const DEFAULT_DEGENERATE_THRESHOLD: f32 = 1e-5;

/// Everything a call can be told besides the mesh and the output.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// How per-triangle tangents are combined.
    pub method: Method,
    /// What happens to degenerate triangles.
    pub degenerate_policy: DegeneratePolicy,
    /// Texture coordinates have V pointing down (glTF, Direct3D): the tangent frame is computed as
    /// for `v' = 1 - v`, which turns the handedness `w` so that `bitangent = w * cross(n, t)`
    /// points towards increasing V as the file stores it upside down.
    pub flip_v: bool,
    /// Quality below which a triangle counts as degenerate (see [`DEFAULT_DEGENERATE_THRESHOLD`]).
    pub degenerate_threshold: f32,
    /// Upper bound on worker threads; 0 and 1 both mean the calling thread only.
    pub threads: u32,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::DEFAULT,
            degenerate_policy: DegeneratePolicy::DEFAULT,
            flip_v: false,
            degenerate_threshold: DEFAULT_DEGENERATE_THRESHOLD,
            threads: 0,
        }
    }
}

impl Options {
    /// The listing, exactly: method LENGYEL with policy LEGACY.
    pub fn legacy() -> Self {
        Options {
            method: Method::Lengyel,
            degenerate_policy: DegeneratePolicy::Legacy,
            ..Options::default()
        }
    }

    /// mikktspace.c's tangents, bit for bit: method MIKKTSPACE with policy LEGACY.
    pub fn mikktspace() -> Self {
        Options {
            method: Method::Mikktspace,
            degenerate_policy: DegeneratePolicy::Legacy,
            ..Options::default()
        }
    }

    /// Options from their C values (0 meaning each default), validated.
    pub fn from_codes(method: u32, policy: u32, flags: u32, threshold: f32, threads: u32) -> Result<Self, Error> {
        let method = Method::from_code(method)?;
        let degenerate_policy = DegeneratePolicy::from_code(policy, method)?;
        if flags & !KNOWN_FLAGS != 0 {
            return Err(Error::UnknownFlags);
        }
        let options = Options {
            method,
            degenerate_policy,
            flip_v: flags & FLAG_FLIP_V != 0,
            degenerate_threshold: if threshold == 0.0 {
                DEFAULT_DEGENERATE_THRESHOLD
            } else {
                threshold
            },
            threads,
        };
        options.validate()?;
        Ok(options)
    }

    /// Checks what the types cannot: the threshold is finite and not negative.
    pub fn validate(&self) -> Result<(), Error> {
        if !self.degenerate_threshold.is_finite() || self.degenerate_threshold < 0.0 {
            return Err(Error::InvalidThreshold);
        }
        Ok(())
    }
}
