//! The C entry points of the tangent-space transforms, `tbasis_to_tangent_space` and
//! `tbasis_from_tangent_space`: what they write, and when. The transforms themselves are tested
//! against their definitions in `crates/tbasis/tests/transform.rs`.

// The C boundary's own source, compiled into this test (the C library has no Rust interface).
#[allow(dead_code)]
#[path = "../src/codes.rs"]
mod codes;
#[path = "../src/fault.rs"]
mod fault;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/ffi.rs"]
mod ffi;
#[path = "../src/guard.rs"]
mod guard;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/status.rs"]
mod status;

use ffi::{tbasis_from_tangent_space, tbasis_status_string, tbasis_to_tangent_space};
use status::{TBASIS_ERROR_INVALID_FRAME, TBASIS_ERROR_NULL_POINTER, TBASIS_OK};

#[test]
fn c_abi_writes_only_on_success() {
    let (n, t) = ([0.0f32, 0.0, 1.0], [1.0f32, 0.0, 0.0, 1.0]);
    let d = [0.25f32, -0.5, 2.0];
    let sentinel = [-7.5f32; 3];
    type Export = unsafe extern "C" fn(*const f32, *const f32, *const f32, *mut f32) -> u32;
    for (name, export) in [
        ("to", tbasis_to_tangent_space as Export),
        ("from", tbasis_from_tangent_space as Export),
    ] {
        let mut result = sentinel;
        let status = unsafe { export(n.as_ptr(), t.as_ptr(), d.as_ptr(), result.as_mut_ptr()) };
        assert_eq!((status, result), (TBASIS_OK, d), "{name}");

        for k in 0..4 {
            let mut result = sentinel;
            let mut inputs = [n.as_ptr(), t.as_ptr(), d.as_ptr()];
            let mut output = result.as_mut_ptr();
            match k {
                3 => output = std::ptr::null_mut(),
                _ => inputs[k] = std::ptr::null(),
            }
            let status = unsafe { export(inputs[0], inputs[1], inputs[2], output) };
            assert_eq!(
                (status, result),
                (TBASIS_ERROR_NULL_POINTER, sentinel),
                "{name}: NULL argument {k}"
            );
        }

        let singular = [0.0f32, 0.0, 3.0, 1.0];
        let mut result = sentinel;
        let status = unsafe { export(n.as_ptr(), singular.as_ptr(), d.as_ptr(), result.as_mut_ptr()) };
        assert_eq!(
            (status, result),
            (TBASIS_ERROR_INVALID_FRAME, sentinel),
            "{name}: singular"
        );

        let nan = [f32::NAN, 0.0, 1.0];
        let mut result = sentinel;
        let status = unsafe { export(nan.as_ptr(), t.as_ptr(), d.as_ptr(), result.as_mut_ptr()) };
        assert_eq!(
            (status, result),
            (TBASIS_ERROR_INVALID_FRAME, sentinel),
            "{name}: NaN normal"
        );

        // In place: `result` may be `direction`.
        let mut inout = d;
        let status = unsafe { export(n.as_ptr(), t.as_ptr(), inout.as_ptr(), inout.as_mut_ptr()) };
        assert_eq!((status, inout), (TBASIS_OK, d), "{name}: in place");
    }
    let text = unsafe { std::ffi::CStr::from_ptr(tbasis_status_string(TBASIS_ERROR_INVALID_FRAME)) };
    let message = status::message_nul(TBASIS_ERROR_INVALID_FRAME).unwrap();
    assert_eq!(text.to_bytes_with_nul(), message.as_bytes());
}

#[test]
fn unaligned_c_arrays_are_read_and_written() {
    // Floats at odd byte offsets: the boundary must not assume alignment.
    let mut bytes = [0u8; 1 + 4 * 13];
    let floats: [f32; 10] = [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 3.0];
    for (k, x) in floats.iter().enumerate() {
        bytes[1 + 4 * k..5 + 4 * k].copy_from_slice(&x.to_ne_bytes());
    }
    let base = bytes.as_mut_ptr().wrapping_add(1).cast::<f32>();
    let status =
        unsafe { tbasis_to_tangent_space(base, base.wrapping_add(3), base.wrapping_add(7), base.wrapping_add(10)) };
    assert_eq!(status, TBASIS_OK);
    let out: Vec<f32> = (0..3)
        .map(|k| f32::from_ne_bytes(bytes[41 + 4 * k..45 + 4 * k].try_into().unwrap()))
        .collect();
    assert_eq!(out, [3.0, 1.0, 2.0]);
}
