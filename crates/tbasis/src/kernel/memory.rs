//! A call's working memory: one byte buffer, the caller's or a fresh zeroed allocation, from which
//! each pipeline cuts its typed arrays.
//!
//! The same code lays the arrays out and sizes them ([`Arena`]), so the size the caller is told
//! (`scratch_size_for`) and the arrays a call takes cannot disagree.
#![forbid(unsafe_code)]

use core::mem::{align_of, size_of};

use crate::kernel::error::Error;
use crate::kernel::views::strided::{pod_prefix_mut, Pod};

/// Either counts the bytes the arrays need or hands them out of caller or heap memory.
pub(crate) enum Arena<'a> {
    /// Counting: every array is empty, the bytes add up (with room to align each array).
    Count(usize),
    /// Cutting arrays from the front of the remaining bytes.
    Carve(&'a mut [u8]),
}

impl<'a> Arena<'a> {
    /// The next `count` elements of `T` (uninitialized as far as meaning goes: any bits).
    pub fn take<T: Pod>(&mut self, count: usize) -> Result<&'a mut [T], Error> {
        match self {
            Arena::Count(total) => {
                let bytes = count
                    .checked_mul(size_of::<T>())
                    .and_then(|b| b.checked_add(align_of::<T>() - 1))
                    .and_then(|b| b.checked_add(*total))
                    .ok_or(Error::SizeOverflow)?;
                *total = bytes;
                Ok(&mut [])
            }
            Arena::Carve(rest) => {
                let bytes = core::mem::take(rest);
                let too_small = Error::ScratchTooSmall {
                    needed: count.saturating_mul(size_of::<T>()),
                    len: bytes.len(),
                };
                let (typed, after) = pod_prefix_mut::<T>(bytes, count).ok_or(too_small)?;
                *rest = after;
                Ok(typed)
            }
        }
    }

    /// The bytes counted so far (0 when carving).
    pub fn counted(&self) -> usize {
        match self {
            Arena::Count(total) => *total,
            Arena::Carve(_) => 0,
        }
    }
}

/// The bytes `layout` takes from an arena.
pub(crate) fn bytes_of<T>(layout: impl FnOnce(&mut Arena<'static>) -> Result<T, Error>) -> Result<usize, Error> {
    let mut arena = Arena::Count(0);
    layout(&mut arena)?;
    Ok(arena.counted())
}

/// `len` zero bytes from the heap, or [`Error::OutOfMemory`]. A fallible reservation first tells
/// whether the memory is there; the zeroed allocation that follows comes from the system already
/// cleared, so a large buffer costs only the pages a call then touches, not a pass over all of it.
pub(crate) fn zeroed_bytes(len: usize) -> Result<Vec<u8>, Error> {
    let mut probe: Vec<u8> = Vec::new();
    probe.try_reserve_exact(len).map_err(|_| Error::OutOfMemory)?;
    drop(probe);
    Ok(vec![0; len])
}

/// Runs `job` on `size` bytes of working memory: the first `size` of the caller's `scratch`
/// ([`Error::ScratchTooSmall`] when it has fewer), or a fresh zeroed allocation.
pub(crate) fn with_memory<R>(
    scratch: Option<&mut [u8]>,
    size: usize,
    job: impl FnOnce(&mut [u8]) -> Result<R, Error>,
) -> Result<R, Error> {
    match scratch {
        Some(bytes) => {
            let len = bytes.len();
            job(bytes
                .get_mut(..size)
                .ok_or(Error::ScratchTooSmall { needed: size, len })?)
        }
        None => job(&mut zeroed_bytes(size)?),
    }
}
