//! Every allocation a C call makes on one thread or two may fail, and the call then returns
//! `TBASIS_ERROR_OUT_OF_MEMORY` with its output untouched: every method and policy, per vertex and
//! per corner, on meshes large enough for two workers (32768 triangles; the library starts one
//! worker per 16384), whose triangle order follows the vertex order (each worker adds a range of
//! vertices) or not (the workers measure chunks of triangles apart and add the terms after).
//!
//! The callback interface (`tbasis::mikktspace`, which the drop-in for mikktspace.c,
//! `libtbasis_mikktspace`, runs) is held to the same on 1, 2 and 4 threads, on a grid of about
//! 72,180 triangles (4 workers' worth), at 180 degrees and at 30: each of its allocations failing
//! in turn makes the call return false with no set call, and without a failure it makes the set
//! calls of one thread, bit for bit. It makes every allocation on the calling thread: on `W`
//! threads, `W` more than on one (each worker's list of the corners it hands on to another, made
//! before any worker starts).
//!
//! Its own binary without the test harness (`harness = false` in Cargo.toml): the allocations of
//! the workers are counted process-wide, so no other thread may run. For each call, a first run
//! records every allocation, on the calling thread and on the workers, with its backtrace; then,
//! for each of them in turn, a run in which that one fails. An allocation whose backtrace reaches
//! `std::thread` before the library is the standard library starting a thread (`std::thread::scope`
//! and `Builder::spawn_scoped` allocate their bookkeeping infallibly: a failure there ends the
//! process, and no stable interface can make them fail softly), so it is counted, checked to be
//! only that, and not failed. Every other one is the library's own. REJECT refuses the grid in
//! order (its collapsed rows) after allocating, and computes on the shuffled one.
//!
//! `cargo test -p tbasis-ffi --test allocation_threads` runs both tests (about a minute in a debug
//! build; the backtraces need its symbols); `ALLOCATION_CALLS=TEXT` keeps the calls whose
//! description holds TEXT, such as `ALLOCATION_CALLS="ANGLE SKIP, shuffled grid, 2 threads"` or
//! `ALLOCATION_CALLS="30 degrees, 4 threads"`.
//!
//! The counts of the C calls on these meshes, which their test checks ([`expected`]), per call,
//! per vertex and per corner alike:
//!
//! | method, policy | 1 thread | 2 threads, grid in order | 2 threads, shuffled |
//! |---|---:|---:|---:|
//! | LENGYEL + LEGACY | 1 | 2 | 2 |
//! | LENGYEL, ANGLE, AREA, UNIFORM + SKIP or REJECT | 1 | 2 | 11 |
//! | the same + INHERIT | 2 | 3 | 12 |
//! | MIKKTSPACE + LEGACY, SKIP or INHERIT | 1 | 1 | 3 |
//! | MIKKTSPACE + REJECT | 1 | 1 (refused) | 3 |
//!
//! One allocation is the working memory (`tbasis_scratch_size`'s bytes), a second one policy
//! INHERIT's adjacency (reserved apart from it); where the workers take ranges of vertices (the
//! grid in order), each block's index bounds, by which they skip the blocks of triangles outside
//! their range, 1 more; where the workers measure chunks of triangles apart (shuffled), the chunks' term lists are 10 more (two sets of one list of 2 x 2 lists), and
//! LEGACY's triangles solved apart keep their terms in 1 more;
//! MIKKTSPACE on two threads, on the shuffled grid, where it groups fan by fan and writes the
//! caller's per-corner output in place, reserves before the workers start the lists of corners
//! each worker may hand on to another (room for every corner of its fans: 2 more), so that
//! nothing fails once the output is written; on the grid in order (its degenerate rows take
//! another route) no worker hands any on. Besides, each `parallel::run` of two parts makes the standard library's 4
//! allocations on the calling thread (1 for the scope, 3 to start the thread; none on the thread
//! itself), which are not failed.

