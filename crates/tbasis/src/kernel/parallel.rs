//! Spreading a call over threads: every method splits its work into consecutive ranges (of
//! vertices, triangles, corners or cells), each worker writing only its own range, so the result
//! is bit-identical whatever the thread count.
//!
//! One rule decides how many workers a call gets, for every method: at most `threads`, and at
//! most one per [`MIN_TRIANGLES_PER_WORKER`] triangles, since below that starting a thread costs
//! more than it saves. With one worker everything runs on the calling thread, so a call with
//! caller scratch on one thread allocates nothing. Nothing here allocates on any thread count
//! (the standard library's thread start excepted: [`run`]).
#![forbid(unsafe_code)]

use std::sync::{Barrier, Condvar, Mutex, PoisonError};
use std::thread::ScopedJoinHandle;

use crate::kernel::error::Error;
use crate::kernel::mesh::Mesh;
use crate::kernel::report::Report;

/// Triangles each worker should have at least. Unit tests split small meshes too
/// (`entry/determinism_tests.rs`).
pub(crate) const MIN_TRIANGLES_PER_WORKER: usize = if cfg!(test) { 8 } else { 16 * 1024 };

/// At most this many ranges: beyond it another thread would not pay on any core count in use.
pub(crate) const MAX_RANGES: usize = 64;

/// How many workers a call on `triangles` triangles uses: at most `threads`, at least 1.
pub fn workers_for(threads: u32, triangles: usize) -> usize {
    (threads.max(1) as usize)
        .min(triangles / MIN_TRIANGLES_PER_WORKER)
        .clamp(1, MAX_RANGES)
}

/// [`workers_for`], for work where each worker reads every triangle with a corner in its vertex
/// range: 1 unless the triangle order follows the vertex order.
pub fn worker_count(threads: u32, mesh: &Mesh) -> usize {
    let vertex_count = mesh.vertex_count();
    let workers = workers_for(threads, mesh.corner_count() / 3);
    if workers > 1 && !split_pays_off(mesh, range_ends(vertex_count, workers).ends()) {
        return 1;
    }
    workers
}

/// How many triangles, evenly spaced, [`split_pays_off`] looks at: enough to tell a share of 3/4
/// within about 3% (the meshes that split share near 1/2, those that do not near 1), few enough
/// that the look (a cache miss each, on a large mesh) costs nothing next to the work it divides
/// (8,192 took 5% of a two-thread LEGACY call on FlightHelmet.cc1 in a profile).
const LOCALITY_SAMPLES: usize = 1024;

