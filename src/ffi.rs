//! The C ABI: descriptors in, statuses out, no panic across the boundary.
//!
//! Each function copies the caller's descriptor structs by value, turns pointers and strides into
//! bounds-carrying views (checking NULLs, strides and sizes), and calls the safe core inside
//! `guard` (`guard.rs`: it catches panics). The doc comments here are the manual cbindgen writes
//! into `include/tbasis.h`.

use core::ffi::{c_char, c_long, c_void};
use core::mem::size_of;
use core::ptr;

use tbasis::{
    check_written, copy_split_vertices, from_tangent_space, generate, generate_corners, generate_corners_with_scratch,
    generate_with_scratch, scratch_size_for, scratch_size_for_counts, span_bytes, split_corners, to_tangent_space,
    Buffer, Element, Error, Footprint, Indices, Mesh, Options, Output, Report, Strided, StridedMut,
};

use crate::codes::*;
use crate::guard::guard;
use crate::status::*;

/// The triangle mesh, read in place. Each attribute pointer addresses vertex 0; vertex `i` starts
/// `i * stride` bytes after it. Pointers need no alignment; strides are in bytes.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct tbasis_mesh {
    /// Number of vertices.
    pub vertex_count: usize,
    /// float x, y, z in the first 12 bytes of each vertex; `(vertex_count - 1) * positions_stride + 12` bytes.
    pub positions: *const c_void,
    /// Bytes from one position to the next; at least 12.
    pub positions_stride: usize,
    /// float x, y, z in the first 12 bytes of each vertex, expected unit length.
    pub normals: *const c_void,
    /// Bytes from one normal to the next; at least 12.
    pub normals_stride: usize,
    /// float u, v in the first 8 bytes of each vertex; NULL: every vertex gets the fallback frame
    /// (not allowed with policy LEGACY or method MIKKTSPACE: `TBASIS_ERROR_NULL_POINTER`).
    pub texcoords: *const c_void,
    /// Bytes from one texture coordinate to the next; at least 8.
    pub texcoords_stride: usize,
    /// `index_count` packed indices of `index_type`; NULL: unindexed, triangle `i` is vertices
    /// `3i, 3i+1, 3i+2`.
    pub indices: *const c_void,
    /// Number of indices, a multiple of 3; must be 0 when `indices` is NULL.
    pub index_count: usize,
    /// `TBASIS_INDEX_U16` or `TBASIS_INDEX_U32` (ignored when `indices` is NULL).
    pub index_type: u32,
}

/// How to compute. All-zero (or a NULL pointer) means the defaults.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct tbasis_options {
    /// A `TBASIS_METHOD_*` value; 0: the recommended default (`TBASIS_METHOD_ANGLE`; with policy
    /// `TBASIS_DEGENERATE_LEGACY`, the listing's method, `TBASIS_METHOD_LENGYEL`).
    pub method: u32,
    /// A `TBASIS_DEGENERATE_*` value; 0: the method's default (`TBASIS_DEGENERATE_LEGACY` for
    /// `TBASIS_METHOD_MIKKTSPACE`, `TBASIS_DEGENERATE_INHERIT` for the others).
    pub degenerate_policy: u32,
    /// `TBASIS_FLAG_*` bits; unknown bits are an error.
    pub flags: u32,
    /// Upper bound on threads; 0 or 1: the calling thread only. Every method uses one worker per
    /// 16384 triangles at most; results are bit-identical whatever the value.
    pub threads: u32,
    /// UV and position shape quality (1 = equilateral, 0 = collapsed) below which a triangle is
    /// degenerate; 0: the default, 1e-5. Not used by policy LEGACY.
    pub degenerate_threshold: f32,
    /// Optional caller memory of `scratch_size` bytes, any alignment, not shared with any other
    /// buffer; with `threads` 0 or 1 the call then allocates nothing (MIKKTSPACE: but for two rare
    /// cases, README "Memory"). Working memory: its contents after a call, successful or not, mean
    /// nothing. NULL: the library allocates.
    pub scratch: *mut c_void,
    /// Size of `scratch` in bytes; at least `tbasis_scratch_size(mesh, options)`.
    pub scratch_size: usize,
}

/// Where results go. Each pointer addresses vertex 0; vertex `i` starts `i * stride` bytes after.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct tbasis_output {
    /// float x, y, z, w written into the first 16 bytes of each vertex: unit tangent and
    /// handedness w = +1 or -1; `(vertex_count - 1) * tangents_stride + 16` bytes. Required
    /// (NULL only with no vertex).
    pub tangents: *mut c_void,
    /// Bytes from one tangent to the next; at least 16.
    pub tangents_stride: usize,
    /// float x, y, z written into the first 12 bytes of each vertex: `w * cross(n, t)`.
    /// NULL: not written.
    pub bitangents: *mut c_void,
    /// Bytes from one bitangent to the next; at least 12.
    pub bitangents_stride: usize,
}

/// The value of a report's triangle index (`first_degenerate_triangle`, `failed_triangle`) when
/// there is no such triangle: `SIZE_MAX`, which no triangle index can be. The header's
/// `#define` of it is written by `build.rs`.
pub const TBASIS_NO_TRIANGLE: usize = usize::MAX;

