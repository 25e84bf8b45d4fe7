//! Seam splitting: turn per-corner tangents into an indexed mesh a GPU can draw, duplicating only
//! the vertices whose corners disagree (mirror seams, orientation flips).
#![forbid(unsafe_code)]

use std::collections::HashMap;

use crate::entry::validate::check_len;
use crate::kernel::error::{Buffer, Error};
use crate::kernel::mesh::Mesh;
use crate::kernel::simd::{self, PREFETCH_CORNERS};
use crate::kernel::views::strided::Strided;

/// The split mesh: a new index buffer, and the vertex each appended vertex copies.
///
/// ```
/// use tbasis::{split_corners, Mesh, SeamSplit, Strided};
///
/// # let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0f32]];
/// # let normals = [[0.0, 0.0, 1.0f32]; 4];
/// let mesh = Mesh::new(&positions, &normals).with_indices(&[0u32, 1, 2, 0, 2, 3]);
/// // Vertex 2's corner in the second triangle carries another tangent: vertex 2 is split.
/// let (a, b) = ([1.0, 0.0, 0.0, 1.0f32], [0.0, 1.0, 0.0, 1.0f32]);
/// let split = split_corners(&mesh, &Strided::from_slice(&[a, a, a, a, b, a]))?;
/// assert_eq!(split, SeamSplit { indices: vec![0, 1, 2, 0, 4, 3], sources: vec![2] });
///
/// // Every vertex buffer grows by the copies: vertex 4 is a copy of vertex 2.
/// let mut grown = positions.to_vec();
/// grown.extend(split.sources.iter().map(|&s| positions[s as usize]));
/// assert_eq!(grown[4], positions[2]);
/// # Ok::<(), tbasis::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SeamSplit {
    /// One index per corner, in corner order: the vertex itself where the corner carries its
    /// vertex's first tangent, otherwise `vertex_count + j` for its `j`-th appended vertex.
    pub indices: Vec<u32>,
    /// Appended vertex `vertex_count + j` copies every attribute of vertex `sources[j]`.
    pub sources: Vec<u32>,
}

/// Splits the vertices of `mesh` whose corners carry different tangents.
///
/// Two corners of a vertex share an output vertex exactly when their tangents have the same bits
/// (all four floats; NaN and -0.0 compared as bits). Each vertex keeps its index for the corners
/// that carry its first tangent in corner order; each further distinct tangent appends one vertex,
/// in the order of first appearance. `corner_tangents` holds one tangent per corner
/// ([`crate::generate_corners`]'s output). Takes time linear in the corner count, and memory
/// linear in the corners and the vertices they use.
///
/// Errors: [`Error::InvalidIndexCount`] (not whole triangles), [`Error::IndexOutOfRange`],
/// [`Error::LengthMismatch`] (`corner_tangents` does not have one element per corner),
/// [`Error::TooManyVertices`] (an index of the result would not fit 32 bits),
/// [`Error::OutOfMemory`].
///
/// ```
/// use tbasis::{split_corners, Indices, Mesh, Strided};
/// let positions = [[0.0f32; 3]; 3];
/// let indices = [0u32, 1, 2, 0, 2, 1];
/// let mesh = Mesh {
///     positions: Strided::from_slice(&positions),
///     normals: Strided::from_slice(&positions),
///     texcoords: None,
///     indices: Indices::U32(Strided::from_slice(&indices)),
/// };
/// // The second triangle is mirrored: its corners carry w = -1.
/// let plus = [1.0f32, 0.0, 0.0, 1.0];
/// let minus = [1.0f32, 0.0, 0.0, -1.0];
/// let corners = [plus, plus, plus, minus, minus, minus];
/// let split = split_corners(&mesh, &Strided::from_slice(&corners)).unwrap();
/// assert_eq!(split.indices, [0, 1, 2, 3, 4, 5]);
/// assert_eq!(split.sources, [0, 2, 1]);
/// ```
pub fn split_corners(mesh: &Mesh, corner_tangents: &Strided<[f32; 4]>) -> Result<SeamSplit, Error> {
    let vertex_count = mesh.vertex_count();
    let corner_count = mesh.corner_count();
    mesh.indices.triangle_count(vertex_count)?;
    check_len(Buffer::CornerTangents, corner_tangents.len(), corner_count)?;
    // Checking every index first also bounds the per-vertex table by the vertices used, not by
    // `vertex_count`.
    let mut used = 0;
    for c in 0..corner_count {
        let v = mesh.indices.corner(c);
        if v >= vertex_count {
            return Err(mesh.index_error());
        }
        used = used.max(v + 1);
    }
    let mut split = SeamSplit::default();
    split
        .indices
        .try_reserve_exact(corner_count)
        .map_err(|_| Error::OutOfMemory)?;
    // Per vertex, the bits of its first tangent; vertices no corner has reached yet hold None.
    let mut first: Vec<Option<[u32; 4]>> = Vec::new();
    first.try_reserve_exact(used).map_err(|_| Error::OutOfMemory)?;
    first.resize(used, None);
    // Further tangents are rare (seams), so a map keeps memory proportional to them.
    let mut appended: HashMap<(usize, [u32; 4]), u32> = HashMap::new();
    // Output indices are u32: vertex_count + appended must stay within 2^32.
    let index_limit = u64::from(u32::MAX) + 1;
    for c in 0..corner_count {
        // The vertices are scattered: each one's entry is asked for ahead of its corner.
        if c + PREFETCH_CORNERS < corner_count {
            simd::prefetch(&first, mesh.indices.corner(c + PREFETCH_CORNERS));
        }
        let v = mesh.indices.corner(c);
        let bits = corner_tangents.get(c).map(f32::to_bits);
        let index = match first[v] {
            None => {
                first[v] = Some(bits);
                v as u64
            }
            Some(kept) if kept == bits => v as u64,
            Some(_) => {
                let next = vertex_count as u64 + split.sources.len() as u64;
                match appended.get(&(v, bits)) {
                    Some(&index) => u64::from(index),
                    None => {
                        if next >= index_limit {
                            return Err(Error::TooManyVertices);
                        }
                        appended.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
                        split.sources.try_reserve(1).map_err(|_| Error::OutOfMemory)?;
                        appended.insert((v, bits), next as u32);
                        split.sources.push(v as u32);
                        next
                    }
                }
            }
        };
        // Only an unindexed mesh of more than 2^32 vertices reaches past 32 bits here.
        split
            .indices
            .push(u32::try_from(index).map_err(|_| Error::TooManyVertices)?);
    }
    Ok(split)
}

