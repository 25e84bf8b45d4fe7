//! `libtbasis_mikktspace`: mikktspace.c's C interface (`genTangSpaceDefault`, `genTangSpace` and
//! the types of mikktspace.h) computed by `tbasis::mikktspace`, for programs that drop mikktspace.c
//! from their build and link this library instead. Its manual is the C header,
//! `include/tbasis_mikktspace.h`.
//!
//! A thin unsafe boundary: [`Callbacks`] reads the mesh through the context's callbacks and hands
//! each tangent space back through them, and `tbasis::mikktspace::generate_tangents_with` does
//! the rest. Everything runs inside `guard` (the C library's `src/guard.rs`): a panic, a library
//! bug, makes the call return 0. The generator calls `set_tangent` only after all its computation,
//! so a panic normally comes before any set call; the header tells callers to ignore set calls
//! made before a 0 all the same.
#![allow(non_camel_case_types, non_snake_case)]
#![warn(missing_docs)]

#[cfg(all(feature = "fault-injection", not(debug_assertions)))]
compile_error!("the feature fault-injection is for test builds only, never a release build");

// The boundary of libtbasis, shared: the panic guard and its test-only injected panic.
#[path = "../../../src/fault.rs"]
mod fault;
#[path = "../../../src/guard.rs"]
mod guard;

use core::ffi::{c_float, c_int, c_void};
use core::sync::atomic::{AtomicU32, Ordering};

use tbasis::mikktspace::{generate_tangents_with, Geometry, Settings};

use crate::guard::guard;

/// mikktspace.h's boolean: 0 or 1.
pub type tbool = c_int;

/// `m_getNumFaces`.
type GetNumFaces = unsafe extern "C" fn(*const SMikkTSpaceContext) -> c_int;
/// `m_getNumVerticesOfFace`.
type GetNumVerticesOfFace = unsafe extern "C" fn(*const SMikkTSpaceContext, c_int) -> c_int;
/// `m_getPosition`, `m_getNormal` and `m_getTexCoord`.
type GetAttribute = unsafe extern "C" fn(*const SMikkTSpaceContext, *mut c_float, c_int, c_int);
/// `m_setTSpaceBasic`.
type SetTSpaceBasic = unsafe extern "C" fn(*const SMikkTSpaceContext, *const c_float, c_float, c_int, c_int);
/// `m_setTSpace`.
type SetTSpace = unsafe extern "C" fn(
    *const SMikkTSpaceContext,
    *const c_float,
    *const c_float,
    c_float,
    c_float,
    tbool,
    c_int,
    c_int,
);

/// mikktspace.h's callback table, member for member; any member may be NULL.
#[repr(C)]
pub struct SMikkTSpaceInterface {
    /// The number of faces.
    pub m_getNumFaces: Option<GetNumFaces>,
    /// The number of vertices of a face: faces of 3 or 4 count, others are ignored.
    pub m_getNumVerticesOfFace: Option<GetNumVerticesOfFace>,
    /// Writes a face vertex's position, 3 floats.
    pub m_getPosition: Option<GetAttribute>,
    /// Writes a face vertex's normal, 3 floats.
    pub m_getNormal: Option<GetAttribute>,
    /// Writes a face vertex's texture coordinate, 2 floats.
    pub m_getTexCoord: Option<GetAttribute>,
    /// Receives a face vertex's tangent and sign.
    pub m_setTSpaceBasic: Option<SetTSpaceBasic>,
    /// Receives a face vertex's tangent, bitangent, their magnitudes and orientation.
    pub m_setTSpace: Option<SetTSpace>,
}

/// mikktspace.h's context: the callbacks and the caller's data, passed back to every callback.
#[repr(C)]
pub struct SMikkTSpaceContext {
    /// The callbacks.
    pub m_pInterface: *mut SMikkTSpaceInterface,
    /// The caller's pointer, for the callbacks.
    pub m_pUserData: *mut c_void,
}

/// The worker threads of later calls (`tbasis_mikktspace_set_threads`); each call reads it once.
static THREADS: AtomicU32 = AtomicU32::new(1);

/// A face or vertex number as the callbacks take it. The generator asks only for faces below
/// `m_getNumFaces`, an `int`, and for their first 4 vertices.
fn int(number: usize) -> c_int {
    c_int::try_from(number).expect("face and vertex numbers come from int counts")
}

/// The context's callbacks, read once when the call starts, as the generator's [`Geometry`].
struct Callbacks {
    context: *const SMikkTSpaceContext,
    num_faces: GetNumFaces,
    num_vertices_of_face: GetNumVerticesOfFace,
    position: GetAttribute,
    normal: GetAttribute,
    tex_coord: GetAttribute,
    set_tspace_basic: Option<SetTSpaceBasic>,
    set_tspace: Option<SetTSpace>,
}

impl Callbacks {
    /// The callbacks of `context`; `None` when it, its interface or one of the five get
    /// callbacks is NULL (mikktspace.c returns 0 for a NULL get callback, and crashes on the rest).
    ///
    /// # Safety
    /// `context`, when not NULL, points to a context whose interface, when not NULL, points to a
    /// valid interface, both readable for the whole call; every callback is safe to call with
    /// `context` as mikktspace.h describes.
    unsafe fn new(context: *const SMikkTSpaceContext) -> Option<Callbacks> {
        // SAFETY: the caller's contract; NULL pointers are refused before the reads.
        let interface = unsafe { context.as_ref()?.m_pInterface.as_ref()? };
        Some(Callbacks {
            context,
            num_faces: interface.m_getNumFaces?,
            num_vertices_of_face: interface.m_getNumVerticesOfFace?,
            position: interface.m_getPosition?,
            normal: interface.m_getNormal?,
            tex_coord: interface.m_getTexCoord?,
            set_tspace_basic: interface.m_setTSpaceBasic,
            set_tspace: interface.m_setTSpace,
        })
    }

