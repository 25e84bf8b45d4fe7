//! Typed working arrays cut from one byte buffer, or counted to size that buffer.
//!
//! The same code lays the arrays out and sizes them, so the size the caller is told and the
//! arrays a call takes cannot disagree.
#![forbid(unsafe_code)]

use core::mem::{align_of, size_of};

use crate::error::Error;
use crate::views::strided::{pod_prefix_mut, Pod};

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
