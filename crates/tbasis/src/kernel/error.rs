//! Why a call failed, naming the triangle, index or buffer at fault and the valid range.
#![forbid(unsafe_code)]

use core::fmt;

use crate::kernel::choices::{DegeneratePolicy, Method};
use crate::kernel::report::Report;

/// A buffer a call reads or writes, as errors name it.
///
/// ```
/// use tbasis::{generate, Buffer, Error, Mesh, Options, Output};
///
/// let mesh = Mesh::new(&[[0.0f32; 3]; 3], &[[0.0, 0.0, 1.0f32]; 3]);
/// let mut tangents = [[0.0f32; 4]; 2]; // one short
/// let error = generate(&mesh, &Options::default(), &mut Output::new(&mut tangents)).unwrap_err();
/// assert_eq!(error, Error::LengthMismatch { buffer: Buffer::Tangents, len: 2, expected: 3 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Buffer {
    /// [`crate::Mesh::positions`].
    Positions,
    /// [`crate::Mesh::normals`].
    Normals,
    /// [`crate::Mesh::texcoords`].
    Texcoords,
    /// [`crate::Mesh::indices`].
    Indices,
    /// [`crate::Output::tangents`], or the per-corner tangents a call writes.
    Tangents,
    /// [`crate::Output::bitangents`].
    Bitangents,
    /// The per-corner tangents a seam split reads.
    CornerTangents,
    /// The caller's scratch memory.
    Scratch,
    /// An attribute buffer [`crate::copy_split_vertices`] fills.
    Attribute,
}

impl Buffer {
    /// The buffer's name in messages: `"positions"`, `"texcoords"`...
    ///
    /// ```
    /// assert_eq!(tbasis::Buffer::Texcoords.name(), "texcoords");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Buffer::Positions => "positions",
            Buffer::Normals => "normals",
            Buffer::Texcoords => "texcoords",
            Buffer::Indices => "indices",
            Buffer::Tangents => "tangents",
            Buffer::Bitangents => "bitangents",
            Buffer::CornerTangents => "corner tangents",
            Buffer::Scratch => "scratch",
            Buffer::Attribute => "attribute",
        }
    }
}

/// Why a call failed. On any error the call has written no output byte.
///
/// Match on the variant for the details, or compare [`Error::kind`] for the category.
///
/// ```
/// use tbasis::{generate, Error, Indices, Mesh, Options, Output, Strided, StridedMut};
///
/// let positions = [[0.0f32; 3]; 3];
/// let normals = [[0.0, 0.0, 1.0f32]; 3];
/// let texcoords = [[0.0f32; 2]; 3];
/// let indices = [0u32, 1, 7];
/// let mut tangents = [[0.0f32; 4]; 3];
/// let mesh = Mesh::new(&positions, &normals)
///     .with_texcoords(&texcoords)
///     .with_indices(Indices::U32(Strided::from_slice(&indices)));
/// let error = generate(&mesh, &Options::default(), &mut Output::new(&mut tangents)).unwrap_err();
///
/// assert_eq!(error, Error::IndexOutOfRange { triangle: 0, index: 7, vertex_count: 3 });
/// assert_eq!(error.to_string(), "triangle 0 uses vertex 7, but the mesh has 3 vertices (0..3)");
/// assert_eq!(tangents, [[0.0; 4]; 3]);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// The method or the policy reads texture coordinates, and the mesh has none.
    MissingTexcoords {
        /// The method asked for.
        method: Method,
        /// The policy asked for.
        policy: DegeneratePolicy,
    },
    /// A stride is smaller than the element it steps over.
    InvalidStride {
        /// Bytes from one element to the next.
        stride: usize,
        /// Bytes of one element.
        element_size: usize,
    },
    /// The index count (or, unindexed, the vertex count) is not a multiple of 3.
    InvalidIndexCount {
        /// The count that does not make whole triangles.
        count: usize,
    },
    /// A triangle uses a vertex the mesh does not have (the first such triangle).
    IndexOutOfRange {
        /// The triangle: its indices are `3 * triangle .. 3 * triangle + 3`.
        triangle: usize,
        /// The index at fault.
        index: usize,
        /// Valid indices are below this.
        vertex_count: usize,
    },
    /// A seam split's source names a vertex the mesh does not have.
    SourceOutOfRange {
        /// Where in `sources`.
        position: usize,
        /// The source at fault.
        source: u32,
        /// Valid sources are below this.
        vertex_count: usize,
    },
    /// A buffer has a different number of elements than the mesh needs.
    LengthMismatch {
        /// The buffer.
        buffer: Buffer,
        /// Its length, in elements.
        len: usize,
        /// The length it must have.
        expected: usize,
    },
    /// A byte buffer is shorter than the elements it must hold span.
    BufferTooShort {
        /// Its length in bytes.
        len: usize,
        /// The bytes its elements span.
        needed: usize,
    },
    /// The size of a buffer, the scratch or a result does not fit the address space.
    SizeOverflow,
    /// A buffer the call writes shares bytes with another buffer of the call.
    Overlap {
        /// The buffer written.
        written: Buffer,
        /// The buffer it shares bytes with.
        other: Buffer,
    },
    /// Policy REJECT met a degenerate triangle (UVs collapsed, zero area, or non-finite input).
    DegenerateUv {
        /// The first degenerate triangle.
        triangle: usize,
        /// What the call found, all degenerate triangles counted.
        report: Report,
    },
    /// An allocation of the call failed (its working memory, or a list it grows); nothing was
    /// written.
    OutOfMemory,
    /// The caller's scratch is smaller than [`crate::scratch_size_for`].
    ScratchTooSmall {
        /// Bytes the call needs.
        needed: usize,
        /// Bytes given.
        len: usize,
    },
    /// [`crate::Options::degenerate_threshold`] is negative, NaN or infinite.
    InvalidThreshold {
        /// The threshold given.
        threshold: f32,
    },
    /// A tangent-space transform got a frame that is singular (normal or tangent zero or parallel,
    /// handedness zero) or not finite, a non-finite direction, or a result that overflows a float.
    InvalidFrame,
    /// A seam split would append vertices whose indices do not fit 32 bits.
    TooManyVertices,
    /// Policy LEGACY with a method that has no legacy form: LEGACY reproduces the listing
    /// (method LENGYEL) or mikktspace.c (method MIKKTSPACE) bit for bit, and nothing else.
    NoLegacyForm {
        /// The method asked for.
        method: Method,
    },
}

