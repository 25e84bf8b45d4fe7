//! The library behind `tbasis-gltf` (README: "tbasis-gltf"): reading a .gltf or .glb, adding
//! TANGENT attributes, writing the result. The binary (`main.rs`) is its command line; the fuzz
//! target (`fuzz/fuzz_targets/gltf_tool.rs`) feeds its reader and converter arbitrary files.

pub mod accessor;
pub mod args;
pub mod batch;
pub mod buffers;
pub mod convert;
pub mod document;
pub mod io;
pub mod memory;
pub mod primitive;
pub mod prune;
pub mod select;
pub mod uri;
