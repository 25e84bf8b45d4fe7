//! Typed arrays in untyped memory: the caller's scratch, or a fresh allocation, cut into the
//! working arrays of a call without copying.

use core::mem::{size_of, MaybeUninit};
use core::sync::atomic::AtomicU32;

use crate::kernel::parallel;
use crate::kernel::sums::VertexSums;

/// Types for which every byte pattern of their size is a valid value.
///
/// # Safety
/// Implementors must be `repr(C)` or primitive, hold only `f32`/integers, and have no padding.
pub unsafe trait Pod: Copy {}
// SAFETY: three f32 + one f32 + three f32, repr(C), no padding.
unsafe impl Pod for VertexSums {}
// SAFETY: primitive numbers and arrays of them have no padding and no invalid bit patterns.
unsafe impl Pod for u32 {}
// SAFETY: as above.
unsafe impl Pod for u8 {}
// SAFETY: as above.
unsafe impl Pod for f32 {}
// SAFETY: as above.
unsafe impl Pod for [f32; 3] {}
// SAFETY: as above.
unsafe impl Pod for [u32; 2] {}
// SAFETY: as above.
unsafe impl Pod for [u32; 3] {}
// SAFETY: as above.
unsafe impl Pod for [f32; 8] {}

/// The first `count` elements of type `T` that fit in `bytes` after its first `T`-aligned address,
/// and the bytes after them; `None` when they do not fit.
///
/// Lets caller-provided scratch serve as typed working memory without copying. The bytes before the
/// aligned address are left unused; `scratch_size` budgets `align_of::<T>() - 1` bytes for them.
pub fn pod_prefix_mut<T: Pod>(bytes: &mut [u8], count: usize) -> Option<(&mut [T], &mut [u8])> {
    if count == 0 {
        // Nothing to align: an empty scratch fits at any address.
        return Some((&mut [], bytes));
    }
    let head = bytes.as_ptr().align_offset(core::mem::align_of::<T>());
    let typed_bytes = count.checked_mul(size_of::<T>())?;
    if head.checked_add(typed_bytes)? > bytes.len() {
        return None;
    }
    let (typed, rest) = bytes[head..].split_at_mut(typed_bytes);
    // SAFETY: `typed` starts T-aligned and holds exactly `count * size_of::<T>()` bytes that this
    // exclusive borrow owns; T is Pod, so whatever the bytes hold is a valid T.
    let typed = unsafe { core::slice::from_raw_parts_mut(typed.as_mut_ptr().cast::<T>(), count) };
    Some((typed, rest))
}

/// `words` as consecutive triples (a trailing one or two words left out): one triangle's corners
/// each.
pub(crate) fn triples(words: &[u32]) -> &[[u32; 3]] {
    // SAFETY: `[u32; 3]` is three `u32`s with no padding and `u32`'s alignment, so the first
    // `words.len() / 3 * 3` words are that many triples, borrowed as long as `words`.
    unsafe { core::slice::from_raw_parts(words.as_ptr().cast::<[u32; 3]>(), words.len() / 3) }
}

/// `words` as atomics, so that workers may each store into elements interleaved with the others'
/// (the weld by value's classes).
pub(crate) fn atomic_words(words: &mut [u32]) -> &[AtomicU32] {
    // Targets that align `AtomicU32` more strictly than `u32` are not supported.
    const { assert!(core::mem::align_of::<AtomicU32>() == core::mem::align_of::<u32>()) };
    // SAFETY: `AtomicU32` has the size, bit validity and (asserted above) alignment of `u32`; the
    // exclusive borrow of `words` lasts as long as the shared one returned, so the elements are
    // reached only through the atomics meanwhile.
    unsafe { core::slice::from_raw_parts(words.as_mut_ptr().cast::<AtomicU32>(), words.len()) }
}

/// `len` zero bytes from the global allocator's zeroed allocation, or `None` when the memory is not
/// there. The system gives fresh pages already zeroed (`calloc`), so nothing writes them here and
/// pages a call never touches are never faulted in (in huge pages where [`advise_huge_pages`]
/// asked for them: 2 MiB at a time); `vec![0; len]` makes the same allocation but
/// aborts the process on failure, which the C boundary must never do. The bytes are the memory the
/// scratch's typed views are carved from ([`pod_prefix_mut`]).
pub(crate) fn try_zeroed_bytes(len: usize) -> Option<Vec<u8>> {
    if len == 0 {
        return Some(Vec::new());
    }
    let layout = std::alloc::Layout::array::<u8>(len).ok()?;
    // SAFETY: `layout` has a nonzero size, as `alloc_zeroed` requires. A non-null result points to
    // `len` initialized (zero) bytes from the global allocator with `layout`, alignment 1 and size
    // `len`: what `Vec::from_raw_parts` needs for a `Vec<u8>` of length and capacity `len`, which
    // then owns and frees it. Before that, the same bytes are borrowed once, exclusively, to ask
    // for huge pages.
    unsafe {
        let pointer = std::alloc::alloc_zeroed(layout);
        if pointer.is_null() {
            return None;
        }
        advise_huge_pages(core::slice::from_raw_parts_mut(pointer.cast(), len));
        Some(Vec::from_raw_parts(pointer, len, len))
    }
}

