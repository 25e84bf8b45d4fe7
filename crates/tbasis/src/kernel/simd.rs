//! Runtime choice of the widest vector instructions the CPU has, for the robust path's kernels
//! and MIKKTSPACE's corner terms.
//!
//! The kernels are written once, as loops over lanes that LLVM vectorizes (`kernel::lanes`). A
//! build for the default x86-64 target may only assume SSE2, four lanes per instruction; here the
//! same kernels are compiled a second time with AVX2 enabled (eight lanes) and that copy runs when
//! the CPU supports it. Both copies perform the same IEEE operations in the same order on every
//! lane: no fused multiply-add (FMA is not enabled, and Rust never contracts `a * b + c`), square
//! roots and divisions correctly rounded in both, and sums added one triangle at a time outside
//! the lane loops. So every path gives the same bits (`entry/determinism_tests.rs` runs each path
//! the machine has and compares).
//!
//! This module and the strided views are the crate's only `unsafe` code: calling a function
//! compiled for AVX2 is sound only on a CPU that has it, which is checked right before. It also
//! holds the other instructions the kernels need from `std::arch`: a cache prefetch, and the
//! listing's add of a term and its flags in one 16-byte store ([`add_and_mark`]).

use crate::kernel::vertex_sums::VertexSums;

/// A set of vector instructions the kernels can be compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Path {
    /// What the build target guarantees (SSE2 on x86-64).
    Baseline,
    /// AVX2, chosen at run time.
    Avx2,
}

impl Path {
    /// Whether this CPU can run the path.
    pub fn supported(self) -> bool {
        match self {
            Path::Baseline => true,
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Path::Avx2 => std::is_x86_feature_detected!("avx2"),
            #[cfg(not(any(target_arch = "x86", target_arch = "x86_64")))]
            Path::Avx2 => false,
        }
    }

    /// The widest supported path (a test may pin one on its thread).
    pub fn best() -> Path {
        #[cfg(test)]
        if let Some(path) = tests::PINNED.with(core::cell::Cell::get) {
            return path;
        }
        if Path::Avx2.supported() {
            Path::Avx2
        } else {
            Path::Baseline
        }
    }
}

/// Runs `kernel` compiled for the best path this CPU supports. `kernel` and what it calls must be
/// inlined into it (`#[inline(always)]`) for the wider copy to exist.
#[inline(always)]
pub(crate) fn run<R>(kernel: impl FnOnce() -> R) -> R {
    match Path::best() {
        #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
        // SAFETY: `best` returns Avx2 only when the CPU reports AVX2.
        Path::Avx2 => unsafe { with_avx2(kernel) },
        _ => kernel(),
    }
}

/// `kernel` compiled with AVX2 enabled.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
#[target_feature(enable = "avx2")]
unsafe fn with_avx2<R>(kernel: impl FnOnce() -> R) -> R {
    kernel()
}

/// How many corners ahead a loop over corners asks for what the later corner's vertex reads
/// ([`prefetch`]): enough for the wait for memory to overlap the work on the corners between.
pub(crate) const PREFETCH_CORNERS: usize = 16;

/// Asks the CPU to bring `items[index]` into its cache ahead of a read, so that lookups that
/// would each wait for memory (a hash table's probes) overlap. A hint: it changes no result.
#[inline(always)]
pub(crate) fn prefetch<T>(items: &[T], index: usize) {
    if let Some(item) = items.get(index) {
        prefetch_address((item as *const T).cast());
    }
}

/// Where a slice's elements lie, without a borrow of it: a loop that writes the slice can still
/// ask for the elements it will need next ([`prefetch_address`]).
#[derive(Clone, Copy)]
pub(crate) struct Addresses {
    base: *const u8,
    size: usize,
    len: usize,
}

impl Addresses {
    pub(crate) fn of<T>(items: &[T]) -> Self {
        Addresses {
            base: items.as_ptr().cast(),
            size: size_of::<T>(),
            len: items.len(),
        }
    }

    /// [`prefetch`] of element `index` (nothing past the end).
    #[inline(always)]
    pub(crate) fn prefetch(self, index: usize) {
        if index < self.len {
            prefetch_address(self.base.wrapping_add(index * self.size));
        }
    }
}