    /// Calls a get callback with an output of `N` floats, zeroed first.
    fn get<const N: usize>(&self, callback: GetAttribute, face: usize, vert: usize) -> [f32; N] {
        let mut out = [0.0f32; N];
        // SAFETY: `new`'s contract; the callback writes N floats (3, or 2 for texture coordinates,
        // the sizes of mikktspace.c's buffers).
        unsafe { callback(self.context, out.as_mut_ptr(), int(face), int(vert)) };
        out
    }
}

impl Geometry for Callbacks {
    fn num_faces(&self) -> usize {
        // SAFETY: `new`'s contract. A negative count is no face, as in mikktspace.c's loops.
        usize::try_from(unsafe { (self.num_faces)(self.context) }).unwrap_or(0)
    }

    fn num_vertices_of_face(&self, face: usize) -> usize {
        // SAFETY: `new`'s contract. A negative count is a face that is neither 3 nor 4: ignored.
        usize::try_from(unsafe { (self.num_vertices_of_face)(self.context, int(face)) }).unwrap_or(0)
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.get(self.position, face, vert)
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.get(self.normal, face, vert)
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.get(self.tex_coord, face, vert)
    }

    /// mikktspace.c's two calls, in its order, with its arguments: `m_setTSpace(tangent, bitangent,
    /// fMagS, fMagT, bIsOrientationPreserving)` then `m_setTSpaceBasic(tangent, fSign)`, each when
    /// set, the same tangent array to both.
    fn set_tangent(&mut self, t: [f32; 3], b: [f32; 3], mag_s: f32, mag_t: f32, keeps: bool, face: usize, vert: usize) {
        let (face, vert) = (int(face), int(vert));
        if let Some(set) = self.set_tspace {
            // SAFETY: `new`'s contract; both arrays hold 3 floats and outlive the call.
            unsafe {
                set(
                    self.context,
                    t.as_ptr(),
                    b.as_ptr(),
                    mag_s,
                    mag_t,
                    tbool::from(keeps),
                    face,
                    vert,
                )
            };
        }
        if let Some(set) = self.set_tspace_basic {
            let sign = if keeps { 1.0 } else { -1.0 };
            // SAFETY: as above.
            unsafe { set(self.context, t.as_ptr(), sign, face, vert) };
        }
    }
}

/// Both entry points: the callbacks checked, the threads read, the generator run inside the guard.
///
/// # Safety
/// [`Callbacks::new`]'s contract.
unsafe fn generate(context: *const SMikkTSpaceContext, angular_threshold: f32) -> tbool {
    guard(0, || {
        // SAFETY: the caller's contract.
        let Some(mut callbacks) = (unsafe { Callbacks::new(context) }) else {
            return 0;
        };
        let settings = Settings {
            angular_threshold,
            threads: THREADS.load(Ordering::Relaxed),
        };
        tbool::from(generate_tangents_with(&mut callbacks, &settings))
    })
}

/// mikktspace.c's `genTangSpaceDefault`: `genTangSpace` at 180 degrees.
///
/// # Safety
/// `pContext` is NULL or points to a context as mikktspace.h describes, whose callbacks may be
/// called from this thread during the call.
#[no_mangle]
pub unsafe extern "C" fn genTangSpaceDefault(pContext: *const SMikkTSpaceContext) -> tbool {
    // SAFETY: the caller's contract.
    unsafe { generate(pContext, 180.0) }
}

/// mikktspace.c's `genTangSpace`: a tangent space for every vertex of every face of 3 or 4
/// vertices, handed to the set callbacks; 1 on success, 0 with no set callback called otherwise.
///
/// # Safety
/// As [`genTangSpaceDefault`].
#[no_mangle]
pub unsafe extern "C" fn genTangSpace(pContext: *const SMikkTSpaceContext, fAngularThreshold: c_float) -> tbool {
    // SAFETY: the caller's contract.
    unsafe { generate(pContext, fAngularThreshold) }
}

/// Sets the worker threads of the calls that start after it (1, the default, or less: the
/// calling thread alone). Each call reads it once, when it starts.
#[no_mangle]
pub extern "C" fn tbasis_mikktspace_set_threads(threads: c_int) {
    THREADS.store(u32::try_from(threads).unwrap_or(1).max(1), Ordering::Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// README ("Replacing mikktspace.c", threads): one worker until a program asks for more, as
    /// with mikktspace.c; counts of 1 or less mean the calling thread alone.
    #[test]
    fn calls_use_one_worker_until_asked_and_counts_below_one_mean_one() {
        assert_eq!(THREADS.load(Ordering::Relaxed), 1, "the default");
        for (asked, used) in [(4, 4), (0, 1), (-3, 1), (i32::MAX, i32::MAX as u32), (1, 1)] {
            tbasis_mikktspace_set_threads(asked);
            assert_eq!(THREADS.load(Ordering::Relaxed), used, "asked for {asked}");
        }
    }
}
