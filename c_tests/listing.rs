//! Rust's view of the C port of the original listing (`listing.c`, `listing.h`), for the
//! programs that link it: the chart and benchmark examples (through crates/compare/build.rs) and the fuzz target
//! (through fuzz/build.rs). Include it with `#[path]`.

use core::ffi::c_long;

extern "C" {
    fn listing_tangents_u32(
        vertex_count: c_long,
        vertex: *const f32,
        normal: *const f32,
        texcoord: *const f32,
        triangle_count: c_long,
        triangle: *const u32,
        tangent: *mut f32,
    ) -> c_long;
}

/// `CalculateTangentArray` as the C port computes it, into `tangents`; returns the number of
/// triangles with a zero UV determinant. Checks only the slice lengths, so that timing it times
/// the port alone.
///
/// # Safety
/// Every index must be below `tangents.len()`, as the listing assumes.
pub unsafe fn listing_tangents(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    texcoords: &[[f32; 2]],
    indices: &[u32],
    tangents: &mut [[f32; 4]],
) -> usize {
    let vertex_count = tangents.len();
    assert!(positions.len() == vertex_count && normals.len() == vertex_count && texcoords.len() == vertex_count);
    assert!(indices.len() % 3 == 0);
    if vertex_count == 0 {
        return 0;
    }
    // SAFETY: packed arrays of vertex_count vertices and indices.len() / 3 triangles, and an output
    // of vertex_count tangents, as listing.h requires; the caller vouches for the indices.
    let status = unsafe {
        listing_tangents_u32(
            vertex_count as c_long,
            positions.as_ptr().cast(),
            normals.as_ptr().cast(),
            texcoords.as_ptr().cast(),
            (indices.len() / 3) as c_long,
            indices.as_ptr(),
            tangents.as_mut_ptr().cast(),
        )
    };
    usize::try_from(status).expect("listing.c could not allocate")
}
