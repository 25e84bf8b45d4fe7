//! Spreading a call over threads: each worker owns a consecutive range of vertices.
//!
//! A worker adds only to the vertices it owns, so each vertex still sums its triangles in triangle
//! order and the result is bit-identical whatever the thread count. Where the triangle order
//! follows the vertex order, a worker reads the triangles with a corner in its range; elsewhere
//! the workers measure ranges of triangles first (`robust::accumulate::accumulate_in_chunks`).
#![forbid(unsafe_code)]

use std::sync::{Mutex, PoisonError};

use crate::error::Error;
use crate::mesh::Mesh;
use crate::report::Report;

/// Vertices each worker should have at least: below that, starting a thread costs more than it
/// saves, so small meshes stay on the calling thread. Unit tests split small meshes too
/// (`thread_count_tests.rs`).
const MIN_VERTICES_PER_WORKER: usize = if cfg!(test) { 16 } else { 32 * 1024 };

/// Every how many triangles [`split_pays_off`] looks at one.
const LOCALITY_SAMPLE_STEP: usize = 16;

/// How many workers a call on `vertex_count` vertices uses: at most `threads`, at least 1.
pub fn workers_for(threads: u32, vertex_count: usize) -> usize {
    (threads.max(1) as usize)
        .min(vertex_count / MIN_VERTICES_PER_WORKER)
        .max(1)
}

/// [`workers_for`], for work where each worker reads every triangle with a corner in its vertex
/// range: 1 unless the triangle order follows the vertex order.
pub fn worker_count(threads: u32, mesh: &Mesh) -> usize {
    let vertex_count = mesh.vertex_count();
    let workers = workers_for(threads, vertex_count);
    if workers > 1 && !split_pays_off(mesh, &range_ends(vertex_count, workers)) {
        return 1;
    }
    workers
}

/// Whether splitting the vertices into ranges `ends` saves time: every worker reads each triangle
/// that has a corner in its range, so when the triangle order does not follow the vertex order
/// (most triangles spanning several ranges), each worker would redo nearly the whole mesh. Looks
/// at every 16th triangle; true when none of the workers would see more than 3/4 of them.
fn split_pays_off(mesh: &Mesh, ends: &[usize]) -> bool {
    let Ok(triangle_count) = mesh.indices.triangle_count(mesh.vertex_count()) else {
        return true;
    };
    let mut seen = vec![0usize; ends.len()];
    let mut sampled = 0usize;
    for t in (0..triangle_count).step_by(LOCALITY_SAMPLE_STEP) {
        let workers = mesh.indices.triangle(t).map(|v| ends.partition_point(|&end| end <= v));
        for (k, &w) in workers.iter().enumerate() {
            if w < seen.len() && !workers[..k].contains(&w) {
                seen[w] += 1;
            }
        }
        sampled += 1;
    }
    seen.iter().all(|&count| 4 * count <= 3 * sampled)
}

/// The exclusive ends of `workers` near-equal consecutive ranges of `vertex_count` vertices.
pub fn range_ends(vertex_count: usize, workers: usize) -> Vec<usize> {
    ends(vertex_count, workers).collect()
}

/// [`range_ends`] one at a time, without allocating.
pub fn ends(count: usize, workers: usize) -> impl Iterator<Item = usize> {
    (1..=workers).map(move |w| (count as u128 * w as u128 / workers as u128) as usize)
}

/// Runs `job` on every part, the first on the calling thread and the others on scoped threads,
/// and returns the results in part order. A panic in a worker resumes on the calling thread.
pub fn run<P: Send, R: Send>(parts: Vec<P>, job: impl Fn(P) -> R + Sync) -> Vec<R> {
    run_spawning(parts, job, || true)
}

/// [`run`], asking `may_spawn` before each thread so a test can make spawning fail. A part whose
/// thread cannot be started (out of threads or memory) runs on the calling thread instead: parts
/// are independent, so the bits are the same either way, never a partial output.
fn run_spawning<P: Send, R: Send>(parts: Vec<P>, job: impl Fn(P) -> R + Sync, may_spawn: impl Fn() -> bool) -> Vec<R> {
    // A part stays in its slot until it runs, so a failed spawn (which drops its closure) loses
    // nothing.
    let slots: Vec<Mutex<Option<P>>> = parts.into_iter().map(|part| Mutex::new(Some(part))).collect();
    let take = |slot: &Mutex<Option<P>>| {
        let part = slot.lock().unwrap_or_else(PoisonError::into_inner).take();
        part.expect("each part runs once")
    };
    let Some((first, others)) = slots.split_first() else {
        return Vec::new();
    };
    std::thread::scope(|scope| {
        let spawned: Vec<_> = others
            .iter()
            .map(|slot| {
                let work = || job(take(slot));
                may_spawn()
                    .then(|| std::thread::Builder::new().spawn_scoped(scope, work).ok())
                    .flatten()
            })
            .collect();
        let mut results = vec![job(take(first))];
        for (slot, handle) in others.iter().zip(spawned) {
            results.push(match handle {
                Some(handle) => handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
                None => job(take(slot)),
            });
        }
        results
    })
}

