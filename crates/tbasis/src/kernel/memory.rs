//! A call's working memory: one byte buffer, the caller's or a fresh zeroed allocation, from which
//! each pipeline cuts its typed arrays.
//!
//! The same code lays the arrays out and sizes them ([`Arena`]), so the size the caller is told
//! (`scratch_size_for`) and the arrays a call takes cannot disagree.
#![forbid(unsafe_code)]

use core::mem::{align_of, size_of};

use crate::kernel::error::Error;
use crate::kernel::sums::{Links, Scratch, VertexSums};
use crate::kernel::views::pod::{pod_prefix_mut, try_written_zero_bytes, try_zeroed_bytes, write_zeros, Pod};

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
pub(crate) fn bytes_of<'a, T>(layout: impl FnOnce(&mut Arena<'a>) -> Result<T, Error>) -> Result<usize, Error> {
    let mut arena = Arena::Count(0);
    layout(&mut arena)?;
    Ok(arena.counted())
}

/// Bytes the arrays for `vertex_count` vertices and `link_bytes` of adjacency take in memory from
/// `place`, as [`vertex_arrays`] lays them out: in the caller's, `vertex_count * 29 + link_bytes +
/// 3` (the 3 let the sums start at a 4-byte boundary wherever the memory begins); on the heap the
/// same without `link_bytes`; 0 for an empty mesh. `None` on overflow.
pub(crate) fn vertex_arrays_bytes(vertex_count: usize, link_bytes: usize, place: Place) -> Option<usize> {
    if vertex_count == 0 {
        return Some(0);
    }
    let in_memory = if place == Place::Caller { link_bytes } else { 0 };
    let mut no_links = Vec::new();
    bytes_of(|arena| vertex_arrays(arena, vertex_count, in_memory, (Place::Caller, 1), &mut no_links).map(|_| ())).ok()
}

/// Takes the arrays for `vertex_count` vertices and `link_bytes` of adjacency from `arena` in
/// memory from `place`: the sums, the adjacency (right after them, so 4-byte aligned), the flags;
/// the sums and flags zero (heap memory comes zero, and written: [`Fresh::Written`]; in the
/// caller's, the sums are zeroed here on up to `workers` threads, the flags on this one). In heap
/// memory the adjacency is only reserved, in `heap_links`.
pub fn vertex_arrays<'a>(
    arena: &mut Arena<'a>,
    vertex_count: usize,
    link_bytes: usize,
    (place, workers): (Place, usize),
    heap_links: &'a mut Vec<u8>,
) -> Result<Scratch<'a>, Error> {
    let in_arena = if place == Place::Caller { link_bytes } else { 0 };
    let sums: &mut [VertexSums] = arena.take(vertex_count)?;
    let links = arena.take(in_arena)?;
    let flags: &mut [u8] = arena.take(vertex_count)?;
    let links = match place {
        Place::Caller => {
            // The zero sum is zero bytes; the flags, 1 byte per vertex, are too few to split.
            write_zeros(sums, workers);
            flags.fill(0);
            Links::Caller(links)
        }
        Place::Heap => Links::reserve(heap_links, link_bytes)?,
    };
    Ok(Scratch {
        sums,
        flags,
        first: 0,
        links,
    })
}

/// Where a call's working memory comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Place {
    /// The caller's scratch: everything a call may touch is laid out in it.
    Caller,
    /// A fresh allocation: memory a call touches only in some cases (policy INHERIT's adjacency)
    /// is reserved apart instead ([`Links::reserve`]), so that a call that does not need it
    /// neither allocates it with the rest nor faults its pages in.
    Heap,
}

/// `len` zero bytes from the heap, or [`Error::OutOfMemory`]: a zeroed allocation from the system,
/// whose fresh pages nobody writes before a call touches them, made fallibly
/// ([`try_zeroed_bytes`]).
pub(crate) fn zeroed_bytes(len: usize) -> Result<Vec<u8>, Error> {
    try_zeroed_bytes(len).ok_or(Error::OutOfMemory)
}

/// An empty vector with room for `n` elements, or [`Error::OutOfMemory`].
pub(crate) fn vec_with_capacity<T>(n: usize) -> Result<Vec<T>, Error> {
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| Error::OutOfMemory)?;
    Ok(v)
}

/// `n` copies of `value`, or [`Error::OutOfMemory`].
pub(crate) fn vec_filled<T: Clone>(n: usize, value: T) -> Result<Vec<T>, Error> {
    let mut v = vec_with_capacity(n)?;
    v.resize(n, value);
    Ok(v)
}