// The C boundary's own source, compiled in to count what it allocates (the C library has no Rust
// interface).
#[allow(dead_code)]
#[path = "../src/codes.rs"]
mod codes;
#[path = "../src/fault.rs"]
mod fault;
// Without the harness its unit test is compiled but not run: its import goes unused.
#[path = "common/c_calls.rs"]
mod c_calls;
#[allow(dead_code, non_camel_case_types, unused_imports)]
#[path = "../src/ffi.rs"]
mod ffi;
#[path = "../src/guard.rs"]
mod guard;
#[allow(dead_code, non_camel_case_types)]
#[path = "../src/status.rs"]
mod status;

use c_calls::{assert_out_of_memory, c_mesh, Entry, UNTOUCHED};
use codes::*;
use tbasis_test_support::alloc_count::{
    allocations, fail_allocation, fail_other_allocation, mark_calling_thread, other_allocations, record_backtraces,
    Counting, Recorded,
};
use tbasis_test_support::cases::Case;
use tbasis_test_support::shapes::{grid, Vertex};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Quads a side of the test grid: 128 x 128 quads, 32768 triangles, two workers' worth.
const SIDE: usize = 128;

/// Where an allocation was made.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Site {
    /// The library (or the C boundary).
    Library,
    /// The standard library starting a thread.
    ThreadStart,
}

/// Tells [`Site`] from the function names of `record`'s backtrace, innermost first: the first one
/// of the library or of `std::thread` decides.
fn site(record: &Recorded) -> Site {
    let boundary = concat!(module_path!(), "::ffi::");
    let functions = record.functions();
    for function in &functions {
        let function = function.trim_start_matches('<');
        if function.starts_with("std::thread::") {
            return Site::ThreadStart;
        }
        if function.starts_with("tbasis::") || function.starts_with(boundary) {
            return Site::Library;
        }
    }
    panic!(
        "an allocation with no frame of the library or of std::thread (a build without symbols?):\n{}",
        functions.join("\n")
    )
}

/// What one call allocated.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Tally {
    /// The library's allocations on the calling thread and on the workers.
    calling: usize,
    workers: usize,
    /// The standard library's thread start, on the calling thread and on the workers.
    thread_start: usize,
    thread_start_on_workers: usize,
}

/// The test grids: a mirror seam down the middle column (mirror-fold vertices, corners whose
/// tangents differ). In order (`shuffled` false), rows 60 to 62 collapse to one `v`: degenerate
/// triangles, and vertices that only touch them (INHERIT's propagation; REJECT refuses the grid).
/// Shuffled, no row collapses (REJECT computes), and the vertices are renumbered at random, so
/// that nearly every triangle has corners in both halves of the vertex range.
fn test_grid(shuffled: bool) -> Case {
    let middle = SIDE as f32 / 2.0;
    let mut case = grid("grid", SIDE, SIDE, |i, j| {
        let (x, y) = (i as f32, j as f32);
        let v = if !shuffled && (60..=62).contains(&j) { 61.0 } else { y };
        Vertex {
            position: [x, y, 0.25 * (x * 0.1).sin()],
            normal: [0.0, 0.0, 1.0],
            uv: [(x - middle).abs() / 16.0, v / 16.0],
        }
    });
    if shuffled {
        let n = case.vertex_count();
        // A fixed permutation: Fisher-Yates driven by a 64-bit LCG.
        let mut order: Vec<usize> = (0..n).collect();
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        for i in (1..n).rev() {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            order.swap(i, (state >> 33) as usize % (i + 1));
        }
        let mut renumbered = vec![0u32; n];
        for (new, &old) in order.iter().enumerate() {
            renumbered[old] = new as u32;
        }
        let permute = |values: &[[f32; 3]]| order.iter().map(|&old| values[old]).collect::<Vec<_>>();
        let texcoords = case.texcoords.as_ref().unwrap();
        case = Case {
            name: "shuffled grid".into(),
            positions: permute(&case.positions),
            normals: permute(&case.normals),
            texcoords: Some(order.iter().map(|&old| texcoords[old]).collect()),
            indices: Some(case.indices.unwrap().iter().map(|&v| renumbered[v as usize]).collect()),
        };
    }
    case
}

