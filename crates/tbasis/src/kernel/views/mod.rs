//! Views over the caller's memory: any stride, any alignment, read and written in place.

pub(crate) mod interleaved;
pub(crate) mod pod;
pub(crate) mod strided;