/// Whether splitting the vertices into ranges `ends` saves time: every worker reads each triangle
/// that has a corner in its range, so when the triangle order does not follow the vertex order
/// (most triangles spanning several ranges), each worker would redo nearly the whole mesh. Looks
/// at [`LOCALITY_SAMPLES`] triangles; true when none of the workers would see more than 3/4 of
/// them.
fn split_pays_off(mesh: &Mesh, ends: &[usize]) -> bool {
    let Ok(triangle_count) = mesh.indices.triangle_count(mesh.vertex_count()) else {
        return true;
    };
    let mut seen = [0usize; MAX_RANGES];
    let seen = &mut seen[..ends.len().min(MAX_RANGES)];
    let mut sampled = 0usize;
    for t in (0..triangle_count).step_by(triangle_count.div_ceil(LOCALITY_SAMPLES).max(1)) {
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

/// Bytes each worker of [`fill`] should have at least: a conservative choice, well above what
/// starting a thread costs. Unit tests split small memory too (`entry/determinism_tests.rs`).
pub(crate) const MIN_FILL_BYTES_PER_WORKER: usize = if cfg!(test) { 4 << 10 } else { 4 << 20 };

/// How many of `workers` [`fill`] uses on `bytes` bytes.
pub(crate) fn fill_workers(bytes: usize, workers: usize) -> usize {
    workers.min(bytes / MIN_FILL_BYTES_PER_WORKER).clamp(1, MAX_RANGES)
}

/// Sets every element of `items` to `value`, on [`fill_workers`] consecutive ranges: a large
/// call's working memory is zeroed before its workers start, and on one thread that wait is the
/// whole of it.
pub(crate) fn fill<T: Copy + Send + Sync>(items: &mut [T], value: T, workers: usize) {
    let ranges = range_ends(items.len(), fill_workers(core::mem::size_of_val(items), workers));
    run_ranges(ranges.ends(), split(items, ranges.ends(), 1), |_, part| {
        part.fill(value)
    });
}

/// The exclusive ends of `workers` (at most [`MAX_RANGES`]) near-equal consecutive ranges of
/// `count` items.
pub fn range_ends(count: usize, workers: usize) -> Ranges {
    Ranges::from_ends(ends(count, workers))
}

/// [`range_ends`] one at a time.
pub fn ends(count: usize, workers: usize) -> impl Iterator<Item = usize> {
    (1..=workers).map(move |w| (count as u128 * w as u128 / workers as u128) as usize)
}

/// Runs `job` on every part (at most [`MAX_RANGES`]), the first on the calling thread and the
/// others on scoped threads, and hands the results to `each` on the calling thread, in part order.
/// A panic in a worker resumes on the calling thread once every worker has ended, so nothing runs
/// on after a call returns or unwinds.
///
/// Nothing here allocates: the parts, their threads' handles and the results stay on the stack.
/// With one part, `job` runs directly. With more, the standard library's `std::thread::scope`
/// and each thread it starts allocate a little of their own on the calling thread (an `Arc` for
/// the scope; an `Arc` and two `Box`es per thread, a few dozen bytes each), which, like every
/// allocation of the standard library's own, ends the process if it fails: neither has a
/// fallible form. A thread the system cannot start (`spawn_scoped`'s error) is no failure: its
/// part runs on the calling thread.
pub fn run<P: Send, R: Send>(parts: impl IntoIterator<Item = P>, job: impl Fn(P) -> R + Sync, each: impl FnMut(R)) {
    run_spawning(parts, job, each, || true)
}

/// `job` on `part`, on the calling thread, through the same compiled job as [`run`]'s when given
/// the same `job` (a reference to one closure, say): one copy of it in the library.
pub fn run_one<P, R>(job: impl Fn(P) -> R, part: P) -> R {
    run_part(&job, part)
}

/// [`run`], folding the results in part order with `merge`; `None` without parts.
pub fn run_folded<P: Send, R: Send>(
    parts: impl IntoIterator<Item = P>,
    job: impl Fn(P) -> R + Sync,
    mut merge: impl FnMut(R, R) -> R,
) -> Option<R> {
    let mut total = None;
    run(parts, job, |result| {
        total = Some(match total.take() {
            Some(before) => merge(before, result),
            None => result,
        });
    });
    total
}

/// [`run`], asking `may_spawn` before each thread so a test can make spawning fail. A part whose
/// thread cannot be started (`spawn_scoped` fails: out of threads, or the system could not map
/// the thread's stack) runs on the calling thread instead: parts are independent, so the bits
/// are the same either way, never a partial output.
fn run_spawning<P: Send, R: Send>(
    parts: impl IntoIterator<Item = P>,
    job: impl Fn(P) -> R + Sync,
    mut each: impl FnMut(R),
    may_spawn: impl Fn() -> bool,
) {
    let mut parts = parts.into_iter();
    let Some(first) = parts.next() else {
        return;
    };
    // One part, the usual case on small meshes and one thread: no slots to build.
    let Some(second) = parts.next() else {
        return each(run_part(&job, first));
    };
    // A part stays in its slot until it runs, so a failed spawn (which drops its closure) loses
    // nothing; its result waits in its slot until every part has run. One lock for all the slots,
    // taken twice per part: the code each kind of part adds to the library stays small.
    let mut slots: [Slot<P, R>; MAX_RANGES - 1] = [const { Slot::Taken }; MAX_RANGES - 1];
    let mut others = 0;
    for (slot, part) in slots.iter_mut().zip(core::iter::once(second).chain(&mut parts)) {
        *slot = Slot::Part(part);
        others += 1;
    }
    assert!(parts.next().is_none(), "more than MAX_RANGES parts");
    let slots = Mutex::new(&mut slots[..others]);
    let run_other = |k: usize| {
        let taken = core::mem::replace(
            &mut slots.lock().unwrap_or_else(PoisonError::into_inner)[k],
            Slot::Taken,
        );
        let Slot::Part(part) = taken else {
            unreachable!("each part runs once")
        };
        let result = run_part(&job, part);
        slots.lock().unwrap_or_else(PoisonError::into_inner)[k] = Slot::Done(result);
    };
    let (mut first, mut first_result) = (Some(first), None);
    let mut run_first = || first_result = first.take().map(|part| run_part(&job, part));
    run_threads(others, &run_other, &mut run_first, &may_spawn);
    each(first_result.expect("the first part ran"));
    for slot in slots.into_inner().unwrap_or_else(PoisonError::into_inner).iter_mut() {
        match core::mem::replace(slot, Slot::Taken) {
            Slot::Done(result) => each(result),
            _ => unreachable!("every part ran"),
        }
    }
}

/// A part of [`run_spawning`] before it runs, its result after, or neither (running, or handed on).
enum Slot<P, R> {
    Part(P),
    Done(R),
    Taken,
}

/// [`run_spawning`]'s threads, compiled once for every kind of part: `run_other(k)` for `k` below
/// `others` on scoped threads (or on the calling thread, after `run_first`, when `may_spawn`
/// says no or the thread cannot be started), `run_first` on the calling thread meanwhile. A
/// panic on a thread resumes on the calling thread once every thread has ended.
#[inline(never)]
fn run_threads(
    others: usize,
    run_other: &(dyn Fn(usize) + Sync),
    run_first: &mut dyn FnMut(),
    may_spawn: &dyn Fn() -> bool,
) {
    // A test that pins a vector path pins it on the workers too.
    #[cfg(test)]
    let pinned = crate::kernel::simd::tests::PINNED.with(core::cell::Cell::get);
    std::thread::scope(|scope| {
        let mut handles: [Option<ScopedJoinHandle<'_, ()>>; MAX_RANGES - 1] = [const { None }; MAX_RANGES - 1];
        for (k, handle) in handles[..others].iter_mut().enumerate() {
            if may_spawn() {
                *handle = std::thread::Builder::new()
                    .spawn_scoped(scope, move || {
                        #[cfg(test)]
                        crate::kernel::simd::tests::PINNED.with(|path| path.set(pinned));
                        run_other(k)
                    })
                    .ok();
            }
        }
        run_first();
        for (k, handle) in handles[..others].iter_mut().enumerate() {
            match handle.take() {
                Some(handle) => handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
                None => run_other(k),
            }
        }
    });
}

/// [`run_folded`] for jobs that wait for one another (at a [`Lockstep`]): every part starts at
/// once, each on its own thread (the first on the calling one), or none does. `None`, with no
/// job run, when a thread cannot be started: the caller then does the work another way.
pub fn run_together<P: Send, R: Send>(
    parts: impl IntoIterator<Item = P>,
    job: impl Fn(P) -> R + Sync,
    merge: impl FnMut(R, R) -> R,
) -> Option<R> {
    run_together_spawning(parts, job, merge, || true)
}

/// [`run_together`], asking `may_spawn` before each thread so a test can make spawning fail.
fn run_together_spawning<P: Send, R: Send>(
    parts: impl IntoIterator<Item = P>,
    job: impl Fn(P) -> R + Sync,
    mut merge: impl FnMut(R, R) -> R,
    may_spawn: impl Fn() -> bool,
) -> Option<R> {
    // Every part is taken before any thread starts: nothing after the first start may panic
    // before the gate opens, or the started threads would wait for it forever.
    let mut parts = parts.into_iter().fuse();
    let first = parts.next()?;
    let mut others: [Option<P>; MAX_RANGES - 1] = core::array::from_fn(|_| parts.next());
    assert!(parts.next().is_none(), "more than MAX_RANGES parts");
    let gate = StartGate::default();
    let job = &job;
    #[cfg(test)]
    let pinned = crate::kernel::simd::tests::PINNED.with(core::cell::Cell::get);
    std::thread::scope(|scope| {
        let opening = Opening(&gate);
        let mut handles: [Option<ScopedJoinHandle<'_, Option<R>>>; MAX_RANGES - 1] = [const { None }; MAX_RANGES - 1];
        let mut all_started = true;
        for (part, handle) in others.iter_mut().filter_map(Option::take).zip(&mut handles) {
            let gate = &gate;
            let started = may_spawn().then(|| {
                std::thread::Builder::new().spawn_scoped(scope, move || {
                    #[cfg(test)]
                    crate::kernel::simd::tests::PINNED.with(|path| path.set(pinned));
                    gate.wait().then(|| run_part(job, part))
                })
            });
            *handle = started.and_then(Result::ok);
            all_started &= handle.is_some();
        }
        gate.open(all_started);
        drop(opening);
        let mut total = all_started.then(|| run_part(job, first));
        for handle in handles.iter_mut().filter_map(Option::take) {
            let result = handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            total = total.zip(result).map(|(before, result)| merge(before, result));
        }
        total
    })
}

/// Whether every thread of a [`run_together`] started, once the calling thread knows; the
/// started ones wait for it.
#[derive(Default)]
struct StartGate {
    all_started: Mutex<Option<bool>>,
    opened: Condvar,
}

impl StartGate {
    /// Says whether every thread started, unless that was said already.
    fn open(&self, all_started: bool) {
        self.all_started
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .get_or_insert(all_started);
        self.opened.notify_all();
    }

    /// Waits until the gate opens; whether every thread started.
    fn wait(&self) -> bool {
        let mut all_started = self.all_started.lock().unwrap_or_else(PoisonError::into_inner);
        loop {
            match *all_started {
                Some(all) => return all,
                None => all_started = self.opened.wait(all_started).unwrap_or_else(PoisonError::into_inner),
            }
        }
    }
}

/// Opens its gate with "not every thread started" when dropped before the gate was opened (a
/// panic while starting them), so that no started thread waits for ever.
struct Opening<'g>(&'g StartGate);

impl Drop for Opening<'_> {
    fn drop(&mut self) {
        self.0.open(false);
    }
}

/// The rounds of a job run by [`run_together`]: every job waits for the others at the end of
/// each round. A job that ends early, by an error or a panic, still waits out its remaining
/// rounds when this is dropped, so that the others never wait for it in vain; a job makes its
/// `Lockstep` first, before anything that could end it.
pub struct Lockstep<'b> {
    barrier: &'b Barrier,
    rounds_left: usize,
}

impl<'b> Lockstep<'b> {
    /// `rounds` rounds at `barrier`, which counts every job.
    pub fn new(barrier: &'b Barrier, rounds: usize) -> Self {
        Lockstep {
            barrier,
            rounds_left: rounds,
        }
    }

    /// Ends this job's round once every job has ended it.
    pub fn end_round(&mut self) {
        if self.rounds_left > 0 {
            self.rounds_left -= 1;
            self.barrier.wait();
        }
    }
}

impl Drop for Lockstep<'_> {
    fn drop(&mut self) {
        while self.rounds_left > 0 {
            self.end_round();
        }
    }
}