/// Runs `call` twice (the first may make one-time allocations) and records the second's
/// allocations on every thread: its result, the tally, and the library's allocations, each as
/// (made on the calling thread, its number counted from the call's start on that thread, or on
/// the other threads together).
fn record<R>(what: &str, mut call: impl FnMut() -> R) -> (R, Tally, Vec<(bool, usize)>) {
    call();
    let (calling_before, other_before) = (allocations(), other_allocations());
    let (result, records) = record_backtraces(&mut call);
    let (calling_made, other_made) = (allocations() - calling_before, other_allocations() - other_before);
    assert_eq!(
        records.len(),
        calling_made + other_made,
        "{what}: allocations not recorded"
    );
    let mut tally = Tally::default();
    let mut library = Vec::new();
    for record in &records {
        match (site(record), record.calling) {
            (Site::Library, true) => {
                tally.calling += 1;
                library.push((true, record.number - calling_before));
            }
            (Site::Library, false) => {
                tally.workers += 1;
                library.push((false, record.number - other_before));
            }
            (Site::ThreadStart, true) => tally.thread_start += 1,
            (Site::ThreadStart, false) => tally.thread_start_on_workers += 1,
        }
    }
    (result, tally, library)
}

/// Runs `call` with the library's allocation `k` failing, one of [`record`]'s: on the calling
/// thread, or on the others (`calling` false).
fn failing<R>((calling, k): (bool, usize), call: impl FnOnce() -> R) -> R {
    if calling {
        fail_allocation(Some(allocations() + k));
        let result = call();
        fail_allocation(None);
        result
    } else {
        fail_other_allocation(Some(other_allocations() + k));
        let result = call();
        fail_other_allocation(None);
        result
    }
}

/// Where [`failing`] made an allocation fail, for a message.
fn thread_of(calling: bool) -> &'static str {
    if calling {
        "the calling thread's"
    } else {
        "the workers'"
    }
}

/// Records what `call` allocates, then fails each of the library's allocations in turn: the call
/// must return `TBASIS_ERROR_OUT_OF_MEMORY` and leave all `count` output elements untouched.
fn fail_each_allocation(what: &str, call: &Entry, count: usize) -> Tally {
    let mut output = vec![[UNTOUCHED; 4]; count];
    let mut written = output.clone();
    let (status, tally, library) = record(what, || call(&mut written));
    // REJECT refuses the grid's collapsed rows, after allocating all the same.
    assert!(
        status == status::TBASIS_OK || status == status::TBASIS_ERROR_DEGENERATE_UV,
        "{what}: status {status}"
    );
    for (calling, k) in library {
        let status = failing((calling, k), || call(&mut output));
        let thread = thread_of(calling);
        assert_out_of_memory(status, &output, &format!("{what}: {thread} allocation {k}"));
    }
    tally
}

/// The library's allocations in one call (on the calling thread, on the workers) that the
/// module's table gives.
fn expected(method: u32, policy: u32, shuffled: bool, threads: u32) -> (usize, usize) {
    let mikktspace = method == TBASIS_METHOD_MIKKTSPACE;
    let memory = 1 + usize::from(policy == TBASIS_DEGENERATE_INHERIT && !mikktspace);
    match (threads, mikktspace, shuffled) {
        (1, _, _) => (memory, 0),
        (_, false, true) if policy == TBASIS_DEGENERATE_LEGACY => (memory + 1, 0),
        (_, false, true) => (memory + 10, 0),
        // The blocks' index bounds.
        (_, false, false) => (memory + 1, 0),
        (_, true, false) => (1, 0),
        (_, true, true) => (3, 0),
    }
}

