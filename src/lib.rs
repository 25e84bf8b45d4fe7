//! The C library of tbasis: `libtbasis.so` and `libtbasis.a`, whose header `include/tbasis.h` is
//! generated from these files. A thin boundary over the `tbasis` crate (crates/tbasis): it turns C
//! buffer descriptions into the crate's checked views, calls it, maps its errors to the fixed
//! `TBASIS_ERROR_*` statuses, and catches any panic before it reaches C.
#![allow(non_camel_case_types)]
#![warn(missing_docs)]

#[cfg(all(feature = "fault-injection", not(debug_assertions)))]
compile_error!("the feature fault-injection is for test builds only, never a release build");

mod codes;
mod fault;
mod ffi;
mod guard;
mod status;