/// One part's work: a function of its own, so that the job's code is compiled once, not at each
/// of the places that may run a part ([`run_spawning`]'s three, [`run_together`]'s two).
#[inline(never)]
fn run_part<P, R>(job: &impl Fn(P) -> R, part: P) -> R {
    job(part)
}

/// Runs `a` on the calling thread and `b` beside it (after `a`, on the calling thread, when no
/// thread can be started) and returns both results. A panic in either resumes on the caller once
/// both have ended. Allocates nothing itself ([`run`]).
pub fn join<A, B, FA, FB>(a: FA, b: FB) -> (A, B)
where
    A: Send,
    B: Send,
    FA: FnOnce() -> A + Send,
    FB: FnOnce() -> B + Send,
{
    /// One of the two jobs, or its result.
    enum Either<A, B> {
        A(A),
        B(B),
    }
    let (mut a_result, mut b_result) = (None, None);
    let job = |part: Either<FA, FB>| match part {
        Either::A(a) => Either::A(a()),
        Either::B(b) => Either::B(b()),
    };
    run([Either::A(a), Either::B(b)], job, |result| match result {
        Either::A(a) => a_result = Some(a),
        Either::B(b) => b_result = Some(b),
    });
    (
        a_result.expect("run ran the first job"),
        b_result.expect("run ran the second job"),
    )
}