/// Method and policy codes, and the name the tally table uses.
const COMBINATIONS: [(u32, u32, &str); 17] = [
    (TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_LEGACY, "LENGYEL LEGACY"),
    (TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_SKIP, "LENGYEL SKIP"),
    (TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_INHERIT, "LENGYEL INHERIT"),
    (TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_REJECT, "LENGYEL REJECT"),
    (TBASIS_METHOD_ANGLE, TBASIS_DEGENERATE_SKIP, "ANGLE SKIP"),
    (TBASIS_METHOD_ANGLE, TBASIS_DEGENERATE_INHERIT, "ANGLE INHERIT"),
    (TBASIS_METHOD_ANGLE, TBASIS_DEGENERATE_REJECT, "ANGLE REJECT"),
    (TBASIS_METHOD_AREA, TBASIS_DEGENERATE_SKIP, "AREA SKIP"),
    (TBASIS_METHOD_AREA, TBASIS_DEGENERATE_INHERIT, "AREA INHERIT"),
    (TBASIS_METHOD_AREA, TBASIS_DEGENERATE_REJECT, "AREA REJECT"),
    (TBASIS_METHOD_UNIFORM, TBASIS_DEGENERATE_SKIP, "UNIFORM SKIP"),
    (TBASIS_METHOD_UNIFORM, TBASIS_DEGENERATE_INHERIT, "UNIFORM INHERIT"),
    (TBASIS_METHOD_UNIFORM, TBASIS_DEGENERATE_REJECT, "UNIFORM REJECT"),
    (TBASIS_METHOD_MIKKTSPACE, TBASIS_DEGENERATE_LEGACY, "MIKKTSPACE LEGACY"),
    (TBASIS_METHOD_MIKKTSPACE, TBASIS_DEGENERATE_SKIP, "MIKKTSPACE SKIP"),
    (
        TBASIS_METHOD_MIKKTSPACE,
        TBASIS_DEGENERATE_INHERIT,
        "MIKKTSPACE INHERIT",
    ),
    (TBASIS_METHOD_MIKKTSPACE, TBASIS_DEGENERATE_REJECT, "MIKKTSPACE REJECT"),
];

/// The tests of this binary, as `cargo test`'s filters and `--list` see them.
const TESTS: [(&str, fn()); 2] = [
    (
        "each_allocation_on_one_and_two_threads_may_fail_and_the_call_says_so",
        c_calls_on_one_and_two_threads,
    ),
    (
        "each_allocation_of_the_callback_interface_on_several_threads_may_fail_with_no_set_call",
        callback_interface_on_several_threads,
    ),
];

fn main() {
    // The test harness's arguments, as far as they apply here: `--list`, `--ignored` (no test is
    // ignored), `--exact`, `--skip NAME` and name filters. `ALLOCATION_CALLS=TEXT` keeps the calls
    // whose description holds TEXT.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let skipped: Vec<&String> = args
        .windows(2)
        .filter(|pair| pair[0] == "--skip")
        .map(|pair| &pair[1])
        .collect();
    let filters: Vec<&String> = args
        .iter()
        .filter(|arg| !arg.starts_with('-') && !skipped.contains(arg))
        .collect();
    let exact = args.iter().any(|arg| arg == "--exact");
    let chosen: Vec<(&str, fn())> = TESTS
        .into_iter()
        .filter(|(name, _)| {
            let matches = |filter: &&String| {
                if exact {
                    name == filter
                } else {
                    name.contains(filter.as_str())
                }
            };
            !args.iter().any(|arg| arg == "--ignored")
                && (filters.is_empty() || filters.iter().any(matches))
                && !skipped.iter().any(|skip| name.contains(skip.as_str()))
        })
        .collect();
    if args.iter().any(|arg| arg == "--list") {
        for (name, _) in chosen {
            println!("{name}: test");
        }
        return;
    }
    let plural = if chosen.len() == 1 { "" } else { "s" };
    println!("running {} test{plural}", chosen.len());
    mark_calling_thread();
    for (name, test) in chosen {
        test();
        println!("test {name} ... ok");
    }
}

