//! meshoptimizer's tangents into the caller's buffer, for the chart and benchmark examples.

use meshopt::TangentOptions;

/// `meshopt_generateTangents`, the C function `meshopt::generate_tangents` calls, with the mesh
/// indexed: one frame per index, written into `per_corner`. Calling it directly rather than
/// through the crate keeps the output buffer the caller's, allocated once before any timing, as it
/// is for the other per-corner generators; the crate allocates a new one on every call.
/// Checks only the slice lengths, so that timing it times meshoptimizer alone.
///
/// # Safety
/// Every index must be below `positions.len()`: meshoptimizer checks them only in debug builds.
pub unsafe fn meshopt_tangents(
    indices: &[u32],
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    texcoords: &[[f32; 2]],
    options: TangentOptions,
    per_corner: &mut [[f32; 4]],
) {
    let vertex_count = positions.len();
    assert!(normals.len() == vertex_count && texcoords.len() == vertex_count);
    assert!(indices.len() % 3 == 0 && per_corner.len() == indices.len());
    // SAFETY: packed arrays of vertex_count vertices and an output of one frame per index, as
    // meshoptimizer.h requires; the caller vouches for the indices.
    unsafe {
        meshopt::ffi::meshopt_generateTangents(
            per_corner.as_mut_ptr().cast(),
            indices.as_ptr(),
            indices.len(),
            positions.as_ptr().cast(),
            vertex_count,
            size_of::<[f32; 3]>(),
            normals.as_ptr().cast(),
            size_of::<[f32; 3]>(),
            texcoords.as_ptr().cast(),
            size_of::<[f32; 2]>(),
            options.bits(),
        );
    }
}
