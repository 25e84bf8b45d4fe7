//! Tangents computed in place in an interleaved vertex buffer, from safe code.
#![forbid(unsafe_code)]

use crate::error::Error;
use crate::generate::generate;
use crate::mesh::{Indices, Mesh, Output};
use crate::options::Options;
use crate::report::Report;
use crate::views::interleaved::views_in_place;

/// Where the attributes sit in each vertex of an interleaved buffer: byte offsets from the start of
/// a vertex of `stride` bytes. Any alignment; the tangent's 16 bytes must not share a byte with
/// the attributes read.
///
/// ```
/// // position, normal, uv, tangent: 3 + 3 + 2 + 4 floats.
/// let layout = tbasis::VertexLayout::new(48, 0, 12, 32).with_texcoord(24);
/// assert_eq!(layout.texcoord, Some(24));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub struct VertexLayout {
    /// Bytes from one vertex to the next.
    pub stride: usize,
    /// Offset of the position, 3 floats.
    pub position: usize,
    /// Offset of the normal, 3 floats.
    pub normal: usize,
    /// Offset of the texture coordinate, 2 floats; `None`: no texture coordinates.
    pub texcoord: Option<usize>,
    /// Offset of the tangent written, 4 floats.
    pub tangent: usize,
}

impl VertexLayout {
    /// A layout without texture coordinates; add them with [`VertexLayout::with_texcoord`].
    ///
    /// ```
    /// // Position, normal and tangent: 3 + 3 + 4 floats.
    /// let layout = tbasis::VertexLayout::new(40, 0, 12, 24);
    /// assert_eq!((layout.stride, layout.tangent, layout.texcoord), (40, 24, None));
    /// ```
    pub fn new(stride: usize, position: usize, normal: usize, tangent: usize) -> Self {
        VertexLayout {
            stride,
            position,
            normal,
            texcoord: None,
            tangent,
        }
    }

    /// With texture coordinates at `offset`.
    ///
    /// ```
    /// use tbasis::VertexLayout;
    ///
    /// let without = VertexLayout::new(48, 0, 12, 32);
    /// let with = without.with_texcoord(24);
    /// assert_eq!((without.texcoord, with.texcoord), (None, Some(24)));
    /// assert_eq!(with.tangent, without.tangent);
    /// ```
    pub fn with_texcoord(self, offset: usize) -> Self {
        VertexLayout {
            texcoord: Some(offset),
            ..self
        }
    }
}

/// [`generate`] on an interleaved vertex buffer, writing each vertex's tangent into its own bytes
/// at `layout.tangent`. The buffer holds `vertices.len() / layout.stride` vertices (trailing bytes
/// of a partial vertex are neither read nor written).
///
/// Fails with [`Error::InvalidStride`] when an attribute does not fit in `layout.stride`, with
/// [`Error::Overlap`] when the tangent shares bytes with an attribute read, and as [`generate`]
/// does; on error no byte has been written.
///
/// ```
/// use tbasis::{generate_interleaved, Options, VertexLayout};
///
/// // Three vertices of 12 floats: position, normal, uv, tangent (written), and 0.0 padding.
/// let floats: [[f32; 12]; 3] = [
///     [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
///     [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
///     [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
/// ];
/// let mut bytes: Vec<u8> = floats.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
/// let layout = VertexLayout::new(48, 0, 12, 32).with_texcoord(24);
///
/// generate_interleaved(&mut bytes, &layout, &[0u16, 1, 2], &Options::default())?;
/// let tangent: Vec<f32> = bytes[32..48].chunks(4).map(|b| f32::from_le_bytes(b.try_into().unwrap())).collect();
/// assert_eq!(tangent, [1.0, 0.0, 0.0, 1.0]);
/// # Ok::<(), tbasis::Error>(())
/// ```
pub fn generate_interleaved<'i>(
    vertices: &mut [u8],
    layout: &VertexLayout,
    indices: impl Into<Indices<'i>>,
    options: &Options,
) -> Result<Report, Error> {
    let indices = indices.into();
    views_in_place(vertices, layout, |positions, normals, texcoords, tangents| {
        let mesh = Mesh {
            positions,
            normals,
            texcoords,
            indices,
        };
        generate(&mesh, options, &mut Output::new(tangents))
    })
}