/// What the call found; filled on `TBASIS_OK`, `TBASIS_ERROR_DEGENERATE_UV` and
/// `TBASIS_ERROR_INDEX_OUT_OF_RANGE` (then only `failed_triangle` is set, the counts are 0), left
/// as it was on every other status.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct tbasis_report {
    /// Triangles whose UV determinant is zero (method LENGYEL with policy LEGACY, the listing) or
    /// whose UV or position quality is below the threshold (other policies), or that read a
    /// non-finite input. Method MIKKTSPACE counts the triangles mikktspace.c cannot use: two corners
    /// at one position, or no texture derivatives (a UV area, |dP/ds| or |dP/dt| that is NaN or not
    /// above the smallest normal float in magnitude); with REJECT, whose test decides instead, a
    /// successful call has none.
    pub degenerate_triangles: usize,
    /// Index of the first such triangle; `TBASIS_NO_TRIANGLE` when there is none.
    pub first_degenerate_triangle: usize,
    /// Vertices given the fallback frame built from their normal alone: never with LEGACY, but
    /// with method MIKKTSPACE (whose default policy is LEGACY) the vertices no triangle uses, in
    /// `tbasis_generate`'s report only (`tbasis_generate_corners` writes no vertex).
    pub fallback_vertices: usize,
    /// Vertices used by non-degenerate triangles of both UV orientations (mirror folds).
    pub mirrored_vertices: usize,
    /// Vertices no triangle uses.
    pub unreferenced_vertices: usize,
    /// Vertices that took their tangent from neighbours (policy INHERIT).
    pub inherited_vertices: usize,
    /// Vertices whose normal is zero, not finite, or off unit length by more than 1e-3 (normalized,
    /// or ignored when it has no direction). Not counted by policy LEGACY.
    pub abnormal_normals: usize,
    /// Corners where method MIKKTSPACE with policy SKIP or INHERIT replaced what mikktspace.c
    /// gives (a non-finite, zero or non-unit tangent, or one not perpendicular to the normal).
    pub repaired_corners: usize,
    /// Method MIKKTSPACE: vertices whose corners do not all get the same bits (the vertices a seam
    /// split must duplicate to draw them exactly). `tbasis_generate` gives each its first corner's.
    pub split_vertices: usize,
    /// The triangle a refusal names: with `TBASIS_ERROR_INDEX_OUT_OF_RANGE` the first triangle
    /// with an index `>= vertex_count` (its indices are `3 * failed_triangle` to
    /// `3 * failed_triangle + 2`), with `TBASIS_ERROR_DEGENERATE_UV` the first degenerate triangle;
    /// `TBASIS_NO_TRIANGLE` on `TBASIS_OK`.
    pub failed_triangle: usize,
}

impl From<Report> for tbasis_report {
    fn from(r: Report) -> Self {
        tbasis_report {
            degenerate_triangles: r.degenerate_triangles,
            first_degenerate_triangle: r.first_degenerate_triangle.unwrap_or(TBASIS_NO_TRIANGLE),
            fallback_vertices: r.fallback_vertices,
            mirrored_vertices: r.mirrored_vertices,
            unreferenced_vertices: r.unreferenced_vertices,
            inherited_vertices: r.inherited_vertices,
            abnormal_normals: r.abnormal_normals,
            repaired_corners: r.repaired_corners,
            split_vertices: r.split_vertices,
            failed_triangle: TBASIS_NO_TRIANGLE,
        }
    }
}

/// Runs `body`, turning a panic (a library bug) into `TBASIS_ERROR_INTERNAL`.
fn boundary_value<T>(body: impl FnOnce() -> Result<T, Failure>) -> Result<T, Failure> {
    guard(Err(Failure::Status(TBASIS_ERROR_INTERNAL)), body)
}

/// Runs `body` and returns its status, a panic (a library bug) becoming `TBASIS_ERROR_INTERNAL`.
fn boundary(body: impl FnOnce() -> Result<(), Failure>) -> tbasis_status {
    match boundary_value(body) {
        Ok(()) => TBASIS_OK,
        Err(failure) => failure.status(),
    }
}

/// Checks a C buffer: its stride covers its element, it is not NULL when it has elements, and its
/// span `(count - 1) * stride + size` fits below the end of the address space.
fn check_buffer(base: *const c_void, stride: usize, count: usize, size: usize) -> Result<(), Failure> {
    let span = span_bytes(count, stride, size)?;
    if count > 0 && base.is_null() {
        return Err(Failure::NULL_POINTER);
    }
    (base as usize)
        .checked_add(span)
        .map(|_| ())
        .ok_or(Failure::Library(Error::SizeOverflow))
}

/// A read view over caller memory, once [`check_buffer`] passes.
///
/// # Safety
/// The caller of the C function promised `base` is readable for the span the header documents.
unsafe fn read_view<'a, T: Element>(
    base: *const c_void,
    stride: usize,
    count: usize,
) -> Result<Strided<'a, T>, Failure> {
    check_buffer(base, stride, count, size_of::<T>())?;
    Ok(Strided::from_raw(base.cast(), stride, count))
}

