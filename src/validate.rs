//! Checks made before any output byte is touched.
#![forbid(unsafe_code)]

use crate::mesh::{Mesh, Output};
use crate::options::{DegeneratePolicy, Options};
use crate::status::Error;
use crate::strided::Footprint;

/// Checks the options, that every per-vertex buffer has `vertex_count` elements, the index count,
/// and that no output byte is an input byte, a byte of the other output, or a scratch byte.
/// Indices themselves are checked while the triangles are read, still before anything is written.
pub fn validate(mesh: &Mesh, options: &Options, output: &Output, scratch: Option<Footprint>) -> Result<(), Error> {
    options.validate()?;
    let vertex_count = mesh.vertex_count();
    let lengths = [
        Some(mesh.normals.len()),
        mesh.texcoords.map(|uvs| uvs.len()),
        Some(output.tangents.len()),
        output.bitangents.as_ref().map(|b| b.len()),
    ];
    if lengths.into_iter().flatten().any(|len| len != vertex_count) {
        return Err(Error::InvalidCount);
    }
    if mesh.texcoords.is_none() && options.degenerate_policy == DegeneratePolicy::Legacy {
        return Err(Error::NullPointer);
    }
    mesh.indices.triangle_count(vertex_count)?;
    check_overlaps(mesh, output, scratch)
}

/// Fails with [`Error::Overlap`] when an output shares a byte with an input, the other output or
/// the scratch, or the scratch shares one with an input.
pub fn check_overlaps(mesh: &Mesh, output: &Output, scratch: Option<Footprint>) -> Result<(), Error> {
    let inputs = [
        Some(mesh.positions.footprint()),
        Some(mesh.normals.footprint()),
        mesh.texcoords.map(|uvs| uvs.footprint()),
        mesh.indices.footprint(),
    ];
    let written = [
        Some(output.tangents.footprint()),
        output.bitangents.as_ref().map(|b| b.footprint()),
        scratch,
    ];
    for (k, out) in written.iter().enumerate() {
        let Some(out) = out else {
            continue;
        };
        let others = inputs.iter().chain(&written[k + 1..]).flatten();
        if others.into_iter().any(|other| out.overlaps(other)) {
            return Err(Error::Overlap);
        }
    }
    Ok(())
}