/// Two consecutive workers' results merged: both reports, or the first error.
pub fn merge_results(first: Result<Report, Error>, second: Result<Report, Error>) -> Result<Report, Error> {
    let (mut total, more) = (first?, second?);
    total.merge(&more);
    Ok(total)
}

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

/// The ranges `triangles` triangles split into for [`workers_for`] workers.
pub(crate) fn ranges(threads: u32, triangles: usize) -> Ranges {
    Ranges::from_ends(ends(triangles, workers_for(threads, triangles)))
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

/// Runs `job(first triangle, part)` for every range, the first on the calling thread ([`run`]);
/// with one range, directly.
pub(crate) fn run_ranges<P: Send>(ends: &[usize], parts: impl Iterator<Item = P>, job: impl Fn(usize, P) + Sync) {
    let starts = core::iter::once(0).chain(ends.iter().copied());
    run(starts.zip(parts), |(first, part)| job(first, part), |()| {});
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_cover_every_vertex_once() {
        assert_eq!(range_ends(10, 3).ends(), [3, 6, 10]);
        assert_eq!(range_ends(usize::MAX, 2).ends().last(), Some(&usize::MAX));
    }

    #[test]
    fn fill_splits_large_memory_only_and_writes_every_element() {
        let least = MIN_FILL_BYTES_PER_WORKER;
        assert_eq!(fill_workers(least - 1, 2), 1);
        assert_eq!(fill_workers(2 * least, 2), 2);
        assert_eq!(fill_workers(2 * least, 8), 2);
        assert_eq!(fill_workers(0, 0), 1);
        // Odd lengths, and a whole range's worth of elements on each side of every cut.
        for (len, workers) in [(2 * least + 3, 2), (4 * least + 1, 4), (least / 2, 2)] {
            let mut bytes = vec![0xA5u8; len];
            fill(&mut bytes, 7, workers);
            assert!(bytes.iter().all(|&b| b == 7), "{len} bytes on {workers} workers");
        }
        let mut words = vec![u32::MAX; least / 2 + 1];
        fill(&mut words, 0, 2);
        assert!(words.iter().all(|&w| w == 0));
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
        use crate::kernel::mesh::Indices;
        use crate::kernel::views::strided::Strided;
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
        // A strip of n vertices has about n / 2 triangles.
        let per = 2 * MIN_TRIANGLES_PER_WORKER + 4;
        assert_eq!(workers_for(8, per, false), 1);
        assert_eq!(workers_for(0, 1000 * per, false), 1);
        assert_eq!(workers_for(4, 1000 * per, false), 4);
        assert_eq!(workers_for(4, 3 * per, false), 3);
        // Every triangle spans both halves: both workers would read all of them.
        assert_eq!(workers_for(2, 1000 * per, true), 1);
    }

    /// [`run_spawning`]'s results, in the order it handed them over.
    fn results<P: Send, R: Send>(parts: Vec<P>, job: impl Fn(P) -> R + Sync, may_spawn: impl Fn() -> bool) -> Vec<R> {
        let mut results = Vec::new();
        run_spawning(parts, job, |result| results.push(result), may_spawn);
        results
    }

    #[test]
    fn run_keeps_part_order() {
        assert_eq!(results(vec![1, 2, 3, 4], |x| x * 10, || true), vec![10, 20, 30, 40]);
        assert_eq!(results(Vec::<u8>::new(), |x| x, || true), Vec::<u8>::new());
        let all: Vec<usize> = (0..MAX_RANGES).collect();
        assert_eq!(results(all.clone(), |x| x, || true), all);
        assert_eq!(run_folded(vec![1, 2, 3], |x| x, |a, b| 10 * a + b), Some(123));
    }

    #[test]
    #[should_panic(expected = "more than MAX_RANGES parts")]
    fn run_refuses_more_parts_than_it_has_room_for() {
        run(0..=MAX_RANGES, |x| x, |_| {});
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
        let none = results(parts.clone(), on_caller, || false);
        assert_eq!(none, (0..6).map(|p| (p * 10, true)).collect::<Vec<_>>());
        // Every other spawn fails: those parts run on the caller, the rest on their threads.
        let attempt = std::sync::atomic::AtomicUsize::new(0);
        let alternate = results(parts, on_caller, || {
            attempt.fetch_add(1, std::sync::atomic::Ordering::Relaxed) % 2 == 1
        });
        let expected: Vec<_> = (0..6).map(|p| (p * 10, p == 0 || p % 2 == 1)).collect();
        assert_eq!(alternate, expected);
    }

    /// The parts of [`run_together`] meet at a barrier in every round: they run at once.
    #[test]
    fn parts_run_together_and_merge_in_order() {
        for parts in [1, 2, 4] {
            let barrier = Barrier::new(parts);
            let job = |part: usize| {
                let mut lockstep = Lockstep::new(&barrier, 3);
                for _ in 0..3 {
                    lockstep.end_round();
                }
                part
            };
            let merged = run_together(0..parts, job, |a, b| 10 * a + b);
            let expected = (0..parts).fold(0, |a, b| 10 * a + b);
            assert_eq!(merged, Some(expected), "{parts} parts");
        }
    }

    #[test]
    #[should_panic(expected = "more than MAX_RANGES parts")]
    fn run_together_refuses_more_parts_than_it_has_room_for() {
        run_together(0..=MAX_RANGES, |x| x, |a, _| a);
    }

    /// A panic while the threads start (here the test's own hook) opens the gate for those
    /// already started: they end without running, and the panic reaches the caller.
    #[test]
    fn a_panic_while_starting_releases_the_started_threads() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let (ran, attempt) = (AtomicUsize::new(0), AtomicUsize::new(0));
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let third_panics = || {
                assert!(attempt.fetch_add(1, Ordering::Relaxed) < 2, "no third thread");
                true
            };
            run_together_spawning(
                0..4,
                |_: usize| ran.fetch_add(1, Ordering::Relaxed),
                |a, _| a,
                third_panics,
            )
        }));
        assert!(outcome.is_err());
        assert_eq!(ran.load(Ordering::Relaxed), 0);
    }

    #[test]
    fn no_part_runs_unless_every_thread_starts() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let (ran, attempt) = (AtomicUsize::new(0), AtomicUsize::new(0));
        // The second of three spawns fails.
        let second_fails = || attempt.fetch_add(1, Ordering::Relaxed) != 1;
        let job = |_: usize| ran.fetch_add(1, Ordering::Relaxed);
        assert_eq!(run_together_spawning(0..4, job, |a, _| a, second_fails), None);
        assert_eq!(ran.load(Ordering::Relaxed), 0);
        assert_eq!(attempt.load(Ordering::Relaxed), 3, "every spawn is tried");
    }

    /// A part that leaves its rounds early, by returning or by a panic, still lets the others
    /// finish theirs, and its panic reaches the caller once they have.
    #[test]
    fn a_part_that_ends_early_waits_out_its_rounds() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        for panics in [false, true] {
            let (barrier, rounds_ended) = (Barrier::new(3), AtomicUsize::new(0));
            let job = |part: usize| {
                let mut lockstep = Lockstep::new(&barrier, 4);
                for round in 0..4 {
                    if part == 1 && round == 1 {
                        assert!(!panics, "part 1 panicked");
                        return Err(part);
                    }
                    lockstep.end_round();
                    rounds_ended.fetch_add(1, Ordering::SeqCst);
                }
                Ok(part)
            };
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                run_together(0..3, job, |a, b| a.and(b))
            }));
            assert_eq!(outcome.is_err(), panics);
            if !panics {
                assert_eq!(outcome.unwrap(), Some(Err(1)));
            }
            // Parts 0 and 2 end all four rounds; part 1 its first only.
            assert_eq!(rounds_ended.load(Ordering::SeqCst), 9, "panics: {panics}");
        }
    }

    /// A panic in any part, the caller's or a worker's, reaches the caller only after every other
    /// part has ended: nothing writes after a call that panicked has returned (the C boundary's
    /// `TBASIS_ERROR_INTERNAL`).
    #[test]
    fn a_panic_resumes_on_the_caller_after_every_part_has_ended() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        for panicking in [0, 1, 3] {
            let ended = AtomicUsize::new(0);
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                run(
                    0..4,
                    |part| {
                        if part == panicking {
                            panic!("part {part}");
                        }
                        std::thread::sleep(std::time::Duration::from_millis(50));
                        ended.fetch_add(1, Ordering::SeqCst);
                    },
                    |()| {},
                )
            }));
            assert!(outcome.is_err(), "part {panicking}'s panic was lost");
            assert_eq!(ended.load(Ordering::SeqCst), 3, "part {panicking} panicked");
        }
    }
}
