//! Read and write views into one interleaved vertex buffer. The one place where views that read
//! and a view that writes come from the same `&mut [u8]`: they are handed out only together with
//! the check that the written bytes are none of the read ones (the library's overlap check, which
//! every call makes before writing).

use crate::kernel::error::Error;
use crate::kernel::views::strided::{Strided, StridedMut};

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

/// Calls `job` with views of the positions, normals, texture coordinates and tangents that
/// `layout` places in `vertices`, after checking that each fits in a vertex.
pub(crate) fn views_in_place<R>(
    vertices: &mut [u8],
    layout: &VertexLayout,
    job: impl FnOnce(
        Strided<'_, [f32; 3]>,
        Strided<'_, [f32; 3]>,
        Option<Strided<'_, [f32; 2]>>,
        StridedMut<'_, [f32; 4]>,
    ) -> Result<R, Error>,
) -> Result<R, Error> {
    let stride = layout.stride;
    let fits = |offset: usize, size: usize| match offset.checked_add(size) {
        Some(end) if end <= stride => Ok(offset),
        _ => Err(Error::InvalidStride {
            stride,
            element_size: offset.saturating_add(size),
        }),
    };
    let position = fits(layout.position, 12)?;
    let normal = fits(layout.normal, 12)?;
    let texcoord = layout.texcoord.map(|offset| fits(offset, 8)).transpose()?;
    let tangent = fits(layout.tangent, 16)?;
    let count = vertices.len().checked_div(stride).unwrap_or(0);
    let base = vertices.as_mut_ptr();
    // SAFETY: every view stays inside `vertices` (`count * stride <= len`, each element ends
    // within its vertex), lives no longer than the exclusive borrow of `vertices`, and every view
    // comes from the one pointer `base`. Reads and writes of the same byte cannot happen: the job
    // hands the views to `generate`, which refuses an output that overlaps an input before it
    // writes anything (`validate::check_written`).
    unsafe {
        job(
            Strided::from_raw(base.wrapping_add(position), stride, count),
            Strided::from_raw(base.wrapping_add(normal), stride, count),
            texcoord.map(|offset| Strided::from_raw(base.wrapping_add(offset), stride, count)),
            StridedMut::from_raw(base.wrapping_add(tangent), stride, count),
        )
    }
}
