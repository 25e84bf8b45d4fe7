//! The per-triangle passes on several threads: consecutive ranges of good triangles (or of the
//! weld's grid cells), each worker writing only its own range, so the result does not depend on
//! the thread count. With one range the work runs on the calling thread and nothing is
//! allocated, so a call with caller scratch on one thread makes no allocation at all.
#![forbid(unsafe_code)]

use crate::parallel;

/// Triangles each worker should have at least: below that a thread costs more than it saves.
/// Unit tests split small meshes too (`thread_count_tests.rs`).
const MIN_TRIANGLES_PER_WORKER: usize = if cfg!(test) { 8 } else { 16 * 1024 };

/// At most this many ranges: beyond it another thread would not pay on any core count in use.
pub(crate) const MAX_RANGES: usize = 64;

/// The exclusive ends of consecutive ranges, held without allocating.
pub(crate) struct Ranges {
    ends: [usize; MAX_RANGES],
    len: usize,
}

impl Ranges {
    /// Ranges ending at `ends` (at most [`MAX_RANGES`], the last one ending the whole).
    pub fn from_ends(ends: impl IntoIterator<Item = usize>) -> Ranges {
        let mut ranges = Ranges {
            ends: [0; MAX_RANGES],
            len: 0,
        };
        for end in ends.into_iter().take(MAX_RANGES) {
            ranges.ends[ranges.len] = end;
            ranges.len += 1;
        }
        ranges
    }

    /// The ends, in order.
    pub fn ends(&self) -> &[usize] {
        &self.ends[..self.len]
    }
}

/// The ranges `triangles` good triangles split into for at most `threads` workers (one range when
/// threads would not pay).
pub(crate) fn ranges(threads: u32, triangles: usize) -> Ranges {
    let workers = (threads.max(1) as usize)
        .min(triangles / MIN_TRIANGLES_PER_WORKER)
        .clamp(1, MAX_RANGES);
    Ranges::from_ends(parallel::ends(triangles, workers))
}

/// Ranges of `count` items, `per` to a triangle, cut where [`ranges`] cuts `count / per` triangles
/// (the last ending at `count`).
pub(crate) fn item_ranges(threads: u32, count: usize, per: usize) -> Ranges {
    let triangles = ranges(threads, count / per);
    let last = triangles.ends().len() - 1;
    Ranges::from_ends(
        triangles
            .ends()
            .iter()
            .enumerate()
            .map(|(i, &end)| if i == last { count } else { per * end }),
    )
}

/// `items` (`per` entries per triangle) cut at the range ends `ends`.
pub(crate) fn split<'a, T>(items: &'a mut [T], ends: &'a [usize], per: usize) -> impl Iterator<Item = &'a mut [T]> {
    let mut rest = items;
    let mut first = 0;
    ends.iter().map(move |&end| {
        let (part, after) = core::mem::take(&mut rest).split_at_mut(per * (end - first));
        (rest, first) = (after, end);
        part
    })
}

/// Runs `job(first triangle, part)` for every range, the first on the calling thread; with one
/// range, without allocating.
pub(crate) fn run<P: Send>(ends: &[usize], mut parts: impl Iterator<Item = P>, job: impl Fn(usize, P) + Sync) {
    if ends.len() <= 1 {
        if let Some(part) = parts.next() {
            job(0, part);
        }
        return;
    }
    let starts = core::iter::once(0).chain(ends.iter().copied());
    let parts: Vec<(usize, P)> = starts.zip(parts).collect();
    parallel::run(parts, |(first, part)| job(first, part));
}