/// A write view over caller memory, once [`check_buffer`] passes.
///
/// # Safety
/// The caller of the C function promised `base` is writable for the span the header documents.
unsafe fn write_view<'a, T: Element>(
    base: *mut c_void,
    stride: usize,
    count: usize,
) -> Result<StridedMut<'a, T>, Failure> {
    check_buffer(base, stride, count, size_of::<T>())?;
    Ok(StridedMut::from_raw(base.cast(), stride, count))
}

/// Builds the safe views of a C mesh description.
unsafe fn mesh_views<'a>(m: &tbasis_mesh) -> Result<Mesh<'a>, Failure> {
    let count = m.vertex_count;
    let texcoords = if m.texcoords.is_null() {
        None
    } else {
        Some(read_view(m.texcoords, m.texcoords_stride, count)?)
    };
    let indices = if m.indices.is_null() {
        Indices::None
    } else {
        match m.index_type {
            TBASIS_INDEX_U16 => Indices::U16(read_view(m.indices, size_of::<u16>(), m.index_count)?),
            TBASIS_INDEX_U32 => Indices::U32(read_view(m.indices, size_of::<u32>(), m.index_count)?),
            _ => return Err(Failure::Status(TBASIS_ERROR_INVALID_INDEX_TYPE)),
        }
    };
    if m.indices.is_null() && m.index_count != 0 {
        return Err(Failure::NULL_POINTER);
    }
    Ok(Mesh {
        positions: read_view(m.positions, m.positions_stride, count)?,
        normals: read_view(m.normals, m.normals_stride, count)?,
        texcoords,
        indices,
    })
}

/// Builds the safe views of a C output description.
unsafe fn output_views<'a>(o: &tbasis_output, count: usize) -> Result<Output<'a>, Failure> {
    let bitangents = if o.bitangents.is_null() {
        None
    } else {
        Some(write_view(o.bitangents, o.bitangents_stride, count)?)
    };
    Ok(Output {
        tangents: write_view(o.tangents, o.tangents_stride, count)?,
        bitangents,
    })
}

/// The options a C call asks for, defaults for NULL.
fn options_of(options: Option<tbasis_options>) -> Result<Options, Failure> {
    let Some(o) = options else {
        return Ok(Options::default());
    };
    let method = method_of(o.method, o.degenerate_policy).ok_or(Failure::Status(TBASIS_ERROR_UNKNOWN_METHOD))?;
    let policy = policy_of(o.degenerate_policy, method).ok_or(Failure::Status(TBASIS_ERROR_UNKNOWN_POLICY))?;
    if o.flags & !TBASIS_FLAG_FLIP_V != 0 {
        return Err(Failure::Status(TBASIS_ERROR_UNKNOWN_FLAGS));
    }
    let threshold = if o.degenerate_threshold == 0.0 {
        tbasis::DEFAULT_DEGENERATE_THRESHOLD
    } else {
        o.degenerate_threshold
    };
    let options = Options::default()
        .with_method(method)
        .with_policy(policy)
        .with_flip_v(o.flags & TBASIS_FLAG_FLIP_V != 0)
        .with_degenerate_threshold(threshold)
        .with_threads(o.threads);
    options.validate()?;
    Ok(options)
}

/// Computes a unit tangent and handedness for every vertex.
///
/// Per triangle, solves `Q1 = s1*T + t1*B`, `Q2 = s2*T + t2*B` for the texture-aligned tangent `T`
/// and bitangent `B` (`Q` are position edges, `s, t` UV edges); per vertex, sums them, removes the
/// normal (`T' = T - (N.T)N`), normalizes, and stores the handedness `w = +1 or -1` so that
/// `bitangent = w * cross(normal, tangent.xyz)`.
///
/// - `mesh`: required; buffers of `vertex_count` vertices (see `tbasis_mesh`).
/// - `options`: NULL or all-zero for the defaults.
/// - `output->tangents`: `(vertex_count - 1) * tangents_stride + 16` bytes, written only on
///   `TBASIS_OK`; it may sit inside the same interleaved vertex array as the inputs, as long as
///   no byte is shared.
/// - `report`: NULL, or filled on `TBASIS_OK`, `TBASIS_ERROR_DEGENERATE_UV` and
///   `TBASIS_ERROR_INDEX_OUT_OF_RANGE` (see `tbasis_report`).
///
/// With method LENGYEL and policy LEGACY the results are bit-identical to the original listing.
/// With the other policies every tangent is finite, unit length, orthogonal to its (normalized)
/// normal, and `w` is exactly +1 or -1.
///
/// Returns `TBASIS_OK`; `TBASIS_ERROR_NULL_POINTER`, `_INVALID_STRIDE`, `_INVALID_INDEX_COUNT`,
/// `_INDEX_OUT_OF_RANGE`, `_INVALID_INDEX_TYPE`, `_UNKNOWN_METHOD`, `_UNKNOWN_POLICY`,
/// `_NO_LEGACY_FORM`, `_UNKNOWN_FLAGS`, `_SIZE_OVERFLOW`, `_OVERLAP`, `_DEGENERATE_UV`,
/// `_OUT_OF_MEMORY`, `_SCRATCH_TOO_SMALL`, `_INVALID_THRESHOLD` or `_INTERNAL`. On any error but
/// `_INTERNAL` no output byte has been written (after `_INTERNAL`, a library bug, the outputs may
/// be partly written: see `TBASIS_ERROR_INTERNAL`).
///
/// # Safety
/// Every non-NULL pointer must be valid for the bytes documented above for the whole call.
#[no_mangle]
pub unsafe extern "C" fn tbasis_generate(
    mesh: *const tbasis_mesh,
    options: *const tbasis_options,
    output: *const tbasis_output,
    report: *mut tbasis_report,
) -> tbasis_status {
    boundary(|| {
        if mesh.is_null() || output.is_null() {
            return Err(Failure::NULL_POINTER);
        }
        let (views, options_desc, opts) = call_inputs(mesh, options)?;
        let mut out = output_views(&ptr::read_unaligned(output), views.vertex_count())?;

        let needed = scratch_size_for(&views, &opts).ok_or(Error::SizeOverflow)?;
        let outputs = [
            (Buffer::Tangents, Some(out.tangents.footprint())),
            (Buffer::Bitangents, out.bitangents.as_ref().map(|b| b.footprint())),
        ];
        let scratch = caller_scratch(options_desc, needed, &views, outputs)?;
        with_report(report, || match scratch {
            Some(bytes) => generate_with_scratch(&views, &opts, &mut out, bytes),
            None => generate(&views, &opts, &mut out),
        })
    })
}

