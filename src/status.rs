//! The C statuses: one fixed value per failure, and the mapping from the crate's errors.
#![forbid(unsafe_code)]

use tbasis::ErrorKind;

/// Result of a call: `TBASIS_OK` (0) or one of the `TBASIS_ERROR_*` values, which never change.
pub type tbasis_status = u32;

/// Success.
pub const TBASIS_OK: tbasis_status = 0;
/// A required pointer is NULL: `mesh`, `output`, `output->tangents` when the mesh has vertices,
/// the `tangents` of `tbasis_generate_corners` when the mesh has corners, or a vertex or index
/// buffer whose count is nonzero (`texcoords` may be NULL except with policy LEGACY or method
/// MIKKTSPACE).
pub const TBASIS_ERROR_NULL_POINTER: tbasis_status = 1;
/// A stride is smaller than its element: 12 bytes for positions and normals, 8 for texcoords,
/// 16 for tangents, 12 for bitangents.
pub const TBASIS_ERROR_INVALID_STRIDE: tbasis_status = 2;
/// `index_count` (or, when `indices` is NULL, `vertex_count`) is not a multiple of 3.
pub const TBASIS_ERROR_INVALID_INDEX_COUNT: tbasis_status = 3;
/// An index is not less than `vertex_count`.
pub const TBASIS_ERROR_INDEX_OUT_OF_RANGE: tbasis_status = 4;
/// `index_type` is neither `TBASIS_INDEX_U16` nor `TBASIS_INDEX_U32` while `indices` is not NULL.
pub const TBASIS_ERROR_INVALID_INDEX_TYPE: tbasis_status = 5;
/// `options->method` is not a `TBASIS_METHOD_*` value.
pub const TBASIS_ERROR_UNKNOWN_METHOD: tbasis_status = 6;
/// `options->degenerate_policy` is not a `TBASIS_DEGENERATE_*` value.
pub const TBASIS_ERROR_UNKNOWN_POLICY: tbasis_status = 7;
/// `options->flags` has a bit that no `TBASIS_FLAG_*` names.
pub const TBASIS_ERROR_UNKNOWN_FLAGS: tbasis_status = 8;
/// `stride * count`, or the address range a buffer spans, overflows; or, with method MIKKTSPACE,
/// the mesh has more than 2^30 - 1 vertices or corners (its working arrays index them in 32 bits).
pub const TBASIS_ERROR_SIZE_OVERFLOW: tbasis_status = 9;
/// An output byte is also an input byte, a byte of the other output, or a scratch byte (or the
/// scratch shares a byte with an input). Interleaving outputs between inputs is fine.
pub const TBASIS_ERROR_OVERLAP: tbasis_status = 10;
/// Policy REJECT found a degenerate triangle; `report->first_degenerate_triangle` names it.
pub const TBASIS_ERROR_DEGENERATE_UV: tbasis_status = 11;
/// An allocation failed: the working memory the call allocates when `options->scratch` is NULL,
/// or one of the smaller ones some calls make (on several threads, or a seam split's lists).
/// Nothing was written. Only the standard library's own bookkeeping to start a worker thread
/// (`threads` > 1: a few dozen bytes per thread) cannot fail softly: the process ends there.
pub const TBASIS_ERROR_OUT_OF_MEMORY: tbasis_status = 12;
/// `options->scratch` is not NULL and `options->scratch_size` is below `tbasis_scratch_size`.
pub const TBASIS_ERROR_SCRATCH_TOO_SMALL: tbasis_status = 13;
/// `options->degenerate_threshold` is negative, NaN or infinite.
pub const TBASIS_ERROR_INVALID_THRESHOLD: tbasis_status = 14;
/// A count is negative (`tbasis_calculate_tangent_array` takes `long`).
pub const TBASIS_ERROR_INVALID_COUNT: tbasis_status = 15;
/// A bug in the library (a panic) was caught at the boundary. Unlike every other error, it may
/// come after writing began: the outputs (and the scratch) may hold any mix of their old bytes
/// and new values, element by element, and must not be used; only the transforms' `result` is
/// certainly unwritten. With `threads` > 1 the same: every worker thread of the call has ended
/// when it returns, so nothing is written afterwards. `*report` is left unchanged.
pub const TBASIS_ERROR_INTERNAL: tbasis_status = 16;
/// `tbasis_to_tangent_space` or `tbasis_from_tangent_space`: an input is NaN or infinite, the
/// frame is singular (`normal` or the tangent zero, `w` zero, or the two parallel), or a result
/// component overflows float.
pub const TBASIS_ERROR_INVALID_FRAME: tbasis_status = 17;
/// `tbasis_split_corners`: the mesh would need more than 2^32 vertices, beyond 32-bit indices.
pub const TBASIS_ERROR_TOO_MANY_VERTICES: tbasis_status = 18;
/// `options->degenerate_policy` is LEGACY with a method that has no legacy form: LEGACY reproduces
/// the listing (method LENGYEL) or mikktspace.c (method MIKKTSPACE), and nothing else.
pub const TBASIS_ERROR_NO_LEGACY_FORM: tbasis_status = 19;

