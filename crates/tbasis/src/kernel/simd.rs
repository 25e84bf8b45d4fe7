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
//! holds the one other instruction the kernels need from `std::arch`, a cache prefetch.

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

    /// `run` with [`Path::best`] pinned to `path` on this thread.
    pub(crate) fn along<R>(path: Path, run: impl FnOnce() -> R) -> R {
        PINNED.with(|p| p.set(Some(path)));
        let result = run();
        PINNED.with(|p| p.set(None));
        result
    }
}