/// The mesh views and the options of a call (the options' C description too, for its scratch).
///
/// # Safety
/// `mesh` (not NULL) and a non-NULL `options` must point to readable descriptors, and the mesh's
/// buffers must be valid as the header documents.
unsafe fn call_inputs<'a>(
    mesh: *const tbasis_mesh,
    options: *const tbasis_options,
) -> Result<(Mesh<'a>, Option<tbasis_options>, Options), Failure> {
    let options_desc = (!options.is_null()).then(|| ptr::read_unaligned(options));
    let opts = options_of(options_desc)?;
    Ok((mesh_views(&ptr::read_unaligned(mesh))?, options_desc, opts))
}

/// Runs `call` and writes what it found to `report` (when not NULL) on success, and on
/// `TBASIS_ERROR_DEGENERATE_UV` and `TBASIS_ERROR_INDEX_OUT_OF_RANGE` with the triangle at fault.
///
/// # Safety
/// `report` must be NULL or writable.
unsafe fn with_report(report: *mut tbasis_report, call: impl FnOnce() -> Result<Report, Error>) -> Result<(), Failure> {
    let (found, result) = match call() {
        Ok(found) => (tbasis_report::from(found), Ok(())),
        Err(Error::DegenerateUv { triangle, report }) => {
            let failed = tbasis_report {
                failed_triangle: triangle,
                ..tbasis_report::from(report)
            };
            (failed, Err(Failure::Status(TBASIS_ERROR_DEGENERATE_UV)))
        }
        Err(error @ Error::IndexOutOfRange { triangle, .. }) => {
            let failed = tbasis_report {
                failed_triangle: triangle,
                ..tbasis_report::from(Report::default())
            };
            (failed, Err(error.into()))
        }
        Err(error) => return Err(error.into()),
    };
    if !report.is_null() {
        ptr::write_unaligned(report, found);
    }
    result
}

/// The caller's scratch bytes from `options`, once they are large enough (`needed`), span valid
/// addresses and share no byte with the mesh or the `outputs` (tangents, bitangents); `None` when the caller
/// brings none.
///
/// # Safety
/// A non-NULL `options.scratch` must be writable for `options.scratch_size` bytes for the call.
unsafe fn caller_scratch<'a>(
    options: Option<tbasis_options>,
    needed: usize,
    mesh: &Mesh,
    outputs: [(Buffer, Option<Footprint>); 2],
) -> Result<Option<&'a mut [u8]>, Failure> {
    let Some(o) = options.filter(|o| !o.scratch.is_null()) else {
        return Ok(None);
    };
    if o.scratch_size < needed {
        return Err(Error::ScratchTooSmall {
            needed,
            len: o.scratch_size,
        }
        .into());
    }
    check_buffer(o.scratch, 1, o.scratch_size, 1)?;
    let scratch = Footprint::contiguous(o.scratch as usize, o.scratch_size);
    let [tangents, bitangents] = outputs;
    check_written(mesh, &[tangents, bitangents, (Buffer::Scratch, Some(scratch))])?;
    // The slice is formed only once it is known to share no byte with any other buffer.
    Ok(Some(core::slice::from_raw_parts_mut(
        o.scratch.cast::<u8>(),
        o.scratch_size,
    )))
}