/// Every C call of the module's table, on one thread and two, each of its allocations failing in
/// turn.
fn c_calls_on_one_and_two_threads() {
    let filter = std::env::var("ALLOCATION_CALLS").ok();
    let mut table = Vec::new();
    for shuffled in [false, true] {
        let case = test_grid(shuffled);
        let mesh = c_mesh(&case);
        let corners = case.indices.as_ref().unwrap().len();
        for threads in [1u32, 2] {
            for (method, policy, name) in COMBINATIONS {
                let options = c_calls::options(method, policy, threads);
                let (per_vertex, per_corner) = (
                    c_calls::per_vertex(&mesh, &options),
                    c_calls::per_corner(&mesh, &options),
                );
                let entries: [(&str, &Entry, usize); 2] = [
                    ("tbasis_generate", &per_vertex, case.vertex_count()),
                    ("tbasis_generate_corners", &per_corner, corners),
                ];
                for (entry, call, count) in entries {
                    let what = format!("{entry}, {name}, {}, {threads} threads", case.name);
                    if filter.as_ref().is_some_and(|filter| !what.contains(filter.as_str())) {
                        continue;
                    }
                    let tally = fail_each_allocation(&what, call, count);
                    eprintln!("{what}: {tally:?}");
                    let (calling, workers) = expected(method, policy, shuffled, threads);
                    assert_eq!(
                        (tally.calling, tally.workers),
                        (calling, workers),
                        "{what}: the library's allocations (calling thread, workers)"
                    );
                    // One scope and one thread per parallel step of two parts, none on one thread.
                    assert_eq!(tally.thread_start % 4, 0, "{what}: {tally:?}");
                    assert_eq!(tally.thread_start_on_workers, 0, "{what}: {tally:?}");
                    if threads == 1 {
                        assert_eq!(tally.thread_start, 0, "{what}: one thread started threads");
                    }
                    table.push((what, tally));
                }
            }
        }
    }
    let failed: usize = table.iter().map(|(_, tally)| tally.calling + tally.workers).sum();
    let thread_starts: usize = table.iter().map(|(_, tally)| tally.thread_start).sum();
    eprintln!(
        "{} calls, {failed} allocations failed one at a time, {thread_starts} of the standard library's thread start left",
        table.len()
    );
    // Every path ran: with no filter, each call; the threads' start was seen and told apart.
    if filter.is_none() {
        assert_eq!(table.len(), 2 * 2 * COMBINATIONS.len() * 2);
        assert!(thread_starts > 0, "no thread started: the calls ran on one thread");
    }
}

/// Cells a side of the callback interface's grid: 256 x 160 faces, 72,180 triangles, so
/// that 4 threads get 4 workers (one per 16,384 triangles) wherever the work is split.
const FACE_GRID: (usize, usize) = (256, 160);

/// One set call: face, vertex, and the bits of the tangent, the bitangent, the magnitudes and
/// the orientation.
type SetCall = (usize, usize, [u32; 9]);

/// The callback interface's mesh, a grid of cells, face `k` on cell `k`: a quad, or a triangle
/// (every 11th from 5), or a face of 5 vertices, ignored (every 13th from 0: face 0 is one, so
/// the interface reads the first position apart). A mirror seam down the middle column, and rows
/// 60 to 62 collapsed to one `v`, as in [`test_grid`]. Every set call is recorded in room made
/// beforehand, so that the geometry allocates nothing during a call.
struct FaceGrid {
    cols: usize,
    rows: usize,
    /// The set calls a call makes: one per vertex of each face of 3 or 4 vertices.
    calls: usize,
    set: Vec<SetCall>,
}

impl FaceGrid {
    fn new((cols, rows): (usize, usize)) -> FaceGrid {
        let mut grid = FaceGrid {
            cols,
            rows,
            calls: 0,
            set: Vec::new(),
        };
        let calls = (0..cols * rows)
            .map(|face| grid.size(face))
            .filter(|&size| size == 3 || size == 4)
            .sum();
        grid.calls = calls;
        grid.set = Vec::with_capacity(calls);
        grid
    }

    fn size(&self, face: usize) -> usize {
        if face % 13 == 0 {
            5
        } else if face % 11 == 5 {
            3
        } else {
            4
        }
    }

    /// The grid point of a face's vertex.
    fn point(&self, face: usize, vert: usize) -> (f32, f32) {
        let (i, j) = (face % self.cols, face / self.cols);
        let (di, dj) = [(0, 0), (1, 0), (1, 1), (0, 1)][vert % 4];
        ((i + di) as f32, (j + dj) as f32)
    }

    /// `generate_tangents_with` at `angular_threshold` on `threads`, the set calls in `self.set`.
    fn generate(&mut self, angular_threshold: f32, threads: u32) -> bool {
        self.set.clear();
        let settings = tbasis::mikktspace::Settings {
            angular_threshold,
            threads,
        };
        tbasis::mikktspace::generate_tangents_with(self, &settings)
    }
}

