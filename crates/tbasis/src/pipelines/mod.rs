//! The three ways to a tangent frame, siblings over the kernel: none imports another.
//!
//! * [`listing`]: the original listing (Lengyel 2001), operation for operation (policy LEGACY
//!   with method LENGYEL).
//! * [`per_vertex`]: the robust per-vertex methods (ANGLE, AREA, UNIFORM and LENGYEL under SKIP,
//!   INHERIT and REJECT), per vertex or per corner.
//! * [`mikktspace`]: mikktspace.c's `genTangSpaceDefault`, float for float (method MIKKTSPACE).
#![forbid(unsafe_code)]

pub(crate) mod listing;
pub(crate) mod mikktspace;
pub(crate) mod per_vertex;