/// Computes a unit tangent and handedness for every triangle corner: `tangents` receives
/// `float x, y, z, w` for corner `k` of triangle `t` at element `3t + k`, that is one element per
/// index (`index_count` elements), or per vertex when `mesh->indices` is NULL (`vertex_count`).
///
/// With `TBASIS_METHOD_MIKKTSPACE` each corner gets exactly mikktspace.c's frame for it. The
/// per-vertex methods give each corner exactly the bits `tbasis_generate` writes for its vertex,
/// except at a mirror fold (a vertex used by non-degenerate triangles of both UV orientations):
/// there a corner of a non-degenerate triangle on the side the vertex's frame does not come from
/// gets that side's own frame and `w` (README, "Degenerate-UV policies").
///
/// Needs the same scratch as `tbasis_generate` (`tbasis_scratch_size`), allocates nothing more
/// per corner, and gives the same `report` (but for `fallback_vertices` with method MIKKTSPACE:
/// see `tbasis_report`); `threads` changes no bit.
///
/// - `mesh`, `options`, `report`: as for `tbasis_generate` (`options` and `report` may be NULL).
/// - `tangents`: `(corner_count - 1) * tangents_stride + 16` bytes, written only on `TBASIS_OK`;
///   it must share no byte with an input or the scratch.
/// - `tangents_stride`: bytes from one corner's tangent to the next; at least 16.
///
/// Returns the statuses of `tbasis_generate`; on any error but `_INTERNAL` no output byte has
/// been written.
///
/// # Safety
/// Every non-NULL pointer must be valid for the bytes documented above for the whole call.
#[no_mangle]
pub unsafe extern "C" fn tbasis_generate_corners(
    mesh: *const tbasis_mesh,
    options: *const tbasis_options,
    tangents: *mut c_void,
    tangents_stride: usize,
    report: *mut tbasis_report,
) -> tbasis_status {
    boundary(|| {
        if mesh.is_null() {
            return Err(Failure::NULL_POINTER);
        }
        let (views, options_desc, opts) = call_inputs(mesh, options)?;
        let mut out = write_view(tangents, tangents_stride, views.corner_count())?;
        let needed = scratch_size_for(&views, &opts).ok_or(Error::SizeOverflow)?;
        let outputs = [(Buffer::Tangents, Some(out.footprint())), (Buffer::Bitangents, None)];
        let scratch = caller_scratch(options_desc, needed, &views, outputs)?;
        with_report(report, || match scratch {
            Some(bytes) => generate_corners_with_scratch(&views, &opts, &mut out, bytes),
            None => generate_corners(&views, &opts, &mut out),
        })
    })
}

/// Splits the vertices whose corners carry different tangents, so that per-corner tangents (from
/// `tbasis_generate_corners`) can be drawn as an indexed mesh: two corners of a vertex share an
/// output vertex exactly when their tangents have the same bits, all four floats. Every vertex
/// keeps its index for the corners that carry its first tangent in index order; each further
/// distinct tangent of a vertex becomes a new vertex `vertex_count + j`, in the order of first
/// appearance, which copies vertex `sources[j]` (`tbasis_copy_split_vertices` copies any
/// attribute). Takes time linear in the corner count.
///
/// With `C` corners (`index_count`, or `vertex_count` when `mesh->indices` is NULL):
///
/// - `mesh`: as for `tbasis_generate` (only its vertex count and indices are read here, but all
///   its buffers are checked);
/// - `corner_tangents`: `(C - 1) * corner_tangents_stride + 16` bytes, float x, y, z, w per corner;
/// - `corner_tangents_stride`: at least 16;
/// - `new_indices`: room for `C` `uint32_t`, always 32-bit (a new index buffer when the mesh is
///   unindexed): corner `i` is drawn with vertex `new_indices[i]`;
/// - `sources`: room for `C` `uint32_t` (a mesh never appends more vertices than it has corners);
///   the first `*appended_count` are written;
/// - `appended_count`: receives the number of vertices appended; the mesh then has
///   `vertex_count + *appended_count` vertices.
///
/// The outputs must share no byte with each other, the mesh's buffers or `corner_tangents`.
///
/// Returns `TBASIS_OK`; `TBASIS_ERROR_NULL_POINTER`, `_INVALID_STRIDE`, `_INVALID_INDEX_COUNT`,
/// `_INDEX_OUT_OF_RANGE`, `_INVALID_INDEX_TYPE`, `_SIZE_OVERFLOW`, `_OVERLAP`, `_OUT_OF_MEMORY`,
/// `_TOO_MANY_VERTICES` (`vertex_count + *appended_count` would exceed 2^32, so the new indices
/// would not fit 32 bits) or `_INTERNAL`. On any error but `_INTERNAL` no output byte has been
/// written.
///
/// # Safety
/// Every non-NULL pointer must be valid for the bytes documented above for the whole call.
#[no_mangle]
pub unsafe extern "C" fn tbasis_split_corners(
    mesh: *const tbasis_mesh,
    corner_tangents: *const c_void,
    corner_tangents_stride: usize,
    new_indices: *mut u32,
    sources: *mut u32,
    appended_count: *mut usize,
) -> tbasis_status {
    boundary(|| {
        if mesh.is_null() || appended_count.is_null() {
            return Err(Failure::NULL_POINTER);
        }
        let views = mesh_views(&ptr::read_unaligned(mesh))?;
        let corners = views.corner_count();
        let tangents = read_view::<[f32; 4]>(corner_tangents, corner_tangents_stride, corners)?;
        let mut indices_out = write_view::<u32>(new_indices.cast(), size_of::<u32>(), corners)?;
        let mut sources_out = write_view::<u32>(sources.cast(), size_of::<u32>(), corners)?;
        check_buffer(appended_count.cast(), 1, size_of::<usize>(), 1)?;
        let count_out = Footprint::contiguous(appended_count as usize, size_of::<usize>());
        let written = [
            (Buffer::Indices, Some(indices_out.footprint())),
            (Buffer::Attribute, Some(sources_out.footprint())),
            (Buffer::Attribute, Some(count_out)),
        ];
        check_written(&views, &written)?;
        if let Some(&(buffer, _)) = written
            .iter()
            .find(|w| w.1.is_some_and(|w| w.overlaps(&tangents.footprint())))
        {
            return Err(Error::Overlap {
                written: buffer,
                other: Buffer::CornerTangents,
            }
            .into());
        }

        let split = split_corners(&views, &tangents)?;
        for (k, &index) in split.indices.iter().enumerate() {
            indices_out.set(k, index);
        }
        for (j, &source) in split.sources.iter().enumerate() {
            sources_out.set(j, source);
        }
        ptr::write_unaligned(appended_count, split.sources.len());
        Ok(())
    })
}

