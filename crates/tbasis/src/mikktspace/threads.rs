//! The per-triangle passes on several threads: consecutive ranges of good triangles, each
//! worker writing only its own range, so the result does not depend on the thread count.
#![forbid(unsafe_code)]

use crate::parallel;

/// Triangles each worker should have at least: below that a thread costs more than it saves.
/// Unit tests split small meshes too (`thread_count_tests.rs`).
const MIN_TRIANGLES_PER_WORKER: usize = if cfg!(test) { 8 } else { 16 * 1024 };

/// The exclusive ends of the triangle ranges `triangles` good triangles split into for at most
/// `threads` workers (one range when threads would not pay).
pub(crate) fn ranges(threads: u32, triangles: usize) -> Vec<usize> {
    let workers = (threads.max(1) as usize)
        .min(triangles / MIN_TRIANGLES_PER_WORKER)
        .max(1);
    parallel::range_ends(triangles, workers)
}

/// `items` (`per` entries per triangle) cut at the triangle ranges `ends`.
pub(crate) fn split<'a, T>(mut items: &'a mut [T], ends: &[usize], per: usize) -> Vec<&'a mut [T]> {
    let mut first = 0;
    let mut parts = Vec::with_capacity(ends.len());
    for &end in ends {
        let (part, rest) = items.split_at_mut(per * (end - first));
        parts.push(part);
        (items, first) = (rest, end);
    }
    parts
}

/// Runs `job(first triangle, part)` for every range, the first on the calling thread.
pub(crate) fn run<P: Send>(ends: &[usize], parts: Vec<P>, job: impl Fn(usize, P) + Sync) {
    let starts = core::iter::once(0).chain(ends.iter().copied());
    let parts: Vec<(usize, P)> = starts.zip(parts).collect();
    parallel::run(parts, |(first, part)| job(first, part));
}