/// Asks the CPU to bring the bytes at `address` into its cache ahead of a read (see
/// [`prefetch`]). Any address will do: a prefetch never faults and reads nothing the program can
/// observe.
#[inline(always)]
pub(crate) fn prefetch_address(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: SSE is part of x86-64, and a prefetch has no effect the program can observe,
        // whatever the address.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(address.cast()) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}

/// The bits [`add_and_mark`] keeps in `weight` besides the flags: those of 1.0, so that `weight`
/// is a normal number, which adding +0 leaves as it is even where the caller's floating-point
/// mode flushes subnormals to zero.
const MARKED: u32 = 0x3f80_0000;

/// Adds `term`'s x, y and z to `sums.primary` and ORs `bits` into the bits of `sums.weight`, in
/// one 16-byte load, add and store. The listing's first loop keeps a vertex's flags there rather
/// than in an array of their own, which cost a second read-modify-write per corner (README,
/// "Speed"). LLVM splits a 4-lane add with an integer lane into three stores, so the lanes are
/// written out here: x, y and z are three IEEE adds, as in the listing; `weight`, a normal number
/// once marked ([`MARKED`]), adds +0 and keeps its bits.
#[inline(always)]
pub(crate) fn add_and_mark(sums: &mut VertexSums, term: glam::Vec3A, bits: u8) {
    let marks = MARKED | u32::from(bits);
    #[cfg(target_arch = "x86_64")]
    {
        use core::arch::x86_64::{
            _mm_add_ps, _mm_castsi128_ps, _mm_loadu_ps, _mm_or_ps, _mm_set_epi32, _mm_setr_ps, _mm_storeu_ps,
        };
        const _: () =
            assert!(core::mem::offset_of!(VertexSums, primary) == 0 && core::mem::offset_of!(VertexSums, weight) == 12);
        let first = core::ptr::from_mut(sums).cast::<f32>();
        let [x, y, z] = term.to_array();
        // SAFETY: SSE2 is part of x86-64; `VertexSums` is `repr(C)` with `primary` then `weight`
        // in its first 16 bytes (asserted above), all `f32`, so the unaligned 16-byte load and
        // store stay inside the one exclusive borrow, and any bits are a valid `f32`.
        unsafe {
            let sum = _mm_add_ps(_mm_loadu_ps(first), _mm_setr_ps(x, y, z, 0.0));
            _mm_storeu_ps(
                first,
                _mm_or_ps(sum, _mm_castsi128_ps(_mm_set_epi32(marks as i32, 0, 0, 0))),
            );
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        for (sum, t) in sums.primary.iter_mut().zip(term.to_array()) {
            *sum += t;
        }
        sums.weight = f32::from_bits(sums.weight.to_bits() | marks);
    }
}

/// The flags [`add_and_mark`] ORed into `sums.weight`.
#[inline(always)]
pub(crate) fn marks(sums: &VertexSums) -> u8 {
    sums.weight.to_bits() as u8
}

#[cfg(test)]
pub(crate) mod tests {
    use super::Path;

    std::thread_local! {
        /// The path [`Path::best`] returns on this thread, when set (`entry/determinism_tests.rs`
        /// runs every supported path and compares).
        pub static PINNED: core::cell::Cell<Option<Path>> = const { core::cell::Cell::new(None) };
    }

    /// Every path this CPU supports, the baseline first. Under CI (`CI` set), whose machines have
    /// AVX2, fails unless there are two to compare; elsewhere says so when there is only one.
    pub(crate) fn supported_paths() -> Vec<Path> {
        let paths: Vec<Path> = [Path::Baseline, Path::Avx2]
            .into_iter()
            .filter(|p| p.supported())
            .collect();
        if paths.len() < 2 {
            assert!(std::env::var_os("CI").is_none(), "CI's CPU lacks AVX2");
            eprintln!("only the baseline path runs on this CPU: nothing to compare it with");
        }
        paths
    }

    /// Every marked `weight` is a normal number that adding +0 leaves as it is, so no rounding
    /// mode or flushing of subnormals can change the flags in it.
    #[test]
    fn every_marked_weight_is_normal_and_keeps_its_bits_when_zero_is_added() {
        for bits in 0..=u8::MAX {
            let weight = f32::from_bits(super::MARKED | u32::from(bits));
            assert!(weight.is_normal(), "flags {bits:#x}");
            let added = core::hint::black_box(weight) + core::hint::black_box(0.0f32);
            assert_eq!(added.to_bits(), weight.to_bits(), "flags {bits:#x}");
        }
    }

    /// `run` with [`Path::best`] pinned to `path` on this thread.
    pub(crate) fn along<R>(path: Path, run: impl FnOnce() -> R) -> R {
        PINNED.with(|p| p.set(Some(path)));
        let result = run();
        PINNED.with(|p| p.set(None));
        result
    }
}