/// Fills the appended vertices of one attribute buffer: element `vertex_count + j` becomes a copy
/// of element `sources[j]`, for every `j`.
///
/// `attribute` holds elements of `element_size` bytes, `stride` bytes apart, and must have room for
/// `vertex_count + sources.len()` of them. Any attribute works this way: positions, normals, UVs,
/// colours, joints, weights, morph targets. On error nothing is written.
///
/// Errors: [`Error::InvalidStride`] (`element_size > stride`), [`Error::BufferTooShort`] (the
/// buffer is too short), [`Error::SourceOutOfRange`] (a source is not below `vertex_count`),
/// [`Error::SizeOverflow`].
///
/// ```
/// use tbasis::copy_split_vertices;
/// // Two RGBA8 colours with room for one appended vertex that copies vertex 0.
/// let mut colours = [255u8, 0, 0, 255, 0, 255, 0, 255, 0, 0, 0, 0];
/// copy_split_vertices(&mut colours, 4, 4, 2, &[0]).unwrap();
/// assert_eq!(colours[8..], [255, 0, 0, 255]);
/// ```
pub fn copy_split_vertices(
    attribute: &mut [u8],
    stride: usize,
    element_size: usize,
    vertex_count: usize,
    sources: &[u32],
) -> Result<(), Error> {
    if element_size > stride {
        return Err(Error::InvalidStride { stride, element_size });
    }
    let total = vertex_count.checked_add(sources.len()).ok_or(Error::SizeOverflow)?;
    let span = crate::kernel::views::strided::span_bytes(total, stride, element_size)?;
    if span > attribute.len() {
        return Err(Error::BufferTooShort {
            len: attribute.len(),
            needed: span,
        });
    }
    if let Some(position) = sources.iter().position(|&s| s as usize >= vertex_count) {
        return Err(Error::SourceOutOfRange {
            position,
            source: sources[position],
            vertex_count,
        });
    }
    for (j, &source) in sources.iter().enumerate() {
        let from = source as usize * stride;
        let to = (vertex_count + j) * stride;
        attribute.copy_within(from..from + element_size, to);
    }
    Ok(())
}