/// Fills the vertices `tbasis_split_corners` appended in one attribute buffer: element
/// `vertex_count + j` becomes a copy of element `sources[j]`, for `j < appended_count`. Call it once
/// per attribute (positions, normals, UVs, colours, joints, weights, morph targets...).
///
/// - `attribute`: `(vertex_count + appended_count - 1) * stride + element_size` bytes, elements of
///   `element_size` bytes `stride` bytes apart: room for the appended vertices after the others;
/// - `stride`: at least `element_size`;
/// - `sources`, `appended_count`: as `tbasis_split_corners` returned them; every source below
///   `vertex_count` (checked even when `element_size` is 0, when nothing is copied and
///   `attribute` may be NULL), and `sources` outside the address range of `attribute`. With
///   `appended_count` 0 nothing is copied and `attribute` and `sources` may be NULL (the stride
///   is still checked).
///
/// Returns `TBASIS_OK`; `TBASIS_ERROR_NULL_POINTER`, `_INVALID_STRIDE`, `_INDEX_OUT_OF_RANGE`,
/// `_SIZE_OVERFLOW`, `_OVERLAP`, `_OUT_OF_MEMORY` or `_INTERNAL`. On any error but `_INTERNAL`
/// no byte has been written.
///
/// # Safety
/// `attribute` must be writable and `sources` readable for the bytes documented above.
#[no_mangle]
pub unsafe extern "C" fn tbasis_copy_split_vertices(
    attribute: *mut c_void,
    stride: usize,
    element_size: usize,
    vertex_count: usize,
    sources: *const u32,
    appended_count: usize,
) -> tbasis_status {
    boundary(|| {
        if element_size > stride {
            return Err(Error::InvalidStride { stride, element_size }.into());
        }
        let total = vertex_count.checked_add(appended_count).ok_or(Error::SizeOverflow)?;
        let source_view = read_view::<u32>(sources.cast(), size_of::<u32>(), appended_count)?;
        if appended_count == 0 {
            return Ok(());
        }
        if element_size == 0 {
            // Nothing to copy (`attribute` may be NULL), but the sources are checked all the same.
            return match (0..appended_count).find(|&j| source_view.get(j) as usize >= vertex_count) {
                Some(position) => Err(Error::SourceOutOfRange {
                    position,
                    source: source_view.get(position),
                    vertex_count,
                }
                .into()),
                None => Ok(()),
            };
        }
        check_buffer(attribute, stride, total, element_size)?;
        let span = span_bytes(total, stride, element_size)?;
        let whole_range = Footprint::contiguous(attribute as usize, span);
        if whole_range.overlaps(&source_view.footprint()) {
            return Err(Error::Overlap {
                written: Buffer::Attribute,
                other: Buffer::Attribute,
            }
            .into());
        }
        // `sources` may be unaligned: read through its view into an aligned copy.
        let mut aligned = Vec::new();
        aligned
            .try_reserve_exact(appended_count)
            .map_err(|_| Error::OutOfMemory)?;
        aligned.extend((0..appended_count).map(|j| source_view.get(j)));
        // The slice is formed only once it is known to share no byte with `sources`.
        let bytes = core::slice::from_raw_parts_mut(attribute.cast::<u8>(), span);
        Ok(copy_split_vertices(
            bytes,
            stride,
            element_size,
            vertex_count,
            &aligned,
        )?)
    })
}

