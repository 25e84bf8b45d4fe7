//! A call's working memory: one byte buffer, the caller's or a fresh zeroed allocation, from which
//! each pipeline cuts its typed arrays.
//!
//! The same code lays the arrays out and sizes them ([`Arena`]), so the size the caller is told
//! (`scratch_size_for`) and the arrays a call takes cannot disagree.
#![forbid(unsafe_code)]

use core::mem::{align_of, size_of};

use crate::kernel::error::Error;
use crate::kernel::sums::{Links, Scratch, VertexSums};
use crate::kernel::views::pod::{pod_prefix_mut, Pod};

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

/// Bytes the arrays for `vertex_count` vertices and `link_bytes` of adjacency take, as
/// [`vertex_arrays`] lays them out: `vertex_count * 29 + link_bytes + 3` (the 3 let the sums start at a
/// 4-byte boundary wherever the memory begins), 0 for an empty mesh. `None` on overflow.
pub(crate) fn vertex_arrays_bytes(vertex_count: usize, link_bytes: usize) -> Option<usize> {
    if vertex_count == 0 {
        return Some(0);
    }
    bytes_of(|arena| vertex_arrays(arena, vertex_count, link_bytes).map(|_| ())).ok()
}

/// Takes the arrays for `vertex_count` vertices and `link_bytes` of adjacency from `arena`: the
/// sums, the adjacency (right after them, so 4-byte aligned), the flags; the sums and flags zeroed.
pub fn vertex_arrays<'a>(arena: &mut Arena<'a>, vertex_count: usize, link_bytes: usize) -> Result<Scratch<'a>, Error> {
    let sums: &mut [VertexSums] = arena.take(vertex_count)?;
    let links = arena.take(link_bytes)?;
    let flags: &mut [u8] = arena.take(vertex_count)?;
    sums.fill(VertexSums::default());
    flags.fill(0);
    Ok(Scratch {
        sums,
        flags,
        first: 0,
        links: Links(links),
    })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::options::DegeneratePolicy;
    use crate::kernel::sums::link_bytes;

    /// `layout` in memory of `size` bytes at byte offset `offset` of a buffer.
    fn carve(buffer: &mut [u8], vertex_count: usize, link_bytes: usize) -> Result<usize, Error> {
        let scratch = vertex_arrays(&mut Arena::Carve(buffer), vertex_count, link_bytes)?;
        let aligned = scratch.links.0.is_empty() || scratch.links.0.as_ptr() as usize % 4 == 0;
        assert!(aligned, "adjacency not aligned");
        Ok(scratch.links.0.len())
    }

    #[test]
    fn the_size_is_enough_at_every_alignment_and_one_byte_less_is_not() {
        for vertex_count in [1usize, 2, 7, 100] {
            for link_bytes in [0, 4 * (2 * vertex_count + 9)] {
                let size = vertex_arrays_bytes(vertex_count, link_bytes).unwrap();
                assert_eq!(size, vertex_count * 29 + link_bytes + 3, "the documented formula");
                let mut buffer = vec![0u8; size + 8];
                for offset in 0..4 {
                    assert_eq!(
                        carve(&mut buffer[offset..offset + size], vertex_count, link_bytes),
                        Ok(link_bytes)
                    );
                }
                // With the worst alignment, one byte less must fail.
                let worst = (0..4).find(|o| (buffer[*o..].as_ptr() as usize) % 4 == 1).unwrap();
                assert!(carve(&mut buffer[worst..worst + size - 1], vertex_count, link_bytes).is_err());
            }
        }
        assert_eq!(vertex_arrays_bytes(0, 0), Some(0));
        assert_eq!(vertex_arrays_bytes(usize::MAX, 0), None);
    }

    #[test]
    fn inherit_needs_its_adjacency_and_the_other_policies_nothing_more() {
        for policy in [
            DegeneratePolicy::Legacy,
            DegeneratePolicy::Skip,
            DegeneratePolicy::Reject,
        ] {
            assert_eq!(link_bytes(policy, 10, 30), Some(0));
        }
        let inherit = DegeneratePolicy::Inherit;
        assert_eq!(link_bytes(inherit, 0, 30), Some(0));
        // 4 bytes per entry: a start and a queue slot per vertex, one entry per corner.
        assert_eq!(link_bytes(inherit, 10, 30), Some(4 * (2 * 10 + 30)));
        let size = vertex_arrays_bytes(10, link_bytes(inherit, 10, 30).unwrap());
        assert_eq!(size, Some(10 * 37 + 30 * 4 + 3));
        assert_eq!(link_bytes(inherit, usize::MAX / 2, 30), None);
    }
}