/// Runs `a` on the calling thread and `b` beside it (after `a`, on the calling thread, when no
/// thread can be started) and returns both results. A panic in either resumes on the caller.
pub fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    let (mut a_result, mut b_result) = (None, None);
    let jobs: Vec<Box<dyn FnOnce() + Send + '_>> =
        vec![Box::new(|| a_result = Some(a())), Box::new(|| b_result = Some(b()))];
    run(jobs, |job| job());
    (
        a_result.expect("run ran the first job"),
        b_result.expect("run ran the second job"),
    )
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
    }

    /// A strip of `n` vertices with triangles of consecutive vertices, or (`scattered`) with one
    /// corner in each half of the vertex range.
    fn strip(n: usize, scattered: bool) -> (Vec<[f32; 3]>, Vec<u32>) {
        let positions = vec![[0.0f32; 3]; n];
        let half = (n / 2) as u32;
        let indices = (0..n as u32 / 2 - 2)
            .flat_map(|i| {
                if scattered {
                    [i, half + i, i + 1]
                } else {
                    [2 * i, 2 * i + 1, 2 * i + 2]
                }
            })
            .collect();
        (positions, indices)
    }

    fn workers_for(threads: u32, n: usize, scattered: bool) -> usize {
        use crate::mesh::Indices;
        use crate::views::strided::Strided;
        let (positions, indices) = strip(n, scattered);
        let mesh = Mesh {
            positions: Strided::from_slice(&positions),
            normals: Strided::from_slice(&positions),
            texcoords: None,
            indices: Indices::U32(Strided::from_slice(&indices)),
        };
        worker_count(threads, &mesh)
    }

    #[test]
    fn workers_follow_threads_size_and_locality() {
        assert_eq!(workers_for(8, MIN_VERTICES_PER_WORKER, false), 1);
        assert_eq!(workers_for(0, 1000 * MIN_VERTICES_PER_WORKER, false), 1);
        assert_eq!(workers_for(4, 1000 * MIN_VERTICES_PER_WORKER, false), 4);
        assert_eq!(workers_for(4, 3 * MIN_VERTICES_PER_WORKER, false), 3);
        // Every triangle spans both halves: both workers would read all of them.
        assert_eq!(workers_for(2, 1000 * MIN_VERTICES_PER_WORKER, true), 1);
    }

    #[test]
    fn run_keeps_part_order() {
        assert_eq!(run(vec![1, 2, 3, 4], |x| x * 10), vec![10, 20, 30, 40]);
        assert_eq!(run(Vec::<u8>::new(), |x| x), Vec::<u8>::new());
    }

    #[test]
    fn join_returns_both_results() {
        let caller = std::thread::current().id();
        let (a, b) = join(|| (1, std::thread::current().id()), || (2, std::thread::current().id()));
        assert_eq!((a.0, b.0), (1, 2));
        assert_eq!(a.1, caller);
    }

    #[test]
    fn parts_whose_thread_fails_to_start_run_on_the_caller() {
        let caller = std::thread::current().id();
        let parts: Vec<usize> = (0..6).collect();
        let on_caller = |part: usize| (part * 10, std::thread::current().id() == caller);
        let none = run_spawning(parts.clone(), on_caller, || false);
        assert_eq!(none, (0..6).map(|p| (p * 10, true)).collect::<Vec<_>>());
        // Every other spawn fails: those parts run on the caller, the rest on their threads.
        let attempt = std::sync::atomic::AtomicUsize::new(0);
        let alternate = run_spawning(parts, on_caller, || {
            attempt.fetch_add(1, std::sync::atomic::Ordering::Relaxed) % 2 == 1
        });
        let expected: Vec<_> = (0..6).map(|p| (p * 10, p == 0 || p % 2 == 1)).collect();
        assert_eq!(alternate, expected);
    }
}