/// Drop-in for the original listing's `CalculateTangentArray`, with its packed layouts: `vertex`
/// and `normal` hold 3 floats per vertex, `texcoord` 2, `triangle` 3 `uint16_t` per triangle,
/// `tangent` receives 4 floats per vertex (`vertex_count * 16` bytes). Same results, bit for bit
/// (method LENGYEL, policy LEGACY), but checked: bad input returns a status and writes nothing.
///
/// Returns `TBASIS_OK`; `TBASIS_ERROR_INVALID_COUNT` (a negative count),
/// `TBASIS_ERROR_NULL_POINTER`, `TBASIS_ERROR_INDEX_OUT_OF_RANGE`, `TBASIS_ERROR_SIZE_OVERFLOW`,
/// `TBASIS_ERROR_OVERLAP`, `TBASIS_ERROR_OUT_OF_MEMORY` or `TBASIS_ERROR_INTERNAL` (after which
/// the outputs may be partly written).
///
/// # Safety
/// The pointers must be valid for the sizes above.
#[no_mangle]
pub unsafe extern "C" fn tbasis_calculate_tangent_array(
    vertex_count: c_long,
    vertex: *const f32,
    normal: *const f32,
    texcoord: *const f32,
    triangle_count: c_long,
    triangle: *const u16,
    tangent: *mut f32,
) -> tbasis_status {
    boundary(|| {
        let negative = |_| Failure::Status(TBASIS_ERROR_INVALID_COUNT);
        let vertex_count = usize::try_from(vertex_count).map_err(negative)?;
        let triangle_count = usize::try_from(triangle_count).map_err(negative)?;
        let index_count = triangle_count.checked_mul(3).ok_or(Error::SizeOverflow)?;
        let mesh = Mesh {
            positions: read_view(vertex.cast(), 12, vertex_count)?,
            normals: read_view(normal.cast(), 12, vertex_count)?,
            texcoords: Some(read_view(texcoord.cast(), 8, vertex_count)?),
            indices: Indices::U16(read_view(triangle.cast(), 2, index_count)?),
        };
        let mut output = Output {
            tangents: write_view(tangent.cast(), 16, vertex_count)?,
            bitangents: None,
        };
        generate(&mesh, &Options::legacy(), &mut output)?;
        Ok(())
    })
}

/// Bytes of `options->scratch` a `tbasis_generate` or `tbasis_generate_corners` call on `mesh`
/// with `options` needs, 0 when the mesh is empty. With `V = vertex_count` and `C` corners
/// (`index_count`, or `vertex_count` when unindexed):
///
/// - per-vertex methods, policies LEGACY, SKIP and REJECT: `29*V + 3` for both calls, whatever
///   `C` (28 bytes of tangent sums and a flag byte per vertex, 3 for alignment; per corner
///   nothing: the corner call keeps each vertex's frames in its sums);
/// - per-vertex methods, policy INHERIT (the default): `37*V + 4*C + 3`, the same plus the
///   adjacency that spreads tangents to the vertices that have none, in time linear in `C`: per
///   vertex a list start and a queue slot, per corner its triangle, 4 bytes each (8 each, so
///   `45*V + 8*C + 3`, when `V` or `C` exceeds `UINT32_MAX`);
/// - `TBASIS_METHOD_MIKKTSPACE`, with `T = C / 3` triangles:
///   `97*C + 65*T + 12*V + 4*max(2*V + 2, C) + 16454` (about 125 bytes per corner, of which
///   `40*C + 8*V + 16415` for the replay of mikktspace.c's weld, reused by the later phases), 0
///   when `V` is 0; with policy REJECT at least `29*V + 3`, in which the degenerate test runs
///   first.
///
/// Returns `SIZE_MAX` when `mesh` is NULL, the options are invalid or the size overflows, and
/// for method MIKKTSPACE past 2^30 - 1 vertices or corners (`TBASIS_ERROR_SIZE_OVERFLOW`).
/// `options` may be NULL (the defaults).
///
/// # Safety
/// `mesh` must be NULL or point to a readable `tbasis_mesh`.
#[no_mangle]
pub unsafe extern "C" fn tbasis_scratch_size(mesh: *const tbasis_mesh, options: *const tbasis_options) -> usize {
    let size = boundary_value(|| {
        if mesh.is_null() {
            return Err(Failure::NULL_POINTER);
        }
        let options = options_of((!options.is_null()).then(|| ptr::read_unaligned(options)))?;
        let mesh = ptr::read_unaligned(mesh);
        let corner_count = if mesh.indices.is_null() {
            mesh.vertex_count
        } else {
            mesh.index_count
        };
        scratch_size_for_counts(&options, mesh.vertex_count, corner_count).ok_or(Failure::Library(Error::SizeOverflow))
    });
    size.unwrap_or(usize::MAX)
}

/// A static, NUL-terminated English description of `status`; unknown values get one too.
/// The pointer stays valid for the life of the program; do not free it.
#[no_mangle]
pub extern "C" fn tbasis_status_string(status: tbasis_status) -> *const c_char {
    let text = message_nul(status).unwrap_or("unknown status\0");
    text.as_ptr().cast()
}