/// Why a C call failed: an error of the crate, or one only a C caller can make.
#[derive(Debug)]
pub(crate) enum Failure {
    /// An error the crate returned.
    Library(tbasis::Error),
    /// A failure found at the boundary (NULL pointers, unknown values, negative counts, panics).
    Status(tbasis_status),
}

impl From<tbasis::Error> for Failure {
    fn from(error: tbasis::Error) -> Self {
        Failure::Library(error)
    }
}

impl Failure {
    pub(crate) const NULL_POINTER: Failure = Failure::Status(TBASIS_ERROR_NULL_POINTER);

    /// The status a C caller gets.
    pub(crate) fn status(&self) -> tbasis_status {
        match self {
            Failure::Status(status) => *status,
            Failure::Library(error) => status_of(error.kind()),
        }
    }
}

/// The C status of an error of the crate.
pub(crate) fn status_of(kind: ErrorKind) -> tbasis_status {
    match kind {
        // In C, missing texture coordinates are a NULL `texcoords`.
        ErrorKind::MissingTexcoords => TBASIS_ERROR_NULL_POINTER,
        ErrorKind::InvalidStride => TBASIS_ERROR_INVALID_STRIDE,
        ErrorKind::InvalidIndexCount => TBASIS_ERROR_INVALID_INDEX_COUNT,
        ErrorKind::IndexOutOfRange | ErrorKind::SourceOutOfRange => TBASIS_ERROR_INDEX_OUT_OF_RANGE,
        ErrorKind::LengthMismatch | ErrorKind::BufferTooShort => TBASIS_ERROR_INVALID_COUNT,
        ErrorKind::SizeOverflow => TBASIS_ERROR_SIZE_OVERFLOW,
        ErrorKind::Overlap => TBASIS_ERROR_OVERLAP,
        ErrorKind::DegenerateUv => TBASIS_ERROR_DEGENERATE_UV,
        ErrorKind::OutOfMemory => TBASIS_ERROR_OUT_OF_MEMORY,
        ErrorKind::ScratchTooSmall => TBASIS_ERROR_SCRATCH_TOO_SMALL,
        ErrorKind::InvalidThreshold => TBASIS_ERROR_INVALID_THRESHOLD,
        ErrorKind::InvalidFrame => TBASIS_ERROR_INVALID_FRAME,
        ErrorKind::TooManyVertices => TBASIS_ERROR_TOO_MANY_VERTICES,
        ErrorKind::NoLegacyForm => TBASIS_ERROR_NO_LEGACY_FORM,
        _ => TBASIS_ERROR_INTERNAL,
    }
}

/// A static, NUL-terminated description of a status; `None` for a value no status has.
pub(crate) fn message_nul(status: tbasis_status) -> Option<&'static str> {
    Some(match status {
        TBASIS_OK => "success\0",
        TBASIS_ERROR_NULL_POINTER => {
            "a required pointer is NULL, or texcoords is NULL where the method or policy needs them\0"
        }
        TBASIS_ERROR_INVALID_STRIDE => "a stride is smaller than its element\0",
        TBASIS_ERROR_INVALID_INDEX_COUNT => "the index count is not a multiple of 3\0",
        TBASIS_ERROR_INDEX_OUT_OF_RANGE => "an index is not less than vertex_count\0",
        TBASIS_ERROR_INVALID_INDEX_TYPE => "index_type is not TBASIS_INDEX_U16 or TBASIS_INDEX_U32\0",
        TBASIS_ERROR_UNKNOWN_METHOD => "unknown method\0",
        TBASIS_ERROR_UNKNOWN_POLICY => "unknown degenerate policy\0",
        TBASIS_ERROR_UNKNOWN_FLAGS => "unknown flag bits\0",
        TBASIS_ERROR_SIZE_OVERFLOW => "a buffer's size overflows the address space\0",
        TBASIS_ERROR_OVERLAP => "an output buffer overlaps an input, the other output or the scratch\0",
        TBASIS_ERROR_DEGENERATE_UV => "a triangle has degenerate texture coordinates or non-finite input\0",
        TBASIS_ERROR_OUT_OF_MEMORY => "out of memory\0",
        TBASIS_ERROR_SCRATCH_TOO_SMALL => "the scratch buffer is smaller than tbasis_scratch_size\0",
        TBASIS_ERROR_INVALID_THRESHOLD => "degenerate_threshold is negative or not finite\0",
        TBASIS_ERROR_INVALID_COUNT => "a count is negative, or a buffer does not hold the count it must\0",
        TBASIS_ERROR_INTERNAL => "internal error\0",
        TBASIS_ERROR_INVALID_FRAME => "the tangent frame is singular, or an input or the result is not finite\0",
        TBASIS_ERROR_TOO_MANY_VERTICES => "the split mesh would need vertex indices beyond 32 bits\0",
        TBASIS_ERROR_NO_LEGACY_FORM => {
            "policy LEGACY needs method LENGYEL (the listing) or MIKKTSPACE (mikktspace.c)\0"
        }
        _ => return None,
    })
}
