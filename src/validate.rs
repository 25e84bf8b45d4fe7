//! Checks made before any output byte is touched.
#![forbid(unsafe_code)]

use crate::mesh::{Mesh, Output};
use crate::options::{DegeneratePolicy, Method, Options};
use crate::status::Error;
use crate::strided::{Footprint, StridedMut};

/// Checks the options, that every per-vertex buffer has `vertex_count` elements, the index count,
/// and that no output byte is an input byte, a byte of the other output, or a scratch byte.
/// Indices themselves are checked while the triangles are read, still before anything is written.
pub fn validate(mesh: &Mesh, options: &Options, output: &Output, scratch: Option<Footprint>) -> Result<(), Error> {
    let outputs = [Some(output.tangents.len()), output.bitangents.as_ref().map(|b| b.len())];
    check_inputs(
        mesh,
        options,
        outputs.into_iter().flatten().all(|len| len == mesh.vertex_count()),
    )?;
    check_overlaps(mesh, output, scratch)
}

/// [`validate`] for a per-corner output: `tangents` has one element per corner.
pub fn validate_corners(
    mesh: &Mesh,
    options: &Options,
    tangents: &StridedMut<[f32; 4]>,
    scratch: Option<Footprint>,
) -> Result<(), Error> {
    check_inputs(mesh, options, tangents.len() == mesh.corner_count())?;
    check_written(mesh, &[Some(tangents.footprint()), scratch])
}

/// The checks both outputs share: options, attribute counts (and `outputs_fit`, the caller's
/// verdict on the output counts), texture coordinates where the method or policy needs them, and
/// an index count that makes whole triangles.
fn check_inputs(mesh: &Mesh, options: &Options, outputs_fit: bool) -> Result<(), Error> {
    options.validate()?;
    let vertex_count = mesh.vertex_count();
    let inputs = [Some(mesh.normals.len()), mesh.texcoords.map(|uvs| uvs.len())];
    if !outputs_fit || inputs.into_iter().flatten().any(|len| len != vertex_count) {
        return Err(Error::InvalidCount);
    }
    let needs_texcoords = options.degenerate_policy == DegeneratePolicy::Legacy || options.method == Method::Mikktspace;
    if mesh.texcoords.is_none() && needs_texcoords {
        return Err(Error::NullPointer);
    }
    mesh.indices.triangle_count(vertex_count).map(|_| ())
}

/// Fails with [`Error::Overlap`] when an output shares a byte with an input, the other output or
/// the scratch, or the scratch shares one with an input.
pub fn check_overlaps(mesh: &Mesh, output: &Output, scratch: Option<Footprint>) -> Result<(), Error> {
    let written = [
        Some(output.tangents.footprint()),
        output.bitangents.as_ref().map(|b| b.footprint()),
        scratch,
    ];
    check_written(mesh, &written)
}

/// Fails with [`Error::Overlap`] when a `written` buffer shares a byte with an input or with
/// another written buffer.
pub fn check_written(mesh: &Mesh, written: &[Option<Footprint>]) -> Result<(), Error> {
    let inputs = [
        Some(mesh.positions.footprint()),
        Some(mesh.normals.footprint()),
        mesh.texcoords.map(|uvs| uvs.footprint()),
        mesh.indices.footprint(),
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
