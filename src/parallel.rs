//! Spreading a call over threads: each worker owns a consecutive range of vertices.
//!
//! A worker reads every triangle but adds only to the vertices it owns, so each vertex still sums
//! its triangles in triangle order and the result is bit-identical whatever the thread count.
#![forbid(unsafe_code)]

use crate::report::Report;
use crate::status::Error;

/// Vertices each worker should have at least: below that, starting a thread costs more than it
/// saves, so small meshes stay on the calling thread.
const MIN_VERTICES_PER_WORKER: usize = 32 * 1024;

/// How many workers a call uses: at most `threads`, at least 1.
pub fn worker_count(threads: u32, vertex_count: usize) -> usize {
    (threads.max(1) as usize)
        .min(vertex_count / MIN_VERTICES_PER_WORKER)
        .max(1)
}

/// The exclusive ends of `workers` near-equal consecutive ranges of `vertex_count` vertices.
pub fn range_ends(vertex_count: usize, workers: usize) -> Vec<usize> {
    (1..=workers)
        .map(|w| (vertex_count as u128 * w as u128 / workers as u128) as usize)
        .collect()
}

/// Runs `job` on every part, the first on the calling thread and the others on scoped threads,
/// and returns the results in part order. A panic in a worker resumes on the calling thread.
pub fn run<P: Send, R: Send>(parts: Vec<P>, job: impl Fn(P) -> R + Sync) -> Vec<R> {
    std::thread::scope(|scope| {
        let mut parts = parts.into_iter();
        let first = parts.next();
        let spawned: Vec<_> = parts.map(|part| scope.spawn(|| job(part))).collect();
        let mut results: Vec<R> = first.map(&job).into_iter().collect();
        for handle in spawned {
            results.push(handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)));
        }
        results
    })
}

/// The workers' reports merged, or the first worker's error.
pub fn merge(results: Vec<Result<Report, Error>>) -> Result<Report, Error> {
    let mut total = Report::default();
    for result in results {
        total.merge(&result?);
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_cover_every_vertex_once() {
        assert_eq!(range_ends(10, 3), vec![3, 6, 10]);
        assert_eq!(range_ends(usize::MAX, 2).last(), Some(&usize::MAX));
        assert_eq!(worker_count(8, 1000), 1);
        assert_eq!(worker_count(0, 10_000_000), 1);
        assert_eq!(worker_count(4, 10_000_000), 4);
        assert_eq!(worker_count(4, 3 * MIN_VERTICES_PER_WORKER), 3);
    }

    #[test]
    fn run_keeps_part_order() {
        assert_eq!(run(vec![1, 2, 3, 4], |x| x * 10), vec![10, 20, 30, 40]);
    }
}
