//! Status codes: one fixed value per failure, shared by the Rust API and the C ABI.
#![forbid(unsafe_code)]

use core::fmt;

/// Why a call failed. The discriminants are the C ABI's `TBASIS_ERROR_*` values and never change.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum Error {
    /// A required pointer is NULL (or a buffer is missing while its count is nonzero).
    NullPointer = 1,
    /// A stride is smaller than the element it steps over.
    InvalidStride = 2,
    /// `index_count` (or, unindexed, `vertex_count`) is not a multiple of 3.
    InvalidIndexCount = 3,
    /// An index is `>= vertex_count`.
    IndexOutOfRange = 4,
    /// `index_type` is neither U16 nor U32.
    InvalidIndexType = 5,
    /// `method` is not one of the `TBASIS_METHOD_*` values.
    UnknownMethod = 6,
    /// `degenerate_policy` is not one of the `TBASIS_DEGENERATE_*` values.
    UnknownPolicy = 7,
    /// `flags` has a bit no `TBASIS_FLAG_*` names.
    UnknownFlags = 8,
    /// `stride * count` (or the address range it spans) does not fit the address space.
    SizeOverflow = 9,
    /// An output buffer shares bytes with an input, with the other output, or with the scratch.
    Overlap = 10,
    /// Policy REJECT met a triangle whose UVs (or inputs) are degenerate; see the report.
    DegenerateUv = 11,
    /// The library could not allocate its scratch memory.
    OutOfMemory = 12,
    /// The caller's scratch is smaller than `tbasis_scratch_size`.
    ScratchTooSmall = 13,
    /// `degenerate_threshold` is negative, NaN or infinite.
    InvalidThreshold = 14,
    /// A count is negative (the legacy signature takes `long`), or a Rust slice is shorter or
    /// longer than the count it must hold.
    InvalidCount = 15,
    /// A bug in the library was caught at the boundary; nothing was written.
    Internal = 16,
    /// A tangent-space transform got a frame that is singular (normal or tangent zero or parallel,
    /// handedness zero) or not finite, a non-finite direction, or a result that overflows a float.
    InvalidFrame = 17,
    /// A seam split would append vertices whose indices do not fit 32 bits.
    TooManyVertices = 18,
}

impl Error {
    /// Every error, in the order of its value.
    pub const ALL: [Error; 18] = [
        Error::NullPointer,
        Error::InvalidStride,
        Error::InvalidIndexCount,
        Error::IndexOutOfRange,
        Error::InvalidIndexType,
        Error::UnknownMethod,
        Error::UnknownPolicy,
        Error::UnknownFlags,
        Error::SizeOverflow,
        Error::Overlap,
        Error::DegenerateUv,
        Error::OutOfMemory,
        Error::ScratchTooSmall,
        Error::InvalidThreshold,
        Error::InvalidCount,
        Error::Internal,
        Error::InvalidFrame,
        Error::TooManyVertices,
    ];

    /// The C status value.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The error with this C status value, if any.
    pub fn from_code(code: u32) -> Option<Error> {
        Error::ALL.iter().copied().find(|e| e.code() == code)
    }

    /// A static, NUL-terminated description; the C ABI hands out its pointer.
    pub const fn message_nul(self) -> &'static str {
        match self {
            Error::NullPointer => "a required pointer is NULL\0",
            Error::InvalidStride => "a stride is smaller than its element\0",
            Error::InvalidIndexCount => "the index count is not a multiple of 3\0",
            Error::IndexOutOfRange => "an index is not less than vertex_count\0",
            Error::InvalidIndexType => "index_type is not TBASIS_INDEX_U16 or TBASIS_INDEX_U32\0",
            Error::UnknownMethod => "unknown method\0",
            Error::UnknownPolicy => "unknown degenerate policy\0",
            Error::UnknownFlags => "unknown flag bits\0",
            Error::SizeOverflow => "a buffer's size overflows the address space\0",
            Error::Overlap => "an output buffer overlaps an input, the other output or the scratch\0",
            Error::DegenerateUv => "a triangle has degenerate texture coordinates or non-finite input\0",
            Error::OutOfMemory => "out of memory\0",
            Error::ScratchTooSmall => "the scratch buffer is smaller than tbasis_scratch_size\0",
            Error::InvalidThreshold => "degenerate_threshold is negative or not finite\0",
            Error::InvalidCount => "a count is negative, or a buffer does not hold the count it must\0",
            Error::Internal => "internal error\0",
            Error::InvalidFrame => "the tangent frame is singular, or an input or the result is not finite\0",
            Error::TooManyVertices => "the split mesh would need vertex indices beyond 32 bits\0",
        }
    }

    /// The description without its terminating NUL.
    pub fn message(self) -> &'static str {
        let text = self.message_nul();
        &text[..text.len() - 1]
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.message())
    }
}

impl std::error::Error for Error {}
