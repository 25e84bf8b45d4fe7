//! Read and write views into one interleaved vertex buffer. The one place where views that read
//! and a view that writes come from the same `&mut [u8]`: they are handed out only together with
//! the check that the written bytes are none of the read ones (the library's overlap check, which
//! every call makes before writing).

use crate::error::Error;
use crate::interleaved::VertexLayout;
use crate::views::strided::{Strided, StridedMut};

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