/// How a call's fresh heap memory starts out: zero either way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Fresh {
    /// Unwritten ([`zeroed_bytes`]): pages a call never touches are never faulted in. For
    /// pipelines that write each array before they read it.
    Untouched,
    /// Written, on up to `workers` threads ([`try_written_zero_bytes`]): for arrays read before
    /// they are written (sums added to). A fresh page read first is mapped to the shared zero
    /// page, so the write after it faults again and, with a second thread running, makes every
    /// core flush its TLB.
    Written { workers: usize },
}

/// Runs `job` on the working memory of one call: the first `size(Place::Caller)` bytes of the
/// caller's `scratch` ([`Error::ScratchTooSmall`] when it has fewer), or `size(Place::Heap)`
/// fresh zero bytes, as `fresh` says; `None` from `size` is [`Error::SizeOverflow`].
pub(crate) fn with_memory<R>(
    scratch: Option<&mut [u8]>,
    size: impl Fn(Place) -> Option<usize>,
    fresh: Fresh,
    job: impl FnOnce(&mut [u8], Place) -> Result<R, Error>,
) -> Result<R, Error> {
    match scratch {
        Some(bytes) => {
            let (needed, len) = (size(Place::Caller).ok_or(Error::SizeOverflow)?, bytes.len());
            let memory = bytes.get_mut(..needed).ok_or(Error::ScratchTooSmall { needed, len })?;
            job(memory, Place::Caller)
        }
        None => {
            let len = size(Place::Heap).ok_or(Error::SizeOverflow)?;
            let mut memory = match fresh {
                Fresh::Untouched => zeroed_bytes(len)?,
                Fresh::Written { workers } => try_written_zero_bytes(len, workers).ok_or(Error::OutOfMemory)?,
            };
            job(&mut memory, Place::Heap)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::options::DegeneratePolicy;
    use crate::kernel::sums::link_bytes;

    /// [`vertex_arrays`] in `buffer` as the caller's; the adjacency's length.
    fn carve(buffer: &mut [u8], vertex_count: usize, link_bytes: usize) -> Result<usize, Error> {
        let mut unused = Vec::new();
        let mut scratch = vertex_arrays(
            &mut Arena::Carve(buffer),
            vertex_count,
            link_bytes,
            (Place::Caller, 1),
            &mut unused,
        )?;
        let links = scratch.links.bytes();
        let aligned = links.is_empty() || links.as_ptr() as usize % 4 == 0;
        assert!(aligned, "adjacency not aligned");
        Ok(links.len())
    }

    #[test]
    fn the_size_is_enough_at_every_alignment_and_one_byte_less_is_not() {
        for vertex_count in [1usize, 2, 7, 100] {
            for link_bytes in [0, 4 * (2 * vertex_count + 9)] {
                let size = vertex_arrays_bytes(vertex_count, link_bytes, Place::Caller).unwrap();
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
        assert_eq!(vertex_arrays_bytes(0, 0, Place::Caller), Some(0));
        // On the heap the adjacency is reserved apart.
        assert_eq!(
            vertex_arrays_bytes(10, 400, Place::Heap),
            vertex_arrays_bytes(10, 0, Place::Caller)
        );
        assert_eq!(vertex_arrays_bytes(usize::MAX, 0, Place::Caller), None);
    }

    #[test]
    fn memory_written_on_several_threads_is_zero() {
        let least = crate::kernel::parallel::MIN_FILL_BYTES_PER_WORKER;
        let vertex_count = 3 * least / 28 + 1; // Sums for three workers.
        for workers in [1, 2, 3] {
            // Filled with 0xA5 and freed, the block is what the next allocation of its size reuses
            // (glibc: once its first, mapped apart, has raised the threshold for mapping).
            let len = vertex_arrays_bytes(vertex_count, 0, Place::Heap).unwrap();
            for _ in 0..2 {
                drop(vec![0xA5u8; len]);
            }
            let heap = try_written_zero_bytes(len, workers).unwrap();
            assert!(
                heap.len() == len && heap.iter().all(|&b| b == 0),
                "heap, {workers} workers"
            );

            let mut caller = vec![0xA5u8; len];
            let mut unused = Vec::new();
            let place = (Place::Caller, workers);
            let scratch = vertex_arrays(&mut Arena::Carve(&mut caller), vertex_count, 0, place, &mut unused).unwrap();
            let zero = VertexSums::default();
            assert!(
                scratch.sums.iter().all(|s| *s == zero),
                "caller's sums, {workers} workers"
            );
            assert!(
                scratch.flags.iter().all(|&f| f == 0),
                "caller's flags, {workers} workers"
            );
        }
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
        let size = vertex_arrays_bytes(10, link_bytes(inherit, 10, 30).unwrap(), Place::Caller);
        assert_eq!(size, Some(10 * 37 + 30 * 4 + 3));
        assert_eq!(link_bytes(inherit, usize::MAX / 2, 30), None);
    }
}