impl tbasis::mikktspace::Geometry for FaceGrid {
    fn num_faces(&self) -> usize {
        self.cols * self.rows
    }

    fn num_vertices_of_face(&self, face: usize) -> usize {
        self.size(face)
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        let (x, y) = self.point(face, vert);
        [x, y, 0.25 * (x * 0.1).sin()]
    }

    fn normal(&self, _face: usize, _vert: usize) -> [f32; 3] {
        [0.0, 0.0, 1.0]
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let (x, y) = self.point(face, vert);
        let v = if (60.0..=62.0).contains(&y) { 61.0 } else { y };
        [(x - self.cols as f32 / 2.0).abs() / 16.0, v / 16.0]
    }

    fn set_tangent(&mut self, t: [f32; 3], b: [f32; 3], s: f32, m: f32, keeps: bool, face: usize, vert: usize) {
        assert!(self.set.len() < self.calls, "more set calls than faces' vertices");
        let bits = [t[0], t[1], t[2], b[0], b[1], b[2], s, m, f32::from(u8::from(keeps))].map(f32::to_bits);
        self.set.push((face, vert, bits));
    }
}

/// The callback interface (`tbasis::mikktspace`, which the drop-in `libtbasis_mikktspace` runs)
/// on 1, 2 and 4 threads, at 180 degrees and at 30 (the sub-group search): the same set calls on
/// every count, bit for bit; on 2 and 4 the workers start; and each of the library's allocations,
/// on the calling thread or on a worker, failing in turn makes the call return false with no set
/// call.
fn callback_interface_on_several_threads() {
    let filter = std::env::var("ALLOCATION_CALLS").ok();
    let mut grid = FaceGrid::new(FACE_GRID);
    let mut calls = 0;
    for threshold in [180.0, 30.0] {
        assert!(grid.generate(threshold, 1), "{threshold} degrees, 1 thread");
        let one_thread = grid.set.clone();
        assert_eq!(one_thread.len(), grid.calls, "a set call per face vertex");
        // The tally on one thread, whatever the filter keeps, then on the last count.
        let (_, single, _) = record(&format!("{threshold} degrees, 1 thread"), || {
            grid.generate(threshold, 1)
        });
        let mut before = None;
        for threads in [1, 2, 4] {
            let what = format!("generate_tangents_with, {threshold} degrees, {threads} threads");
            if filter.as_ref().is_some_and(|filter| !what.contains(filter.as_str())) {
                continue;
            }
            let (ok, tally, library) = record(&what, || grid.generate(threshold, threads));
            assert!(ok, "{what}: returned false");
            assert!(grid.set == one_thread, "{what}: other set calls than on one thread");
            for &(calling, k) in &library {
                let ok = failing((calling, k), || grid.generate(threshold, threads));
                let thread = thread_of(calling);
                assert!(
                    !ok && grid.set.is_empty(),
                    "{what}: {thread} allocation {k} failed, yet the call returned {ok} after {} set calls",
                    grid.set.len()
                );
            }
            eprintln!("{what}: {tally:?}");
            assert!(tally.calling >= 10, "{what}: {tally:?}");
            // Every allocation is made on the calling thread, the workers' included: on several
            // threads, one list per worker of the corners it hands on to another, made before
            // any worker starts.
            assert_eq!(tally.workers, 0, "{what}: {tally:?}");
            let lists = if threads == 1 { 0 } else { threads as usize };
            assert_eq!(tally.calling, single.calling + lists, "{what}: {tally:?}");
            // Threads are started from the calling thread alone, more of them on 4 threads than
            // on 2: the work is split.
            assert_eq!(tally.thread_start_on_workers, 0, "{what}: {tally:?}");
            if threads == 1 {
                assert_eq!(tally.thread_start, 0, "{what}: one thread started threads");
            }
            let fewer = before.map_or(0, |before: Tally| before.thread_start);
            assert!(
                tally.thread_start > fewer || threads == 1,
                "{what}: {tally:?} after {before:?}"
            );
            before = Some(tally);
            calls += 1;
        }
    }
    if filter.is_none() {
        assert_eq!(calls, 6);
    }
}
