//! The C values of the options: index types, methods, policies and flags, and the methods and
//! policies they name. Shared with the Python package, which takes the same values.
#![forbid(unsafe_code)]

use tbasis::{DegeneratePolicy, Method};

/// `index_type`: 16-bit indices.
pub const TBASIS_INDEX_U16: u32 = 1;
/// `index_type`: 32-bit indices.
pub const TBASIS_INDEX_U32: u32 = 2;

/// `method`: the original listing (Lengyel 2001): each triangle adds its unnormalized dP/du.
pub const TBASIS_METHOD_LENGYEL: u32 = 1;
/// `method` (the default, except with policy LEGACY: there the listing's, LENGYEL): each
/// triangle's tangent in the vertex's tangent plane, weighted by the
/// corner angle, in mikktspace.c's arithmetic; mikktspace.c's per-vertex frame on clean meshes
/// (README, "Methods", says where exactly).
pub const TBASIS_METHOD_ANGLE: u32 = 2;
/// `method`: unit face tangents weighted by triangle area.
pub const TBASIS_METHOD_AREA: u32 = 3;
/// `method`: unit face tangents with equal weights (per-face averaging).
pub const TBASIS_METHOD_UNIFORM: u32 = 4;
/// `method`: exactly mikktspace.c's `genTangSpaceDefault`, per corner (`tbasis_generate_corners`;
/// `tbasis_generate` gives each vertex its first corner's frame). Needs `texcoords`. Its default
/// policy (0) is LEGACY: exactly mikktspace.c; SKIP and INHERIT replace only the frames
/// mikktspace.c leaves unusable (README, "MikkTSpace, bit for bit").
pub const TBASIS_METHOD_MIKKTSPACE: u32 = 5;

/// `degenerate_policy`: exactly the listing (method LENGYEL, or 0) or mikktspace.c (method
/// MIKKTSPACE), bit for bit, inf/NaN included; any other method with it is
/// `TBASIS_ERROR_NO_LEGACY_FORM`.
pub const TBASIS_DEGENERATE_LEGACY: u32 = 1;
/// `degenerate_policy`: degenerate triangles contribute nothing; vertices left without a tangent
/// get the fallback frame built from their normal.
pub const TBASIS_DEGENERATE_SKIP: u32 = 2;
/// `degenerate_policy` (the default): like SKIP, but vertices left without a tangent first take
/// one from their neighbours across shared triangles.
pub const TBASIS_DEGENERATE_INHERIT: u32 = 3;
/// `degenerate_policy`: refuse a mesh with any degenerate triangle (`TBASIS_ERROR_DEGENERATE_UV`).
pub const TBASIS_DEGENERATE_REJECT: u32 = 4;

/// `flags` bit: texture coordinates have V pointing down (glTF, Direct3D). The frame is computed
/// as for `v' = 1 - v`, so `w` matches what those conventions expect.
pub const TBASIS_FLAG_FLIP_V: u32 = 1;

/// The method a `method` value names beside the `degenerate_policy` value `policy`: 0 is the
/// default, the listing's (`TBASIS_METHOD_LENGYEL`) with policy LEGACY, else `TBASIS_METHOD_ANGLE`.
pub fn method_of(code: u32, policy: u32) -> Option<Method> {
    Some(match code {
        0 if policy == TBASIS_DEGENERATE_LEGACY => Method::Lengyel,
        0 => Method::DEFAULT,
        TBASIS_METHOD_LENGYEL => Method::Lengyel,
        TBASIS_METHOD_ANGLE => Method::Angle,
        TBASIS_METHOD_AREA => Method::Area,
        TBASIS_METHOD_UNIFORM => Method::Uniform,
        TBASIS_METHOD_MIKKTSPACE => Method::Mikktspace,
        _ => return None,
    })
}

/// The policy a `degenerate_policy` value names for `method`; 0 is that method's default.
pub fn policy_of(code: u32, method: Method) -> Option<DegeneratePolicy> {
    Some(match code {
        0 => DegeneratePolicy::default_for(method),
        TBASIS_DEGENERATE_LEGACY => DegeneratePolicy::Legacy,
        TBASIS_DEGENERATE_SKIP => DegeneratePolicy::Skip,
        TBASIS_DEGENERATE_INHERIT => DegeneratePolicy::Inherit,
        TBASIS_DEGENERATE_REJECT => DegeneratePolicy::Reject,
        _ => return None,
    })
}
