//! Support shared by this crate's tests. The repository's own test support is reused by path:
//! what a test needs and how it is skipped (`needs.rs`), mikktspace.c as the reference
//! (`mikktspace_reference.rs`) and the corpus manifest (`load.rs`).
#![allow(dead_code)]

#[path = "../../../../tests/common/load.rs"]
pub mod load;
#[path = "../../../../tests/common/mikktspace_reference.rs"]
pub mod mikktspace_reference;
#[path = "../../../../tests/common/needs.rs"]
pub mod needs;

pub mod document;
pub mod fixture;
pub mod tool;
pub mod validator;