/// The category of an [`Error`], without its details.
///
/// ```
/// use tbasis::{ErrorKind, Options};
///
/// let error = Options::default().with_degenerate_threshold(-1.0).validate().unwrap_err();
/// assert_eq!(error.kind(), ErrorKind::InvalidThreshold);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[allow(missing_docs)] // Each is the variant of [`Error`] of the same name.
pub enum ErrorKind {
    MissingTexcoords,
    InvalidStride,
    InvalidIndexCount,
    IndexOutOfRange,
    SourceOutOfRange,
    LengthMismatch,
    BufferTooShort,
    SizeOverflow,
    Overlap,
    DegenerateUv,
    OutOfMemory,
    ScratchTooSmall,
    InvalidThreshold,
    InvalidFrame,
    TooManyVertices,
    NoLegacyForm,
}

impl Error {
    /// The category, for comparing errors without their details.
    ///
    /// ```
    /// use tbasis::{Error, ErrorKind};
    /// let error = Error::ScratchTooSmall { needed: 32, len: 31 };
    /// assert_eq!(error.kind(), ErrorKind::ScratchTooSmall);
    /// ```
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::MissingTexcoords { .. } => ErrorKind::MissingTexcoords,
            Error::InvalidStride { .. } => ErrorKind::InvalidStride,
            Error::InvalidIndexCount { .. } => ErrorKind::InvalidIndexCount,
            Error::IndexOutOfRange { .. } => ErrorKind::IndexOutOfRange,
            Error::SourceOutOfRange { .. } => ErrorKind::SourceOutOfRange,
            Error::LengthMismatch { .. } => ErrorKind::LengthMismatch,
            Error::BufferTooShort { .. } => ErrorKind::BufferTooShort,
            Error::SizeOverflow => ErrorKind::SizeOverflow,
            Error::Overlap { .. } => ErrorKind::Overlap,
            Error::DegenerateUv { .. } => ErrorKind::DegenerateUv,
            Error::OutOfMemory => ErrorKind::OutOfMemory,
            Error::ScratchTooSmall { .. } => ErrorKind::ScratchTooSmall,
            Error::InvalidThreshold { .. } => ErrorKind::InvalidThreshold,
            Error::InvalidFrame => ErrorKind::InvalidFrame,
            Error::TooManyVertices => ErrorKind::TooManyVertices,
            Error::NoLegacyForm { .. } => ErrorKind::NoLegacyForm,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::MissingTexcoords { method, policy } => write!(
                f,
                "method {method:?} with policy {policy:?} needs texture coordinates, and the mesh has none"
            ),
            Error::InvalidStride { stride, element_size } => write!(
                f,
                "a stride of {stride} bytes is smaller than its {element_size}-byte element"
            ),
            Error::InvalidIndexCount { count } => write!(
                f,
                "{count} indices (or unindexed vertices) do not make whole triangles: the count must be a multiple of 3"
            ),
            Error::IndexOutOfRange {
                triangle,
                index,
                vertex_count,
            } => write!(
                f,
                "triangle {triangle} uses vertex {index}, but the mesh has {vertex_count} vertices (0..{vertex_count})"
            ),
            Error::SourceOutOfRange {
                position,
                source,
                vertex_count,
            } => write!(
                f,
                "sources[{position}] is vertex {source}, but the mesh has {vertex_count} vertices (0..{vertex_count})"
            ),
            Error::LengthMismatch { buffer, len, expected } => write!(
                f,
                "{} has {len} elements where the mesh needs {expected}",
                buffer.name()
            ),
            Error::BufferTooShort { len, needed } => write!(
                f,
                "a buffer of {len} bytes is shorter than the {needed} bytes its elements span"
            ),
            Error::SizeOverflow => f.write_str("a buffer's size overflows the address space"),
            Error::Overlap { written, other } => write!(
                f,
                "the {} output shares bytes with the {} buffer",
                written.name(),
                other.name()
            ),
            Error::DegenerateUv { triangle, report } => write!(
                f,
                "policy Reject: triangle {triangle} has degenerate texture coordinates, zero area or non-finite input ({} degenerate triangles in all)",
                report.degenerate_triangles
            ),
            Error::OutOfMemory => f.write_str("out of memory: an allocation of the call failed"),
            Error::ScratchTooSmall { needed, len } => write!(
                f,
                "the scratch holds {len} bytes; this call needs {needed} (scratch_size_for)"
            ),
            Error::InvalidThreshold { threshold } => write!(
                f,
                "degenerate_threshold {threshold} is not a finite number >= 0"
            ),
            Error::InvalidFrame => f.write_str(
                "the tangent frame is singular (normal or tangent zero or parallel, handedness zero), or an input or the result is not finite",
            ),
            Error::TooManyVertices => f.write_str("the split mesh would need vertex indices beyond 32 bits"),
            Error::NoLegacyForm { method } => write!(
                f,
                "policy Legacy reproduces the listing (method Lengyel) or mikktspace.c (method Mikktspace); method {method:?} has no legacy form"
            ),
        }
    }
}

impl std::error::Error for Error {}
