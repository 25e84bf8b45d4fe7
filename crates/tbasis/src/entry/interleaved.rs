//! Tangents computed in place in an interleaved vertex buffer, from safe code.
#![forbid(unsafe_code)]

use crate::entry::generate::generate;
use crate::kernel::error::Error;
use crate::kernel::mesh::{Indices, Mesh, Output};
use crate::kernel::options::Options;
use crate::kernel::report::Report;
use crate::kernel::views::interleaved::{views_in_place, VertexLayout};

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
