//! The C values of the options: index types, methods, policies and flags, and the methods and
//! policies they name. Shared with the Python package, which takes the same values.
#![forbid(unsafe_code)]

use tbasis::{DegeneratePolicy, Method};

/// `index_type`: 16-bit indices.
pub const TBASIS_INDEX_U16: u32 = 1;
/// `index_type`: 32-bit indices.
pub const TBASIS_INDEX_U32: u32 = 2;

/// `method`: the original listing (Lengyel 2001); each triangle adds its unnormalized dP/du.
pub const TBASIS_METHOD_LENGYEL: u32 = 1;
/// `method` (the default): each triangle's tangent projected into the vertex's tangent plane,
/// normalized and weighted by the corner angle measured in that plane, in mikktspace.c's
/// arithmetic: per vertex, mikktspace.c's frame for the vertex's first corner wherever the vertex's
/// triangles and normal are clean (see the README's "Methods").
pub const TBASIS_METHOD_ANGLE: u32 = 2;
/// `method`: unit face tangents weighted by triangle area.
pub const TBASIS_METHOD_AREA: u32 = 3;
/// `method`: unit face tangents with equal weights (per-face averaging).
pub const TBASIS_METHOD_UNIFORM: u32 = 4;
/// `method`: exactly what mikktspace.c's `genTangSpaceDefault` hands to `setTSpaceBasic`, float
/// for float, per corner (`tbasis_generate_corners`): the tangents almost every normal map is
/// baked against. Needs `texcoords`. Its default policy (0) is LEGACY, which is exactly
/// mikktspace.c, including what it writes for degenerate and non-finite input; SKIP and INHERIT
/// differ only where mikktspace.c writes a non-finite, zero or non-unit tangent or one not
/// perpendicular to the normal, and there write a finite unit tangent perpendicular to it.
/// `tbasis_generate` gives each vertex its first corner's frame.
pub const TBASIS_METHOD_MIKKTSPACE: u32 = 5;

/// `degenerate_policy`: exactly the listing (or, with method MIKKTSPACE, exactly mikktspace.c),
/// bit for bit, including its inf/NaN.
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

/// The method a `method` value names; 0 is the default (`TBASIS_METHOD_ANGLE`).
pub fn method_of(code: u32) -> Option<Method> {
    Some(match code {
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
