//! Checks made before any output byte is touched.
#![forbid(unsafe_code)]

use crate::kernel::error::{Buffer, Error};
use crate::kernel::mesh::{Mesh, Output};
use crate::kernel::options::{DegeneratePolicy, Method, Options};
use crate::kernel::views::strided::{Footprint, StridedMut};

/// Checks the options, that every per-vertex buffer has `vertex_count` elements, the index count,
/// and that no output byte is an input byte, a byte of the other output, or a scratch byte.
/// Indices themselves are checked while the triangles are read, still before anything is written.
pub fn validate(mesh: &Mesh, options: &Options, output: &Output, scratch: Option<Footprint>) -> Result<(), Error> {
    let lens = [
        Some((Buffer::Tangents, output.tangents.len())),
        output.bitangents.as_ref().map(|b| (Buffer::Bitangents, b.len())),
    ];
    check_inputs(mesh, options, &lens, mesh.vertex_count())?;
    check_written(
        mesh,
        &[
            (Buffer::Tangents, Some(output.tangents.footprint())),
            (Buffer::Bitangents, output.bitangents.as_ref().map(|b| b.footprint())),
            (Buffer::Scratch, scratch),
        ],
    )
}

/// [`validate`] for a per-corner output: `tangents` has one element per corner.
pub fn validate_corners(
    mesh: &Mesh,
    options: &Options,
    tangents: &StridedMut<[f32; 4]>,
    scratch: Option<Footprint>,
) -> Result<(), Error> {
    check_inputs(
        mesh,
        options,
        &[Some((Buffer::Tangents, tangents.len()))],
        mesh.corner_count(),
    )?;
    check_written(
        mesh,
        &[
            (Buffer::Tangents, Some(tangents.footprint())),
            (Buffer::Scratch, scratch),
        ],
    )
}

/// Fails with [`Error::LengthMismatch`] unless `buffer` has `expected` elements.
pub fn check_len(buffer: Buffer, len: usize, expected: usize) -> Result<(), Error> {
    if len != expected {
        return Err(Error::LengthMismatch { buffer, len, expected });
    }
    Ok(())
}

/// The checks both outputs share, in this order: options, attribute counts, output counts
/// (`outputs`, each `(buffer, len)`, must hold `output_len` elements), texture coordinates where
/// the method or policy needs them, and an index count that makes whole triangles.
fn check_inputs(
    mesh: &Mesh,
    options: &Options,
    outputs: &[Option<(Buffer, usize)>],
    output_len: usize,
) -> Result<(), Error> {
    options.validate()?;
    let vertex_count = mesh.vertex_count();
    check_len(Buffer::Normals, mesh.normals.len(), vertex_count)?;
    if let Some(uvs) = mesh.texcoords {
        check_len(Buffer::Texcoords, uvs.len(), vertex_count)?;
    }
    for &(buffer, len) in outputs.iter().flatten() {
        check_len(buffer, len, output_len)?;
    }
    let needs_texcoords = options.degenerate_policy == DegeneratePolicy::Legacy || options.method == Method::Mikktspace;
    if mesh.texcoords.is_none() && needs_texcoords {
        return Err(Error::MissingTexcoords {
            method: options.method,
            policy: options.degenerate_policy,
        });
    }
    mesh.indices.triangle_count(vertex_count).map(|_| ())
}

/// Fails with [`Error::Overlap`] when a `written` buffer shares a byte with an input of `mesh` or
/// with another written buffer. Every call makes this check before it writes; callers that build
/// views over raw memory ([`Strided::from_raw`](crate::Strided::from_raw)) make it before they
/// form a `&mut` slice that may alias an input.
///
/// ```
/// use tbasis::{check_written, Buffer, Mesh};
/// let mesh = Mesh::new(&[[0.0f32; 3]; 3], &[[0.0, 0.0, 1.0f32]; 3]);
/// let elsewhere = vec![[0.0f32; 3]; 3];
/// let unrelated = tbasis::Strided::from_slice(&elsewhere).footprint();
/// assert!(check_written(&mesh, &[(Buffer::Tangents, Some(unrelated))]).is_ok());
/// let positions = mesh.positions.footprint();
/// assert!(check_written(&mesh, &[(Buffer::Tangents, Some(positions))]).is_err());
/// ```
pub fn check_written(mesh: &Mesh, written: &[(Buffer, Option<Footprint>)]) -> Result<(), Error> {
    let inputs = [
        (Buffer::Positions, Some(mesh.positions.footprint())),
        (Buffer::Normals, Some(mesh.normals.footprint())),
        (Buffer::Texcoords, mesh.texcoords.map(|uvs| uvs.footprint())),
        (Buffer::Indices, mesh.indices.footprint()),
    ];
    for (k, &(name, out)) in written.iter().enumerate() {
        let Some(out) = out else {
            continue;
        };
        let others = inputs.iter().chain(&written[k + 1..]);
        for &(other, footprint) in others {
            if footprint.is_some_and(|footprint| out.overlaps(&footprint)) {
                return Err(Error::Overlap { written: name, other });
            }
        }
    }
    Ok(())
}