/// The library's version, `TBASIS_VERSION_MAJOR * 1000000 + TBASIS_VERSION_MINOR * 1000 +
/// TBASIS_VERSION_PATCH`, equal to the header's `TBASIS_VERSION` when header and library match.
#[no_mangle]
pub extern "C" fn tbasis_version() -> u32 {
    tbasis::VERSION
}

/// `to_tangent_space` or `from_tangent_space`: normal, tangent, direction in; result out.
type Transform = fn([f32; 3], [f32; 4], [f32; 3]) -> Result<[f32; 3], Error>;

/// Reads the three arrays of a transform call, checking for NULL first (`result` too), calls
/// `transform` and writes `result` only when it succeeds.
unsafe fn transform_vertex(
    normal: *const f32,
    tangent: *const f32,
    direction: *const f32,
    result: *mut f32,
    transform: Transform,
) -> tbasis_status {
    boundary(|| {
        if normal.is_null() || tangent.is_null() || direction.is_null() || result.is_null() {
            return Err(Failure::NULL_POINTER);
        }
        // Every input is copied before `result` is written, so `result` may alias any of them.
        let value = transform(
            ptr::read_unaligned(normal.cast::<[f32; 3]>()),
            ptr::read_unaligned(tangent.cast::<[f32; 4]>()),
            ptr::read_unaligned(direction.cast::<[f32; 3]>()),
        )?;
        ptr::write_unaligned(result.cast::<[f32; 3]>(), value);
        Ok(())
    })
}

/// Moves an object-space `direction` into the tangent space of one vertex:
/// `result = inverse(M) * direction`, where `M = [T B N]` has the columns `T = tangent.xyz`,
/// `B = tangent.w * cross(normal, T)` (the bitangent `tbasis_generate` implies) and
/// `N = normal`. `result[0]` is the coordinate along `T`, `result[1]` along `B`, `result[2]` along
/// the normal, as normal maps store them. For CPU-side baking and tools.
///
/// `inverse(M)` is the exact inverse, not the transpose, so the frame need not be orthonormal (a
/// normal that is not unit length or not orthogonal to `T` is fine): `tbasis_from_tangent_space`
/// maps `result` back to `direction` up to rounding. For an orthonormal frame it is the transpose
/// product `(dot(T, d), dot(B, d), dot(N, d))`. Computed in double precision, rounded to float once.
///
/// - `normal`: 3 floats, the vertex normal, any nonzero length.
/// - `tangent`: 4 floats, `x, y, z, w`; `w` is the handedness (`+1` or `-1` as
///   `tbasis_generate` writes it; another nonzero value scales `B`).
/// - `direction`: 3 floats, the object-space vector (e.g. towards the light).
/// - `result`: 3 floats, written only on `TBASIS_OK`. It may be the same array as `direction`
///   (or overlap any input): every input is read before it is written.
///
/// Pointers need no alignment.
///
/// Returns `TBASIS_OK`; `TBASIS_ERROR_NULL_POINTER` (any pointer is NULL),
/// `TBASIS_ERROR_INVALID_FRAME` (an input is NaN or infinite; `normal` or `T` is zero, `w` is
/// zero, or `normal` and `T` are parallel: `|cross(normal, T)| <= 1e-6 * |normal| * |T|`; or a
/// result component overflows float) or `TBASIS_ERROR_INTERNAL`. On any error `result` has not
/// been written.
///
/// # Safety
/// Each pointer must be NULL or valid for the floats listed above.
#[no_mangle]
pub unsafe extern "C" fn tbasis_to_tangent_space(
    normal: *const f32,
    tangent: *const f32,
    direction: *const f32,
    result: *mut f32,
) -> tbasis_status {
    transform_vertex(normal, tangent, direction, result, to_tangent_space)
}

/// Moves a tangent-space `direction` (x along the tangent, y along the bitangent, z along the
/// normal, e.g. a decoded normal-map sample) into object space: `result = M * direction =
/// x * T + y * B + z * N`, with `M`, `T` and `B` as in `tbasis_to_tangent_space`. Nothing is
/// normalized. Computed in double precision, rounded to float once.
///
/// - `normal`, `tangent`, `result`: as in `tbasis_to_tangent_space`.
/// - `direction`: 3 floats, the tangent-space vector.
///
/// The frame is checked as by `tbasis_to_tangent_space` (a singular frame is refused although
/// `M * direction` would exist), so the two functions accept the same frames and invert each other.
///
/// Returns `TBASIS_OK`; `TBASIS_ERROR_NULL_POINTER`, `TBASIS_ERROR_INVALID_FRAME` or
/// `TBASIS_ERROR_INTERNAL`, as for `tbasis_to_tangent_space`. On any error `result` has not been
/// written.
///
/// # Safety
/// Each pointer must be NULL or valid for the floats listed above.
#[no_mangle]
pub unsafe extern "C" fn tbasis_from_tangent_space(
    normal: *const f32,
    tangent: *const f32,
    direction: *const f32,
    result: *mut f32,
) -> tbasis_status {
    transform_vertex(normal, tangent, direction, result, from_tangent_space)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_internal() {
        assert_eq!(boundary(|| panic!("bug")), TBASIS_ERROR_INTERNAL);
    }
}