/// Sets every byte of `items` to zero on up to `workers` threads ([`parallel::fill`], with the
/// same instance as [`try_written_zero_bytes`]: one copy of the threads' code in the library).
pub(crate) fn write_zeros<T: Pod>(items: &mut [T], workers: usize) {
    let len = core::mem::size_of_val(items);
    // SAFETY: the bytes of `items`, borrowed exclusively for the call, seen as `MaybeUninit<u8>`,
    // which any byte is; only zeros are written into them, and zero bytes are a valid `T` (Pod:
    // every byte pattern is one).
    let bytes = unsafe { core::slice::from_raw_parts_mut(items.as_mut_ptr().cast::<MaybeUninit<u8>>(), len) };
    parallel::fill(bytes, MaybeUninit::new(0), workers);
}

/// `len` zero bytes, written on up to `workers` threads ([`parallel::fill`]), or `None` when the
/// memory is not there: for arrays read before they are written (the per-vertex sums), whose
/// zeroing would otherwise run on one thread before the workers start. The allocation is the
/// plain one (`malloc`), which reuses memory freed before it; [`try_zeroed_bytes`]'s would zero it
/// on one thread first wherever it is not fresh from the system.
pub(crate) fn try_written_zero_bytes(len: usize, workers: usize) -> Option<Vec<u8>> {
    let mut bytes = Vec::new();
    bytes.try_reserve_exact(len).ok()?;
    parallel::fill(&mut bytes.spare_capacity_mut()[..len], MaybeUninit::new(0), workers);
    // SAFETY: the capacity is at least `len`, and `fill` has written each of the first `len`
    // elements: it returns only once every range is done (a worker's panic resumes on this thread,
    // and this line is not reached).
    unsafe { bytes.set_len(len) };
    Some(bytes)
}

/// Asks the system to back the 2 MiB-aligned part of `memory` with huge pages when they are
/// faulted in (Linux: `madvise(MADV_HUGEPAGE)`, which matters where transparent huge pages are
/// enabled only for memory that asks, a common default). A call's working memory is fresh and
/// large: in 4 KiB pages, first touches cost a fault each (about 72,000 a call on a 1M-vertex
/// mesh with method MIKKTSPACE). Only from 32 MiB on, glibc's largest threshold for mapping an
/// allocation on its own (`DEFAULT_MMAP_THRESHOLD_MAX` on 64-bit systems): its `malloc` maps every
/// allocation that large apart and unmaps it when it is freed, so the advice ends with the memory
/// instead of staying on heap memory the program reuses. Advice only: whether the
/// system follows it changes no byte, and its failure is ignored.
#[cfg(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64")))]
fn advise_huge_pages(memory: &mut [MaybeUninit<u8>]) {
    const HUGE_PAGE: usize = 2 << 20;
    const HUGE_PAGES_FROM: usize = 32 << 20;
    /// `MADV_HUGEPAGE` in Linux's generic `mman-common.h`, which both architectures use.
    const MADV_HUGEPAGE: core::ffi::c_int = 14;
    extern "C" {
        fn madvise(address: *mut core::ffi::c_void, len: usize, advice: core::ffi::c_int) -> core::ffi::c_int;
    }
    let (start, len) = (memory.as_mut_ptr() as usize, memory.len());
    let Some(first) = start.checked_next_multiple_of(HUGE_PAGE) else {
        return;
    };
    let end = (start + len) / HUGE_PAGE * HUGE_PAGE;
    if len >= HUGE_PAGES_FROM && end > first {
        // SAFETY: `madvise` from the C library the standard library links, with its C signature;
        // the range lies inside `memory`, which this function borrows exclusively, and
        // MADV_HUGEPAGE changes no byte of it (nor whether it is initialized).
        unsafe {
            let address = memory.as_mut_ptr().wrapping_add(first - start);
            madvise(address.cast(), end - first, MADV_HUGEPAGE);
        }
    }
}

/// Elsewhere there is nothing to ask.
#[cfg(not(all(target_os = "linux", any(target_arch = "x86_64", target_arch = "aarch64"))))]
fn advise_huge_pages(_: &mut [MaybeUninit<u8>]) {}
